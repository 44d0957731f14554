#!/usr/bin/env bash
# Installs the Debian packages vcontact needs (only those missing; chromium is for the
# test that renders the HTML report headless, clang-format for the format check), then
# configures and builds in Release. Safe to run again: it installs nothing and rebuilds
# nothing that is already up to date.
#
# Usage: setup.sh [TARGET ...]   build only these CMake targets (the demo builds only the
#                                `vcontact` program); with none, everything (tests included).
# Environment: VCONTACT_BUILD_DIR (default: build), VCONTACT_JOBS (default: nproc).
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."

PACKAGES=(
  g++ make cmake pkg-config
  libeigen3-dev libboost-dev libtbb-dev
  libassimp-dev nlohmann-json3-dev libcli11-dev
  libcgal-dev libgmp-dev libmpfr-dev
  libfcl-dev
  # fcl's CMake package finds and links libccd (fcl-config.cmake: find_dependency(ccd)).
  libccd-dev
  libceres-dev libsundials-dev
  # muparser compiles the formulas of expression effects (dynamics/effects/expression.cpp).
  libmuparser-dev
  libgtest-dev libgmock-dev libbenchmark-dev
  chromium clang-format
  # The Python package (python/, docs/PYTHON.md): bindings, NumPy arrays, its pytest suite.
  pybind11-dev python3-dev python3-numpy python3-pytest
  # three.js, inlined into the page `vcontact view` writes (docs/VIEWER.md); node parses the
  # page's own script, report/view.js, in the CTest checks/view_script_parses.
  libjs-three nodejs
  # Derivative-free global search for fits whose loss is not smooth (trajectories, docs/DATASET.md).
  libnlopt-cxx-dev
  # Studies (docs/STUDY.md): Dask distributed runs them, SciPy's qmc samples the designs,
  # h5py writes the large tables.
  python3-dask python3-distributed python3-scipy python3-h5py
  # Simbody's elastic foundation, the reference of the mesh–mesh query benchmark (issue 33,
  # benchmarks/simbody_bench.cpp, vcontact_simbody_bench); the rest of the build does not use it.
  libsimbody-dev
)
# The libFuzzer harnesses (tests/fuzz, -DVCONTACT_FUZZ=ON) need clang and its fuzzer and
# sanitizer runtimes; a normal build does not.
if [ "${VCONTACT_FUZZ:-0}" = 1 ]; then
  PACKAGES+=(clang-14 libclang-rt-14-dev)
fi

missing=()
for p in "${PACKAGES[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$p")
  fi
done
if ((${#missing[@]})); then
  sudo=""
  if [ "$(id -u)" -ne 0 ]; then sudo="sudo"; fi
  echo "vcontact setup: installing ${#missing[@]} Debian packages: ${missing[*]}"
  $sudo apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq --no-install-recommends \
    "${missing[@]}" >/dev/null
  echo "vcontact setup: packages installed"
fi

build="${VCONTACT_BUILD_DIR:-build}"
jobs="${VCONTACT_JOBS:-$(nproc)}"
if [ ! -f "$build/CMakeCache.txt" ]; then
  cmake -S . -B "$build" -DCMAKE_BUILD_TYPE=Release >/dev/null
fi
targets=()
for t in "$@"; do targets+=(--target "$t"); done
echo "vcontact setup: building ${*:-everything} in $build with $jobs jobs"
cmake --build "$build" -j"$jobs" "${targets[@]}"
