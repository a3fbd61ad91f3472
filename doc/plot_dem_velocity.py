#!/usr/bin/python3
"""Plot the projectile velocity history of a DEM run.

    /usr/bin/python3 doc/plot_dem_velocity.py results-dem-km2/history_dem.csv doc/dem_velocity.png
"""
import csv
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt

rows = list(csv.DictReader(open(sys.argv[1])))
t = [float(r["t [us]"]) for r in rows]
v = [float(r["projectile velocity [m/s]"]) for r in rows]
failed = [float(r["failed elements"]) for r in rows]
fig, ax = plt.subplots(figsize=(6, 4))
ax.plot(t, v, label="DEM, 400 fibres")
first = next((ti for ti, f in zip(t, failed) if f > 0), None)
if first is not None:
    ax.axvline(first, color="r", ls="--", lw=0.8,
               label="first fibre break (%.2f us)" % first)
ax.set_xlabel("t [us]")
ax.set_ylabel("projectile velocity [m/s]")
ax.set_title("KM2 yarn, 120 m/s, DEM")
ax.grid(True, alpha=0.3)
ax.legend()
fig.tight_layout()
fig.savefig(sys.argv[2], dpi=120)
