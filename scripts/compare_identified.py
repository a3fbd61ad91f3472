#!/usr/bin/python3
"""FE runs against the DEM on the paper's impact: projectile velocity, section
width at the impact point and spreading front against time
(doc/identification.md section 5).

  compare_identified.py DEM.csv OUT.png LABEL=history_fe.csv [LABEL=...]

DEM.csv is either a `comparison.csv` of a `Model = both` run (its DEM
columns are used) or a DEM `history_dem.csv`. Prints, at a few instants,
each FE run's velocity difference to the DEM and both widths relative to
their initial value, and the largest velocity difference before the first
failure of either model. The width is the second-moment width
4 sqrt(<z^2>) where the files have it (doc/identification.md section 2.4),
else each model's own extent of the section.
"""
import csv
import sys

import numpy as np


def load(path):
    with open(path) as f:
        rows = list(csv.DictReader(f))
    keys = rows[0].keys()

    def col(*names):
        for n in names:
            if n in keys:
                return np.array([float(r[n]) for r in rows])
        raise KeyError("none of %s in %s" % (names, path))

    out = {"t": col("t [us]")}
    # The second-moment width (the same definition in both models) where
    # the file has it, else the extent of the nodes or fibre centres.
    if "v DEM [m/s]" in keys:
        out["v"] = col("v DEM [m/s]")
        out["width"] = col("RMS width at impact DEM [mm]",
                           "width at impact DEM [mm]")
        out["spreading"] = col("spreading front DEM [mm]")
        out["failed"] = np.zeros_like(out["t"])
    else:
        out["v"] = col("projectile velocity [m/s]")
        out["width"] = col("section RMS width at impact [mm]",
                           "section width at impact [mm]")
        out["spreading"] = col("spreading front [mm]")
        out["failed"] = col("failed elements", "broken trusses")
    return out


def main():
    if len(sys.argv) < 4:
        sys.exit(__doc__)
    dem = load(sys.argv[1])
    png = sys.argv[2]
    runs = []
    for arg in sys.argv[3:]:
        label, path = arg.split("=", 1)
        runs.append((label, load(path)))

    instants = [5.0, 10.0, 15.0, 20.0, 25.0, 28.0]
    w0_dem = dem["width"][0]
    print("%-28s %s" % ("t [us]", " ".join("%8.1f" % t for t in instants)))
    print("%-28s %s" % ("DEM v [m/s]", " ".join(
        "%8.2f" % np.interp(t, dem["t"], dem["v"]) for t in instants)))
    print("%-28s %s" % ("DEM width / initial", " ".join(
        "%8.3f" % (np.interp(t, dem["t"], dem["width"]) / w0_dem)
        for t in instants)))
    print("%-28s %s" % ("DEM spreading front [mm]", " ".join(
        "%8.2f" % np.interp(t, dem["t"], dem["spreading"])
        for t in instants)))
    for label, r in runs:
        w0 = r["width"][0]
        print("%-28s %s" % (label + " v - v_DEM", " ".join(
            "%8.2f" % (np.interp(t, r["t"], r["v"]) -
                       np.interp(t, dem["t"], dem["v"])) for t in instants)))
        print("%-28s %s" % (label + " width / initial", " ".join(
            "%8.3f" % (np.interp(t, r["t"], r["width"]) / w0)
            for t in instants)))
        print("%-28s %s" % (label + " spreading [mm]", " ".join(
            "%8.2f" % np.interp(t, r["t"], r["spreading"])
            for t in instants)))
        failed = np.nonzero(r["failed"] > 0)[0]
        t_end = min(r["t"][failed[0]] if len(failed) else r["t"][-1], 28.0)
        mask = r["t"] <= t_end
        dv = np.abs(r["v"][mask] - np.interp(r["t"][mask], dem["t"],
                                             dem["v"]))
        print("  %s: largest |v - v_DEM| up to %.1f us: %.2f m/s; largest "
              "width / initial %.3f (DEM %.3f)"
              % (label, t_end, dv.max(), (r["width"][mask] / w0).max(),
                 (dem["width"][dem["t"] <= t_end] / w0_dem).max()))

    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, ax = plt.subplots(1, 3, figsize=(14, 4))
    ax[0].plot(dem["t"], dem["v"], "k-", lw=2, label="DEM")
    ax[1].plot(dem["t"], dem["width"] / w0_dem, "k-", lw=2, label="DEM")
    ax[2].plot(dem["t"], dem["spreading"], "k-", lw=2, label="DEM")
    for label, r in runs:
        ax[0].plot(r["t"], r["v"], label=label)
        ax[1].plot(r["t"], r["width"] / r["width"][0], label=label)
        ax[2].plot(r["t"], r["spreading"], label=label)
    ax[0].set_ylabel("projectile velocity [m/s]")
    ax[1].set_ylabel("width 4 sqrt(<z^2>) at the impact point / initial [-]")
    ax[2].set_ylabel("spreading front [mm]")
    for a in ax:
        a.set_xlabel("t [us]")
        a.grid(alpha=0.3)
        a.legend(fontsize=8)
    fig.suptitle("120 m/s impact on the KM2 yarn: FE runs against the DEM",
                 fontsize=10)
    fig.tight_layout()
    fig.savefig(png, dpi=110)
    print("wrote " + png)


if __name__ == "__main__":
    main()
