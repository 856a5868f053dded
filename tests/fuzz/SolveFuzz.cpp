// libFuzzer target: `gbxc solve` on a buffer that checks clean, under a work budget (a
// small search budget and a wall-time cap of 1 s per input), in a report format chosen by the
// input. A runtime failure (exit 3) is a fine answer; a crash, hang or leak is not.
#include <unistd.h>

#include <cstddef>
#include <cstdlib>
#include <cstdint>
#include <sstream>
#include <string>

#include "Solve.h"
#include "driver/Driver.h"
#include "report/Formats.h"

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
  // A report never prints a non-finite number (LANGUAGE.md §10): in JSON, an unquoted
  // nan or inf after `:`, `[` or `,` outside a string (a column may be named `max(x, info)`).
  if (status == 0 && o.format == "json") {
    const std::string r = out.str();
    bool inString = false;
    for (size_t i = 0; i < r.size(); ++i) {
      if (inString) {
        if (r[i] == '\\') ++i;
        else if (r[i] == '"') inString = false;
        continue;
      }
      if (r[i] == '"') inString = true;
      if (r[i] != ':' && r[i] != '[' && r[i] != ',') continue;
      size_t j = r.find_first_not_of(" \n-", i + 1);
      if (j != std::string::npos && (r.compare(j, 3, "nan") == 0 || r.compare(j, 3, "inf") == 0)) __builtin_trap();
    }
  }
  return 0;
}
