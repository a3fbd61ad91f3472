#!/usr/bin/python3
"""The compaction that the Charmetant law sees behind the transverse kink
(doc/identification.md section 5.3).

When the yarn deflects by w(x) and its cross-sections stay normal to x
(the continuum has no reason to rotate them: the law has no longitudinal
shear stiffness), F = I + w' e_y (x) e_x rotates the fibre but not the
section: I4 = 1 + w'^2, J = 1, so I_tc = -1/4 ln(1 + w'^2) with no change
of the section's area. This script reads one FE snapshot (a single-piece
`fe_NNNN.0.vtu` written by deal.II, zlib-compressed binary) and prints,
along the yarn, the slope w' of the centre line, the cells' mean I_tc and
the kinematic prediction -1/4 ln(1 + w'^2 (1 + eps)^-2...) to first order.

  fe_kink_compaction.py fe_NNNN.0.vtu [fe_0000.0.vtu]

The second file (the reference snapshot) gives the cells' undeformed x.
"""
import base64
import re
import struct
import sys
import zlib

import numpy as np


def read_arrays(path):
    """Every DataArray of a deal.II zlib-compressed binary VTU, by name."""
    text = open(path).read()
    arrays = {}
    for m in re.finditer(r'<DataArray type="(\w+)"(?: Name="([^"]*)")?'
                         r'(?: NumberOfComponents="(\d+)")? format="binary"'
                         r'>\s*(.*?)\s*</DataArray>', text, re.S):
        kind, name, ncomp, data = m.groups()
        name = name or "points"
        # Header: number of blocks, block size, last block size, then the
        # compressed size of each block, as uint32, base64 on its own.
        head = base64.b64decode(data[:24])
        nblocks = struct.unpack("<I", head[:4])[0]
        hlen = 4 * (3 + nblocks)
        hb64 = 4 * ((hlen + 2) // 3)
        header = struct.unpack("<%dI" % (3 + nblocks),
                               base64.b64decode(data[:hb64])[:hlen])
        raw = base64.b64decode(data[hb64:])
        out, pos = b"", 0
        for size in header[3:]:
            out += zlib.decompress(raw[pos:pos + size])
            pos += size
        dtype = {"Float32": "<f4", "Float64": "<f8", "Int32": "<i4",
                 "UInt8": "<u1", "Int64": "<i8", "UInt32": "<u4"}[kind]
        a = np.frombuffer(out, dtype=dtype)
        if ncomp:
            a = a.reshape(-1, int(ncomp))
        arrays[name] = a
    return arrays


def main():
    if len(sys.argv) < 2:
        sys.exit(__doc__)
    now = read_arrays(sys.argv[1])
    ref = read_arrays(sys.argv[2]) if len(sys.argv) > 2 else now
    conn = now["connectivity"].reshape(-1, 8)
    xc = ref["points"][conn][:, :, 0].mean(axis=1)
    yc = now["points"][conn][:, :, 1].mean(axis=1)
    itc = now["I_tc"][conn].mean(axis=1)
    ie = now["I_e"][conn].mean(axis=1)
    layers = np.unique(np.round(xc, 9))
    rows = []
    for x in layers:
        sel = np.abs(xc - x) < 1e-9
        rows.append((x, yc[sel].mean(), itc[sel].mean(), ie[sel].mean()))
    rows = np.array(rows)
    slope = np.gradient(rows[:, 1], rows[:, 0])
    # Fibre stretch lambda_f = exp(I_e); the deflection part of I4 is w'^2,
    # so the kinematic compaction is 1/2 ln(lambda_ax) - 1/2 ln(lambda_f)
    # with lambda_f^2 = lambda_ax^2 + w'^2, i.e. -1/4 ln(1 + w'^2/lambda_ax^2).
    lam_f = np.exp(rows[:, 3])
    lam_ax2 = np.maximum(lam_f ** 2 - slope ** 2, 1e-12)
    kin = -0.25 * np.log1p(slope ** 2 / lam_ax2)
    print("%10s %10s %12s %14s" % ("x [mm]", "slope w'", "mean I_tc",
                                   "-1/4 ln(1+w'^2)"))
    step = max(1, len(rows) // 25)
    for k in range(0, len(rows), step):
        print("%10.3f %10.4f %12.5f %14.5f" % (rows[k, 0] * 1e3, slope[k],
                                               rows[k, 2], kin[k]))
    behind = np.abs(slope) > 0.05
    if behind.any():
        print("behind the kink (|w'| > 0.05, %d layers): mean I_tc %.5f, "
              "kinematic prediction %.5f" % (behind.sum(),
                                             rows[behind, 2].mean(),
                                             kin[behind].mean()))


if __name__ == "__main__":
    main()
