// libFuzzer target: what `gbxc check` does with a buffer (parse, names, types, units,
// lowering), then both diagnostic renderings. Any crash, hang, leak or sanitizer report is
// a bug: bad input must come back as diagnostics.
#include <unistd.h>

#include <cstddef>
#include <cstdlib>
#include <cstdint>
#include <string>

#include "driver/Driver.h"

// Inputs run in an empty folder of their own: an `import "x.gbx"` finds nothing there, so
// what an input does never depends on the files around it.
extern "C" int LLVMFuzzerInitialize(int*, char***) {
  char dir[] = "/tmp/gbx-fuzz-XXXXXX";
  if (mkdtemp(dir) && chdir(dir) == 0) return 0;
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  std::string text(reinterpret_cast<const char*>(data), size);
  auto c = gbx::driver::compileText("fuzz.gbx", text);
  (void)c->diags.renderText(c->sources);
  (void)c->diags.renderJson(c->sources);
  return 0;
}
