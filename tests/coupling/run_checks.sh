# Sourced by the hybrid yarn's run tests (hybrid_run.sh, fibre_bars_run.sh,
# quarter_symmetry.sh, whole_yarn.sh) after tests/lib.sh (fail,
# same_history); they define $exe, $src and the functions that write their
# cases' parameter files.

# same_on_ranks PRM N...: run the case of PRM on each number of ranks (in
# rank folders ranksN); every history the same as on the first.
same_on_ranks() {
  local prm=$1 first=""
  shift
  for n in "$@"; do
    "$prm" "ranks$n" > "ranks$n.prm"
    mpirun -np "$n" "$exe" "ranks$n.prm" > "ranks$n.stdout" 2>&1
    rc=$?
    if [ $rc -ne 0 ]; then
      fail "$n rank(s): exit $rc (3 = a verification check failed)"
      tail -25 "ranks$n.stdout"
      continue
    fi
    if [ -z "$first" ]; then
      first=$n
    elif ! same_history "ranks$first/history_hybrid.csv" "ranks$n/history_hybrid.csv"; then
      fail "$n ranks: history_hybrid.csv differs from $first rank(s)'"
    fi
  done
}

# restart_same PRM ROW REFERENCE: stopped by SIGTERM at history row ROW and
# continued with --restart, the history byte for byte that of REFERENCE.
restart_same() {
  local prm=$1 row=$2 reference=$3 dir="stopped_$1"
  "$prm" "$dir" > "$dir.prm"
  YARN_IMPACT_SIGNAL_AT_ROW=$row "$exe" "$dir.prm" > "$dir.stdout" 2> "$dir.stderr"
  rc=$?
  [ $rc -eq 6 ] || fail "$prm, signal: expected exit 6, got $rc: $(head -c 300 "$dir.stderr")"
  "$exe" --restart "$dir.prm" > "$dir.restarted" 2> "$dir.restarted.stderr"
  rc=$?
  [ $rc -eq 0 ] || fail "$prm, restart: exit $rc: $(head -c 300 "$dir.restarted.stderr")"
  cmp -s "$reference" "$dir/history_hybrid.csv" ||
    fail "$prm, restart: history_hybrid.csv differs from the uninterrupted run's"
}

# refuse PRM NAME PATTERN TEXT: PRM's case with TEXT appended refused by
# --check with exit 1 and one line naming PATTERN.
refuse() {
  local prm=$1 name=$2 pattern=$3
  shift 3
  { "$prm" bad; printf '%b' "$*"; } > bad.prm
  "$exe" --check bad.prm > bad.stdout 2> bad.stderr
  rc=$?
  if [ $rc -ne 1 ] || [ "$(wc -l < bad.stderr)" -ne 1 ] || ! grep -q "$pattern" bad.stderr; then
    fail "$name: expected exit 1 and one line naming $pattern, got $rc: $(head -c 300 bad.stderr)"
  fi
}

# momentum_conserved DIR LABEL: the projectile's and the yarn's momentum
# along the impact direction conserved to round-off (momentum_balance.py).
momentum_conserved() {
  /usr/bin/python3 "$src/tests/coupling/momentum_balance.py" "$1" "$2" ||
    fail "$2: the momentum of the projectile and the yarn is not conserved"
}

# same_motion SYMMETRY WHAT (each run's momentum checked too): the case of case_prm SYMMETRY FAR DIR (which
# the test defines) run with half symmetry and with SYMMETRY, for each far
# field, their histories compared by compare_histories.py (the same motion
# within round-off); WHAT names the second model in the messages.
same_motion() {
  local other=$1 what=$2 far tag sym
  for far in continuum "fibre bars"; do
    tag=${far// /_}
    for sym in half "$other"; do
      case_prm "$sym" "$far" "${sym}_$tag" > "${sym}_$tag.prm"
      "$exe" "${sym}_$tag.prm" > "${sym}_$tag.stdout" 2>&1 ||
        { fail "$sym, $far: exit $?"; tail -5 "${sym}_$tag.stdout"; }
      momentum_conserved "${sym}_$tag" "$sym, $far"
    done
    /usr/bin/python3 "$src/tests/coupling/compare_histories.py" \
      "half_$tag/history_hybrid.csv" "${other}_$tag/history_hybrid.csv" \
      "$far: $what against half" ||
      fail "$far: the $what's history differs from the half model's"
  done
}
