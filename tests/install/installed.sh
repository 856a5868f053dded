#!/usr/bin/env bash
# An installed gbxc on its own: `cmake --install` into a temporary prefix, the prefix moved
# elsewhere, then every spec given solved by the moved program from an unrelated folder, with
# no variable pointing at any stdlib. Usage: installed.sh BUILD_DIR SPEC...
set -euo pipefail
build=$1
shift
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cmake --install "$build" --prefix "$work/first" >/dev/null
test -x "$work/first/bin/gbxc"
test -f "$work/first/share/gbxc/stdlib/klingelnberg.gbx"
test -f "$work/first/share/doc/gbxc/README.md"
mv "$work/first" "$work/moved"
cd "$work"
unset GBX_PATH GBX_STDLIB_PATH
# The program alone, without the stdlib it was installed with: an import is a clear error.
mkdir -p "$work/alone/bin"
cp "$work/moved/bin/gbxc" "$work/alone/bin/"
printf 'import materials;\n' >"$work/imports.gbx"
if "$work/alone/bin/gbxc" check "$work/imports.gbx" 2>"$work/err.txt"; then
  echo "FAIL: gbxc without its stdlib accepted an import" >&2
  exit 1
fi
grep -q 'E0203.*no folder of modules was found' "$work/err.txt" || { echo "FAIL: unclear error without a stdlib:" >&2; cat "$work/err.txt" >&2; exit 1; }
status=0
for spec in "$@"; do
  if ! "$work/moved/bin/gbxc" solve "$spec" --no-timings --quiet >"$work/out.txt" 2>"$work/err.txt"; then
    echo "FAIL: the moved installation could not solve $spec:" >&2
    cat "$work/err.txt" >&2
    status=1
  else
    echo "ok: $spec ($(head -1 "$work/out.txt"))"
  fi
done
exit $status
