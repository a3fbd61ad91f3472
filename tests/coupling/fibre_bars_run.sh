#!/bin/bash
# Usage: fibre_bars_run.sh YARN_IMPACT SOURCE_DIR
# The hybrid yarn with a far field of fibre bars (Hybrid/Far field =
# fibre bars, doc/hybrid.md section 3.4), the paper's case with a 3 mm DEM
# part over the first 1.8 us (the bar wave reaches the clamp at 1.66 us).
# Physics and consistency checks, no recorded numbers:
# - the run's own checks: the longitudinal front's speed, fitted from 1 us
#   until it reaches the clamp (through the DEM part, the overlap and the
#   bars), within 2 % of Smith's bar speed (measured -1.2 %), and the
#   largest energy balance error, the bars and both ties included, at most
#   0.05 % of the initial energy (the projectile's deceleration is the DEM
#   part's until the bars' waves come back, checked by hybrid_run.sh);
# - the same history on 1, 2 and 3 MPI ranks (each rank steps its own
#   fibres' bars, the sums over fibres are in fibre order, the DEM part's
#   sums are reproducible): byte for byte;
# - stopped by SIGTERM at a history row and continued with --restart: the
#   same history, byte for byte (the bars' checkpoint);
# - bad set-ups refused by --check with one line naming the parameter.
exe=$1
src=$2
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cd "$work" || exit 1
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
failures=0
fail() {
  echo "FAILED $*"
  failures=$((failures + 1))
}
. "$src/tests/coupling/run_checks.sh"

bars_prm() {
  cat "$src/prm/hybrid/km2_120ms_hybrid.prm"
  printf 'subsection Hybrid\n  set DEM half-length = 3e-3\n'
  printf '  set Far field = fibre bars\nend\n'
  printf 'subsection Time\n  set End time = 1.8e-6\nend\n'
  printf 'subsection Output\n  set Directory = %s\n  set Snapshot interval = 0\nend\n' "$1"
  printf 'subsection Verification\n  set Checks = longitudinal speed, energy\n'
  printf '  set Window end = 1.8e-6\n  set Energy tolerance = 5e-4\n  set Tolerance = 0.02\nend\n'
}

# 3 ranks on this 2-core machine: oversubscribed.
export OMPI_MCA_rmaps_base_oversubscribe=1
same_on_ranks bars_prm 1 2 3
grep -E "longitudinal speed|energy error" ranks1/summary.txt

restart_same bars_prm 9 ranks1/history_hybrid.csv

refuse bars_prm "fibre bars with a DEM part at the clamp" "Hybrid/Clamp DEM length" \
  'subsection Hybrid\n  set Clamp DEM length = 2e-3\nend\n'
refuse bars_prm "fibre bars with the linear law" "FE/Constitutive law" \
  'subsection FE\n  set Constitutive law = Linear transversely isotropic\nend\n'
refuse bars_prm "an unknown far field" "Far field" \
  'subsection Hybrid\n  set Far field = springs\nend\n'

if [ $failures -ne 0 ]; then
  echo "$failures check(s) failed"
  exit 1
fi
echo "fibre bars: bar speed, energy, 1 = 2 = 3 ranks, restart, bad set-ups: all passed"
