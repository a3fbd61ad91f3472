#!/bin/bash
# Sanity check of the LAMMPS set-up on a small yarn (40 fibres x 6 mm,
# 13 760 spheres, 1 rank, a few seconds): the cylinder moves at 120 m/s for
# 1500 steps, then stands still for 1500. Checks: no LAMMPS error, the
# cylinder touches the yarn (spheres within R + r of its axis), no sphere
# faster than 1000 m/s (a blow-up; the spheres the nose throws off move at
# ~2 x 120 m/s), and once the cylinder stands still the energy (kinetic +
# rotational + truss; the contact springs' energy is not tallied by LAMMPS's
# granular styles) does not grow by more than 5 %.
#   NICE=19 bash bench/lammps/check.sh
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
work=${WORK:-$here/work}
dt=${DT:-1.2e-9}
rot=${ROT:-1}
nice_level=${NICE:-0}
mkdir -p "$work"; cd "$work"
nice -n "$nice_level" /usr/bin/python3 "$here/make_yarn.py" --fibres 40 --length 6e-3 \
  --data check.data --params check.params.in
nice -n "$nice_level" lmp -in "$here/yarn.in" -log check.lammps -screen none \
  -var nsteps 3000 -var stop 1500 -var thermo 100 -var dt "$dt" -var rot "$rot" \
  -var data check.data -var params check.params.in || true
grep -v WARNING check.lammps | sed -n '/^Step/,/^Loop time/p'
grep -v WARNING check.lammps | awk '
  /^ERROR/ { err = 1 }
  /^Step/ { on = 1; next }
  /^Loop time/ { on = 0; done = 1 }
  on && $1 ~ /^[0-9]+$/ {
    if ($10 > 0) touched = 1
    if ($11 > vmax) vmax = $11
    if ($1 == 1500) e_stop = $7
    if ($1 > 1500 && $7 > emax) emax = $7
  }
  END {
    ok = !err && done && touched && vmax < 1000 && emax <= 1.05 * e_stop
    printf "check: %s (error %d, finished %d, cylinder touched %d, max speed %.0f m/s, energy at stop %.4g J, largest after %.4g J)\n",
      ok ? "PASSED" : "FAILED", err, done, touched, vmax, e_stop, emax
    exit !ok
  }'
