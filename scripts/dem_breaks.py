#!/usr/bin/python3
"""The DEM's trusses in a snapshot (doc/hybrid.md section 5): reads
DIR/dem_NNNN.pvtu and its pieces (a DEM run's or the DEM part of a hybrid
run) and prints, by the reference |x| of each truss's mid-point:

- by default, the number of broken trusses (cell field `broken`) in bins of
  0.5 mm;
- with --spread, how unevenly the fibres are strained (cell field `strain`,
  trusses not broken) in bins of --bin mm: the mean, the standard deviation
  over the fibres and the largest strain, and the mean strain of the fibres
  in the middle third of the section's width (|z| below a third of the
  largest |z|) less that of the outer third (|z| above two thirds): the
  width-wise profile that a continuum's section field can carry.

Usage: dem_breaks.py [--spread] [--bin MM] DIR/dem_NNNN.pvtu
"""
import argparse
import base64
import os
import re
import struct
import sys

import numpy as np

TYPES = {"Float32": np.float32, "Float64": np.float64, "Int32": np.int32,
         "Int64": np.int64, "UInt8": np.uint8, "UInt32": np.uint32}


def decode(block, dtype):
    """A VTK inline binary array: base64 of a UInt32 byte count, then of the
    data."""
    block = block.strip()
    n = struct.unpack("<I", base64.b64decode(block[:8])[:4])[0]
    return np.frombuffer(base64.b64decode(block[8:])[:n], dtype=dtype)


def piece_arrays(path):
    text = open(path).read()
    named = {}
    for m in re.finditer(r'<DataArray type="(\w+)" Name="(\w+)" '
                         r'NumberOfComponents="(\d+)"[^>]*>([^<]*)</DataArray>', text):
        a = decode(m.group(4), TYPES[m.group(1)])
        nc = int(m.group(3))
        named[m.group(2)] = a.reshape(-1, nc) if nc > 1 else a
    points = re.search(r'<Points>\s*<DataArray type="(\w+)"[^>]*>([^<]*)</DataArray>', text)
    named["points"] = decode(points.group(2), TYPES[points.group(1)]).reshape(-1, 3)
    cells = re.search(r'<Cells>\s*<DataArray type="(\w+)"[^>]*>([^<]*)</DataArray>', text)
    named["lines"] = decode(cells.group(2), TYPES[cells.group(1)]).reshape(-1, 2)
    return named


def trusses(record):
    """Reference mid-points [m], strains and broken flags of every truss of
    the snapshot @p record."""
    pieces = re.findall(r'Source="([^"]+)"', open(record).read())
    mids, strains, broken = [], [], []
    for piece in pieces:
        a = piece_arrays(os.path.join(os.path.dirname(record), piece))
        reference = a["points"] - a["displacement"]
        ends = a["lines"]
        mids.append(0.5 * (reference[ends[:, 0]] + reference[ends[:, 1]]))
        strains.append(a["strain"])
        broken.append(a["broken"])
    return np.concatenate(mids), np.concatenate(strains), np.concatenate(broken)


def main():
    parser = argparse.ArgumentParser(
        prog="dem_breaks.py",
        description="Broken trusses, or the spread of the fibres' strains, "
                    "along the yarn in a DEM snapshot.")
    parser.add_argument("record", help="DIR/dem_NNNN.pvtu")
    parser.add_argument("--spread", action="store_true",
                        help="print the fibres' strain spread per bin")
    parser.add_argument("--bin", type=float, default=None,
                        help="bin width along |x| [mm] (0.5 for breaks, "
                             "1 for --spread)")
    args = parser.parse_args()
    width = args.bin if args.bin is not None else (1. if args.spread else 0.5)
    if not width > 0.:
        sys.exit("dem_breaks.py: error: --bin must be positive")
    try:
        mids, strains, broken = trusses(args.record)
    except (OSError, KeyError, AttributeError, ValueError, struct.error) as e:
        sys.exit(f"dem_breaks.py: error: cannot read the snapshot "
                 f"'{args.record}': {e}")
    x = np.abs(mids[:, 0]) * 1e3
    if not args.spread:
        xs = x[broken != 0]
        print(f"{args.record}: {len(xs)} broken trusses")
        if len(xs):
            counts, edges = np.histogram(xs, bins=np.arange(0., xs.max() + width, width))
            for k, c in enumerate(counts):
                if c:
                    print(f"  |x| {edges[k]:5.1f} to {edges[k + 1]:5.1f} mm: {c}")
        return
    whole = broken == 0
    z = np.abs(mids[:, 2]) / np.abs(mids[:, 2]).max()
    print(f"{args.record}: strain of the trusses not broken, by |x|")
    print("  |x| from  to [mm]    mean      std  largest  middle - outer third")
    for lo in np.arange(0., x.max(), width):
        m = whole & (x >= lo) & (x < lo + width)
        if not m.any():
            continue
        e = strains[m].astype(float)
        middle, outer = m & (z < 1. / 3.), m & (z > 2. / 3.)
        profile = (strains[middle].mean() - strains[outer].mean()
                   if middle.any() and outer.any() else float("nan"))
        print(f"  {lo:6.2f} {lo + width:6.2f}  {e.mean():.5f}  {e.std():.5f}"
              f"  {e.max():.5f}  {profile:+.5f}")


if __name__ == "__main__":
    main()
