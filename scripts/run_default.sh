#!/bin/bash
# README command 1: install, build, run the default case (the paper's study:
# FE and DEM side by side) and render its figures.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
# The default case runs both models; the DEM part uses every core.
mpirun -np "$(nproc)" build/yarn-impact prm/default.prm

# Pictures of the yarns (the paper's Fig. 3-5) rendered from the VTU output
# with ParaView's pvbatch, without a display.
missing=""
for p in paraview python3-paraview xvfb xauth; do
  dpkg -s "$p" > /dev/null 2>&1 || missing="$missing $p"
done
if [ -n "$missing" ]; then
  echo "Installing (for the pictures):$missing"
  export DEBIAN_FRONTEND=noninteractive
  apt-get update -qq
  apt-get install -y -qq --no-install-recommends $missing
fi
bash scripts/make_figures.sh results/default results/default/figures
