"""Render snapshots of a yarn-impact run with ParaView (pvbatch).

Usage (a display is needed; xvfb-run provides one):
  xvfb-run -a pvbatch scripts/render_yarn.py RUN.pvd OUT_PREFIX FIELD T1 [T2 ...]
                      [--view side|top|section] [--y-scale S] [--range LO HI]

Writes OUT_PREFIX_<t>us.png for each time t (in us, the .pvd time unit),
colouring the yarn by FIELD (cell or point data, e.g. longitudinal_strain,
I_tc, axial_strain, fibre_id). side: looking along z (the transverse wave);
top: looking down y (the spreading of the width); section: the section at
x = 0, looking along x. The thin yarn is stretched by S along y in the side
view so that the deflection shows (default 1: true scale).
"""
import sys

from paraview.simple import (ColorBy, GetActiveViewOrCreate, GetAnimationScene,
                             GetColorTransferFunction, OpenDataFile, Render,
                             ResetCamera, SaveScreenshot, Show, Slice,
                             Transform, UpdatePipeline)


def main(argv):
    args = [a for a in argv]
    view_kind, y_scale, value_range = "side", 1.0, None
    if "--view" in args:
        i = args.index("--view")
        view_kind = args[i + 1]
        del args[i:i + 2]
    if "--y-scale" in args:
        i = args.index("--y-scale")
        y_scale = float(args[i + 1])
        del args[i:i + 2]
    if "--range" in args:
        i = args.index("--range")
        value_range = (float(args[i + 1]), float(args[i + 2]))
        del args[i:i + 3]
    if len(args) < 4:
        sys.exit(__doc__)
    pvd, prefix, field = args[0], args[1], args[2]
    times = [float(t) for t in args[3:]]

    reader = OpenDataFile(pvd)
    source = reader
    if view_kind == "section":
        source = Slice(Input=reader)
        source.SliceType.Origin = [0.0, 0.0, 0.0]
        source.SliceType.Normal = [1.0, 0.0, 0.0]
    if y_scale != 1.0:
        source = Transform(Input=source)
        source.Transform.Scale = [1.0, y_scale, 1.0]

    view = GetActiveViewOrCreate("RenderView")
    view.ViewSize = [1400, 500] if view_kind != "section" else [900, 500]
    view.OrientationAxesVisibility = 1
    display = Show(source, view)
    if reader.PointData.GetArray(field) is not None:
        ColorBy(display, ("POINTS", field))
    else:
        ColorBy(display, ("CELLS", field))
    display.SetScalarBarVisibility(view, True)
    lut = GetColorTransferFunction(field)
    if value_range:
        lut.RescaleTransferFunction(*value_range)

    camera = view.GetActiveCamera()
    if view_kind == "side":
        camera.SetPosition(0, 0, 1)
        camera.SetViewUp(0, 1, 0)
    elif view_kind == "top":
        camera.SetPosition(0, 1, 0)
        camera.SetViewUp(0, 0, -1)
    else:
        camera.SetPosition(1, 0, 0)
        camera.SetViewUp(0, 1, 0)
    camera.SetFocalPoint(0, 0, 0)

    scene = GetAnimationScene()
    scene.UpdateAnimationUsingDataTimeSteps()
    for t in times:
        scene.AnimationTime = t
        UpdatePipeline(time=t, proxy=source)
        if not value_range:
            display.RescaleTransferFunctionToDataRange(False, True)
        ResetCamera(view)
        Render(view)
        SaveScreenshot(f"{prefix}_{t:g}us.png", view,
                       ImageResolution=view.ViewSize)


if __name__ == "__main__":
    main(sys.argv[1:])
