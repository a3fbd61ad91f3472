#!/usr/bin/python3
"""Write the LAMMPS data file of YarnImpact's DEM yarn (the whole yarn, no
symmetry) and an include file with the derived parameters for yarn.in.

The layout is the one of source/dem/packing.cc (hexagonal_packing, without
the quarter-symmetry rule) and source/dem/fibre_chains.cc:
  - fibre centres: the sites of a hexagonal lattice of spacing d (rows along
    z, row distance sqrt(3)/2 d, odd rows shifted by d/2), the N closest to
    the centre in the ellipse norm rho = sqrt((y/a_y)^2 + (z/a_z)^2), ties
    ordered by (|y|, |z|, y, z); the ellipse "enlargement" is max(1, rho_max)
    (1.0195 for the paper's 400 fibres); centres multiplied by (1 + 1e-9) so
    that touching neighbours start 1e-9 d apart;
  - stations: n = 2 ceil(L / (2 s)) equal trusses of L0 = L / n along x in
    [-L/2, L/2] (the paper: n = 2118, L0 = 11.992 um, 2119 spheres a fibre);
  - sphere mass rho_f A_f L0 (A_f = pi d^2 / 4): the fibre's mass per length;
  - truss stiffness k = E A_f / L0 (LAMMPS bond harmonic: K = k / 2).
x: along the yarn, y: thickness (impact direction, the projectile moves to
-y), z: width (the projectile's axis). Units: SI.

Atom types: 1 = free spheres, 2 = clamped spheres (both end sections).
Only python3 + numpy (Debian's python3-numpy).
"""

import argparse
import math
import sys

import numpy as np


def hexagonal_packing(n, d, a_y, a_z, max_scale=1.1):
    h = 0.5 * math.sqrt(3.0) * d
    rows = int(math.ceil(max_scale * a_y / h)) + 2
    cols = int(math.ceil(max_scale * a_z / d)) + 2
    sites = []
    for j in range(-rows, rows + 1):
        for i in range(-cols, cols + 1):
            y = j * h
            z = (i + 0.5 * (abs(j) % 2)) * d
            rho = math.sqrt((y / a_y) ** 2 + (z / a_z) ** 2)
            if rho <= max_scale * (1.0 + 1e-12):
                sites.append((rho, abs(y), abs(z), y, z))
    sites.sort()
    if len(sites) < n:
        sys.exit("make_yarn.py: only %d fibres fit in the ellipse enlarged by %g"
                 % (len(sites), max_scale))
    sel = sites[:n]
    scale = max(1.0, max(s[0] for s in sel))
    y = np.array([s[3] for s in sel]) * (1.0 + 1e-9)
    z = np.array([s[4] for s in sel]) * (1.0 + 1e-9)
    return y, z, scale


def main():
    p = argparse.ArgumentParser(description=__doc__,
                                formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--fibres", type=int, default=400)
    p.add_argument("--length", type=float, default=25.4e-3, help="yarn length between the clamps [m]")
    p.add_argument("--diameter", type=float, default=12e-6, help="fibre (sphere) diameter [m]")
    p.add_argument("--spacing", type=float, default=12e-6, help="largest sphere spacing [m]")
    p.add_argument("--a-y", type=float, default=0.0575e-3, help="thickness semi-axis [m]")
    p.add_argument("--a-z", type=float, default=0.267e-3, help="width semi-axis [m]")
    p.add_argument("--modulus", type=float, default=84.62e9, help="fibre Young modulus [Pa]")
    p.add_argument("--density", type=float, default=1440.0, help="fibre density [kg/m^3]")
    p.add_argument("--contact-ratio", type=float, default=0.2,
                   help="normal contact stiffness / truss stiffness (fibre-fibre and projectile)")
    p.add_argument("--tangential-ratio", type=float, default=2.0 / 7.0)
    p.add_argument("--damping-ratio", type=float, default=0.1)
    p.add_argument("--friction", type=float, default=0.2)
    p.add_argument("--proj-diameter", type=float, default=2.2e-3)
    p.add_argument("--proj-speed", type=float, default=120.0)
    p.add_argument("--data", default="yarn.data")
    p.add_argument("--params", default="yarn_params.in")
    a = p.parse_args()

    d = a.diameter
    r = 0.5 * d
    fy, fz, scale = hexagonal_packing(a.fibres, d, a.a_y, a.a_z)
    nf = len(fy)
    n_seg = 2 * int(math.ceil(a.length / (2.0 * a.spacing) - 1e-9))
    L0 = a.length / n_seg
    ns = n_seg + 1
    xs = -0.5 * a.length + L0 * np.arange(ns)
    xs[-1] = 0.5 * a.length

    area = math.pi * d * d / 4.0
    m = a.density * area * L0
    k = a.modulus * area / L0
    vol = math.pi / 6.0 * d ** 3
    rho_sphere = m / vol  # LAMMPS sphere density that gives the mass m
    kn = a.contact_ratio * k
    kt = a.tangential_ratio * kn
    zeta = a.damping_ratio
    # LAMMPS gran/hooke: F_damp = m_eff gamma_n v_n; ours c_n = 2 zeta sqrt(m_eff k_n)
    gamma_pair = 2.0 * zeta * math.sqrt(kn / (0.5 * m))  # m_eff = m/2
    gamma_wall = 2.0 * zeta * math.sqrt(kn / m)  # m_eff = m (rigid wall)
    R = 0.5 * a.proj_diameter
    ytop = float(np.max(fy)) + r
    yc = ytop + R  # the projectile starts touching the top of the yarn

    # Atoms: fibre f, station s -> id = f * ns + s + 1
    natoms = nf * ns
    nbonds = nf * n_seg
    ids = np.arange(1, natoms + 1)
    X = np.tile(xs, nf)
    Y = np.repeat(fy, ns)
    Z = np.repeat(fz, ns)
    st = np.tile(np.arange(ns), nf)
    types = np.where((st == 0) | (st == ns - 1), 2, 1)
    mol = np.repeat(np.arange(1, nf + 1), ns)

    margin = 4.0 * d
    ymin, ymax = float(fy.min()) - r, ytop
    zmin, zmax = float(fz.min()) - r, float(fz.max()) + r
    with open(a.data, "w") as f:
        f.write("YarnImpact DEM yarn: %d fibres x %d spheres, L = %.6g m, L0 = %.10g m, "
                "packing scale %.6f\n\n" % (nf, ns, a.length, L0, scale))
        f.write("%d atoms\n%d bonds\n2 atom types\n1 bond types\n\n" % (natoms, nbonds))
        f.write("%.17g %.17g xlo xhi\n" % (-0.5 * a.length - margin, 0.5 * a.length + margin))
        f.write("%.17g %.17g ylo yhi\n" % (ymin - margin, ymax + margin))
        f.write("%.17g %.17g zlo zhi\n\n" % (zmin - margin, zmax + margin))
        # atom_style hybrid sphere bond: id type x y z diameter density molecule
        f.write("Atoms # hybrid\n\n")
        rows = np.empty((natoms, 3))
        rows[:, 0], rows[:, 1], rows[:, 2] = X, Y, Z
        lines = ["%d %d %.17g %.17g %.17g %.17g %.17g %d\n"
                 % (i, t, x, y, z, d, rho_sphere, mo)
                 for i, t, (x, y, z), mo in zip(ids.tolist(), types.tolist(),
                                                rows.tolist(), mol.tolist())]
        f.writelines(lines)
        f.write("\nBonds\n\n")
        b1 = (np.arange(nf)[:, None] * ns + np.arange(n_seg)[None, :] + 1).ravel()
        bid = np.arange(1, nbonds + 1)
        np.savetxt(f, np.column_stack([bid, np.ones(nbonds, dtype=np.int64), b1, b1 + 1]),
                   fmt="%d")

    with open(a.params, "w") as f:
        f.write("# Written by make_yarn.py: derived parameters (SI units)\n")
        f.write("variable nfibres  equal %d\n" % nf)
        f.write("variable nstation equal %d\n" % ns)
        f.write("variable L0       equal %.17g\n" % L0)
        f.write("variable msphere  equal %.17g\n" % m)
        f.write("variable ktruss   equal %.17g\n" % k)
        f.write("variable Kbond    equal %.17g  # bond harmonic E = K (r - r0)^2: K = k/2\n" % (0.5 * k))
        f.write("variable kn       equal %.17g\n" % kn)
        f.write("variable kt       equal %.17g\n" % kt)
        f.write("variable gn_pair  equal %.17g  # 2 zeta sqrt(kn / (m/2)) [1/s]\n" % gamma_pair)
        f.write("variable gn_wall  equal %.17g  # 2 zeta sqrt(kn / m) [1/s]\n" % gamma_wall)
        f.write("variable mu       equal %.17g\n" % a.friction)
        f.write("variable Rproj    equal %.17g\n" % R)
        f.write("variable yproj0   equal %.17g  # projectile axis at start (touching)\n" % yc)
        f.write("variable vproj    equal %.17g\n" % a.proj_speed)
        f.write("variable ytop     equal %.17g\n" % ytop)
        f.write("variable rsphere  equal %.17g\n" % r)

    print("make_yarn.py: %d fibres (packing scale %.4f), %d spheres a fibre, L0 = %.6g m, "
          "%d atoms, %d bonds; m = %.5g kg, k = %.5g N/m, kn = %.5g N/m, kt = %.5g N/m; "
          "sqrt(m/k) = %.4g s -> %s, %s"
          % (nf, scale, ns, L0, natoms, nbonds, m, k, kn, kt, math.sqrt(m / k), a.data, a.params))


if __name__ == "__main__":
    main()
