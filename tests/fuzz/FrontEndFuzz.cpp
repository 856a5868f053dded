// libFuzzer target: what `gbxc check` does with a buffer (parse, names, types, units,
// lowering), then both diagnostic renderings, then what `gbxc fmt` does with it. Any
// crash, hang, leak or sanitizer report is a bug: bad input must come back as diagnostics.
// A layout that would change how the text reads throws out of formatText: a finding too.
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string>

#include "driver/Driver.h"
#include "format/Formatter.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  std::string text(reinterpret_cast<const char*>(data), size);
  auto c = gbx::driver::compileText("fuzz.gbx", text);
  (void)c->diags.renderText(c->sources);
  (void)c->diags.renderJson(c->sources);

  gbx::source::SourceManager sm;
  gbx::diag::DiagnosticEngine diags;
  auto once = gbx::format::formatText("fuzz.gbx", text, sm, diags);
  if (once) {
    // The layout is a fixed point.
    auto twice = gbx::format::formatText("fuzz.gbx", *once, sm, diags);
    if (!twice || *twice != *once) std::abort();
  }
  return 0;
}
