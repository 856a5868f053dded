#!/usr/bin/env bash
# The Debian package CPack makes from a build: it holds the program, the stdlib and the docs,
# and declares what it depends on. Usage: deb.sh BUILD_DIR
set -euo pipefail
build=$(cd "$1" && pwd)
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
(cd "$work" && cpack --config "$build/CPackConfig.cmake" -G DEB -B "$work" >/dev/null)
deb=$(ls "$work"/gbxc_*.deb)
depends=$(dpkg-deb -f "$deb" Depends)
echo "package: $(basename "$deb"); Depends: $depends"
[[ $depends == *libc6* ]] || { echo "FAIL: the package declares no dependency on libc6" >&2; exit 1; }
# The libc6 it asks for is at least the newest glibc symbol version the program uses: a
# smaller one lets the package install on a system where gbxc cannot start.
needed=$(objdump -T "$build/gbxc" | grep -o 'GLIBC_[0-9.]*' | sed 's/GLIBC_//' | sort -V | tail -1)
declared=$(grep -o 'libc6 (>= [0-9.]*' <<<"$depends" | grep -o '[0-9.]*$')
if [[ -z $declared || $(printf '%s\n%s\n' "$needed" "$declared" | sort -V | tail -1) != "$declared" ]]; then
  echo "FAIL: the package asks for libc6 >= ${declared:-nothing}, but gbxc uses GLIBC_$needed" >&2
  exit 1
fi
contents=$(dpkg-deb -c "$deb")
for f in ./usr/bin/gbxc ./usr/share/gbxc/stdlib/klingelnberg.gbx ./usr/share/doc/gbxc/README.md \
         ./usr/share/doc/gbxc/tutorial.md ./usr/share/doc/gbxc/site/index.html ./usr/share/man/man1/gbxc.1 \
         ./usr/share/bash-completion/completions/gbxc ./usr/share/zsh/vendor-completions/_gbxc; do
  grep -q " $f\$" <<<"$contents" || { echo "FAIL: the package lacks $f" >&2; exit 1; }
done
# The Python module, where the build has it, where Debian's python3 finds it.
if [[ -d $build/python/gbxc ]]; then
  for f in ./usr/lib/python3/dist-packages/gbxc/__init__.py ./usr/lib/python3/dist-packages/gbxc/py.typed; do
    grep -q " $f\$" <<<"$contents" || { echo "FAIL: the package lacks $f" >&2; exit 1; }
  done
  grep -q ' ./usr/lib/python3/dist-packages/gbxc/_gbxc\..*\.so$' <<<"$contents" || { echo "FAIL: the package lacks the module's native part" >&2; exit 1; }
fi
