// libFuzzer target: `gbxc solve` on a buffer that checks clean, under a work budget (a
// small search budget and a wall-time cap of 1 s per input), in a report format chosen by the
// input. A runtime failure (exit 3) is a fine answer; a crash, hang or leak is not.
#include <cstddef>
#include <cstdint>
#include <sstream>
#include <string>

#include "FuzzSupport.h"
#include "Solve.h"
#include "driver/Driver.h"
#include "report/Formats.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  std::string text(reinterpret_cast<const char*>(data), size);
  auto c = gbx::driver::compileText("fuzz.gbx", text);
  if (!c->ok()) return 0;
  gbx::rt::SolveOptions o;
  const auto& formats = gbx::rt::reportFormats();
  o.format = std::string(formats[size % formats.size()].name);
  o.quiet = true;
  o.timings = false;
  o.maxDesigns = 1e5;
  o.timeLimit = 1;
  std::ostringstream out, err;
  int status = gbx::rt::solve(c->program, o, out, err);
  // A report never prints a non-finite number (docs/cli.md).
  if (status == 0 && o.format == "json" && gbx::fuzz::jsonHasNonFinite(out.str())) __builtin_trap();
  return 0;
}
