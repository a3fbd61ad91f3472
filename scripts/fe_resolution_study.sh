#!/bin/bash
# FE resolution study of the paper's case: 1x, 2x, 4x refinement along the
# axis and in the section, quarter model (the symmetry test shows it gives
# the full model's history). Prints a markdown table of the projectile
# velocity at 10, 20, 25 and 30 us, the first cell failure and the
# cut-through time, and writes the same as 'key: value' lines to
# OUT_DIR/values.txt (aAXIAL_sSECTION_v_10us, ..._first_failure_us,
# ..._cut_through_us: the registry's case fe_resolution).
# Usage: scripts/fe_resolution_study.sh [BUILD_DIR] [OUT_DIR]
set -uo pipefail
build=${1:-build}
out=${2:-results/fe_resolution}
mkdir -p "$out"
rm -f "$out/values.txt"
printf '| cells along the axis | section refinements | cells (full yarn) | v(10 us) | v(20 us) | v(25 us) | v(30 us) | first failure [us] | cut through [us] | wall [s] |\n'
printf '|---|---|---|---|---|---|---|---|---|---|\n'
for axial in 100 200 400; do
  for section in 0 1 2; do
    dir="$out/a${axial}_s${section}"
    cat > "$dir.prm" <<PRM
set Symmetry = quarter
subsection Output
  set Directory         = $dir
  set Overwrite         = true
  set Snapshot interval = 0
  set Verbosity         = quiet
end
subsection FE
  set Cells along the axis = $axial
  set Section refinements  = $section
end
PRM
    start=$(date +%s)
    "$build/yarn-impact" "$dir.prm" > "$dir.log" 2>&1
    wall=$(( $(date +%s) - start ))
    /usr/bin/python3 - "$dir" "$axial" "$section" "$wall" <<'PY'
import csv, sys
d, axial, section, wall = sys.argv[1], int(sys.argv[2]), int(sys.argv[3]), float(sys.argv[4])
rows = list(csv.DictReader(open(d + "/history_fe.csv")))
def v(t):
    r = min(rows, key=lambda r: abs(float(r["t [us]"]) - t))
    return float(r["projectile velocity [m/s]"])
fail = next((round(float(r["t [us]"]), 2) for r in rows if int(r["failed elements"]) > 0), None)
cut, summary = None, True
try:
    for line in open(d + "/summary.txt"):
        if "yarn cut through:" in line and "us" in line:
            cut = float(line.split()[-2])
except FileNotFoundError:  # a run stopped by an error writes no summary
    summary = False
cells = 12 * 4 ** section * axial
error = [l.split("yarn-impact: error: ", 1)[1].strip() for l in open(d + ".log") if "yarn-impact: error: " in l]
key = f"a{axial}_s{section}_"
with open(d.rsplit("/", 1)[0] + "/values.txt", "a") as f:
    for t in (10, 20, 25, 30):
        f.write(f"{key}v_{t}us: {v(t)!r}\n")
    f.write(f"{key}first_failure_us: {fail if fail is not None else 'none'}\n")
    f.write(f"{key}cut_through_us: {cut if cut is not None else ('no' if summary else 'stopped')}\n")
    f.write(f"{key}wall_s: {wall:.0f}\n")
print(f"| {axial} | {section} | {cells} | {v(10):.2f} | {v(20):.2f} | {v(25):.2f} | {v(30):.2f} | "
      f"{fail if fail is not None else 'none'} | {cut if cut is not None else ('no' if summary else '-')} | {wall:.0f} |"
      + (f" stopped: {error[0]}" if error else ""))
PY
  done
done
