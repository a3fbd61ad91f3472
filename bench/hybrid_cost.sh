#!/bin/bash
# Cost of the hybrid yarn against the full DEM, side by side on this
# machine (a benchmark, not a test; doc/hybrid.md section 6).
#
#   bench/hybrid_cost.sh [RANKS=2] [HYBRID_PRM=prm/hybrid/km2_600ms_fibre_bars.prm]
#                        [DEM_PRM=prm/study/dem_600ms.prm]
#
# Runs the two cases one after the other (nothing else should run on the
# machine), without snapshots, in a temporary folder, and prints for each:
# steps, wall time of the whole run, time in the forces (the timer's
# "forces" section: contact, trusses, bars and coupling), wall time per
# step, and the hybrid's time over the DEM's.
set -euo pipefail
cd "$(dirname "$0")/.."
ranks=${1:-2}
hybrid_prm=${2:-prm/hybrid/km2_600ms_fibre_bars.prm}
dem_prm=${3:-prm/study/dem_600ms.prm}
exe=build/yarn-impact
[ -x "$exe" ] || { echo "hybrid_cost.sh: build $exe first (README)"; exit 1; }
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

run() {
  local name=$1 prm=$2
  {
    cat "$prm"
    printf 'subsection Output\n  set Directory = %s\n  set Snapshot interval = 0\nend\n' "$work/$name"
  } > "$work/$name.prm"
  mpirun -np "$ranks" "$exe" "$work/$name.prm" > "$work/$name.log" 2>&1 ||
    { echo "hybrid_cost.sh: $name failed:"; tail -5 "$work/$name.log"; exit 1; }
}

echo "Side by side on $(nproc) cores, $ranks rank(s), commit $(git rev-parse --short HEAD 2>/dev/null || echo unknown)"
run dem "$dem_prm"
run hybrid "$hybrid_prm"
/usr/bin/python3 - "$work" "$dem_prm" "$hybrid_prm" << 'END'
import re, sys
work, dem_prm, hybrid_prm = sys.argv[1:4]
rows = {}
for name in ("dem", "hybrid"):
    log = open(f"{work}/{name}.log").read()
    wall = float(re.search(r"Total wallclock time elapsed since start\s*\|\s*([0-9.e+]+)s", log).group(1))
    # The forces' calls: one a step.
    match = re.search(r"\|\s*forces\s*\|\s*(\d+)\s*\|\s*([0-9.e+]+)s", log)
    rows[name] = (int(match.group(1)), wall, float(match.group(2)))
print(f"| Run | steps | wall [s] | forces [s] | per step [ms] |")
print(f"|---|---|---|---|---|")
for name, prm in (("dem", dem_prm), ("hybrid", hybrid_prm)):
    steps, wall, forces = rows[name]
    print(f"| {prm} | {steps} | {wall:.1f} | {forces:.1f} | {1e3 * wall / steps:.2f} |")
print(f"hybrid / DEM wall time: {rows['hybrid'][1] / rows['dem'][1]:.2f}")
# The same as "key: value" lines, for the registry of runs
# (scripts/registry.py, extractor summary).
for name in ("dem", "hybrid"):
    steps, wall, forces = rows[name]
    print(f"{name} steps: {steps}")
    print(f"{name} wall [s]: {wall:.1f}")
    print(f"{name} forces [s]: {forces:.1f}")
    print(f"{name} per step [ms]: {1e3 * wall / steps:.2f}")
END
