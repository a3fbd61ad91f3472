#!/usr/bin/python3
"""The tent of a strip of warp yarns struck along a line, against Smith.

Usage: check_tent.py WIDE_DIR WIDE_STDOUT NARROW_DIR NARROW_STDOUT

Both runs (fabric_runs.sh tent): 3 warp yarns along x, their ends clamped,
across weft yarns with free ends, struck by a thin cylinder along z (the
line impact: every warp yarn is loaded alike, each as a yarn hit by
Smith's projectile), no failure. WIDE has its weft yarns 4 mm apart, NARROW
1 mm apart. Over the window [1, 4] us (the tent has left the cylinder, the
longitudinal wave has not reached the clamps) the checks are:

- Smith's jump conditions for one warp yarn alone (EA and mass per length
  from the run's set-up lines; linear tension E A eps, whose force the
  run's own Smith line, with the law's nonlinear stress, confirms within
  2 %) integrated from the velocity at 1 us give the velocity lost by
  4 us within 6 % of the WIDE run's, and the tent's front speed (the
  least-squares slope of the history's cone front along the warp, in
  reference coordinates) within 12 %: with weft yarns 4 mm apart the weft
  hardly loads the warp (crimp 0.07 % of length, one crossing per 4 mm).
- NARROW loses more velocity than WIDE (by at least 0.08 of Smith's loss):
  the weft yarns' inertia adds to the warp's where they are dense; and less
  than the same jump conditions with the weft's whole mass moving with the
  warp across the fabric (r = 1/2 below), the bound of a fully engaged weft.
- The longitudinal front short of the clamps and the energy error below
  0.5 % in both runs.

The jump conditions, Lagrangian, across the kink moving at U (mass per
length m_w of the warp for the axial motion, m_T = m_w / r with the weft
moving along for the transverse one; eps0 ahead, eps1 behind, theta the
arms' angle, the arms moving at (0, -V), the material ahead flowing in at
w = c eps0):
  U^2 = T(eps1) / (m_T (1 + eps1)),  V = U (1 + eps1) sin(theta),
  c eps0 = U ((1 + eps0) - (1 + eps1) cos(theta)),
  T(eps0) - T(eps1) cos(theta) = m_w U c eps0.
With r = 1 they are Smith's (eps0 = eps1); the force of the two arms on the
projectile is 2 T(eps1) sin(theta).
"""
import csv
import math
import os
import re
import sys

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from checks import check, finish, integrate  # noqa: E402

N_WARP = 3            # warp yarns of the strip (the whole patch)
PROJECTILE_MASS = 9.91e-6
WINDOW = (1.0, 4.0)   # us


def setup(stdout):
    """EA [N], mass per length [kg/m] and the run's own Smith line."""
    text = open(stdout).read()
    m = re.search(r"mass per length ([0-9.e+-]+) mg/m, EA ([0-9.e+-]+) N", text)
    s = re.search(r"Smith theory at ([0-9.e+-]+) m/s: strain ([0-9.e+-]+), "
                  r"transverse wave ([0-9.e+-]+) m/s, deceleration ([0-9.e+-]+)",
                  text)
    if not m or not s:
        sys.exit("check_tent.py: no set-up lines in " + stdout)
    return (float(m.group(2)), float(m.group(1)) * 1e-6,
            {"v": float(s.group(1)), "decel": float(s.group(4))})


def jump(EA, mw, V, r):
    """(eps0, eps1, theta, U) of the kink at projectile speed V [m/s]."""
    c = math.sqrt(EA / mw)
    mT = mw / r

    def speed(e1):
        return math.sqrt(EA * e1 / (mT * (1 + e1)))

    def g(x):
        e0, e1, th = x
        U = speed(e1)
        return np.array([
            V - U * (1 + e1) * math.sin(th),
            c * e0 - U * ((1 + e0) - (1 + e1) * math.cos(th)),
            EA * e0 - EA * e1 * math.cos(th) - mw * U * c * e0])
    # Start from Smith's small-strain estimate; Newton, numerical Jacobian.
    e = 0.6 * (V / c) ** (4. / 3.)
    x = np.array([e, e, math.asin(min(0.99, V / (c * math.sqrt(e))))])
    for _ in range(60):
        f = g(x)
        J = np.empty((3, 3))
        for k in range(3):
            d = np.zeros(3)
            d[k] = 1e-9 * max(abs(x[k]), 1e-6)
            J[:, k] = (g(x + d) - f) / d[k]
        step = np.linalg.solve(J, -f)
        x = x + step
        if np.max(np.abs(step)) < 1e-14:
            break
    e0, e1, th = x
    return e0, e1, th, speed(e1)


def force(EA, mw, V, r):
    """Force of the two arms of one warp yarn on the projectile [N]."""
    _, e1, th, _ = jump(EA, mw, V, r)
    return 2 * EA * e1 * math.sin(th)


def smith_loss(EA, mw, v1, r, duration):
    """Velocity lost over DURATION [s] from v1 under N_WARP yarns' force
    (classical Runge-Kutta, 60 steps)."""
    def a(u):
        return -N_WARP * force(EA, mw, u, r) / PROJECTILE_MASS
    return v1 - integrate(a, v1, duration, 60)


def parameter(run, name):
    """A number of the run's parameters.prm."""
    text = open(run + "/parameters.prm").read()
    return float(re.search(r"set %s\s*=\s*([0-9.e+-]+)" % name, text).group(1))


def history(run):
    with open(run + "/history_fabric.csv") as f:
        rows = list(csv.DictReader(f))
    return {k: np.array([float(r[k]) for r in rows]) for k in rows[0]}


def measure(run, stdout, name):
    EA, mw, own = setup(stdout)
    h = history(run)
    t = h["t [us]"]
    v = h["projectile velocity [m/s]"]
    v1, v4 = np.interp(WINDOW[0], t, v), np.interp(WINDOW[1], t, v)
    duration = (WINDOW[1] - WINDOW[0]) * 1e-6
    bare = smith_loss(EA, mw, v1, 1.0, duration)
    full = smith_loss(EA, mw, v1, 0.5, duration)
    inside = (t >= WINDOW[0] - 1e-9) & (t <= WINDOW[1] + 1e-9)
    front = np.polyfit(t[inside], h["cone front along warp [mm]"][inside], 1)[0] * 1e3
    U = jump(EA, mw, 0.5 * (v1 + v4), 1.0)[3]
    print("%s: velocity %.2f -> %.2f m/s over [1, 4] us, lost %.2f; Smith, "
          "warp alone %.2f, weft moving along %.2f; front %.0f m/s, Smith %.0f m/s"
          % (name, v1, v4, v1 - v4, bare, full, front, U))
    forces = {}
    for r, what in ((1.0, "warp alone"), (0.5, "weft moving along")):
        _, e1, th, u = jump(EA, mw, own["v"], r)
        forces[r] = 2 * EA * e1 * math.sin(th)
        print("%s: jump conditions at %.0f m/s, %s (r = %.1f): eps1 %.2f %%, "
              "U %.0f m/s, %.1f N a warp yarn"
              % (name, own["v"], what, r, 100 * e1, u, forces[r]))
    # The linear tension against the run's own Smith line (nonlinear law).
    linear = forces[1.0] / PROJECTILE_MASS
    check(abs(linear / own["decel"] - 1) < 0.02,
          "%s: Smith's deceleration at %.0f m/s with E A eps %.4g m/s^2, the "
          "run's own %.4g (within 2 %%)" % (name, own["v"], linear, own["decel"]))
    # The window: the longitudinal front short of the clamps at its end.
    half = 0.5e3 * parameter(run, "Weft yarns") * parameter(run, "Yarn spacing")
    lfront = np.interp(WINDOW[1], t, h["longitudinal front [mm]"])
    check(lfront < half - 1.0,
          "%s: longitudinal front %.2f mm at 4 us, short of the clamps at %.2f mm"
          % (name, lfront, half))
    err = np.max(np.abs(h["energy error [%]"]))
    check(err < 0.5, "%s: largest energy error %.3f %% (below 0.5 %%)" % (name, err))
    return (v1 - v4) / bare, (v1 - v4) / full, front / U


def main():
    if len(sys.argv) != 5:
        sys.exit(__doc__)
    # The solver against Smith's closed form V^2 = c^2 (2 e sqrt(e (1 + e)) - e^2).
    EA, mw = 3860.0, 61.1e-6
    c = math.sqrt(EA / mw)
    e1 = jump(EA, mw, 600.0, 1.0)[1]
    closed = c * math.sqrt(2 * e1 * math.sqrt(e1 * (1 + e1)) - e1 ** 2)
    check(abs(closed / 600.0 - 1) < 1e-9,
          "jump conditions with r = 1: strain %.6f gives Smith's V %.9f m/s"
          % (e1, closed))

    wide_bare, wide_full, wide_front = measure(sys.argv[1], sys.argv[2], "wide")
    narrow_bare, narrow_full, narrow_front = measure(sys.argv[3], sys.argv[4], "narrow")
    check(abs(wide_bare - 1) < 0.06,
          "wide (weft 4 mm apart): velocity lost %.3f of Smith's for the warp "
          "alone (within 6 %%)" % wide_bare)
    check(abs(wide_front - 1) < 0.12,
          "wide: tent front %.3f of Smith's speed (within 12 %%)" % wide_front)
    check(narrow_bare > wide_bare + 0.08,
          "narrow (weft 1 mm apart): velocity lost %.3f of Smith's for the "
          "warp alone, more than wide's %.3f + 0.08" % (narrow_bare, wide_bare))
    check(narrow_full < 1.0,
          "narrow: velocity lost %.3f of the fully engaged weft's (below 1)"
          % narrow_full)
    finish()


if __name__ == "__main__":
    main()
