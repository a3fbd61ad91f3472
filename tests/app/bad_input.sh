#!/bin/bash
# Usage: bad_input.sh YARN_IMPACT SOURCE_DIR
# Each tests/app/bad/*.prm starts with a line "# expect: TEXT": running it
# must exit non-zero, print TEXT on stderr, and create no output directory.
# Then: parameter files that are not readable files, and output directories
# that hold an earlier run (refused, or replaced with Output/Overwrite).
exe=$1
src=$2
. "$(dirname "$(readlink -f "$0")")/../lib.sh"
test_begin

expect_failure() { # name, expected text, command...
  local name=$1 text=$2
  shift 2
  rm -rf out results
  "$@" > stdout 2> stderr
  local rc=$?
  if [ $rc -eq 0 ]; then
    echo "FAILED $name: exit code 0"; failures=$((failures + 1))
  elif ! grep -qF -- "$text" stderr; then
    echo "FAILED $name: expected '$text', got: $(cat stderr)"; failures=$((failures + 1))
  elif [ "$(wc -l < stderr)" -ne 1 ]; then
    echo "FAILED $name: message is not one line: $(cat stderr)"; failures=$((failures + 1))
  elif [ -e out ] || [ -e results ]; then
    echo "FAILED $name: the output directory was created"; failures=$((failures + 1))
  else
    echo "ok     $name: $(cat stderr)"
  fi
}

# The small mesh and orientation files that bad/fabric_mesh_*.prm and
# bad/fabric_orientation_*.prm name, relative to the working folder.
cp "$src"/bad/mesh/* .
for prm in "$src"/bad/*.prm; do
  text=$(sed -n 's/^# expect: //p' "$prm" | head -1)
  expect_failure "$(basename "$prm")" "$text" "$exe" "$prm"
  expect_failure "--check $(basename "$prm")" "$text" "$exe" --check "$prm"
done

expect_failure "missing file" "cannot open the parameter file" "$exe" missing.prm
touch a_file
printf 'subsection Output\n set Directory = a_file/sub\nend\n' > unwritable.prm
expect_failure "unwritable output directory" "Parameter 'Output/Directory'" "$exe" unwritable.prm
expect_failure "unknown option" "invalid command line" "$exe" --frobnicate

# A parameter file that is not a readable regular file is refused, never read
# as an empty file (which would run the default case into ./results).
mkdir dir.prm
expect_failure "directory as the file" "'dir.prm': it is a directory" "$exe" dir.prm
expect_failure "--check directory as the file" "'dir.prm': it is a directory" "$exe" --check dir.prm
mkfifo fifo.prm
expect_failure "fifo as the file" "'fifo.prm': it is not a regular file" timeout 20 "$exe" fifo.prm
expect_failure "--check fifo as the file" "'fifo.prm': it is not a regular file" timeout 20 "$exe" --check fifo.prm
if [ "$(id -u)" -ne 0 ]; then # root reads any file
  printf 'set Model = fe\n' > unreadable.prm
  chmod 000 unreadable.prm
  expect_failure "unreadable file" "'unreadable.prm': permission denied" "$exe" unreadable.prm
fi

# An output directory that holds an earlier run: a 0.4 us run with 5
# snapshots, then a 0.2 us run (3 snapshots) into the same folder.
run_prm() { # end time, extra Output lines
  printf 'set Symmetry = quarter\nsubsection Time\n  set End time = %s\nend\n' "$1"
  printf 'subsection Output\n  set Directory = out\n  set Snapshot interval = 0.1e-6\n'
  printf '  set Verbosity = quiet\n%s\nend\n' "$2"
  printf 'subsection FE\n  set Cells along the axis = 40\nend\n'
}
run_prm 0.4e-6 "" > long.prm
run_prm 0.2e-6 "" > short.prm
run_prm 0.2e-6 "  set Overwrite = true" > short_overwrite.prm
rm -rf out
if "$exe" long.prm > stdout 2>&1 && [ -f out/fe_0004.pvtu ]; then
  echo "ok     earlier run"
else
  echo "FAILED earlier run: $(cat stdout)"; failures=$((failures + 1))
fi
touch out/notes.txt
listing() { ls -l --full-time out; md5sum out/*; }
listing > before
"$exe" short.prm > stdout 2> stderr
rc=$?
if [ $rc -ne 1 ]; then
  echo "FAILED reused directory: exit code $rc"; failures=$((failures + 1))
elif ! grep -qF "Parameter 'Output/Directory' = 'out' holds the output of an earlier run" stderr ||
     ! grep -qF "Output/Overwrite = true" stderr || [ "$(wc -l < stderr)" -ne 1 ]; then
  echo "FAILED reused directory: $(cat stderr)"; failures=$((failures + 1))
elif listing | cmp -s - before; then
  echo "ok     reused directory: $(cat stderr)"
else
  echo "FAILED reused directory: its content changed"; failures=$((failures + 1))
fi
"$exe" short_overwrite.prm > stdout 2> stderr
rc=$?
if [ $rc -ne 0 ]; then
  echo "FAILED Overwrite = true: exit code $rc: $(cat stderr)"; failures=$((failures + 1))
elif ! grep -q "^Output/Overwrite: removed the 14 output files of an earlier run from 'out'" stdout; then
  echo "FAILED Overwrite = true: no line saying so: $(head -3 stdout)"; failures=$((failures + 1))
elif [ -e out/fe_0003.pvtu ] || [ -e out/fe_0004.0.vtu ] || [ ! -f out/fe_0002.pvtu ] ||
     [ ! -f out/notes.txt ] || [ ! -f out/summary.txt ]; then
  echo "FAILED Overwrite = true: left $(ls out | tr '\n' ' ')"; failures=$((failures + 1))
else
  echo "ok     Overwrite = true: $(grep '^Output/Overwrite' stdout); kept notes.txt"
fi

# The parameter file is <Directory>/parameters.prm: refused even with
# Overwrite, since the run would write its resolved parameters over it.
cp short_overwrite.prm out/parameters.prm
listing > before
"$exe" out/parameters.prm > stdout 2> stderr
rc=$?
if [ $rc -ne 1 ] || [ "$(wc -l < stderr)" -ne 1 ] ||
   ! grep -qF "would overwrite the parameter file 'out/parameters.prm'" stderr; then
  echo "FAILED input file in the output directory (exit $rc): $(cat stderr)"; failures=$((failures + 1))
elif listing | cmp -s - before; then
  echo "ok     input file in the output directory: $(cat stderr)"
else
  echo "FAILED input file in the output directory: its content changed"; failures=$((failures + 1))
fi

# A valid file passes --check and writes nothing.
rm -rf out
printf 'subsection Output\n set Directory = out\nend\n' > valid.prm
if "$exe" --check valid.prm > stdout 2>&1 && [ ! -e out ] && grep -q "valid" stdout; then
  echo "ok     --check on a valid file"
else
  echo "FAILED --check on a valid file: $(cat stdout)"; failures=$((failures + 1))
fi
if "$exe" --print-parameters | grep -q "set Model"; then
  echo "ok     --print-parameters"
else
  echo "FAILED --print-parameters"; failures=$((failures + 1))
fi
if "$exe" --help | grep -q "Usage"; then
  echo "ok     --help"
else
  echo "FAILED --help"; failures=$((failures + 1))
fi
test_end
