#!/bin/bash
# The whole study of doc/validation.md in one command (about 21 minutes on
# the 2-core machine, 10 of them the default case): the default case (FE
# and DEM side by side, figures), the FE alone with the hyperelastic law,
# the linear law, the density from the fibres and a refined section, the FE
# resolution study, and the DEM contact-stiffness and friction sensitivity
# runs; prints the tables of doc/validation.md.
#   bash scripts/run_study.sh            (after or instead of run_default.sh)
set -euo pipefail
cd "$(dirname "$0")/.."
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
np=$(nproc)

# Section 1 and 3: the paper's study with its figures (skipped if done).
[ -f results/default/summary.txt ] || bash scripts/run_default.sh

# The study's own runs start afresh (yarn-impact refuses a folder holding an
# earlier run); the default case above is kept.
rm -rf results/fe_study results/dem_study

# Section 2: the FE model alone, Charmetant and linear law, refined section;
# section 1: the FE density from the fibres (runs C, D, E, B).
for run in fe_hyper fe_linear fe_hyperdens fe_hyper_section; do
  build/yarn-impact "prm/study/$run.prm" > /dev/null
done
echo "## FE laws and density (doc/validation.md sections 1 and 2)"
/usr/bin/python3 scripts/history_table.py \
  "Charmetant=results/fe_study/hyper/history_fe.csv" \
  "linear TI=results/fe_study/linear/history_fe.csv" \
  "Charmetant, section refined twice=results/fe_study/hyper_section/history_fe.csv" \
  "Charmetant, density from fibres=results/fe_study/hyperdens/history_fe.csv" \
  "DEM (default case)=results/default/history_dem.csv"

# Section 4: FE resolution.
echo "## FE resolution (doc/validation.md section 4)"
bash scripts/fe_resolution_study.sh build results/fe_resolution

# Section 4: DEM contact stiffness and friction.
for run in dem_kn_low dem_no_friction; do
  mpirun -np "$np" build/yarn-impact "prm/study/$run.prm" > /dev/null || true
done
echo "## DEM sensitivity (doc/validation.md section 4)"
/usr/bin/python3 scripts/history_table.py \
  "DEM default=results/default/history_dem.csv" \
  "contact stiffness halved=results/dem_study/kn_low/history_dem.csv" \
  "no friction=results/dem_study/no_friction/history_dem.csv"
