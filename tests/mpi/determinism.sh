#!/usr/bin/env bash
# The same files from `gbxc solve SPEC --jobs 1`, `--jobs 2` and `mpirun -n 4 … --jobs 2`
# (docs/optimisation.md), for each SPEC: every table (designs, Monte Carlo statistics, every
# sample), every chart and the report, byte for byte: the search's join, the optimiser's
# candidates and the Monte Carlo samples are what the ranks share. Two threads per rank as
# well: the ranks must exchange at the same points whatever their threads do.
#   determinism.sh GBXC GBXC_MPI SPEC...
set -euo pipefail
gbxc=$1 mpi=$2
shift 2
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
for spec in "$@"; do
  rm -rf "$work"/*
  "$gbxc" solve "$spec" --no-timings --format csv --jobs 1 -o "$work/jobs1" >/dev/null
  "$gbxc" solve "$spec" --no-timings --format csv --jobs 2 -o "$work/jobs2" >/dev/null
  # --oversubscribe: more ranks than cores; --allow-run-as-root: CI is root. A bound on the
  # time: ranks that wait on each other forever fail the test instead of hanging it.
  timeout 300 mpirun --oversubscribe --allow-run-as-root -n 4 "$mpi" solve "$spec" --no-timings --format csv --jobs 2 \
    -o "$work/ranks4" >/dev/null
  # A spec that draws samples must have written them (else the comparison proves little).
  if grep -q "samples = " "$spec" && grep -q "tolerances" "$spec"; then
    test -s "$work/jobs1/samples.csv" || { echo "no samples.csv from $spec" >&2; exit 1; }
  fi
  diff -r "$work/jobs1" "$work/jobs2"
  diff -r "$work/jobs1" "$work/ranks4"
  echo "same bytes: $(ls "$work/jobs1" | wc -l) files of $(basename "$spec") for --jobs 1, --jobs 2 and mpirun -n 4"
done
