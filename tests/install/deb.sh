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
contents=$(dpkg-deb -c "$deb")
for f in ./usr/bin/gbxc ./usr/share/gbxc/stdlib/klingelnberg.gbx ./usr/share/doc/gbxc/README.md; do
  grep -q " $f\$" <<<"$contents" || { echo "FAIL: the package lacks $f" >&2; exit 1; }
done
