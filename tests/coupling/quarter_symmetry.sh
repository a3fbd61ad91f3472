#!/bin/bash
# Usage: quarter_symmetry.sh YARN_IMPACT SOURCE_DIR
# The hybrid yarn with quarter symmetry (x >= 0, z >= 0) against the same
# yarn with half symmetry, whose fibres and mesh are symmetric about z = 0
# (a consistency check against an independent run, no recorded numbers):
# - the fibres: the 393 sites of a hexagonal lattice of spacing d inside
#   the paper's ellipse, a layout symmetric about z = 0 with fibres on the
#   plane (half fibres in the quarter model);
# - the ready case (prm/hybrid/km2_120ms_hybrid.prm) with a 3 mm DEM part
#   over 0.6 us, the longitudinal wave through the overlap and into the FE
#   part, with each far field (continuum and fibre bars);
# - the histories of the whole yarn agree: the projectile's velocity and
#   force, the energies and the largest strain within 1e-5 (the two models
#   sum their forces in different orders), the
#   failed elements equal (relative to each quantity's largest value
#   over the run).
# - every one of these runs conserves the projectile's and the yarn's
#   momentum along the impact direction within 1e-9 of m v0
#   (momentum_balance.py);
exe=$1
src=$2
. "$(dirname "$(readlink -f "$0")")/../lib.sh"
test_begin

/usr/bin/python3 - << 'END'
import math
d, ay, az = 12e-6, 0.0575e-3, 0.267e-3
h = d * math.sqrt(3) / 2
with open("fibres.txt", "w") as out:
    for i in range(-10, 11):
        for j in range(-40, 41):
            y, z = i * h, (j + 0.5 * (i % 2)) * d
            if (y / ay) ** 2 + (z / az) ** 2 <= 1:
                out.write(f"{y:.15e} {z:.15e}\n")
END
n=$(wc -l < fibres.txt)

# case SYMMETRY FAR_FIELD DIR
case_prm() {
  cat "$src/prm/hybrid/km2_120ms_hybrid.prm"
  printf 'set Symmetry = %s\n' "$1"
  printf 'subsection Yarn\n  set Number of fibres = %s\nend\n' "$n"
  printf 'subsection DEM\n  set Fibre layout = file\n  set Fibre file = %s\nend\n' "$work/fibres.txt"
  printf 'subsection Hybrid\n  set DEM half-length = 3e-3\n  set Far field = %s\nend\n' "$2"
  printf 'subsection Time\n  set End time = 0.6e-6\nend\n'
  printf 'subsection Output\n  set Directory = %s\n  set Snapshot interval = 0\n' "$3"
  printf '  set History interval = 0.05e-6\nend\n'
}

. "$src/tests/coupling/run_checks.sh"
same_motion quarter "quarter model"

test_end "hybrid: quarter = half for both far fields: all passed"
