#!/usr/bin/python3
"""Plot histories written by yarn-impact.

Usage: plot_history.py OUTPUT.png COLUMN HISTORY.csv[:LABEL] [HISTORY.csv[:LABEL] ...]

COLUMN is a column name of the history CSV (for example
"projectile velocity [m/s]"); time in us is on the horizontal axis.
"""
import csv
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def main():
    if len(sys.argv) < 4:
        sys.exit(__doc__)
    output, column = sys.argv[1], sys.argv[2]
    fig, ax = plt.subplots(figsize=(6.4, 4.2))
    for spec in sys.argv[3:]:
        path, _, label = spec.partition(":")
        with open(path) as f:
            rows = list(csv.DictReader(f))
        if not rows or column not in rows[0]:
            sys.exit(f"{path}: no column '{column}'")
        t = [float(r["t [us]"]) for r in rows]
        y = [float(r[column]) for r in rows]
        ax.plot(t, y, label=label or path)
    ax.set_xlabel("t [us]")
    ax.set_ylabel(column)
    ax.grid(True, alpha=0.3)
    ax.legend()
    fig.tight_layout()
    fig.savefig(output, dpi=120)


if __name__ == "__main__":
    main()
