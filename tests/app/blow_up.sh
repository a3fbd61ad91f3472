#!/bin/bash
# A run whose time step is never updated while a fast projectile crushes the
# yarn must stop with a message naming the step, the time and the cause, a
# non-zero exit code, and keep the history and the snapshots before it.
exe=$1
src=$2
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cd "$work" || exit 1
"$exe" "$src/blow_up.prm" > stdout 2> stderr
rc=$?
cat stderr
if [ $rc -eq 0 ]; then echo "FAILED: exit code 0"; exit 1; fi
grep -q "numerical failure in the fe model at step" stderr || { echo "FAILED: no step in message"; exit 1; }
grep -q "t = " stderr || { echo "FAILED: no time in message"; exit 1; }
[ -f out/fe.pvd ] && [ -f out/history_fe.csv ] && [ -f out/fe_0000.pvtu ] || { echo "FAILED: history or snapshots lost"; exit 1; }
echo "ok: blow-up detected, $(grep -c pvtu out/fe.pvd) good snapshot(s) kept"
