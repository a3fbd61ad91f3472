"""compare_histories.py A B LABEL: two histories of the hybrid yarn that
must describe the same motion (a symmetric model against the whole one,
or the quarter against the half), by the coupling tests quarter_symmetry.sh
and whole_yarn.sh. Passes when they have 13 rows each, the same failed
elements at every row, and the projectile's velocity and force, the
energies and the largest strain within 1e-5 of each column's largest
magnitude over the run (round-off: the models add their contacts in
another order); prints the largest difference."""
import csv
import sys

COLUMNS = ["projectile velocity [m/s]", "contact force [N]",
           "yarn kinetic energy [mJ]", "elastic energy [mJ]",
           "contact energy [mJ]", "dissipated energy [mJ]",
           "max longitudinal strain [-]"]
ROWS = 13
TOLERANCE = 1e-5


def main():
    a, b = (list(csv.DictReader(open(p))) for p in sys.argv[1:3])
    ok = len(a) == len(b) == ROWS
    worst = (0., "", "")
    for c in COLUMNS:
        scale = max(abs(float(x[c])) for x in a)
        for x, y in zip(a, b):
            d = abs(float(x[c]) - float(y[c])) / scale if scale > 0. else 0.
            if d > worst[0]:
                worst = (d, c, x["t [us]"])
    for x, y in zip(a, b):
        ok = ok and x["failed elements"] == y["failed elements"]
    print(f"{sys.argv[3]}, largest relative difference {worst[0]:.2e} "
          f"({worst[1]} at {worst[2]} us), {len(a)} rows")
    return 0 if ok and worst[0] <= TOLERANCE else 1


if __name__ == "__main__":
    sys.exit(main())
