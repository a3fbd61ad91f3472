#!/bin/bash
# Figures of the paper's study (Fig. 3-6) from a `Model = both` run:
#   scripts/make_figures.sh [RUN_DIR] [FIGURE_DIR]
# RUN_DIR defaults to results/km2_120ms_compare (prm/km2_120ms_compare.prm),
# FIGURE_DIR to doc/figures. Needs ParaView's pvbatch and xvfb-run:
#   apt-get install -y --no-install-recommends paraview python3-paraview xvfb xauth
set -euo pipefail
run=${1:-results/km2_120ms_compare}
out=${2:-doc/figures}
here=$(cd "$(dirname "$0")" && pwd)
mkdir -p "$out"
render() { xvfb-run -a pvbatch "$here/render_yarn.py" "$@" > /dev/null 2>&1; }

# Fig. 3 and 4: the yarn at 0, 10, 25 and 40 us, side view (deflection
# exaggerated 5 times), coloured by the fibre strain.
render "$run/dem.pvd" "$out/dem_side" axial_strain 0 10 25 40 --view side --y-scale 5 --range 0 0.045
render "$run/fe.pvd" "$out/fe_side" longitudinal_strain 0 10 25 40 --view side --y-scale 5 --range 0 0.045
# Fig. 5: spreading at 10 us, seen from above (width along z).
render "$run/dem.pvd" "$out/dem_top" axial_strain 10 --view top
render "$run/fe.pvd" "$out/fe_top" I_tc 10 --view top
# The FE section under the projectile at 10 us (compaction).
render "$run/fe.pvd" "$out/fe_section" I_tc 10 --view section
# Fig. 6 and the wave fronts.
cp "$run/velocity_comparison.png" "$run/wave_fronts.png" "$out/"
ls "$out"
