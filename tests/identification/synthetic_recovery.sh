#!/bin/bash
# Curves of the FE law with known constants (Table 1 of the paper, and a
# second set far from it) -> identify_charmetant.py -> the same constants
# within 1 %.
set -euo pipefail
curves=$(readlink -f "$1")
scripts=$2
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cd "$work"
status=0
for set in "80077.19e6 1055.82e6 2.205 649.75e6" "60000e6 5000e6 3.1 40e6"; do
  read -r ke ktc p ktd <<< "$set"
  "$curves" $ke $ktc $p $ktd
  /usr/bin/python3 "$scripts/identify_charmetant.py" --expect "$ke,$ktc,$p,$ktd" \
    --tolerance 0.01 elementary_tension.csv elementary_compaction.csv \
    elementary_distortion.csv || status=1
done
exit $status
