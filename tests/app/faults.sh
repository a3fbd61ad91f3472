#!/bin/bash
# Usage: faults.sh YARN_IMPACT
# Faults while writing output must not lose data. A full disk is simulated
# by the fault injection YARN_IMPACT_DISK_FULL_AFTER=N (every output write
# after N bytes fails with ENOSPC; doc/user-guide.md), and, where this
# machine lets us mount one, by a real 100 kB tmpfs. Each case must end with
# exit code 5 and one line naming the file and "no space left on device";
# the history must end with its last whole row; no summary.txt, snapshot or
# PVD may be left half-written (no *.tmp either).
exe=$1
. "$(dirname "$(readlink -f "$0")")/../lib.sh"
test_begin cleanup
cleanup() { mountpoint -q "$work/tmpfs" 2> /dev/null && umount "$work/tmpfs"; }

# A small FE case: quarter symmetry, 40 cells along the axis.
fe_prm() { # directory, end time, snapshot interval
  printf 'set Symmetry = quarter\nsubsection Time\n  set End time = %s\nend\n' "$2"
  printf 'subsection Output\n  set Directory = %s\n  set Snapshot interval = %s\n' "$1" "$3"
  printf '  set History interval = 0.01e-6\n  set Verbosity = quiet\nend\n'
  printf 'subsection FE\n  set Cells along the axis = 40\nend\n'
}
# A small DEM case (40 fibres, 2 mm).
dem_prm() { # directory, snapshot interval
  printf 'set Model = dem\nset Symmetry = half\n'
  printf 'subsection Yarn\n  set Length = 2e-3\n  set Number of fibres = 40\n'
  printf '  set Thickness semi-axis = 0.0182e-3\n  set Width semi-axis = 0.0844e-3\nend\n'
  printf 'subsection Projectile\n  set Mass = 0.991e-6\n  set Diameter = 1e-3\nend\n'
  printf 'subsection Time\n  set End time = 0.3e-6\nend\n'
  printf 'subsection Output\n  set Directory = %s\n  set Snapshot interval = %s\n' "$1" "$2"
  printf '  set History interval = 0.01e-6\n  set Verbosity = quiet\nend\n'
}

# check NAME DIR FILE-PATTERN [RANKS]: the last run failed as a full disk
# on FILE-PATTERN, and DIR holds nothing half-written.
check() {
  local name=$1 dir=$2 file=$3
  if [ "$rc" -ne 5 ]; then
    fail "$name: exit code $rc (expected 5): $(head -c 300 stderr)"; return
  fi
  # The program's one line comes first (mpirun may add its own note after).
  if { [ -z "$4" ] && [ "$(wc -l < stderr)" -ne 1 ]; } ||
     ! head -1 stderr | grep -qE "^yarn-impact: error: cannot write '[^']*$file': no space left on device\.$"; then
    fail "$name: message: $(head -c 300 stderr)"; return
  fi
  if ls "$dir" | grep -q '\.tmp$'; then
    fail "$name: a temporary file was left: $(ls "$dir")"; return
  fi
  if [ -e "$dir/summary.txt" ]; then
    fail "$name: summary.txt written by a failed run"; return
  fi
  for h in "$dir"/history_*.csv; do
    [ -e "$h" ] || continue
    local ncol
    ncol=$(head -1 "$h" | awk -F, '{print NF}')
    if [ -n "$(tail -c 1 "$h")" ] ||
       awk -F, -v n="$ncol" 'NF != n { bad = 1 } END { exit !bad }' "$h"; then
      fail "$name: $h does not end with a whole row"; return
    fi
  done
  # Every snapshot listed in the PVD is whole (a VTU ends with </VTKFile>).
  for pvd in "$dir"/*.pvd; do
    [ -e "$pvd" ] || continue
    grep -q "</VTKFile>" "$pvd" || { fail "$name: $pvd is not whole"; return; }
    for rec in $(sed -n 's/.*file="\([^"]*\)".*/\1/p' "$pvd"); do
      [ -f "$dir/$rec" ] && tail -c 20 "$dir/$rec" | grep -q "</VTKFile>" ||
        { fail "$name: $rec listed in $pvd is missing or cut"; return; }
    done
  done
  for vtu in "$dir"/*.vtu; do
    [ -e "$vtu" ] || continue
    tail -c 20 "$vtu" | grep -q "</VTKFile>" || { fail "$name: $vtu is cut"; return; }
  done
  echo "ok     $name: $(head -1 stderr) ($(ls "$dir" | wc -l) whole files kept)"
}

run() { # env-limit command...
  local limit=$1
  shift
  YARN_IMPACT_DISK_FULL_AFTER=$limit "$@" > stdout 2> stderr
  rc=$?
}

# 1. The history: the limit falls in the middle of its third row. The
#    bytes before it are parameters.prm (which grows with every new
#    parameter) and the history's header, measured on a run without a fault.
fe_prm h0 0.3e-6 0 > h0.prm
"$exe" h0.prm > /dev/null 2>&1 || fail "FE run without a fault"
header=$(head -1 h0/history_fe.csv | wc -c)
row=$(sed -n 2p h0/history_fe.csv | wc -c)
fe_prm h 0.3e-6 0 > h.prm
run $(($(wc -c < h0/parameters.prm) + header + 2 * row + row / 2)) "$exe" h.prm
check "FE, disk full in the history" h "history_fe.csv"
rows=$(($(wc -l < h/history_fe.csv) - 1))
[ "$rows" -ge 1 ] || fail "FE history: no row kept"

# 2. The summary, the last write of a run without snapshots: the limit falls
#    in the middle of it (its length varies a little with the wall time).
fe_prm s0 0.3e-6 0 > s0.prm
"$exe" s0.prm > /dev/null 2>&1 || fail "FE run without a fault"
total=$(cat s0/* | wc -c)
fe_prm s 0.3e-6 0 > s.prm
run $((total - $(wc -c < s0/summary.txt) / 2)) "$exe" s.prm
check "FE, disk full in the summary" s "summary.txt"
cmp -s s0/history_fe.csv s/history_fe.csv || fail "FE summary case: the history is not whole"

# 3. An FE snapshot, on 1 and 2 ranks.
fe_prm f1 0.3e-6 0.1e-6 > f1.prm
run 60000 "$exe" f1.prm
check "FE, disk full in a snapshot" f1 "vtu"
fe_prm f2 0.3e-6 0.1e-6 > f2.prm
# 50000 bytes: inside the third snapshot (45000-55000 fail there since the
# history rows gained two columns and the snapshots the damage field).
run 50000 mpirun -np 2 "$exe" f2.prm
check "FE on 2 ranks, disk full in a snapshot" f2 "vtu" 2

# 4. A DEM snapshot and the DEM history, on 1 and 2 ranks.
dem_prm d1 0.1e-6 > d1.prm
run 200000 "$exe" d1.prm
check "DEM, disk full in a snapshot" d1 "vtu"
dem_prm d2 0 > d2.prm
run 6000 mpirun -np 2 "$exe" d2.prm
check "DEM on 2 ranks, disk full in the history" d2 "history_dem.csv" 2

# 5. The resolved parameters, the first file a run writes.
fe_prm p 0.3e-6 0 > p.prm
run 100 "$exe" p.prm
check "FE, disk full in parameters.prm" p "parameters.prm"

# 6. A real full disk: a 100 kB tmpfs, where this machine allows mounting.
mkdir tmpfs
if mount -t tmpfs -o size=100k tmpfs tmpfs 2> /dev/null; then
  fe_prm tmpfs/out 0.3e-6 0.02e-6 > t.prm
  "$exe" t.prm > stdout 2> stderr
  rc=$?
  # Whichever file the disk runs out in (a snapshot piece or the PVD
  # record after it: it moves with the size of what was written before,
  # parameters.prm growing with every new parameter), the run must stop
  # with its line naming that file and leave nothing half-written.
  check "FE on a full 100 kB tmpfs" tmpfs/out "(vtu|pvd)"
  umount tmpfs
else
  echo "note   a tmpfs cannot be mounted here: the real full disk is not tried"
fi

test_end
