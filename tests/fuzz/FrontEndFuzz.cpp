// libFuzzer target: what `gbxc check` does with a buffer (parse, names, types, units,
// lowering), then both diagnostic renderings. Any crash, hang, leak or sanitizer report is
// a bug: bad input must come back as diagnostics.
#include <cstddef>
#include <cstdint>
#include <string>

#include "driver/Driver.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  std::string text(reinterpret_cast<const char*>(data), size);
  auto c = gbx::driver::compileText("fuzz.gbx", text);
  (void)c->diags.renderText(c->sources);
  (void)c->diags.renderJson(c->sources);
  return 0;
}
