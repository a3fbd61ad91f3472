"""Render a woven ply of a `Model = fabric` run in perspective (pvbatch).

Usage (a display is needed; xvfb-run provides one):
  xvfb-run -a pvbatch scripts/render_ply.py RUN/fabric.pvd OUT_PREFIX FIELD
      T1 [T2 ...] [--y-scale S] [--range LO HI] [--title TEXT]
      [--width PIXELS]

Writes OUT_PREFIX_<T>us.png for each requested time T (in us), the ply seen
from above and aside (the impact direction is -y, the warp yarns along x,
the weft yarns along z), its deflection stretched S times (default 1: true
scale) if the cone (the pyramid) is to show more, coloured by FIELD (point or cell data of
the fabric's VTU: longitudinal_strain, damage, I_tc, yarn, ply, ...).
Failed cells are not drawn. A requested time is rendered at the nearest
snapshot; one with no snapshot within 0.5 us is skipped with a message.
The helpers (fonts, labels, background) are those of render_yarn.py.
"""
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))

from paraview.simple import (Clip, ColorBy,  # noqa: E402
                             GetActiveViewOrCreate, GetColorTransferFunction,
                             OpenDataFile, SaveScreenshot, Show, Transform,
                             UpdatePipeline)

from render_yarn import (TITLES, option, scalar_bar,  # noqa: E402
                         text, white_background)

TITLES = dict(TITLES, damage="fibre damage [-]", yarn="yarn number",
              ply="ply number")


def main(argv):
    args = list(argv)
    y_scale = float(option(args, "--y-scale", default=1.0))
    value_range = option(args, "--range", count=2)
    title = option(args, "--title")
    width = int(option(args, "--width", default=1400))
    if len(args) < 4:
        sys.exit(__doc__)
    pvd, prefix, field = args[0], args[1], args[2]
    requested = [float(t) for t in args[3:]]
    if title is None:
        title = TITLES.get(field, field)

    reader = OpenDataFile(pvd)
    available = list(getattr(reader, "TimestepValues", []) or [0.0])
    if not isinstance(available, list):
        available = [available]
    source = reader
    if reader.PointData.GetArray("failed") is not None:
        # A clip by the scalar, not Threshold, which crashes ParaView
        # 5.11 on some of these snapshots.
        source = Clip(Input=source)
        source.ClipType = "Scalar"
        source.Scalars = ["POINTS", "failed"]
        source.Value = 0.5
        source.Invert = 1
        source.Crinkleclip = 1
    mm = Transform(Input=source)
    mm.Transform.Scale = [1e3, 1e3 * y_scale, 1e3]

    view = GetActiveViewOrCreate("RenderView")
    white_background(view)
    view.OrientationAxesVisibility = 1
    view.EnableRenderOnInteraction = 0
    view.ViewSize = [width, int(0.72 * width)]

    display = Show(mm, view)
    display.Representation = "Surface"
    display.Ambient = 0.3
    display.Diffuse = 0.8
    display.Specular = 0.1
    ColorBy(display, ("POINTS" if reader.PointData.GetArray(field)
                      is not None else "CELLS", field))
    lut = GetColorTransferFunction(field)
    lut.ApplyPreset("Turbo", True)
    lut.AutomaticRescaleRangeMode = "Never"
    bar = scalar_bar(lut, view, title)
    bar.WindowLocation = "Lower Center"
    bar.ScalarBarLength = 0.4
    bar.RangeLabelFormat = "%.3g"

    time_label = text(view, "", "Upper Left Corner", 30)
    note = ("deflection (y) exaggerated x%g, failed cells not shown"
            % y_scale if y_scale != 1.0 else "failed cells not shown")
    text(view, note, "Upper Right Corner", 22)

    for t_req in requested:
        t = min(available, key=lambda a: abs(a - t_req))
        if abs(t - t_req) > 0.5:
            print(f"render_ply: {pvd} has no snapshot at {t_req:g} us; "
                  "skipped", flush=True)
            continue
        view.ViewTime = t
        UpdatePipeline(time=t, proxy=mm)
        b = mm.GetDataInformation().GetBounds()
        if b[0] > b[1]:
            print(f"render_ply: nothing to show at {t:g} us; skipped",
                  flush=True)
            continue
        if value_range:
            lo_v, hi_v = (float(v) for v in value_range)
        else:
            info = mm.PointData.GetArray(field) or \
                mm.CellData.GetArray(field)
            lo_v, hi_v = info.GetRange() if info else (0.0, 1.0)
            if hi_v <= lo_v:
                hi_v = lo_v + 1.0
        lut.RescaleTransferFunction(lo_v, hi_v)
        centre = [(b[2 * i] + b[2 * i + 1]) / 2 for i in range(3)]
        extent = max(b[1] - b[0], b[5] - b[4])
        # From above the ply and aside, the struck face's side: the cone
        # shows as the ply's depression, the yarns' weave in the light.
        view.CameraFocalPoint = centre
        view.CameraPosition = [centre[0] + 0.75 * extent,
                               centre[1] + 1.1 * extent,
                               centre[2] + 1.6 * extent]
        view.CameraViewUp = [0.0, 1.0, 0.0]
        view.CameraViewAngle = 30
        view.CameraParallelProjection = 0
        time_label.Input.Text = "t = %.1f \u00b5s" % t
        out = f"{prefix}_{t_req:g}us.png"
        SaveScreenshot(out, view, ImageResolution=view.ViewSize,
                       TransparentBackground=0)
        print(f"render_ply: wrote {out} (t = {t:.4g} us)", flush=True)


if __name__ == "__main__":
    main(sys.argv[1:])
