#pragma once
// What the fuzz targets and the regression test share.
#include <unistd.h>

#include <cstdlib>
#include <string>

namespace gbx::fuzz {

// An unquoted nan or inf after `:`, `[` or `,` of a JSON report, outside its strings (a
// column may be named `max(x, info)`): a non-finite number docs/cli.md forbids.
inline bool jsonHasNonFinite(const std::string& r) {
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
    if (j != std::string::npos && (r.compare(j, 3, "nan") == 0 || r.compare(j, 3, "inf") == 0)) return true;
  }
  return false;
}

// Inputs run in an empty folder of their own: an `import "x.gbx"` finds nothing there, so
// what an input does never depends on the files around it.
inline void enterEmptyFolder() {
  char dir[] = "/tmp/gbx-fuzz-XXXXXX";
  if (mkdtemp(dir)) (void)chdir(dir);
}

} // namespace gbx::fuzz
