#!/bin/bash
# Usage: impact_speed.sh YARN_IMPACT
# Any impact velocity either runs (the yarn breaks) or is refused with a
# reason: the FE stable step follows the closing speed of the impact
# (doc/fe-model.md), and a step too small to reach the end time is refused.
exe=$1
. "$(dirname "$(readlink -f "$0")")/../lib.sh"
test_begin

case_prm() { # velocity, directory, extra FE lines, extra top-level lines
  printf 'set Symmetry = quarter\nsubsection Projectile\n  set Initial velocity = %s\nend\n' "$1"
  printf '%s\n' "$4"
  printf 'subsection Time\n  set End time = 2e-6\nend\n'
  printf 'subsection Output\n  set Directory = %s\n  set Snapshot interval = 0\nend\n' "$2"
  printf 'subsection FE\n  set Cells along the axis = 50\n%s\nend\n' "$3"
}

# Above Smith's critical velocity (1017 m/s) the yarn breaks at once: the
# run must go through, conserving energy, with the first failure within
# 0.5 us and the projectile keeping more than 95 % of its speed.
for v in 1500 5000; do
  case_prm $v v$v "" > v$v.prm
  "$exe" v$v.prm > stdout 2> stderr
  rc=$?
  first=$(sed -n 's/^  first failure: *\([0-9.]*\) us/\1/p' v$v/summary.txt 2> /dev/null)
  vr=$(sed -n 's/^  final projectile velocity: *\([0-9.]*\) m.s/\1/p' v$v/summary.txt 2> /dev/null)
  err=$(sed -n 's/^  largest energy error: *\([0-9.]*\) %.*/\1/p' v$v/summary.txt 2> /dev/null)
  if [ $rc -ne 0 ]; then
    fail "$v m/s: exit $rc: $(head -c 300 stderr)"
  elif [ -z "$first" ] || ! awk -v f="$first" 'BEGIN { exit !(f < 0.5) }'; then
    fail "$v m/s: no failure within 0.5 us (first failure: '$first')"
  elif ! awk -v r="$vr" -v v="$v" 'BEGIN { exit !(r > 0.95 * v && r < v) }'; then
    fail "$v m/s: residual velocity $vr m/s"
  elif ! awk -v e="$err" 'BEGIN { exit !(e < 1.0) }'; then
    fail "$v m/s: energy error $err % (limit 1 %)"
  else
    echo "ok     $v m/s: first failure at $first us, residual velocity $vr m/s, largest energy error $err %"
  fi
done

# A projectile that would cross a cell in one step, and a units typo.
refused() { # name, velocity, extra FE lines, extra top-level lines
  case_prm "$2" r "$3" "$4" > r.prm
  rm -rf r
  "$exe" r.prm > stdout 2> stderr
  rc=$?
  if [ $rc -ne 1 ] || [ "$(wc -l < stderr)" -ne 1 ] ||
     ! grep -qF "more than Time/Maximum number of steps" stderr; then
    fail "$1: exit $rc: $(head -c 300 stderr)"
  else
    echo "ok     $1: $(cat stderr)"
  fi
}
refused "1e8 m/s" 1e8 ""
# (with the sudden law: the progressive law refuses such a k_e earlier,
# its softening snapping back, tests/app/bad)
refused "k_e = 1e30 Pa" 120 "  subsection Charmetant
    set k_e = 1e30
  end" "subsection Yarn
  set Failure model = sudden
end"
# The DEM: a projectile that would jump over spheres is refused the same way.
printf 'set Model = dem\nset Symmetry = half\nsubsection Yarn\n  set Length = 2e-3\n' > d.prm
printf '  set Number of fibres = 40\n  set Thickness semi-axis = 0.0182e-3\n' >> d.prm
printf '  set Width semi-axis = 0.0844e-3\nend\nsubsection Projectile\n' >> d.prm
printf '  set Mass = 0.991e-6\n  set Diameter = 1e-3\n  set Initial velocity = 1e8\nend\n' >> d.prm
printf 'subsection Output\n  set Directory = d\nend\n' >> d.prm
"$exe" d.prm > stdout 2> stderr
rc=$?
if [ $rc -ne 1 ] || ! grep -qF "dem model's stable time step" stderr ||
   ! grep -qF "Time/Maximum number of steps" stderr; then
  fail "DEM at 1e8 m/s: exit $rc: $(head -c 300 stderr)"
else
  echo "ok     DEM at 1e8 m/s: $(cat stderr)"
fi
test_end
