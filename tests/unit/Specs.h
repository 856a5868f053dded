#pragma once
// The example specs, read from the source tree, for tests.
#include <fstream>
#include <sstream>
#include <string>

inline std::string readSpec(const std::string& name) {
  std::ifstream in(std::string(GBX_SOURCE_DIR) + "/specs/" + name, std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}
