#!/usr/bin/python3
"""Checks of Model = fabric runs (fabric_runs.sh) on their history CSVs
and summaries. Prints one line per check, "ok" or "FAILED", and exits 1
if one failed.

  energy DIR        the 4 x 4 patch hit at 120 m/s by the cylinder or the
                    sphere, no failure, a history row at every step, 2.5 us:
    (1) energy balance: the projectile's lost kinetic energy against the
        yarns' kinetic, strain and contact energy (projectile and yarn
        contacts) plus the friction dissipated by both contacts, at every
        row, within 2 % of the energy lost by the end; the run's own energy
        error column within 0.3 % of the initial energy;
    (2) momentum: the projectile's momentum lost, m (v0 - v), against the
        impulse of the history's contact force, the trapezoidal sum over
        the steps (velocity Verlet's), within 1e-6 of it;
    (3) the yarn contact's forces cancel: their net force summed over all
        steps below 1e-12 of the sum of their magnitudes (summary), and
        the yarns touched (touching contacts and dissipation positive);
    (4) the yarn contact's own columns: its energy and dissipation within
        the contact and dissipated columns at every row (to their 10
        digits), and
        at the end the summary's figures (printed to 6 digits);
    (5) the primary and the secondary yarns' kinetic and strain energies
        sum to the yarns' kinetic and strain energy columns at every row,
        within 1e-9 of them (their 10 digits; the sums are reproducible
        sums of the same terms) plus 1e-15 mJ, and the primary yarns hold
        energy at the end (the secondary ones may hold none: under the
        cylinder along z of the 4 x 4 patch, the secondary weft yarns at
        x = +-1.5 mm are not touched within 2.5 us).
  fragments DIR     the V50 ply (prm/fabric/km2_ply_v50.prm) with sudden
                    failure, perforated at 550 m/s, 5 us: the fragments of
                    its broken yarns strike each other once the projectile
                    has passed. The run's energy error column below 0.5 %
                    of the initial energy at every row (3.35 % with the
                    yarn contact that kept the faces of failed cells);
                    cells failed and the yarn contact left their faces out
                    (summary); the projectile through (above 0.9 of its
                    initial velocity at the end); the yarn contact's forces
                    cancel (below 1e-12 of their magnitudes).
  momentum DIR conserved|clamped   the 4 x 4 patch of energy with
                    Fabric/Clamped edges = none (conserved) or all
                    (clamped): the total momentum along the impact
                    direction, the projectile's m v plus the history's
                    yarn momentum, against the projectile's initial m v0 at
                    every row. Free: nothing outside the projectile and the
                    yarns acts on them, and the velocity Verlet steps
                    conserve it to round-off (the contact force and the
                    yarns' internal forces are applied equal and opposite
                    in the same kicks): within 1e-9 of m v0 (the CSV's
                    projectile velocity has 10 digits). Clamped: the clamps'
                    reactions change it by more than 1e-3 of m v0 once the
                    waves reach them, which shows the check can fail.
  mirror PLUS MINUS CENTRE   the 4 x 4 patch struck by the flat cylinder
                    at (x, z) = (0.25, 0.125) mm, at its image under the half
                    turn about y, (-0.25, -0.125) mm, which maps the patch and
                    its clamps onto themselves, and at the centre, 2.5 us:
                    every column of PLUS and MINUS the same at every row,
                    within 1e-9 of the column's largest magnitude (the
                    displacements' asymmetry of check_symmetry.py is 1e-13);
                    the projectile's velocity off the centre differing from
                    the centred impact's by more than 1e-3 m/s (the offset
                    acts).
  cone DIR          1 warp yarn across 5 weft yarns struck by the cylinder,
                    no failure, 1.5 us: the history's cone front along the
                    warp (the farthest reference |x| of a surface node within
                    half a spacing of z = 0 deflected by more than 10 um)
                    against its transverse front (the farthest station, by
                    its nodes' mean current |x|, deflected by more than
                    10 um: the same front measured by other code) within
                    0.0625 mm, half a cell, at every row: a station of the
                    crimped yarn is normal to its tangent, its nodes spread
                    along x by a_y times the crimp's slope; the front past
                    0.3 mm by the end.
  single_warp FABRIC FE   1 warp yarn across 5 weft yarns and the same
                    crimped yarn alone (Model = fe), 0.5 us: until the
                    struck warp yarn reaches a weft yarn (between 0.5 and
                    0.6 us) they are the same yarn, made by other code (the
                    patch's mesh, clamps and fibre directions), hit by the
                    same projectile with the same step: the projectile's
                    velocity lost within 1 % and the yarn's kinetic plus
                    strain energy within 2 % of the FE's from 0.2 us on, and
                    no yarn contact (no touching contact, no contact energy
                    or dissipation). What differs: the crimp's phase (round-off)
                    and the steps, equal to 2e-5, which the chattering
                    projectile contact amplifies.
"""
import csv
import os
import re
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from checks import check, finish  # noqa: E402


def history(directory, name):
    with open(f"{directory}/history_{name}.csv") as f:
        rows = list(csv.reader(f))
    return [[float(x) for x in r] for r in rows[1:]]


def yarn_contact_remark(directory):
    text = open(f"{directory}/summary.txt").read()
    m = re.search(r"yarn contact: (\d+) touching contacts at the end, (\d+) "
                  r"candidate lists built, (\d+) faces of failed cells left "
                  r"out; energy (\S+) mJ, dissipated (\S+) mJ; net force "
                  r"over the sum of \|forces\|, all steps, (\S+)",
                  text)
    if not m:
        check(False, f"{directory}/summary.txt has no yarn contact remark")
        return None
    return (int(m.group(1)), int(m.group(2)), float(m.group(4)),
            float(m.group(5)), float(m.group(6)), int(m.group(3)))


# Columns of the history CSV (doc/user-guide.md, "History columns").
T, STEP, V, F, KY, KP, EL, EC, ED, EW, ERR = 0, 1, 4, 5, 6, 7, 8, 9, 10, 11, 12
FAILED = 14
MASS = 9.91e-6  # projectile mass [kg], prm/fabric/km2_patch.prm


def energy(directory):
    rows = history(directory, "fabric")
    kp0 = rows[0][KP]
    lost_end = kp0 - rows[-1][KP]
    worst = max(abs(r[KY] + r[EL] + r[EC] + r[ED] - (kp0 - r[KP]))
                for r in rows)
    check(worst <= 0.02 * lost_end,
          f"energy balance: largest |yarn kinetic + strain + contact + "
          f"dissipated - projectile energy lost| {worst:.4g} mJ, "
          f"{100 * worst / lost_end:.3f} % of the {lost_end:.4g} mJ lost "
          f"(at most 2 %)")
    err = max(abs(r[ERR]) for r in rows)
    check(err <= 0.3, f"energy error column: largest {err:.4g} % of the "
          f"initial energy (at most 0.3 %)")
    steps = all(b[STEP] == a[STEP] + 1 for a, b in zip(rows, rows[1:]))
    check(steps, "a history row at every step")
    impulse = sum(0.5 * (b[T] - a[T]) * 1e-6 * (a[F] + b[F])
                  for a, b in zip(rows, rows[1:]))
    momentum = MASS * (rows[0][V] - rows[-1][V])
    rel = abs(impulse - momentum) / momentum
    check(rel <= 1e-6, f"momentum: projectile's lost {momentum:.8g} kg m/s, "
          f"impulse of the contact force {impulse:.8g} N s, relative "
          f"difference {rel:.2g} (at most 1e-6)")
    remark = yarn_contact_remark(directory)
    if remark:
        touching, builds, e, d, balance, _ = remark
        check(touching > 0 and d > 0,
              f"yarn contact engaged: {touching} touching contacts at the "
              f"end, {d:.4g} mJ dissipated by friction, {e:.4g} mJ stored")
        check(balance < 1e-12, f"yarn contact forces cancel: net over "
              f"magnitudes {balance:.3g} (below 1e-12)")
        with open(f"{directory}/history_fabric.csv") as f:
            header = next(csv.reader(f))
        ce = header.index("yarn contact energy [mJ]")
        cd = header.index("yarn contact dissipated energy [mJ]")
        inside = all(0 <= r[ce] <= r[EC] * (1 + 1e-9) + 1e-12 and
                     0 <= r[cd] <= r[ED] * (1 + 1e-9) + 1e-12 for r in rows)
        end = abs(rows[-1][ce] - e) <= 1e-5 * max(e, 1e-12) and \
            abs(rows[-1][cd] - d) <= 1e-5 * d
        check(inside and end, f"yarn contact columns: within the contact "
              f"and dissipated columns at every row; at the end "
              f"{rows[-1][ce]:.6g} and {rows[-1][cd]:.6g} mJ, the summary's "
              f"{e:.6g} and {d:.6g} mJ")
    groups(directory, rows)


def fragments(directory):
    rows = history(directory, "fabric")
    err = max(abs(r[ERR]) for r in rows)
    check(err < 0.5, f"fragments: largest energy error {err:.4g} % of the "
          f"initial energy (below 0.5 %)")
    failed = rows[-1][FAILED]
    check(failed > 0 and rows[-1][V] > 0.9 * rows[0][V],
          f"fragments: {failed:.0f} failed cells, the projectile through at "
          f"{rows[-1][V]:.2f} m/s of {rows[0][V]:.0f}")
    remark = yarn_contact_remark(directory)
    if remark:
        balance, removed = remark[4], remark[5]
        check(removed > 0, f"fragments: {removed} faces of failed cells "
              f"left out of the yarn contact")
        check(balance < 1e-12, f"fragments: yarn contact forces cancel: "
              f"net over magnitudes {balance:.3g} (below 1e-12)")


def groups(directory, rows):
    with open(f"{directory}/history_fabric.csv") as f:
        header = next(csv.reader(f))
    pk, pe, sk, se = (header.index(f"{g} yarns {e} energy [mJ]")
                      for g in ("primary", "secondary")
                      for e in ("kinetic", "strain"))
    worst = max(max(abs(r[pk] + r[sk] - r[KY]) / (abs(r[KY]) + 1e-6),
                    abs(r[pe] + r[se] - r[EL]) / (abs(r[EL]) + 1e-6))
                for r in rows)
    ok = all(abs(r[pk] + r[sk] - r[KY]) <= 1e-9 * abs(r[KY]) + 1e-15 and
             abs(r[pe] + r[se] - r[EL]) <= 1e-9 * abs(r[EL]) + 1e-15
             for r in rows)
    last = rows[-1]
    some = last[pk] + last[pe] > 0
    check(ok and some, f"primary + secondary yarns: their kinetic and "
          f"strain energies sum to the yarns' within {worst:.3g} of them (at "
          f"most 1e-9 plus 1e-15 mJ); at the end primary {last[pk]:.4g} + "
          f"{last[pe]:.4g} mJ, secondary {last[sk]:.4g} + {last[se]:.4g} mJ")


def momentum(directory, mode):
    with open(f"{directory}/history_fabric.csv") as f:
        header = next(csv.reader(f))
    col = header.index("yarn momentum [kg m/s]")
    rows = history(directory, "fabric")
    p0 = MASS * rows[0][V]
    worst = max(abs(MASS * r[V] + r[col] - p0) for r in rows) / p0
    if mode == "conserved":
        check(worst <= 1e-9, f"momentum of a free patch: largest |m v + yarn "
              f"momentum - m v0| {worst:.3g} of m v0 = {p0:.8g} kg m/s over "
              f"{len(rows)} rows (at most 1e-9)")
    else:
        check(worst > 1e-3, f"momentum of a clamped patch: largest |m v + "
              f"yarn momentum - m v0| {worst:.3g} of m v0 (the clamps' "
              f"reactions: above 1e-3)")


def mirror(plus_dir, minus_dir, centre_dir):
    plus = history(plus_dir, "fabric")
    minus = history(minus_dir, "fabric")
    centre = history(centre_dir, "fabric")
    same = len(plus) == len(minus)
    worst = 0.
    for c in range(len(plus[0])):
        scale = max(abs(r[c]) for r in plus)
        if scale > 0.:
            worst = max(worst, max(abs(a[c] - b[c]) for a, b in
                                   zip(plus, minus)) / scale)
    check(same and worst <= 1e-9, f"mirror: the impacts at (0.25, 0.125) and "
          f"(-0.25, -0.125) mm, {len(plus)} and {len(minus)} rows, largest "
          f"difference {worst:.3g} of a column's largest magnitude (at most "
          f"1e-9)")
    dv = max(abs(a[V] - b[V]) for a, b in zip(plus, centre))
    check(dv > 1e-3, f"offset: the projectile's velocity differs from the "
          f"centred impact's by up to {dv:.4g} m/s (above 1e-3)")


def cone(directory):
    with open(f"{directory}/history_fabric.csv") as f:
        header = next(csv.reader(f))
    cw = header.index("cone front along warp [mm]")
    tf = header.index("transverse front [mm]")
    rows = history(directory, "fabric")
    worst = max(abs(r[cw] - r[tf]) for r in rows)
    check(worst <= 0.0625 and rows[-1][cw] > 0.3,
          f"cone front along the warp against the transverse front: largest "
          f"difference {worst:.4g} mm over {len(rows)} rows (at most 0.0625 "
          f"mm); at the end {rows[-1][cw]:.4g} and {rows[-1][tf]:.4g} mm "
          f"(past 0.3 mm)")


def interpolate(rows, col, t):
    for a, b in zip(rows, rows[1:]):
        if a[T] <= t <= b[T]:
            w = (t - a[T]) / (b[T] - a[T])
            return (1 - w) * a[col] + w * b[col]
    return rows[-1][col]


def single_warp(fabric_dir, fe_dir):
    fab = history(fabric_dir, "fabric")
    fe = history(fe_dir, "fe")
    worst_v = worst_e = 0.
    for r in fab:
        if r[T] < 0.2 or r[T] > fe[-1][T]:
            continue
        dv_fe = fe[0][V] - interpolate(fe, V, r[T])
        e_fe = interpolate(fe, KY, r[T]) + interpolate(fe, EL, r[T])
        worst_v = max(worst_v, abs((fab[0][V] - r[V]) - dv_fe) / dv_fe)
        worst_e = max(worst_e, abs(r[KY] + r[EL] - e_fe) / e_fe)
    check(worst_v <= 0.01, f"projectile velocity lost: largest difference "
          f"{100 * worst_v:.3f} % of the FE yarn's (at most 1 %)")
    check(worst_e <= 0.02, f"yarn kinetic plus strain energy: largest "
          f"difference {100 * worst_e:.3f} % of the FE yarn's (at most 2 %)")
    remark = yarn_contact_remark(fabric_dir)
    if remark:
        touching, builds, e, d, balance, _ = remark
        check(touching == 0 and d == 0 and e == 0,
              f"no yarn contact: {touching} touching contacts, {e} mJ "
              f"stored, {d} mJ dissipated")


if sys.argv[1] == "energy":
    energy(sys.argv[2])
elif sys.argv[1] == "fragments":
    fragments(sys.argv[2])
elif sys.argv[1] == "momentum":
    momentum(sys.argv[2], sys.argv[3])
elif sys.argv[1] == "mirror":
    mirror(sys.argv[2], sys.argv[3], sys.argv[4])
elif sys.argv[1] == "cone":
    cone(sys.argv[2])
elif sys.argv[1] == "single_warp":
    single_warp(sys.argv[2], sys.argv[3])
finish()
