#!/bin/bash
# Usage: whole_yarn.sh YARN_IMPACT SOURCE_DIR
# The hybrid yarn modelled whole (Symmetry = none: the DEM part |x| <= a,
# an FE part, an overlap and, with fibre bars, bars on each side) against
# the same yarn with half symmetry (a consistency check against an
# independent run, no recorded numbers):
# - the ready case (prm/hybrid/km2_120ms_hybrid.prm) with a 3 mm DEM part
#   over 0.6 us, the longitudinal wave through both overlaps and into both
#   FE parts, with each far field (continuum and fibre bars); the DEM's
#   fibres lie along x, so its layout is symmetric about x = 0;
# - the histories of the whole yarn agree: the projectile's velocity and
#   force, the energies and the largest strain within 1e-5 of each
#   quantity's largest value over the run (the whole DEM part sums its
#   contacts in another order than the half's, whose plane x = 0 holds
#   half spheres), the failed elements equal;
# - every one of these runs conserves the projectile's and the yarn's
#   momentum along the impact direction within 1e-9 of m v0
#   (momentum_balance.py);
# - the whole yarn with fibre bars to 0.3 us: its history on 2 ranks byte
#   for byte that of 1 rank stopped by SIGTERM and continued with
#   --restart (every part's checkpoint);
# - its snapshot a multiblock of the FE part, the DEM part, the bars and
#   the side x < 0's FE part and bars, every file there;
# - bad set-ups refused by --check with one line naming the parameter.
exe=$1
src=$2
. "$(dirname "$(readlink -f "$0")")/../lib.sh"
test_begin

# case_prm SYMMETRY FAR_FIELD DIR
case_prm() {
  cat "$src/prm/hybrid/km2_120ms_hybrid.prm"
  printf 'set Symmetry = %s\n' "$1"
  printf 'subsection Hybrid\n  set DEM half-length = 3e-3\n  set Far field = %s\nend\n' "$2"
  printf 'subsection Time\n  set End time = 0.6e-6\nend\n'
  printf 'subsection Output\n  set Directory = %s\n  set Snapshot interval = 0\n' "$3"
  printf '  set History interval = 0.05e-6\nend\n'
}

. "$src/tests/coupling/run_checks.sh"
same_motion none "whole yarn"

# The whole yarn with fibre bars to 0.3 us on 2 ranks, with its snapshot
# at 0.3 us; on 1 rank stopped at row 4 and continued: the same history
# byte for byte (one check of both: the ranks' and the checkpoint's).
whole_prm() {
  case_prm none "fibre bars" "$1"
  printf 'subsection Time\n  set End time = 0.3e-6\nend\n'
  printf 'subsection Output\n  set Snapshot interval = 0.3e-6\nend\n'
}
same_on_ranks whole_prm 2
if [ -f ranks2/history_hybrid.csv ]; then
  restart_same whole_prm 4 ranks2/history_hybrid.csv
fi

vtm=$(ls ranks2/hybrid_*.vtm 2> /dev/null | tail -1)
if [ -z "$vtm" ]; then
  fail "2 ranks: no snapshot"
else
  for block in fe dem bars fe_left bars_left; do
    file=$(sed -n "s/.* name=\"$block\" file=\"\([^\"]*\)\".*/\1/p" "$vtm")
    [ -n "$file" ] && [ -f "ranks2/$file" ] ||
      fail "snapshot: block $block missing from $vtm or its file"
  done
fi

# Bad set-ups of the whole yarn: one line naming the parameter, exit 1.
plain_prm() {
  cat "$src/prm/hybrid/km2_120ms_hybrid.prm"
  printf 'set Symmetry = none\n'
}
refuse plain_prm "a DEM part at the clamps" "Hybrid/Clamp DEM length" \
  'subsection Hybrid\n  set Clamp DEM length = 2e-3\nend\n'
refuse plain_prm "contact zone in an overlap" "Hybrid/DEM half-length" \
  'subsection Hybrid\n  set DEM half-length = 1.5e-3\nend\n'
refuse plain_prm "overlap as wide as the DEM part" "Hybrid/Overlap width" \
  'subsection Hybrid\n  set Overlap width = 7e-3\nend\n'

test_end "hybrid: whole yarn = half for both far fields, 1 = 2 ranks, restart, snapshot, bad set-ups: all passed"
