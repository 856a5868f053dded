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

// The shared acceptance corpus's copy of a spec (tests/golden/ir): the v1 models as the
// corpus states them, where the project's own spec has moved on.
inline std::string readCorpusSpec(const std::string& name) {
  std::ifstream in(std::string(GBX_GOLDEN_DIR) + "/ir/" + name, std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}
