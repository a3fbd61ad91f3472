#!/bin/bash
# Usage: compare.sh SUMMARY RECORD ABS REL
# A record test (label "record"): the summary.txt that a test's run wrote
# (Output/Verbosity = checks writes the whole scaled summary there and
# prints only the check lines) against its recorded summary RECORD, with
# numdiff at the declared absolute and relative tolerances ABS and REL
# (a number passes when either holds); text must match exactly.
summary=$1
record=$2
abs=$3
rel=$4
if [ ! -f "$summary" ]; then
  echo "FAILED no summary $summary (its test did not run)"
  exit 1
fi
if ! command -v numdiff > /dev/null; then
  echo "FAILED numdiff is not installed"
  exit 1
fi
if numdiff -q -a "$abs" -r "$rel" -s ' \t\r\n=,:;<>[](){}^' \
  "$record" "$summary" > /dev/null 2>&1; then
  echo "record $(basename "$record"): the summary matches within" \
    "-a $abs -r $rel: PASSED"
  exit 0
fi
echo "record $(basename "$record"): the summary differs beyond" \
  "-a $abs -r $rel: FAILED"
numdiff -a "$abs" -r "$rel" -s ' \t\r\n=,:;<>[](){}^' "$record" "$summary" |
  head -40
exit 1
