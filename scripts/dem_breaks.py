#!/usr/bin/python3
"""Where the DEM's trusses are broken in a snapshot (doc/hybrid.md section
5.2): reads DIR/dem_NNNN.pvtu and its pieces (the cell field `broken`, the
point fields `displacement`), and prints the number of broken trusses and a
histogram of their reference |x| (the mid-point of the truss) in bins of
0.5 mm.

Usage: dem_breaks.py DIR/dem_NNNN.pvtu
"""
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


def main():
    if len(sys.argv) != 2:
        sys.exit("usage: dem_breaks.py DIR/dem_NNNN.pvtu")
    record = sys.argv[1]
    try:
        pieces = re.findall(r'Source="([^"]+)"', open(record).read())
        xs = []
        for piece in pieces:
            a = piece_arrays(os.path.join(os.path.dirname(record), piece))
            reference = a["points"] - a["displacement"]
            broken = np.nonzero(a["broken"])[0]
            ends = a["lines"][broken]
            xs.extend(0.5 * (reference[ends[:, 0], 0] + reference[ends[:, 1], 0]))
    except (OSError, KeyError, AttributeError, ValueError) as e:
        sys.exit(f"dem_breaks.py: error: cannot read the snapshot '{record}': {e}")
    xs = np.abs(np.array(xs)) * 1e3
    print(f"{record}: {len(xs)} broken trusses")
    if len(xs):
        counts, edges = np.histogram(xs, bins=np.arange(0., xs.max() + 0.5, 0.5))
        for k, c in enumerate(counts):
            if c:
                print(f"  |x| {edges[k]:5.1f} to {edges[k + 1]:5.1f} mm: {c}")


main()
