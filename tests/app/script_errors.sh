#!/bin/bash
# Usage: script_errors.sh SOURCE_DIR CHARMETANT_CURVES
# The scripts behave like the executable (issue 28, class 7): bad
# arguments and files give one line "SCRIPT: error: ..." and a non-zero
# exit, never a traceback (identify_charmetant.py: missing, folder, binary,
# malformed, non-numeric, non-finite, empty CSVs, bad --expect; and
# ballistic_sweep.py: bad --velocities, --models, --build, --out, --np;
# plot_fabric.py: missing, foreign and empty histories). The fabric
# sweep's V50 table reports a perforation below its bracket.
# The sweep, on a fake build (a script standing in for yarn-impact that
# writes a history and a summary), keys its runs on the exact velocity (120
# and 120.4 m/s are two runs), reuses them when nothing changed, and runs
# them again when the executable or the base prm changes.
src=$1
curves=$2
. "$(dirname "$(readlink -f "$0")")/../lib.sh"
test_begin
py=/usr/bin/python3
identify="$src/scripts/identify_charmetant.py"
sweep="$src/scripts/ballistic_sweep.py"

# refused NAME CODE TEXT COMMAND...: exit CODE, one line on stderr starting
# with "SCRIPT: error:" and holding TEXT, no traceback.
refused() {
  local name=$1 code=$2 text=$3
  shift 3
  "$@" > stdout 2> stderr
  local rc=$?
  local script
  script=$(basename "$2")
  if [ $rc -ne "$code" ]; then
    fail "$name: exit $rc (expected $code): $(head -c 300 stderr)"
  elif grep -q Traceback stderr stdout; then
    fail "$name: a traceback: $(tail -2 stderr)"
  elif [ "$(wc -l < stderr)" -ne 1 ] || ! grep -q "^$script: error: " stderr; then
    fail "$name: not one '$script: error:' line: $(head -c 300 stderr)"
  elif ! grep -qF -- "$text" stderr; then
    fail "$name: expected '$text', got: $(cat stderr)"
  else
    echo "ok     $name: $(cat stderr)"
  fi
}

# identify_charmetant.py
"$curves" 80077.19e6 1055.82e6 2.205 649.75e6 > /dev/null
good="elementary_tension.csv elementary_compaction.csv elementary_distortion.csv"
# shellcheck disable=SC2086
$py "$identify" --expect 80077.19e6,1055.82e6,2.205,649.75e6 $good > stdout 2> stderr ||
  fail "identify on good curves: $(tail -3 stderr)"
refused "identify: missing CSV" 1 "cannot read missing.csv: No such file" $py "$identify" missing.csv
mkdir folder.csv
refused "identify: a folder" 1 "folder.csv is a folder" $py "$identify" folder.csv
head -c 3000 /bin/sh > binary.csv
refused "identify: binary CSV" 1 "binary.csv is not a text CSV" $py "$identify" binary.csv
printf '\x01\x00\x02binary\n' > nul.csv
refused "identify: NUL bytes" 1 "nul.csv is not a text CSV" $py "$identify" nul.csv
: > empty.csv
refused "identify: empty CSV" 1 "no rows in empty.csv" $py "$identify" empty.csv
printf 'a,b\n1,2\n' > other.csv
refused "identify: another CSV" 1 "other.csv is not a CSV of an elementary test (its 'loading' column is missing" $py "$identify" other.csv
head -1 elementary_tension.csv | cut -d, -f1-3 > cut.csv
sed -n 2p elementary_tension.csv | cut -d, -f1-3 >> cut.csv
refused "identify: columns missing" 1 "cut.csv lacks the column(s)" $py "$identify" cut.csv
awk -F, -v OFS=, 'NR == 1 { for (i = 1; i <= NF; i++) if ($i == "F_xx") c = i } NR == 3 { $c = "abc" } { print }' elementary_tension.csv > text.csv
refused "identify: a value not a number" 1 "text.csv, row 3: F_xx = 'abc' is not a number" $py "$identify" text.csv
awk -F, -v OFS=, 'NR == 1 { for (i = 1; i <= NF; i++) if ($i == "tau_xx") c = i } NR == 4 { $c = "nan" } { print }' elementary_tension.csv > nan.csv
refused "identify: a NaN" 1 "nan.csv, row 4: tau_xx = nan is not finite" $py "$identify" nan.csv
refused "identify: bad --expect" 2 "'1,2' is not four finite non-zero numbers" $py "$identify" --expect 1,2 elementary_tension.csv
refused "identify: bad --tolerance" 2 "'-1' must be positive" $py "$identify" --tolerance=-1 elementary_tension.csv
refused "identify: unknown option" 2 "unrecognized arguments" $py "$identify" --frobnicate elementary_tension.csv

# ballistic_sweep.py with a fake build.
mkdir fake
cat > fake/yarn-impact <<'SH'
#!/bin/bash
# Stands in for yarn-impact: the run's velocity as its residual velocity.
prm=$1
dir=$(sed -n 's/^ *set Directory = //p' "$prm")
v=$(sed -n 's/^ *set Initial velocity = //p' "$prm")
mkdir -p "$dir"
printf 't [us],projectile velocity [m/s],projectile kinetic energy [mJ],failed elements\n0,%s,10,0\n1,%s,9,1\n' "$v" "$v" > "$dir/history_fe.csv"
echo "yarn cut through: 0.5 us" > "$dir/summary.txt"
echo "$v" >> "$(dirname "$0")/runs.txt"
SH
chmod +x fake/yarn-impact
sweep_runs() { # the number of runs a sweep made
  rm -f fake/runs.txt
  $py "$sweep" --build fake --out sw --models charmetant --velocities 120,120.4 \
    --no-bisection > stdout 2> stderr || fail "sweep: $(tail -3 stderr)"
  [ -f fake/runs.txt ] && wc -l < fake/runs.txt || echo 0
}
n=$(sweep_runs)
[ "$n" -eq 2 ] && echo "ok     sweep: 120 and 120.4 m/s are two runs" || fail "sweep: $n runs for 120 and 120.4 m/s"
if ! grep -q "^charmetant,120,120.0000," sw/ballistics.csv || ! grep -q "^charmetant,120.4,120.4000," sw/ballistics.csv; then
  fail "sweep: each velocity has its own result: $(cat sw/ballistics.csv)"
fi
n=$(sweep_runs)
[ "$n" -eq 0 ] && echo "ok     sweep: both reused when nothing changed" || fail "sweep: $n runs again with nothing changed"
echo "# another build" >> fake/yarn-impact
n=$(sweep_runs)
[ "$n" -eq 2 ] && echo "ok     sweep: both run again after the executable changed" || fail "sweep: $n runs after the executable changed"
rm sw/charmetant_120.4ms_4e-05s.key
n=$(sweep_runs)
[ "$n" -eq 1 ] && echo "ok     sweep: a run without its key file is run again" || fail "sweep: $n runs with one key file gone"

refused "sweep: bad --velocities" 2 "'12o' is not a velocity" $py "$sweep" --build fake --out sw --velocities 100,12o
refused "sweep: negative velocity" 2 "velocity '-5' must be a finite positive number" $py "$sweep" --build fake --out sw --velocities=-5
refused "sweep: nan velocity" 2 "velocity 'nan' must be a finite positive" $py "$sweep" --build fake --out sw --velocities nan
refused "sweep: empty velocity" 2 "'' is not a velocity" $py "$sweep" --build fake --out sw --velocities 100,
refused "sweep: bad --models" 2 "unknown model 'fem'" $py "$sweep" --build fake --out sw --models fem
refused "sweep: model twice" 2 "a model is named twice" $py "$sweep" --build fake --out sw --models dem,dem
refused "sweep: bad --np" 2 "'0' must be positive" $py "$sweep" --build fake --out sw --np 0
refused "sweep: missing --build" 1 "--build nowhere is not a folder" $py "$sweep" --build nowhere --out sw
mkdir empty_build
refused "sweep: --build without yarn-impact" 1 "holds no executable yarn-impact" $py "$sweep" --build empty_build --out sw
touch a_file
refused "sweep: --out is a file" 1 "exists and is not a folder" $py "$sweep" --build fake --out a_file
refused "sweep: --out under a file" 1 "cannot be created" $py "$sweep" --build fake --out a_file/sub

# plot_fabric.py: a fabric history's plots; refused files.
plot_fabric="$src/scripts/plot_fabric.py"
refused "plot_fabric: missing history" 1 "cannot read missing.csv" $py "$plot_fabric" missing.csv pf
refused "plot_fabric: not a fabric history" 1 "is not a fabric history: no column" $py "$plot_fabric" sw/ballistics.csv pf
refused "plot_fabric: empty history" 1 "empty.csv has no rows" $py "$plot_fabric" empty.csv pf

# The fabric sweep's V50 (fabric_ballistics.py) reports a perforation that
# is not monotonic in the impact velocity: a run perforating below the
# highest velocity that does not is printed and written to fabric_v50.csv;
# none when it is monotonic.
$py - "$src/scripts" > fabric_v50.txt 2>&1 <<'PY' || fail "fabric V50 report: $(tail -3 fabric_v50.txt)"
import csv, os, sys
sys.path.insert(0, sys.argv[1])
import fabric_ballistics as fb
def runs(perforated):
    return [{"velocity": v, "residual": 0.5 * v if p else 0.6 * v,
             "broken": 4 if p else 0, "primary": 4, "perforated": p,
             "absorbed": 1.0, "broken_at": 4.0 if p else None, "end": 5.0,
             "wall": None} for v, p in perforated]
for name, perforated, bracket, expect in (
        ("monotonic", [(200, False), (250, False), (300, True)],
         (250, 300), ""),
        ("not monotonic", [(200, False), (250, True), (290, False),
                           (300, True)], (290, 300), "250")):
    os.makedirs(name, exist_ok=True)
    fb.write(name, runs(perforated), bracket[1], bracket, None, None)
    rows = {r["quantity"]: r["value"] for r in
            csv.DictReader(open(os.path.join(name, "fabric_v50.csv")))}
    got = rows.get("perforated below the bracket [m/s]")
    print("%s: perforated below the bracket %r (expected %r): %s"
          % (name, got, expect, "yes" if got == expect else "no"))
PY
cat fabric_v50.txt
if grep -q ": no$" fabric_v50.txt || [ "$(grep -c ': yes$' fabric_v50.txt)" -ne 2 ]; then
  fail "fabric V50 report: $(cat fabric_v50.txt)"
elif ! grep -q "perforation is not monotonic in the impact velocity: perforated at 250 m/s, below 290 m/s" fabric_v50.txt; then
  fail "fabric V50 report: no line for the non-monotonic sweep"
elif [ "$(grep -c 'not monotonic in the impact' fabric_v50.txt)" -ne 1 ]; then
  fail "fabric V50 report: a line for the monotonic sweep too"
else
  echo "ok     fabric V50: a perforation below the bracket reported, none when monotonic"
fi

test_end "all script cases passed"
