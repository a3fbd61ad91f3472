#!/bin/bash
# The FE failure laws on the paper's case and its refinements, and at 200
# and 300 m/s, on one rank; the tables of doc/validation.md section 6.
# Usage: scripts/failure_study.sh [BUILD_DIR] [OUT_DIR] [CASE...]
# (from the repository root; CASE names from the list below, all if none).
# The DEM references: doc/figures/history_dem_km2_120ms.csv (120 m/s),
# history_dem_km2_200ms.csv (prm/study/dem_200ms.prm) and
# history_dem_km2_300ms.csv.
build=${1:-build}
out=${2:-results/failure_study}
shift 2 2> /dev/null
mkdir -p "$out"
root=$(cd "$(dirname "$0")/.." && pwd)

case_lines() { # name -> the prm lines of that case
  local v=120 model=progressive fric="" mesh="" spread="" tail="" fibres=""
  case $1 in
    sudden_mu0)     model=sudden; fric=0 ;;
    sudden)         model=sudden ;;
    progressive_mu0) fric=0 ;;
    progressive) ;;
    progressive_nospread) spread=0 ;;
    progressive_spread05) spread=0.5 ;;
    # The FE yarn with the DEM yarn's mass per length and axial stiffness
    # (FE/Density from fibres, FE/Axial modulus from fibres).
    progressive_fibres) fibres=1 ;;
    progressive_axial2x) mesh="set Cells along the axis = 200" ;;
    progressive_section2x) mesh="set Section refinements = 1" ;;
    progressive_section4x) mesh="set Section refinements = 2" ;;
    sudden_section2x) model=sudden; mesh="set Section refinements = 1" ;;
    sudden_section4x) model=sudden; mesh="set Section refinements = 2" ;;
    sudden_200)      model=sudden; v=200 ;;
    progressive_200) v=200 ;;
    sudden_300)      model=sudden; v=300 ;;
    progressive_300) v=300 ;;
    # The bilinear envelope with the tail identified from the DEM
    # (doc/identification.md section 8).
    tail)           tail=1 ;;
    tail_axial2x)   tail=1; mesh="set Cells along the axis = 200" ;;
    tail_section2x) tail=1; mesh="set Section refinements = 1" ;;
    tail_200)       tail=1; v=200 ;;
    tail_300)       tail=1; v=300 ;;
    *) echo "unknown case $1" >&2; return 1 ;;
  esac
  # An include is resolved against the including file's folder ($out).
  echo "include $root/prm/km2_120ms_fe_progressive.prm"
  echo "subsection Yarn"
  echo "  set Failure model = $model"
  [ -n "$spread" ] && echo "  set Damage onset spread = $spread"
  [ -n "$tail" ] && printf '  set Softening tail stress = 0.128\n  set Softening tail energy = 2.085e4\n'
  echo "end"
  echo "subsection Projectile"
  echo "  set Initial velocity = $v"
  echo "end"
  echo "subsection Output"
  echo "  set Directory = $out/$1"
  echo "  set Snapshot interval = 0"
  echo "  set Overwrite = true"
  echo "end"
  echo "subsection FE"
  echo "  $mesh"
  [ -n "$fric" ] && printf '  subsection Contact\n    set Friction coefficient = %s\n  end\n' "$fric"
  [ -n "$fibres" ] && printf '  set Density from fibres = true\n  set Axial modulus from fibres = true\n'
  echo "end"
}

cases=("$@")
[ ${#cases[@]} -eq 0 ] && cases=(sudden_mu0 sudden progressive_mu0 progressive
  progressive_nospread progressive_spread05 progressive_fibres progressive_axial2x progressive_section2x progressive_section4x
  sudden_section2x sudden_section4x sudden_200 progressive_200 sudden_300
  progressive_300 tail tail_axial2x tail_section2x tail_200 tail_300)
for c in "${cases[@]}"; do
  case_lines "$c" > "$out/$c.prm" || exit 1
  /usr/bin/time -f "$c: %e s" "$build/yarn-impact" "$out/$c.prm" \
    > "$out/$c.log" 2>&1 || echo "$c: exit $?"
  tail -1 "$out/$c.log"
done
