#!/usr/bin/python3
"""Plots of a `Model = both` run, from its comparison.csv.

Usage: plot_comparison.py DIRECTORY

Writes DIRECTORY/velocity_comparison.png (the paper's Fig. 6: projectile
velocity of both models) and DIRECTORY/wave_fronts.png (longitudinal,
transverse and spreading front positions of both models against time).
"""
import csv
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def column(rows, name):
    return [float(r[name]) for r in rows]


def main():
    if len(sys.argv) != 2:
        sys.exit(__doc__)
    directory = sys.argv[1]
    with open(os.path.join(directory, "comparison.csv")) as f:
        rows = list(csv.DictReader(f))
    t = column(rows, "t [us]")

    fig, ax = plt.subplots(figsize=(6.4, 4.2))
    ax.plot(t, column(rows, "v FE [m/s]"), label="FE (hyperelastic continuum)")
    ax.plot(t, column(rows, "v DEM [m/s]"), label="DEM (fibres)")
    ax.set_xlabel("t [us]")
    ax.set_ylabel("projectile velocity [m/s]")
    ax.grid(True, alpha=0.3)
    ax.legend()
    fig.tight_layout()
    fig.savefig(os.path.join(directory, "velocity_comparison.png"), dpi=120)

    fig, ax = plt.subplots(figsize=(6.4, 4.2))
    for front, style in (("longitudinal", ":"), ("transverse", "-"),
                         ("spreading", "--")):
        for model, colour in (("FE", "C0"), ("DEM", "C1")):
            ax.plot(t, column(rows, f"{front} front {model} [mm]"), style,
                    color=colour, label=f"{front}, {model}")
    ax.set_xlabel("t [us]")
    ax.set_ylabel("front position from the impact point [mm]")
    ax.grid(True, alpha=0.3)
    ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(os.path.join(directory, "wave_fronts.png"), dpi=120)


if __name__ == "__main__":
    main()
