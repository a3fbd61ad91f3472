#!/bin/bash
# Usage: restart.sh YARN_IMPACT
# Checkpoint and restart (doc/user-guide.md): a run stopped by a signal, or
# by a full disk after periodic checkpoints, and continued with --restart
# must write the same history as the uninterrupted run, byte for byte (the
# CSV holds 10 significant digits; the state is restored bitwise, FE and
# DEM alike, so the steps after the restart are the same steps). A check of
# the physics it is not: it checks that the restart loses and changes
# nothing. Refusals (other parameters, another rank count, no checkpoint, a
# damaged checkpoint) must exit 1 with one line saying why.
exe=$1
. "$(dirname "$(readlink -f "$0")")/../lib.sh"
test_begin

# run RANKS ARGS...: run on RANKS ranks; sets rc, stderr in ./stderr.
run() {
  local n=$1; shift
  if [ "$n" -eq 1 ]; then
    "$exe" "$@" > stdout 2> stderr
  else
    mpirun -np "$n" "$exe" "$@" > stdout 2> stderr
  fi
  rc=$?
}

# A small FE case: quarter symmetry, 40 cells along the axis.
fe_prm() { # directory, end time, checkpoint interval
  printf 'set Symmetry = quarter\nsubsection Time\n  set End time = %s\nend\n' "$2"
  printf 'subsection Output\n  set Directory = %s\n  set Snapshot interval = 0.5e-6\n' "$1"
  printf '  set History interval = 0.05e-6\n  set Checkpoint interval = %s\n' "$3"
  printf '  set Verbosity = quiet\nend\n'
  printf 'subsection FE\n  set Cells along the axis = 40\nend\n'
}
# A small DEM case (40 fibres, 2 mm).
dem_prm() { # directory, checkpoint interval, model
  printf 'set Model = %s\nset Symmetry = half\n' "${3:-dem}"
  printf 'subsection Yarn\n  set Length = 2e-3\n  set Number of fibres = 40\n'
  printf '  set Thickness semi-axis = 0.0182e-3\n  set Width semi-axis = 0.0844e-3\nend\n'
  printf 'subsection Projectile\n  set Mass = 0.991e-6\n  set Diameter = 1e-3\nend\n'
  printf 'subsection Time\n  set End time = 0.6e-6\nend\n'
  printf 'subsection Output\n  set Directory = %s\n  set Snapshot interval = 0.2e-6\n' "$1"
  printf '  set History interval = 0.01e-6\n  set Checkpoint interval = %s\n' "$2"
  printf '  set Verbosity = quiet\nend\n'
  printf 'subsection FE\n  set Cells along the axis = 40\nend\n'
}

# same NAME REF DIR FILES...: the files of DIR are those of REF, and DIR
# holds no checkpoint any more (removed at the end of a run).
same() {
  local name=$1 ref=$2 dir=$3; shift 3
  for f in "$@"; do
    cmp -s "$ref/$f" "$dir/$f" || fail "$name: $f differs from the uninterrupted run's"
  done
  if ls "$dir" | grep -q '^checkpoint_'; then
    fail "$name: checkpoints left after the run ended: $(ls "$dir" | grep checkpoint_ | head -3)"
  fi
}

# stopped NAME: the last run was stopped by a signal: exit 6 and one line.
stopped() {
  if [ "$rc" -ne 6 ] || ! head -1 stderr | grep -qE "^yarn-impact: stopped: the (fe|dem) run was stopped by SIGTERM at t = .* us \(step [0-9]+\); its state is saved in .*checkpoint_(fe|dem)\.txt; continue it with: yarn-impact --restart .*\.prm$"; then
    fail "$1: expected exit 6 and the stop line, got $rc: $(head -c 300 stderr)"
  fi
}

# refused NAME PATTERN: the last run exited 1 with a line matching PATTERN.
refused() {
  if [ "$rc" -ne 1 ] || ! head -1 stderr | grep -qE "^yarn-impact: error: $2"; then
    fail "$1: expected exit 1 and '$2', got $rc: $(head -c 300 stderr)"
  fi
}

# --- FE, 1 rank: SIGTERM at a history row, restart.
fe_prm ref_fe 2e-6 0 > ref_fe.prm
run 1 ref_fe.prm
[ "$rc" -eq 0 ] || fail "fe reference: exit $rc: $(head -c 300 stderr)"
fe_prm fe 2e-6 0 > fe.prm
YARN_IMPACT_SIGNAL_AT_ROW=17 run 1 fe.prm
stopped "fe signal"
[ -s fe/checkpoint_fe.txt ] || fail "fe signal: no checkpoint_fe.txt"
# The refusals, on this checkpoint, before it is used.
run 2 --restart fe.prm
refused "fe other rank count" "the checkpoint 'fe/checkpoint_fe.txt' was written by 1 MPI ranks: restart it on 1, not 2\.$"
fe_prm fe 3e-6 0 > fe_longer.prm
run 1 --restart fe_longer.prm
refused "fe other parameters" "--restart: the parameters differ from those of the run in Output/Directory = 'fe'"
run 1 fe.prm
refused "fe rerun without --restart" "Parameter 'Output/Directory' = 'fe' holds the output of an earlier run"
cp fe/checkpoint_fe_0_rank0.bin saved.bin
head -c 1000 saved.bin > fe/checkpoint_fe_0_rank0.bin
run 1 --restart fe.prm
refused "fe damaged checkpoint" "the newest checkpoint of the fe model is damaged: 'fe/checkpoint_fe_0_rank0.bin': its length does not match its header \(1000 bytes, the header says [0-9]+\): it is cut or damaged; there is no older checkpoint to continue from\.$"
cp saved.bin fe/checkpoint_fe_0_rank0.bin
run 1 --restart fe.prm
[ "$rc" -eq 0 ] || fail "fe restart: exit $rc: $(head -c 300 stderr)"
same "fe restart" ref_fe fe history_fe.csv

# --- FE with the progressive failure law, stopped while cells are being
# damaged (30.5 us; damage, its history variable and the eroded/damaged
# counts must come back).
prog_prm() { # directory
  printf 'set Symmetry = quarter\nsubsection Yarn\n  set Failure model = progressive\nend\n'
  printf 'subsection Time\n  set End time = 34e-6\nend\n'
  printf 'subsection Output\n  set Directory = %s\n  set Snapshot interval = 0\n' "$1"
  printf '  set History interval = 0.1e-6\n  set Verbosity = quiet\nend\n'
  printf 'subsection FE\n  set Cells along the axis = 40\nend\n'
}
prog_prm ref_prog > ref_prog.prm
run 1 ref_prog.prm
[ "$rc" -eq 0 ] || fail "progressive reference: exit $rc: $(head -c 300 stderr)"
awk -F, 'NR > 1 && $15 > 0 {found = 1} END {exit !found}' ref_prog/history_fe.csv ||
  fail "progressive reference: no failed cell by 34 us (the case no longer tests restarts through damage)"
prog_prm prog > prog.prm
YARN_IMPACT_SIGNAL_AT_ROW=305 run 1 prog.prm
stopped "progressive signal"
run 1 --restart prog.prm
[ "$rc" -eq 0 ] || fail "progressive restart: exit $rc: $(head -c 300 stderr)"
same "progressive restart" ref_prog prog history_fe.csv

# --- FE: periodic checkpoints, then a full disk; restart from the last one.
fe_prm ref_fe_long 4e-6 0 > ref_fe_long.prm
run 1 ref_fe_long.prm
total=$(du -sb ref_fe_long | cut -f1)
for share in 40 70; do
  fe_prm "disk$share" 4e-6 0.5e-6 > "disk$share.prm"
  YARN_IMPACT_DISK_FULL_AFTER=$((total * share / 100)) run 1 "disk$share.prm"
  [ "$rc" -eq 5 ] || fail "fe disk full ($share %): exit $rc (expected 5)"
  [ -s "disk$share/checkpoint_fe.txt" ] || fail "fe disk full ($share %): no checkpoint before the failure"
  run 1 --restart "disk$share.prm"
  [ "$rc" -eq 0 ] || fail "fe restart after a full disk ($share %): exit $rc: $(head -c 300 stderr)"
  same "fe restart after a full disk ($share %)" ref_fe_long "disk$share" history_fe.csv
done

# --- DEM, 1 and 2 ranks: SIGTERM, restart, bitwise. On 2 ranks, with a
# checkpoint at every row besides (a tiny wall-clock interval, decided on
# rank 0): the slots alternate many times, and writing checkpoints changes
# nothing in the run.
# Trusses break from 0.21 us on (Failure strain 1 %), before and after the
# stop at 0.23 us: their break times (breaks_dem.csv) must come back too.
breaking() { printf 'subsection Yarn\n  set Failure strain = 0.01\nend\n'; }
for n in 1 2; do
  { dem_prm "ref_dem$n" 0; breaking; } > "ref_dem$n.prm"
  run $n "ref_dem$n.prm"
  [ "$rc" -eq 0 ] || fail "dem reference on $n ranks: exit $rc: $(head -c 300 stderr)"
  awk -F, 'NR > 1 && $1 < 0.23 {b = 1} NR > 1 && $1 > 0.23 {a = 1} END {exit !(a && b)}' "ref_dem$n/breaks_dem.csv" ||
    fail "dem reference on $n ranks: no truss broken before and after the stop (the case no longer tests restarts through breaks)"
  # Every failed element of the history is listed, once (half symmetry:
  # the history counts the whole yarn, twice the modelled half).
  listed=$(($(wc -l < "ref_dem$n/breaks_dem.csv") - 1))
  failed=$(tail -1 "ref_dem$n/history_dem.csv" | cut -d, -f15)
  [ $((2 * listed)) -eq "$failed" ] ||
    fail "dem reference on $n ranks: breaks_dem.csv lists $listed broken trusses, the history $failed failed elements (the whole yarn)"
  { dem_prm "dem$n" 0; breaking; } > "dem$n.prm"
  if [ $n -eq 2 ]; then
    printf 'subsection Output\n  set Checkpoint wall-clock interval = 1e-9\nend\n' >> "dem$n.prm"
  fi
  YARN_IMPACT_SIGNAL_AT_ROW=23 run $n "dem$n.prm"
  stopped "dem signal on $n ranks"
  if [ $n -eq 2 ] && ! grep -q "^generation = 23$" "dem$n/checkpoint_dem.txt"; then
    fail "dem wall-clock checkpoints: $(grep generation "dem$n/checkpoint_dem.txt") (expected 23, one per row)"
  fi
  run $n --restart "dem$n.prm"
  [ "$rc" -eq 0 ] || fail "dem restart on $n ranks: exit $rc: $(head -c 300 stderr)"
  same "dem restart on $n ranks" "ref_dem$n" "dem$n" history_dem.csv breaks_dem.csv
done

# --- Model = both, stopped in its DEM part: the FE part is not run again,
# and the comparison is the same.
dem_prm ref_both 0 both > ref_both.prm
run 1 ref_both.prm
[ "$rc" -eq 0 ] || fail "both reference: exit $rc: $(head -c 300 stderr)"
dem_prm both 0 both > both.prm
fe_rows=$(($(wc -l < ref_both/history_fe.csv) - 1))
YARN_IMPACT_SIGNAL_AT_ROW=$((fe_rows + 30)) run 1 both.prm
stopped "both signal"
grep -q "the dem run was stopped" stderr || fail "both signal: not stopped in the DEM part: $(head -c 300 stderr)"
run 1 --restart both.prm
[ "$rc" -eq 0 ] || fail "both restart: exit $rc: $(head -c 300 stderr)"
grep -q "\[fe\] restarted from its checkpoint at .* (its run had finished)" stdout ||
  fail "both restart: the FE part was not taken from its checkpoint"
same "both restart" ref_both both history_fe.csv history_dem.csv comparison.csv

# --- A real SIGTERM from outside (as a job scheduler sends it), at any time:
# the run stops at its next history row.
fe_prm ref_term 12e-6 0 > ref_term.prm
run 1 ref_term.prm
fe_prm term 12e-6 0 > term.prm
"$exe" term.prm > stdout 2> stderr &
pid=$!
while [ ! -s term/history_fe.csv ] && kill -0 $pid 2> /dev/null; do sleep 0.05; done
kill -TERM $pid 2> /dev/null
wait $pid
rc=$?
if [ "$rc" -eq 0 ]; then
  echo "note: the external SIGTERM came after the end of the run; nothing to restart"
else
  stopped "external SIGTERM"
  run 1 --restart term.prm
  [ "$rc" -eq 0 ] || fail "restart after an external SIGTERM: exit $rc: $(head -c 300 stderr)"
fi
same "restart after an external SIGTERM" ref_term term history_fe.csv

test_end "all restart cases passed"
