#!/usr/bin/python3
"""The cone of a ply struck at a point, against Smith and the membrane.

Usage: check_pyramid.py TAPE_DIR TAPE_STDOUT CRIMPED_DIR CRIMPED_STDOUT

Both runs (fabric_runs.sh pyramid): a square ply of 21 x 21 yarns 1 mm
apart, every end clamped, quarter model, struck at its centre by the flat
cylinder (2.2 mm, 9.91 mg) at 600 m/s, no failure, 2.2 us. TAPE has thin
yarns (thickness semi-axis 0.02 mm) with a crimp of 0.022 mm, whose
straightening is 0.12 % of their length: the net of taut strings that the
closed forms assume. CRIMPED has the example's yarns (0.0575 mm) with a
crimp of 0.065 mm: 1.04 % of straightening, about half the strain behind
the front. Over the window [0.6, 2.2] us (the fronts have left the face's
crossings at 1 mm; the longitudinal wave, back from the clamps, has not
reached the cone) the checks are:

- The cone front along the principal yarns (the mean of the least-squares
  slopes of the history's fronts along the warp and the weft) moves at
  Smith's speed for the fabric's mass per yarn within 12 %: the jump
  conditions of check_tent.py with the crossing yarns' mass moving along
  (r = 1/2), at the window's mean projectile velocity. Both runs.
- The cone is a diamond, not a circle: a woven net has no shear stiffness,
  so the front runs along the yarns, a secondary yarn's tent starting where
  a principal yarn's front crosses it; the points reached then satisfy
  |x| + |z| <= R, whose front along the diagonal is R / sqrt(2). The
  diagonal front's slope times sqrt(2) is within 0.7 to 1.2 of the
  principal ones' (an isotropic membrane's circle gives sqrt(2) = 1.41).
  Both runs.
- The projectile's velocity lost over the window, against the diamond cone
  moving along at the projectile's velocity: from the window's start (the
  fabric's momentum P1 there, a cone mass P1 / V1), the front grown at the
  speed above, the cone's mass growing by rho_A 2 (R^2 - R1^2) (the area of
  the diamond), the momentum conserved. TAPE within 15 % of it; CRIMPED
  less than TAPE's fraction (the straightening lowers the tension behind
  the front). Both below Phoenix and Porwal's membrane from the same
  state (an isotropic membrane of speed c / sqrt(2), its cone a circle
  whose front moves at (c / sqrt(2)) sqrt(eps), eps from V = sqrt(2)
  (c / sqrt(2)) eps^(3/4)), whose circle holds more fabric than the
  diamond.
- The energy error below 0.5 % for both (the face presses the crimped
  ply's crossings deeper than the yarn contact's detection depth at the
  impact, which its touching contacts follow: doc/fe-model.md section
  8.4).

rho_A is the patch's yarn mass over its area (the set-up lines), c the
bar wave speed sqrt(EA / m), m the mass per length.
"""
import math
import os
import re
import sys

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from checks import check, finish, integrate  # noqa: E402
from check_tent import history, jump, parameter  # noqa: E402

PROJECTILE_MASS = 9.91e-6   # kg
WINDOW = (0.6, 2.2)         # us
FOOTPRINT = 1.0             # mm: the crossings under the face farthest out


def setup(stdout):
    """EA [N], mass per length [kg/m], the patch's yarn mass [kg]."""
    text = open(stdout).read()
    m = re.search(r"yarn mass ([0-9.e+-]+) mg, mass per length ([0-9.e+-]+) "
                  r"mg/m, EA ([0-9.e+-]+) N", text)
    if not m:
        sys.exit("check_pyramid.py: no set-up line in " + stdout)
    return float(m.group(3)), float(m.group(2)) * 1e-6, float(m.group(1)) * 1e-6


def cone(EA, mw, rho_A, v0, v1, R1, shape):
    """The projectile's velocity [m/s] and the front [m] at the window's
    end, from V1 and R1 at its start: SHAPE 'diamond' (Smith's speed with
    r = 1/2, area 2 R^2) or 'membrane' (Phoenix and Porwal's speed, area
    pi R^2); classical Runge-Kutta on R, 100 steps."""
    c_m = math.sqrt(EA / mw) / math.sqrt(2)
    k = 2.0 if shape == "diamond" else math.pi
    M1 = PROJECTILE_MASS * (v0 / v1 - 1)   # the cone's mass at the start

    def velocity(R):
        return PROJECTILE_MASS * v0 / (PROJECTILE_MASS + M1 + rho_A * k * (R * R - R1 * R1))

    def speed(R):
        V = velocity(R)
        if shape == "diamond":
            return jump(EA, mw, V, 0.5)[3]
        eps = (V / (math.sqrt(2) * c_m)) ** (4. / 3.)
        return c_m * math.sqrt(eps)
    R = integrate(speed, R1, (WINDOW[1] - WINDOW[0]) * 1e-6, 100)
    return velocity(R), R


def measure(run, stdout, name):
    EA, mw, mass = setup(stdout)
    c = math.sqrt(EA / mw)
    nx, nz = parameter(run, "Warp yarns"), parameter(run, "Weft yarns")
    s = parameter(run, "Yarn spacing")
    rho_A = mass / (nx * s * nz * s)
    v0 = parameter(run, "Initial velocity")
    h = history(run)
    t = h["t [us]"]
    v = h["projectile velocity [m/s]"]
    warp = h["cone front along warp [mm]"]
    weft = h["cone front along weft [mm]"]
    diag = h["cone front along diagonal [mm]"]
    inside = (t >= WINDOW[0] - 1e-9) & (t <= WINDOW[1] + 1e-9)
    slope = {k: np.polyfit(t[inside], f[inside], 1)[0] * 1e3
             for k, f in (("warp", warp), ("weft", weft), ("diagonal", diag))}
    principal = 0.5 * (slope["warp"] + slope["weft"])
    v1, v2 = np.interp(WINDOW[0], t, v), np.interp(WINDOW[1], t, v)
    vmean = np.mean(v[inside])
    U = jump(EA, mw, vmean, 0.5)[3]
    U1 = jump(EA, mw, vmean, 1.0)[3]
    c_m = c / math.sqrt(2)
    u_pp = c_m * (vmean / (math.sqrt(2) * c_m)) ** (2. / 3.)
    print("%s: rho_A %.4f kg/m^2, c %.0f m/s; fronts over [%.1f, %.1f] us: warp "
          "%.0f, weft %.0f, diagonal %.0f m/s; Smith at %.1f m/s: %.0f m/s with "
          "the crossing yarns' mass (r = 1/2), %.0f alone; Phoenix and Porwal "
          "%.0f m/s" % (name, rho_A, c, WINDOW[0], WINDOW[1], slope["warp"],
                        slope["weft"], slope["diagonal"], vmean, U, U1, u_pp))
    # The window: the cone has left the face's crossings at its start; the
    # longitudinal wave, reflected at the clamps, has not reached it at its
    # end.
    half = 0.5e3 * nx * s
    R1 = 0.5 * (np.interp(WINDOW[0], t, warp) + np.interp(WINDOW[0], t, weft))
    R2 = 0.5 * (np.interp(WINDOW[1], t, warp) + np.interp(WINDOW[1], t, weft))
    back = (2 * half - R2) / (c * 1e-3)
    check(R1 >= FOOTPRINT and back > WINDOW[1],
          "%s: the front at %.2f mm at %.1f us (past the face's crossings at "
          "%.1f mm); the longitudinal wave back at it at %.2f us, after %.1f us"
          % (name, R1, WINDOW[0], FOOTPRINT, back, WINDOW[1]))
    check(abs(principal / U - 1) < 0.12,
          "%s: the front along the principal yarns at %.0f m/s, %.3f of Smith's "
          "for the fabric's mass per yarn (within 12 %%)" % (name, principal, principal / U))
    ratio = slope["diagonal"] * math.sqrt(2) / principal
    check(0.7 < ratio < 1.2,
          "%s: the diagonal front's speed times sqrt(2) is %.3f of the principal "
          "ones' (a diamond: 1; a circle: 1.414; within 0.7 to 1.2)" % (name, ratio))
    vd, Rd = cone(EA, mw, rho_A, v0, v1, R1 * 1e-3, "diamond")
    vm, Rm = cone(EA, mw, rho_A, v0, v1, R1 * 1e-3, "membrane")
    lost = v1 - v2
    print("%s: velocity %.2f -> %.2f m/s, lost %.2f; the diamond cone %.2f "
          "(front %.2f -> %.2f mm, the run's %.2f), the membrane's circle %.2f "
          "(front %.2f mm)" % (name, v1, v2, lost, v1 - vd, R1, Rd * 1e3, R2,
                               v1 - vm, Rm * 1e3))
    check(lost < v1 - vm,
          "%s: velocity lost %.3f of Phoenix and Porwal's membrane (below 1)"
          % (name, lost / (v1 - vm)))
    err = np.max(np.abs(h["energy error [%]"]))
    check(err < 0.5, "%s: largest energy error %.3f %% (below 0.5 %%)"
          % (name, err))
    return lost / (v1 - vd)


def main():
    if len(sys.argv) != 5:
        sys.exit(__doc__)
    tape = measure(sys.argv[1], sys.argv[2], "tape")
    crimped = measure(sys.argv[3], sys.argv[4], "crimped")
    check(abs(tape - 1) < 0.15,
          "tape: velocity lost %.3f of the diamond cone's (within 15 %%)" % tape)
    check(crimped < tape,
          "crimped: velocity lost %.3f of the diamond cone's, less than the "
          "tape's %.3f" % (crimped, tape))
    finish()


if __name__ == "__main__":
    main()
