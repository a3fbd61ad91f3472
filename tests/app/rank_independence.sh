#!/bin/bash
# Usage: rank_independence.sh YARN_IMPACT SOURCE_DIR
# A physics-free check, not a regression record: the paper's FE case
# (prm/km2_120ms_fe.prm, 40 us, no snapshots) with Yarn/Failure on (up to
# its first failure, at 35.9 us, it steps as with failure off; the cut and
# the yarn's recoil after it follow), and fe/parallel's half yarn with
# friction and contact damping (20 us),
# must write byte-identical history CSVs on 1, 2 and 3 MPI ranks (3 is more
# than a 2-core machine has: oversubscribed). The runs are compared with
# each other, not with a recorded file, so the test fails whenever the
# partition changes the dynamics or a reduced observable, by any amount.
exe=$1
src=$2
. "$(dirname "$(readlink -f "$0")")/../lib.sh"
test_begin
for case in failure half_friction; do
  for n in 1 2 3; do
    dir=${case}_$n
    { case $case in
        failure)
          cat "$src/prm/km2_120ms_fe.prm"
          printf 'subsection Yarn\n  set Failure = true\nend\n' ;;
        half_friction)
          cat "$src/tests/fe/parallel.prm" ;;
      esac
      printf 'subsection Output\n  set Directory = %s\n  set Overwrite = true\n' "$dir"
      printf '  set Snapshot interval = 0\nend\n'
    } > "$dir.prm"
    if ! mpirun -np "$n" "$exe" "$dir.prm" > "$dir.stdout" 2>&1; then
      echo "FAILED $case, $n rank(s): the run stopped"
      tail -5 "$dir.stdout"
      failures=$((failures + 1))
      continue
    fi
    if [ "$n" -gt 1 ]; then
      if cmp -s "${case}_1/history_fe.csv" "$dir/history_fe.csv"; then
        echo "ok     $case: $n ranks write the history of 1 rank byte for byte ($(wc -l < "$dir/history_fe.csv") lines)"
      else
        echo "FAILED $case: $n ranks differ from 1 rank:"
        diff "${case}_1/history_fe.csv" "$dir/history_fe.csv" | head -4 | cut -c1-200
        failures=$((failures + 1))
      fi
    fi
  done
done
test_end
