#!/usr/bin/env python3
"""What the DEM impact model's slab decomposition would do on 2 to 256 MPI
ranks of a cluster: a model, not a measurement (doc/performance-dem.md,
"Past two cores").

It follows the code (source/dem/decomposition.cc, dem_model.cc):
- the half yarn's cross-sections (stations) are cut into slabs along x; with
  x symmetry the first slab, which holds the impact point, is
  `DEM/Impact slab share` of an even one;
- a rank stores its own slab and the whole slabs of both neighbours, and
  keeps G ghost cross-sections of each neighbour up to date (G starts at
  `DEM/Ghost stations` = 4 and grows when broken fibres recoil; 13 is what
  the cut cases reach);
- every step: two ghost exchanges (positions, velocities) with each
  neighbour, one MPI_Allreduce of the x-extents of every cross-section
  (2 doubles per station, the ghost-completeness check) and one of the
  force on the projectile (1 double).

Inputs are the paper's yarn and the code's memory estimate (600 bytes per
sphere and 160 MB per rank, core/memory_estimate.cc, DEM::memory_estimate)
and, as assumptions stated on the command line, the time of one
sphere-step on one core and the network's latency and bandwidth. The
default core time is that of the 2-rank DEM benchmark from the impact in
doc/performance.md (106.8 M sphere-steps/s on 2 ranks, 2-vCPU AMD EPYC VM:
18.7 ns per sphere-step per rank); the default network is a 100 Gb/s
InfiniBand-class link (1.5 us latency, 12.5 GB/s).

    python3 scripts/dem_scaling_model.py [--ns-per-sphere-step 18.7]
        [--latency-us 1.5] [--bandwidth-GBps 12.5] [--ghosts 4]
"""
import argparse
import math

p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
p.add_argument("--fibres", type=int, default=400)
p.add_argument("--length", type=float, default=0.0254, help="yarn length [m]")
p.add_argument("--spacing", type=float, default=12e-6, help="sphere spacing [m]")
p.add_argument("--slab-share", type=float, default=0.92)
p.add_argument("--ghosts", type=int, default=4, help="ghost cross-sections G")
p.add_argument("--ns-per-sphere-step", type=float, default=18.7)
p.add_argument("--latency-us", type=float, default=1.5)
p.add_argument("--bandwidth-GBps", type=float, default=12.5)
p.add_argument("--steps", type=int, default=58566,
               help="steps of the paper's case to 40 us (dt 0.683 ns)")
a = p.parse_args()

n_st = round(0.5 * a.length / a.spacing) + 1  # half yarn, x symmetry
nf = a.fibres
alpha = a.latency_us * 1e-6
beta = a.bandwidth_GBps * 1e9
t_s = a.ns_per_sphere_step * 1e-9


def slabs(P):
    first = min(n_st, round(a.slab_share * n_st / P)) if P > 1 else n_st
    starts = [0] + [first + (n_st - first) * (q - 1) // (P - 1)
                    for q in range(1, P)] + [n_st]
    return [starts[q + 1] - starts[q] for q in range(P)]


def row(P, G):
    s = slabs(P)
    thinnest = min(s)
    fits = P == 1 or thinnest >= G + 1
    owned = max(s) * nf
    stored = (min(3, P) * max(s)) * nf
    mem = 600 * stored + 160e6
    ghost_bytes = G * nf * 3 * 8  # one exchange to one neighbour
    extents_bytes = 2 * n_st * 8
    logP = math.ceil(math.log2(P)) if P > 1 else 0
    # 2 exchanges x 2 neighbours, sent at once: one latency, the bytes of both
    t_halo = (2 * (alpha + 2 * ghost_bytes / beta)) if P > 1 else 0.
    t_reduce = (logP * (2 * alpha + extents_bytes / beta)) if P > 1 else 0.
    t_comp = owned * t_s
    t_step = t_comp + t_halo + t_reduce
    eff = (n_st * nf * t_s) / (P * t_step)
    return dict(P=P, slab=thinnest, fits=fits, owned=owned, mem=mem / 1e6,
                halo=ghost_bytes / 1e3, ext=extents_bytes / 1e3,
                comp=t_comp * 1e3, comm=(t_halo + t_reduce) * 1e3,
                eff=eff, run=t_step * a.steps)


print(f"# {nf} fibres x {a.length * 1e3:g} mm, half symmetry: {n_st} "
      f"cross-sections, {n_st * nf} spheres; {a.ns_per_sphere_step} ns per "
      f"sphere-step and core, network {a.latency_us} us + "
      f"{a.bandwidth_GBps} GB/s (assumed)")
for G in sorted({a.ghosts, 13}):
    print(f"\n## ghost layers G = {G}\n")
    print("| ranks | thinnest slab [stations] | slabs fit | spheres per rank "
          "| memory per rank [MB] | ghost message [kB] | extents allreduce [kB] "
          "| compute per step [ms] | communication per step [ms] "
          "| efficiency | paper's case (58 566 steps) [s] |")
    print("|---|---|---|---|---|---|---|---|---|---|---|")
    for P in [1, 2, 4, 8, 16, 32, 64, 128, 256]:
        r = row(P, G)
        print(f"| {P} | {r['slab']} | {'yes' if r['fits'] else 'no'} "
              f"| {r['owned']} | {r['mem']:.0f} | {r['halo']:.1f} "
              f"| {r['ext']:.1f} | {r['comp']:.3f} | {r['comm']:.3f} "
              f"| {r['eff']:.2f} | {r['run']:.0f} |")

# After the cut: a slab decomposition by cross-section holds while no sphere
# meets a sphere of a slab beyond its neighbours' (the run stops with "fibres
# slid across the slabs of more than two MPI ranks" otherwise). On 2 ranks
# the paper's case ends with ghost layers of 372 and 472 of the other rank's
# 530 cross-sections (doc/performance.md): cut pieces swing back by up to
# `--recoil-stations` cross-sections.
recoil = 472
print(f"\n## after the cut (pieces recoil by up to {recoil} cross-sections)\n")
for P in [2, 3, 4, 5, 8, 16]:
    s = min(slabs(P)[1:]) if P > 1 else n_st
    ok = P <= 2 or 2 * s >= recoil
    print(f"- {P} ranks: slabs of {s} cross-sections, two of them "
          f"{2 * s}: {'holds' if ok else 'a recoiling piece may cross two slabs'}")

# What would fit: memory 600 B per sphere + 160 MB per rank.
c_bar = 7950.  # bar wave speed of KM2 [m/s], doc/theory.md
t_end = 40e-6
half_useful = c_bar * t_end  # the longitudinal wave does not reach the clamp
st_useful = round(half_useful / a.spacing) + 1
spheres_useful = st_useful * nf
print(f"\n## what fits\n")
print(f"- the longest useful yarn for {t_end * 1e6:g} us: the longitudinal wave "
      f"travels {half_useful * 1e3:.0f} mm, so a half yarn of that length "
      f"({st_useful} cross-sections, {spheres_useful / 1e6:.1f} M spheres, "
      f"{600 * spheres_useful / 1e9:.1f} GB) never sees its clamp; on 64 "
      f"ranks {spheres_useful // 64} spheres per rank, "
      f"{spheres_useful / 64 * t_s * 1e3:.2f} ms per step, "
      f"{spheres_useful / 64 * t_s * a.steps / 60:.1f} min for {a.steps} steps "
      f"before the cut, with no slab thinner than "
      f"{st_useful // 64} cross-sections")
pitch = 0.6e-3
side = 10e-3
n_yarns = 2 * round(side / pitch)
patch = n_yarns * nf * (round(side / a.spacing) + 1)
print(f"- a woven patch {side * 1e3:g} x {side * 1e3:g} mm of this yarn "
      f"(pitch {pitch * 1e3:g} mm, {n_yarns} yarns): {patch / 1e6:.1f} M spheres, "
      f"{600 * patch / 1e9:.1f} GB; {patch * t_s * a.steps / 64 / 60:.0f} min "
      f"on 64 ranks at the benchmark's rate, but slabs along one yarn's axis "
      f"cannot hold it (the crossing yarns run through every slab): it needs "
      f"a decomposition by position in x and z")
