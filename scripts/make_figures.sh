#!/bin/bash
# Figures of the paper's study (Fig. 3-6) from a `Model = both` run:
#   scripts/make_figures.sh [RUN_DIR] [FIGURE_DIR] [DEM_RUN_DIR]
# RUN_DIR defaults to results/default (prm/default.prm), FIGURE_DIR to
# doc/figures. DEM_RUN_DIR (default RUN_DIR) is where the DEM snapshots are
# taken from: a DEM-only run of the same case (e.g. results-dem-km2,
# prm/km2_120ms_dem.prm) when the `both` run's DEM stopped early.
# A time that a .pvd does not hold is skipped (render_yarn.py says so).
# Needs ParaView's pvbatch and xvfb-run:
#   apt-get install -y --no-install-recommends paraview python3-paraview xvfb xauth
set -euo pipefail
run=${1:-results/default}
out=${2:-doc/figures}
dem=${3:-$run}
here=$(cd "$(dirname "$0")" && pwd)
mkdir -p "$out"
log=$(mktemp)
trap 'rm -f "$log"' EXIT
# render ARGS: one pvbatch under its own X server; tried three times, as a
# fresh Xvfb now and then refuses the connection ("bad X server connection").
render() {
  local try
  for try in 1 2 3; do
    if xvfb-run -a -s "-screen 0 2400x2000x24" \
         pvbatch "$here/render_yarn.py" "$@" > "$log" 2>&1; then
      grep '^render_yarn:' "$log" || true
      return 0
    fi
    # ParaView 5.11's Threshold (hiding the broken DEM trusses) crashes on
    # some snapshots: draw those with the broken trusses.
    if grep -q SIGSEGV "$log" && [[ " $* " != *" --keep-broken "* ]]; then
      set -- "$@" --keep-broken
    fi
    sleep 2
  done
  cat "$log" >&2
  echo "make_figures.sh: render_yarn.py $* failed" >&2
  exit 1
}
# One pvbatch per time: ParaView 5.11's Threshold (hiding the failed cells
# and broken trusses) can crash when the time changes in one session.
# render_each PVD PREFIX FIELD "T1 T2 ..." [OPTIONS]
render_each() {
  local pvd=$1 prefix=$2 field=$3 times=$4 t
  shift 4
  for t in $times; do render "$pvd" "$prefix" "$field" "$t" "$@"; done
}
for pvd in "$run/fe.pvd" "$dem/dem.pvd"; do
  echo "$pvd holds t [us] =" $(grep -o 'timestep="[^"]*"' "$pvd" | cut -d'"' -f2)
done

# Fig. 3 and 4: the yarn at 0, 10, 25, 30, 35 and 40 us, side view
# (deflection exaggerated 5 times), coloured by the fibre strain.
render_each "$dem/dem.pvd" "$out/dem_side" axial_strain "0 10 25 30 35 40" --view side --y-scale 5 --range 0 0.045
render_each "$run/fe.pvd" "$out/fe_side" longitudinal_strain "0 10 25 30 35 40" --view side --y-scale 5 --range 0 0.045
# Fig. 5: spreading at 10 and 25 us, seen from above (width along z,
# exaggerated 5 times).
render_each "$dem/dem.pvd" "$out/dem_top" axial_strain "10 25" --view top --z-scale 5 --range 0 0.045
render_each "$run/fe.pvd" "$out/fe_top" I_tc "10 25" --view top --z-scale 5
# The FE section under the projectile at 10 us (compaction), true scale.
render "$run/fe.pvd" "$out/fe_section" I_tc 10 --view section
# Fig. 6 and the wave fronts (drawn from comparison.csv, or from the two
# histories where the run has none).
/usr/bin/python3 "$here/plot_comparison.py" "$run"
cp "$run/velocity_comparison.png" "$run/wave_fronts.png" "$out/"
echo "$out: velocity_comparison.png wave_fronts.png"
