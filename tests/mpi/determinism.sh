#!/usr/bin/env bash
# The same files from `gbxc solve SPEC --jobs 1`, `--jobs 2` and `mpirun -n 4` (LANGUAGE.md
# §19): every table (designs, Monte Carlo statistics, every sample), every chart and the
# report, byte for byte.
#   determinism.sh GBXC GBXC_MPI SPEC
set -euo pipefail
gbxc=$1 mpi=$2 spec=$3
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
"$gbxc" solve "$spec" --no-timings --format csv --jobs 1 -o "$work/jobs1" >/dev/null
"$gbxc" solve "$spec" --no-timings --format csv --jobs 2 -o "$work/jobs2" >/dev/null
# --oversubscribe: four ranks on a machine with fewer cores; --allow-run-as-root: CI is root.
mpirun --oversubscribe --allow-run-as-root -n 4 "$mpi" solve "$spec" --no-timings --format csv -o "$work/ranks4" >/dev/null
test -s "$work/jobs1/samples.csv" || { echo "no samples.csv: $spec is not a Monte Carlo spec" >&2; exit 1; }
diff -r "$work/jobs1" "$work/jobs2"
diff -r "$work/jobs1" "$work/ranks4"
echo "same bytes: $(ls "$work/jobs1" | wc -l) files for --jobs 1, --jobs 2 and mpirun -n 4"
