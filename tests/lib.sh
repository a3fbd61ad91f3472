# Sourced by the shell tests: what every one of them sets up and ends with.
#
#   source "$src/tests/lib.sh"
#   test_begin [CLEANUP]   a scratch folder $work, removed at exit (after the
#                          function CLEANUP, if given, has run: it stops the
#                          script's background runs); the working folder;
#                          mpirun allowed as root and on more ranks than
#                          cores; no failure yet
#   fail TEXT...           one failed check: "FAILED TEXT", counted
#   test_end [TEXT]        exit 1 naming the number of failed checks, or
#                          print TEXT (if given) and exit 0
#   same_history A B       two history CSVs byte for byte, or say where
#                          they first differ (the row's time and column)

test_begin() {
  _test_cleanup=${1:-}
  work=$(mktemp -d)
  trap '_test_exit' EXIT
  cd "$work" || exit 1
  export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
  export OMPI_MCA_rmaps_base_oversubscribe=1
  failures=0
}

_test_exit() {
  [ -n "$_test_cleanup" ] && "$_test_cleanup"
  rm -rf "$work"
}

fail() {
  echo "FAILED $*"
  failures=$((failures + 1))
}

test_end() {
  if [ "$failures" -ne 0 ]; then
    echo "$failures check(s) failed"
    exit 1
  fi
  [ -n "${1:-}" ] && echo "$1"
  exit 0
}

# Every sum over spheres, bars and cells is reproducible (the same on any
# number of ranks), so histories are compared byte for byte; on a
# difference, the first row and column that differ.
same_history() {
  cmp -s "$1" "$2" && return 0
  /usr/bin/python3 - "$1" "$2" << 'END'
import csv, sys
a, b = (list(csv.reader(open(p))) for p in sys.argv[1:3])
if len(a) != len(b) or a[0] != b[0]:
    print(f"{len(a)} against {len(b)} rows, or other columns")
    sys.exit(1)
h = a[0]
for x, y in zip(a[1:], b[1:]):
    for k in range(len(h)):
        if x[k] != y[k]:
            print(f"t = {x[0]} us, {h[k]}: {x[k]} against {y[k]}")
            sys.exit(1)
END
  return 1
}
