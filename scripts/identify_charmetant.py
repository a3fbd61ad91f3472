#!/usr/bin/python3
"""Identify the Charmetant law's constants k_e, k_tc, p, k_td from the CSVs of
the DEM elementary tests (doc/identification.md section 3).

The law W = k_e I_e^2/2 + k_tc |I_tc|^p + k_td I_td^2/2 is linear in the
moduli for a fixed p, so the fit is a one-dimensional search over p with a
non-negative linear least-squares solve for the moduli inside (variable
projection). The Kirchhoff stress of the law at each row's deformation
gradient F is tau = (dW/dF) F^T, with the derivatives of the invariants
taken by central differences of their closed forms.

  identify_charmetant.py [--prm OUT.prm] [--base BASE.prm] [--plot OUT.png]
                         [--directory DIR] CSV...

Rows used: tension rows before the first fibre break (tau_xx); compaction
and distortion rows of the loading branch: their deviator tau_yy - tau_zz
and tau_yz always, their mean transverse stress (tau_yy + tau_zz)/2 only
where the section's area has decreased (I_tc < 0). Where the packing has
dilated (I_tc >= 0, a granular packing's usual state under shear), its
pressure is the confinement it needs to carry a shear stress, which no
hyperelastic law can carry, and a fit to it would only drive k_tc to zero
(doc/identification.md section 3). Each test (a CSV, and a confining
pressure of the distortion CSV) is weighted by its own RMS stress, so that
the GPa of tension does not drown the MPa of the section. Prints the constants with their standard errors (from the
Jacobian at the optimum), the residual of each test, and the constants
fitted to each test alone.

A bad argument or CSV (missing, unreadable, not a CSV, a column missing or
not a number, no usable rows) gives one line "identify_charmetant.py:
error: ..." and exit 2 (command line) or 1, never a traceback.
"""
import argparse
import csv
import math
import os
import sys

import folder_lock
import script_errors
import numpy as np
from scipy.optimize import minimize_scalar, nnls

PROG = os.path.basename(__file__)


Failure = script_errors.Failure


def invariants(F):
    """(I_e, I_tc, I_td) of deformation gradients F[..., 3, 3] (fibre = x),
    as the FE code evaluates them (doc/theory.md section 1)."""
    C = np.einsum("...ki,...kj->...ij", F, F)
    J = np.linalg.det(F)
    I4 = C[..., 0, 0]
    t11 = C[..., 1, 1] - C[..., 0, 1] ** 2 / I4
    t22 = C[..., 2, 2] - C[..., 0, 2] ** 2 / I4
    t12 = C[..., 1, 2] - C[..., 0, 1] * C[..., 0, 2] / I4
    s2 = ((t11 - t22) ** 2 + 4.0 * t12 ** 2) / (4.0 * J * J / I4)
    return (0.5 * np.log(I4), 0.5 * np.log(J) - 0.25 * np.log(I4),
            0.5 * np.arcsinh(np.sqrt(s2)))


def kirchhoff_bases(F, h=1e-7):
    """For each F (n x 3 x 3): G_e = dI_e/dF F^T, G_tc = dI_tc/dF F^T and
    G_td = d(I_td^2/2)/dF F^T (I_td^2 is smooth where I_td is not)."""
    n = F.shape[0]
    dIe = np.zeros((n, 3, 3))
    dItc = np.zeros((n, 3, 3))
    dItd = np.zeros((n, 3, 3))
    for a in range(3):
        for b in range(3):
            Fp = F.copy()
            Fm = F.copy()
            Fp[:, a, b] += h
            Fm[:, a, b] -= h
            ep, cp, dp = invariants(Fp)
            em, cm, dm = invariants(Fm)
            dIe[:, a, b] = (ep - em) / (2 * h)
            dItc[:, a, b] = (cp - cm) / (2 * h)
            dItd[:, a, b] = (0.5 * dp ** 2 - 0.5 * dm ** 2) / (2 * h)
    FT = np.transpose(F, (0, 2, 1))
    return dIe @ FT, dItc @ FT, dItd @ FT


def component(c, T):
    """Stress component c of the tensors T[..., 3, 3]."""
    if c == "xx":
        return T[..., 0, 0]
    if c == "yz":
        return T[..., 1, 2]
    if c == "dev":
        return T[..., 1, 1] - T[..., 2, 2]
    if c == "mean":
        return 0.5 * (T[..., 1, 1] + T[..., 2, 2])
    raise KeyError(c)


class Group:
    """The rows of one test (a CSV, or one confining pressure of it)."""

    def __init__(self, name, rows, components):
        self.name = name
        self.rows = rows
        self.components = components
        F = np.zeros((len(rows), 3, 3))
        for k, r in enumerate(rows):
            F[k] = [[float(r["F_xx"]), 0.0, 0.0],
                    [0.0, float(r["F_yy"]), float(r["F_yz"])],
                    [0.0, float(r["F_zy"]), float(r["F_zz"])]]
        self.F = F
        self.Ie, self.Itc, self.Itd = invariants(F)
        self.Ge, self.Gtc, self.Gtd = kirchhoff_bases(F)
        tau = np.zeros((len(rows), 3, 3))
        for k, r in enumerate(rows):
            tau[k] = [[float(r["tau_xx"]), 0.0, 0.0],
                      [0.0, float(r["tau_yy"]), float(r["tau_yz"])],
                      [0.0, float(r["tau_yz"]), float(r["tau_zz"])]]
        # Rows of each component that the fit uses (see the module doc).
        self.mask = {c: np.ones(len(rows), bool) for c in components}
        if "mean" in components:
            self.mask["mean"] = self.Itc < 0
        self.tau = {c: component(c, tau) * self.mask[c] for c in components}
        y = np.concatenate([self.tau[c][self.mask[c]] for c in components])
        self.scale = max(float(np.sqrt(np.mean(y ** 2))), 1e-300)

    def columns(self, p):
        """Design matrix (rows x [k_e, k_tc, k_td]) at exponent p, and the
        derivative of the k_tc column with respect to p, both scaled."""
        a = np.abs(self.Itc)
        sgn = np.sign(self.Itc)
        with np.errstate(divide="ignore", invalid="ignore"):
            g1 = np.where(a > 0, p * a ** (p - 1) * sgn, 0.0)
            dg1 = np.where(a > 0, (a ** (p - 1) + p * a ** (p - 1) *
                                   np.log(np.where(a > 0, a, 1.0))) * sgn, 0.0)
        A, dA, y = [], [], []
        for c in self.components:
            w = self.mask[c]
            A.append(np.column_stack([self.Ie * component(c, self.Ge),
                                      g1 * component(c, self.Gtc),
                                      component(c, self.Gtd)])[w])
            dA.append((dg1 * component(c, self.Gtc))[w])
            y.append(self.tau[c][w])
        return (np.vstack(A) / self.scale, np.concatenate(dA) / self.scale,
                np.concatenate(y) / self.scale)


LABELS = {"dev": "tau_yy - tau_zz", "mean": "(tau_yy + tau_zz)/2, I_tc < 0",
          "yz": "tau_yz"}


def short_name(path):
    """The CSV's folder and name: the compaction tests share a file name."""
    folder = os.path.basename(os.path.dirname(os.path.abspath(path)))
    return folder + "/" + os.path.basename(path)


NEEDED = {"tension": ["loading", "broken_fibres", "F_xx", "F_yy", "F_yz",
                       "F_zy", "F_zz", "tau_xx", "tau_yy", "tau_yz",
                       "tau_zz"],
          "other": ["loading", "phase", "confining_pressure",
                    "imposed_strain", "F_xx", "F_yy", "F_yz", "F_zy", "F_zz",
                    "tau_xx", "tau_yy", "tau_yz", "tau_zz"]}
NUMBERS = ["broken_fibres", "confining_pressure", "imposed_strain", "F_xx",
           "F_yy", "F_yz", "F_zy", "F_zz", "tau_xx", "tau_yy", "tau_yz",
           "tau_zz"]


def read_csv(path):
    """The rows of an elementary-test CSV, checked: every column the fit
    reads is there and every number is finite. Raises Failure."""
    if os.path.isdir(path):
        raise Failure("%s is a folder, not a CSV of an elementary test" % path)
    try:
        with open(path, newline="") as f:
            text = f.read()
    except OSError as e:
        raise Failure("cannot read %s: %s" % (path, e.strerror or e))
    except UnicodeDecodeError:
        raise Failure("%s is not a text CSV (binary data)" % path)
    if "\0" in text:
        raise Failure("%s is not a text CSV (binary data)" % path)
    try:
        rows = list(csv.DictReader(text.splitlines()))
    except csv.Error as e:
        raise Failure("%s is not a valid CSV: %s" % (path, e))
    if not rows:
        raise Failure("no rows in %s" % path)
    loading = rows[0].get("loading")
    if loading not in ("tension", "compaction", "distortion"):
        raise Failure("%s is not a CSV of an elementary test (its 'loading' "
                      "column is %s, not tension, compaction or distortion)"
                      % (path, "missing" if loading is None
                         else "'%s'" % loading))
    needed = NEEDED["tension" if loading == "tension" else "other"]
    missing = [c for c in needed if c not in rows[0]]
    if missing:
        raise Failure("%s lacks the column(s) %s" % (path, ", ".join(missing)))
    for k, r in enumerate(rows):
        if r.get("loading") != loading:
            raise Failure("%s, row %d: loading '%s' in a %s test"
                          % (path, k + 2, r.get("loading"), loading))
        for c in needed:
            if c in NUMBERS:
                try:
                    v = float(r[c])
                except (TypeError, ValueError):
                    raise Failure("%s, row %d: %s = '%s' is not a number"
                                  % (path, k + 2, c, r[c]))
                if not math.isfinite(v):
                    raise Failure("%s, row %d: %s = %s is not finite"
                                  % (path, k + 2, c, r[c]))
    return rows


def read_groups(files):
    groups = []
    for path in files:
        rows = read_csv(path)
        loading = rows[0]["loading"]
        if loading == "tension":
            used = [r for r in rows if float(r["broken_fibres"]) == 0]
            if not used:
                raise Failure("%s: no tension row before the first fibre "
                              "break" % path)
            groups.append(Group(short_name(path), used, ["xx"]))
        else:
            pressures = sorted({float(r["confining_pressure"]) for r in rows})
            for pc in pressures:
                used = [r for r in rows if r["phase"] == "load" and
                        float(r["confining_pressure"]) == pc and
                        float(r["imposed_strain"]) > 0]
                name = short_name(path)
                if pc > 0:
                    name += " p_c=%g MPa" % (pc * 1e-6)
                if not used:
                    raise Failure("%s: no loading row (phase load, imposed "
                                  "strain > 0)%s" % (
                                      path, " at p_c = %g Pa" % pc
                                      if pc > 0 else ""))
                groups.append(Group(name, used, ["dev", "mean", "yz"]))
    return groups


def solve(groups, p, free):
    """Non-negative moduli at exponent p for the moduli flagged in free."""
    parts = [g.columns(p) for g in groups]
    A = np.vstack([a for a, _, _ in parts])
    y = np.concatenate([b for _, _, b in parts])
    cols = [k for k in range(3) if free[k]]
    k = np.zeros(3)
    if cols:
        sol, _ = nnls(A[:, cols], y)
        k[cols] = sol
    r = A @ k - y
    return k, float(r @ r), A, y


def fit(groups, p_bounds=(2.0, 8.0)):
    """Returns (k_e, k_tc, p, k_td), their standard errors and the residual
    sum of squares (scaled). p is kept at 2 or more: below 2 the compaction
    tangent p (p - 1) k_tc |I_tc|^(p-2) / 4 is infinite at rest, and the
    explicit FE model's stable step with it."""
    free = [any(np.max(np.abs(g.Ie)) > 1e-6 for g in groups),
            any(np.max(np.abs(g.Itc)) > 1e-6 for g in groups),
            any(np.max(np.abs(g.Itd)) > 1e-6 for g in groups)]
    if free[1]:
        res = minimize_scalar(lambda p: solve(groups, p, free)[1],
                              bounds=p_bounds, method="bounded",
                              options={"xatol": 1e-10})
        p = float(res.x)
    else:
        p = float("nan")
    k, ssr, A, y = solve(groups, p if free[1] else 2.0, free)
    # Jacobian in (k_e, k_tc, p, k_td) at the optimum.
    dA = np.concatenate([g.columns(p if free[1] else 2.0)[1] for g in groups])
    J = np.column_stack([A[:, 0], A[:, 1], k[1] * dA, A[:, 2]])
    use = [0 if not free[0] else 1, free[1], free[1], free[2]]
    use = [i for i, u in enumerate(use) if u]
    m, nparam = len(y), len(use)
    errors = np.full(4, float("nan"))
    cond = float("nan")
    if m > nparam and nparam > 0:
        # Each test's rows reweighted by that test's own residual RMS (its
        # noise, not its stress scale), so that the scatter of one test
        # does not widen the interval of a constant fitted to another.
        weights, start = np.zeros(m), 0
        for g in groups:
            n_g = sum(int(g.mask[c].sum()) for c in g.components)
            r_g = (A @ k - y)[start:start + n_g]
            weights[start:start + n_g] = 1.0 / max(
                float(np.sqrt(np.mean(r_g ** 2))), 1e-12)
            start += n_g
        Ju = J[:, use] * weights[:, None]
        scale = np.array([k[0], k[1], p if free[1] else 1.0, k[2]])[use]
        # Of the relative sensitivities (columns times the constants).
        cond = float(np.linalg.cond(Ju * np.where(scale != 0, scale, 1.0)))
        try:
            cov = np.linalg.inv(Ju.T @ Ju)
            errors[use] = np.sqrt(np.abs(np.diag(cov)))
        except np.linalg.LinAlgError:
            pass
    theta = np.array([k[0], k[1], p, k[2]])
    return theta, errors, ssr, cond


def predicted(group, theta):
    k_e, k_tc, p, k_td = theta
    A, _, y = group.columns(p if np.isfinite(p) else 2.0)
    return (A @ np.array([k_e, k_tc, k_td]) * group.scale,
            y * group.scale)


def write_prm(path, base, theta, directory, sources):
    """The FE case of @p base with the identified constants."""
    with open(base) as f:
        text = f.read()
    k_e, k_tc, p, k_td = theta
    lines = text.splitlines()
    out = ["# Written by scripts/identify_charmetant.py from " +
           ", ".join(sources) + ":",
           "# the FE case of %s with the Charmetant constants identified"
           % base,
           "# from the DEM elementary tests (doc/identification.md)."]
    skip_comment = True
    for line in lines:
        if skip_comment and line.startswith("#"):
            continue
        skip_comment = False
        s = line.strip()
        if s.startswith("set Directory"):
            line = line[:line.index("=") + 1] + " " + directory
        out.append(line)
    out += ["",
            "subsection FE",
            "  subsection Charmetant",
            "    set k_e  = %.6e" % k_e,
            "    set k_tc = %.6e" % k_tc,
            "    set p    = %.6f" % (p if np.isfinite(p) else 2.0),
            "    set k_td = %.6e" % k_td,
            "  end",
            "end", ""]
    with open(path, "w") as f:
        f.write("\n".join(out))


def plot(path, groups, theta):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    n = len(groups)
    ncol = min(n, 3)
    nrow = (n + ncol - 1) // ncol
    fig, axes = plt.subplots(nrow, ncol, figsize=(5.2 * ncol, 3.9 * nrow),
                             squeeze=False)
    for ax in axes.flat[n:]:
        ax.axis("off")
    for ax, g in zip(axes.flat, groups):
        pred, meas = predicted(g, theta)
        m = len(g.rows)
        if g.components == ["xx"]:
            ax.plot(g.Ie * 100, meas[:m] * 1e-6, "k.", ms=3, label="DEM")
            ax.plot(g.Ie * 100, pred[:m] * 1e-6, "r-", label="fit")
            ax.set_xlabel("I_e [%]")
            ax.set_ylabel("tau_xx [MPa]")
        else:
            strain = np.array([float(r["imposed_strain"]) for r in g.rows])
            for k, (c, col) in enumerate(zip(g.components, "brg")):
                w = g.mask[c]
                lo = sum(int(g.mask[cc].sum()) for cc in g.components[:k])
                n_c = int(w.sum())
                ax.plot(strain[w], meas[lo:lo + n_c] * 1e-6, col + ".",
                        ms=3, label="DEM " + LABELS[c])
                ax.plot(strain[w], pred[lo:lo + n_c] * 1e-6,
                        col + ("x" if c == "mean" else "-"), lw=1,
                        label="fit " + LABELS[c])
            ax.set_xlabel("plate strain 1 - gap/gap_0 [-]")
            ax.set_ylabel("Kirchhoff stress [MPa]")
        ax.set_title(g.name, fontsize=9)
        ax.grid(alpha=0.3)
        ax.legend(fontsize=7)
    fig.suptitle("Charmetant law fitted to the DEM elementary tests: "
                 "k_e %.4g MPa, k_tc %.4g MPa, p %.3f, k_td %.4g MPa"
                 % (theta[0] * 1e-6, theta[1] * 1e-6, theta[2],
                    theta[3] * 1e-6), fontsize=9)
    fig.tight_layout()
    fig.savefig(path, dpi=120)


# The output folders this process holds (folder_lock).
_folders = []


class Parser(argparse.ArgumentParser):
    """argparse with its errors on one line (no usage block), exit 2."""

    def error(self, message):
        sys.stderr.write("%s: error: %s (see --help)\n" % (PROG, message))
        sys.exit(2)


def expected_constants(text):
    try:
        values = [float(v) for v in text.split(",")]
    except ValueError:
        raise argparse.ArgumentTypeError(
            "'%s' is not four numbers k_e,k_tc,p,k_td" % text)
    if len(values) != 4 or not all(math.isfinite(v) and v != 0
                                   for v in values):
        raise argparse.ArgumentTypeError(
            "'%s' is not four finite non-zero numbers k_e,k_tc,p,k_td" % text)
    return values


def positive_float(text):
    try:
        v = float(text)
    except ValueError:
        raise argparse.ArgumentTypeError("'%s' is not a number" % text)
    if not (math.isfinite(v) and v > 0):
        raise argparse.ArgumentTypeError("'%s' must be positive" % text)
    return v


def main():
    ap = Parser(description=__doc__.splitlines()[0])
    ap.add_argument("csv", nargs="+")
    ap.add_argument("--prm", help="write the FE case with the constants")
    ap.add_argument("--base", default=os.path.join(
        os.path.dirname(os.path.abspath(__file__)), "..", "prm",
        "km2_120ms_fe.prm"), help="FE case the written .prm is based on")
    ap.add_argument("--directory", default="results/km2_120ms_fe_identified",
                    help="Output/Directory of the written .prm")
    ap.add_argument("--plot", help="PNG of the curves and the fit")
    ap.add_argument("--expect", type=expected_constants, help="k_e,k_tc,p,k_td the fit must return "
                    "(a test): exit 1 if any differs by more than --tolerance")
    ap.add_argument("--tolerance", type=positive_float, default=0.01,
                    help="relative tolerance of --expect")
    ap.add_argument("--each", action="store_true",
                    help="also fit each test alone")
    args = ap.parse_args()

    if args.prm and not os.path.isfile(args.base):
        raise Failure("--base %s is not a parameter file" % args.base)
    # One identification per output folder (of --prm and --plot).
    for option, target in (("--prm", args.prm), ("--plot", args.plot)):
        if not target:
            continue
        folder = os.path.dirname(os.path.abspath(target))
        if not os.path.isdir(folder):
            raise Failure("%s %s: its folder %s does not exist"
                          % (option, target, folder))
        if folder not in _folders:
            folder_lock.hold_folder(folder, ".identify.lock",
                                    "identification",
                                    "the folder of " + option, Failure)
            _folders.append(folder)
    groups = read_groups(args.csv)
    theta, err, ssr, cond = fit(groups)
    names = ["k_e [MPa]", "k_tc [MPa]", "p [-]", "k_td [MPa]"]
    unit = [1e-6, 1e-6, 1.0, 1e-6]
    print("Charmetant constants from %d tests (%d rows):"
          % (len(groups), sum(len(g.rows) for g in groups)))
    for name, v, e, u in zip(names, theta, err, unit):
        print("  %-11s %14.6g  +- %.3g" % (name, v * u, e * u))
    print("  condition number of the relative Jacobian %.3g" % cond)
    print("Residual per test (RMS of fit - DEM over the test's RMS stress):")
    for g in groups:
        pred, meas = predicted(g, theta)
        rel = math.sqrt(np.mean((pred - meas) ** 2)) / g.scale
        print("  %-48s %8.4f   (RMS stress %.4g MPa, %d rows)"
              % (g.name, rel, g.scale * 1e-6, len(g.rows)))
    if args.each:
        print("Each test alone:")
        for g in groups:
            t, e, _, _ = fit([g])
            print("  %-48s k_e %.6g  k_tc %.4g  p %.4g  k_td %.4g MPa"
                  % (g.name, t[0] * 1e-6, t[1] * 1e-6, t[2], t[3] * 1e-6))
    if args.prm:
        try:
            write_prm(args.prm, args.base, theta, args.directory,
                      [os.path.basename(c) for c in args.csv])
        except OSError as e:
            raise Failure("cannot write %s from %s: %s"
                          % (args.prm, args.base, e.strerror or e))
        except UnicodeDecodeError:
            raise Failure("--base %s is not a text parameter file" % args.base)
        print("wrote " + args.prm)
    if args.plot:
        try:
            plot(args.plot, groups, theta)
        except (OSError, ValueError) as e:
            raise Failure("cannot write the plot %s: %s" % (args.plot, e))
        print("wrote " + args.plot)
    if args.expect:
        expected = args.expect
        ok = True
        for name, v, e in zip(names, theta, expected):
            rel = abs(v / e - 1.0)
            good = rel <= args.tolerance
            ok = ok and good
            print("  %s: identified %.6g, expected %.6g, relative error "
                  "%.2e: %s" % (name.split()[0], v, e, rel,
                                "PASSED" if good else "FAILED"))
        sys.exit(0 if ok else 1)


if __name__ == "__main__":
    sys.exit(script_errors.run(main, PROG))
