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
# The reference, the manual page, the site and the shell completion are installed, and the
# installed docs name no file outside the installation.
for f in share/doc/gbxc/tutorial.md share/doc/gbxc/language.md share/doc/gbxc/catalogue.md \
         share/doc/gbxc/diagnostics.md share/doc/gbxc/cli.md share/doc/gbxc/site/index.html \
         share/doc/gbxc/site/tutorial.html share/man/man1/gbxc.1 share/bash-completion/completions/gbxc \
         share/zsh/vendor-completions/_gbxc; do
  test -s "$work/first/$f" || { echo "FAIL: the installation lacks $f" >&2; exit 1; }
done
if grep -rlE '\.\./shared|LANGUAGE\.md|DOMAIN\.md' "$work/first/share"; then
  echo "FAIL: the installed files above point outside the installation" >&2
  exit 1
fi
grep -q '^\.SH NAME' "$work/first/share/man/man1/gbxc.1"
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
# Help, completion and the import order from the moved installation.
"$work/moved/bin/gbxc" help solve | grep -q -- '--time-limit'
mkdir -p "$work/shop" "$work/path"
printf 'const shop_width = 42 mm;\n' >"$work/shop/shopstd.gbx"
printf 'const shop_width = 1 mm;\nconst path_only = 3;\n' >"$work/path/shopstd.gbx"
printf 'import shopstd;\ngearbox G { stage s: spur { pinion.z = 20; wheel.z = 40; normal_module = 2 mm; face_width = shop_width; } report { columns s.face_width; } }\n' >"$work/shop/uses.gbx"
GBX_PATH="$work/path" "$work/moved/bin/gbxc" solve "$work/shop/uses.gbx" --quiet | grep -q ' 42\.0000' ||
  { echo "FAIL: an import did not take the module beside the spec before GBX_PATH's" >&2; exit 1; }
out=$(bash -c 'source "$1"; COMP_WORDS=(gbxc solve "$2" --gearbox ""); COMP_CWORD=4; _gbxc; echo "${COMPREPLY[*]}"' _ \
  "$work/moved/share/bash-completion/completions/gbxc" "$work/shop/uses.gbx")
[[ $out == G ]] || { echo "FAIL: bash completion of --gearbox gave '$out'" >&2; exit 1; }
out=$(bash -c 'source "$1"; COMP_WORDS=(gbxc solve --format ""); COMP_CWORD=3; _gbxc; echo "${COMPREPLY[*]}"' _ \
  "$work/moved/share/bash-completion/completions/gbxc")
[[ $out == "text json csv md html" ]] || { echo "FAIL: bash completion of --format gave '$out'" >&2; exit 1; }
# The Python module from the moved prefix, where the build has it: it imports with the
# prefix's folder on PYTHONPATH, finds the stdlib beside itself and solves a spec that
# imports from it.
if [[ -d $build/python/gbxc ]]; then
  printf 'import materials;\ngearbox P { stage s: spur { pinion.z = 20; wheel.z = 40; normal_module = 2 mm; face_width = 20 mm; material = steel_18CrNiMo7_6; } operating { input_speed = 1000 rpm; power = 5 kW; } }\n' >"$work/py.gbx"
  out=$(PYTHONPATH="$work/moved/${GBX_PYTHON_DIR:-lib/python3/dist-packages}" "${GBX_PYTHON:-/usr/bin/python3}" -c \
    'import sys, gbxc; r = gbxc.solve(sys.argv[1]); assert r.gearboxes["P"].designs, r.errors; print(gbxc.__file__)' "$work/py.gbx") ||
    { echo "FAIL: the Python module of the moved installation did not solve" >&2; exit 1; }
  [[ $out == "$work/moved/"* ]] || { echo "FAIL: Python imported gbxc from $out, not the moved installation" >&2; exit 1; }
  echo "ok: the Python module from the moved prefix ($out)"
fi
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
