# Sourced by the hybrid yarn's run tests.
# same_history A B: every column byte for byte but the energy balance's,
# which the DEM part sums per rank (as Model = dem does): those within
# 1e-9 of the initial energy.
same_history() {
  /usr/bin/python3 - "$1" "$2" << 'END'
import csv, sys
a, b = (list(csv.reader(open(p))) for p in sys.argv[1:3])
if len(a) != len(b) or a[0] != b[0]:
    sys.exit(1)
h = a[0]
energy = [k for k, n in enumerate(h) if "energy" in n or "external work" in n]
scale = float(a[1][h.index("projectile kinetic energy [mJ]")])
for x, y in zip(a[1:], b[1:]):
    for k in range(len(h)):
        if x[k] == y[k]:
            continue
        bound = 1e-9 * (100. if "[%]" in h[k] else scale)
        if k not in energy or abs(float(x[k]) - float(y[k])) > bound:
            print(f"t = {x[0]} us, {h[k]}: {x[k]} against {y[k]}")
            sys.exit(1)
END
}
