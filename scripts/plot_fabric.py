#!/usr/bin/env python3
"""Plots of a `Model = fabric` run from its history (doc/fabric.md):

  python3 scripts/plot_fabric.py RUN/history_fabric.csv OUT_PREFIX [TITLE]

writes OUT_PREFIX_velocity.png (the projectile's velocity and the contact
force against time), OUT_PREFIX_energy.png (the energy partition: the
projectile's kinetic energy, the primary and the secondary yarns' kinetic
and strain energies, the yarn contact's stored energy and its friction
work, the damage and erosion (dissipated), and the energy error) and
OUT_PREFIX_cone.png (the transverse (cone) front along the warp, the weft
and the diagonal). A missing or unreadable file, or a history without the
fabric's columns, gives one line `plot_fabric.py: error: ...` and exit 1.
"""
import csv
import sys

COLUMNS = {
    "t": "t [us]",
    "v": "projectile velocity [m/s]",
    "force": "contact force [N]",
    "ke_p": "projectile kinetic energy [mJ]",
    "ke_primary": "primary yarns kinetic energy [mJ]",
    "se_primary": "primary yarns strain energy [mJ]",
    "ke_secondary": "secondary yarns kinetic energy [mJ]",
    "se_secondary": "secondary yarns strain energy [mJ]",
    "contact": "yarn contact energy [mJ]",
    "friction": "yarn contact dissipated energy [mJ]",
    "dissipated": "dissipated energy [mJ]",
    "projectile_contact": "contact energy [mJ]",
    "error": "energy error [%]",
    "warp": "cone front along warp [mm]",
    "weft": "cone front along weft [mm]",
    "diagonal": "cone front along diagonal [mm]",
}


def fail(message):
    print("plot_fabric.py: error: " + message, file=sys.stderr)
    sys.exit(1)


def read(path):
    try:
        with open(path, newline="") as f:
            rows = list(csv.DictReader(f))
    except (OSError, UnicodeDecodeError, csv.Error) as e:
        fail("cannot read %s: %s" % (path, e))
    if not rows:
        fail("%s has no rows" % path)
    missing = [c for c in COLUMNS.values() if c not in rows[0]]
    if missing:
        fail("%s is not a fabric history: no column %s"
             % (path, ", ".join(repr(c) for c in missing)))
    try:
        return {k: [float(r[c]) for r in rows] for k, c in COLUMNS.items()}
    except ValueError as e:
        fail("%s: %s" % (path, e))


def main(argv):
    if len(argv) not in (2, 3):
        sys.exit(__doc__)
    h = read(argv[0])
    prefix = argv[1]
    title = argv[2] if len(argv) == 3 else ""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    t = h["t"]
    fig, ax = plt.subplots(figsize=(7, 4.2))
    ax.plot(t, h["v"], color="C0", label="projectile velocity")
    ax.set_xlabel("t [us]")
    ax.set_ylabel("projectile velocity [m/s]", color="C0")
    ax2 = ax.twinx()
    ax2.plot(t, h["force"], color="C3", lw=0.8, label="contact force")
    ax2.set_ylabel("projectile contact force [N]", color="C3")
    ax.set_title(title)
    ax.grid(alpha=0.3)
    fig.tight_layout()
    fig.savefig(prefix + "_velocity.png", dpi=120)
    plt.close(fig)

    fig, ax = plt.subplots(figsize=(7, 4.6))
    lost = [h["ke_p"][0] - e for e in h["ke_p"]]
    series = [
        ("projectile: kinetic energy lost", lost, "k", "-"),
        ("primary yarns: kinetic", h["ke_primary"], "C0", "-"),
        ("primary yarns: strain", h["se_primary"], "C0", "--"),
        ("secondary yarns: kinetic", h["ke_secondary"], "C1", "-"),
        ("secondary yarns: strain", h["se_secondary"], "C1", "--"),
        ("yarn contact: stored", h["contact"], "C2", ":"),
        ("yarn contact: friction", h["friction"], "C2", "-"),
        ("damage and erosion", [d - f for d, f in
                                zip(h["dissipated"], h["friction"])],
         "C3", "-"),
    ]
    for label, values, colour, style in series:
        ax.plot(t, values, color=colour, ls=style, label=label)
    ax.set_xlabel("t [us]")
    ax.set_ylabel("energy [mJ]")
    # Two lines: the case and the error do not fit one at this width.
    ax.set_title((title + "\n" if title else "") + "largest energy error "
                 "%.3f %% of the initial energy"
                 % max(abs(e) for e in h["error"]), fontsize=10)
    ax.grid(alpha=0.3)
    ax.legend(fontsize=8, loc="upper left")
    fig.tight_layout()
    fig.savefig(prefix + "_energy.png", dpi=120)
    plt.close(fig)

    fig, ax = plt.subplots(figsize=(7, 4.2))
    for key, label in (("warp", "along the warp (x)"),
                       ("weft", "along the weft (z)"),
                       ("diagonal", "along the diagonal")):
        ax.plot(t, h[key], label=label)
    ax.set_xlabel("t [us]")
    ax.set_ylabel("transverse (cone) front [mm]")
    ax.set_title(title)
    ax.grid(alpha=0.3)
    ax.legend(fontsize=9)
    fig.tight_layout()
    fig.savefig(prefix + "_cone.png", dpi=120)
    plt.close(fig)
    print("plot_fabric.py: wrote %s_velocity.png, %s_energy.png, "
          "%s_cone.png" % (prefix, prefix, prefix))


if __name__ == "__main__":
    main(sys.argv[1:])
