#!/bin/bash
# Usage: bad_input.sh YARN_IMPACT SOURCE_DIR
# Each tests/app/bad/*.prm starts with a line "# expect: TEXT": running it
# must exit non-zero, print TEXT on stderr, and create no output directory.
exe=$1
src=$2
failures=0
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cd "$work" || exit 1

expect_failure() { # name, expected text, command...
  local name=$1 text=$2
  shift 2
  rm -rf out
  "$@" > stdout 2> stderr
  local rc=$?
  if [ $rc -eq 0 ]; then
    echo "FAILED $name: exit code 0"; failures=$((failures + 1))
  elif ! grep -qF -- "$text" stderr; then
    echo "FAILED $name: expected '$text', got: $(cat stderr)"; failures=$((failures + 1))
  elif [ "$(wc -l < stderr)" -ne 1 ]; then
    echo "FAILED $name: message is not one line: $(cat stderr)"; failures=$((failures + 1))
  elif [ -e out ]; then
    echo "FAILED $name: the output directory was created"; failures=$((failures + 1))
  else
    echo "ok     $name: $(cat stderr)"
  fi
}

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

# A valid file passes --check and writes nothing.
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
echo "$failures failed"
[ $failures -eq 0 ]
