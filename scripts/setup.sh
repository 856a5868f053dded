#!/usr/bin/env bash
# Installs what a fresh Debian machine lacks, then configures and builds gbxc.
#   scripts/setup.sh              release build in build/
#   scripts/setup.sh --sanitize   AddressSanitizer + UBSan build in build-asan/: the whole suite
#                                 and the libFuzzer targets (clang), one build for both
#   scripts/setup.sh --fuzz       the same
#   scripts/setup.sh --mpi        gbxc over Open MPI in build-mpi/: `mpirun -n N build-mpi/gbxc solve FILE`
#                                 shares the work over N ranks (the release build has it too, as
#                                 build/gbxc-mpi, beside a gbxc that needs no MPI)
# Idempotent: packages already present are not touched; the build is incremental.
# Works on a bare Debian bookworm (debootstrap --variant=minbase): as root it needs no sudo;
# as another user it uses sudo, and only when a package is missing.
set -euo pipefail
cd "$(dirname "$0")/.."

build_dir=build
# The release build has the Python module (docs/python.md), built for Debian's python3.
cmake_args=(-DCMAKE_BUILD_TYPE=RelWithDebInfo -DGBX_PYTHON=ON -DPython3_EXECUTABLE=/usr/bin/python3)
extra_packages=()
if [[ "${1:-}" == "--sanitize" || "${1:-}" == "--fuzz" ]]; then
  build_dir=build-asan
  # clang, so that the fuzz targets link libFuzzer; every library instrumented for its
  # coverage as well. -O1 with assertions kept: fast enough to fuzz and to run the suite
  # under the sanitizers, and an assertion is a finding.
  cmake_args=(-DCMAKE_BUILD_TYPE=RelWithDebInfo "-DCMAKE_CXX_FLAGS_RELWITHDEBINFO=-O1 -g1" -DGBX_FUZZ=ON
              -DCMAKE_CXX_COMPILER=clang++)
  extra_packages=(clang libclang-rt-dev)
elif [[ "${1:-}" == "--mpi" ]]; then
  build_dir=build-mpi
  cmake_args=(-DCMAKE_BUILD_TYPE=RelWithDebInfo -DGBX_MPI=ON)
fi

# ccache: the compiler launcher (scripts/ccache-launch).
# uuid-dev: the ANTLR runtime's CMake target links -luuid, and libantlr4-runtime-dev does
# not depend on it.
# chromium: the tests render every example's HTML report in a real (headless) browser.
# python3-jsonschema: a test validates every spec's JSON report against docs/report.schema.json.
# dpkg-dev, file: `cpack -G DEB` reads the program's shared libraries (dpkg-shlibdeps, and
# CPack's own check with `file`) for the .deb's Depends.
# universal-ctags: a test measures every function's length (Conventions.NoFunctionOver…).
# pandoc, mkdocs: the manual page (from docs/cli.md) and the documentation site.
# libopenmpi-dev, openmpi-bin: build/gbxc-mpi, and the test that four MPI ranks write the
# same report as one thread.
# python3-dev, pybind11-dev: the Python module; python3-numpy its arrays; python3-pytest its
# tests; python3-pandas, python3-matplotlib the documentation's scripts, run as tests.
packages=(g++ cmake ninja-build ccache antlr4 default-jre-headless libantlr4-runtime-dev uuid-dev
          libeigen3-dev libgsl-dev libfmt-dev googletest libgtest-dev chromium poppler-utils python3-jsonschema dpkg-dev file universal-ctags
          libopenmpi-dev openmpi-bin libnlopt-dev pandoc mkdocs python3-dev pybind11-dev python3-numpy python3-pytest
          python3-pandas python3-matplotlib ${extra_packages[@]+"${extra_packages[@]}"})
missing=()
for p in "${packages[@]}"; do
  # Installed, not merely known to dpkg (a removed package keeps its config-files state).
  [[ $(dpkg-query -W -f='${db:Status-Status}' "$p" 2>/dev/null) == installed ]] || missing+=("$p")
done
if ((${#missing[@]})); then
  echo "setup: installing ${missing[*]}"
  as_root=()
  if ((EUID != 0)); then
    if ! command -v sudo >/dev/null 2>&1; then
      echo "setup: not root and no sudo; as root run:" >&2
      echo "  apt-get update && apt-get install --no-install-recommends ${missing[*]}" >&2
      exit 1
    fi
    as_root=(sudo)
  fi
  # Through env: sudo resets the environment, which would drop DEBIAN_FRONTEND.
  "${as_root[@]}" env DEBIAN_FRONTEND=noninteractive apt-get update -q
  "${as_root[@]}" env DEBIAN_FRONTEND=noninteractive \
    apt-get install -y -q --no-install-recommends "${missing[@]}"
  echo "setup: packages installed in ${SECONDS}s"
fi

# Compiles through ccache (scripts/ccache-launch): a rebuild of sources compiled before, in
# this checkout or another on the machine, takes the objects from the cache.
cmake_args+=("-DCMAKE_CXX_COMPILER_LAUNCHER=$PWD/scripts/ccache-launch")
# GBX_ACCEPTANCE_DIR: a folder of acceptance specs kept outside the repository (optional).
cmake -S . -B "$build_dir" -G Ninja "${cmake_args[@]}" -DGBX_ACCEPTANCE_DIR="${GBX_ACCEPTANCE_DIR:-}" >/dev/null
cmake --build "$build_dir"
