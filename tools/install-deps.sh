#!/usr/bin/env bash
# Installs, with apt-get, the Debian 12 packages flange needs that are missing.
# Run as root (or with sudo). Nothing is installed when everything is there.
#   tools/install-deps.sh            compiler, CMake, Eigen, Boost 1.81, Catch2, Google Benchmark,
#                                    valgrind (the memcheck test), tinyxml2 (flange-urdf), python3
#                                    (tools/doc_snippets.py: the docs' snippets become tests)
#   tools/install-deps.sh --plots    also gnuplot, for docs/*.png
#   tools/install-deps.sh --peers    also MuJoCo and Simbody, the work-precision study's peers
#   tools/install-deps.sh --ensembles  also oneTBB, Boost.MPI and Open MPI, for parallel ensembles
#   tools/install-deps.sh --urdf     also MuJoCo, which checks flange-urdf's scenes against the same URDF files
#   tools/install-deps.sh --sanitizers  also clang 14, its sanitizer runtimes and libFuzzer
#                                    (tools/sanitizers.sh)
#   tools/install-deps.sh --viewer   also headless Chromium and npm, and three.js from npm into
#                                    tools/viewer/node_modules (the trajectory pages inline it)
#   tools/install-deps.sh --python   also pybind11, Python's headers, numpy, pytest and matplotlib
#                                    (scene modules for Python, docs/python.md)
# (the options may be given together.)
set -euo pipefail
viewer=0
# Boost 1.81, not Debian's default 1.74: its uBLAS compiles as C++20, which
# keeps rosenbrock4 header-only. Installing it replaces libboost1.74-dev.
packages=(g++ cmake make libeigen3-dev libboost1.81-dev catch2 libbenchmark-dev valgrind libtinyxml2-dev python3)
for arg in "$@"; do
  case "$arg" in
    --plots) packages+=(gnuplot-nox) ;;
    --peers) packages+=(libmujoco-dev libsimbody-dev) ;;
    --ensembles) packages+=(libtbb-dev libboost-mpi1.81-dev openmpi-bin) ;;
    --urdf) packages+=(libmujoco-dev) ;;
    --sanitizers) packages+=(clang-14 libclang-rt-14-dev libfuzzer-14-dev) ;;
    --python) packages+=(pybind11-dev python3-dev python3-numpy python3-pytest python3-matplotlib) ;;
    --viewer)
      viewer=1
      packages+=(chromium-headless-shell)
      command -v npm >/dev/null || packages+=(npm)
      ;;
    *) echo "install-deps: unknown option $arg (use --plots, --peers, --ensembles, --urdf, --sanitizers, --viewer, --python)" >&2; exit 2 ;;
  esac
done
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if ((${#missing[@]})); then
  echo "install-deps: installing ${missing[*]}"
  sudo=""
  if [[ $(id -u) -ne 0 ]]; then sudo="sudo"; fi
  $sudo apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
fi
# three.js for the trajectory viewer, pinned in tools/viewer/package.json.
if ((viewer)) && [[ ! -f "$(dirname "$0")/viewer/node_modules/three/build/three.min.js" ]]; then
  echo "install-deps: npm install three.js into tools/viewer/node_modules"
  (cd "$(dirname "$0")/viewer" && npm install --silent --no-audit --no-fund --no-package-lock)
fi
