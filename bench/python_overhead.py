"""The Python module's overhead over the command line's own solve in the same process: the
thruster spec solved N times each way, alternating (gbxc.solve, then driver::run's `gbxc solve
--format json` through the module's `cli`), wall seconds of each; prints one line of results."""

import statistics
import sys
import time

import gbxc
from gbxc import _gbxc

spec, n = sys.argv[1], int(sys.argv[2])
api, cli = [], []
for _ in range(n):
    t = time.perf_counter()
    report = gbxc.solve(spec, timings=False)
    api.append(time.perf_counter() - t)
    t = time.perf_counter()
    status, out, _ = _gbxc.cli(["solve", spec, "--format", "json", "--no-timings", "-q"])
    cli.append(time.perf_counter() - t)
    assert status == 0 and out == report.to_json()
a, c = statistics.median(api), statistics.median(cli)
print(f"runs={n} api_ms={a * 1e3:.3f} cli_ms={c * 1e3:.3f} overhead_ms={(a - c) * 1e3:.3f} ratio={a / c:.3f} "
      f"api_min_ms={min(api) * 1e3:.3f} cli_min_ms={min(cli) * 1e3:.3f}")
