#!/usr/bin/python3
"""Projectile velocity of the FE failure laws against the DEM, to 40 us.

Usage: plot_failure.py OUT.png TITLE DEM_HISTORY FE_SUDDEN_DIR FE_PROGRESSIVE_DIR

Draws the three velocity histories (the DEM's held at its last value after
its history ends: the projectile is free once the yarn is cut), marks each
model's first failure and cut-through (from the FE summaries; for the DEM
the first history row with a broken truss, and the first row after it
where the contact force is below 2 % of its peak), and writes OUT.png.
"""

import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402


def read(path):
    with open(path) as f:
        header = f.readline().rstrip("\n").split(",")
    data = np.genfromtxt(path, delimiter=",", skip_header=1, ndmin=2)
    return {h: data[:, i] for i, h in enumerate(header)}


def summary_time(run, key):
    with open(os.path.join(run, "summary.txt")) as f:
        for line in f:
            if line.strip().startswith(key):
                try:
                    return float(line.split(":", 1)[1].split()[0])
                except ValueError:
                    return None
    return None


def main():
    out, title, dem_path, sudden, progressive = sys.argv[1:6]
    dem = read(dem_path)
    t_d, v_d, F_d = (dem["t [us]"], dem["projectile velocity [m/s]"],
                     dem["contact force [N]"])
    k1 = int(np.argmax(dem["failed elements"] > 0))
    k2 = k1 + int(np.argmax(F_d[k1:] < 0.02 * F_d[k1:].max()))
    fig, ax = plt.subplots(figsize=(7, 4.5))
    ax.plot(t_d, v_d, "k-", lw=1.8, label="DEM")
    if t_d[-1] < 40:
        ax.plot([t_d[-1], 40], [v_d[-1], v_d[-1]], "k:", lw=1.2,
                label="DEM, held after its history ends (free projectile)")
    ax.axvline(t_d[k1], color="k", lw=0.6, ls="--")
    ax.axvline(t_d[k2], color="k", lw=0.6, ls="-.")
    for run, name, colour in ((sudden, "FE, sudden (paper's criterion)",
                               "tab:red"),
                              (progressive, "FE, progressive", "tab:blue")):
        fe = read(os.path.join(run, "history_fe.csv"))
        ax.plot(fe["t [us]"], fe["projectile velocity [m/s]"], color=colour,
                lw=1.4, label=name)
        for key, style in (("first failure", "--"),
                           ("yarn cut through", "-.")):
            t = summary_time(run, key)
            if t is not None:
                ax.axvline(t, color=colour, lw=0.6, ls=style)
    ax.set_xlim(0, 40)
    ax.set_xlabel("t [us]")
    ax.set_ylabel("projectile velocity [m/s]")
    ax.set_title(title + "\n(dashed: first failure, dash-dot: cut-through)",
                 fontsize=10)
    ax.grid(alpha=0.3)
    ax.legend(fontsize=8, loc="lower left")
    fig.tight_layout()
    fig.savefig(out, dpi=130)


if __name__ == "__main__":
    main()
