#!/bin/bash
# Usage: tiny_intervals.sh YARN_IMPACT
# Output intervals far below the step (1e-20 s for the history, the
# snapshots and the checkpoints) must not turn the catch-up of the next
# output time into an endless loop: the run ends (within a minute; it takes
# about a second) with a history row, a snapshot and a checkpoint at every
# step, as an interval of one step would give. A check of termination and
# of the row count, not a recorded output.
exe=$1
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cd "$work" || exit 1
cat > t.prm << 'END'
set Symmetry = quarter
subsection Time
  set End time = 0.1e-6
end
subsection Output
  set Directory = out
  set History interval = 1e-20
  set Snapshot interval = 1e-20
  set Checkpoint interval = 1e-20
  set Verbosity = quiet
end
subsection FE
  set Cells along the axis = 40
end
END
timeout 60 "$exe" t.prm > stdout 2> stderr
rc=$?
if [ $rc -ne 0 ]; then
  echo "FAILED: exit $rc (124: it did not end within 60 s): $(head -c 300 stderr)"
  exit 1
fi
steps=$(tail -1 out/history_fe.csv | cut -d, -f2)
rows=$(($(wc -l < out/history_fe.csv) - 1))
if [ "$rows" -ne $((steps + 1)) ]; then
  echo "FAILED: $rows history rows for $steps steps (expected one a step and t = 0)"
  exit 1
fi
records=$(grep -c 'DataSet' out/fe.pvd)
if [ "$records" -ne $((steps + 1)) ]; then
  echo "FAILED: $records snapshots for $steps steps (expected one a step and t = 0)"
  exit 1
fi
echo "tiny intervals: $steps steps, $rows rows, $records snapshots"
