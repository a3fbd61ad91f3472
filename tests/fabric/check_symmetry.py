#!/usr/bin/python3
"""The half-turn symmetry of a struck patch (fabric_runs.sh energy and
sphere). With n_warp + n_weft even, the woven patch is its own image under
the half turn about the y axis, (x, y, z) -> (-x, y, -z): warp i goes onto
warp n_warp - 1 - i with its crimp, weft j onto weft n_weft - 1 - j, the
sections (ellipses, meshed symmetrically) onto themselves; so are the
cylinder along z and the sphere centred on x = z = 0, and the clamps. The
displacement field must then be symmetric: u(-x, y, -z) = (-u_x, u_y, -u_z)
at the image of every vertex. Checked on every snapshot of DIR (one MPI
rank: one piece per snapshot) after the first, against the largest
displacement: within 1e-6 of it plus 1e-12 m (the VTU's displacements are
32-bit floats, 6e-8 relative; before the projectile touches, the
displacements are round-off of 1e-19 m). An independent check of the patch's mesh, clamps
and fibre directions (a wrong sign or index breaks the symmetry) and of
the contacts' forces, which nothing in the code makes symmetric.

Usage: check_symmetry.py DIR. Exits 1 if a check fails.
"""
import array
import base64
import glob
import re
import struct
import sys
import zlib


def read(path):
    """Reference position -> displacement of every vertex of a .vtu."""
    text = open(path).read()
    res = {}
    for m in re.finditer(r'<DataArray type="(\w+)"(?: Name="(\w+)")? '
                         r'NumberOfComponents="(\d+)" format="binary">\s*'
                         r'(\S+)\s*</DataArray>', text):
        name = m.group(2) or "points"
        if name not in ("points", "displacement"):
            continue
        # deal.II's zlib-compressed binary: a base64 header of 3 + n
        # 32-bit integers (n blocks), then the base64 blocks.
        s = m.group(4)
        n_blocks = struct.unpack("<I", base64.b64decode(s[:8])[:4])[0]
        header = (((3 + n_blocks) * 4 + 2) // 3) * 4
        a = array.array("f" if m.group(1) == "Float32" else "d")
        a.frombytes(zlib.decompress(base64.b64decode(s[header:])))
        res[name] = a
    P, U = res["points"], res["displacement"]
    nodes = {}
    for i in range(len(P) // 3):
        X = tuple(P[3 * i + d] - U[3 * i + d] for d in range(3))
        key = tuple(round(c / 2e-6) for c in X)
        nodes[key] = (X, (U[3 * i], U[3 * i + 1], U[3 * i + 2]))
    return nodes


def image(nodes, key, X):
    """The vertex at (-x, y, -z), within 1e-8 m, or None."""
    for dx in (-1, 0, 1):
        for dy in (-1, 0, 1):
            for dz in (-1, 0, 1):
                c = nodes.get((-key[0] + dx, key[1] + dy, -key[2] + dz))
                if c and abs(c[0][0] + X[0]) < 1e-8 and \
                        abs(c[0][1] - X[1]) < 1e-8 and \
                        abs(c[0][2] + X[2]) < 1e-8:
                    return c
    return None


def main():
    failures = 0
    files = sorted(glob.glob(f"{sys.argv[1]}/fe_*.vtu"))[1:]
    if not files:
        print(f"FAILED no snapshot in {sys.argv[1]}")
        sys.exit(1)
    for f in files:
        nodes = read(f)
        largest = max(max(abs(c) for c in u) for X, u in nodes.values())
        worst, missing = 0., 0
        for key, (X, u) in nodes.items():
            c = image(nodes, key, X)
            if c is None:
                missing += 1
                continue
            v = c[1]
            worst = max(worst, abs(u[0] + v[0]), abs(u[1] - v[1]),
                        abs(u[2] + v[2]))
        ok = missing == 0 and worst <= 1e-6 * largest + 1e-12
        failures += not ok
        print(("ok     " if ok else "FAILED ") +
              f"half-turn symmetry, {f.split('/')[-1]}: {len(nodes)} vertices, "
              f"{missing} without an image; largest asymmetry {worst:.3g} m, "
              f"{worst / largest:.2g} of the largest displacement {largest:.4g} "
              f"m (at most 1e-6 of it plus 1e-12 m)")
    sys.exit(1 if failures else 0)


if __name__ == "__main__":
    main()
