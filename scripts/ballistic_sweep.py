#!/usr/bin/python3
"""Ballistic answers in one command: a velocity sweep of the FE (Charmetant
and linear laws with the paper's sudden failure, and the Charmetant law with
the progressive failure identified from the DEM), the DEM and the hybrid yarn, each model's critical
velocity by bisection, Smith's critical velocity, a CSV and plots
(doc/ballistics.md); and one woven ply (model `fabric`): its residual
velocity, its V50 by bisection, the Lambert-Jonas fit and the membrane
estimate of Phoenix and Porwal (doc/fabric.md section 6).

Usage:
  python3 scripts/ballistic_sweep.py [--build build] [--out results/ballistics]
      [--np 2] [--models charmetant,linear,dem]
      [--velocities 60,120,200,300,450,600,800,1000,1200]
      [--dem-velocities 300,450,600,1000]
      [--hybrid-velocities 300,450,600,1000] [--tolerance 5]
      [--dem-tolerance 10] [--fabric-velocities 200,300,400,550]
      [--fabric-tolerance 10] [--fabric-prm prm/fabric/km2_ply_v50.prm]
      [--no-bisection] [--plots-only]

Each run is the paper's case (prm/km2_120ms_fe.prm, the linear law of
prm/study/fe_linear.prm, the progressive law of
prm/km2_120ms_fe_progressive.prm, model `progressive`, not in the default
--models, prm/km2_120ms_dem.prm, and the hybrid yarn with
fibre bars and 400 FE cells along the axis of
prm/hybrid/km2_600ms_fibre_bars.prm, model `hybrid`, not in
the default --models) at another impact velocity,
without snapshots, stopping 2 us after the yarn is cut through or at 40 us.
Model `fabric` (not in the default --models; on --np ranks) runs the ply of
--fabric-prm at --fabric-velocities to that prm's own End time, and writes
fabric_ballistics.csv, fabric_v50.csv and fabric_residual_velocity.png:
perforated when at the end every primary yarn is broken and the projectile
moves on; V50, the lowest velocity that perforates, by bisection to
--fabric-tolerance (scripts/fabric_ballistics.py).
Runs already done (their summary.txt exists) are reused, so an interrupted
sweep goes on where it stopped: a run's folder is named after its exact
velocity and end time (120 and 120.4 m/s are two runs), and a run is reused
only if its key file (NAME.key beside it: SHA-256 of the executable, of the
generated prm and of the prm it includes) matches; else it is run again.

Bad arguments, files or runs give one line "ballistic_sweep.py: error: ..."
and exit 2 (command line) or 1, never a traceback.

What is measured, per run (from history_<model>.csv and summary.txt):
  residual velocity      projectile velocity at the end of the run [m/s]
  energy absorbed        loss of projectile kinetic energy [mJ]
  first break            time of the first failed cell / broken truss [us]
  cut through            time the yarn is cut through [us]

A model's critical velocity is the lowest impact velocity at which the yarn
is cut through before the longitudinal wave, reflected at the clamps, is back
at the impact point (t_r = L / c, 3.2 us here): above it the yarn breaks on
the first strain wave, as in Smith's definition (strain behind the front =
failure strain); below it the yarn breaks, if at all, on the reflected
waves. Found by bisection between the sweep's velocities, to --tolerance.
"""
import argparse
import hashlib
import math
import os
import re
import subprocess
import sys
import time

import fabric_ballistics
import folder_lock
import script_errors

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))

# The paper's yarn (prm/km2_120ms_fe.prm; doc/theory.md).
LENGTH = 0.0254  # [m]
FAILURE_STRAIN = 0.0452  # [-]
FIBRE_MODULUS = 84.62e9  # [Pa]
DENSITY = 1440.0  # [kg/m^3], fibre density
PROJECTILE_MASS = 9.91e-6  # [kg]

MODELS = {
    "charmetant": ("fe", "prm/km2_120ms_fe.prm", ""),
    "linear": ("fe", "prm/km2_120ms_fe.prm",
               "subsection FE\n  set Constitutive law = Linear transversely "
               "isotropic\nend\n"),
    "progressive": ("fe", "prm/km2_120ms_fe_progressive.prm", ""),
    "dem": ("dem", "prm/km2_120ms_dem.prm", ""),
    # The ready case's FE cells of 5 trusses carry the short waves the
    # transverse front brings into the overlap, which set when the bars are
    # cut at the clamp (doc/hybrid.md 5.9).
    "hybrid": ("hybrid", "prm/hybrid/km2_600ms_fibre_bars.prm", ""),
    "fabric": ("fabric", fabric_ballistics.BASE, ""),
}
LABELS = {"charmetant": "FE, Charmetant law",
          "progressive": "FE, Charmetant law, progressive failure",
          "linear": "FE, linear TI law",
          "dem": "DEM",
          "hybrid": "hybrid, DEM |x| <= 4.89 mm, fibre bars, 400 FE cells",
          "fabric": "one woven ply, flat cylinder"}
# The models run on MPI ranks (--np); the FE runs on one.
PARALLEL_KINDS = ("dem", "hybrid", "fabric")


def smith_critical_velocity(eps=FAILURE_STRAIN, E=FIBRE_MODULUS, rho=DENSITY):
    """Smith's critical velocity of a linear elastic yarn [m/s]:
    V_c = c sqrt(2 eps sqrt(eps (1 + eps)) - eps^2), c = sqrt(E / rho)."""
    c = math.sqrt(E / rho)
    return c * math.sqrt(2. * eps * math.sqrt(eps * (1. + eps)) - eps * eps)


def reflection_time(E=FIBRE_MODULUS, rho=DENSITY):
    """Time for the longitudinal wave to reach a clamp and come back to the
    impact point, L / c [s]."""
    return LENGTH / math.sqrt(E / rho)


PROG = os.path.basename(__file__)


Failure = script_errors.Failure


def exact(x):
    """The shortest text that reads back as the float @p x exactly."""
    return repr(float(x))


def run_name(model, velocity, end_time):
    """Folder name of a run: the exact velocity [m/s] and end time [s], so
    that two velocities that differ at all never share a run."""
    return "%s_%sms_%ss" % (model, exact(velocity), exact(end_time))


def base_prm(model):
    """The prm a model's runs include."""
    return os.path.join(ROOT, MODELS[model][1])


def case_prm(model, velocity, end_time, out):
    """The prm text of a run (its Output/Directory @p out)."""
    kind, base, extra = MODELS[model]
    if kind == "fabric":  # to the base's own End time (@p end_time)
        return fabric_ballistics.case_prm(base_prm(model), velocity, out,
                                          exact)
    return ("include %s\n%s" % (os.path.join(ROOT, base), extra) +
            "subsection Projectile\n  set Initial velocity = %s\nend\n"
            % exact(velocity) +
            "subsection Time\n  set End time = %s\n"
            "  set Stop when cut through = true\n"
            "  set Time after cut through = 2e-6\nend\n" % exact(end_time) +
            "subsection Output\n  set Directory = %s\n"
            "  set Snapshot interval = 0\n  set Overwrite = true\n"
            "  set Verbosity = quiet\nend\n" % out)


def sha256_file(path):
    h = hashlib.sha256()
    try:
        with open(path, "rb") as f:
            for block in iter(lambda: f.read(1 << 20), b""):
                h.update(block)
    except OSError as e:
        raise Failure("cannot read %s: %s" % (path, e.strerror or e))
    return h.hexdigest()


def run_key(executable_hash, model, prm_text):
    """What a run's results depend on: the build, the generated prm and the
    prm it includes."""
    base = base_prm(model)
    return ("executable %s\nprm %s\nbase %s\n" %
            (executable_hash, hashlib.sha256(prm_text.encode()).hexdigest(),
             sha256_file(base)))


def reusable(out, key_file, key):
    """Whether the run in @p out is whole and was made with @p key."""
    if not os.path.exists(os.path.join(out, "summary.txt")):
        return False
    try:
        with open(key_file) as f:
            return f.read() == key
    except (OSError, UnicodeDecodeError):
        return False


def run_case(args, model, velocity, end_time):
    """Run one case (or reuse it) and return its measured figures."""
    kind, base, extra = MODELS[model]
    name = run_name(model, velocity, end_time)
    out = os.path.join(args.out, name)
    text = case_prm(model, velocity, end_time, out)
    key = run_key(args.executable_hash, model, text)
    key_file = os.path.join(args.out, name + ".key")
    if not reusable(out, key_file, key):
        prm = os.path.join(args.out, name + ".prm")
        try:
            if os.path.exists(key_file):
                os.remove(key_file)
            with open(prm, "w") as f:
                f.write(text)
        except OSError as e:
            raise Failure("cannot write %s: %s" % (prm, e.strerror or e))
        command = [args.executable, prm]
        if kind in PARALLEL_KINDS and args.np > 1:
            command = ["mpirun", "-np", str(args.np)] + command
        start = time.time()
        env = dict(os.environ, OMPI_ALLOW_RUN_AS_ROOT="1",
                   OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1")
        log_name = os.path.join(args.out, name + ".log")
        try:
            with open(log_name, "w") as log:
                rc = subprocess.call(command, stdout=log,
                                     stderr=subprocess.STDOUT, env=env)
        except OSError as e:
            raise Failure("cannot run %s: %s" % (command[0],
                                                 e.strerror or e))
        wall = time.time() - start
        print("  %-10s %6s m/s to %4.1f us: exit %d, %.0f s" %
              (model, "%g" % velocity, end_time * 1e6, rc, wall), flush=True)
        if os.path.exists(os.path.join(out, "summary.txt")):
            try:
                with open(key_file, "w") as f:
                    f.write(key)
                with open(os.path.join(args.out, name + ".wall"), "w") as f:
                    f.write("%.1f\n" % wall)
            except OSError as e:
                raise Failure("cannot write %s: %s" % (key_file,
                                                       e.strerror or e))
    if kind == "fabric":
        return fabric_ballistics.measure(
            out, os.path.join(args.out, name + ".log"), velocity,
            wall_time(os.path.join(args.out, name + ".wall")))
    return measure(out, kind, velocity)


def wall_time(path):
    """The wall time [s] the sweep measured for a run (None if unknown)."""
    try:
        with open(path) as f:
            return float(f.read())
    except (OSError, ValueError, UnicodeDecodeError):
        return None


def measure(out, kind, velocity):
    history = os.path.join(out, "history_%s.csv" % kind)
    if not os.path.exists(history):
        raise Failure("the run in %s wrote no history: see %s.log"
                      % (out, out))
    h = script_errors.history_columns(
        history, ("t [us]", "projectile velocity [m/s]",
                  "projectile kinetic energy [mJ]", "failed elements"),
        out + ".log")
    t, v = h["t [us]"], h["projectile velocity [m/s]"]
    ke, failed = h["projectile kinetic energy [mJ]"], h["failed elements"]
    first = next((t[i] for i in range(len(t)) if failed[i] > 0), None)
    cut = None
    if os.path.exists(os.path.join(out, "summary.txt")):
        try:
            with open(os.path.join(out, "summary.txt")) as f:
                text = f.read()
        except (OSError, UnicodeDecodeError) as e:
            raise Failure("cannot read %s/summary.txt: %s" % (out, e))
        m = re.search(r"yarn cut through:\s+([0-9.]+) us", text)
        cut = float(m.group(1)) if m else None
    return {"velocity": velocity, "residual": v[-1],
            "absorbed": ke[0] - ke[-1], "first_break": first,
            "cut_through": cut, "end": t[-1]}


def breaks_at_once(result, t_r):
    return result["cut_through"] is not None and \
        result["cut_through"] < t_r * 1e6


def bisect(args, model, results, t_r):
    """Critical velocity between the sweep's velocities, to the tolerance."""
    ordered = sorted(results, key=lambda r: r["velocity"])
    lo = max((r["velocity"] for r in ordered if not breaks_at_once(r, t_r)),
             default=None)
    hi = min((r["velocity"] for r in ordered if breaks_at_once(r, t_r)
              and (lo is None or r["velocity"] > lo)), default=None)
    if lo is None or hi is None:
        return None, lo, hi
    tolerance = args.dem_tolerance if MODELS[model][0] in PARALLEL_KINDS \
        else args.tolerance
    while hi - lo > tolerance:
        mid = 0.5 * (lo + hi)
        # Only whether the yarn is cut before t_r matters here.
        r = run_case(args, model, mid, t_r + 1e-6)
        results.append(r)
        if breaks_at_once(r, t_r):
            hi = mid
        else:
            lo = mid
    return 0.5 * (lo + hi), lo, hi


def plot(args, table, critical, smith):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    plt.rcParams.update({"font.size": 11, "axes.grid": True,
                         "grid.alpha": 0.3, "figure.facecolor": "white"})
    quantities = [("residual", "residual velocity [m/s]", "residual_velocity"),
                  ("absorbed", "energy absorbed by the yarn [mJ]",
                   "energy_absorbed"),
                  ("first_break", "time of first break [us]", "first_break"),
                  ("cut_through", "time of cut-through [us]", "cut_through")]
    styles = {"charmetant": "o-", "progressive": "D-.", "linear": "s--",
              "dem": "^-", "hybrid": "v:"}
    for key, label, file in quantities:
        fig, ax = plt.subplots(figsize=(6.4, 4.4))
        for model, rows in table.items():
            # A bisection run that stopped at t_r + 1 us without a cut has
            # no residual velocity: it is left out of the plots.
            rows = sorted((r for r in rows if r[key] is not None and
                           (r["cut_through"] is not None or
                            r["end"] >= args.end_time * 1e6 - 1e-3)),
                          key=lambda r: r["velocity"])
            ax.plot([r["velocity"] for r in rows], [r[key] for r in rows],
                    styles[model], label=LABELS[model], ms=4)
        if key == "residual":
            vmax = max(r["velocity"] for rows in table.values() for r in rows)
            ax.plot([0, vmax], [0, vmax], ":", color="grey",
                    label="no deceleration")
        ax.axvline(smith, color="k", lw=1, ls="-.",
                   label="Smith V_c = %.0f m/s" % smith)
        for model, vc in critical.items():
            if vc is not None:
                ax.axvline(vc, lw=0.8, ls=":",
                           color=ax.lines[list(table).index(model)].get_color(),
                           label="V_c %s = %.0f m/s" % (LABELS[model], vc))
        ax.set_xlabel("impact velocity [m/s]")
        ax.set_ylabel(label)
        ax.set_xlim(left=0)
        ax.legend(fontsize=9)
        fig.tight_layout()
        fig.savefig(os.path.join(args.out, file + ".png"), dpi=130)
        plt.close(fig)


class Parser(argparse.ArgumentParser):
    """argparse with its errors on one line (no usage block), exit 2."""

    def error(self, message):
        sys.stderr.write("%s: error: %s (see --help)\n" % (PROG, message))
        sys.exit(2)


def velocity_list(text):
    """A comma-separated list of finite positive velocities [m/s]."""
    values = []
    for item in text.split(","):
        try:
            v = float(item)
        except ValueError:
            raise argparse.ArgumentTypeError(
                "'%s' is not a velocity (a comma-separated list of numbers "
                "in m/s, e.g. 120,300)" % item.strip())
        if not (math.isfinite(v) and v > 0):
            raise argparse.ArgumentTypeError(
                "velocity '%s' must be a finite positive number of m/s"
                % item.strip())
        values.append(v)
    return values


def model_list(text):
    models = [m.strip() for m in text.split(",")]
    for m in models:
        if m not in MODELS:
            raise argparse.ArgumentTypeError(
                "unknown model '%s' (choose from %s)" % (m, ",".join(MODELS)))
    if len(set(models)) != len(models):
        raise argparse.ArgumentTypeError("a model is named twice in '%s'"
                                         % text)
    return models


def positive(kind):
    def convert(text):
        try:
            v = kind(text)
        except ValueError:
            raise argparse.ArgumentTypeError("'%s' is not a number" % text)
        if not (math.isfinite(v) and v > 0):
            raise argparse.ArgumentTypeError("'%s' must be positive" % text)
        return v
    return convert


def check_setup(args):
    """The build holds an executable yarn-impact, and --out is a folder that
    can be written (created if missing)."""
    if not os.path.isdir(args.build):
        raise Failure("--build %s is not a folder (a build folder holding "
                      "yarn-impact)" % args.build)
    args.executable = os.path.join(os.path.abspath(args.build), "yarn-impact")
    if not (os.path.isfile(args.executable) and
            os.access(args.executable, os.X_OK)):
        raise Failure("--build %s holds no executable yarn-impact (build it "
                      "first, or name the build folder)" % args.build)
    if os.path.exists(args.out) and not os.path.isdir(args.out):
        raise Failure("--out %s exists and is not a folder" % args.out)
    try:
        os.makedirs(args.out, exist_ok=True)
    except OSError as e:
        raise Failure("--out %s cannot be created: %s"
                      % (args.out, e.strerror or e))
    if not os.access(args.out, os.W_OK | os.X_OK):
        raise Failure("--out %s is not writable" % args.out)
    # One sweep per folder: its runs, keys and tables are this sweep's.
    folder_lock.hold_folder(args.out, ".sweep.lock", "sweep", "--out",
                            Failure)
    args.executable_hash = sha256_file(args.executable)


def main():
    p = Parser(description=__doc__.split("\n")[0])
    p.add_argument("--build", default=os.path.join(ROOT, "build"))
    p.add_argument("--out", default=os.path.join(ROOT, "results/ballistics"))
    p.add_argument("--np", type=positive(int), default=os.cpu_count() or 1)
    p.add_argument("--models", type=model_list,
                   default="charmetant,linear,dem")
    p.add_argument("--velocities", type=velocity_list,
                   default="60,120,200,300,450,600,800,1000,1200")
    # Fewer DEM points, each minutes long (doc/ballistics.md).
    p.add_argument("--dem-velocities", type=velocity_list,
                   default="300,450,600,1000")
    p.add_argument("--hybrid-velocities", type=velocity_list,
                   default="300,450,600,1000")
    p.add_argument("--end-time", type=positive(float), default=40e-6)
    p.add_argument("--tolerance", type=positive(float), default=5.)
    p.add_argument("--dem-tolerance", type=positive(float), default=10.)
    # A few velocities of the ply (one run is a minute or two on 2 ranks).
    p.add_argument("--fabric-velocities", type=velocity_list,
                   default="200,300,400,550")
    p.add_argument("--fabric-tolerance", type=positive(float), default=10.)
    p.add_argument("--fabric-prm", default=os.path.join(ROOT, MODELS[
        "fabric"][1]))
    p.add_argument("--no-bisection", action="store_true")
    args = p.parse_args()
    args.out = os.path.abspath(args.out)
    if not os.path.isfile(args.fabric_prm):
        raise Failure("--fabric-prm %s is not a file" % args.fabric_prm)
    MODELS["fabric"] = ("fabric", os.path.abspath(args.fabric_prm), "")
    check_setup(args)
    t_r = reflection_time()
    smith = smith_critical_velocity()
    print("Smith's critical velocity (linear yarn, eps_b = %g): %.1f m/s; "
          "reflection time L/c = %.2f us" % (FAILURE_STRAIN, smith, t_r * 1e6))
    start = time.time()
    table, critical = {}, {}
    for model in args.models:
        if model == "fabric":
            fabric_series(args)
            continue
        velocities = {"dem": args.dem_velocities,
                      "hybrid": args.hybrid_velocities}.get(model,
                                                           args.velocities)
        results = [run_case(args, model, v, args.end_time)
                   for v in velocities]
        table[model] = results
        if not args.no_bisection:
            critical[model], lo, hi = bisect(args, model, results, t_r)
            print("  %s: critical velocity %s (between %s and %s m/s)" %
                  (model, "%.1f m/s" % critical[model]
                   if critical[model] else "not bracketed", lo, hi),
                  flush=True)
    if not table:
        print("Wrote the fabric series in %.0f s" % (time.time() - start))
        return 0
    write_tables(args, table, critical, smith, t_r)
    try:
        plot(args, table, critical, smith)
    except ImportError as e:
        raise Failure("cannot draw the plots (%s); the tables are written"
                      % e)
    print("Wrote %s/ballistics.csv, critical_velocities.csv and 4 PNGs in "
          "%.0f s" % (args.out, time.time() - start))


def fabric_series(args):
    """The ply at --fabric-velocities, its V50 by bisection, the
    Lambert-Jonas fit and the membrane estimate (fabric_ballistics.py)."""
    base = base_prm("fabric")
    end_time = fabric_ballistics.prm_number(base, "End time")

    def run(v):
        return run_case(args, "fabric", v, end_time)
    results = [run(v) for v in args.fabric_velocities]
    v50, lo, hi = (None, None, None) if args.no_bisection else \
        fabric_ballistics.bisect_v50(run, results, args.fabric_tolerance)
    fit = fabric_ballistics.lambert_jonas(results, v50)
    estimate = fabric_ballistics.membrane_estimate(base, results[0]["report"])
    print("  fabric: V50 %s; membrane estimate (Phoenix-Porwal) %.0f m/s"
          % ("not sought (--no-bisection)" if args.no_bisection else
             "%.1f m/s (between %s and %s m/s)" % (v50, lo, hi) if v50 else
             "not bracketed (between %s and %s m/s)" % (lo, hi),
             estimate["v50"]), flush=True)
    try:
        fabric_ballistics.write(args.out, results, v50, (lo, hi), fit,
                                estimate)
    except ImportError as e:
        raise Failure("cannot draw the fabric plot (%s)" % e)
    except OSError as e:
        raise Failure("cannot write the fabric tables in %s: %s"
                      % (args.out, e.strerror or e))


def write_tables(args, table, critical, smith, t_r):
    with open(os.path.join(args.out, "ballistics.csv"), "w") as f:
        f.write("model,impact velocity [m/s],residual velocity [m/s],"
                "energy absorbed [mJ],first break [us],cut through [us],"
                "end of run [us],breaks at once\n")
        for model, rows in table.items():
            for r in sorted(rows, key=lambda r: r["velocity"]):
                f.write("%s,%g,%.4f,%.5f,%s,%s,%.3f,%d\n" % (
                    model, r["velocity"], r["residual"], r["absorbed"],
                    "" if r["first_break"] is None else "%.3f" % r["first_break"],
                    "" if r["cut_through"] is None else "%.3f" % r["cut_through"],
                    r["end"], breaks_at_once(r, t_r)))
    with open(os.path.join(args.out, "critical_velocities.csv"), "w") as f:
        f.write("model,critical velocity [m/s]\n")
        f.write("Smith (linear yarn),%.1f\n" % smith)
        for model, vc in critical.items():
            f.write("%s,%s\n" % (model, "" if vc is None else "%.1f" % vc))


if __name__ == "__main__":
    sys.exit(script_errors.run(main, PROG))
