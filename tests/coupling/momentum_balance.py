"""momentum_balance.py DIR LABEL: the hybrid yarn's momentum balance along
the impact direction, a physics check (no recorded numbers). Nothing
outside the projectile and the yarn acts on them along -y until a
transverse wave reaches a clamp (the clamps hold the ends; the symmetry
planes x = 0 and z = 0 take no force along y), and every force inside
them is applied equal and opposite in the same kick: the projectile
contact, the DEM's contacts and trusses, the FE part's nodal forces, the
overlap's constraint forces (their shape values sum to one at every
sphere) and the fibre bars (along x only). So the projectile's m v plus
the history's `yarn momentum [kg m/s]` (all parts, weighted masses) stays
the projectile's m v0 to round-off. Passes when it does, within 1e-9 of
m v0 at every row (the CSV's projectile velocity has 10 digits), while
the yarn has taken at least 1e-4 of m v0 (the check would see a coupling
that created or lost momentum); prints the largest deviation. The mass
and the impact velocity are read from DIR/parameters.prm."""
import csv
import re
import sys

TOLERANCE = 1e-9


def projectile(directory):
    """(mass [kg], velocity [m/s]) of the run's resolved parameters."""
    values, section = {}, []
    for line in open(f"{directory}/parameters.prm"):
        words = line.split()
        if not words:
            continue
        if words[0] == "subsection":
            section.append(" ".join(words[1:]))
        elif words[0] == "end":
            section.pop()
        elif words[0] == "set" and section == ["Projectile"]:
            name, value = re.match(r"\s*set\s+(.*?)\s*=\s*(\S+)", line).groups()
            values[name] = value
    return float(values["Mass"]), float(values["Initial velocity"])


def main():
    directory, label = sys.argv[1:3]
    mass, v0 = projectile(directory)
    rows = list(csv.DictReader(open(f"{directory}/history_hybrid.csv")))
    p0 = mass * v0
    worst, taken = 0., 0.
    for r in rows:
        yarn = float(r["yarn momentum [kg m/s]"])
        total = mass * float(r["projectile velocity [m/s]"]) + yarn
        worst = max(worst, abs(total - p0) / p0)
        taken = max(taken, yarn / p0)
    print(f"{label}: momentum of projectile and yarn, largest deviation "
          f"{worst:.2e} of m v0 over {len(rows)} rows (at most "
          f"{TOLERANCE:g}); the yarn took up to {taken:.2e} of it")
    sys.exit(0 if len(rows) > 5 and worst <= TOLERANCE and taken >= 1e-4
             else 1)


if __name__ == "__main__":
    main()
