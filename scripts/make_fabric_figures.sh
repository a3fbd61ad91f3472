#!/bin/bash
# The figures of doc/fabric.md (sections 5 and 6) from two runs made here:
#   scripts/make_fabric_figures.sh [BUILD_DIR] [FIGURE_DIR] [RUN_DIR]
# BUILD_DIR defaults to build, FIGURE_DIR to doc/figures, RUN_DIR to
# results/fabric-figures. The runs, on 2 MPI ranks (NP to change it):
#   - the example, prm/fabric/km2_patch.prm as it is (10 us, a snapshot
#     every 1 us): its velocity, energy partition and cone fronts
#     (plot_fabric.py) and the ply at 3 and 8 us (render_ply.py);
#   - the ply of the ballistic limit, prm/fabric/km2_ply_v50.prm at 250 m/s
#     (below its V50), with a snapshot every 1 us: the same plots and the
#     pyramid at 2 and 5 us, its deflection stretched 2 times.
# Needs matplotlib, ParaView's pvbatch and xvfb-run:
#   apt-get install -y --no-install-recommends python3-matplotlib paraview \
#     python3-paraview xvfb xauth
set -euo pipefail
build=${1:-build}
out=${2:-doc/figures}
runs=${3:-results/fabric-figures}
np=${NP:-2}
here=$(cd "$(dirname "$0")" && pwd)
mkdir -p "$out" "$runs"
log=$(mktemp)
trap 'rm -f "$log"' EXIT
# run NAME PRM SED: the case PRM, edited by SED, into RUN_DIR/NAME.
run() {
  local name=$1 prm=$2 edit=$3
  rm -rf "${runs:?}/$name"
  sed -e "s|^\( *set Directory *=\).*|\1 $runs/$name|" -e "$edit" \
    "$prm" > "$runs/$name.prm"
  echo "make_fabric_figures.sh: running $name"
  mpirun -np "$np" "$build/yarn-impact" "$runs/$name.prm" > "$runs/$name.log"
}
# render ARGS: one pvbatch under its own X server per picture, tried three
# times (a fresh Xvfb now and then refuses the connection).
render() {
  local try
  for try in 1 2 3; do
    if xvfb-run -a -s "-screen 0 2400x2000x24" \
         pvbatch "$here/render_ply.py" "$@" > "$log" 2>&1; then
      grep '^render_ply:' "$log" || true
      return 0
    fi
    sleep 2
  done
  cat "$log" >&2
  echo "make_fabric_figures.sh: render_ply.py $* failed" >&2
  exit 1
}
run example prm/fabric/km2_patch.prm "s|x|x|"
run ply_250ms prm/fabric/km2_ply_v50.prm \
  "s|^\( *set Initial velocity *=\).*|\1 250|;s|^\( *set Snapshot interval *=\).*|\1 1e-6|"
/usr/bin/python3 "$here/plot_fabric.py" "$runs/example/history_fabric.csv" \
  "$out/fabric_example" "the example (8 x 8 yarns, cylinder at 120 m/s)"
/usr/bin/python3 "$here/plot_fabric.py" "$runs/ply_250ms/history_fabric.csv" \
  "$out/fabric_ply_250ms" "the V50 ply, flat cylinder at 250 m/s"
for t in 3 8; do
  render "$runs/example/fabric.pvd" "$out/fabric_example" longitudinal_strain "$t" --range 0 0.03
done
for t in 2 5; do
  render "$runs/ply_250ms/fabric.pvd" "$out/fabric_ply_250ms" longitudinal_strain "$t" --range 0 0.045 --y-scale 2
done
