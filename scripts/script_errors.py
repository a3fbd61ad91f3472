"""One line per failure for the scripts that users run on their own files
(ballistic_sweep.py, identify_charmetant.py): a bad argument, file or run
ends with "PROG: error: ..." on stderr and a non-zero exit, never a
traceback."""
import csv
import sys


class Failure(Exception):
    """A bad argument, file or run: one line, exit code 1."""


def run(main, prog):
    """Call main() and return its exit code; any failure becomes one line
    naming PROG (the script's file name) and exit code 1 (130 when
    interrupted)."""
    try:
        return main()
    except Failure as e:
        sys.stderr.write("%s: error: %s\n" % (prog, e))
        return 1
    except KeyboardInterrupt:
        sys.stderr.write("%s: error: interrupted\n" % prog)
        return 130
    except OSError as e:
        sys.stderr.write("%s: error: %s%s\n" % (
            prog, e.strerror or e,
            ": " + e.filename if getattr(e, "filename", None) else ""))
        return 1
    except Exception as e:  # never a traceback
        sys.stderr.write("%s: error: %s: %s\n" % (prog, type(e).__name__, e))
        return 1


def history_columns(path, names, see=""):
    """{name: [float per row]} of the columns NAMES of the history CSV at
    PATH; a history that cannot be read, lacks a column or has no rows is a
    Failure naming it (and SEE, where the run's log is)."""
    hint = " (see %s)" % see if see else ""
    try:
        with open(path) as f:
            rows = list(csv.DictReader(f))
        columns = {n: [float(r[n]) for r in rows] for n in names}
    except (OSError, UnicodeDecodeError, csv.Error, KeyError, ValueError,
            TypeError) as e:
        raise Failure("cannot read the history %s: %s%s" % (path, e, hint))
    if not rows:
        raise Failure("the history %s has no rows%s" % (path, hint))
    return columns
