#!/bin/bash
# Usage: portable_kernel.sh YARN_IMPACT SOURCE_DIR
# fe/bar_wave_speed (tests/fe/bar_wave_speed.prm) with the portable cell
# kernel, which ctest forces with YARN_IMPACT_PORTABLE_KERNEL=1 (the
# default run takes the AVX2/FMA one where the CPU has it):
# - the run names the kernel it ran on its "[fe] mesh" line: portable;
# - the same physics check as fe/bar_wave_speed: the longitudinal strain
#   front at Smith's sqrt(k_e/rho) = 7950 m/s within 2 % (PASSED);
# - the same summary as recorded in bar_wave_speed.output, within the
#   tolerances the test machinery compares with (numdiff -a 1e-6 -r 1e-8).
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
# The test's own run (Verbosity = test: the summary alone on stdout).
"$exe" "$src/tests/fe/bar_wave_speed.prm" > output 2>&1 ||
  fail "the run exited with $?"
grep "check longitudinal front speed" output
grep -q "check longitudinal front speed .*: PASSED$" output ||
  fail "the longitudinal front speed check"
if command -v numdiff > /dev/null; then
  numdiff -q -a 1e-6 -r 1e-8 -s ' \t\r\n=,:;<>[](){}^' \
    "$src/tests/fe/bar_wave_speed.output" output > /dev/null 2>&1
else
  cmp -s "$src/tests/fe/bar_wave_speed.output" output
fi || {
  fail "the summary differs from bar_wave_speed.output"
  diff "$src/tests/fe/bar_wave_speed.output" output
}

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
