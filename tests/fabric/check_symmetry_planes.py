#!/usr/bin/python3
"""Symmetry planes of the woven patch (fabric_runs.sh symmetry_planes;
doc/fabric.md section 10).

  check_symmetry_planes.py mirror WHOLE
      The whole patch's own mirror symmetry (an exact identity, the mirror
      symmetry): with odd numbers of yarns the planes x = 0 and z = 0 lie
      on the middle yarns' centrelines, about which the plain weave, its
      clamps and a centred sphere are their own images, so that the
      displacement must satisfy u(-x, y, z) = (-u_x, u_y, u_z) and
      u(x, y, -z) = (u_x, u_y, -u_z). Checked on every snapshot of WHOLE
      but the first, before and after its first yarn contact (the first
      row of the history with a yarn contact energy), within 1e-6 of the
      largest displacement plus 1e-12 m (the VTU's 32-bit floats): the
      yarn contact shares a node on a plane over the edge between a face
      and its mirror image equally among the tied faces, whatever their
      order (doc/fabric.md section 10), so that nothing breaks the
      symmetry but round-off.

  check_symmetry_planes.py compare WHOLE REDUCED TOLERANCE
      A half or quarter model against the whole patch (an exact identity,
      the mirror symmetry: the reduced model computes the symmetric
      solution on its part of the cells): (1) the same rows at the same
      times, the reduced model's first yarn contact at the whole's row;
      (2) every column but the station profile's, at every row of the run,
      before and after the first yarn contact, within 1e-9 of the column's
      largest magnitude over the run (explicit dynamics on the same cells:
      the same arithmetic but for the order of the sums, the rounding of
      the mirrored vertices and the tied faces' shares); (3) at the end,
      the velocity the projectile lost within TOLERANCE of the whole's
      (relative; the column's 10 digits resolve 1e-7 of it). The station
      profile's columns (fronts, section widths, plateau strain) average
      over the meshed nodes, a node on a plane once for its images, and are
      not the whole patch's.

Exits 1 if a check fails.
"""
import csv
import glob
import os
import re
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from check_symmetry import read  # noqa: E402

STATION_PROFILE = ("longitudinal front [mm]", "transverse front [mm]",
                   "spreading front [mm]", "section width at impact [mm]",
                   "plateau strain [-]", "section RMS width at impact [mm]")


def history(directory):
    rows = list(csv.reader(open(f"{directory}/history_fabric.csv")))
    return rows[0], [[float(x) for x in r] for r in rows[1:]]


def first_yarn_contact(header, rows):
    k = header.index("yarn contact energy [mJ]")
    return next(i for i, r in enumerate(rows) if r[k] > 0.)


def image(nodes, key, X, plane):
    """The vertex at X mirrored in the plane (0: x = 0, 2: z = 0), within
    1e-8 m, or None."""
    target = list(X)
    target[plane] = -target[plane]
    k0 = list(key)
    k0[plane] = -k0[plane]
    for dx in (-1, 0, 1):
        for dy in (-1, 0, 1):
            for dz in (-1, 0, 1):
                c = nodes.get((k0[0] + dx, k0[1] + dy, k0[2] + dz))
                if c and all(abs(c[0][d] - target[d]) < 1e-8
                             for d in range(3)):
                    return c
    return None


def asymmetry(path):
    """Largest asymmetry [m] in either plane, the largest displacement [m],
    the vertices without an image."""
    nodes = read(path)
    largest = max(max(abs(c) for c in u) for X, u in nodes.values())
    worst, missing = 0., 0
    for plane in (0, 2):
        for key, (X, u) in nodes.items():
            c = image(nodes, key, X, plane)
            if c is None:
                missing += 1
                continue
            v = list(c[1])
            v[plane] = -v[plane]
            worst = max(worst, max(abs(u[d] - v[d]) for d in range(3)))
    return worst, largest, missing


def mirror(whole):
    header, rows = history(whole)
    t_contact = rows[first_yarn_contact(header, rows)][0]
    times = {}
    for line in open(f"{whole}/fabric.pvd"):
        m = re.search(r'timestep="([^"]+)".*file="fe_(\d+)\.pvtu"', line)
        if m:
            times[int(m.group(2))] = float(m.group(1))
    failures, before, after = 0, 0, 0
    for f in sorted(glob.glob(f"{whole}/fe_*.0.vtu"))[1:]:
        t = times[int(re.search(r"fe_(\d+)\.0\.vtu", f).group(1))]
        worst, largest, missing = asymmetry(f)
        text = (f"the whole patch's mirror symmetry at {t:.3g} us: "
                f"{missing} vertices without an image; largest asymmetry "
                f"{worst:.3g} m, {worst / largest:.2g} of the largest "
                f"displacement {largest:.4g} m")
        before += t < t_contact
        after += t >= t_contact
        ok = missing == 0 and worst <= 1e-6 * largest + 1e-12
        failures += not ok
        print(("ok     " if ok else "FAILED ") + text +
              (" (before" if t < t_contact else " (after") +
              f" the first yarn contact at {t_contact:.4g} us: "
              "at most 1e-6 of it plus 1e-12 m)")
    if before == 0 or after == 0:
        print("FAILED no snapshot before or none after the first yarn "
              "contact")
        failures += 1
    return failures


def compare(whole, reduced, tolerance):
    h, a = history(whole)
    h2, b = history(reduced)
    failures = 0
    first = first_yarn_contact(h, a)
    first_b = first_yarn_contact(h2, b)
    ok = first == first_b and len(a) > first
    failures += not ok
    print(("ok     " if ok else "FAILED ") +
          f"{reduced}: first yarn contact at row {first_b} "
          f"({b[first_b][0]:.4g} us), the whole's at row {first} "
          f"({a[first][0]:.4g} us)")
    ok = len(a) == len(b) and all(
        abs(r[0] - q[0]) < 1e-9 for r, q in zip(a, b))
    failures += not ok
    print(("ok     " if ok else "FAILED ") +
          f"{reduced}: {len(b)} rows at the whole's {len(a)} times")
    worst, where = 0., ""
    for c in h:
        if c in STATION_PROFILE or c in ("t [us]", "dt [ns]"):
            continue
        k, j = h.index(c), h2.index(c)
        scale = max(abs(r[k]) for r in a) or 1.
        for r, s in zip(a, b):
            d = max(abs(r[k] - s[j]), abs(r[0] - s[0])) / scale
            if d > worst:
                worst, where = d, f"{c} at {r[0]:.4g} us"
    ok = worst <= 1e-9
    failures += not ok
    print(("ok     " if ok else "FAILED ") +
          f"{reduced} against the whole patch at every row, {first} before "
          f"and {len(a) - first} from the first yarn contact: largest "
          f"difference {worst:.2g} of the column's largest magnitude "
          f"({where or 'none'}; at most 1e-9)")
    kv = h.index("projectile velocity [m/s]")
    v0 = a[0][kv]
    lost_a, lost_b = v0 - a[-1][kv], v0 - b[-1][h2.index(
        "projectile velocity [m/s]")]
    d = abs(lost_b - lost_a) / lost_a
    ok = abs(a[-1][0] - b[-1][0]) < 1e-9 and d <= tolerance
    failures += not ok
    print(("ok     " if ok else "FAILED ") +
          f"{reduced}: velocity lost by {a[-1][0]:.4g} us {lost_b:.6g} m/s "
          f"against the whole's {lost_a:.6g} m/s, {100 * d:.3g} % apart "
          f"(at most {100 * tolerance:.3g} %)")
    return failures


def main():
    if sys.argv[1] == "mirror":
        failures = mirror(sys.argv[2])
    else:
        failures = compare(sys.argv[2], sys.argv[3], float(sys.argv[4]))
    sys.exit(1 if failures else 0)


if __name__ == "__main__":
    main()
