#!/usr/bin/env bash
# Command 1 of the README: install what is missing (Debian bookworm), configure,
# build, and run the main job (the 1D two-bar impact on its default file).
#   bash tools/setup.sh            set up, build, run the main job
#   bash tools/setup.sh --no-run   set up and build only (used by .ci/run)
set -euo pipefail
cd "$(dirname "$0")/.."

# libopenblas0-pthread: CHOLMOD's supernodal factorisation and multi-column
# solves spend their time in BLAS (dgemm, dsyrk, dtrsm). Debian's default
# libblas.so.3 is the reference BLAS; the OpenBLAS package replaces it
# through update-alternatives (a 3D ball of 88k unknowns: factorisation
# 71 s -> 8 s, doc/performance.md).
packages="libdeal.ii-dev numdiff cmake g++ make python3-matplotlib libopenblas0-pthread"
missing=""
for p in $packages; do
  dpkg -s "$p" > /dev/null 2>&1 || missing="$missing $p"
done
if [ -n "$missing" ]; then
  echo "Installing:$missing"
  SUDO=""
  [ "$(id -u)" -ne 0 ] && SUDO="sudo"
  $SUDO apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq --no-install-recommends $missing
fi

cmake -S . -B build -DCMAKE_BUILD_TYPE=Release
cmake --build build -j2

if [ "${1:-}" != "--no-run" ]; then
  ./build/bin/two_bars_1d parameter_files/two_bars_1d.prm
fi
