#!/bin/bash
# Usage: step_collapse.sh YARN_IMPACT
# A run whose stable time step collapses must stop, not crawl on: the
# FE yarn without failure struck at 5000 m/s crushes its cells under the
# nose (nothing erodes them) and the step falls by orders of magnitude
# within 0.1 us. Expected: exit 4, one line naming the step, its value and
# the set-up's, the time; the history up to it kept. Before the guard
# (below a millionth of the set-up's step) this run took hours of steps of
# 1e-6 ns and more to reach its end.
exe=$1
. "$(dirname "$(readlink -f "$0")")/../lib.sh"
test_begin
cat > crush.prm << 'END'
set Symmetry = quarter
subsection Yarn
  set Failure = false
end
subsection Projectile
  set Initial velocity = 5000
end
subsection Time
  set End time = 3e-6
end
subsection FE
  set Cells along the axis = 40
end
subsection Output
  set Directory = out
  set Snapshot interval = 0
  set Verbosity = quiet
end
END
timeout 300 "$exe" crush.prm > stdout 2> stderr
rc=$?
[ "$rc" -eq 4 ] || fail "exit $rc, expected 4: $(head -c 300 stderr)"
[ "$(wc -l < stderr)" -eq 1 ] || fail "not one line: $(cat stderr)"
grep -qE "^yarn-impact: error: numerical failure in the fe model at step [0-9]+, t = [0-9.e-]+ us: the stable time step fell to [0-9.e+-]+ ns, below a millionth of its [0-9.]+ ns at the start" stderr ||
  fail "the message: $(head -c 300 stderr)"
rows=$(($(wc -l < out/history_fe.csv) - 1))
[ "$rows" -ge 1 ] || fail "the history was not kept"
test_end "a collapsing step stops the run: $(head -c 200 stderr)"
