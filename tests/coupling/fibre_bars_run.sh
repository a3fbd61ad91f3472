#!/bin/bash
# Usage: fibre_bars_run.sh YARN_IMPACT SOURCE_DIR [ranks]
# With `ranks` (ctest label long, apart from the default suite): only the
# history on 1, 2 and 3 MPI ranks, byte for byte; without it every other
# check below on 1 rank.
# The hybrid yarn with a far field of fibre bars (Hybrid/Far field =
# fibre bars, doc/hybrid.md section 3.4), the paper's case with a 3 mm DEM
# part over the first 1.8 us (the bar wave reaches the clamp at 1.66 us).
# Physics and consistency checks, no recorded numbers:
# - the run's own checks: the longitudinal front's speed, fitted from 1 us
#   until it reaches the clamp (through the DEM part, the overlap and the
#   bars), within 2 % of Smith's bar speed (measured -1.2 %), and the
#   largest energy balance error, the bars and both ties included, at most
#   0.05 % of the initial energy (the projectile's deceleration is the DEM
#   part's until the bars' waves come back, checked by hybrid_run.sh);
# - the projectile's and the yarn's momentum along the impact direction
#   conserved within 1e-9 of m v0 at every row (momentum_balance.py: the
#   bars move along x only, the FE nodes carry the transverse mass);
# - the same history on 1, 2 and 3 MPI ranks (each rank steps its own
#   fibres' bars, the sums over fibres are in fibre order, the DEM part's
#   sums are reproducible): byte for byte;
# - stopped by SIGTERM at a history row and continued with --restart: the
#   same history, byte for byte (the bars' checkpoint);
# - bad set-ups refused by --check with one line naming the parameter.
exe=$1
src=$2
mode=${3:-}
. "$(dirname "$(readlink -f "$0")")/../lib.sh"
test_begin
. "$src/tests/coupling/run_checks.sh"

bars_prm() {
  cat "$src/prm/hybrid/km2_120ms_hybrid.prm"
  printf 'subsection Hybrid\n  set DEM half-length = 3e-3\n'
  printf '  set Far field = fibre bars\nend\n'
  printf 'subsection Time\n  set End time = 1.8e-6\nend\n'
  printf 'subsection Output\n  set Directory = %s\n  set Snapshot interval = 1.8e-6\nend\n' "$1"
  printf 'subsection Verification\n  set Checks = longitudinal speed, energy\n'
  printf '  set Window end = 1.8e-6\n  set Energy tolerance = 5e-4\n  set Tolerance = 0.02\nend\n'
}

if [ "$mode" = ranks ]; then
  same_on_ranks bars_prm 1 2 3
  snapshots="ranks1 ranks3"
else
  same_on_ranks bars_prm 1
  snapshots=ranks1
  grep -E "longitudinal speed|energy error" ranks1/summary.txt
  momentum_conserved ranks1 "fibre bars"
  restart_same bars_prm 9 ranks1/history_hybrid.csv
fi

# The bars' snapshot at 1.8 us (the bar wave has reached the clamp): named
# by the multiblock record, one piece per rank, 400 fibres whose reference
# x runs from the overlap's start (the DEM part of 2.88 mm less the 1 mm
# overlap, on FE cell boundaries) to the clamp (12.7 mm), one bar per DEM
# truss (12 um), the bar wave's strain in them (above 0.5 %), and with
# `ranks` the same points and strains on 1 and 3 ranks.
# shellcheck disable=SC2086
/usr/bin/python3 - $snapshots << 'END' || fail "the bars' snapshot"
import base64, re, struct, sys
import numpy as np
def arrays(path):
    text = open(path).read()
    out = {}
    for m in re.finditer(r'<DataArray type="(\w+)"(?: Name="(\w+)")?[^>]*>([^<]*)</DataArray>', text):
        b = m.group(3).strip()
        n = struct.unpack("<I", base64.b64decode(b[:8])[:4])[0]
        t = {"Float32": np.float32, "Int32": np.int32, "UInt8": np.uint8}[m.group(1)]
        out[m.group(2) or "Points"] = np.frombuffer(base64.b64decode(b[8:])[:n], dtype=t)
    return out
def snapshot(d, ranks):
    if 'file="bars_0001.pvtu"' not in open(d + "/hybrid_0001.vtm").read():
        sys.exit(f"{d}/hybrid_0001.vtm does not name bars_0001.pvtu")
    pieces = re.findall(r'Source="([^"]+)"', open(d + "/bars_0001.pvtu").read())
    if len(pieces) != ranks:
        sys.exit(f"{d}: {len(pieces)} pieces on {ranks} ranks")
    a = [arrays(d + "/" + p) for p in pieces]
    # Reference positions: the points less their displacements.
    pts = (np.concatenate([x["Points"] for x in a]).reshape(-1, 3) -
           np.concatenate([x["displacement"] for x in a]).reshape(-1, 3))
    strain = np.concatenate([x["strain"] for x in a])
    return pts, strain
p1, e1 = snapshot(sys.argv[1], 1)
p3, e3 = snapshot(sys.argv[2], 3) if len(sys.argv) > 2 else (p1, e1)
nodes = len(p1) // 400
spacing = (p1[:, 0].max() - p1[:, 0].min()) / (nodes - 1)
if (len(p1) != 400 * nodes or not 1.5e-3 < p1[:, 0].min() < 2.0e-3 or
        abs(p1[:, 0].max() - 12.7e-3) > 1e-6 or abs(spacing / 12e-6 - 1) > 0.01):
    sys.exit(f"{len(p1)} points from reference x = {p1[:, 0].min()} to {p1[:, 0].max()} m, spacing {spacing} m")
if not e1.max() > 0.005 or not np.array_equal(p1, p3) or not np.array_equal(e1, e3):
    sys.exit(f"strains {e1.min()} to {e1.max()}, 1 = 3 ranks: {np.array_equal(p1, p3)}")
print(f"bars' snapshot: {len(p1)} points, strains {e1.min():.3e} to {e1.max():.3e}"
      + (", 1 = 3 ranks" if len(sys.argv) > 2 else ""))
END
[ "$mode" = ranks ] &&
  test_end "fibre_bars_run: the same history on 1, 2 and 3 ranks, the same bars' snapshot on 1 and 3"

# With a DEM part at the clamp (Hybrid/Clamp DEM length = 2 mm; FE cells
# of 5 trusses, so that the profile samples the bars every 60 um, as the
# DEM parts every truss), 2 us: the bars end in the clamp part's overlap
# (10.72 to 11.74 mm), free, each sphere there tied to its fibre's bar
# node in x. The run's own checks: the bar speed fitted from 1 us until
# the front reaches the clamp (through the bars and the clamp part) within
# 2 % of Smith's (measured +0.23 %), the energy balance within 0.05 %
# (0.0004 %); the momentum conserved; and in the snapshot at 2 us, where
# the bar wave has crossed the clamp overlap, each sphere's truss strain
# there that of its fibre's bar at the same reference x (one bar per
# truss: the tie makes them one fibre) within 1e-6 of the largest strain
# (the snapshot's float32; measured 9.3e-10 at strains up to 0.91 %).
clamp_prm() {
  bars_prm "$1"
  printf 'subsection Hybrid\n  set Clamp DEM length = 2e-3\n'
  printf '  set FE cells along the axis = 400\nend\n'
  printf 'subsection Time\n  set End time = 2e-6\nend\n'
  printf 'subsection Output\n  set Snapshot interval = 2e-6\nend\n'
}
clamp_prm clamp > clamp.prm
"$exe" clamp.prm > clamp.stdout 2>&1 ||
  { fail "fibre bars with a clamp part: exit $? (3 = a check failed)"; tail -25 clamp.stdout; }
grep -E "longitudinal speed|energy error" clamp/summary.txt
momentum_conserved clamp "fibre bars with a clamp part"
/usr/bin/python3 - "$src" clamp << 'END' || fail "fibre bars with a clamp part: the tie at the clamp"
import sys
import numpy as np
sys.path.insert(0, sys.argv[1] + "/scripts")
from dem_breaks import piece_arrays
def trusses(path):
    """(fibre, reference x of the mid-point in um) -> strain."""
    a = piece_arrays(path)
    ref = a["points"] - a["displacement"]
    ends = a["lines"]
    x = np.rint(0.5e6 * (ref[ends[:, 0], 0] + ref[ends[:, 1], 0])).astype(int)
    return {(int(a["fibre_id"][i]), int(xi)): float(e)
            for i, xi, e in zip(ends[:, 0], x, a["strain"])}
d = sys.argv[2]
bars, clamp = trusses(d + "/bars_0001_r0.vtu"), trusses(d + "/dem_clamp_0001_r0.vtu")
common = [k for k in clamp if k in bars]
worst = max(abs(bars[k] - clamp[k]) for k in common)
largest = max(abs(clamp[k]) for k in common)
print(f"clamp overlap: {len(common)} trusses on bars, largest strain {largest:.3e}, "
      f"largest |bar - truss| {worst:.2e}")
# The snapshot's strains are float32: a few units in their last place.
if len(common) < 400 * 80 or largest < 1e-3 or worst > 1e-6 * largest:
    sys.exit("the clamp part's trusses do not follow their bars")
END
refuse bars_prm "the section's tie with a clamp part" "Hybrid/Transverse tie" \
  'subsection Hybrid\n  set Clamp DEM length = 2e-3\n  set Transverse tie = section mean\nend\n'
refuse bars_prm "fibre bars with the linear law" "FE/Constitutive law" \
  'subsection FE\n  set Constitutive law = Linear transversely isotropic\nend\n'
refuse bars_prm "an unknown far field" "Far field" \
  'subsection Hybrid\n  set Far field = springs\nend\n'

test_end "fibre bars: bar speed, energy, restart, snapshot, bad set-ups: all passed"
