"""The fabric series of ballistic_sweep.py (doc/fabric.md section 6): one
ply of Model = fabric (prm/fabric/km2_ply_v50.prm, or --fabric-prm) struck
at several velocities, its perforation, its V50 by bisection, the
Lambert-Jonas fit of its residual velocities, and the membrane estimate of
Phoenix and Porwal to compare with.

Perforation (a run is one ply until its End time, no stop criterion): at
the end time the history's `broken yarns` is at least the number of primary
yarns (the yarns under the projectile's face at the start, from the run's
set-up report) and the projectile still moves on (velocity > 0). The count
is of yarns with a broken section, not of which: a secondary yarn broken
while a primary one holds would count, which the table's broken yarns show.
A run that stops before its end time (a numerical failure) counts as
perforated if its primary yarns broke before; otherwise it is an error.

V50: the lowest impact velocity that perforates, by bisection between the
highest velocity that does not and the lowest that does, to the tolerance.
The bisection assumes that perforation is monotonic in the impact velocity;
a run that perforates below the highest velocity that does not is reported
(one line, and the row `perforated below the bracket [m/s]` of
fabric_v50.csv, empty when none): the V50 is then not one number (doc/fabric.md
section 15).
"""
import math
import os
import re

import script_errors

Failure = script_errors.Failure

BASE = "prm/fabric/km2_ply_v50.prm"
HISTORY = "history_fabric.csv"


def prm_number(path, name):
    """The number of the first `set NAME = VALUE` line of the prm file PATH
    (subsections are not told apart: the names read here are unique)."""
    try:
        with open(path) as f:
            text = f.read()
    except (OSError, UnicodeDecodeError) as e:
        raise Failure("cannot read %s: %s" % (path, e))
    m = re.search(r"^\s*set\s+%s\s*=\s*(\S+)" % re.escape(name), text, re.M)
    if not m:
        raise Failure("%s sets no '%s' (the fabric series needs it)"
                      % (path, name))
    try:
        return float(m.group(1))
    except ValueError:
        raise Failure("%s: '%s' is not a number" % (path, m.group(1)))


def case_prm(base, velocity, out, exact):
    """The prm text of one run of the ply at VELOCITY [m/s] into OUT: the
    base case with its own end time, no snapshots."""
    return ("include %s\n" % base +
            "subsection Projectile\n  set Initial velocity = %s\nend\n"
            % exact(velocity) +
            "subsection Output\n  set Directory = %s\n"
            "  set Snapshot interval = 0\n  set Overwrite = true\n"
            "  set Verbosity = quiet\nend\n" % out)


def setup_report(log):
    """From the run's set-up report (its log): the primary yarns, the
    yarns' mass [kg], mass per length [kg/m], EA [N] and bar wave speed
    [m/s]."""
    try:
        with open(log) as f:
            text = f.read()
    except (OSError, UnicodeDecodeError) as e:
        raise Failure("cannot read the run's log %s: %s" % (log, e))
    p = re.search(r"\[fabric\] primary yarns[^:]*:\s*(.*)", text)
    y = re.search(r"\[fabric\] yarn mass ([0-9.eE+-]+) mg, mass per length "
                  r"([0-9.eE+-]+) mg/m, EA ([0-9.eE+-]+) N, bar wave speed "
                  r"([0-9.eE+-]+) m/s", text)
    if not p or not y:
        raise Failure("the log %s has no fabric set-up report (primary "
                      "yarns, yarn mass): see it" % log)
    primary = [s for s in p.group(1).split(",") if s.strip()]
    return {"primary": len(primary), "yarn_mass": float(y.group(1)) * 1e-6,
            "mass_per_length": float(y.group(2)) * 1e-6,
            "EA": float(y.group(3)), "c": float(y.group(4))}


def measure(out, log, velocity, wall):
    """The figures of one run: residual velocity [m/s] at the end, energy
    absorbed [mJ], broken yarns at the end, primary yarns, perforated, the
    time the broken yarns first reach the primary count [us]."""
    h = script_errors.history_columns(
        os.path.join(out, HISTORY),
        ("t [us]", "projectile velocity [m/s]",
         "projectile kinetic energy [mJ]", "broken yarns"), log)
    t, v = h["t [us]"], h["projectile velocity [m/s]"]
    ke = h["projectile kinetic energy [mJ]"]
    broken = [int(x) for x in h["broken yarns"]]
    report = setup_report(log)
    n = report["primary"]
    broken_at = next((t[i] for i in range(len(t)) if broken[i] >= n), None)
    if not os.path.exists(os.path.join(out, "summary.txt")) and \
            broken_at is None:
        # Stopped early (a numerical failure, a signal) before its primary
        # yarns broke: neither perforated nor not.
        raise Failure("the run in %s stopped at %.3f us, before its end "
                      "time, without perforating: see %s" % (out, t[-1], log))
    return {"velocity": velocity, "residual": v[-1],
            "absorbed": ke[0] - ke[-1], "broken": broken[-1], "primary": n,
            "perforated": broken[-1] >= n and v[-1] > 0.,
            "broken_at": broken_at, "end": t[-1], "wall": wall,
            "report": report}


def bisect_v50(run, results, tolerance):
    """V50 between the highest velocity that does not perforate and the
    lowest above it that does, halved to TOLERANCE [m/s] with RUN(v);
    (None, lo, hi) when the sweep does not bracket it."""
    lo = max((r["velocity"] for r in results if not r["perforated"]),
             default=None)
    hi = min((r["velocity"] for r in results if r["perforated"]
              and (lo is None or r["velocity"] > lo)), default=None)
    if lo is None or hi is None:
        return None, lo, hi
    while hi - lo > tolerance:
        r = run(0.5 * (lo + hi))
        results.append(r)
        if r["perforated"]:
            hi = r["velocity"]
        else:
            lo = r["velocity"]
    return hi, lo, hi


def perforated_below(results, highest_not):
    """The velocities [m/s] that perforate below HIGHEST_NOT, the highest
    velocity that does not (ascending; empty when perforation is monotonic
    in the velocity)."""
    if highest_not is None:
        return []
    return sorted(r["velocity"] for r in results
                  if r["perforated"] and r["velocity"] < highest_not)


def lambert_jonas(results, v50):
    """Fit v_r = a (v^p - V50^p)^(1/p) to the perforating runs above V50,
    V50 the bisection's: (a, p, largest residual [m/s]), or None without
    three such runs or a converged fit."""
    if v50 is None:
        return None
    points = sorted((r["velocity"], r["residual"]) for r in results
                    if r["perforated"] and r["velocity"] > v50)
    if len(points) < 3:
        return None
    try:
        import numpy
        from scipy.optimize import curve_fit
    except ImportError:
        return None
    v = numpy.array([p[0] for p in points])
    vr = numpy.array([p[1] for p in points])

    def model(x, a, p):
        return a * numpy.power(numpy.maximum(x ** p - v50 ** p, 0.), 1. / p)
    try:
        (a, p), _ = curve_fit(model, v, vr, p0=(0.9, 2.), maxfev=20000,
                              bounds=([0.1, 1.], [1.5, 20.]))
    except (RuntimeError, ValueError):
        return None
    return a, p, float(numpy.max(numpy.abs(model(v, a, p) - vr)))


def membrane_estimate(base, report):
    """The ply's V50 by the membrane model of Phoenix and Porwal (Int. J.
    Solids Struct. 40 (2003) 6723-6765) in the form restated by Meng et
    al. (Extreme Mech. Lett., 2017, doi:10.1016/j.eml.2017.06.001, their
    Eqs. 1, 3 and A.2):
    V50 = sqrt(2) (1 + Gamma) c (eps_b / K)^(3/4), Gamma = rho_A A_p / m_p,
    with the strain concentration K at the projectile's rim closed here
    (doc/fabric.md section 6): the cone's material picks up the velocity
    V at its front (F = pi rho_A V d(r_c^2)/dt, so that V = V0 / (1 +
    Gamma) exp(-Gamma (rho^2 - 1)), rho = r_c / r_p), the strain at the
    cone's front follows V by the 1-D relation V = sqrt(2) c eps_c^(3/4),
    and the strain inside the cone falls as 1/r (eps(r_p) = rho eps_c):
    K = max over rho of rho exp(-4/3 Gamma (rho^2 - 1)), at rho^2 =
    3 / (8 Gamma). Inputs: the model's own yarns (the set-up report's
    mass and bar wave speed c), the patch's area, the prm's projectile
    and failure strain. Also Cunniff's velocity U*^(1/3), U* = (sigma_b
    eps_b / 2 rho) c, sigma_b = E eps_b, E / rho = c^2."""
    n_warp = prm_number(base, "Warp yarns")
    n_weft = prm_number(base, "Weft yarns")
    s = prm_number(base, "Yarn spacing")
    m_p = prm_number(base, "Mass")
    r_p = 0.5 * prm_number(base, "Diameter")
    eps_b = prm_number(base, "Failure strain")
    c = report["c"]
    rho_A = report["yarn_mass"] / (n_warp * s * n_weft * s)
    gamma = rho_A * math.pi * r_p ** 2 / m_p
    rho2 = max(1., 3. / (8. * gamma))
    K = math.sqrt(rho2) * math.exp(-4. / 3. * gamma * (rho2 - 1.))
    v50 = math.sqrt(2.) * (1. + gamma) * c * (eps_b / K) ** 0.75
    u_star = 0.5 * c * c * eps_b * eps_b * c
    return {"areal_density": rho_A, "gamma": gamma, "c": c, "K": K,
            "cone_radius": math.sqrt(rho2) * r_p, "v50": v50,
            "v_at_once": math.sqrt(2.) * (1. + gamma) * c * eps_b ** 0.75,
            "cunniff_velocity": u_star ** (1. / 3.),
            "patch_half_width": 0.5 * min(n_warp, n_weft) * s}


def write(out, results, v50, bracket, fit, estimate):
    """fabric_ballistics.csv (one row per run), fabric_v50.csv (the model's
    V50, the fit and the estimate) and fabric_residual_velocity.png."""
    with open(os.path.join(out, "fabric_ballistics.csv"), "w") as f:
        f.write("impact velocity [m/s],residual velocity [m/s],"
                "broken yarns,primary yarns,perforated,energy absorbed [mJ],"
                "primary yarns broken at [us],end of run [us],wall time [s]\n")
        for r in sorted(results, key=lambda r: r["velocity"]):
            f.write("%g,%.4f,%d,%d,%d,%.5f,%s,%.3f,%s\n" % (
                r["velocity"], r["residual"], r["broken"], r["primary"],
                r["perforated"], r["absorbed"],
                "" if r["broken_at"] is None else "%.3f" % r["broken_at"],
                r["end"], "" if r["wall"] is None else "%.0f" % r["wall"]))
    with open(os.path.join(out, "fabric_v50.csv"), "w") as f:
        f.write("quantity,value\n")
        rows = [("V50 of the model [m/s]", v50),
                ("highest velocity not perforating [m/s]", bracket[0]),
                ("lowest velocity perforating [m/s]", bracket[1])]
        below = perforated_below(results, bracket[0])
        rows.append(("perforated below the bracket [m/s]",
                     below[0] if below else None))
        if below:
            print("  fabric: perforation is not monotonic in the impact "
                  "velocity: perforated at %s m/s, below %g m/s, which does "
                  "not perforate; the V50 above is the bisection's between "
                  "%g and %g m/s" % (", ".join("%g" % v for v in below),
                                     bracket[0], bracket[0], bracket[1]),
                  flush=True)
        if fit:
            rows += [("Lambert-Jonas a", fit[0]), ("Lambert-Jonas p", fit[1]),
                     ("Lambert-Jonas largest residual [m/s]", fit[2])]
        if estimate:
            rows += [("areal density [kg/m^2]", estimate["areal_density"]),
                     ("Gamma = rho_A A_p / m_p", estimate["gamma"]),
                     ("bar wave speed c [m/s]", estimate["c"]),
                     ("strain concentration K", estimate["K"]),
                     ("cone radius at the peak strain [mm]",
                      estimate["cone_radius"] * 1e3),
                     ("patch half-width [mm]",
                      estimate["patch_half_width"] * 1e3),
                     ("membrane V50 (Phoenix-Porwal) [m/s]", estimate["v50"]),
                     ("membrane perforation at impact (K = 1) [m/s]",
                      estimate["v_at_once"]),
                     ("Cunniff velocity U*^(1/3) [m/s]",
                      estimate["cunniff_velocity"])]
            if v50:
                rows.append(("model V50 / U*^(1/3)",
                             v50 / estimate["cunniff_velocity"]))
            rows.append(("membrane V50 / U*^(1/3)",
                         estimate["v50"] / estimate["cunniff_velocity"]))
        for name, value in rows:
            f.write("%s,%s\n" % (name, "" if value is None else "%.6g" % value))
    plot(out, results, v50, fit, estimate)


def plot(out, results, v50, fit, estimate):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    rows = sorted(results, key=lambda r: r["velocity"])
    fig, ax = plt.subplots(figsize=(6.4, 4.4))
    for done, style, label in [(True, "o", "perforated"),
                               (False, "x", "not perforated")]:
        pts = [r for r in rows if r["perforated"] == done]
        ax.plot([r["velocity"] for r in pts], [r["residual"] for r in pts],
                style, label=label + " (one ply, fabric)")
    vmax = max(r["velocity"] for r in rows)
    ax.plot([0, vmax], [0, vmax], ":", color="grey", label="no deceleration")
    if fit and v50:
        import numpy
        x = numpy.linspace(v50, vmax, 100)
        ax.plot(x, fit[0] * (x ** fit[1] - v50 ** fit[1]) ** (1. / fit[1]),
                "-", label="Lambert-Jonas a = %.3f, p = %.2f" % fit[:2])
    if v50:
        ax.axvline(v50, color="k", lw=1, ls="-.",
                   label="V50 of the model = %.0f m/s" % v50)
    if estimate:
        ax.axvline(estimate["v50"], color="r", lw=1, ls="--",
                   label="membrane estimate = %.0f m/s" % estimate["v50"])
    ax.axhline(0, color="grey", lw=0.5)
    ax.set_xlabel("impact velocity [m/s]")
    ax.set_ylabel("residual velocity at the end of the run [m/s]")
    ax.grid(True, alpha=0.3)
    ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(os.path.join(out, "fabric_residual_velocity.png"), dpi=130)
    plt.close(fig)
