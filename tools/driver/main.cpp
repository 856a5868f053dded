#include <iostream>
#include <streambuf>
#include <string>
#include <vector>
#ifdef __GLIBC__
#include <malloc.h>
#endif

#include "driver/Driver.h"
#include "parallel/Ranks.h"

namespace {

// Where the other ranks' output goes: nowhere, without holding it.
class Discard : public std::streambuf {
protected:
  int overflow(int c) override { return c == traits_type::eof() ? 0 : c; }
  std::streamsize xsputn(const char*, std::streamsize n) override { return n; }
};

} // namespace

int main(int argc, char** argv) {
#ifdef __GLIBC__
  // Large buffers (the search's halves and kept designs, a listing's ranked list) come and
  // go in turn. Taken from the heap, and kept there when freed, each reuses pages an earlier
  // one touched instead of mapping fresh ones: page faults were a fifth of a long listing's CPU.
  mallopt(M_MMAP_THRESHOLD, 32 << 20);
  mallopt(M_TRIM_THRESHOLD, 256 << 20);
#endif
  // Under mpirun each rank solves; rank 0 alone speaks and writes (runtime/parallel/Ranks.h).
  gbx::rt::par::Session ranks(&argc, &argv);
  std::vector<std::string> args(argv + 1, argv + argc);
  if (!gbx::rt::par::root()) {
    // Only `solve` shares its work; without MPI in this build nothing is shared at all, and
    // every command is rank 0's alone.
    if (gbx::rt::par::alone() || args.empty() || args[0] != "solve") return 0;
    Discard nothing;
    std::ostream quiet(&nothing);
    return gbx::driver::run(args, quiet, quiet);
  }
  if (gbx::rt::par::alone())
    std::cerr << "gbxc: note: started by mpirun, but this gbxc was built without MPI: rank 0 solves alone; "
                 "build/gbxc-mpi (or a -DGBX_MPI=ON build) shares the work over the ranks\n";
  return gbx::driver::run(args, std::cout, std::cerr);
}
