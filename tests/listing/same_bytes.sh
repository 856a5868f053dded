#!/bin/sh
# A long CSV listing, byte for byte, against bench/listing_program (written for that listing
# alone, sharing nothing with gbxc): every design of a 4-stage and a 3-stage spur case, one
# per orbit of interchangeable stages, ranked by |ratio - target| then the stages' ratios.
#   same_bytes.sh GBXC LISTING_PROGRAM
set -eu
gbxc=$1
program=$2
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
spec() { # STAGES MAX_TEETH
  {
    echo "gearbox Bench {"
    echo "  stage s0: spur { pinion.z in 12..$2; wheel.z in 12..$2; require coprime(pinion.z, wheel.z); }"
    i=1
    list=s0
    while [ "$i" -lt "$1" ]; do
      echo "  stage s$i like s0;"
      list="$list, s$i"
      i=$((i + 1))
    done
    echo "  interchangeable $list;"
    echo "  require ratio == 13.36838 +- 0.0001%;"
    echo "  minimize abs(ratio - 13.36838);"
    echo "  report { top 1000000; }"
    echo "}"
  } > "$dir/s$1_$2.gbx"
}
for case in "4 64" "3 100"; do
  set -- $case
  spec "$1" "$2"
  "$program" "$1" "$2" > "$dir/want.csv"
  rows=$(($(wc -l < "$dir/want.csv") - 1))
  [ "$rows" -gt 100 ] || { echo "only $rows designs from the program for $1 stages, teeth 12..$2"; exit 1; }
  for jobs in 1 2; do
    "$gbxc" solve "$dir/s$1_$2.gbx" --format csv --jobs "$jobs" > "$dir/got.csv"
    if ! cmp -s "$dir/want.csv" "$dir/got.csv"; then
      echo "$1 stages, teeth 12..$2, --jobs $jobs: the listing differs from the program's ($rows designs)"
      diff "$dir/want.csv" "$dir/got.csv" | head -10
      exit 1
    fi
  done
  echo "$1 stages, teeth 12..$2: $rows designs, same bytes"
done
