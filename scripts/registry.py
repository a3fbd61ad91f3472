#!/usr/bin/python3
"""The registry of runs, doc/results/ (doc/results/README.md): one JSON
file per run, written by scripts/reproduce.sh through this script, never
edited by hand.

  registry.py record --case NAME --level quick|full --command CMD
                     --wall SECONDS --depends PATH... --extract KIND ARG...

writes doc/results/NAME.json with the case, the level, the command, the
git commit (short and full) and whether the tree was dirty (and where), the
machine (uname -m, the CPU model, the core count), the date, the wall time
and the quantities that the extractor KIND reads from the run's outputs:

  history DIR|CSV         history_fe.csv or history_dem.csv and summary.txt
                          of a run (or one history CSV): velocity at given
                          times, first failure, cut-through, final
                          velocity, energy error, the range of the section
                          width at impact over 0-20 us, the spreading front
  fit LOG                 the constants printed by identify_charmetant.py
  failure DIR DEM_CSV     the same FE run against a DEM history (the columns
                          of scripts/failure_table.py)
  summary DIR             every "key: number" line of summary.txt
  elementary LOG          the printed summary of an elementary DEM test
  fibre_failure LOG       the printed lines of identify_fibre_failure.py
  compare LOG             the printed lines of compare_identified.py
  kink LOG                the printed lines of fe_kink_compaction.py
  consistency LOG         the model consistency lines of a Model = both run
  recovery LOG            the relative errors printed by identify_charmetant.py
                          --expect (test identification/synthetic_recovery)
  segment_length LOG      the differences printed by the test
                          dem/elementary_segment_length
  sweep DIR               ballistics.csv and critical_velocities.csv of
                          scripts/ballistic_sweep.py: per model and impact
                          velocity V (its dot as _), MODEL_V_residual,
                          _absorbed, _first_break, _cut_through, _end,
                          _at_once (1 if the yarn breaks at once);
                          critical_MODEL, the bisection's bracket
                          critical_MODEL_below and _above, critical_smith
  run DIR [LOG]           the history quantities of DIR, and the run's
                          steps, its largest strain, the times its
                          longitudinal and transverse fronts reach the
                          clamp, the "window:" lines of its summary (the
                          Smith checks) and, from the printed LOG, the
                          set-up lines (mass, EA, stable steps, kernel)

  registry.py show NAME   prints an entry
"""
import argparse
import csv
import datetime
import json
import os
import platform
import re
import subprocess
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
REGISTRY = os.path.join(ROOT, "doc", "results")
TIMES = (1, 5, 10, 15, 20, 25, 28, 30, 32, 35, 40)


def git(*args):
    return subprocess.run(["git", "-C", ROOT] + list(args),
                          capture_output=True, text=True).stdout.strip()


def machine():
    model = "unknown"
    try:
        for line in open("/proc/cpuinfo"):
            if line.startswith("model name"):
                model = line.split(":", 1)[1].strip()
                break
    except OSError:
        pass
    return {"arch": platform.machine(), "cpu": model,
            "cores": os.cpu_count()}


def slug(text):
    return re.sub(r"[^a-z0-9]+", "_", text.lower()).strip("_")


def number(text):
    m = re.match(r"\s*([-+]?\d+(?:\.\d*)?(?:[eE][-+]?\d+)?)", text)
    return float(m.group(1)) if m else None


def read_csv(path):
    with open(path) as f:
        rows = list(csv.DictReader(f))
    return {k: [float(r[k]) for r in rows] for k in rows[0]}


def summary_pairs(path):
    """Every 'key: value' line of a summary: numbers as numbers, the rest as
    text ('none', 'no')."""
    out = {}
    for line in open(path):
        if ":" not in line or line.startswith(" " * 5):
            continue
        key, value = line.split(":", 1)
        key = slug(key)
        if not key or key in out:
            continue
        v = number(value)
        out[key] = v if v is not None else value.strip()
    return out


def history_file(run):
    for name in ("history_fe.csv", "history_dem.csv", "history_hybrid.csv"):
        path = os.path.join(run, name)
        if os.path.exists(path):
            return path
    raise SystemExit("registry.py: no history CSV in " + run)


def extract_history(run):
    """RUN is a run folder, or one history CSV of it (a Model = both run
    has two): then the first failure is the CSV's first row with a failed
    element, and the summary is not read."""
    if run.endswith(".csv"):
        h = read_csv(run)
        s = {}
        first = next((ti for ti, f in zip(h["t [us]"], h["failed elements"])
                      if f > 0), None)
        if first is not None:
            s["first_failure"] = first
        summary = ""
    else:
        h = read_csv(history_file(run))
        summary = os.path.join(run, "summary.txt")
        s = summary_pairs(summary) if os.path.exists(summary) else {}
    t, v = h["t [us]"], h["projectile velocity [m/s]"]
    q = {}
    for time in TIMES:
        if time <= t[-1] + 1e-9:
            k = min(range(len(t)), key=lambda i: abs(t[i] - time))
            q["v_%gus" % time] = v[k]
    if "max longitudinal strain [-]" in h:
        for time in (10, 20, 30):
            if time <= t[-1] + 1e-9:
                k = min(range(len(t)), key=lambda i: abs(t[i] - time))
                q["strain_max_%gus_pct" % time] = (
                    100. * h["max longitudinal strain [-]"][k])
    if "section RMS width at impact [mm]" in h:
        q["rms_width_0_mm"] = h["section RMS width at impact [mm]"][0]
    q["end_us"] = t[-1]
    q["v_end"] = v[-1]
    first = s.get("first_failure")
    q["first_failure_us"] = first if isinstance(first, float) else "none"
    cut = s.get("yarn_cut_through")
    q["cut_through_us"] = cut if isinstance(cut, float) else "none"
    q["energy_error_max_pct"] = max(abs(x) for x in h["energy error [%]"])
    eroded = s.get("eroded_cells")
    if eroded is not None:
        q["eroded_cells"] = eroded
        # "eroded cells: 20 (first at 19.6002 us)": the whole cell text
        # with the time rounded, "none" without erosion
        text = next(line.split(":", 1)[1].strip() for line in open(summary)
                    if line.strip().startswith("eroded cells"))
        m = re.search(r"first at ([\d.]+) us", text)
        q["eroded_text"] = ("%d (first at %.2f us)" % (eroded, float(m.group(1)))
                            if m else text)
    w = [x for ti, x in zip(t, h["section width at impact [mm]"])
         if ti <= 20.0 + 1e-6]
    if w and w[0] > 0:  # a single fibre has no width
        change = [100. * (x / w[0] - 1.) for x in w]
        q["width_min_pct"], q["width_max_pct"] = min(change), max(change)
    # The spreading front over 0-20 us: in how many samples it is out of
    # the nose, and its farthest position.
    rows = [(ti, sf, tf) for ti, sf, tf in zip(
        t, h["spreading front [mm]"], h["transverse front [mm]"])
        if ti <= 20.0 + 1e-6]
    q["samples_20us"] = len(rows)
    q["spreading_samples_20us"] = sum(1 for r in rows if r[1] > 0)
    far = max(rows, key=lambda r: r[1])
    q["spreading_max_20us_mm"], q["spreading_max_at_us"] = far[1], far[0]
    q["transverse_at_spreading_max_mm"] = far[2]
    return q


def extract_failure(run, dem_csv):
    q = extract_history(run)
    fe = read_csv(history_file(run))
    dem = read_csv(dem_csv)
    t_d, v_d = dem["t [us]"], dem["projectile velocity [m/s]"]
    best, at = -1.0, None
    dvs = []
    for ti, vi in zip(fe["t [us]"], fe["projectile velocity [m/s]"]):
        if ti > t_d[-1] + 1e-9:
            break
        # linear interpolation of the DEM history at ti
        k = next(i for i in range(1, len(t_d)) if t_d[i] >= ti) \
            if ti > t_d[0] else 1
        a = (ti - t_d[k - 1]) / (t_d[k] - t_d[k - 1])
        d = abs(vi - (v_d[k - 1] + a * (v_d[k] - v_d[k - 1])))
        dvs.append((ti, d))
        if d > best:
            best, at = d, ti
    q["dv_max"], q["dv_max_at_us"] = best, at
    # The DEM reference: its first break (the first row with a broken
    # truss) and the end of its history; the FE against it.
    k1 = next(i for i, f in enumerate(dem["failed elements"]) if f > 0)
    q["dem_first_break_us"] = t_d[k1]
    q["dem_end_us"] = t_d[-1]
    if isinstance(q["first_failure_us"], float):
        q["first_failure_vs_dem_us"] = q["first_failure_us"] - t_d[k1]
    q["dv_at_dem_end"] = dvs[-1][1]
    # Before any fibre breaks: up to the DEM's first break.
    q["dv_max_before_break"] = max(
        (d for ti, d in dvs if ti <= t_d[k1] + 1e-9), default=0.0)
    above = [ti for ti, d in dvs if d > 2.0]
    later = [ti for ti, d in dvs if above and ti > above[-1]]
    if later:
        q["dv_below_2_from_us"] = later[0]
    return q


def extract_summary(path):
    """A run folder's summary.txt, or a printed log."""
    if os.path.isdir(path):
        path = os.path.join(path, "summary.txt")
    return summary_pairs(path)


def lines_of(log):
    return open(log).read().splitlines()


def extract_elementary(log):
    q = {}
    for line in lines_of(log):
        m = re.match(r"\s+(.+?)\s{2,}(\S.*)$", line)
        if not m or line.strip().startswith("check"):
            continue
        key, value = m.group(1), m.group(2)
        if key.startswith("fibre break strains"):
            vals = [number(x) for x in value.replace("%", "").split(",")]
            q["break_strain_min_pct"], q["break_strain_mean_pct"] = vals[:2]
            q["break_strain_max_pct"] = vals[2]
            q["break_strain_std_pct"] = number(value.split("std")[1])
        elif key.startswith("broken fibres"):
            q["broken_fibres"] = number(value)
        elif number(value) is not None:
            q[slug(key)] = number(value)
    return q


FIBRE_FAILURE = {
    "break_strain_min_pct": r"fibre break strains .*min ([\d.]+) %",
    "break_strain_spread_pct": r"spread of break strains\s+([\d.]+)",
    "peak_stress_mpa": r"peak axial Kirchhoff stress\s+([\d.]+)",
    "release_energy_j": r"truss energy released at the break\s+(\S+)",
    "dem_first_break_us": r"^\s+first break\s+([\d.]+)",
    "dem_peak_force_n": r"cut through \(force below 2 % of its peak ([\d.]+)",
    "dem_cut_us": r"cut through \(force below .*\)\s+([\d.]+) us",
    "dissipation_rate_mj_us": r"dissipation rate before the break\s+(\S+)",
    "failure_energy_mj": r"energy dissipated by the failure\s+(\S+)",
    "fe_area_mm2": r"FE section area\s+(\S+)",
    "plateau_from_us": r"plateau force \(median, ([\d.]+)-",
    "plateau_force_n": r"plateau force .*\)\s+([\d.]+) N",
    "plateau_ratio": r"plateau force .*N \(([\d.]+) of",
    "kink_us": r"force within 25 % of the plateau from\s+([\d.]+)",
    "tail_energy_mj": r"energy dissipated from there to the cut\s+(\S+)",
    "fe_strain_at_first_break_pct": r"up to the DEM's first break\s+([\d.]+) %",
    "fe_strain_at_first_break_t_us": r"up to the DEM's first break .*at ([\d.]+) us",
    "fe_strain_passed_again_us": r"first passed after it at\s+([\d.]+)",
    "strain_ratio": r"DEM fibre break strain / FE onset\s+([\d.]+)",
    "fe_strain_at_cut_pct": r"up to the DEM's cut-through\s+([\d.]+) %",
    "fe_strain_at_cut_t_us": r"up to the DEM's cut-through .*\(([\d.]+) us",
    "failure_strain": r"Yarn/Failure strain \(fibres, DEM\)\s+(\S+)",
    "onset": r"Yarn/Damage onset strain\s+(\S+)",
    "spread": r"Yarn/Damage onset spread\s+(\S+)",
    "back_face_onset": r"back-face onset ([\d.]+)",
    "g_f": r"Fracture energy G_f\s+(\S+)",
    "tail_stress": r"Yarn/Softening tail stress\s+(\S+)",
    "g_t": r"Softening tail energy G_t\s+(\S+)",
    "tail_kink_strain_pct": r"its kink and end .*face\s+([\d.]+) %",
    "tail_end_strain_pct": r"its kink and end .*, ([\d.]+) % fibre",
    "cell_energy_back_face": r"elastic energy per area .*onset\s+(\S+)",
    "final_strain_back_face_pct": r"final fibre strain of that cell .*\)\s+([\d.]+)",
}


def extract_fibre_failure(log):
    text = open(log).read()
    q = {}
    for key, pattern in FIBRE_FAILURE.items():
        m = re.search(pattern, text, re.M)
        if not m:
            raise SystemExit("registry.py: '%s' not in %s" % (key, log))
        q[key] = float(m.group(1))
    return q


def extract_compare(log):
    """compare_identified.py: a 't [us]' line with the instants, then one
    line per quantity and run; the largest differences."""
    q = {}
    instants = None
    for line in lines_of(log):
        if line.startswith("t [us]"):
            instants = [number(x) for x in line[28:].split()]
            continue
        if instants and len(line) > 28 and not line.startswith(" "):
            label, values = line[:28].strip(), line[28:].split()
            if len(values) != len(instants):
                continue
            for ti, x in zip(instants, values):
                if number(x) is not None:
                    q["%s.%gus" % (slug(label), ti)] = number(x)
        m = re.match(r"\s+(.+?): largest \|v - v_DEM\| up to ([\d.]+) us: "
                     r"([\d.]+) m/s", line)
        if m:
            q[slug(m.group(1)) + ".dv_max"] = float(m.group(3))
            q[slug(m.group(1)) + ".dv_max_until_us"] = float(m.group(2))
            w = re.search(r"largest width / initial ([\d.]+) \(DEM ([\d.]+)\)",
                          line)
            if w:
                q[slug(m.group(1)) + ".width_max"] = float(w.group(1))
                q["dem.width_max_until_%gus" % float(m.group(2))] = float(
                    w.group(2))
    return q


def extract_kink(log):
    q = {}
    run = None
    for line in lines_of(log):
        if line.startswith("-- "):
            run = slug(line[3:])
            continue
        m = re.search(r"mean I_tc (\S+), kinematic prediction (\S+)", line)
        if run and m:
            q[run + ".itc_mean"] = float(m.group(1).rstrip(","))
            q[run + ".itc_kinematic"] = float(m.group(2))
            # how much of the kinematic compaction the section's shear
            # relieves
            q[run + ".relieved_pct"] = 100. * (1. - q[run + ".itc_mean"]
                                               / q[run + ".itc_kinematic"])
    return q


def extract_consistency(log):
    """The mass per length and axial stiffness lines of each model against
    the DEM: mass_fe, mass_dem, mass_diff_pct (FE/DEM - 1), and for another
    model M (the hybrid) mass_M and mass_M_diff_pct; the same with ea;
    the wall time of each model's run (wall_fe_s, wall_dem_s, wall_M_s) and
    its ratio to the DEM's (wall_M_ratio), where the run printed them."""
    q = {}
    for line in lines_of(log):
        m = re.search(r"wall time \[s\]:\s+(\w+) ([\d.]+), DEM ([\d.]+) "
                      r"\(\w+/DEM = ([\d.]+)\)", line)
        if m:
            model = m.group(1).lower()
            q["wall_" + model + "_s"] = float(m.group(2))
            q["wall_dem_s"] = float(m.group(3))
            q["wall_" + model + "_ratio"] = float(m.group(4))
            continue
        for key, pat in (("mass", r"mass per length \[mg/m\]:"),
                         ("ea", r"axial stiffness EA \[N\]:")):
            if not re.search(pat, line):
                continue
            m = re.search(r"(\w+) ([\d.]+), DEM ([\d.]+) \(\w+/DEM - 1 = "
                          r"([-+\d.]+) %", line)
            if not m:
                continue
            model = m.group(1).lower()
            if model == "fe":
                q[key + "_fe"], q[key + "_dem"], q[key + "_diff_pct"] = (
                    float(m.group(2)), float(m.group(3)), float(m.group(4)))
            else:
                q[key + "_" + model] = float(m.group(2))
                q[key + "_" + model + "_diff_pct"] = float(m.group(4))
    if not q:
        raise SystemExit("registry.py: no model consistency lines in " + log)
    return q


def extract_recovery(log):
    errors = [float(x) for x in re.findall(r"relative error\s+([-+\d.eE]+\d)",
                                           open(log).read())]
    if not errors:
        raise SystemExit("registry.py: no relative errors in " + log)
    return {"largest_relative_error": max(abs(e) for e in errors),
            "constants_checked": len(errors)}


def extract_segment_length(log):
    """tests/dem/elementary_segment_length.sh: the largest difference of
    each column between 3 and 7 cross-sections over its scale."""
    q = {}
    for line in lines_of(log):
        m = re.match(r"(\w+)\s+largest difference (\S+) \(scale (\S+)\)",
                     line)
        if m:
            q[m.group(1) + "_rel"] = float(m.group(2)) / float(m.group(3))
    if not q:
        raise SystemExit("registry.py: no differences in " + log)
    q["stress_rel_max"] = max(v for k, v in q.items()
                              if k.startswith("tau_"))
    return q


def extract_fit(log):
    """identify_charmetant.py: the first block of constants (the joint
    fit), each with its standard error, and the condition number."""
    q = {}
    for line in lines_of(log):
        m = re.match(r"\s+(k_e|k_tc|p|k_td) \[[^\]]*\]\s+(\S+)\s+\+-\s+(\S+)",
                     line)
        if m and m.group(1) not in q:
            q[m.group(1)], q[m.group(1) + "_error"] = (float(m.group(2)),
                                                       float(m.group(3)))
        m = re.search(r"condition number of the relative Jacobian (\S+)", line)
        if m and "condition_number" not in q:
            q["condition_number"] = float(m.group(1))
    if "k_e" not in q:
        raise SystemExit("registry.py: no fitted constants in " + log)
    return q


def extract_sweep(folder):
    q = {}
    def rows(name):
        with open(os.path.join(folder, name)) as f:
            return list(csv.DictReader(f))
    for row in rows("critical_velocities.csv"):
        model = "smith" if row["model"].startswith("Smith") else row["model"]
        v = number(row["critical velocity [m/s]"])
        if v is not None:
            q["critical_" + model] = v
    for row in rows("ballistics.csv"):
        model, v = row["model"], float(row["impact velocity [m/s]"])
        key = "%s_%s" % (model, ("%g" % v).replace(".", "_"))
        for column, name in (("residual velocity [m/s]", "residual"),
                             ("energy absorbed [mJ]", "absorbed"),
                             ("first break [us]", "first_break"),
                             ("cut through [us]", "cut_through"),
                             ("end of run [us]", "end")):
            x = number(row[column])
            if x is not None:
                q["%s_%s" % (key, name)] = x
        at_once = number(row["breaks at once"]) or 0.
        q[key + "_at_once"] = at_once
        # The bisection's bracket: the model's fastest run that does not
        # break the yarn at once and its slowest run that does.
        crit = q.get("critical_" + model)
        if crit is None:
            continue
        if at_once:
            if v >= crit and v < q.get("critical_%s_above" % model, 1e300):
                q["critical_%s_above" % model] = v
        elif v <= crit and v > q.get("critical_%s_below" % model, -1.):
            q["critical_%s_below" % model] = v
    if not q:
        raise SystemExit("registry.py: no sweep results in " + folder)
    return q


def extract_run(run, log=None):
    """A run folder: extract_history's quantities; the last step; the first
    times the longitudinal front reaches the clamp (its largest position,
    the half span) and the transverse front the last station before it
    (within 3 % of the half span); every "window: NAME VALUE" line of the
    summary as window_NAME (and window_fit_end_us where the fit stopped at
    the clamp); with LOG, the printed set-up lines of an FE run."""
    q = extract_history(run)
    h = read_csv(history_file(run))
    t = h["t [us]"]
    q["steps"] = h["step"][-1]
    if "max longitudinal strain [-]" in h:
        q["strain_max_pct"] = 100. * max(h["max longitudinal strain [-]"])
    half = max(h["longitudinal front [mm]"])
    q["half_span_mm"] = half
    for key, column, level in (
            ("longitudinal_clamp_us", "longitudinal front [mm]", 1.0),
            ("transverse_clamp_us", "transverse front [mm]", 0.97)):
        hit = [ti for ti, x in zip(t, h[column]) if x >= level * half - 1e-9]
        if hit:
            q[key] = hit[0]
    summary = os.path.join(run, "summary.txt")
    for line in open(summary):
        m = re.match(r"\s+window: (.+?)\s{2,}(\S+)", line)
        if m and number(m.group(2)) is not None:
            q["window_" + slug(m.group(1))] = number(m.group(2))
        m = re.search(r"fitted up to ([\d.]+) us", line)
        if m:
            q["window_fit_end_us"] = float(m.group(1))
    if log:
        text = open(log).read()
        for key, pattern in (
                ("contact_step_ns", r"stable step of a surface node on it ([\d.]+) ns"),
                ("mass_mg", r"yarn mass ([\d.]+) mg"),
                ("mass_per_length_mg_m", r"mass per length ([\d.]+) mg/m"),
                ("ea_n", r"EA ([\d.]+) N"),
                ("stable_step_ns", r"stable time step ([\d.]+) ns"),
                ("used_step_ns", r"stable time step [\d.]+ ns, used ([\d.]+) ns")):
            m = re.search(pattern, text)
            if m:
                q[key] = float(m.group(1))
        m = re.search(r"cell kernel: (\S+)", text)
        if m:
            q["kernel"] = m.group(1)
    return q


EXTRACTORS = {
    "sweep": extract_sweep,
    "fit": extract_fit,
    "segment_length": extract_segment_length,
    "history": extract_history, "failure": extract_failure,
    "summary": extract_summary, "elementary": extract_elementary,
    "fibre_failure": extract_fibre_failure, "compare": extract_compare,
    "kink": extract_kink, "consistency": extract_consistency,
    "recovery": extract_recovery, "run": extract_run,
}


def record(args):
    quantities = {}
    for spec in args.extract:
        kind, *params = spec.split(":")
        prefix = ""
        if "=" in kind:
            prefix, kind = kind.split("=", 1)
            prefix += "."
        q = EXTRACTORS[kind](*params)
        quantities.update({prefix + k: v for k, v in q.items()})
    # Not stripped: each porcelain line starts with its two status columns,
    # blank ones included. The registry's own files do not count.
    status = subprocess.run(["git", "-C", ROOT, "status", "--porcelain"],
                            capture_output=True, text=True).stdout
    dirty = [line[3:] for line in status.splitlines()
             if line[3:] and not line[3:].startswith("doc/results/")]
    entry = {
        "case": args.case,
        "level": args.level,
        "command": args.command,
        "commit": git("rev-parse", "--short", "HEAD"),
        "commit_full": git("rev-parse", "HEAD"),
        "dirty": bool(dirty),
        "dirty_paths": dirty,
        "depends": args.depends,
        "machine": machine(),
        "date": datetime.datetime.now(datetime.timezone.utc)
                .strftime("%Y-%m-%dT%H:%M:%SZ"),
        "wall_s": round(args.wall, 1),
        "quantities": quantities,
    }
    os.makedirs(REGISTRY, exist_ok=True)
    path = os.path.join(REGISTRY, args.case + ".json")
    with open(path + ".tmp", "w") as f:
        json.dump(entry, f, indent=1, sort_keys=True)
        f.write("\n")
    os.replace(path + ".tmp", path)
    print("registry: %s (%d quantities, %.1f s)" % (
        os.path.relpath(path, ROOT), len(quantities), args.wall))


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    sub = ap.add_subparsers(dest="what", required=True)
    r = sub.add_parser("record")
    r.add_argument("--case", required=True)
    r.add_argument("--level", choices=("quick", "full"), required=True)
    r.add_argument("--command", required=True)
    r.add_argument("--wall", type=float, required=True)
    r.add_argument("--depends", nargs="+",
                   default=["source", "include", "prm"])
    r.add_argument("--extract", nargs="+", required=True,
                   help="KIND:ARG:ARG, optionally PREFIX=KIND:ARG")
    s = sub.add_parser("show")
    s.add_argument("case")
    args = ap.parse_args()
    if args.what == "record":
        record(args)
    else:
        print(open(os.path.join(REGISTRY, args.case + ".json")).read())


if __name__ == "__main__":
    main()
