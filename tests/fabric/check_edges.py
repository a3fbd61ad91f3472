#!/usr/bin/python3
"""The clamped and free edges of a struck patch (fabric_runs.sh edges):
Fabric/Clamped edges = all, warp ends, weft ends or none on the 4 x 4
patch of the example's yarns (s = 1 mm, the patch 4 mm wide). In the last
snapshot of DIR (one MPI rank), the vertices whose reference |x| is above
n s / 2 - 0.05 mm are the end sections of the warp yarns (no weft vertex
lies beyond x_j + a_z = 1.767 mm, the cells are 0.125 mm long), those
whose |z| is, the end sections of the weft yarns. A clamped family's end
vertices must have a displacement of exactly 0, a free family's must move:
their largest displacement above 1e-3 of the patch's largest (by then
the longitudinal waves have crossed the patch several times).

Usage: check_edges.py DIR all|warp|weft|none. Exits 1 if a check fails.
"""
import glob
import sys

from check_symmetry import read

EDGE = 2e-3 - 0.05e-3  # [m], n s / 2 - 0.05 mm for the 4 x 4 patch


def main():
    directory, mode = sys.argv[1], sys.argv[2]
    files = sorted(glob.glob(f"{directory}/fe_*.vtu"))
    if not files:
        print(f"FAILED no snapshot in {directory}")
        sys.exit(1)
    nodes = read(files[-1])
    largest = max(max(abs(c) for c in u) for X, u in nodes.values())
    failures = 0
    for family, axis in (("warp", 0), ("weft", 2)):
        ends = [u for X, u in nodes.values() if abs(X[axis]) > EDGE]
        moved = max(max(abs(c) for c in u) for u in ends)
        clamped = mode in ("all", family)
        ok = len(ends) > 0 and (moved == 0. if clamped
                                else moved > 1e-3 * largest)
        failures += not ok
        print(("ok     " if ok else "FAILED ") +
              f"{mode}: the {len(ends)} end vertices of the {family} yarns "
              f"{'clamped' if clamped else 'free'}: largest displacement "
              f"{moved:.4g} m, {moved / largest:.3g} of the patch's largest "
              f"({'exactly 0' if clamped else 'above 1e-3 of it'})")
    sys.exit(1 if failures else 0)


if __name__ == "__main__":
    main()
