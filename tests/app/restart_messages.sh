#!/bin/bash
# Usage: restart_messages.sh YARN_IMPACT
# Messages that do not mislead (issue 28, class 6): a --restart refusal
# names the parameters that differ; Output/Directory may differ (a stopped
# run's folder moved elsewhere is continued there, to the uninterrupted
# history byte for byte); a --restart of a finished run is refused without
# advice that would delete its results, and touches nothing; an info file
# saying 0 ranks, or a checkpoint info file that is a directory, is refused
# as damaged naming the file.
exe=$1
. "$(dirname "$(readlink -f "$0")")/../lib.sh"
test_begin

# refused NAME REGEX ARGS...: exit 1, one line matching REGEX (grep -E).
refused() {
  local name=$1 regex=$2
  shift 2
  "$exe" "$@" > stdout 2> stderr
  local rc=$?
  if [ $rc -ne 1 ] || ! grep -qE -- "$regex" stderr || [ "$(wc -l < stderr)" -ne 1 ]; then
    fail "$name: expected exit 1 and '$regex', got $rc: $(head -c 400 stderr)"
  elif grep -q "Overwrite" stderr; then
    fail "$name: the message advises Overwrite: $(cat stderr)"
  else
    echo "ok     $name: $(cat stderr)"
  fi
}

fe_prm() { # directory, end time
  printf 'set Symmetry = quarter\nsubsection Time\n  set End time = %s\nend\n' "$2"
  printf 'subsection Output\n  set Directory = %s\n  set Snapshot interval = 0\n' "$1"
  printf '  set History interval = 0.05e-6\n  set Verbosity = quiet\nend\n'
  printf 'subsection FE\n  set Cells along the axis = 40\nend\n'
}
fe_prm ref 1e-6 > ref.prm
fe_prm run 1e-6 > run.prm
"$exe" ref.prm > /dev/null 2>&1 || fail "reference run"

stop() { # prm: stopped by the injected signal at row 9, exit 6
  YARN_IMPACT_SIGNAL_AT_ROW=9 "$exe" "$1" > stdout 2> stderr
  [ $? -eq 6 ] || fail "stop $1: $(head -c 300 stderr)"
}
stop run.prm

# Other parameters: named, with both values.
fe_prm run 2e-6 > longer.prm
refused "other End time" "the parameters differ .*: Time/End time \('1e-6' there, '2e-6' here\); a restart must continue the same run" --restart longer.prm
{ fe_prm run 1e-6; printf 'subsection Projectile\n  set Initial velocity = 130\nend\nsubsection FE\n  set Cells along the axis = 44\nend\n'; } > two.prm
refused "two other parameters" "FE/Cells along the axis \('40' there, '44' here\), Projectile/Initial velocity \('120' there, '130' here\)" --restart two.prm

# Info file damaged: 0 ranks, or a directory in its place.
cp run/checkpoint_fe.txt saved_info.txt
sed -i 's/^ranks = .*/ranks = 0/' run/checkpoint_fe.txt
refused "info file with 0 ranks" "the checkpoint file 'run/checkpoint_fe.txt' cannot be used \(its checksum does not match" --restart run.prm
# The same with its own checksum made right (CRC-32 of the text before it).
/usr/bin/python3 - run/checkpoint_fe.txt <<'PY'
import sys, zlib
t = open(sys.argv[1]).read()
body = t[:t.index("info checksum")]
open(sys.argv[1], "w").write(body + "info checksum = %d\n" % zlib.crc32(body.encode()))
PY
refused "info file with 0 ranks, checksum right" "the checkpoint file 'run/checkpoint_fe.txt' cannot be used \(its fields do not fit together\)" --restart run.prm
grep -q " on 0" stderr && fail "0 ranks: the message asks for 0 ranks"
rm run/checkpoint_fe.txt && mkdir run/checkpoint_fe.txt
refused "info file is a directory" "'run/checkpoint_fe.txt'" --restart run.prm
rmdir run/checkpoint_fe.txt && cp saved_info.txt run/checkpoint_fe.txt

# A moved folder is continued in its new place.
mv run moved
fe_prm moved 1e-6 > moved.prm
"$exe" --restart moved.prm > stdout 2> stderr
rc=$?
if [ $rc -ne 0 ]; then
  fail "moved folder: exit $rc: $(head -c 300 stderr)"
elif ! cmp -s ref/history_fe.csv moved/history_fe.csv; then
  fail "moved folder: the history differs from the uninterrupted run's"
else
  echo "ok     moved folder continued: history identical to the uninterrupted run's"
fi

# A finished run: refused, nothing touched, no advice to overwrite.
listing() { ls -l --full-time moved; md5sum moved/*; }
listing > before
refused "restart of a finished run" "the run in Output/Directory = 'moved' has finished .*its results are kept" --restart moved.prm
listing > after
cmp -s before after || fail "restart of a finished run: the folder changed"

# A folder that stopped before its first checkpoint.
fe_prm early 1e-6 > early.prm
mkdir early && cp moved/parameters.prm early/ && sed -i 's/= moved/= early/' early/parameters.prm
refused "no checkpoint" "holds no checkpoint .*in another Output/Directory" --restart early.prm

test_end "all restart message cases passed"
