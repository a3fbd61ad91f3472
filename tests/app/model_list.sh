#!/bin/bash
# Usage: model_list.sh YARN_IMPACT
# Several models in one run (`Model = fe, dem, hybrid`, doc/user-guide.md):
# - each model runs as it does alone: the FE and DEM histories equal those of
#   a `Model = both` run of the same problem byte for byte, and the columns
#   of comparison.csv they share with it too;
# - the comparison is right: each `v M - v DEM` column is the difference of
#   the two velocity columns, and the summary's largest |v_M - v_DEM| is the
#   largest over the rows it names;
# - physics: before any fibre breaks the hybrid (fibres near the nose, bars
#   on the continuum beyond) follows the full DEM within 0.02 m/s, ten times
#   closer than the FE with the paper's constants, whose mass per length is
#   6.4 % below the DEM's (doc/theory.md section 1.7);
# - a run stopped in its third model continues with --restart, the first
#   two taken from their checkpoints, to the same files;
# - a list naming a model twice, the fabric with others, or an unknown name
#   is refused with one line naming `Model`, exit 1.
exe=$1
. "$(dirname "$(readlink -f "$0")")/../lib.sh"
test_begin

# The small yarn of tests/dem/model_comparison.prm: 40 fibres, 4 mm, 2 us.
case_prm() { # directory, Model
  printf 'set Model = %s\nset Symmetry = half\n' "$2"
  printf 'subsection Yarn\n  set Length = 4e-3\n  set Number of fibres = 40\n'
  printf '  set Thickness semi-axis = 0.0182e-3\n  set Width semi-axis = 0.0844e-3\n'
  printf '  set Failure model = sudden\nend\n'
  printf 'subsection Projectile\n  set Mass = 0.991e-6\n  set Diameter = 1e-3\nend\n'
  printf 'subsection Time\n  set End time = 2e-6\nend\n'
  printf 'subsection Hybrid\n  set DEM half-length = 1.2e-3\n  set Overlap width = 0.4e-3\n'
  printf '  set Far field = fibre bars\n  set FE cells along the axis = 64\nend\n'
  printf 'subsection Output\n  set Directory = %s\n  set Snapshot interval = 0\n' "$1"
  printf '  set Verbosity = quiet\nend\n'
}
run() {
  mpirun -np 2 "$exe" "$@" > stdout 2> stderr
  rc=$?
}

case_prm both both > both.prm
run both.prm
[ "$rc" -eq 0 ] || fail "Model = both: exit $rc: $(head -c 300 stderr)"
case_prm three "fe, dem, hybrid" > three.prm
run three.prm
[ "$rc" -eq 0 ] || fail "Model = fe, dem, hybrid: exit $rc: $(head -c 300 stderr)"
for f in history_fe.csv history_dem.csv; do
  same_history both/$f three/$f || fail "$f: the three-model run's differs from Model = both's"
done
[ -s three/history_hybrid.csv ] || fail "no history_hybrid.csv"

/usr/bin/python3 - three both << 'END' || fail "comparison.csv or the summary (above)"
import csv, re, sys
three, both = (list(csv.DictReader(open(f"{d}/comparison.csv"))) for d in sys.argv[1:3])
bad = []
shared = [k for k in both[0] if k in three[0]]
if len(shared) != len(both[0]):
    bad.append(f"columns of Model = both missing: {set(both[0]) - set(shared)}")
if len(three) != len(both) or any(a[k] != b[k] for a, b in zip(three, both) for k in shared):
    bad.append("the FE and DEM columns differ from Model = both's")
for r in three:
    for m in ("FE", "hybrid"):
        dv = float(r[f"v {m} [m/s]"]) - float(r["v DEM [m/s]"])
        # 8 significant digits: 1e-5 m/s at 120 m/s.
        if abs(dv - float(r[f"v {m} - v DEM [m/s]"])) > 2e-5:
            bad.append(f"t = {r['t [us]']}: v {m} - v DEM is not the difference")
summary = open(f"{sys.argv[1]}/summary.txt").read()
largest = {}
for m in ("FE", "hybrid"):
    hit = re.search(rf"largest \|v_{m} - v_DEM\| up to ([0-9.]+) us: ([0-9.]+) m/s", summary)
    if not hit:
        bad.append(f"the summary gives no largest |v_{m} - v_DEM|")
        continue
    until, value = float(hit.group(1)), float(hit.group(2))
    got = max(abs(float(r[f"v {m} - v DEM [m/s]"])) for r in three
              if float(r["t [us]"]) <= until + 1e-9)
    if abs(got - value) > 1e-4:
        bad.append(f"{m}: the summary's {value} m/s, the rows' {got:.4f}")
    largest[m] = value
if "hybrid" in largest and "FE" in largest:
    print(f"largest |v - v_DEM| before any break: FE {largest['FE']:.4f}, hybrid {largest['hybrid']:.4f} m/s")
    if not (largest["hybrid"] <= 0.02 and largest["hybrid"] <= 0.1 * largest["FE"]):
        bad.append("the hybrid does not follow the DEM within 0.02 m/s and ten times closer than the FE")
for b in bad:
    print(b)
sys.exit(1 if bad else 0)
END

# Stopped in the hybrid, continued: the FE and DEM from their checkpoints.
case_prm stop "fe, dem, hybrid" > stop.prm
rows=$(($(wc -l < three/history_fe.csv) + $(wc -l < three/history_dem.csv) - 2))
YARN_IMPACT_SIGNAL_AT_ROW=$((rows + 10)) run stop.prm
if [ "$rc" -ne 6 ] || ! grep -q "the hybrid run was stopped" stderr; then
  fail "signal in the hybrid part: exit $rc: $(head -c 300 stderr)"
fi
run --restart stop.prm
[ "$rc" -eq 0 ] || fail "restart: exit $rc: $(head -c 300 stderr)"
for f in history_fe.csv history_dem.csv history_hybrid.csv comparison.csv; do
  same_history three/$f stop/$f || fail "$f after the restart differs"
done

# Refusals, before anything is written.
for model in "fe, fe" "both, dem" "fe, fabric" "fe, bogus"; do
  case_prm refused "$model" > refused.prm
  run refused.prm
  if [ "$rc" -ne 1 ] || ! head -1 stderr | grep -q "Model" || [ -e refused ]; then
    fail "Model = $model: expected exit 1, one line naming Model and no output; got $rc: $(head -c 300 stderr)"
  fi
done
test_end "model list: the three models as alone, compared, restarted; bad lists refused"
