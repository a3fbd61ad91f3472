#!/bin/bash
# Usage: concurrent_runs.sh YARN_IMPACT
# One owner per output folder (doc/user-guide.md, "One run, one folder"):
# - two runs started at the same time on one folder: exactly one runs, the
#   other exits 7 with one line naming the folder and the holder's PID and
#   host, and the folder holds the winner's output alone;
# - while a run is alive (held with SIGSTOP, so that the test does not
#   depend on timing), a second run on 2 ranks, even with Output/Overwrite,
#   and a --restart are refused the same way, and the live run ends with
#   the history of an undisturbed run;
# - the lock of a dead owner (SIGKILL) or a lock file left with a dead PID
#   does not block: the restart or the new run goes on.
exe=$1
. "$(dirname "$(readlink -f "$0")")/../lib.sh"
test_begin cleanup
pids=()
cleanup() {
  for p in "${pids[@]}"; do kill -KILL "$p" 2> /dev/null; done
}
host=$(hostname)

# A small FE case (about a second): directory, end time, extra Output lines.
fe_prm() {
  printf 'set Symmetry = quarter\nsubsection Time\n  set End time = %s\nend\n' "$2"
  printf 'subsection Output\n  set Directory = %s\n  set Snapshot interval = 0.5e-6\n' "$1"
  printf '  set History interval = 0.05e-6\n  set Checkpoint interval = 0.5e-6\n'
  printf '  set Verbosity = quiet\n%s\nend\n' "$3"
  printf 'subsection FE\n  set Cells along the axis = 40\nend\n'
}

# in_use FILE DIR PID: FILE's first line is the refusal naming DIR and PID.
in_use() {
  head -1 "$1" | grep -qxF "yarn-impact: error: Parameter 'Output/Directory' = '$2' is in use by another run: process $3 on host $host holds its lock '$2/.yarn-impact.lock'; wait for that run to end, or choose another directory."
}

# wait_for FILE PID: wait until FILE exists, while PID runs.
wait_for() {
  while [ ! -e "$1" ] && kill -0 "$2" 2> /dev/null; do sleep 0.02; done
  [ -e "$1" ]
}

for t in 8e-6 6e-6 4e-6 3e-6; do
  fe_prm "ref_$t" $t > "ref_$t.prm"
  "$exe" "ref_$t.prm" > /dev/null 2>&1 || fail "reference $t: exit $?"
done

# stopped PID: whether PID is stopped (SIGSTOP).
stopped() { ps -o stat= -p "$1" | grep -q '^T'; }

# 1. Two runs started together on one folder, twice. Each waits stopped
# until both are ready, then both are let go at once. The runs last a few
# seconds, so that on a loaded machine the second still starts while the
# first runs; a try where one started after the other ended (exit 0 and
# exit 1, an earlier run's output) proves nothing and is made again, up to
# 5 tries.
races=0
for try in 1 2 3 4 5; do
  [ $races -lt 2 ] || break
  dir="race$try"
  fe_prm "$dir" 8e-6 > "a$try.prm"
  fe_prm "$dir" 6e-6 > "b$try.prm"
  bash -c 'kill -STOP $$; exec "$0" "$1"' "$exe" "a$try.prm" > a.out 2> a.err &
  pa=$!
  bash -c 'kill -STOP $$; exec "$0" "$1"' "$exe" "b$try.prm" > b.out 2> b.err &
  pb=$!
  pids+=($pa $pb)
  while ! stopped $pa || ! stopped $pb; do sleep 0.01; done
  kill -CONT $pa $pb
  wait $pa; ra=$?
  wait $pb; rb=$?
  if [ $ra -eq 0 ] && [ $rb -eq 7 ]; then
    winner=$pa; t=8e-6; loser=b.err
  elif [ $ra -eq 7 ] && [ $rb -eq 0 ]; then
    winner=$pb; t=6e-6; loser=a.err
  elif [ $((ra + rb)) -eq 1 ] && [ $((ra * rb)) -eq 0 ] &&
       grep -qF "holds the output of an earlier run" a.err b.err; then
    echo "note   race $try: one run started after the other had ended; again"
    continue
  else
    fail "race $try: exit codes $ra and $rb (expected 0 and 7): $(cat a.err b.err | head -c 400)"
    continue
  fi
  races=$((races + 1))
  if ! in_use $loser "$dir" $winner || [ "$(wc -l < $loser)" -ne 1 ]; then
    fail "race $try: refusal: $(head -c 300 $loser)"
  elif ! cmp -s "ref_$t/history_fe.csv" "$dir/history_fe.csv" ||
       ! grep -q "set End time *= $t\$" "$dir/parameters.prm"; then
    fail "race $try: the folder does not hold the winner's run alone"
  else
    echo "ok     race $try: one ran, the other: $(cat $loser)"
  fi
done
[ $races -ge 1 ] || fail "races: no try had both runs at once"

# 2. A live run (stopped with SIGSTOP after its first checkpoint): a new run
# on 2 ranks with Output/Overwrite and a --restart are refused, and remove
# nothing.
fe_prm live 4e-6 > live.prm
fe_prm live 4e-6 "  set Overwrite = true" > live_overwrite.prm
"$exe" live.prm > live.out 2> live.err &
pl=$!
pids+=($pl)
if ! wait_for live/checkpoint_fe.txt $pl; then
  fail "live run: ended before its first checkpoint: $(head -c 300 live.err)"
else
  kill -STOP $pl
  mpirun -np 2 "$exe" live_overwrite.prm > stdout 2> stderr
  rc=$?
  if [ $rc -ne 7 ] || ! in_use stderr live $pl; then
    fail "second run with Overwrite on a live folder: exit $rc: $(head -c 300 stderr)"
  else
    echo "ok     second run on 2 ranks with Overwrite: $(head -1 stderr)"
  fi
  "$exe" --restart live.prm > stdout 2> stderr
  rc=$?
  if [ $rc -ne 7 ] || ! in_use stderr live $pl || [ "$(wc -l < stderr)" -ne 1 ]; then
    fail "--restart of a live run: exit $rc: $(head -c 300 stderr)"
  else
    echo "ok     --restart of a live run: $(cat stderr)"
  fi
  kill -CONT $pl
fi
wait $pl
rc=$?
if [ $rc -ne 0 ] || ! cmp -s ref_4e-6/history_fe.csv live/history_fe.csv; then
  fail "live run: exit $rc, or its history differs from an undisturbed run's: $(head -c 300 live.err)"
fi

# 3. An owner killed with SIGKILL leaves its lock file, not its lock: the
# restart goes on and ends with the uninterrupted history.
fe_prm killed 4e-6 > killed.prm
"$exe" killed.prm > /dev/null 2>&1 &
pk=$!
pids+=($pk)
if wait_for killed/checkpoint_fe.txt $pk; then
  kill -STOP $pk
  kill -KILL $pk
  wait $pk 2> /dev/null
  "$exe" --restart killed.prm > stdout 2> stderr
  rc=$?
  if [ $rc -ne 0 ] || ! cmp -s ref_4e-6/history_fe.csv killed/history_fe.csv; then
    fail "restart after SIGKILL: exit $rc: $(head -c 300 stderr)"
  else
    echo "ok     restart after SIGKILL of the owner"
  fi
else
  fail "killed run: ended before its first checkpoint"
fi

# 4. A lock file naming a dead process of this host: taken over, and the
# new owner's PID written.
mkdir stale
echo "999999999 $host" > stale/.yarn-impact.lock
fe_prm stale 3e-6 > stale.prm
"$exe" stale.prm > stdout 2> stderr &
ps=$!
pids+=($ps)
wait $ps
rc=$?
if [ $rc -ne 0 ] || [ "$(cat stale/.yarn-impact.lock)" != "$ps $host" ]; then
  fail "stale lock file: exit $rc, lock file '$(cat stale/.yarn-impact.lock)': $(head -c 300 stderr)"
elif ls stale | grep -q lock; then
  fail "stale lock file: the lock file shows in the folder's listing"
else
  echo "ok     stale lock file of a dead process: taken over"
fi

test_end "all concurrent-run cases passed"
