#!/usr/bin/python3
"""Checks of the fabric run on a mesh read from a file (fabric_runs.sh
mesh_file, doc/fabric.md section 8). Prints one line per check, "ok" or
"FAILED", and exits 1 if one failed.

  check_mesh_file.py GENERATED READ ESTIMATED PER_CELL
    GENERATED: the 4 x 4 patch generated; READ: the same patch written by
    write-patch-mesh and read back with its orientation file of the patch's
    directions at every Gauss point; ESTIMATED: the patch written without
    physical surfaces, read without an orientation file (directions
    estimated, end faces found by their normals); PER_CELL: that mesh with
    the orientation file of each cell's mean direction.
    (1) READ against GENERATED: every column at every row within 1e-9 of
        the column's largest magnitude, the energies [mJ] within 1e-9 of
        the projectile's initial kinetic energy. Not byte for byte: GridIn
        orders each hexahedron's vertices its own way (it turns every
        cell of the patch), so that the cells' sums run in another order,
        a round-off difference; the 10 digits of the CSV hide it but in
        columns that hold round-off only (the secondary yarns' energies
        before anything touches them, below 1e-26 mJ).
    (2) ESTIMATED against PER_CELL: the projectile's velocity at every row
        within 1e-3 m/s (the estimated directions are within 0.01 degrees
        of the cells' mean directions: write-patch-mesh --compare, checked
        by fabric_runs.sh).
    (3) ESTIMATED against GENERATED: the projectile's velocity at every
        row within 5 % of the velocity the generated run has lost by its
        end (a direction per cell against one per Gauss point: the crimp
        turns the tangent by up to 7 degrees across a cell of 1/8 mm).
"""
import csv
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from checks import check, finish  # noqa: E402


def history(directory):
    with open(directory + "/history_fabric.csv") as f:
        rows = list(csv.reader(f))
    return rows[0], [[float(x) for x in r] for r in rows[1:]]


generated, read, estimated, per_cell = sys.argv[1:5]
head, g = history(generated)
head_r, r = history(read)
_, e = history(estimated)
_, c = history(per_cell)
check(head == head_r and len(g) == len(r) == len(e) == len(c),
      f"the four histories have the same columns and {len(g)} rows")

v = head.index("projectile velocity [m/s]")
kinetic0 = g[0][head.index("projectile kinetic energy [mJ]")]
worst, where = 0., ""
for k, name in enumerate(head):
    scale = max(abs(row[k]) for row in g)
    if "[mJ]" in name:
        scale = max(scale, kinetic0)
    for x, y in zip(g, r):
        d = abs(x[k] - y[k]) / scale if scale > 0 else abs(x[k] - y[k])
        if d > worst:
            worst, where = d, f"{name} at {x[0]} us"
check(worst <= 1e-9,
      f"read mesh with the patch's directions against the generated patch: "
      f"largest difference {worst:.2g} of the column's scale ({where or 'none'})")

d = max(abs(x[v] - y[v]) for x, y in zip(e, c))
check(d <= 1e-3,
      f"estimated directions against the cells' mean directions: projectile "
      f"velocity within {d:.2g} m/s")

lost = g[0][v] - g[-1][v]
d = max(abs(x[v] - y[v]) for x, y in zip(e, g))
check(d <= 0.05 * lost,
      f"estimated directions against the generated patch: projectile "
      f"velocity within {d:.3g} m/s, {100 * d / lost:.2f} % of the "
      f"{lost:.3f} m/s lost (final {e[-1][v]:.4f} against {g[-1][v]:.4f} m/s)")
finish()
