#!/bin/bash
# Usage: signals.sh YARN_IMPACT PRM_DIR
# Every run stops (doc/user-guide.md, exit codes): a SIGTERM or SIGINT is
# honoured within a few seconds in every mode, however long the history
# interval (here History interval = End time: no row between t = 0 and the
# end, so a run that waited for its next row would not stop):
# - an FE impact run on 1 rank (SIGTERM, SIGINT) and on 2 ranks under
#   mpirun (the signal sent to the ranks, as a scheduler does): exit 6
#   (mpirun's too), one line, a whole checkpoint and no temporary file;
#   `--restart` then ends with the history of the uninterrupted run, byte
#   for byte;
# - an elementary test (compaction) on 1 and 2 ranks: exit 6, one line
#   naming the .partial file of its rows so far, whole rows in it, no
#   finished CSV and no summary.
# Each stop must come within 3 s of the signal on 1 rank, 5 s under mpirun
# (the run stops within a few steps, tens of milliseconds here; mpirun
# takes about a second more to end after its ranks).
exe=$1
prm_dir=$2
. "$(dirname "$(readlink -f "$0")")/../lib.sh"
test_begin cleanup
pids=()
cleanup() {
  for p in "${pids[@]}"; do kill -KILL "$p" 2> /dev/null; done
}

# An FE case of about 2 s, with no history row between t = 0 and its end.
fe_prm() {
  printf 'set Symmetry = quarter\nsubsection Time\n  set End time = 30e-6\n'
  printf '  set Safety factor = 0.4\nend\n'
  printf 'subsection Output\n  set Directory = %s\n  set Snapshot interval = 0\n' "$1"
  printf '  set History interval = 30e-6\n  set Verbosity = quiet\nend\n'
  printf 'subsection FE\n  set Cells along the axis = 160\nend\n'
}

# launch RANKS ARGS...: start the run in the background; sets pid (of the
# process or of mpirun).
launch() {
  local n=$1
  shift
  if [ "$n" -eq 1 ]; then
    "$exe" "$@" > stdout 2> stderr &
  else
    mpirun -np "$n" "$exe" "$@" > stdout 2> stderr &
  fi
  pid=$!
  pids+=($pid)
}

# signal_run RANKS SIGNAL FILE: wait until FILE exists (the run is in its
# time loop), send SIGNAL to the run (to the ranks under mpirun), wait for
# it; sets rc and waited (seconds from the signal to the end).
signal_run() {
  local n=$1 sig=$2 file=$3
  while [ ! -s "$file" ] && kill -0 "$pid" 2> /dev/null; do sleep 0.02; done
  sleep 0.2
  local targets=$pid
  [ "$n" -eq 1 ] || targets=$(pgrep -P "$pid")
  local t0
  t0=$(date +%s%N)
  # shellcheck disable=SC2086
  kill -"$sig" $targets 2> /dev/null
  wait "$pid"
  rc=$?
  waited=$((($(date +%s%N) - t0) / 1000000))
  limit=3000
  [ "$n" -eq 1 ] || limit=5000
}

fe_prm ref > ref.prm
"$exe" ref.prm > /dev/null 2>&1 || fail "fe reference: exit $?"

for n in 1 2; do
  for sig in TERM INT; do
    dir="fe_${n}_$sig"
    fe_prm "$dir" > "$dir.prm"
    launch "$n" "$dir.prm"
    signal_run "$n" "$sig" "$dir/history_fe.csv"
    line=$(grep -c . stderr)
    [ "$n" -eq 1 ] || line=$(grep -c '^yarn-impact' stderr)
    if [ "$rc" -ne 6 ] || [ "$line" -ne 1 ] ||
      ! head -1 stderr | grep -qE "^yarn-impact: stopped: the fe run was stopped by SIG$sig at t = [0-9.e+-]+ us \(step [0-9]+\); its state is saved in $dir/checkpoint_fe\.txt; continue it with: yarn-impact --restart $dir\.prm$"; then
      fail "fe on $n rank(s), SIG$sig: expected exit 6 and the stop line, got $rc: $(head -c 300 stderr)"
      continue
    fi
    [ "$waited" -le "$limit" ] || fail "fe on $n rank(s), SIG$sig: stopped $waited ms after the signal"
    if ls "$dir" | grep -q '\.tmp$'; then
      fail "fe on $n rank(s), SIG$sig: a temporary file is left: $(ls "$dir")"
    fi
    if [ "$n" -eq 1 ]; then
      "$exe" --restart "$dir.prm" > stdout 2> stderr
    else
      mpirun -np "$n" "$exe" --restart "$dir.prm" > stdout 2> stderr
    fi
    rc=$?
    [ "$rc" -eq 0 ] || fail "fe on $n rank(s), SIG$sig: restart exit $rc: $(head -c 300 stderr)"
    cmp -s ref/history_fe.csv "$dir/history_fe.csv" ||
      fail "fe on $n rank(s), SIG$sig: the restarted history differs from the uninterrupted one"
    echo "fe on $n rank(s), SIG$sig: stopped in $waited ms, restart cmp-identical"
  done
done

# Elementary tests: no checkpoint, the rows so far kept as .partial.
for n in 1 2; do
  sig=TERM
  [ "$n" -eq 1 ] || sig=INT
  dir="el_$n"
  sed -e "s|set Directory .*|set Directory = $dir|" \
    "$prm_dir/elementary/compaction.prm" > "$dir.prm"
  launch "$n" "$dir.prm"
  signal_run "$n" "$sig" "$dir/elementary_compaction.csv.partial"
  if [ "$rc" -ne 6 ] ||
    ! grep -qE "^yarn-impact: stopped: the elementary test \(compaction\) was stopped by SIG$sig at t = [0-9.]+ us; its rows so far are in $dir/elementary_compaction\.csv\.partial \(the elementary tests write no checkpoints: run it again to finish it\)$" stderr ||
    [ "$(grep -c '^yarn-impact' stderr)" -ne 1 ]; then
    fail "elementary on $n rank(s), SIG$sig: expected exit 6 and the stop line, got $rc: $(head -c 300 stderr)"
    continue
  fi
  [ "$waited" -le "$limit" ] || fail "elementary on $n rank(s), SIG$sig: stopped $waited ms after the signal"
  [ ! -e "$dir/elementary_compaction.csv" ] && [ ! -e "$dir/summary.txt" ] ||
    fail "elementary on $n rank(s), SIG$sig: a finished CSV or summary was written"
  fields=$(awk -F, '{print NF}' "$dir/elementary_compaction.csv.partial" | sort -u)
  [ "$fields" = "30" ] || fail "elementary on $n rank(s), SIG$sig: rows of $fields fields in the .partial file"
  echo "elementary on $n rank(s), SIG$sig: stopped in $waited ms, $(($(wc -l < "$dir/elementary_compaction.csv.partial") - 1)) whole rows kept"
done

test_end "signals: every run stopped within a few seconds with exit 6"
