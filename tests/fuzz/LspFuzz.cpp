// libFuzzer target: `gbxc lsp` reading any bytes as its input stream (framing, JSON,
// requests on documents of any text). The server answers or ignores; it never dies.
#include <cstddef>
#include <cstdint>
#include <sstream>
#include <string>

#include "lsp/Server.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  std::istringstream in(std::string(reinterpret_cast<const char*>(data), size));
  std::ostringstream out;
  (void)gbx::lsp::serve(in, out);
  return 0;
}
