#!/usr/bin/env python3
"""Identify the FE progressive fibre-failure law from the DEM's output.

The law (doc/theory.md section 5) has the onset, the largest Gauss-point
fibre strain of a cell at which its fibres start to break, its spread
across the section, G_f, the energy dissipated per unit area of a crack
across the yarn, and the tail of a bilinear softening curve. They are
taken from the DEM, not from the FE impact curve:

1. The DEM tension test to failure (prm/elementary/tension.prm, its
   elementary_tension.csv): the strain of the first fibre break is the
   onset, and the spread of break strains (last minus first) the width of
   the failure in homogeneous tension. In this test every fibre sees the
   same strain, so the spread is zero and the energy the segment releases
   is the elastic energy of a 48 um periodic segment: W_0 times its
   length, a property of the segment, not a fracture energy (printed, not
   used).
2. The DEM impact (history_dem.csv of prm/km2_120ms_dem.prm): the fibres
   break one after another from the first break to the cut-through. The
   energy the DEM yarn dissipates in that interval, less the friction and
   damping it dissipated at the rate it had before the first break, is the
   energy the failure dissipates. Divided by the number of crack bands the
   FE forms (2: its impact point is a node layer, and the cells on both
   sides soften together, measured in doc/validation.md section 6) and by
   the FE section area (pi a_y a_z), it is G_f.
3. The onset, calibrated at 120 m/s. The DEM tension test gives the
   fibres' break strain (4.52 %), but an FE cell averages some 30 fibres
   over 0.254 mm and does not resolve the strain peak of the fibres on
   the nose when the reflected transverse wave comes back: at the DEM's
   first break (29.6 us, a fibre at 4.52 %) the FE's largest cell strain
   is below 3.6 %. The onset is therefore the largest cell strain the FE
   (run without failure, FE_HISTORY: prm/study/fe_no_failure.prm) has
   reached up to the DEM's first break: the FE cell starts breaking when
   it is strained beyond the state in which the DEM's first fibre broke.
   This is one calibration at one velocity (the first-break time), done
   on the FE strain history, not on its velocity; 200 and 300 m/s verify
   it without recalibrating (doc/validation.md section 6).

4. The spread of the onset across the section (doc/theory.md section
   5.4). The DEM's fibres break in the order of their depth below the
   struck face, the first at the DEM's first break and the last at its
   cut-through; a cell at the back face holds the last ones. By the same
   rule as 3, the back face's onset is the largest cell strain the FE
   without failure has reached up to the DEM's cut-through, and the
   spread s is its ratio to the onset, less 1 (Yarn/Damage onset spread:
   eps_0 (1 + s z), z the depth). Again on the FE strain history and the
   DEM's break times, not on the velocity.
5. The tail of the softening (doc/theory.md section 5.5). After its
   peak the DEM's contact force falls within about a microsecond to a
   plateau, an eighth of the peak, which it holds while the last fibres
   break, until the cut-through. The plateau force is the median force
   from the first row below half the peak to the cut-through; its ratio
   to the peak is the tail stress beta (Yarn/Softening tail stress: the
   angle of the yarn at the nose is taken to be the same at the peak and
   on the plateau, so the force ratio is the ratio of the fibre
   tensions). The kink is the first row after the peak at which the force
   is within 25 % of the plateau force; the energy the failure dissipates
   from there to the cut-through (less the friction trend, as in 2), per
   band and unit area, is the tail energy G_t (Yarn/Softening tail
   energy).

Usage:
  scripts/identify_fibre_failure.py TENSION_SUMMARY TENSION_CSV DEM_HISTORY_CSV
      FE_HISTORY_CSV [--bands 2]

TENSION_SUMMARY is the test's summary.txt: its line "fibre break strains:
min, mean, max" gives the break strains of the fibres exactly (the CSV
samples the strain every 0.1 %).

Prints the identified values and the checks the FE validation applies
(G_f above the elastic energy per area of a cell at the onset).
"""

import argparse
import csv
import math
import sys


def read_csv(path):
    with open(path, newline="") as f:
        rows = list(csv.reader(f))
    header = rows[0]
    def number(x):
        try:
            return float(x)
        except ValueError:
            return math.nan  # text columns (loading, phase)

    data = [[number(x) for x in r] for r in rows[1:] if r]
    return header, data


def column(header, name):
    for i, h in enumerate(header):
        if h == name:
            return i
    sys.exit(f"{name!r}: no such column (have {header})")


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("tension_summary")
    ap.add_argument("tension_csv")
    ap.add_argument("dem_history_csv")
    ap.add_argument("fe_history_csv",
                    help="FE history at 120 m/s without failure")
    ap.add_argument("--bands", type=int, default=2,
                    help="crack bands the FE forms at the impact point [-]")
    ap.add_argument("--thickness-semi-axis", type=float, default=0.0575e-3,
                    help="FE ellipse semi-axis a_y [m]")
    ap.add_argument("--width-semi-axis", type=float, default=0.267e-3,
                    help="FE ellipse semi-axis a_z [m]")
    ap.add_argument("--k-e", type=float, default=80077.19e6,
                    help="FE fibre modulus k_e [Pa]")
    ap.add_argument("--cell-length", type=float, default=0.254e-3,
                    help="FE cell length along the yarn [m] (paper's mesh)")
    a = ap.parse_args()

    # 1. Tension to failure.
    h, rows = read_csv(a.tension_csv)
    i_eps = column(h, "imposed_strain")
    i_broken = column(h, "broken_fibres")
    i_truss = column(h, "truss_energy")
    i_tau = column(h, "tau_xx")
    first = next(r for r in rows if r[i_broken] > 0)
    last = next(r for r in rows if r[i_broken] >= max(x[i_broken] for x in rows))
    before = rows[rows.index(first) - 1]
    eps_first, eps_last = first[i_eps], last[i_eps]
    print("DEM tension test to failure (%s)" % a.tension_csv)
    print("  first fibre break between the samples %.4f and %.4f %%"
          % (100 * before[i_eps], 100 * eps_first))
    print("  all fibres broken by the sample       %.4f %%" % (100 * eps_last))
    with open(a.tension_summary) as f:
        line = next(l for l in f if "fibre break strains" in l)
    values = line.split("max")[1].split("%")[0].split(",")
    eps_min, eps_mean, eps_max = (float(x) / 100 for x in values)
    std = float(line.split("std")[1].split("%")[0]) / 100
    print("  fibre break strains (summary): min %.4f %%, max %.4f %%, "
          "std %.4f %%" % (100 * eps_min, 100 * eps_max, 100 * std))
    print("  spread of break strains               %.4f %%"
          % (100 * (eps_max - eps_min)))
    eps_first = eps_min
    print("  peak axial Kirchhoff stress           %.1f MPa"
          % (max(r[i_tau] for r in rows) * 1e-6))
    print("  truss energy released at the break    %.4e J (the segment's "
          "elastic energy, not a fracture energy)"
          % (before[i_truss] - last[i_truss]))

    # 2. The impact.
    h, rows = read_csv(a.dem_history_csv)
    i_t = column(h, "t [us]")
    i_f = column(h, "failed elements")
    i_d = column(h, "dissipated energy [mJ]")
    i_F = column(h, "contact force [N]")
    i_v = column(h, "projectile velocity [m/s]")
    k1 = next(k for k, r in enumerate(rows) if r[i_f] > 0)
    t1 = rows[k1][i_t]
    # Cut-through: the first row after the first break where the contact
    # force is below 2 % of its peak (the yarn no longer holds the nose).
    peak = max(r[i_F] for r in rows[k1:])
    k2 = next(k for k in range(k1, len(rows)) if rows[k][i_F] < 0.02 * peak)
    t2 = rows[k2][i_t]
    # Friction and damping rate before the break, over the 3 us before it.
    k0 = next(k for k, r in enumerate(rows) if r[i_t] >= t1 - 3.0)
    kb = k1 - 1
    rate = (rows[kb][i_d] - rows[k0][i_d]) / (rows[kb][i_t] - rows[k0][i_t])
    dE = (rows[k2][i_d] - rows[kb][i_d]) - rate * (t2 - rows[kb][i_t])
    area = math.pi * a.thickness_semi_axis * a.width_semi_axis
    G_f = dE * 1e-3 / (a.bands * area)
    print("DEM impact (%s)" % a.dem_history_csv)
    print("  first break                            %.2f us" % t1)
    print("  cut through (force below 2 %% of its peak %.1f N) %.2f us"
          % (peak, t2))
    print("  projectile velocity at first break, cut  %.2f, %.2f m/s"
          % (rows[kb][i_v], rows[k2][i_v]))
    print("  dissipation rate before the break      %.4f mJ/us" % rate)
    print("  energy dissipated by the failure       %.3f mJ" % dE)
    print("  FE section area                        %.6f mm^2" % (area * 1e6))

    # 5. The tail: the plateau after the force's fall, and the energy
    # dissipated on it.
    k_peak = max(range(k1, k2), key=lambda k: rows[k][i_F])
    k_half = next(k for k in range(k_peak, k2) if rows[k][i_F] < 0.5 * peak)
    plateau = sorted(rows[k][i_F] for k in range(k_half, k2))
    F_p = plateau[len(plateau) // 2]
    beta = F_p / peak
    k_kink = next(k for k in range(k_peak, k2) if rows[k][i_F] <= 1.25 * F_p)
    t_kink = rows[k_kink][i_t]
    dE_tail = (rows[k2][i_d] - rows[k_kink][i_d]) - rate * (t2 - t_kink)
    G_t = dE_tail * 1e-3 / (a.bands * area)
    print("  plateau force (median, %.2f-%.2f us)   %.2f N (%.3f of the peak)"
          % (rows[k_half][i_t], t2, F_p, beta))
    print("  force within 25 %% of the plateau from  %.2f us" % t_kink)
    print("  energy dissipated from there to the cut  %.3f mJ" % dE_tail)

    # 3. The onset.
    h, rows = read_csv(a.fe_history_csv)
    i_t = column(h, "t [us]")
    i_s = column(h, "max longitudinal strain [-]")
    before = [r for r in rows if r[i_t] <= t1 + 1e-9]
    k = max(range(len(before)), key=lambda j: before[j][i_s])
    onset = before[k][i_s]
    after = next((r for r in rows if r[i_t] > t1 and r[i_s] > onset), None)
    print("FE without failure (%s)" % a.fe_history_csv)
    print("  largest cell strain up to the DEM's first break  %.4f %% "
          "(at %.2f us)" % (100 * onset, before[k][i_t]))
    if after:
        print("  first passed after it at               %.2f us"
              % after[i_t])
    print("  DEM fibre break strain / FE onset      %.3f"
          % (eps_first / onset))

    upto_cut = [r for r in rows if r[i_t] <= t2 + 1e-9]
    onset_back = max(r[i_s] for r in upto_cut)
    spread = onset_back / onset - 1.
    print("  largest cell strain up to the DEM's cut-through  %.4f %% "
          "(%.2f us)" % (100 * onset_back, t2))
    # The admissible G_f is set by the largest onset, the back face's.
    I0 = math.log1p(onset_back)
    G_min = 0.5 * a.cell_length * a.k_e * I0 * I0
    I_u = 2 * G_f / (a.cell_length * a.k_e * I0)
    print("Identified")
    print("  Yarn/Failure strain (fibres, DEM)      %.4f" % eps_first)
    print("  Yarn/Damage onset strain               %.4f" % onset)
    print("  Yarn/Damage onset spread               %.3f (back-face onset "
          "%.4f)" % (spread, onset_back))
    print("  Yarn/Fracture energy G_f               %.4g J/m^2 (%d bands)"
          % (G_f, a.bands))
    print("  Yarn/Softening tail stress             %.3f" % beta)
    print("  Yarn/Softening tail energy G_t         %.4g J/m^2 (%d bands)"
          % (G_t, a.bands))
    I0_face = math.log1p(onset)
    I_k = beta * I0_face + 2 * (G_f - G_t) / (a.cell_length * a.k_e * I0_face)
    I_u_tail = 2 * G_t / (a.cell_length * a.k_e * beta * I0_face)
    print("  its kink and end in a %.3f mm cell at the struck face   "
          "%.2f %%, %.2f %% fibre strain"
          % (a.cell_length * 1e3, 100 * math.expm1(I_k),
             100 * math.expm1(I_u_tail)))
    print("  elastic energy per area of a %.3f mm cell at the back-face "
          "onset  %.4g J/m^2"
          % (a.cell_length * 1e3, G_min))
    print("  final fibre strain of that cell (linear curve)  %.2f %%"
          % (100 * math.expm1(I_u)))
    if G_f <= G_min:
        sys.exit("G_f is not above the cell's elastic energy: snap-back")


if __name__ == "__main__":
    main()
