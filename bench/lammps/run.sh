#!/bin/bash
# LAMMPS benchmark of YarnImpact's DEM yarn: generate the data file (if not
# there yet), run N steps with mpirun and print the milliseconds per step
# from LAMMPS's own loop time (set-up and data reading excluded).
#
#   bash bench/lammps/run.sh NSTEPS [NFIBRES [LENGTH]]
#     NSTEPS   number of time steps                    (required)
#     NFIBRES  fibres (default 400: the paper's yarn)
#     LENGTH   yarn length in metres (default 25.4e-3)
#   environment: NP (ranks, default 2), DT (time step, default 1.2e-9 s),
#     ROT (1: fix nve/sphere, 0: fix nve without rotations, default 1),
#     THERMO (steps between thermo lines, default 100), NICE (default 0),
#     WORK (folder for data and logs, default bench/lammps/work)
#
# Full-size benchmark (400 fibres x 25.4 mm, 847 600 spheres, 2 ranks):
#   bash bench/lammps/run.sh 1000
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
nsteps=${1:?usage: run.sh NSTEPS [NFIBRES [LENGTH]]}
nfibres=${2:-400}
length=${3:-25.4e-3}
np=${NP:-2}
dt=${DT:-1.2e-9}
rot=${ROT:-1}
thermo=${THERMO:-100}
nice_level=${NICE:-0}
work=${WORK:-$here/work}
python=${PYTHON:-/usr/bin/python3}   # Debian's python3 with python3-numpy
mkdir -p "$work"
tag="${nfibres}f_${length}"
data="$work/yarn_$tag.data"
params="$work/yarn_$tag.params.in"
if [ ! -s "$data" ] || [ ! -s "$params" ]; then
  nice -n "$nice_level" "$python" "$here/make_yarn.py" --fibres "$nfibres" \
    --length "$length" --data "$data.tmp" --params "$params"
  mv "$data.tmp" "$data"
fi
if [ "$(id -u)" = 0 ]; then
  export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
fi
log="$work/log_${tag}_np${np}_${nsteps}steps.lammps"
cd "$work"
nice -n "$nice_level" mpirun -np "$np" lmp -in "$here/yarn.in" -log "$log" \
  -screen none -var nsteps "$nsteps" -var dt "$dt" -var rot "$rot" \
  -var thermo "$thermo" -var data "$data" -var params "$params"
grep -v WARNING "$log" | sed -n '/^Step/,/^Loop time/p'
loop=$(grep '^Loop time of' "$log" | tail -1)
[ -n "$loop" ] || { echo "run.sh: no loop time in $log" >&2; exit 1; }
# "Loop time of T on P procs for N steps with A atoms"
echo "$loop" | awk '{t=$4; p=$6; n=$9; a=$12;
  printf "LAMMPS: %d atoms, %d ranks, %d steps: %.3f s loop time, %.3f ms per step\n", a, p, n, t, 1000*t/n}'
