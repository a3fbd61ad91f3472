#!/usr/bin/python3
"""Plots of a run of several models (`Model = both`, `fe, dem, hybrid`).

Usage: plot_comparison.py DIRECTORY

Writes DIRECTORY/velocity_comparison.png (the paper's Fig. 6: projectile
velocity of every model of the run) and DIRECTORY/wave_fronts.png
(longitudinal, transverse and spreading front positions of every model
against time). Reads DIRECTORY/comparison.csv (the models on one time grid,
written by a run that reached its end); without it, each model's own
history (history_fe.csv, history_dem.csv, history_hybrid.csv), each over
the time it ran.
"""
import csv
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

STYLE = {
    "figure.facecolor": "white",
    "axes.facecolor": "white",
    "savefig.facecolor": "white",
    "axes.edgecolor": "black",
    "axes.labelcolor": "black",
    "text.color": "black",
    "xtick.color": "black",
    "ytick.color": "black",
    "axes.grid": True,
    "grid.alpha": 0.3,
    "font.size": 11,
    "legend.frameon": True,
    "legend.framealpha": 0.9,
}
MODELS = (("FE", "FE (hyperelastic continuum)", "C0"),
          ("DEM", "DEM (fibres)", "C3"),
          ("hybrid", "hybrid (fibres near the nose, continuum and fibre "
           "bars beyond)", "C2"))
FRONTS = (("longitudinal", ":"), ("transverse", "-"), ("spreading", "--"))


def read(path):
    with open(path) as f:
        return list(csv.DictReader(f))


def column(rows, name):
    return [float(r[name]) for r in rows]


def series(directory):
    """{model: {"t": [...], "v": [...], front: [...]}} from comparison.csv,
    or from the two histories; and a note on the source."""
    comparison = os.path.join(directory, "comparison.csv")
    data = {}
    if os.path.exists(comparison):
        rows = read(comparison)
        for model, _, _ in MODELS:
            if f"v {model} [m/s]" not in rows[0]:
                continue
            d = {"t": column(rows, "t [us]"),
                 "v": column(rows, f"v {model} [m/s]")}
            for front, _ in FRONTS:
                d[front] = column(rows, f"{front} front {model} [mm]")
            data[model] = d
        return data, "comparison.csv"
    for model, _, _ in MODELS:
        path = os.path.join(directory, f"history_{model.lower()}.csv")
        if not os.path.exists(path):
            continue
        rows = read(path)
        d = {"t": column(rows, "t [us]"),
             "v": column(rows, "projectile velocity [m/s]")}
        for front, _ in FRONTS:
            d[front] = column(rows, f"{front} front [mm]")
        data[model] = d
    if not data:
        sys.exit(f"{directory}: no comparison.csv nor history_*.csv")
    return data, ", ".join(f"history_{m.lower()}.csv" for m in data)


def end_note(ax, data):
    """Mark where a model's history stops before the other's."""
    t_end = max(d["t"][-1] for d in data.values())
    for model, _, colour in MODELS:
        if model in data and data[model]["t"][-1] < 0.98 * t_end:
            t = data[model]["t"][-1]
            ax.axvline(t, color=colour, lw=0.8, ls="-.")
            ax.annotate(f"{model} history ends at {t:.3g} \u00b5s",
                        xy=(t, 0.03), xycoords=("data", "axes fraction"),
                        xytext=(4, 0), textcoords="offset points",
                        color=colour, fontsize=9)


def resolved_entries(directory):
    """{"Section/Entry": value} of the run's resolved DIRECTORY/parameters.prm
    (empty without it)."""
    path = os.path.join(directory, "parameters.prm")
    entries, section = {}, []
    if not os.path.exists(path):
        return entries
    with open(path) as f:
        for line in f:
            words = line.split()
            if words[:1] == ["subsection"]:
                section.append(" ".join(words[1:]))
            elif words[:1] == ["end"] and section:
                section.pop()
            elif words[:1] == ["set"] and "=" in line:
                name, value = line.split("=", 1)
                key = "/".join(section + [name.strip()[4:].strip()])
                entries[key] = value.strip()
    return entries


def fe_label(entries):
    """The FE curve's legend: the law and the failure model of the run (the
    generic label without its parameters)."""
    if not entries:
        return MODELS[0][1]
    law = entries.get("FE/Constitutive law", "?")
    if entries.get("Yarn/Failure", "true") != "true":
        failure = "no failure"
    else:
        failure = {"sudden": "sudden failure (the paper's)",
                   "progressive": "progressive failure (identified)"}.get(
                       entries.get("Yarn/Failure model"), "?")
    return f"FE, {law} law, {failure}"


def hybrid_label(entries):
    """The hybrid curve's legend: its DEM half-length and far field."""
    if not entries:
        return MODELS[2][1]
    a = float(entries.get("Hybrid/DEM half-length", "nan")) * 1e3
    far = entries.get("Hybrid/Far field", "?")
    return f"hybrid, fibres to |x| = {a:.2g} mm, {far} beyond"


def main():
    if len(sys.argv) != 2:
        sys.exit(__doc__)
    directory = sys.argv[1]
    data, source = series(directory)
    plt.rcParams.update(STYLE)
    run = os.path.basename(os.path.normpath(directory))

    fig, ax = plt.subplots(figsize=(6.4, 4.4))
    entries = resolved_entries(directory)
    labels = {"FE": fe_label(entries), "hybrid": hybrid_label(entries)}
    for model, label, colour in MODELS:
        if model in data:
            # Dashed, so that the DEM's curve shows under the hybrid's.
            ax.plot(data[model]["t"], data[model]["v"], color=colour,
                    ls="--" if model == "hybrid" else "-",
                    label=labels.get(model, label))
    end_note(ax, data)
    ax.set_xlabel("time t [\u00b5s]")
    ax.set_ylabel("projectile velocity [m/s]")
    ax.set_xlim(left=0)
    ax.set_title(f"Projectile velocity ({run}: {source})", fontsize=10)
    ax.legend(loc="upper right")
    fig.tight_layout()
    fig.savefig(os.path.join(directory, "velocity_comparison.png"), dpi=150)

    fig, ax = plt.subplots(figsize=(6.4, 4.4))
    for front, style in FRONTS:
        for model, _, colour in MODELS:
            if model in data:
                ax.plot(data[model]["t"], data[model][front], style,
                        color=colour, label=f"{front} front, {model}")
    end_note(ax, data)
    ax.set_xlabel("time t [\u00b5s]")
    ax.set_ylabel("front position from the impact point [mm]")
    ax.set_xlim(left=0)
    ax.set_ylim(bottom=0)
    ax.set_title(f"Wave fronts ({run}: {source})", fontsize=10)
    ax.legend(fontsize=8, loc="center right")
    fig.tight_layout()
    fig.savefig(os.path.join(directory, "wave_fronts.png"), dpi=150)


if __name__ == "__main__":
    main()
