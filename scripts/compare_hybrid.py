#!/usr/bin/python3
"""Compare a hybrid run with the full DEM on the same case (doc/hybrid.md
section 5): the largest projectile-velocity difference up to the end or to
2 us after the DEM's cut, the first break, the cut-through and the RMS
section width at the impact point.

Usage: compare_hybrid.py HISTORY_HYBRID.csv HISTORY_DEM.csv
Prints one table row per quantity; exits 1 with one line on a bad file.
"""
import bisect
import csv
import os
import sys


def load(path):
    try:
        with open(path, newline="") as f:
            rows = list(csv.reader(f))
        header = rows[0]
        data = [[float(x) for x in r] for r in rows[1:] if r]
    except (OSError, IndexError, ValueError) as e:
        sys.exit(f"compare_hybrid.py: error: cannot read the history '{path}': {e}")
    if not data:
        sys.exit(f"compare_hybrid.py: error: the history '{path}' has no rows")
    return {name: [r[k] for r in data] for k, name in enumerate(header)}


def first_time(h, column, test):
    for t, x in zip(h["t [us]"], h[column]):
        if test(x):
            return t
    return None


def value_at(h, column, t):
    times = h["t [us]"]
    k = min(range(len(times)), key=lambda i: abs(times[i] - t))
    return h[column][k], times[k]


def shared_rows(hy, dem, column):
    """(t, hybrid value, DEM value) at the hybrid's rows that the DEM's
    history also has (within 1e-3 us): where the two write rows at
    different times, a nearest row would compare values up to half a row
    interval apart, which is large where the velocity changes fast (at a
    first break). Without any shared row, the DEM's value interpolated
    linearly between its rows."""
    times = dem["t [us]"]
    out, j = [], 0
    for t, x in zip(hy["t [us]"], hy[column]):
        while j + 1 < len(times) and times[j + 1] <= t + 1e-3:
            j += 1
        if abs(times[j] - t) <= 1e-3:
            out.append((t, x, dem[column][j]))
    if len(out) > 1:
        return out
    values = dem[column]
    return [(t, x, interpolate(t, times, values))
            for t, x in zip(hy["t [us]"], hy[column])]


def interpolate(t, times, values):
    """values linearly interpolated at t between the rows around it (the
    first or last row's value outside them)."""
    k = bisect.bisect_right(times, t)
    if k == 0:
        return values[0]
    if k == len(times):
        return values[-1]
    w = (t - times[k - 1]) / (times[k] - times[k - 1])
    return (1 - w) * values[k - 1] + w * values[k]


def main():
    if len(sys.argv) != 3:
        sys.exit(__doc__.strip().splitlines()[-2])
    hy, dem = load(sys.argv[1]), load(sys.argv[2])
    v = "projectile velocity [m/s]"
    failed = "failed elements"
    width = "section RMS width at impact [mm]"
    first = {n: first_time(h, failed, lambda x: x > 0) for n, h in (("hybrid", hy), ("dem", dem))}
    # The cut-through, from the summary.txt beside each history.
    def cut(path):
        summary = os.path.join(os.path.dirname(os.path.abspath(path)), "summary.txt")
        try:
            for line in open(summary):
                if "yarn cut through:" in line and "us" in line:
                    return float(line.split(":")[1].split()[0])
        except (OSError, ValueError):
            pass
        return None
    cuts = {"hybrid": cut(sys.argv[1]), "dem": cut(sys.argv[2])}
    end = min(hy["t [us]"][-1], dem["t [us]"][-1])
    if cuts["dem"] is not None:
        end = min(end, cuts["dem"] + 2.0)
    worst, at, before = 0.0, 0.0, 0.0
    for t, x, y in shared_rows(hy, dem, v):
        if t > end + 1e-9:
            break
        if abs(x - y) > worst:
            worst, at = abs(x - y), t
        # Before the DEM's row that first records a break (that row itself
        # already carries the force of the breaking step).
        if first["dem"] is None or t < first["dem"] - 1e-3:
            before = max(before, abs(x - y))
    print(f"compared up to {end:.2f} us (hybrid to {hy['t [us]'][-1]:.2f} us)")
    print(f"largest |v_hybrid - v_DEM| before the DEM's first break: {before:.3f} m/s")
    print(f"largest |v_hybrid - v_DEM|: {worst:.3f} m/s at {at:.2f} us")
    for name in ("hybrid", "dem"):
        f, c = first[name], cuts[name]
        print(f"{name:7s} first break: {'none' if f is None else f'{f:.2f} us'},"
              f" cut through: {'no' if c is None else f'{c:.2f} us'}")
    # At 10 and 20 us when both runs reach them, and at the end of the
    # comparison; each run's row nearest to the same time.
    for t in sorted({x for x in (10.0, 20.0) if x < end} | {end}):
        a, ta = value_at(hy, width, t)
        b, _ = value_at(dem, width, ta)
        print(f"RMS width at impact at {ta:.2f} us: hybrid {a:.4f} mm, DEM {b:.4f} mm"
              f" ({100 * (a / b - 1):+.2f} %)")


main()
