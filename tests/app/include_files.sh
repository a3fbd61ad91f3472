#!/bin/bash
# Usage: include_files.sh YARN_IMPACT
# `include FILE` in a parameter file is as safe as the top-level file
# (doc/user-guide.md, "Parameter files"): a cycle (direct, through other
# files, or through another spelling of the same file), a directory, a fifo,
# /dev/null, a missing or unreadable file, an include nested too deep, an
# include bomb and an included file that leaves a subsection open are
# refused with exit 1 and one line naming the chain of files, before
# anything is written, by --check, a run and --restart alike. A relative
# include is resolved against the including file's folder, from any working
# folder; an error inside an included file names that file and its line;
# the run's parameters.prm is the expanded, valid parameter set. Also: a
# parameter file with an unknown extension is refused naming it.
exe=$1
. "$(dirname "$(readlink -f "$0")")/../lib.sh"
test_begin

# refused NAME TEXT ARGS...: exit 1, one line on stderr holding TEXT (a
# fixed string), nothing written (no folder out).
refused() {
  local name=$1 text=$2
  shift 2
  rm -rf out
  timeout 20 "$exe" "$@" > stdout 2> stderr
  local rc=$?
  if [ $rc -ne 1 ]; then
    fail "$name: exit $rc (expected 1): $(head -c 300 stderr)"
  elif ! grep -qF -- "$text" stderr; then
    fail "$name: expected '$text', got: $(head -c 300 stderr)"
  elif [ "$(wc -l < stderr)" -ne 1 ]; then
    fail "$name: the message is not one line: $(head -c 300 stderr)"
  elif [ -e out ]; then
    fail "$name: the output folder was created"
  else
    echo "ok     $name: $(cat stderr)"
  fi
}

# Every refusal in each mode: --check, a run, --restart.
refused_all() {
  local name=$1 text=$2 file=$3
  refused "$name" "$text" "$file"
  refused "--check $name" "$text" --check "$file"
  refused "--restart $name" "$text" --restart "$file"
}

# A valid small case (quarter FE, 40 cells, 0.2 us) in pieces.
printf 'set Symmetry = quarter\nsubsection Time\n  set End time = 0.2e-6\nend\n' > time.prm
printf 'subsection Output\n  set Directory = out\n  set Verbosity = quiet\n  set Snapshot interval = 0\nend\n' > output.prm

printf 'include a.prm\n' > a.prm
refused_all "direct cycle" "a.prm includes a.prm: an include cycle (line 1 of 'a.prm')." a.prm

printf 'include time.prm\ninclude c1.prm\n' > b1.prm
printf '# a comment\n\ninclude c2.prm\n' > c1.prm
printf 'subsection FE\n  include b1.prm\nend\n' > c2.prm
refused_all "indirect cycle" "b1.prm includes c1.prm includes c2.prm includes b1.prm: an include cycle (line 2 of 'c2.prm')." b1.prm

mkdir -p sub
printf 'include ../spelt.prm\n' > sub/inner.prm
printf 'include sub/inner.prm\n' > spelt.prm
refused "cycle through another spelling" "spelt.prm includes sub/inner.prm includes sub/../spelt.prm: an include cycle" spelt.prm
ln -s spelt.prm link.prm
printf 'include link.prm\n' > via_link.prm
printf 'include via_link.prm\n' > link_start.prm
refused "cycle through a symbolic link" "an include cycle" link.prm

printf 'include time.prm\ninclude sub\n' > dir.prm
refused_all "include of a directory" "dir.prm includes sub: cannot include 'sub': it is a directory (line 2 of 'dir.prm')." dir.prm

mkfifo fifo
printf 'include fifo\n' > fifo.prm
refused_all "include of a fifo" "fifo.prm includes fifo: cannot include 'fifo': it is not a regular file (a fifo, socket or device)" fifo.prm

printf 'include /dev/null\n' > null.prm
refused_all "include of /dev/null" "null.prm includes /dev/null: cannot include '/dev/null': it is not a regular file" null.prm
printf 'include /dev/zero\n' > zero.prm
refused "include of /dev/zero" "cannot include '/dev/zero': it is not a regular file" zero.prm

printf 'include output.prm\ninclude missing.prm\n' > missing_inc.prm
refused_all "include of a missing file" "missing_inc.prm includes missing.prm: cannot include 'missing.prm': no such file or directory (line 2 of 'missing_inc.prm')." missing_inc.prm

if [ "$(id -u)" -ne 0 ]; then # root reads any file
  printf 'set Model = fe\n' > unreadable.prm
  chmod 000 unreadable.prm
  printf 'include unreadable.prm\n' > unreadable_inc.prm
  refused "include of an unreadable file" "cannot include 'unreadable.prm': permission denied" unreadable_inc.prm
fi

# Deeper than 32 files (no cycle).
for i in $(seq 0 39); do printf 'include deep%d.prm\n' $((i + 1)) > deep$i.prm; done
printf 'set Symmetry = quarter\n' > deep40.prm
refused "includes nested too deep" "includes nested more than 32 files deep" deep0.prm

# An include bomb: each level includes the next twice (2^26 copies).
for i in $(seq 0 25); do printf 'include bomb%d.prm\ninclude bomb%d.prm\n' $((i + 1)) $((i + 1)) > bomb$i.prm; done
printf 'set Symmetry = quarter # a line of 40 characters\n' > bomb26.prm
refused "include bomb" "the expanded parameter text is larger than 16 MiB" bomb0.prm

# An included file must close the subsections it opens.
printf 'subsection Time\n  set End time = 0.2e-6\n' > open.prm
printf 'include open.prm\nend\n' > open_inc.prm
refused "included file leaves a subsection open" "open_inc.prm includes open.prm: 'subsection' and 'end' lines of 'open.prm' do not match" open_inc.prm

# An error inside an included file names that file and its line.
printf 'subsection Time\n  set End time = 0.2e-6\n  set Frobnication = 1\nend\n' > bad_entry.prm
printf '# line 1\ninclude bad_entry.prm\nset Symmetry = quarter\n' > bad_entry_inc.prm
refused "error in an included file" "Line <3> of file <bad_entry.prm>" bad_entry_inc.prm
printf 'subsection Time\n  set End time = 0.2e-6\nend\nthis is not a line\n' > bad_line.prm
printf 'include time.prm\n\ninclude bad_line.prm\n' > bad_line_inc.prm
refused "syntax error in an included file" "Line <4> of file <bad_line.prm>" bad_line_inc.prm
printf 'set Symmetry = quarter\nsubsection Time\n  set End time = -1\nend\n' > bad_value.prm
printf 'include bad_value.prm\n' > bad_value_inc.prm
refused "bad value in an included file" "Parameter 'Time/End time' must be positive" bad_value_inc.prm

# An unknown extension names the file.
printf 'set Symmetry = quarter\n' > case.txt
refused "unknown extension" "the parameter file 'case.txt' has an unknown extension '.txt'" case.txt
printf 'set Symmetry = quarter\n' > case
refused "no extension" "the parameter file 'case' has no extension" case

# A relative include is resolved against the including file's folder, from
# any working folder: cases/run/case.prm includes ../common/base.prm, which
# includes time.prm of its own folder (and output.prm twice: no cycle).
mkdir -p cases/run cases/common elsewhere
printf 'set Symmetry = quarter\nsubsection Time\n  set End time = 0.2e-6\nend\n' > cases/common/time.prm
printf 'include time.prm\nsubsection FE\n  set Cells along the axis = 40\nend\n' > cases/common/base.prm
printf 'subsection Output\n  set Directory = out\n  set Verbosity = quiet\n  set Snapshot interval = 0\nend\n' > cases/common/output.prm
printf 'include ../common/base.prm\ninclude ../common/output.prm\ninclude ../common/output.prm\nsubsection Projectile\n  set Initial velocity = 123.5\nend\n' > cases/run/case.prm
cd elsewhere || exit 1
rm -rf out
if ! "$exe" --check ../cases/run/case.prm > stdout 2> stderr; then
  fail "relative include, --check: $(head -c 300 stderr)"
elif ! "$exe" ../cases/run/case.prm > stdout 2> stderr; then
  fail "relative include, run: $(head -c 300 stderr)"
elif ! grep -q "set Initial velocity *= 123.5" out/parameters.prm ||
     ! grep -q "set Cells along the axis *= 40" out/parameters.prm ||
     ! grep -q "set End time *= 0.2e-6" out/parameters.prm ||
     grep -qi "^ *include" out/parameters.prm; then
  fail "relative include: parameters.prm does not hold the included values"
elif ! "$exe" --check out/parameters.prm > stdout 2> stderr; then
  fail "relative include: parameters.prm is not valid: $(head -c 300 stderr)"
else
  echo "ok     relative include from another folder: run and parameters.prm valid"
fi
# Its folder holds the run now: --restart of the ended run is refused (its
# checkpoints are gone), and the included file would be overwritten.
cd .. || exit 1
printf 'include out/parameters.prm\n' > elsewhere/self.prm
printf 'subsection Output\n  set Overwrite = true\nend\n' >> elsewhere/self.prm
(cd elsewhere && "$exe" self.prm > stdout 2> stderr)
if [ $? -ne 1 ] || ! grep -qF "would overwrite the parameter file 'out/parameters.prm'" elsewhere/stderr; then
  fail "an included file the run would overwrite: $(head -c 300 elsewhere/stderr)"
else
  echo "ok     an included file the run would overwrite: $(cat elsewhere/stderr)"
fi

test_end "all include cases passed"
