#!/bin/bash
# README command 1: install, build, run the default case (the paper's study:
# FE and DEM side by side) and render its figures.
set -euo pipefail
cd "$(dirname "$0")/.."
# ParaView's pvbatch (with xvfb, no display needed) renders the pictures.
bash scripts/setup.sh paraview python3-paraview xvfb xauth
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
# The default case runs both models; the DEM part uses every core. A rerun
# starts afresh (yarn-impact refuses a folder holding an earlier run).
rm -rf results/default
mpirun -np "$(nproc)" build/yarn-impact prm/default.prm
# The paper's Fig. 6 and the wave fronts, from comparison.csv.
/usr/bin/python3 scripts/plot_comparison.py results/default
# Pictures of the yarns (the paper's Fig. 3-5) from the VTU output.
bash scripts/make_figures.sh results/default results/default/figures
