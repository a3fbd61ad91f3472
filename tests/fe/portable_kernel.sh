#!/bin/bash
# Usage: portable_kernel.sh YARN_IMPACT SOURCE_DIR
# fe/bar_wave_speed (tests/fe/bar_wave_speed.prm) with the portable cell
# kernel, which ctest forces with YARN_IMPACT_PORTABLE_KERNEL=1 (the
# default run takes the AVX2/FMA one where the CPU has it):
# - the run names the kernel it ran on its "[fe] mesh" line: portable;
# - the same physics check as fe/bar_wave_speed, the same lines as its
#   bar_wave_speed.output: the longitudinal strain front at Smith's
#   sqrt(k_e/rho) = 7950 m/s within 2 % (PASSED);
# - the same summary (summary.txt) as its record
#   tests/records/fe/bar_wave_speed.output, within the tolerances that
#   record/fe/bar_wave_speed declares (tests/fe/CMakeLists.txt).
exe=$1
src=$2
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cd "$work" || exit 1
failures=0
fail() {
  echo "FAILED $*"
  failures=$((failures + 1))
}

if [ "$YARN_IMPACT_PORTABLE_KERNEL" != 1 ]; then
  fail "YARN_IMPACT_PORTABLE_KERNEL=1 is not set"
fi
# The test's own run (Verbosity = checks: the check lines alone on stdout,
# the summary in run/summary.txt).
"$exe" "$src/tests/fe/bar_wave_speed.prm" > output 2>&1 ||
  fail "the run exited with $?"
grep "check longitudinal front speed" output
grep -q "check longitudinal front speed .*: PASSED$" output ||
  fail "the longitudinal front speed check"
cmp -s "$src/tests/fe/bar_wave_speed.output" output || {
  fail "the check lines differ from bar_wave_speed.output"
  diff "$src/tests/fe/bar_wave_speed.output" output
}
bash "$src/tests/records/compare.sh" run/summary.txt \
  "$src/tests/records/fe/bar_wave_speed.output" 1e-3 1e-4 ||
  fail "the summary differs from its record"

# Again with Verbosity = normal, which prints the set-up report.
{
  cat "$src/tests/fe/bar_wave_speed.prm"
  printf 'subsection Output\n  set Directory = normal\n'
  printf '  set Verbosity = normal\nend\n'
} > normal.prm
"$exe" normal.prm > stdout 2>&1 || fail "the normal run exited with $?"
grep "\[fe\] mesh" stdout
grep -q "^\[fe\] mesh: .*, cell kernel: portable$" stdout ||
  fail "the run does not name the portable cell kernel"

if [ $failures -eq 0 ]; then
  echo "portable kernel: all checks PASSED"
fi
exit $failures
