#!/usr/bin/env bash
# The shaft model's cost: bench/shaft_bench three times in one run (the median of each
# figure), against one ISO 6336 mesh rating in the same process. Rewrites the "Shafts"
# section of docs/performance.md.
set -euo pipefail
cd "$(dirname "$0")/.."
cmake --build build --target shaft_bench >/dev/null
out=$(mktemp)
for i in 1 2 3; do build/bench/shaft_bench >>"$out"; done
python3 - "$out" <<'PY'
import re, statistics, sys
text = open(sys.argv[1]).read()
def med(pattern):
    return statistics.median(float(x) for x in re.findall(pattern, text))
static = med(r"(?m)^static ([\d.]+) us")
stations = re.search(r"(?m)^static [\d.]+ us \((\d+) stations\)", text).group(1)
modes200 = med(r"(?m)^modes ([\d.]+) us \(200")
rating = med(r"(?m)^rating ([\d.]+) us")
sec = ["## Shafts", "",
       "`bench/shaft_bench.cpp`: a shaft of 200 elements (200 stepped, partly hollow segments, 100",
       "loads with torque and thrust, two bearings, one elastic), its static solve (both bending",
       "planes at one sparse LDL^T factorisation, torsion and thrust in closed form) and its first",
       "natural frequencies (a dense generalised eigenproblem on 400 dofs), against one ISO 6336",
       "mesh rating in the same process; the median of three runs, each the median of 7 repeats.", "",
       "| measure | value | ratio to one rating |", "| --- | ---: | ---: |",
       f"| static solve, {stations} stations | {static:.0f} us | {static/rating:.0f} |",
       f"| first natural frequencies, 200 elements | {modes200/1000:.0f} ms | {modes200/rating:.0f} |",
       f"| one mesh rated | {rating:.2f} us | 1 |", ""]
sys.path.insert(0, "bench")
from section import write_section
write_section(sec)
print("\n".join(sec))
PY
rm -f "$out"
