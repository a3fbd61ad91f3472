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


def integrate(rate, y, duration, steps):
    """y after DURATION of dy/dt = rate(y) from Y, by classical
    Runge-Kutta in STEPS equal steps."""
    h = duration / steps
    for _ in range(steps):
        k1 = rate(y)
        k2 = rate(y + 0.5 * h * k1)
        k3 = rate(y + 0.5 * h * k2)
        k4 = rate(y + h * k3)
        y += h * (k1 + 2 * k2 + 2 * k3 + k4) / 6
    return y


def finish():
    """Exit with 1 if any check failed, else 0."""
    sys.exit(1 if _failures else 0)
