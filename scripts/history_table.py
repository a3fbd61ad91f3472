#!/usr/bin/python3
"""Markdown table of runs: projectile velocity at given times, the first
failure (broken truss or failed cell), and the range of the section width at
the impact point over 0-20 us relative to its initial value (the spreading
comparison of doc/validation.md section 2), from their history CSV files.

Usage: history_table.py LABEL=DIR/history_X.csv [LABEL=...]
"""
import csv
import sys

TIMES = (10, 20, 25, 28)
WIDTH_WINDOW = 20.0  # [us]


def main():
    if len(sys.argv) < 2:
        sys.exit(__doc__)
    print("| run | " + " | ".join(f"v({t} us) [m/s]" for t in TIMES)
          + " | first failure [us] | end [us] | width at impact, 0-20 us |")
    print("|---" * (len(TIMES) + 4) + "|")
    for spec in sys.argv[1:]:
        label, _, path = spec.partition("=")
        rows = list(csv.DictReader(open(path)))
        t = [float(r["t [us]"]) for r in rows]

        def v_at(time):
            if time > t[-1] + 1e-9:
                return "-"
            k = min(range(len(t)), key=lambda i: abs(t[i] - time))
            return f"{float(rows[k]['projectile velocity [m/s]']):.2f}"

        first = next((ti for ti, r in zip(t, rows)
                      if int(r["failed elements"]) > 0), None)
        print(f"| {label} | " + " | ".join(v_at(x) for x in TIMES)
              + f" | {first:.2f} |" if first is not None else
              f"| {label} | " + " | ".join(v_at(x) for x in TIMES) + " | none |",
              end="")
        w = [float(r["section width at impact [mm]"])
             for ti, r in zip(t, rows) if ti <= WIDTH_WINDOW + 1e-6]
        change = [100. * (x / w[0] - 1.) for x in w]
        print(f" {t[-1]:.1f} | {min(change):+.1f} % ... {max(change):+.1f} % |")


if __name__ == "__main__":
    main()
