#pragma once
// Work shared over threads and, in a build with Open MPI (-DGBX_MPI=ON) started by
// `mpirun -n N`, over ranks (docs/optimisation.md). Every rank runs the whole solve; the loops
// that cost (Monte Carlo samples) share their iterations, and every rank receives every
// result, so what follows is the same on each and rank 0 alone writes the report.
#include <cstddef>
#include <functional>
#include <vector>

namespace gbx::rt::par {

// MPI for the life of the program, when it was started by mpirun; nothing otherwise (a
// plain `gbxc` never initialises MPI).
class Session {
public:
  Session(int* argc, char*** argv);
  ~Session();
  Session(const Session&) = delete;
  Session& operator=(const Session&) = delete;
};

int rank();  // 0 without MPI
// How many ranks a sharing map() called here would deal its work to: 1 without MPI, alone,
// or off the program's main thread.
int sharingRanks();
inline bool root() { return rank() == 0; }
// Started by mpirun in a build without MPI: rank() is the launcher's, and nothing is shared.
bool alone();

// The threads a solve may use (`--jobs`), for the loops deep inside it.
void setJobs(int jobs);
int jobs();

// `work` on `threads` threads at once (this one among them); returns when every one has.
void onThreads(int threads, const std::function<void()>& work);

// f(i) for every i < n, over `jobs` threads; with shareRanks, also over the ranks
// round-robin, the results gathered to every rank. The results in index order. Every rank
// must make the same shareRanks calls in the same order, so only fixed points of a pass
// share (the Monte Carlo samples' scenes and quantities), never a call whose occurrence
// could depend on timing (a cache hit, a thread pool's share). Called from another thread
// than the program's main one, it runs on that thread alone.
std::vector<std::vector<double>> map(size_t n, int jobs, const std::function<std::vector<double>(size_t)>& f,
                                     bool shareRanks = false);

} // namespace gbx::rt::par
