#pragma once
// Work shared over threads and, in a build with Open MPI (-DGBX_MPI=ON) started by
// `mpirun -n N`, over ranks (LANGUAGE.md §19). Every rank runs the whole solve; the loops
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

int rank();   // 0 without MPI
int ranks();  // 1 without MPI
inline bool root() { return rank() == 0; }
// Whether this build can share work over ranks.
bool built();

// The threads a solve may use (`--jobs`), for the loops deep inside it.
void setJobs(int jobs);
int jobs();

// f(i) for every i < n, over `jobs` threads on each rank and the ranks round-robin; the
// results in index order, on every rank. Called from another thread than the program's
// main one (a worker of the search or of this very function), it runs on that thread alone
// and shares nothing with the other ranks: every rank calls the ranks' exchange in the
// same order only from its main thread.
std::vector<std::vector<double>> map(size_t n, int jobs, const std::function<std::vector<double>(size_t)>& f);

} // namespace gbx::rt::par
