#!/usr/bin/env python3
"""Compare a DEM run with a reference run of the same case (doc/performance-dem.md,
"The step from the contacts"): the criteria a change of the DEM's time step
or contact stiffness must meet.

    python3 scripts/dem_step_check.py REFERENCE_DIR NEW_DIR

Each directory is a run's output folder (history_dem.csv, summary.txt).
Prints, for both runs: the steps and their sizes, the first truss break,
the cut-through, the largest energy error, and for the new run the largest
|v_new - v_ref| up to the reference's first break (the velocities are
compared at the reference's history times, linearly interpolated), with a
verdict against the tolerances of issue 17 (0.2 m/s, 0.2 us, 0.5 us,
0.2 %).
"""
import csv
import sys

import numpy as np


def read_run(directory):
    with open(f"{directory}/history_dem.csv") as f:
        rows = list(csv.reader(f))
    head = rows[0]
    data = np.array([[float(x) for x in r] for r in rows[1:]])
    col = {name: k for k, name in enumerate(head)}
    cut = None
    with open(f"{directory}/summary.txt") as f:
        for line in f:
            if line.strip().startswith("yarn cut through:"):
                value = line.split(":", 1)[1].split()[0]
                cut = float(value) if value not in ("no", "none") else None
    t = data[:, col["t [us]"]]
    failed = data[:, col["failed elements"]]
    broken = np.nonzero(failed > 0)[0]
    return {
        "t": t,
        "v": data[:, col["projectile velocity [m/s]"]],
        "dt": data[:, col["dt [ns]"]],
        "steps": int(data[-1, col["step"]]),
        "first_break": t[broken[0]] if len(broken) else None,
        "cut": cut,
        "energy_error": np.max(np.abs(data[:, col["energy error [%]"]])),
    }


def describe(name, run):
    fb = f"{run['first_break']:.4f} us" if run["first_break"] is not None else "none"
    cut = f"{run['cut']:.4f} us" if run["cut"] is not None else "none"
    # The rows' steps include those shortened to land on a row's time.
    lo, hi = np.percentile(run["dt"][1:], [5, 95])
    mean = 1e3 * run["t"][-1] / run["steps"]
    print(f"{name}: {run['steps']} steps, mean dt {mean:.4f} ns (5-95 % of "
          f"the rows' steps {lo:.4f}-{hi:.4f} ns), first break {fb}, "
          f"cut through {cut}, v(end) {run['v'][-1]:.4f} m/s, "
          f"largest energy error {run['energy_error']:.4f} %")


def main():
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    ref, new = read_run(sys.argv[1]), read_run(sys.argv[2])
    describe("reference", ref)
    describe("new      ", new)
    t_end = ref["first_break"] if ref["first_break"] is not None else ref["t"][-1]
    mask = ref["t"] <= t_end + 1e-9
    dv = np.max(np.abs(np.interp(ref["t"][mask], new["t"], new["v"]) - ref["v"][mask]))
    checks = [("largest |dv| up to the reference's first break [m/s]", dv, 0.2)]
    if ref["first_break"] is not None and new["first_break"] is not None:
        checks.append(("first break moved by [us]",
                       abs(new["first_break"] - ref["first_break"]), 0.2))
    if ref["cut"] is not None and new["cut"] is not None:
        checks.append(("cut-through moved by [us]", abs(new["cut"] - ref["cut"]), 0.5))
    checks.append(("largest energy error of the new run [%]", new["energy_error"], 0.2))
    ok = True
    for label, value, tol in checks:
        verdict = "met" if value <= tol else "NOT met"
        ok = ok and value <= tol
        print(f"  {label}: {value:.4f} (<= {tol}: {verdict})")
    print(f"steps: new/reference = {new['steps'] / ref['steps']:.3f}")
    sys.exit(0 if ok else 1)


if __name__ == "__main__":
    main()
