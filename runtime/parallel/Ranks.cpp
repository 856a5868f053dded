#include "parallel/Ranks.h"

#include <algorithm>
#include <atomic>
#include <cstdlib>
#include <thread>

#ifdef GBX_MPI
#include <mpi.h>
#endif

namespace gbx::rt::par {

namespace {

// Whether this thread is running a share of onThreads' work: a `map` inside it runs serially
// (no pool inside a pool), whichever thread started the outer one (the program's main
// thread, or a thread of the Python module's).
thread_local bool tSharing = false;

} // namespace

void onThreads(int threads, const std::function<void()>& work) {
  auto share = [&work] {
    bool was = tSharing;
    tSharing = true;
    work();
    tSharing = was;
  };
  std::vector<std::thread> pool;
  for (int t = 1; t < threads; ++t)
    pool.emplace_back(share);
  share();
  for (auto& th : pool) th.join();
}

namespace {

int gRank = 0, gRanks = 1;
bool gStarted = false;
bool gLoneRank = false;  // under mpirun, in a build without MPI
std::atomic<int> gJobs{1};

// The iterations of this rank, over the threads, each result in its slot.
void runShare(size_t n, int jobs, const std::function<std::vector<double>(size_t)>& f, std::vector<std::vector<double>>& out, int rank,
              int ranks) {
  std::vector<size_t> mine;
  for (size_t i = static_cast<size_t>(rank); i < n; i += static_cast<size_t>(ranks)) mine.push_back(i);
  std::atomic<size_t> next{0};
  auto work = [&] {
    for (size_t j = next++; j < mine.size(); j = next++) out[mine[j]] = f(mine[j]);
  };
  onThreads(static_cast<int>(std::min<size_t>(static_cast<size_t>(std::max(1, jobs)), mine.size())), work);
}

#ifdef GBX_MPI
// Every rank's results to every rank: each packs (index, length, values…) of its own.
void gather(std::vector<std::vector<double>>& out) {
  std::vector<double> pack;
  for (size_t i = static_cast<size_t>(gRank); i < out.size(); i += static_cast<size_t>(gRanks)) {
    pack.push_back(static_cast<double>(i));
    pack.push_back(static_cast<double>(out[i].size()));
    pack.insert(pack.end(), out[i].begin(), out[i].end());
  }
  int mine = static_cast<int>(pack.size());
  std::vector<int> counts(static_cast<size_t>(gRanks)), offsets(static_cast<size_t>(gRanks));
  MPI_Allgather(&mine, 1, MPI_INT, counts.data(), 1, MPI_INT, MPI_COMM_WORLD);
  int total = 0;
  for (int r = 0; r < gRanks; ++r) {
    offsets[static_cast<size_t>(r)] = total;
    total += counts[static_cast<size_t>(r)];
  }
  std::vector<double> all(static_cast<size_t>(total));
  MPI_Allgatherv(pack.data(), mine, MPI_DOUBLE, all.data(), counts.data(), offsets.data(), MPI_DOUBLE, MPI_COMM_WORLD);
  for (size_t p = 0; p + 1 < all.size();) {
    size_t i = static_cast<size_t>(all[p]), len = static_cast<size_t>(all[p + 1]);
    p += 2;
    if (i < out.size()) out[i].assign(all.begin() + static_cast<std::ptrdiff_t>(p), all.begin() + static_cast<std::ptrdiff_t>(p + len));
    p += len;
  }
}

// Started by mpirun (Open MPI's launcher sets these): a plain run stays a plain process.
bool underMpirun() { return std::getenv("OMPI_COMM_WORLD_SIZE") || std::getenv("PMIX_RANK") || std::getenv("PMI_RANK"); }
#endif

} // namespace

Session::Session([[maybe_unused]] int* argc, [[maybe_unused]] char*** argv) {
#ifndef GBX_MPI
  // Started by mpirun without MPI in this build: every process would solve alone and write
  // the same report; only the launcher's rank 0 does (rank() says which this is).
  for (const char* name : {"OMPI_COMM_WORLD_RANK", "PMIX_RANK", "PMI_RANK"})
    if (const char* r = std::getenv(name); r && *r) {
      gRank = std::atoi(r);
      gLoneRank = true;
      break;
    }
#endif
#ifdef GBX_MPI
  if (!underMpirun()) return;
  int provided = 0;
  MPI_Init_thread(argc, argv, MPI_THREAD_FUNNELED, &provided);
  MPI_Comm_rank(MPI_COMM_WORLD, &gRank);
  MPI_Comm_size(MPI_COMM_WORLD, &gRanks);
  gStarted = true;
#endif
}

Session::~Session() {
#ifdef GBX_MPI
  if (gStarted) MPI_Finalize();
#endif
  gStarted = false;
}

int rank() { return gRank; }
bool alone() { return gLoneRank; }
int sharingRanks() { return !tSharing && gStarted && gRanks > 1 ? gRanks : 1; }

void setJobs(int jobs) { gJobs = std::max(1, jobs); }
int jobs() { return gJobs; }

std::vector<std::vector<double>> map(size_t n, int jobs, const std::function<std::vector<double>(size_t)>& f, bool shareRanks) {
  std::vector<std::vector<double>> out(n);
  if (tSharing) {
    for (size_t i = 0; i < n; ++i) out[i] = f(i);
    return out;
  }
  const bool ranked = shareRanks && gStarted && gRanks > 1;
  runShare(n, jobs, f, out, ranked ? gRank : 0, ranked ? gRanks : 1);
#ifdef GBX_MPI
  if (ranked) gather(out);
#endif
  return out;
}

} // namespace gbx::rt::par
