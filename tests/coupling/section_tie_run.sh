#!/bin/bash
# Usage: section_tie_run.sh YARN_IMPACT SOURCE_DIR
# The hybrid yarn with a far field of fibre bars and the overlap's
# transverse tie on the section's mean per node layer (Hybrid/Transverse
# tie = section mean, doc/hybrid.md section 2.5): the case of
# fibre_bars_run.sh (the paper's yarn at 120 m/s, a 3 mm DEM part) over
# the first 0.4 us. Physics and consistency checks, no recorded numbers:
# - the energy balance, the bars, both ties and their multipliers'
#   work included, within 0.05 % of the initial energy (the run's own
#   check): multipliers that did work on the admissible velocities would
#   break it;
# - the projectile's and the yarn's momentum along the impact direction
#   (y, the direction the tie acts in) within 1e-9 of m v0 at every row
#   (momentum_balance.py): the tie's forces on spheres and nodes sum to
#   zero;
# - the same history on 1 and 2 MPI ranks byte for byte (every rank solves
#   the same small system from exact gathers);
# - stopped by SIGTERM and continued with --restart: the same history
#   byte for byte;
# - `section affine` runs and conserves momentum too;
# - the coarse tie with the continuum far field refused by --check with
#   one line naming the parameter.
# In 0.4 us the transverse front (0.3 mm) does not reach the overlap: the
# tie there carries the section's small motion under the bar wave, and
# the run checks the tie inside the whole model (its momentum, energy,
# ranks and restart). The multipliers' algebra (balance, the constraints
# to round-off, no work, closed forms) is checked by the unit test
# section_tie.
exe=$1
src=$2
. "$(dirname "$(readlink -f "$0")")/../lib.sh"
test_begin
. "$src/tests/coupling/run_checks.sh"

tie_prm() {
  cat "$src/prm/hybrid/km2_120ms_hybrid.prm"
  printf 'subsection Hybrid\n  set DEM half-length = 3e-3\n'
  printf '  set Far field = fibre bars\n  set Transverse tie = %s\nend\n' "${tie:-section mean}"
  printf 'subsection Time\n  set End time = 0.4e-6\nend\n'
  printf 'subsection Output\n  set Directory = %s\n  set Snapshot interval = 0\n' "$1"
  printf '  set History interval = 0.05e-6\nend\n'
  printf 'subsection Verification\n  set Checks = energy\n'
  printf '  set Energy tolerance = 5e-4\nend\n'
}

same_on_ranks tie_prm 1 2
grep -E "energy error" ranks1/summary.txt
momentum_conserved ranks1 "section mean"
restart_same tie_prm 6 ranks1/history_hybrid.csv

tie="section affine"
tie_prm affine > affine.prm
"$exe" affine.prm > affine.stdout 2>&1 ||
  { fail "section affine: exit $?"; tail -5 affine.stdout; }
momentum_conserved affine "section affine"
unset tie

refuse tie_prm "the section tie with the continuum far field" \
  "Hybrid/Transverse tie" \
  'subsection Hybrid\n  set Far field = continuum\nend\n'
refuse tie_prm "an unknown transverse tie" "Transverse tie" \
  'subsection Hybrid\n  set Transverse tie = springs\nend\n'

test_end "section tie: energy, momentum, 1 = 2 ranks, restart, affine, bad set-ups: all passed"
