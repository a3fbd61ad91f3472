#!/bin/bash
# Every shipped prm file parses and validates.
exe=$1
src=$2
failures=0
# File names in them (Fabric/Mesh file) are relative to the repository's
# root, where the examples run.
cd "$src" || exit 1
for prm in "$src"/prm/*.prm "$src"/prm/study/*.prm "$src"/prm/elementary/*.prm "$src"/prm/fabric/*.prm; do
  if "$exe" --check "$prm" > /dev/null; then echo "ok     $prm"; else echo "FAILED $prm"; failures=$((failures + 1)); fi
done
[ $failures -eq 0 ]
