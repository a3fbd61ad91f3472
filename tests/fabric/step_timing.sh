#!/bin/bash
# Usage: step_timing.sh YARN_IMPACT SOURCE_DIR
# Consistency (the same run with a clock read or not; serial against
# parallel): Fabric/Step timing only reads clocks (doc/fabric.md section
# 8). The 4 x 4 patch of the example's yarns (prm/fabric/km2_patch.prm),
# the flat cylinder, 2 us, a history row every 0.05 us, on 2 ranks with
# the timing off and on and on 1 rank with it on: the three histories byte
# for byte the same; the timing's table in the summary when it is on
# (its 9 parts and the force evaluations it counted), and not when it is off,
# so that the check can fail if the entry were not read.
exe=$1
src=$2
. "$(dirname "$(readlink -f "$0")")/../lib.sh"
test_begin

# prm DIR TIMING RANKS: the case with Fabric/Step timing = TIMING.
prm() {
  printf 'include %s/prm/fabric/km2_patch_fsp.prm\n' "$src"
  printf 'subsection Fabric\n  set Warp yarns = 4\n  set Weft yarns = 4\n'
  printf '  set Step timing = %s\nend\n' "$2"
  printf 'subsection Time\n  set End time = 2e-6\nend\n'
  printf 'subsection Output\n  set Directory = %s\n  set Snapshot interval = 0\n' "$1"
  printf '  set History interval = 0.05e-6\n  set Verbosity = quiet\nend\n'
}

for c in off_2:false:2 on_2:true:2 on_1:true:1; do
  IFS=: read -r dir timing n <<< "$c"
  prm "$dir" "$timing" > "$dir.prm"
  mpirun -np "$n" "$exe" "$dir.prm" > "$dir.out" 2> "$dir.err" ||
    fail "$dir: exit $?: $(head -c 300 "$dir.err")"
done

for dir in on_2 on_1; do
  if same_history off_2/history_fabric.csv "$dir/history_fabric.csv"; then
    echo "ok     the history with the step timing on ($dir) is the one with it off, byte for byte"
  else
    fail "the history with the step timing on ($dir) differs from the one with it off"
  fi
done

# The table: each part's line and the force evaluations it counted (the
# steps and the first).
steps=$(grep -o 'fabric step by part ([0-9]* steps' on_2/summary.txt | grep -o '[0-9]*')
parts=$(grep -c -E '^ *(yarn contact: (list checks|list builds|exchange|forces)|FE forces and projectile contact|integration|stable step|observables|output) \|' on_2/summary.txt)
if [ -n "$steps" ] && [ "$steps" -gt 0 ] && [ "$parts" -eq 9 ]; then
  echo "ok     the summary with the timing on has the table: 9 parts, $steps force evaluations"
else
  fail "the summary with the timing on has no table of the 9 parts (found $parts, steps '$steps')"
fi
if grep -q 'fabric step by part' off_2/summary.txt; then
  fail "the summary with the timing off has the table"
else
  echo "ok     the summary with the timing off has no table"
fi
test_end
