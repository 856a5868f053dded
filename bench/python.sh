#!/usr/bin/env bash
# The Python module's overhead (bench/python_overhead.py): gbxc.solve against the command
# line's own solve in the same process, alternating, on the thruster spec. Rewrites the
# "The Python module" section of docs/performance.md.
#   bench/python.sh [RUNS]     (builds first if needed; default 40 runs each way)
set -euo pipefail
cd "$(dirname "$0")/.."
[[ -d build/python/gbxc ]] || ./scripts/setup.sh >/dev/null
cmake --build build --target gbxc_python >/dev/null
runs=${1:-40}
line=$(PYTHONPATH=build/python /usr/bin/python3 bench/python_overhead.py specs/thruster_two_stage.gbx "$runs")
echo "$line"
/usr/bin/python3 - "$line" <<'PY'
import re, sys
r = dict(re.findall(r"(\S+)=(\S+)", sys.argv[1]))
sec = ["## The Python module", "",
       "`bench/python.sh` (`bench/python_overhead.py`): what `gbxc.solve` costs over the command line's",
       "own solve, both in one Python process, alternating, on `specs/thruster_two_stage.gbx` (its four",
       "gearboxes, 31 designs searched, rated ones among them). The command line's is `driver::run` with",
       "`solve --format json`, the JSON written to a string; `gbxc.solve` is the same solve plus the",
       "report read into Python objects (the JSON parsed, the designs, scenes and arrays built). Wall",
       "time, median of the runs; each run's JSON is checked to be the same bytes both ways.", "",
       "| measure | value |", "| --- | ---: |",
       f"| runs each way | {r['runs']} |",
       f"| `gbxc.solve`, median | {float(r['api_ms']):.2f} ms |",
       f"| command line in the same process, median | {float(r['cli_ms']):.2f} ms |",
       f"| overhead per solve | {float(r['overhead_ms']):.2f} ms |",
       f"| ratio, `gbxc.solve` / command line | {float(r['ratio']):.3f} |",
       f"| fastest of each | {float(r['api_min_ms']):.2f} ms / {float(r['cli_min_ms']):.2f} ms |", ""]
sys.path.insert(0, "bench")
from section import write_section
write_section(sec)
PY
