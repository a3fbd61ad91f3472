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
# - the same history on 1 and 2 MPI ranks (every rank steps every bar in
#   the same order): byte for byte but the energy columns, which the DEM
#   part sums rank by rank (within 1e-9 of the initial energy);
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
. "$src/tests/coupling/same_history.sh"

bars_prm() {
  cat "$src/prm/hybrid/km2_120ms_hybrid.prm"
  printf 'subsection Hybrid\n  set DEM half-length = 3e-3\n'
  printf '  set Far field = fibre bars\nend\n'
  printf 'subsection Time\n  set End time = 1.8e-6\nend\n'
  printf 'subsection Output\n  set Directory = %s\n  set Snapshot interval = 0\nend\n' "$1"
  printf 'subsection Verification\n  set Checks = longitudinal speed, energy\n'
  printf '  set Window end = 1.8e-6\n  set Energy tolerance = 5e-4\n  set Tolerance = 0.02\nend\n'
}

for n in 1 2; do
  bars_prm "ranks$n" > "ranks$n.prm"
  mpirun -np "$n" "$exe" "ranks$n.prm" > "ranks$n.stdout" 2>&1
  rc=$?
  if [ $rc -ne 0 ]; then
    fail "$n rank(s): exit $rc (3 = a verification check failed)"
    tail -25 "ranks$n.stdout"
    continue
  fi
  if [ "$n" -gt 1 ] && ! same_history ranks1/history_hybrid.csv "ranks$n/history_hybrid.csv"; then
    fail "$n ranks: history_hybrid.csv differs from 1 rank's"
  fi
done
grep -E "longitudinal speed|energy error" ranks1/summary.txt

bars_prm stopped > stopped.prm
YARN_IMPACT_SIGNAL_AT_ROW=9 "$exe" stopped.prm > stopped.stdout 2> stopped.stderr
rc=$?
[ $rc -eq 6 ] || fail "signal: expected exit 6, got $rc: $(head -c 300 stopped.stderr)"
"$exe" --restart stopped.prm > restarted.stdout 2> restarted.stderr
rc=$?
[ $rc -eq 0 ] || fail "restart: exit $rc: $(head -c 300 restarted.stderr)"
cmp -s ranks1/history_hybrid.csv stopped/history_hybrid.csv ||
  fail "restart: history_hybrid.csv differs from the uninterrupted run's"

refuse() {
  local name=$1 pattern=$2
  shift 2
  { bars_prm bad; printf '%b' "$*"; } > bad.prm
  "$exe" --check bad.prm > bad.stdout 2> bad.stderr
  rc=$?
  if [ $rc -ne 1 ] || [ "$(wc -l < bad.stderr)" -ne 1 ] || ! grep -q "$pattern" bad.stderr; then
    fail "$name: expected exit 1 and one line naming $pattern, got $rc: $(head -c 300 bad.stderr)"
  fi
}
refuse "fibre bars with a DEM part at the clamp" "Hybrid/Clamp DEM length" \
  'subsection Hybrid\n  set Clamp DEM length = 2e-3\nend\n'
refuse "fibre bars with the linear law" "FE/Constitutive law" \
  'subsection FE\n  set Constitutive law = Linear transversely isotropic\nend\n'
refuse "an unknown far field" "Far field" \
  'subsection Hybrid\n  set Far field = springs\nend\n'

if [ $failures -ne 0 ]; then
  echo "$failures check(s) failed"
  exit 1
fi
echo "fibre bars: bar speed, energy, 1 = 2 ranks, restart, bad set-ups: all passed"
