#!/bin/bash
# Usage: ballistic_sweep.sh BUILD_DIR SOURCE_DIR OUT [record]
# A quick FE sweep of scripts/ballistic_sweep.py (Charmetant law, 600, 800
# and 1000 m/s, above the FE's critical velocity of about 400 m/s) into
# OUT/sweep.
# Physics checks (app/ballistic_sweep, which runs the sweep): the yarn
# breaks at once at every velocity (cut through before the longitudinal
# wave reflected at the clamps is back, 3.31 us), and the residual velocity
# increases with the impact velocity, staying below it.
# Record (record/app/ballistic_sweep, with "record": reads the sweep that
# app/ballistic_sweep left in OUT, runs nothing): the residual velocities
# within a declared 1 m/s of 590.91, 788.67, 988.48 m/s (591.84, 790.36,
# 991.92 m/s before the FE projectile friction became 0.2, the DEM's, and
# the stable step used the cell altitudes; the two together take 0.9 to
# 3.4 m/s more).
build=$1
src=$2
out=$3
mode=${4:-physics}
if [ "$mode" = physics ]; then
  rm -rf "$out"
  mkdir -p "$out"
  /usr/bin/python3 "$src/scripts/ballistic_sweep.py" --build "$build" \
    --out "$out/sweep" --models charmetant --velocities 600,800,1000 \
    --no-bisection > "$out/log" 2>&1 || {
    cat "$out/log"
    echo "FAILED: the sweep failed"
    exit 1
  }
elif [ ! -f "$out/sweep/ballistics.csv" ]; then
  echo "FAILED no sweep in $out (app/ballistic_sweep did not run)"
  exit 1
fi
/usr/bin/python3 - "$out/sweep/ballistics.csv" "$mode" <<'PY'
import csv, sys
rows = list(csv.DictReader(open(sys.argv[1])))
v = [float(r["impact velocity [m/s]"]) for r in rows]
vr = [float(r["residual velocity [m/s]"]) for r in rows]
once = [r["breaks at once"] == "1" for r in rows]
failures = 0
def check(name, ok):
    global failures
    print(("ok     " if ok else "FAILED ") + name)
    failures += not ok
check("3 runs: %s" % v, v == [600., 800., 1000.])
if sys.argv[2] == "record":
    for w, r, ref in zip(v, vr, [590.91, 788.67, 988.48]):
        check("record: %g m/s keeps %.2f m/s (recorded %.2f, within 1 m/s)"
              % (w, r, ref), abs(r - ref) < 1.)
    sys.exit(failures > 0)
check("the yarn breaks at once at each velocity: %s" % once, all(once))
check("residual velocity increases with the impact velocity",
      all(b > a for a, b in zip(vr, vr[1:])))
check("residual velocity below the impact velocity",
      all(r < w for r, w in zip(vr, v)))
for png in ["residual_velocity", "energy_absorbed", "first_break", "cut_through"]:
    import os
    check("plot %s.png written" % png,
          os.path.getsize(os.path.join(os.path.dirname(sys.argv[1]), png + ".png")) > 1000)
sys.exit(failures > 0)
PY
