#!/bin/bash
# Usage: guards.sh YARN_IMPACT SOURCE_DIR
# Guards for every mode (doc/user-guide.md, exit codes):
# - a non-finite checked quantity stops the run with one line and exit 4,
#   never a row of nan: Projectile/Mass = 1e308 makes the projectile's
#   kinetic energy infinite and the energy balance error NaN, in the FE,
#   DEM and hybrid models;
# - an elementary test too large for the machine (Elementary
#   test/Cross-sections) is refused by --check and by the run with one line
#   naming the parameter, exit 1 and nothing written; one too large for an
#   MPI message the same way;
# - a second ballistic sweep on the same --out (on a fake build whose
#   yarn-impact sleeps) and a second identification writing into a folder
#   held by another are refused with one line naming the folder and the
#   holder's PID, exit 1.
exe=$1
src=$2
py=/usr/bin/python3
. "$(dirname "$(readlink -f "$0")")/../lib.sh"
test_begin cleanup
pids=()
cleanup() {
  for p in "${pids[@]}"; do kill -KILL "$p" 2> /dev/null; done
}

# refused NAME CODE PATTERN CMD...: CMD exits CODE with PATTERN on the one
# line of its stderr.
refused() {
  local name=$1 code=$2 pattern=$3
  shift 3
  "$@" > stdout 2> stderr
  local rc=$?
  if [ $rc -ne "$code" ] || [ "$(grep -c . stderr)" -ne 1 ] ||
    ! grep -qE "$pattern" stderr; then
    fail "$name: expected exit $code and one line matching '$pattern', got $rc: $(head -c 400 stderr)"
  fi
}

# 1. Non-finite energies.
for model in fe dem hybrid; do
  case $model in
    fe) base=$src/prm/km2_120ms_fe.prm ;;
    dem) base=$src/prm/dem_quick.prm ;;
    hybrid) base=$src/prm/hybrid/km2_120ms_hybrid.prm ;;
  esac
  {
    grep -v 'Directory\|Verbosity\|Snapshot interval' "$base"
    printf 'subsection Projectile\n  set Mass = 1e308\nend\n'
    printf 'subsection Output\n  set Directory = nan_%s\n  set Snapshot interval = 0\n  set Verbosity = quiet\nend\n' "$model"
  } > "nan_$model.prm"
  refused "NaN energy, $model" 4 "^yarn-impact: error: numerical failure in the $model model at step 0, t = 0 us: the projectile's kinetic energy, its work or the energy balance error is not a finite number" \
    "$exe" "nan_$model.prm"
  if grep -qi nan "nan_$model/history_$model.csv" 2> /dev/null; then
    fail "NaN energy, $model: a row of nan was written"
  fi
done

# 2. Elementary tests too large.
for cs in 100000 2000000000; do
  sed -e "s|set Directory .*|set Directory = big_$cs|" \
    -e "s|set Cross-sections .*|set Cross-sections = $cs|" \
    "$src/prm/elementary/compaction.prm" > "big_$cs.prm"
  pattern="^yarn-impact: error: Parameter 'Elementary test/Cross-sections' makes the elementary (set-up need about [0-9.e+]+ GB .* more than the [0-9.e+]+ GB of memory available here|test's segment [0-9.e+]+ spheres, more than one MPI message can exchange)"
  refused "elementary, $cs cross-sections, --check" 1 "$pattern" "$exe" --check "big_$cs.prm"
  refused "elementary, $cs cross-sections, run" 1 "$pattern" "$exe" "big_$cs.prm"
  [ ! -e "big_$cs" ] || fail "elementary, $cs cross-sections: the run wrote $(ls "big_$cs")"
done

# 3. Scripts hold their output folders.
mkdir fake
printf '#!/bin/sh\nsleep 20\n' > fake/yarn-impact
chmod +x fake/yarn-impact
$py "$src/scripts/ballistic_sweep.py" --build fake --out sweep \
  --velocities 120 --models charmetant --no-bisection > first.out 2>&1 &
first=$!
pids+=($first)
for _ in $(seq 200); do
  [ -s sweep/.sweep.lock ] && break
  sleep 0.05
done
refused "second sweep" 1 "^ballistic_sweep.py: error: --out $work/sweep is in use by another sweep: process $first on host $(hostname) holds its lock $work/sweep/.sweep.lock; wait for it to end, or choose another --out$" \
  $py "$src/scripts/ballistic_sweep.py" --build fake --out sweep --velocities 120 --models charmetant --no-bisection
children=$(pgrep -P $first)
kill -TERM $first $children 2> /dev/null
wait $first 2> /dev/null

mkdir ident
echo "$$ $(hostname)" > ident/.identify.lock
$py -c 'import fcntl, sys, time
f = open(sys.argv[1], "a")
fcntl.flock(f, fcntl.LOCK_EX)
time.sleep(20)' ident/.identify.lock > /dev/null 2>&1 &
holder=$!
pids+=($holder)
sleep 0.3
refused "second identification" 1 "^identify_charmetant.py: error: the folder of --prm $work/ident is in use by another identification: process $$ on host $(hostname) holds its lock $work/ident/.identify.lock" \
  $py "$src/scripts/identify_charmetant.py" any.csv --prm ident/x.prm
kill -TERM $holder 2> /dev/null
wait $holder 2> /dev/null

test_end "guards: non-finite energies stopped, too-large elementary tests refused, second sweep and identification refused"
