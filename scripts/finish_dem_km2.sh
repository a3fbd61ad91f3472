#!/bin/bash
# After `mpirun -np 2 build-dem/yarn-impact prm/km2_120ms_dem.prm` has run to
# 40 us (log in $1, default /tmp/dem_km2.log): print the numbers doc/dem.md
# asks for, plot the velocity history and render the pictures.
#   scripts/finish_dem_km2.sh [LOG]
set -e
log=${1:-/tmp/dem_km2.log}
dir=results-dem-km2
csv=$dir/history_dem.csv
grep -E "Elapsed \(wall|Maximum resident" "$log" || true
/usr/bin/python3 - "$csv" <<'PY'
import csv, sys
rows = list(csv.DictReader(open(sys.argv[1])))
t = [float(r["t [us]"]) for r in rows]
v = [float(r["projectile velocity [m/s]"]) for r in rows]
f = [float(r["failed elements"]) for r in rows]
first = next((ti for ti, fi in zip(t, f) if fi > 0), None)
print("first break at", first, "us; last row t =", t[-1], "us, broken", f[-1])
for T in (10, 20, 25, 30, 40):
    k = min(range(len(t)), key=lambda i: abs(t[i] - T))
    print(f"v({t[k]:.2f} us) = {v[k]:.2f} m/s, broken {f[k]:.0f}, energy error {rows[k]['energy error [%]']} %")
PY
/usr/bin/python3 doc/plot_dem_velocity.py "$csv" doc/dem_velocity.png
xvfb-run -a pvbatch scripts/render_yarn.py $dir/dem.pvd doc/figures/dem_side \
  axial_strain 0 10 25 40 --view side --y-scale 5
xvfb-run -a pvbatch scripts/render_yarn.py $dir/dem.pvd doc/figures/dem_top \
  axial_strain 10 --view top
