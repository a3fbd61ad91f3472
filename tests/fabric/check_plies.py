#!/usr/bin/python3
"""Checks of the plies and the broken yarns of Model = fabric runs
(fabric_runs.sh plies and broken) on their history CSVs and snapshots.
Prints one line per check, "ok" or "FAILED", and exits 1 if one failed.

  plies DIR H A AY [shifted]
                     a patch of two plies, their mid-planes H [m] apart,
                     crimp amplitude A [m], thickness semi-axis AY [m],
                     struck at the centre by the cylinder, no failure, a
                     history row at every step, a snapshot at t = 0;
                     shifted: the lower ply shifted in the fabric's plane
                     (Fabric/Ply offset x, z), where (3) does not apply:
    (0) the gap g between the plies at rest, the lowest vertex of the upper
        ply's mesh above the highest of the lower one's (the first
        snapshot), positive and at most the ellipses' H - 2 (A + AY) (the
        meshed section reaches beyond the ellipse by its area-preserving
        scale), above 0.9 of it;
    (1) the plies' energies: each ply's kinetic and strain energies sum to
        the yarns' kinetic and strain energy columns at every row, within
        1e-9 of them (their 10 digits; reproducible sums of the same
        terms) plus 1e-15 mJ;
    (2) the lower ply is set in motion only through the yarn contact: its
        kinetic and strain energies stay at round-off (below 1e-20 mJ; at
        rest every yarn holds some 1e-27 mJ) until the upper ply can have
        crossed the gap g between them (the bottoms of one ply's crossings
        to the tops of the next's, aligned plies), that is at every row
        before t_0 + g / (2 v_0), t_0 the first row
        with a contact force, v_0 the projectile's initial speed (a light
        body struck elastically by a heavy one leaves at 2 v_0 at most);
    (3) and it moves (kinetic energy above 1e-6 mJ) before the projectile
        has travelled D = (A + a) + H - a / cos(theta), tan(theta) =
        pi A / S (S the yarn spacing 1 mm, a = (H - g) / 2 - A the meshed
        section's semi-thickness): from its start on the crests' tops to
        the top of the lower ply's warp yarns under its lowest line
        (x = 0, where their slope is theta), which it cannot pass
        without the upper ply pressing the lower one; printed with the
        delay after t_0 over g / v_0, the time to cross the gap at the
        projectile's speed (aligned plies only: the bound takes the
        lower ply's crossings under the upper one's);
    (4) the cone's fronts of each ply: the fabric's fronts (along the
        warp, the weft and the diagonal) are the farthest of the plies'
        at every row; the lower ply's are 0 at every row of (2), where it
        is at rest, and above 0 by the end; they are never beyond the
        struck ply's, which leads the cone.
  broken DIR         a patch with a low Yarn/Failure strain, sudden
                     failure, and a snapshot at its last row:
    (1) the history's broken yarns 0 at every row without a failed or
        eroded cell, never decreasing, and above 0 at the end;
    (2) at most (failed + eroded cells) / 12 (a section has 12 cells);
    (2') the energy error below 0.5 % of the initial energy at every row,
        through the failures;
    (3) the last snapshot's count by other code: each cell's yarn, ply,
        failed state, damage and reference centre, its section the
        interval of Cells per spacing per Yarn spacing along its yarn (x
        of a warp yarn, z of a weft yarn), a yarn broken where one of its
        sections has every cell failed (broken, fully damaged or eroded):
        equal to the history's last row.

Usage: check_plies.py plies DIR H A AY [shifted]
       check_plies.py broken DIR N_WARP N_WEFT S CPS
"""
import array
import base64
import csv
import glob
import math
import os
import re
import struct
import sys
import zlib

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from checks import check, finish  # noqa: E402


def history(directory):
    with open(f"{directory}/history_fabric.csv") as f:
        rows = list(csv.reader(f))
    return rows[0], [[float(x) for x in r] for r in rows[1:]]


# Columns of the history CSV (doc/user-guide.md, "History columns").
T, DISP, V, F, KY, EL, FAILED, ERODED = 0, 3, 4, 5, 6, 8, 14, 22


def plies(directory, h, a, ay, shifted=False):
    header, rows = history(directory)
    cols = [(header.index(f"ply {p} kinetic energy [mJ]"),
             header.index(f"ply {p} strain energy [mJ]")) for p in (0, 1)]
    worst = max(max(abs(sum(r[k] for k, e in cols) - r[KY]) /
                    (abs(r[KY]) + 1e-6),
                    abs(sum(r[e] for k, e in cols) - r[EL]) /
                    (abs(r[EL]) + 1e-6)) for r in rows)
    ok = all(abs(sum(r[k] for k, e in cols) - r[KY]) <=
             1e-9 * abs(r[KY]) + 1e-15 and
             abs(sum(r[e] for k, e in cols) - r[EL]) <=
             1e-9 * abs(r[EL]) + 1e-15 for r in rows)
    check(ok, f"plies: their kinetic and strain energies sum to the yarns' "
          f"within {worst:.3g} of them (at most 1e-9 plus 1e-15 mJ)")
    v0 = rows[0][V]
    ellipses = h - 2 * (a + ay)
    files = sorted(glob.glob(f"{directory}/fe_*.vtu"))
    if not files:
        check(False, f"no snapshot in {directory}")
        return
    low, high = {}, {}
    for centre, yarn, ply, failed, damage, lo, hi in read_cells(files[0]):
        low[ply] = min(low.get(ply, 1.), lo)
        high[ply] = max(high.get(ply, -1.), hi)
    gap = low[0] - high[1]
    check(0.9 * ellipses < gap <= ellipses,
          f"gap between the plies at rest {1e3 * gap:.4g} mm (the "
          f"ellipses' {1e3 * ellipses:.4g} mm; within 0.9 to 1 of it)")
    t0 = next(r[T] for r in rows if r[F] != 0.)
    bound = t0 + 1e6 * gap / (2 * v0)
    k1, e1 = cols[1]
    still = [r for r in rows if r[T] < bound]
    top = max(max(r[k1], r[e1]) for r in still)
    check(still and top < 1e-20, f"lower ply at rest until the upper one "
          f"can reach it: gap {1e3 * gap:.4g} mm, first contact at "
          f"{t0:.4g} us, its energies at most {top:.3g} mJ before "
          f"{bound:.4g} us (below 1e-20 mJ)")
    # The meshed section's semi-thickness, from the gap.
    am = 0.5 * (h - gap) - a
    reach = 1e3 * ((a + am) + h - am / math.cos(math.atan(math.pi * a / 1e-3)))
    moving = next((r for r in rows if r[k1] > 1e-6), None)
    last = rows[-1]
    if moving is None:
        check(False, f"the lower ply never moves (at the end {last[k1]:.4g} "
              f"mJ kinetic)")
        return
    crossing = 1e6 * gap / v0
    lines = ("warp", "weft", "diagonal")
    whole = [header.index(f"cone front along {d} [mm]") for d in lines]
    ply = [[header.index(f"ply {p} cone front along {d} [mm]") for d in lines]
           for p in (0, 1)]
    check(all(r[whole[d]] == max(r[ply[0][d]], r[ply[1][d]])
              for r in rows for d in range(3)),
          "cone fronts: the fabric's the farthest of the plies' at every row")
    at_rest = max(r[c] for r in still for c in ply[1])
    led = all(r[ply[1][d]] <= r[ply[0][d]] for r in rows for d in range(3))
    check(at_rest == 0. and max(last[c] for c in ply[1]) > 0. and led,
          f"cone fronts: the lower ply's {at_rest:.4g} mm while at rest, "
          f"{', '.join(f'{last[c]:.4g}' for c in ply[1])} mm at the end "
          f"(warp, weft, diagonal; above 0), never beyond the struck "
          f"ply's ({', '.join(f'{last[c]:.4g}' for c in ply[0])} mm at "
          f"the end): {'yes' if led else 'NO'}")
    if shifted:
        print(f"(lower ply moving at {moving[T]:.4g} us, the projectile "
              f"{moving[DISP]:.4g} mm down; at the end ply 1 "
              f"{last[k1]:.4g} + {last[e1]:.4g} mJ, ply 0 "
              f"{last[cols[0][0]]:.4g} + {last[cols[0][1]]:.4g} mJ)")
        return
    check(moving[DISP] < reach,
          f"lower ply moving at {moving[T]:.4g} us, the projectile "
          f"{moving[DISP]:.4g} mm down (before {reach:.4g} mm); "
          f"{moving[T] - t0:.4g} us after the first contact, "
          f"{(moving[T] - t0) / crossing:.3f} times g / v0 = "
          f"{crossing:.4g} us; at the end ply 1 {last[k1]:.4g} + "
          f"{last[e1]:.4g} mJ, ply 0 {last[cols[0][0]]:.4g} + "
          f"{last[cols[0][1]]:.4g} mJ (kinetic + strain)")


def read_cells(path):
    """Each cell's reference centre, yarn, ply, failed state, damage and
    its vertices' lowest and highest reference y."""
    text = open(path).read()
    res = {}
    for m in re.finditer(r'<DataArray type="(\w+)"([^>]*)format="binary">'
                         r'\s*(\S+)\s*</DataArray>', text):
        name = re.search(r'Name="(\w+)"', m.group(2))
        name = name.group(1) if name else "points"
        s = m.group(3)
        n_blocks = struct.unpack("<I", base64.b64decode(s[:8])[:4])[0]
        header = (((3 + n_blocks) * 4 + 2) // 3) * 4
        kind = {"Float32": "f", "Float64": "d", "Int32": "i", "UInt32": "I",
                "Int64": "q", "UInt8": "B"}[m.group(1)]
        arr = array.array(kind)
        arr.frombytes(zlib.decompress(base64.b64decode(s[header:])))
        res[name] = arr
    P, U = res["points"], res["displacement"]
    conn = res["connectivity"]
    cells = []
    # deal.II writes a cell's fields at each of its own 8 vertices.
    for c in range(len(conn) // 8):
        centre = [0., 0., 0.]
        for i in conn[8 * c:8 * c + 8]:
            for d in range(3):
                centre[d] += (P[3 * i + d] - U[3 * i + d]) / 8
        i = conn[8 * c]
        ys = [P[3 * j + 1] - U[3 * j + 1] for j in conn[8 * c:8 * c + 8]]
        cells.append((centre, int(res["yarn"][i]), int(res["ply"][i]),
                      res["failed"][i], res["damage"][i], min(ys), max(ys)))
    return cells


def broken(directory, n_warp, n_weft, s, cps):
    header, rows = history(directory)
    col = header.index("broken yarns")
    zero = all(r[col] == 0 for r in rows if r[FAILED] == 0 and r[ERODED] == 0)
    rising = all(b[col] >= a[col] for a, b in zip(rows, rows[1:]))
    last = rows[-1]
    first = next((r[T] for r in rows if r[col] > 0), float("nan"))
    failed = next((r[T] for r in rows if r[FAILED] + r[ERODED] > 0),
                  float("nan"))
    check(zero and rising and last[col] > 0,
          f"broken yarns: 0 at every row without a failed cell (the first "
          f"at {failed:.4g} us), never falling, {last[col]:.0f} at the end "
          f"(the first at {first:.4g} us; "
          f"{last[FAILED]:.0f} failed and {last[ERODED]:.0f} eroded cells)")
    error = header.index("energy error [%]")
    worst = max(abs(r[error]) for r in rows)
    check(worst < 0.5, f"energy error at most {worst:.3f} % of the initial "
          f"energy through the failures (below 0.5 %)")
    check(last[col] * 12 <= last[FAILED] + last[ERODED],
          f"broken yarns: {last[col]:.0f} x 12 cells at most the failed and "
          f"eroded ones, {last[FAILED] + last[ERODED]:.0f}")
    files = sorted(glob.glob(f"{directory}/fe_*.vtu"))
    if not files:
        check(False, f"no snapshot in {directory}")
        return
    sections = {}
    per_ply = n_warp + n_weft
    for centre, yarn, ply, failed, damage, lo, hi in read_cells(files[-1]):
        warp = yarn % per_ply < n_warp
        along = centre[0] if warp else centre[2]
        n = n_weft if warp else n_warp
        k = math.floor((along + 0.5 * n * s) / (s / cps))
        key = (yarn, k)
        total, down = sections.get(key, (0, 0))
        sections[key] = (total + 1, down + (failed != 0 or damage >= 1))
    yarns = {y for (y, k), (total, down) in sections.items() if down == total}
    check(len(yarns) == last[col], f"broken yarns in the last snapshot "
          f"({files[-1].split('/')[-1]}, {len(sections)} sections), "
          f"counted from its cells: {len(yarns)} ({sorted(yarns)}), the "
          f"history's {last[col]:.0f}")


if sys.argv[1] == "plies":
    plies(sys.argv[2], *(float(x) for x in sys.argv[3:6]),
          shifted=sys.argv[6:7] == ["shifted"])
elif sys.argv[1] == "broken":
    broken(sys.argv[2], int(sys.argv[3]), int(sys.argv[4]),
           float(sys.argv[5]), int(sys.argv[6]))
finish()
