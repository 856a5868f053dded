#!/usr/bin/env bash
# Runs the libFuzzer targets of tests/fuzz (build them with scripts/setup.sh --sanitize).
#   scripts/fuzz.sh [SECONDS] [front_end|solve|lsp]...   each target for SECONDS (default 120)
# Seeds: the committed corpus (tests/fuzz/corpus/<target>), specs/, the golden inputs and
# the regression folder, with the language's dictionary. New inputs go to
# build-asan/corpus/<target> (never into the tree). A crash, leak, timeout or sanitizer
# report stops the target, leaves its reproducer in build-asan/artifacts/ and fails the run;
# copy it into tests/fuzz/regressions/ with what it must give, once fixed.
set -euo pipefail
cd "$(dirname "$0")/.."
# Absolute paths: the targets run each input in an empty folder of their own.
root=$PWD

seconds=${1:-120}
shift || true
targets=("$@")
((${#targets[@]})) || targets=(front_end solve lsp)

mkdir -p build-asan/artifacts
seeds=(specs tests/fuzz/regressions)
for d in tests/golden/*/; do seeds+=("${d%/}"); done
[[ -n ${GBX_ACCEPTANCE_DIR:-} && -d $GBX_ACCEPTANCE_DIR ]] && seeds+=("$GBX_ACCEPTANCE_DIR")

status=0
for t in "${targets[@]}"; do
  exe=build-asan/tests/fuzz/fuzz_$t
  [[ -x $exe ]] || { echo "fuzz: $exe is not built (scripts/setup.sh --sanitize)" >&2; exit 2; }
  work=build-asan/corpus/$t
  mkdir -p "$work" "tests/fuzz/corpus/$t"
  # solve: each input is capped at 1 s of wall time inside the target; 30 s is a hang.
  timeout=10
  [[ $t == solve ]] && timeout=30
  echo "== fuzz_$t for ${seconds} s"
  # Only .gbx files seed the run (the golden folders also hold expected outputs).
  seed_dir=build-asan/seeds
  rm -rf "$seed_dir" && mkdir -p "$seed_dir"
  for d in "${seeds[@]}"; do
    for f in "$d"/*.gbx; do [[ -f $f ]] && cp "$f" "$seed_dir/$(echo "$f" | tr '/' '_')"; done
  done
  if ! ASAN_OPTIONS=detect_leaks=1:allocator_may_return_null=1 UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1 \
      "$exe" "$root/$work" "$root/tests/fuzz/corpus/$t" "$root/$seed_dir" -dict="$root/tests/fuzz/gbx.dict" \
      -max_total_time="$seconds" -timeout="$timeout" -rss_limit_mb=2560 -max_len=16384 \
      -artifact_prefix="$root/build-asan/artifacts/$t-" -print_final_stats=1 2> "build-asan/fuzz_$t.log"; then
    status=1
    echo "fuzz_$t FAILED: reproducer in build-asan/artifacts/; log in build-asan/fuzz_$t.log" >&2
    grep -E "ERROR|SUMMARY|Test unit written" "build-asan/fuzz_$t.log" >&2 || true
  fi
  grep -E "stat::number_of_executed_units|stat::peak_rss_mb|stat::new_units_added" "build-asan/fuzz_$t.log" || true
done
exit $status
