"""The pass/fail lines of the fabric tests' checkers (check_*.py): one
"ok" or "FAILED" line a check, and an exit status that counts the
failures."""
import sys

_failures = 0


def check(ok, text):
    """Print TEXT as a passed or a failed check; count a failure."""
    global _failures
    print(("ok     " if ok else "FAILED ") + text)
    if not ok:
        _failures += 1


def finish():
    """Exit with 1 if any check failed, else 0."""
    sys.exit(1 if _failures else 0)
