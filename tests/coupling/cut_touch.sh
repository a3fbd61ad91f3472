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
END
# Row 60 (1.2 us) lies after the touch (about 1.0 us).
restart_same touch_prm 60 ranks1/history_hybrid.csv

test_end "the hybrid's FE part touched after the cut: energy balance, restart"
