#!/bin/bash
# Usage: checkpoint_damage.sh YARN_IMPACT
# Checkpoints prove they are whole (doc/user-guide.md, "Checkpoint and
# restart"). A run of the FE and of the DEM, on 1 and 2 ranks, is stopped
# by a signal after earlier checkpoints, so that both slots hold one. Then
# bytes and single bits are flipped, one at a time, at offsets spread over
# the info file and every rank file of the newest slot (header, state,
# checksum), and the restart must
# - refuse a damaged info file (exit 1, one line naming it);
# - fall back to the older slot for a damaged rank file of the newest, with
#   one warning line naming that file;
# - ignore a damaged file of the older slot (the newest is whole);
# and never restore a flip silently. A fallback restart run to its end
# writes the history of the uninterrupted run, byte for byte; both slots
# damaged, a changed parameters.prm and a checkpoint of format 1 are
# refused.
exe=$1
. "$(dirname "$(readlink -f "$0")")/../lib.sh"
test_begin
checked=0

# run RANKS ARGS...: run on RANKS ranks; sets rc, stdout and stderr.
run() {
  local n=$1; shift
  if [ "$n" -eq 1 ]; then
    "$exe" "$@" > stdout 2> stderr
  else
    mpirun -np "$n" "$exe" "$@" > stdout 2> stderr
  fi
  rc=$?
}

# flip FILE OFFSET MASK: XOR the byte at OFFSET with MASK, in place.
flip() {
  local byte
  byte=$(od -An -tu1 -j "$2" -N 1 "$1" | tr -d ' ')
  printf "$(printf '\\%03o' $((byte ^ $3)))" |
    dd of="$1" bs=1 seek="$2" conv=notrunc status=none
}

# The cases of tests/app/restart.sh, with periodic checkpoints.
fe_prm() { # directory
  printf 'set Symmetry = quarter\nsubsection Time\n  set End time = 2e-6\nend\n'
  printf 'subsection Output\n  set Directory = %s\n  set Snapshot interval = 0.5e-6\n' "$1"
  printf '  set History interval = 0.05e-6\n  set Checkpoint interval = 0.3e-6\n'
  printf '  set Verbosity = quiet\nend\n'
  printf 'subsection FE\n  set Cells along the axis = 40\nend\n'
}
dem_prm() { # directory
  printf 'set Model = dem\nset Symmetry = half\n'
  printf 'subsection Yarn\n  set Length = 2e-3\n  set Number of fibres = 40\n'
  printf '  set Thickness semi-axis = 0.0182e-3\n  set Width semi-axis = 0.0844e-3\nend\n'
  printf 'subsection Projectile\n  set Mass = 0.991e-6\n  set Diameter = 1e-3\nend\n'
  printf 'subsection Time\n  set End time = 0.6e-6\nend\n'
  printf 'subsection Output\n  set Directory = %s\n  set Snapshot interval = 0.2e-6\n' "$1"
  printf '  set History interval = 0.01e-6\n  set Checkpoint interval = 0.1e-6\n'
  printf '  set Verbosity = quiet\nend\n'
}

# offsets FILE RANK RANKS: offsets spread over a rank file. On 1 rank: the
# header's magic, format, rank, generation and length, the state at a
# third and two thirds, its last byte, and the checksum; on 2 ranks, half
# of them in each rank's file (every damaged restart costs seconds there).
offsets() {
  local size
  size=$(stat -c %s "$1")
  local all=(0 9 12 26 33 $((size / 3)) $((2 * size / 3)) $((size - 5)) $((size - 1)))
  if [ "$3" -eq 1 ]; then
    echo "${all[@]}"
  elif [ "$2" -eq 0 ]; then
    echo "${all[0]} ${all[5]}"
  else
    echo "${all[4]} ${all[8]}"
  fi
}

# restart_damaged RANKS MODEL DIR PRM COMMAND...: restore the stopped run,
# damage it with COMMAND, restart it and stop it at its first row.
restart_damaged() {
  local n=$1 model=$2 dir=$3 prm=$4; shift 4
  rm -rf "$dir" && cp -a "saved_$dir" "$dir"
  "$@"
  YARN_IMPACT_SIGNAL_AT_ROW=1 run "$n" --restart "$prm"
  checked=$((checked + 1))
}

for model in fe dem; do
  for n in 1 2; do
    case="$model on $n ranks"
    dir="${model}$n"
    "${model}_prm" "ref_$dir" > "ref_$dir.prm"
    run "$n" "ref_$dir.prm"
    [ "$rc" -eq 0 ] || fail "$case reference: exit $rc: $(head -c 300 stderr)"
    "${model}_prm" "$dir" > "$dir.prm"
    # FE: checkpoints at 0.3 and 0.6 us, stopped at 0.85 us; DEM: at 0.1,
    # 0.2 and 0.3 us, stopped at 0.35 us.
    YARN_IMPACT_SIGNAL_AT_ROW=$([ $model = fe ] && echo 17 || echo 35) run "$n" "$dir.prm"
    if [ "$rc" -ne 6 ]; then
      fail "$case: the run was not stopped by its signal: exit $rc: $(head -c 300 stderr)"
      continue
    fi
    info="$dir/checkpoint_$model.txt"
    slot=$(sed -n 's/^slot = //p' "$info")
    older=$((1 - slot))
    if ! grep -q '^older generation = [1-9]' "$info"; then
      fail "$case: no older checkpoint: $(cat "$info")"
      continue
    fi
    cp -a "$dir" "saved_$dir"

    # The info file: refused, naming it. A byte or a bit at offsets over
    # the whole file, its own checksum and its last newline included.
    size=$(stat -c %s "$info")
    if [ "$n" -eq 2 ]; then
      info_offsets=$((size / 2))
    elif [ $model = fe ]; then
      info_offsets="0 $((size / 4)) $((3 * size / 4)) $((size - 1))"
    else
      info_offsets="$((size / 3)) $((2 * size / 3)) $((size - 3))"
    fi
    k=0
    for off in $info_offsets; do
      mask=$([ $((k % 2)) -eq 0 ] && echo 255 || echo $((1 << (k % 8))))
      k=$((k + 1))
      restart_damaged "$n" "$model" "$dir" "$dir.prm" flip "$info" "$off" "$mask"
      if [ "$rc" -ne 1 ] ||
         ! head -1 stderr | grep -qF "yarn-impact: error: the checkpoint file '$info' cannot be used (" ||
         { [ "$n" -eq 1 ] && [ "$(wc -l < stderr)" -ne 1 ]; }; then
        fail "$case: info file flipped at $off (mask $mask): exit $rc: $(head -c 300 stderr)"
      fi
    done

    # Each rank file of the newest slot: the older slot is taken, saying so.
    for ((r = 0; r < n; r++)); do
      file="$dir/checkpoint_${model}_${slot}_rank$r.bin"
      for off in $(offsets "saved_$file" "$r" "$n"); do
        mask=$([ $((k % 2)) -eq 0 ] && echo 255 || echo $((1 << (k % 8))))
        k=$((k + 1))
        restart_damaged "$n" "$model" "$dir" "$dir.prm" flip "$file" "$off" "$mask"
        if [ "$rc" -ne 6 ] ||
           ! head -1 stderr | grep -qE "^yarn-impact: warning: the newest checkpoint of the $model model is damaged: '$file': .*; continuing from the older checkpoint at t = [0-9.e+-]+ us \(step [0-9]+\)\.$" ||
           ! grep -q "^yarn-impact: stopped: " stderr; then
          fail "$case: $file flipped at $off (mask $mask): no fallback to the older slot: exit $rc: $(head -c 400 stderr)"
        fi
      done
    done

    if [ "$n" -eq 1 ]; then
      # A rank file of the older slot: the newest is whole and is used,
      # silently.
      file="$dir/checkpoint_${model}_${older}_rank0.bin"
      restart_damaged "$n" "$model" "$dir" "$dir.prm" flip "$file" 100 16
      if [ "$rc" -ne 6 ] || grep -q "warning" stderr; then
        fail "$case: older slot flipped: the newest was not taken: exit $rc: $(head -c 300 stderr)"
      fi
      # Both slots damaged: refused, naming both files (on 2 ranks the
      # fallbacks above name the file of either rank already).
      file="$dir/checkpoint_${model}_${slot}_rank0.bin"
      file2="$dir/checkpoint_${model}_${older}_rank0.bin"
      restart_damaged "$n" "$model" "$dir" "$dir.prm" eval "flip $file 200 1; flip $file2 300 128"
      if [ "$rc" -ne 1 ] || [ "$(wc -l < stderr)" -ne 1 ] ||
         ! grep -qE "^yarn-impact: error: the newest checkpoint of the $model model is damaged: '$file': its checksum does not match its contents; so is the older one: '$file2': its checksum does not match its contents\.$" stderr; then
        fail "$case: both slots damaged: exit $rc: $(head -c 400 stderr)"
      fi
    fi
    if [ "$dir" = fe1 ]; then
      # A changed parameters.prm: refused (the same check in every case).
      restart_damaged "$n" "$model" "$dir" "$dir.prm" flip "$dir/parameters.prm" 20 4
      if [ "$rc" -ne 1 ] || ! grep -qF "yarn-impact: error: --restart: the parameters differ" stderr; then
        fail "$case: parameters.prm flipped: exit $rc: $(head -c 300 stderr)"
      fi
    fi

    # A fallback restart run to its end: the uninterrupted run's history.
    rm -rf "$dir" && cp -a "saved_$dir" "$dir"
    flip "$dir/checkpoint_${model}_${slot}_rank$((n - 1)).bin" 5000 8
    run "$n" --restart "$dir.prm"
    if [ "$rc" -ne 0 ] || ! head -1 stderr | grep -q "^yarn-impact: warning: the newest checkpoint"; then
      fail "$case: fallback restart: exit $rc: $(head -c 300 stderr)"
    elif ! cmp -s "ref_$dir/history_$model.csv" "$dir/history_$model.csv"; then
      fail "$case: fallback restart: the history differs from the uninterrupted run's"
    elif ls "$dir" | grep -q '^checkpoint_'; then
      fail "$case: fallback restart: checkpoints left after the run ended"
    else
      echo "ok     $case: fallback restart ends with the uninterrupted history"
    fi
  done
done

# A checkpoint of format 1 (written before the checksums): refused as such.
rm -rf fe1 && cp -a saved_fe1 fe1
printf '# yarn-impact checkpoint of the fe model: restart with yarn-impact --restart\ngeneration = 2\nslot = 1\nranks = 1\ntime = 8.5e-07\nstep = 41\ncompleted = 0\n' > fe1/checkpoint_fe.txt
run 1 --restart fe1.prm
if [ "$rc" -ne 1 ] || [ "$(wc -l < stderr)" -ne 1 ] ||
   ! grep -qF "yarn-impact: error: the checkpoint file 'fe1/checkpoint_fe.txt' cannot be used (it is of checkpoint format 1, written by an earlier version of yarn-impact without checksums; this version reads format 4 only)" stderr; then
  fail "format 1: exit $rc: $(head -c 300 stderr)"
fi

echo "$checked damaged restarts checked"
test_end "all checkpoint damage cases passed"
