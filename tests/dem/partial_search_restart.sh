#!/bin/bash
# Partial searches across a restart (consistency and the list check): the
# case of partial_search.prm (quarter symmetry, cut fibres, most failing
# blocks searched again at their fast spheres only, DEM/Check lists on),
# stopped by SIGTERM at a history row and continued with --restart, must
# give the history of the run that was not stopped, byte for byte. A
# checkpoint does not store the blocks' cell grids of their builds: the
# first partial search after the restart makes each again from the build
# positions. A grid of other positions (the set-up's, kept over the
# restart) loses pairs, which the list check of every force evaluation
# finds (the run stops with exit 4 naming the two spheres): the test fails.
exe=$1
src=$2
. "$(dirname "$(readlink -f "$0")")/../lib.sh"
test_begin
for run in whole stopped; do
  sed -e "s#set Directory         = run#set Directory = $run#" \
      "$src/partial_search.prm" > $run.prm
  grep -q "Directory = $run" $run.prm || fail "$run.prm: no output directory set"
done
"$exe" whole.prm > /dev/null || fail "the run that was not stopped: exit $?"
YARN_IMPACT_SIGNAL_AT_ROW=14 "$exe" stopped.prm > /dev/null 2> stderr
rc=$?
[ $rc -eq 6 ] || fail "the stopped run exited with $rc, not 6: $(head -c 300 stderr)"
"$exe" --restart stopped.prm > /dev/null 2> stderr
rc=$?
[ $rc -eq 0 ] || fail "the restart exited with $rc: $(head -c 300 stderr)"
for f in history_dem.csv breaks_dem.csv; do
  same_history whole/$f stopped/$f ||
    fail "$f after the restart differs from the run that was not stopped"
done
rows=$(wc -l < whole/history_dem.csv)
[ "$rows" -gt 20 ] || fail "only $rows history rows"
test_end "partial searches across a restart: history and breaks byte for byte ($rows rows)"
