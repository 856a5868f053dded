#include <iostream>
#include <sstream>
#include <string>
#include <vector>

#include "driver/Driver.h"
#include "parallel/Ranks.h"

int main(int argc, char** argv) {
  // Under mpirun each rank solves; rank 0 alone speaks and writes (runtime/parallel/Ranks.h).
  gbx::rt::par::Session ranks(&argc, &argv);
  std::vector<std::string> args(argv + 1, argv + argc);
  if (!gbx::rt::par::root()) {
    std::ostringstream quiet;
    return gbx::driver::run(args, quiet, quiet);
  }
  return gbx::driver::run(args, std::cout, std::cerr);
}
