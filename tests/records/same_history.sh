#!/bin/bash
# Usage: same_history.sh HISTORY HISTORY...
# A consistency check (the runs are compared with each other, not with a
# record): every history the same as the first, byte for byte (every sum
# over spheres and cells is reproducible, so the same case gives the same
# history on any number of ranks and with any neighbour-list blocks);
# otherwise the first row and column that differ.
first=$1
failures=0
if [ $# -lt 2 ]; then
  echo "FAILED fewer than two histories to compare"
  exit 1
fi
for h in "$@"; do
  if [ ! -f "$h" ]; then
    echo "FAILED no history $h (its test did not run)"
    failures=$((failures + 1))
  fi
done
[ $failures -eq 0 ] || exit 1
shift
for h in "$@"; do
  if cmp -s "$first" "$h"; then
    continue
  fi
  failures=$((failures + 1))
  echo "FAILED $h differs from $first:"
  /usr/bin/python3 - "$first" "$h" << 'END'
import csv, sys
a, b = (list(csv.reader(open(p))) for p in sys.argv[1:3])
if len(a) != len(b) or a[0] != b[0]:
    print(f"  {len(a)} against {len(b)} rows, or other columns")
    sys.exit(0)
for x, y in zip(a[1:], b[1:]):
    for k, name in enumerate(a[0]):
        if x[k] != y[k]:
            print(f"  t = {x[0]}, {name}: {x[k]} against {y[k]}")
            sys.exit(0)
END
done
if [ $failures -eq 0 ]; then
  echo "the same history, byte for byte, in all $(($# + 1)) runs: PASSED"
fi
exit $failures
