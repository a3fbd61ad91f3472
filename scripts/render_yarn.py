"""Render snapshots of a yarn-impact run with ParaView (pvbatch).

Usage (a display is needed; xvfb-run provides one):
  xvfb-run -a pvbatch scripts/render_yarn.py RUN.pvd OUT_PREFIX FIELD T1 [T2 ...]
      [--view side|top|section] [--y-scale S] [--z-scale S] [--range LO HI]
      [--title TEXT] [--x X] [--width PIXELS] [--keep-broken]

Writes OUT_PREFIX_<T>us.png for each requested time T (in us, the .pvd time
unit), colouring the yarn by FIELD (point or cell data, e.g.
longitudinal_strain, I_tc, axial_strain, strain, fibre_id). A requested time
is rendered at the nearest snapshot of the .pvd; a time with no snapshot
within 0.5 us is skipped with a message (the picture is labelled with the
snapshot's own time).

Views (the yarn axis is x, the impact direction -y, the width z; the points
of the VTU files are the deformed positions):
  side     looking along -z (the transverse wave; x right, y up);
  top      looking down -y from the projectile's side (the spreading width;
           x right, z down);
  section  the slice with normal x through the impact point (at X, default
           just inside the smallest x of the mesh: x = 0 is the symmetry
           plane of a half model, the middle of a full one: give --x 0),
           looking along +x (z right, y up), framed on the section.
--y-scale / --z-scale stretch y / z so that the deflection / the spreading
show (default 1: true scale); the picture says so ("deflection x5").

--keep-broken draws the broken DEM trusses too (ParaView 5.11's Threshold,
which hides them, crashes on some DEM snapshots).

Pictures are for print: white background, dark text, the camera fitted to
the data (parallel projection), the time written on the picture, a colour
bar with a title and unit, and axes in mm with their true values.
"""
import math
import os
import sys

from paraview.simple import (ColorBy, GetActiveViewOrCreate,
                             GetColorTransferFunction, GetScalarBar,
                             OpenDataFile, Render, SaveScreenshot, Show,
                             Slice, Text, Threshold, Transform,
                             UpdatePipeline)

TITLES = {
    "longitudinal_strain": "longitudinal strain [-]",
    "axial_strain": "fibre axial strain [-]",
    "strain": "truss strain [-]",
    "I_tc": "I_tc (transverse compaction) [-]",
    "I_td": "I_td (transverse distortion) [-]",
    "I_e": "I_e (elongation) [-]",
    "fibre_id": "fibre number",
    "failed": "failed [0/1]",
}
# vtkGridAxesActor3D label mask bits (the edges whose labels are drawn).
MIN_X, MIN_Y, MIN_Z = 1, 2, 4
# ParaView's own fonts lack square brackets in this build: use DejaVu Sans.
FONT_FILE = "/usr/share/fonts/truetype/dejavu/DejaVuSans.ttf"
BLACK = [0.0, 0.0, 0.0]
WHITE = [1.0, 1.0, 1.0]


def nice_ticks(lo, hi, count=5):
    """Round tick values covering [lo, hi] (about count intervals)."""
    span = hi - lo
    if span <= 0:
        return [lo]
    raw = span / count
    magnitude = 10 ** math.floor(math.log10(raw))
    step = min((m * magnitude for m in (1, 2, 2.5, 5, 10)
                if m * magnitude >= raw), default=10 * magnitude)
    first = math.ceil(lo / step - 1e-9) * step
    ticks = []
    value = first
    while value <= hi + 1e-9 * step:
        ticks.append(0.0 if abs(value) < 1e-12 * step else value)
        value += step
    return ticks


def option(args, name, count=1, default=None):
    if name not in args:
        return default
    i = args.index(name)
    values = args[i + 1:i + 1 + count]
    del args[i:i + 1 + count]
    return values[0] if count == 1 else values


def set_font(proxy, prefix=""):
    """Use FONT_FILE for the text property prefix+FontFamily of proxy."""
    if os.path.exists(FONT_FILE):
        setattr(proxy, prefix + "FontFamily", "File")
        setattr(proxy, prefix + "FontFile", FONT_FILE)
    else:
        setattr(proxy, prefix + "FontFamily", "Arial")


def text(view, string, location, size):
    source = Text(Text=string)
    display = Show(source, view)
    display.Color = BLACK
    set_font(display)
    display.FontSize = size
    display.WindowLocation = location
    display.Bold = 0
    display.Shadow = 0
    return display


def scalar_bar(lut, view, title):
    """The colour bar of LUT in VIEW for print: TITLE, dark text in
    FONT_FILE, horizontal, labels %.3g; the caller places it."""
    bar = GetScalarBar(lut, view)
    bar.Title = title
    bar.ComponentTitle = ""
    bar.TitleColor = BLACK
    bar.LabelColor = BLACK
    bar.TitleFontSize = 22
    bar.LabelFontSize = 19
    set_font(bar, "Title")
    set_font(bar, "Label")
    bar.TitleBold = 0
    bar.LabelBold = 0
    bar.TitleShadow = 0
    bar.LabelShadow = 0
    bar.Orientation = "Horizontal"
    bar.LabelFormat = "%.3g"
    bar.AutomaticLabelFormat = 0
    bar.Visibility = 1
    return bar


def white_background(view):
    for prop, value in (("UseColorPaletteForBackground", 0),
                        ("BackgroundColorMode", "Single Color"),
                        ("Background", WHITE)):
        try:
            setattr(view, prop, value)
        except AttributeError:
            pass


def main(argv):
    args = list(argv)
    view_kind = option(args, "--view", default="side")
    y_scale = float(option(args, "--y-scale", default=1.0))
    z_scale = float(option(args, "--z-scale", default=1.0))
    value_range = option(args, "--range", count=2)
    title = option(args, "--title")
    x_section = option(args, "--x")
    keep_broken = "--keep-broken" in args
    if keep_broken:
        args.remove("--keep-broken")
    width = int(option(args, "--width", default=1600 if view_kind != "section"
                       else 1000))
    if len(args) < 4 or view_kind not in ("side", "top", "section"):
        sys.exit(__doc__)
    pvd, prefix, field = args[0], args[1], args[2]
    requested = [float(t) for t in args[3:]]
    if value_range:
        value_range = [float(v) for v in value_range]
    if title is None:
        title = TITLES.get(field, field)

    reader = OpenDataFile(pvd)
    available = list(getattr(reader, "TimestepValues", []) or [0.0])
    if not isinstance(available, list):
        available = [available]

    source = reader
    hidden, hidden_what = None, ""
    # Failed FE cells and broken DEM trusses are not drawn: they carry no
    # load, and a failed cell is left as a large distorted element.
    if reader.PointData.GetArray("failed") is not None:
        source = Threshold(Input=source)
        source.Scalars = ["POINTS", "failed"]
        source.LowerThreshold, source.UpperThreshold = -0.5, 0.5
        source.AllScalars = 1
        hidden, hidden_what = source, "failed cells not shown"
    elif reader.CellData.GetArray("broken") is not None and not keep_broken:
        source = Threshold(Input=source)
        source.Scalars = ["CELLS", "broken"]
        source.LowerThreshold, source.UpperThreshold = -0.5, 0.5
        hidden, hidden_what = source, "broken trusses not shown"
    # Everything is shown in mm; the exaggeration is part of the transform
    # and undone in the axis labels (AxesGrid.DataScale).
    mm = Transform(Input=source)
    mm.Transform.Scale = [1e3, 1e3 * y_scale, 1e3 * z_scale]
    source = mm
    if view_kind == "section":
        UpdatePipeline(time=available[0], proxy=reader)
        xmin, xmax = reader.GetDataInformation().GetBounds()[0:2]
        x0 = (float(x_section) if x_section is not None
              else xmin + 1e-3 * (xmax - xmin))
        source = Slice(Input=mm)
        source.SliceType = "Plane"
        source.SliceType.Origin = [1e3 * x0, 0.0, 0.0]
        source.SliceType.Normal = [1.0, 0.0, 0.0]
        try:
            source.Triangulatetheslice = 0
        except AttributeError:
            pass

    view = GetActiveViewOrCreate("RenderView")
    white_background(view)
    view.OrientationAxesVisibility = 0
    view.CameraParallelProjection = 1
    view.EnableRenderOnInteraction = 0

    display = Show(source, view)
    display.Representation = "Surface"
    if view_kind == "section" and reader.PointData.GetArray("failed") \
            is not None:  # FE: show the cells of the section
        display.Representation = "Surface With Edges"
        display.EdgeColor = [0.25, 0.25, 0.25]
    display.Ambient = 0.25
    display.Diffuse = 0.8
    display.Specular = 0.0
    if view_kind != "section":
        display.LineWidth = 1.0
    if reader.PointData.GetArray(field) is not None:
        ColorBy(display, ("POINTS", field))
    else:
        ColorBy(display, ("CELLS", field))
    lut = GetColorTransferFunction(field)
    lut.ApplyPreset("Turbo" if field != "I_tc" else "Cool to Warm", True)
    if field == "I_tc":
        lut.ApplyPreset("Cool to Warm", True)
    lut.AutomaticRescaleRangeMode = "Never"

    bar = scalar_bar(lut, view, title)
    bar.WindowLocation = "Any Location"
    bar.ScalarBarThickness = 18
    bar.ScalarBarLength = 0.42
    bar.DrawTickMarks = 1
    bar.AddRangeLabels = 0
    bar.UseCustomLabels = 1

    # Axes in mm with their true values.
    grid = view.AxesGrid
    grid.Visibility = 1
    grid.XTitle, grid.YTitle, grid.ZTitle = "x [mm]", "y [mm]", "z [mm]"
    grid.DataScale = [1.0, y_scale, z_scale]
    for axis in "XYZ":
        setattr(grid, axis + "TitleColor", BLACK)
        setattr(grid, axis + "LabelColor", BLACK)
        setattr(grid, axis + "TitleFontSize", 20)
        setattr(grid, axis + "LabelFontSize", 17)
        setattr(grid, axis + "TitleBold", 0)
        set_font(grid, axis + "Title")
        set_font(grid, axis + "Label")
    grid.GridColor = [0.55, 0.55, 0.55]
    grid.ShowGrid = 0
    grid.ShowEdges = 1

    # Screen axes (right, up) as data axes, and the camera.
    if view_kind == "side":
        screen, direction, up = (0, 1), [0, 0, -1], [0, 1, 0]
    elif view_kind == "top":
        screen, direction, up = (0, 2), [0, -1, 0], [0, 0, -1]
    else:
        screen, direction, up = (2, 1), [1, 0, 0], [0, 1, 0]
    depth = [i for i in range(3) if i not in screen][0]
    grid.AxesToLabel = (MIN_X, MIN_Y, MIN_Z)[screen[0]] | \
        (MIN_X, MIN_Y, MIN_Z)[screen[1]]

    notes = []
    if y_scale != 1.0:
        notes.append(f"deflection (y) exaggerated x{y_scale:g}")
    if z_scale != 1.0:
        notes.append(f"width (z) exaggerated x{z_scale:g}")
    if keep_broken and reader.CellData.GetArray("broken") is not None:
        notes.append("broken trusses drawn")
    if view_kind == "section":
        notes.append(f"section at x = {1e3 * x0:.3g} mm, seen along +x")
    time_label = text(view, "", "Upper Left Corner", 30)
    notes_label = text(view, "", "Upper Right Corner", 22)

    # Margins in pixels: top for the labels, bottom for the x axis labels and
    # the colour bar, left for the y axis labels.
    top, bottom, left, right = 80, 200, 160, 60
    min_height, max_height = (480, 1300) if view_kind != "section" \
        else (360, 1000)

    # paraview.simple resets the camera at a view's first Render(): do it
    # now, before the camera is placed.
    Render(view)
    for t_req in requested:
        t = min(available, key=lambda a: abs(a - t_req))
        if abs(t - t_req) > 0.5:
            print(f"render_yarn: {pvd} has no snapshot at {t_req:g} us "
                  f"(snapshots: {', '.join(f'{a:.4g}' for a in available)}); "
                  "skipped", flush=True)
            continue
        view.ViewTime = t
        UpdatePipeline(time=t, proxy=source)
        b = source.GetDataInformation().GetBounds()
        if b[0] > b[1]:
            print(f"render_yarn: nothing to show at {t:g} us; skipped",
                  flush=True)
            continue
        lo = [b[2 * i] for i in range(3)]
        hi = [b[2 * i + 1] for i in range(3)]
        w_d = max(hi[screen[0]] - lo[screen[0]], 1e-9)
        h_d = max(hi[screen[1]] - lo[screen[1]], 1e-9)
        # Pixels per mm: fill the width, then fit the height.
        s = (width - left - right) / w_d
        height = int(round(top + bottom + h_d * s))
        w = width
        if height > max_height:
            height = max_height
            s = (height - top - bottom) / h_d
            w = max(int(round(left + right + w_d * s)), min(width, 1000))
        height = max(height, min_height)
        view.ViewSize = [w, height]
        centre = [(lo[i] + hi[i]) / 2 for i in range(3)]
        grid.UseCustomBounds = 1
        grid.CustomBounds = list(b)
        # Where the data centre goes on the screen (pixels from the lower
        # left corner), and the focal point that puts it there.
        px = left + (w - left - right) / 2
        py = bottom + (height - top - bottom) / 2
        focal = list(centre)
        sign_right = 1.0
        sign_up = 1.0 if view_kind != "top" else -1.0
        focal[screen[0]] = centre[screen[0]] + sign_right * (w / 2 - px) / s
        focal[screen[1]] = centre[screen[1]] + sign_up * (height / 2 - py) / s
        distance = 10 * max(w_d, h_d, hi[depth] - lo[depth], 1.0)
        position = [focal[i] - distance * direction[i] for i in range(3)]
        view.CameraFocalPoint = focal
        view.CameraPosition = position
        view.CameraViewUp = up
        view.CameraParallelScale = height / (2 * s)

        if value_range:
            lo_v, hi_v = value_range
        else:
            data = source.PointData.GetArray(field) or \
                source.CellData.GetArray(field)
            lo_v, hi_v = data.GetRange()
            if field == "I_tc":  # diverging map centred on 0
                a = max(abs(lo_v), abs(hi_v), 1e-12)
                lo_v, hi_v = -a, a
            ticks = nice_ticks(lo_v, hi_v)
            step = ticks[1] - ticks[0] if len(ticks) > 1 else 1.0
            if ticks[0] > lo_v + 1e-9 * step:
                lo_v = ticks[0] - step
            if ticks[-1] < hi_v - 1e-9 * step:
                hi_v = ticks[-1] + step
        lut.RescaleTransferFunction(lo_v, hi_v)
        bar.CustomLabels = nice_ticks(lo_v, hi_v)
        bar.Position = [0.5 - bar.ScalarBarLength / 2, 12.0 / height]
        time_label.Input.Text = f"t = {t:.1f} \u00b5s"
        shown = list(notes)
        if hidden is not None:
            n_all = reader.GetDataInformation().GetNumberOfCells()
            n_shown = hidden.GetDataInformation().GetNumberOfCells()
            if n_shown < n_all:
                shown.append(hidden_what)
        notes_label.Input.Text = "\n".join(shown)
        Render(view)
        out = f"{prefix}_{t_req:g}us.png"
        SaveScreenshot(out, view, ImageResolution=[w, height],
                       TransparentBackground=0)
        print(f"render_yarn: {out} (t = {t:.4g} us)", flush=True)


if __name__ == "__main__":
    main(sys.argv[1:])
