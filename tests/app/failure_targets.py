#!/usr/bin/env python3
"""The paper's FE case (120 m/s) with the progressive fibre-failure law
against the stored DEM history (doc/figures/history_dem_km2_120ms.csv):
the targets of doc/validation.md section 6.

Usage: failure_targets.py YARN_IMPACT SOURCE_DIR [extra prm lines...]

Runs prm/km2_120ms_fe_progressive.prm on one rank (with the extra lines
appended, e.g. a refined mesh) and checks, each on a line of its own:
- first failure (first damaged cell) within 1 us of the DEM's first break;
- cut-through within 1 us of the DEM's;
- |v_FE - v_DEM| <= 2 m/s at every DEM history time up to 40 us (the DEM
  history is interpolated on the FE times);
- largest energy error <= 0.5 %.
Prints each target with MET or MISSED and the measured value. The first
failure and the energy error are met and asserted at their targets. Two
targets are not met (doc/validation.md section 6: with the onset spread
across the thickness the FE section is still cut through within 0.5 us
of its first damage, at 30.41 us, where the DEM's fibres break over
4.6 us; largest |v_FE - v_DEM| 2.98 m/s): for them the test asserts a
regression bound just above the level reached (cut-through within 4.0 us
of the DEM's, |v_FE - v_DEM| <= 3.5 m/s), so that a change that makes
the agreement worse fails. With --strict every target is asserted (run
it by hand: it fails today).
"""

import os
import subprocess
import sys
import tempfile

import numpy as np


def read(path):
    with open(path) as f:
        header = f.readline().rstrip("\n").split(",")
    data = np.genfromtxt(path, delimiter=",", skip_header=1)
    return {h: data[:, i] for i, h in enumerate(header)}


def summary_value(text, key):
    for line in text.splitlines():
        if line.strip().startswith(key):
            v = line.split(":", 1)[1].split()[0]
            try:
                return float(v)
            except ValueError:
                return None
    return None


def main():
    args = [a for a in sys.argv[1:] if a != "--strict"]
    strict = len(args) != len(sys.argv) - 1
    exe, source = args[0], args[1]
    extra = "\n".join(args[2:])
    dem = read(os.path.join(source, "doc/figures/history_dem_km2_120ms.csv"))
    t_dem_first, t_dem_cut = 29.6, 34.2  # doc/validation.md section 1
    with tempfile.TemporaryDirectory() as work:
        prm = os.path.join(work, "case.prm")
        with open(prm, "w") as f:
            f.write("include %s\n" % os.path.join(
                source, "prm/km2_120ms_fe_progressive.prm"))
            f.write("subsection Output\n  set Directory = %s\n"
                    "  set Snapshot interval = 0\n  set Overwrite = true\n"
                    "end\n" % os.path.join(work, "run"))
            f.write(extra + "\n")
        # The prm includes another by a path relative to the source tree.
        run = subprocess.run([exe, prm], cwd=source, capture_output=True,
                             text=True)
        if run.returncode != 0:
            print("FAILED: the run exited with %d: %s"
                  % (run.returncode, run.stderr[-500:]))
            return 1
        fe = read(os.path.join(work, "run/history_fe.csv"))
        with open(os.path.join(work, "run/summary.txt")) as f:
            summary = f.read()
    first = summary_value(summary, "first failure:")
    cut = summary_value(summary, "yarn cut through:")
    err = summary_value(summary, "largest energy error:")
    t = fe["t [us]"]
    keep = t <= 40.0 + 1e-9
    v_dem = np.interp(t[keep], dem["t [us]"], dem["projectile velocity [m/s]"])
    dv = np.abs(fe["projectile velocity [m/s]"][keep] - v_dem)
    k = int(np.argmax(dv))
    # (target, met, regression bound held, measured)
    cut_gap = abs(cut - t_dem_cut) if cut is not None else float("inf")
    checks = [
        ("first failure within 1 us of the DEM's 29.6 us",
         first is not None and abs(first - t_dem_first) <= 1.0, None,
         "%s us" % first),
        ("cut-through within 1 us of the DEM's 34.2 us", cut_gap <= 1.0,
         cut_gap <= 4.0, "%s us (regression bound: within 4.0 us)" % cut),
        ("|v_FE - v_DEM| <= 2 m/s up to 40 us", dv.max() <= 2.0,
         dv.max() <= 3.5,
         "largest %.2f m/s at %.1f us (regression bound: 3.5 m/s)"
         % (dv.max(), t[keep][k])),
        ("energy error <= 0.5 %", err is not None and err <= 0.5, None,
         "%s %%" % err),
    ]
    failed = 0
    for name, met, bound, measured in checks:
        ok = met if (strict or bound is None) else bound
        verdict = "MET" if met else ("MISSED, regression bound %s" % (
            "held" if bound else "BROKEN") if bound is not None else "MISSED")
        print("%s: %s" % (name, verdict))
        print("  measured: %s" % measured, file=sys.stderr)
        failed += not ok
    print("PASSED" if not failed else "FAILED")
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
