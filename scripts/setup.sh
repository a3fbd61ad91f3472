#!/bin/bash
# Install what is missing (Debian 12, as root), configure in Release and
# build. Used by the README's two commands and by CI. Arguments are further
# Debian packages to install if missing (run_default.sh: ParaView).
set -euo pipefail
cd "$(dirname "$0")/.."

packages="cmake g++ make libdeal.ii-dev numdiff openmpi-bin python3-matplotlib python3-numpy python3-scipy $*"
missing=""
for p in $packages; do
  dpkg -s "$p" > /dev/null 2>&1 || missing="$missing $p"
done
if [ -n "$missing" ]; then
  echo "Installing:$missing"
  export DEBIAN_FRONTEND=noninteractive
  apt-get update -qq
  apt-get install -y -qq --no-install-recommends $missing
fi

# Open MPI refuses to start as root unless told.
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1

cmake -S . -B build -DCMAKE_BUILD_TYPE=Release > build.log 2>&1 || { cat build.log; exit 1; }
cmake --build build -j "$(nproc)" >> build.log 2>&1 || { tail -50 build.log; exit 1; }
echo "Built build/yarn-impact (log in build.log)"
