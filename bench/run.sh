#!/usr/bin/env bash
# Runs the search benchmark and rewrites docs/performance.md. Same-run comparisons only:
# this machine is shared, so every ratio below comes from one invocation of this script.
#   bench/run.sh            (builds first if needed)
#   GBX_BASELINE=OTHER/gbxc GBX_BASELINE_NAME="gbxc at 87b43f7" bench/run.sh
#                           (the marine optimisation timed against another build as well)
set -euo pipefail
cd "$(dirname "$0")/.."
[[ -x build/bench/search_bench ]] || ./scripts/setup.sh >/dev/null
cmake --build build --target search_bench dynamics_bench rating_bench mitm_program listing_program gbxc >/dev/null
# gbxc-mpi where Open MPI is installed (the Monte Carlo ranks' table).
cmake --build build --target gbxc-mpi >/dev/null 2>&1 || true
py=/usr/bin/python3
if ! $py -c 'import scipy' 2>/dev/null; then
  sudo=""; [[ $(id -u) -ne 0 ]] && sudo=sudo
  DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -q python3-scipy >/dev/null
fi
b=build/bench/search_bench
out=$(mktemp)
for c in paper2 spur3 spur4; do
  for j in 1 2; do $b $c $j >>"$out"; done
done
for c in spur3-50 spur3-60 spur3-70 spur4-30 spur4-35 spur4-40; do $b $c 1 >>"$out"; done
# The meet-in-the-middle reference in the same process (times), alone (its memory); the
# listing of every design; the helical top 10 against an exhaustive ranking; the front end.
mitm=$(mktemp)
for c in mitm3 mitm4 ref3 ref4 list4 check; do $b $c >>"$mitm"; done
$b helical 2 >>"$mitm"
d=build/bench/dynamics_bench
dyn=$(mktemp) params=$(mktemp)
$d params "$params"
$d wp | sed 's/^/gbxc /' >>"$dyn"
$py bench/scipy_mesh.py "$params" | sed 's/^/scipy /' >>"$dyn"
$d rhs >"$dyn.rhs"
$d steady >"$dyn.steady"
build/bench/rating_bench >"$dyn.rating"
# The corpus's marine optimisation (contact-line scene) settled (200 periods) and periodic,
# whole process, alternating A B A B in this run; CPU seconds of each.
settle_spec=$(mktemp --suffix=.gbx) periodic_spec=$(mktemp --suffix=.gbx)
cp tests/golden/ir/marine_reducer.gbx "$settle_spec"
sed 's/^    settle = 200 mesh_periods;.*/    steady_state = periodic;/' "$settle_spec" >"$periodic_spec"
TIMEFORMAT=%U
for i in 1 2 3; do
  { time build/gbxc solve "$settle_spec" --gearbox MarineReducerOptimised --no-timings >/dev/null; } 2>>"$dyn.opt.settle"
  { time build/gbxc solve "$periodic_spec" --gearbox MarineReducerOptimised --no-timings >/dev/null; } 2>>"$dyn.opt.periodic"
done
# The project's marine optimisation (loaded mesh, worst over 4 tolerance corners), one run;
# with GBX_BASELINE (another build's gbxc, e.g. of an earlier commit) the two alternate, one
# run each, and the section gives the speed-up of this build over it.
{ time build/gbxc solve specs/marine_reducer.gbx --gearbox MarineReducerOptimised --no-timings --jobs 1 >"$dyn.robust.out"; } 2>"$dyn.robust"
: >"$dyn.robust.base"
if [ -n "${GBX_BASELINE:-}" ] && [ -x "$GBX_BASELINE" ]; then
  { time "$GBX_BASELINE" solve specs/marine_reducer.gbx --gearbox MarineReducerOptimised --no-timings --jobs 1 >"$dyn.robust.base.out"; } 2>"$dyn.robust.base"
  { time build/gbxc solve specs/marine_reducer.gbx --gearbox MarineReducerOptimised --no-timings --jobs 1 >/dev/null; } 2>>"$dyn.robust"
  echo "${GBX_BASELINE_NAME:-$GBX_BASELINE}" >>"$dyn.robust.base"
fi
# Paper P4's whole mechanism for 0.1 s: msbdf with the analytic Jacobian against rk8pd.
for m in msbdf rk8pd; do
  sed -e 's/^    duration = 1 s;/    duration = 0.1 s;/' -e "s/method = msbdf;/method = $m;/" specs/electric_cylinder.gbx >"$dyn.ec.gbx"
  for i in 1 2 3; do
    { time build/gbxc solve "$dyn.ec.gbx" --gearbox ElectricCylinderBuilt --no-timings >/dev/null; } 2>>"$dyn.ec.$m"
  done
done
$py - "$out" "$dyn" "$dyn.rhs" "$dyn.rating" "$dyn.steady" "$dyn.opt.settle" "$dyn.opt.periodic" "$dyn.robust" "$dyn.robust.out" \
  "$dyn.ec.msbdf" "$dyn.ec.rk8pd" "$mitm" <<'PY'
import math, sys
rows = [l.split() for l in open(sys.argv[1])]
def pairs(n): return sum(1 for p in range(12, n + 1) for w in range(p + 1, n + 1) if math.gcd(p, w) == 1)
def multisets(n, k): return math.comb(pairs(n) + k - 1, k)
import platform, subprocess
cpu = next((l.split(":", 1)[1].strip() for l in open("/proc/cpuinfo") if l.startswith("model name")), platform.machine())
lines = ["# Performance", "",
         f"Produced by `bench/run.sh` ({cpu}, 2 cores, shared) in one run; times are medians of",
         "repeated searches (front end excluded), memory is the peak RSS of the benchmark process.",
         "The reference is a plain enumeration of every multiset of coprime reduction pairs,",
         "checked exactly (`bench/search_bench.cpp`); where it would take too long it is run on",
         "smaller tooth ranges and extrapolated by the number of multisets it must visit.", "",
         "## Tooth-count search", "",
         "| case | jobs | designs | search time | peak memory |", "| --- | ---: | ---: | ---: | ---: |"]
names = {"paper2": "thruster, two bevel stages (paper P0, docs/sources.md)",
         "spur3": "3 spur stages, teeth 12..100, 13.36838 ± 1e-6 rel., top 100",
         "spur4": "4 spur stages, teeth 12..100, 13.36838 ± 1e-6 rel., top 100"}
for r in rows:
    if r[0] in names:
        t = float(r[3])
        lines.append(f"| {names[r[0]]} | {r[1]} | {r[2]} | {t*1000:.3f} ms | {float(r[5]):.0f} MiB |")
lines += ["", "## Against the brute-force reference", "",
          "| case | designs | gbxc | reference | ratio |", "| --- | ---: | ---: | ---: | ---: |"]
ref = {}
for r in rows:
    if "-" in r[0]:
        k, n = int(r[0][4]), int(r[0].split("-")[1])
        ref.setdefault(k, []).append((n, float(r[4]), float(r[3])))
        lines.append(f"| {k} stages, teeth 12..{n} | {r[2]} | {float(r[3])*1000:.2f} ms | {float(r[4]):.3f} s | {float(r[4])/float(r[3]):.0f}x |")
lines += ["", "Extrapolated to teeth 12..100 (reference time per visited multiset, taken from the",
          "largest range run, times the multisets of the full range):", "",
          "| case | gbxc (measured) | reference (extrapolated) | ratio |", "| --- | ---: | ---: | ---: |"]
full = {int(r[0][4]): float(r[3]) for r in rows if r[0] in ("spur3", "spur4") and r[1] == "1"}
for k, pts in sorted(ref.items()):
    n, t, _ = max(pts)
    per = t / multisets(n, k)
    est = per * multisets(100, k)
    shown = f"{est:.0f} s" if est < 600 else f"{est:.0f} s ({est/3600:.1f} h)"
    lines.append(f"| {k} stages | {full[k]:.3f} s | {shown} | {est/full[k]:.0f}x |")
# ---- against the meet-in-the-middle reference ---------------------------------------
mr = {l.split()[0]: l.split()[1:] for l in open(sys.argv[12])}
peak = {r[0]: float(r[5]) for r in rows if r[0] in ("spur3", "spur4") and r[1] == "1"}
lines += ["", "## Against a meet-in-the-middle reference", "",
          "`bench/mitm_reference.h`: a straightforward C++ meet-in-the-middle written for these cases",
          "alone (coprime pairs sorted by ratio, the right half bucketed by log ratio, each left entry",
          "scanning the buckets its window covers, every match confirmed in 128-bit integers, the",
          "best 100 by |ratio - target| in a heap). Times: gbxc's search (top 100) and the reference",
          "alternating in one process (`search_bench mitm3|mitm4`), medians, both checked to give the",
          "same count and the same best 100. Memory: peak RSS of a process running only one of them",
          "(`search_bench spur3|spur4` for gbxc, with its compiled spec; `ref3|ref4`).", "",
          "| case | designs | gbxc | reference | time ratio | gbxc peak | reference peak | memory ratio |",
          "| --- | ---: | ---: | ---: | ---: | ---: | ---: | ---: |"]
for k in (3, 4):
    cnt, g, r = mr[f"mitm{k}"]
    rp = float(mr[f"ref{k}"][2])
    lines.append(f"| {k} spur stages, teeth 12..100, top 100 | {cnt} | {float(g)*1000:.1f} ms | {float(r)*1000:.1f} ms | "
                 f"{float(g)/float(r):.2f}x | {peak[f'spur{k}']:.1f} MiB | {rp:.1f} MiB | {peak[f'spur{k}']/rp:.2f}x |")
cnt, g, r, gb, rb = mr["list4"]
lines += ["", "Every design of the 4-stage case listed: `gbxc solve --format csv` in-process (search, ranking,",
          "the report's rows, CSV) against the reference writing one CSV line per design as it finds",
          "it (unranked: the output bound), medians of three:", "",
          "| case | designs | gbxc | reference | ratio | gbxc bytes | reference bytes |", "| --- | ---: | ---: | ---: | ---: | ---: | ---: |",
          f"| 4 spur stages, every design as CSV | {cnt} | {float(g):.2f} s | {float(r):.2f} s | {float(g)/float(r):.1f}x | {int(gb)} | {int(rb)} |"]
cnt, pr, ex, pk = mr["helical"]
lines += ["", "Objective-bounded top N: three helical stages, ratio 40 +- 0.5 %, pinions 17..30, wheels",
          "65..120, modules {2, 2.5, 3} mm, `minimize s1.mass + s2.mass + s3.mass`, top 10. The pruned",
          "search (median of three) against an exhaustive one that keys every design with the",
          "evaluator (`exhaustive`, two threads); the bench fails unless both give the same count and",
          "the same top 10:", "",
          "| case | designs | pruned | exhaustive | ratio |", "| --- | ---: | ---: | ---: | ---: |",
          f"| helical, top 10 by total mass | {cnt} | {float(pr):.3f} s | {float(ex):.1f} s | {float(ex)/float(pr):.0f}x |"]
import subprocess, time
def whole(cmd, n=30):
    ts = []
    for _ in range(n):
        t0 = time.perf_counter()
        subprocess.run(cmd, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
        ts.append(time.perf_counter() - t0)
    return sorted(ts)[n // 2]
chk = whole(["build/gbxc", "check", "specs/thruster_two_stage.gbx"])
ver = whole(["build/gbxc", "--version"])
lines += ["", "The front end: `gbxc check specs/thruster_two_stage.gbx` as a whole process (wall, median of",
          "30 runs; `gbxc --version` shows what starting the process alone costs) and in-process",
          "(`search_bench check`: parse, check and lower, median of 200):", "",
          "| measure | time |", "| --- | ---: |",
          f"| check, whole process | {chk*1000:.2f} ms |", f"| gbxc --version, whole process | {ver*1000:.2f} ms |",
          f"| check, in-process | {float(mr['check'][0])*1000:.3f} ms |", "",
          "Targets: in-process within 2x of the reference on the 3- and 4-stage cases with at most 2x",
          "its memory; every design listed within 3x of the output bound; the helical top 10 under",
          "5 s and the same as the exhaustive ranking; `check` of a small spec under 5 ms.", ""]
# ---- whole processes: written by bench/processes.sh (called below) -----------------
import os, sys, tempfile
sys.path.insert(0, "bench")
from rusage import run_rusage
def median(v): return sorted(v)[len(v) // 2]
lines += ["## Against a faster meet-in-the-middle program, whole processes", "", "(bench/processes.sh)", ""]
# ---- Monte Carlo and the optimiser over MPI ranks -----------------------------------
if os.path.exists("build/gbxc-mpi") and subprocess.run(["sh", "-c", "command -v mpirun"], capture_output=True).returncode == 0:
    mpirun = ["mpirun", "--oversubscribe", "--allow-run-as-root", "-n"]
    mc = "specs/marine_tolerances.gbx"
    plain = {j: run_rusage(["build/gbxc", "solve", mc, "--no-timings", "--jobs", str(j)]) for j in (1, 2)}
    ranks = {n: run_rusage(mpirun + [str(n), "build/gbxc-mpi", "solve", mc, "--no-timings"]) for n in (1, 2, 4)}
    sweep = "specs/spur_resonance.gbx"
    def medians(runs): return tuple(median([r[i] for r in runs]) for i in range(3))
    swr = {n: medians([run_rusage(mpirun + [str(n), "build/gbxc-mpi", "solve", sweep, "--no-timings"]) for _ in range(3)]) for n in (1, 2, 4)}
    # The parts of one solve: the samples' scenes and quantities, and the rest (the nominal
    # scene with its error estimate, the rating, the report), from a run without samples.
    nos = tempfile.NamedTemporaryFile("w", suffix=".gbx", delete=False)
    nos.write(open(mc).read().replace("samples = 2000;", "samples = 2;"))
    nos.close()
    rest = median([run_rusage(["build/gbxc", "solve", nos.name, "--no-timings"])[0] for _ in range(3)])
    os.unlink(nos.name)
    n_samples = 2000
    per_sample = (plain[1][0] - rest) / n_samples
    # What the ranks exchange: per sample, the scene's numbers and each quantity, each with
    # its index and length (doubles).
    gather_bytes = n_samples * ((2 + 2) + 3 * (2 + 1)) * 8
    lines += ["## Monte Carlo over MPI ranks", "",
              f"`{mc}`: 2000 samples, each a loaded-mesh scene (240 slices x 512 positions) and two",
              "ratings; `mpirun --oversubscribe -n N build/gbxc-mpi solve` against `build/gbxc --jobs J`,",
              "one run each, on this 2-core machine (4 ranks share 2 cores). Efficiency: the one-rank",
              "wall time over N times the N-rank wall time (over the cores used, min(N, 2), in brackets).", "",
              "| run | wall | CPU (all ranks) | speed-up | efficiency |", "| --- | ---: | ---: | ---: | ---: |"]
    t1 = ranks[1][2]
    for j in (1, 2):
        lines.append(f"| gbxc --jobs {j} | {plain[j][2]:.2f} s | {plain[j][0]:.2f} s | {t1/plain[j][2]:.2f}x | - |")
    for n in (1, 2, 4):
        w = ranks[n][2]
        lines.append(f"| mpirun -n {n} | {w:.2f} s | {ranks[n][0]:.2f} s | {t1/w:.2f}x | {t1/(n*w):.2f} ({t1/(min(n, 2)*w):.2f}) |")
    lines += ["", "The same report, byte for byte, from each (`tests/mpi/determinism.sh`, in the suite).", "",
              f"On paper, from these figures: a sample costs {per_sample*1000:.1f} ms of CPU; the rest of the solve,",
              f"which every rank repeats, {rest*1000:.0f} ms; the gather moves {gather_bytes/1024:.0f} KiB to every rank",
              "(four MPI_Allgatherv calls: one per sampled scene and quantity, plus their sizes; taken",
              "at 1 GB/s and 50 us per doubling step on a cluster's network). Wall time",
              "T(N) = rest + ceil(2000 / N) x per sample + gather:", "",
              "| ranks | T(N) | speed-up | efficiency |", "| ---: | ---: | ---: | ---: |"]
    t_1 = rest + n_samples * per_sample
    for n in (1, 2, 4, 64, 1024):
        gather = 0 if n == 1 else gather_bytes / 1e9 + 4 * 50e-6 * math.log2(n)
        t = rest + math.ceil(n_samples / n) * per_sample + gather
        lines.append(f"| {n} | {t*1000:.0f} ms | {t_1/t:.1f}x | {t_1/(n*t):.2f} |")
    big = 10000
    t_big1 = rest + big * per_sample
    t_big = rest + math.ceil(big / 1024) * per_sample + gather_bytes * big / n_samples / 1e9 + 4 * 50e-6 * 10
    lines += ["", "Beyond a few tens of ranks the part every rank repeats (the nominal scene's error",
              "estimate against finer runs, the rating, the report) decides; with 10 000 samples 1024",
              f"ranks would reach {t_big1/t_big:.0f}x (efficiency {t_big1/(1024*t_big):.2f}).", "",
              f"A sweep is not shared over ranks: `{sweep}` (its sweep of a periodic scene, each point",
              "starting from the last point's orbit, so that near a resonance the up- and down-sweeps",
              "keep their branches) runs whole on every rank, median of three:", "",
              "| ranks | wall | CPU (all ranks) |", "| ---: | ---: | ---: |"]
    for n in (1, 2, 4):
        lines.append(f"| {n} | {swr[n][2]*1000:.0f} ms | {swr[n][0]*1000:.0f} ms |")
    # The optimiser's candidates over ranks: the marine optimisation (11 candidates).
    mo = ["solve", "specs/marine_reducer.gbx", "--gearbox", "MarineReducerOptimised", "--no-timings", "--jobs", "1"]
    opt_plain = run_rusage(["build/gbxc"] + mo)
    opt_ranks = {n: run_rusage(mpirun + [str(n), "build/gbxc-mpi"] + mo) for n in (1, 2, 4)}
    o1 = opt_ranks[1][2]
    lines += ["", "The optimiser's candidates over ranks: the marine optimisation (`specs/marine_reducer.gbx`,",
              "`MarineReducerOptimised`: 11 candidates, each a Nelder-Mead run of loaded-mesh scenes; some",
              "take twice as long as others, so 4 ranks hold 3, 3, 3 and 2), `--jobs 1` per rank, one run each:", "",
              "| run | wall | CPU (all ranks) | speed-up | efficiency |", "| --- | ---: | ---: | ---: | ---: |",
              f"| gbxc --jobs 1 | {opt_plain[2]:.2f} s | {opt_plain[0]:.2f} s | {o1/opt_plain[2]:.2f}x | - |"]
    for n in (1, 2, 4):
        w = opt_ranks[n][2]
        lines.append(f"| mpirun -n {n} | {w:.2f} s | {opt_ranks[n][0]:.2f} s | {o1/w:.2f}x | {o1/(n*w):.2f} ({o1/(min(n, 2)*w):.2f}) |")
    lines.append("")
# ---- dynamics -------------------------------------------------------------------
dyn = [l.split() for l in open(sys.argv[2])]
curves = {}
for who, method, rtol, err, cpu, rhs in dyn:
    curves.setdefault(f"{who} {method}", []).append((float(rtol), float(err), float(cpu), int(rhs)))
def at_error(points, target):
    # log-log interpolation of CPU time at a given error along a work-precision curve
    pts = sorted((e, c) for _, e, c, _ in points if e > 0)
    for (e1, c1), (e2, c2) in zip(pts, pts[1:]):
        if e1 <= target <= e2:
            f = (math.log(target) - math.log(e1)) / (math.log(e2) - math.log(e1))
            return math.exp(math.log(c1) + f * (math.log(c2) - math.log(c1)))
    return None
lines += ["## Dynamics: the marine-reducer vibration scene", "",
          "The acceptance corpus's scene (`tests/golden/ir/marine_reducer.gbx`: single mesh, 5 stiffness harmonics, damping,",
          "transmission error; 200 mesh periods settled, one recorded at 160 samples) integrated",
          "by gbxc and, with the same equations, parameters, sample times and scaled tolerances",
          "(`bench/scipy_mesh.py`), by `scipy.integrate.solve_ivp` (Debian python3-scipy). The",
          "error is that of rms(acceleration) against gbxc's rk8pd at rtol 1e-14; CPU time is the",
          "median of five runs for gbxc, one run for scipy.", "",
          "| solver | rtol | error | CPU time | RHS evaluations |", "| --- | ---: | ---: | ---: | ---: |"]
for name, pts in curves.items():
    for rtol, err, cpu, rhs in pts:
        lines.append(f"| {name} | {rtol:.0e} | {err:.2e} | {cpu*1000:.2f} ms | {rhs} |")
lines += ["", "At matched error (CPU time interpolated along each curve, log-log):", "",
          "| error | gbxc rk8pd | scipy DOP853 | scipy RK45 | ratio to DOP853 | ratio to RK45 |",
          "| ---: | ---: | ---: | ---: | ---: | ---: |"]
for target in (1e-6, 1e-7, 1e-8):
    g = at_error(curves.get("gbxc rk8pd", []), target)
    d = at_error(curves.get("scipy DOP853", []), target)
    r = at_error(curves.get("scipy RK45", []), target)
    fmt = lambda x: f"{x*1000:.2f} ms" if x else "out of range"
    ratio = lambda x: f"{x/g:.0f}x" if x and g else "-"
    lines.append(f"| {target:.0e} | {fmt(g)} | {fmt(d)} | {fmt(r)} | {ratio(d)} | {ratio(r)} |")
lines += ["", "Target: gbxc at least 50x faster than scipy at error 1e-8.", "",
          "### Cost of one right-hand side, by effect", "",
          "Each effect adds its own term; effects a scene does not list cost nothing.", "",
          "| model | ns per RHS call |", "| --- | ---: |"]
rhs = [l.rstrip("\n").split("|") for l in open(sys.argv[3])]
for name, ns, _ in rhs:
    lines.append(f"| {name} | {float(ns):.1f} |")
hand, base = float(rhs[0][1]), float(rhs[1][1])
lines += ["", f"The base model against the hand-written base: {base/hand:.2f}x (target: within 1.3x).", ""]
# ---- periodic steady state --------------------------------------------------------
steady = {}
for l in open(sys.argv[5]):
    way, rtol, err, cpu, rhs_n = l.split()
    steady.setdefault(way, {})[rtol] = (float(err), float(cpu), int(rhs_n))
lines += ["### Periodic steady state against settling", "",
          "The same scene, `dynamics_bench steady`: the periodic orbit found directly (shooting;",
          "the scene is linear, so one Newton step on the monodromy matrix plus a confirming one)",
          "against 200 settled periods, both with rk8pd and one period recorded. Error of",
          "rms(acceleration) against the periodic orbit at rtol 1e-13; CPU time the median of five.", "",
          "| rtol | periodic error | periodic RHS | periodic CPU | settle error | settle RHS | settle CPU | CPU ratio | RHS ratio |",
          "| ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: |"]
for rtol in steady.get("periodic", {}):
    pe, pc, pr = steady["periodic"][rtol]
    se, sc, sr = steady["settle"][rtol]
    lines.append(f"| {float(rtol):.0e} | {pe:.2e} | {pr} | {pc*1000:.2f} ms | {se:.2e} | {sr} | {sc*1000:.2f} ms | {sc/pc:.1f}x | {sr/pr:.1f}x |")
opt_s = sorted(float(x) for x in open(sys.argv[6]).read().split())
opt_p = sorted(float(x) for x in open(sys.argv[7]).read().split())
ms_, mp_ = opt_s[len(opt_s)//2], opt_p[len(opt_p)//2]
lines += ["", "The corpus's marine optimisation (`MarineReducerOptimised` of `tests/golden/ir/marine_reducer.gbx`),",
          "whole process, its scene settled (`settle = 200 mesh_periods`, as the corpus writes it) against",
          "`steady_state = periodic`, three alternating runs each, median user CPU:", "",
          "| scene | CPU |", "| --- | ---: |",
          f"| settle 200 periods | {ms_:.2f} s |", f"| periodic | {mp_:.2f} s |",
          f"| ratio | {ms_/mp_:.1f}x (target: at least 5x) |", ""]
robust_runs = sorted(float(x) for x in open(sys.argv[8]).read().split())
robust = robust_runs[0]
evals = next((l.split(";")[1].split()[0] for l in open(sys.argv[9]) if "objective evaluations" in l), "?")
base = open(sys.argv[8] + ".base").read().split()
lines += ["The project's marine optimisation (`specs/marine_reducer.gbx`: `loaded_mesh` with 240 slices x",
          "512 positions and 32 harmonics, the objective `worst(…)` over a box of two tolerances, so",
          "five scene runs per evaluation), `--jobs 1`, user CPU (the least of this build's runs):", "",
          "| measure | value |", "| --- | ---: |",
          f"| whole process | {robust:.2f} s |", f"| objective evaluations | {evals} |",
          f"| per evaluation (five scene runs) | {robust/float(evals)*1000:.2f} ms |" if evals != "?" else ""]
if len(base) >= 2:
    b = float(base[0])
    def optimum(path):
        return [l.strip() for l in open(path) if l.strip().startswith(("optimum:", "worst(vibration", "over the tolerance box"))]
    same = optimum(sys.argv[9]) == optimum(sys.argv[8] + ".base.out")
    lines += [f"| the same run by `{' '.join(base[1:])}`, between this build's two | {b:.2f} s |",
              f"| speed-up | {b/robust:.1f}x (target: at least 5x; the search issue measured 52 s, 43.5 ms per evaluation) |",
              f"| the optimum, its worst corner and its range over the box, as printed | {'the same' if same else 'DIFFERENT'} |"]
else:
    lines += ["| speed-up | not measured in this run: give GBX_BASELINE (an earlier build's gbxc) |"]
lines += ["", "The table is built per position by Newton on the piecewise-linear load balance (warm-started",
          "from the last position, two passes of the pairs each), kept for an identical input, and the",
          "linear orbit is found from one monodromy matrix with the record run confirming it.", ""]
ec_m = sorted(float(x) for x in open(sys.argv[10]).read().split())
ec_r = sorted(float(x) for x in open(sys.argv[11]).read().split())
em, er = ec_m[len(ec_m)//2], ec_r[len(ec_r)//2]
lines += ["## Dynamics: paper P4's whole mechanism", "",
          "`specs/electric_cylinder.gbx` (`ElectricCylinderBuilt`) with every scene cut to",
          "0.1 s (the two planetary stage scenes with rk8pd in both); the source paper's contact damping makes the light",
          "idler stiff. Whole process, median user CPU of three runs each:", "",
          "| whole-gearbox scenes integrated by | CPU |", "| --- | ---: |",
          f"| msbdf, analytic Jacobian | {em:.2f} s |", f"| rk8pd | {er:.2f} s |",
          f"| ratio | {er/em:.1f}x |", ""]
# ---- rating ---------------------------------------------------------------------
rating = {l.split()[0]: l.split()[1:] for l in open(sys.argv[4])}
rated, with_rule, without = int(rating["search"][0]), float(rating["search"][1]), float(rating["search"][2])
lines += ["## Load capacity (ISO 6336)", "",
          "`bench/rating_bench.cpp`: one mesh rated (ISO/TR 6336-30 Example 1's pair, method B with",
          "the Y_F iteration), median of 7 x 20 000; and one helical stage searched over 76 857",
          "tooth-count pairs with and without `require pinion.contact_safety >= 1.1`, median of 5.",
          "The strength rule runs after the ratio rule, so only the candidates that passed it are rated.", "",
          "| measure | value |", "| --- | ---: |",
          f"| one mesh rated | {float(rating['mesh'][0])/1000:.2f} us |",
          f"| search without the strength rule | {without*1000:.1f} ms |",
          f"| search with it ({rated} candidates rated) | {with_rule*1000:.1f} ms |",
          f"| cost per rated candidate (quantity lookup, inputs, rating) | {(with_rule-without)/rated*1e6:.2f} us |",
          f"| ratio with / without | {with_rule/without:.2f} |", ""]
open("docs/performance.md", "w").write("\n".join(lines))
print("\n".join(lines))
PY
rm -f "$mitm" "$out" "$dyn" "$dyn.rhs" "$dyn.rating" "$dyn.steady" "$dyn.opt.settle" "$dyn.opt.periodic" "$settle_spec" "$periodic_spec" "$params" \
  "$dyn.robust" "$dyn.robust.out" "$dyn.ec.gbx" "$dyn.ec.msbdf" "$dyn.ec.rk8pd"
# The sizing and shaft sections, appended to the file just written.
bench/processes.sh >/dev/null
bench/sizing.sh >/dev/null
bench/shaft.sh >/dev/null
bench/python.sh >/dev/null
bench/balance.sh >/dev/null
