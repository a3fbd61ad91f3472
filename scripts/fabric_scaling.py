#!/usr/bin/env python3
"""The cost of a larger `Model = fabric` case from the fabric benchmark's
measurements: an estimate, not a measurement (doc/fabric.md section 9).

Input: the outputs of `bench_fabric_throughput` (its `key: value` lines) for
the same case on 1, 2, 3 ... ranks. From them:
- the cells, dofs and yarn-contact surface nodes per cell of the measured
  case, and the mean step (the step depends on the cells' size and the
  contact springs, not on the patch's extent or its plies);
- the cell-steps per second per core of the timed loop on each rank count,
  and the parallel efficiency E(N) = rate per core on N ranks / on 1;
- the peak memory per rank fitted as M(N) = R + D / N [MB] over the rank
  counts: R is what every rank holds whole (the patch's serial mesh, from
  which the yarn contact's surface is made, p4est's coarse mesh of every
  cell, the contact's arrays of every surface node), D what the ranks share
  out; both grow with the cells.

The panel: `--size` [m] square at the measured pitch `--pitch` [m] with
`--cells-per-spacing` and the 12-cell section, `--plies` plies, run to
`--end-time` [s]; its wall time on each N of `--ranks` is
cells x steps / (rate per core on 1 rank x N x E), E the `--efficiency`
given, or the one measured on the largest rank count; the rates are those
of the timed loop without its snapshots (StepTimer's `output`), so that
the estimate leaves the snapshots out.

    python3 scripts/fabric_scaling.py RUN_1RANK.txt RUN_2RANKS.txt ...
        [--size 0.1] [--plies 4] [--pitch 0.747e-3] [--cells-per-spacing 8]
        [--end-time 100e-6] [--efficiency E] [--ranks 16 64 256 1024]
"""
import argparse
import sys


def read_run(path):
    """The benchmark's `key: value` lines as a dict of floats (or text)."""
    values = {}
    with open(path) as f:
        for line in f:
            if line.startswith("  output |"):
                # StepTimer's line of the snapshots: wall s, ..., CPU s.
                fields = line.split("|")
                values["output [s]"] = float(fields[1])
                values["output, CPU [s]"] = float(fields[4])
                continue
            if ": " not in line or line.startswith(" "):
                continue
            key, value = line.rstrip("\n").split(": ", 1)
            try:
                values[key] = float(value)
            except ValueError:
                values[key] = value
    for key in ("ranks", "cells", "dofs", "contact surface nodes", "steps",
                "mean step [ns]", "timed loop [s]", "timed loop, CPU [s]",
                "peak memory per rank, largest [MB]", "output [s]"):
        if key not in values:
            sys.exit(f"fabric_scaling.py: {path} has no '{key}' line "
                     "(not an output of bench_fabric_throughput?)")
    return values


def fit_memory(runs):
    """Least squares of M(N) = R + D / N over the runs [MB]."""
    xs = [1.0 / r["ranks"] for r in runs]
    ys = [r["peak memory per rank, largest [MB]"] for r in runs]
    n = len(xs)
    if n == 1:
        return ys[0], 0.0
    mx, my = sum(xs) / n, sum(ys) / n
    sxx = sum((x - mx) ** 2 for x in xs)
    D = sum((x - mx) * (y - my) for x, y in zip(xs, ys)) / sxx if sxx else 0.0
    return my - D * mx, D


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("runs", nargs="+", help="bench_fabric_throughput outputs")
    p.add_argument("--size", type=float, default=0.1, help="panel side [m]")
    p.add_argument("--plies", type=int, default=4)
    p.add_argument("--pitch", type=float, default=0.747e-3,
                   help="yarn spacing [m]")
    p.add_argument("--cells-per-spacing", type=int, default=8)
    p.add_argument("--section-cells", type=int, default=12)
    p.add_argument("--end-time", type=float, default=100e-6, help="[s]")
    p.add_argument("--efficiency", type=float, default=None,
                   help="parallel efficiency on the cluster (default: the "
                        "one measured on the largest rank count)")
    p.add_argument("--ranks", type=int, nargs="+",
                   default=[16, 64, 256, 1024])
    p.add_argument("--clock", choices=["wall", "cpu"], default="wall",
                   help="the loop's wall time, or its CPU time (on a "
                        "machine loaded by other jobs)")
    a = p.parse_args()
    loop_key = "timed loop [s]" if a.clock == "wall" else "timed loop, CPU [s]"
    output_key = "output [s]" if a.clock == "wall" else "output, CPU [s]"

    runs = sorted((read_run(f) for f in a.runs), key=lambda r: r["ranks"])
    # The loop without its snapshots (written at the start and the end of a
    # short run; their cost is per snapshot, not per step).
    loop = "loop without snapshots"
    for r in runs:
        r[loop] = r[loop_key] - r[output_key]
    base = runs[0]
    if base["ranks"] != 1:
        sys.exit("fabric_scaling.py: give the run on 1 rank (the efficiency "
                 "is measured against it)")
    for r in runs:
        if r["cells"] != base["cells"]:
            sys.exit("fabric_scaling.py: the runs are not of the same case")

    cells = base["cells"]
    print(f"Measured case: {base.get('case', '?')}: {cells:.0f} cells, "
          f"{base['dofs']:.0f} dofs, {base['contact surface nodes']:.0f} "
          f"contact surface nodes, {base['steps']:.0f} steps, mean step "
          f"{base['mean step [ns]']:.4f} ns")
    print(f"ranks | loop without snapshots [s] ({a.clock}) | cell-steps/s "
          "per core (loop) | "
          "efficiency | peak memory per rank [MB]")
    rate1 = cells * base["steps"] / base[loop]
    efficiency = {}
    for r in runs:
        rate = cells * r["steps"] / r[loop] / r["ranks"]
        efficiency[int(r["ranks"])] = rate / rate1
        print(f"{r['ranks']:.0f} | {r[loop]:.2f} | "
              f"{rate / 1e6:.3f} M | {rate / rate1:.3f} | "
              f"{r['peak memory per rank, largest [MB]']:.0f}")
    R, D = fit_memory(runs)
    print(f"memory per rank fitted: {R:.0f} MB held whole + {D:.0f} MB / N "
          f"shared out ({1e3 * R / cells:.2f} + {1e3 * D / cells:.2f} kB "
          "per cell / N)")

    n_yarns = round(a.size / a.pitch)
    panel_cells = (a.section_cells * a.cells_per_spacing * 2 * n_yarns *
                   n_yarns * a.plies)
    scale = panel_cells / cells
    steps = a.end_time / (base["mean step [ns]"] * 1e-9)
    E = a.efficiency if a.efficiency is not None else \
        efficiency[max(efficiency)]
    print()
    print(f"Panel: {a.size * 1e3:.0f} x {a.size * 1e3:.0f} mm, {a.plies} "
          f"plies, {n_yarns} x {n_yarns} yarns per ply at "
          f"{a.pitch * 1e3:.3f} mm, {a.cells_per_spacing} cells per spacing")
    print(f"cells {panel_cells:.4g}, dofs {base['dofs'] * scale:.4g}, "
          f"contact surface nodes {base['contact surface nodes'] * scale:.4g}"
          f", steps to {a.end_time * 1e6:.0f} us {steps:.4g}, cell-steps "
          f"{panel_cells * steps:.4g}")
    print(f"wall time ({a.clock} clock, no snapshots) from "
          f"{rate1 / 1e6:.3f} M cell-steps/s on one core and a parallel "
          f"efficiency of {E:.2f}:")
    print("ranks | wall time [h] | peak memory per rank [GB]")
    for n in a.ranks:
        hours = panel_cells * steps / (rate1 * n * E) / 3600.
        memory = (R + D / n) * scale / 1e3
        print(f"{n} | {hours:.3g} | {memory:.3g}")


if __name__ == "__main__":
    main()
