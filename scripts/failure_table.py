#!/usr/bin/env python3
"""Compare FE runs with a DEM history: the figures of the failure targets.

Usage: failure_table.py DEM_HISTORY_CSV FE_RUN_DIR [FE_RUN_DIR ...]

For each FE run directory (with history_fe.csv and summary.txt) prints one
Markdown table row: first failure and cut-through (from the summary), the
velocity at the end, the largest |v_FE - v_DEM| up to the DEM history's
last time (the DEM interpolated on the FE times) and where it is, the
largest energy error, and the eroded cells. The DEM's own first break (the
first history row with a broken truss) and cut-through (the first row after
it where the contact force is below 2 % of its peak) head the table.
"""

import os
import sys

import numpy as np


def read(path):
    with open(path) as f:
        header = f.readline().rstrip("\n").split(",")
    data = np.genfromtxt(path, delimiter=",", skip_header=1, ndmin=2)
    return {h: data[:, i] for i, h in enumerate(header)}


def summary_line(path, key):
    with open(path) as f:
        for line in f:
            if line.strip().startswith(key):
                return line.split(":", 1)[1].strip()
    return "?"


def main():
    dem = read(sys.argv[1])
    t_d = dem["t [us]"]
    v_d = dem["projectile velocity [m/s]"]
    F_d = dem["contact force [N]"]
    k1 = int(np.argmax(dem["failed elements"] > 0))
    peak = F_d[k1:].max()
    k2 = k1 + int(np.argmax(F_d[k1:] < 0.02 * peak))
    print("DEM: first break %.2f us, cut through %.2f us, v = %.2f m/s at "
          "%.2f us (last row)" % (t_d[k1], t_d[k2], v_d[-1], t_d[-1]))
    print("| run | first failure [us] | cut through [us] | v(end) [m/s] "
          "| max abs(v_FE - v_DEM) [m/s] (at t [us]) | largest energy error "
          "[%] | eroded cells |")
    print("|---|---|---|---|---|---|---|")
    for run in sys.argv[2:]:
        fe = read(os.path.join(run, "history_fe.csv"))
        t = fe["t [us]"]
        v = fe["projectile velocity [m/s]"]
        keep = t <= t_d[-1] + 1e-9
        dv = np.abs(v[keep] - np.interp(t[keep], t_d, v_d))
        k = int(np.argmax(dv))
        s = os.path.join(run, "summary.txt")
        print("| %s | %s | %s | %.2f (%.1f us) | %.2f (%.1f) | %.3f | %s |" % (
            os.path.basename(run.rstrip("/")),
            summary_line(s, "first failure").replace(" us", ""),
            summary_line(s, "yarn cut through").replace(" us", ""),
            v[-1], t[-1], dv.max(), t[keep][k],
            np.abs(fe["energy error [%]"]).max(),
            summary_line(s, "eroded cells")))


if __name__ == "__main__":
    main()
