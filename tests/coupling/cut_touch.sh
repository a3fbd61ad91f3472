#!/bin/bash
# Usage: cut_touch.sh YARN_IMPACT SOURCE_DIR
# The hybrid yarn after its cut (doc/hybrid.md section 1): once every fibre
# is broken, the projectile may touch the FE part, whose contact then acts
# (with fibre bars: on the bar nodes, doc/hybrid.md section 3.4). A 5 mm yarn with fibre bars (DEM part a = 1.6 mm,
# overlap 0.4 mm) struck at 600 m/s: the bar waves come back from the
# clamps at 0.33 us, the bars break by the clamp and by the overlap, the
# yarn is cut at 0.60 us, and the free halves, dragged around the nose,
# meet it in the FE part at about 1.0 us (where the run stopped with
# exit 4 when any touch of the FE part stopped it). Physics and
# consistency checks, no recorded numbers:
# - the run reaches its end (exit 0), and its summary gives the first
#   touch of the FE part at a projectile displacement past the one at
#   the cut (the touch is tested only after the cut);
# - the energy balance, the bar nodes' contact with the projectile
#   included, within 0.05 % of the initial energy to the end (the run's
#   own check): a contact force on the projectile without its penalty
#   energy in the balance would break it;
# - each part's energy balance (the FE part with its bars, the DEM part
#   with the projectile; the history's per-part columns, doc/hybrid.md
#   2.3) within 0.05 %, the two summing to the run's to 1e-6 %, and the
#   projectile's work on the FE part positive after the touch;
# - stopped by SIGTERM after the touch and continued with --restart: the
#   same history, byte for byte (the touch is in the checkpoint).
exe=$1
src=$2
. "$(dirname "$(readlink -f "$0")")/../lib.sh"
test_begin
. "$src/tests/coupling/run_checks.sh"

touch_prm() {
  cat "$src/prm/hybrid/km2_120ms_hybrid.prm"
  printf 'subsection Yarn\n  set Length = 5e-3\nend\n'
  printf 'subsection Projectile\n  set Initial velocity = 600\nend\n'
  printf 'subsection Hybrid\n  set DEM half-length = 1.6e-3\n'
  printf '  set Overlap width = 0.4e-3\n  set Far field = fibre bars\nend\n'
  printf 'subsection Time\n  set End time = 1.3e-6\nend\n'
  printf 'subsection Output\n  set Directory = %s\n  set Snapshot interval = 0\n' "$1"
  printf '  set History interval = 0.02e-6\nend\n'
  printf 'subsection Verification\n  set Checks = energy\n'
  printf '  set Energy tolerance = 5e-4\nend\n'
}

same_on_ranks touch_prm 1
grep -E "energy error|cut through|Hybrid contact" ranks1/summary.txt
/usr/bin/python3 - ranks1 << 'END' || fail "the touch of the FE part"
import csv, re, sys
d = sys.argv[1]
text = open(d + "/summary.txt").read()
touch = re.search(r"Hybrid contact: the projectile touched the FE part after "
                  r"the yarn was cut, at a projectile displacement of "
                  r"([\d.]+) mm", text)
cut = re.search(r"yarn cut through:\s+([\d.]+) us", text)
if not touch or not cut:
    sys.exit("no touch of the FE part or no cut in the summary")
rows = list(csv.DictReader(open(d + "/history_hybrid.csv")))
t_cut = float(cut.group(1))
at_cut = min(rows, key=lambda r: abs(float(r["t [us]"]) - t_cut))
u_cut = float(at_cut["projectile displacement [mm]"])
u_touch = float(touch.group(1))
u_end = float(rows[-1]["projectile displacement [mm]"])
print(f"cut at {t_cut} us (projectile at {u_cut:.4f} mm), first touch of "
      f"the FE part at {u_touch:.4f} mm, end at {u_end:.4f} mm")
if not u_cut < u_touch < u_end:
    sys.exit("the touch is not between the cut and the end")
# Each part's energy balance (doc/hybrid.md 2.3), in % of the initial
# energy: the two must sum to the run's balance (the columns are the
# totals' terms, split) and each stay within the run's 0.05 %.
r0 = rows[0]
def value(r, k):
    return float(r[k + " [mJ]"])
e0 = sum(value(r0, k) for k in ("projectile kinetic energy",
                                "FE part energy", "DEM part energy"))
worst = [0., 0., 0.]
for r in rows:
    w_c = value(r, "coupling work on the DEM part")
    w_p = value(r, "projectile work on the FE part")
    fe = value(r, "FE part energy") - value(r0, "FE part energy") - w_p + w_c
    dem = (value(r, "DEM part energy") - value(r0, "DEM part energy") +
           value(r, "projectile kinetic energy") -
           value(r0, "projectile kinetic energy") + w_p - w_c)
    fe, dem = 100. * fe / e0, 100. * dem / e0
    total = float(r["energy error [%]"])
    worst = [max(worst[0], abs(fe)), max(worst[1], abs(dem)),
             max(worst[2], abs(fe + dem - total))]
print(f"largest energy error of the FE part {worst[0]:.4f} %, of the DEM "
      f"part {worst[1]:.4f} %, their sum off the run's by {worst[2]:.1e} %; "
      f"projectile work on the FE part {w_p:.4f} mJ")
if worst[2] > 1e-6:
    sys.exit("the parts' energy balances do not sum to the run's")
if max(worst[:2]) > 0.05:
    sys.exit("a part's energy balance is off by more than 0.05 %")
if w_p <= 0.:
    sys.exit("no work of the projectile on the FE part after the touch")
END
# Row 60 (1.2 us) lies after the touch (about 1.0 us).
restart_same touch_prm 60 ranks1/history_hybrid.csv

test_end "the hybrid's FE part touched after the cut: energy balance, restart"
