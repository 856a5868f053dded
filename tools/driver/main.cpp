#include <iostream>
#include <string>
#include <vector>

#include "driver/Driver.h"

int main(int argc, char** argv) {
  std::vector<std::string> args(argv + 1, argv + argc);
  return gbx::driver::run(args, std::cout, std::cerr);
}
