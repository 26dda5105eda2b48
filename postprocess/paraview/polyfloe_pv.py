"""What PolyFloe's ParaView scripts share: arguments, reading a results folder, a top view, colour maps on a fixed
range, pictures, animations and state files. Runs inside ParaView's Python (pvbatch or pvpython; headless:
`bash scripts/pvbatch.sh SCRIPT.py ...`), never in /usr/bin/python3.

Every script takes a results folder (what `polyfloe run -o DIR` wrote) and writes into -o OUT (default
RESULTS/paraview): NAME.png at the chosen time, NAME.pvsm (the pipeline as a ParaView state file: File > Load
State, "Search files under specified directory" pointing at any results folder of the same kind), and with
--animation NAME_frames/NAME.NNNN.png, one per frame, and NAME.avi where ParaView has its FFMPEG writer.
"""
import argparse
import math
import os
import sys

from paraview import servermanager
import paraview.simple as pv

# The look shared by every picture: white background, dark text.
TEXT = [0.1, 0.1, 0.1]
WALL = [0.35, 0.35, 0.35]
ICE = [0.93, 0.95, 0.97]


def fail(script, message):
    """Stops with a message naming the script and what to do (exit 2: bad input)."""
    sys.stderr.write(f"{script}: {message}\n")
    sys.exit(2)


def arguments(script, description, time_help="the picture's time [s] (default: the last frame)", extra=None):
    """The shared command line; `extra(parser)` adds a script's own options."""
    ap = argparse.ArgumentParser(prog=script, description=description)
    ap.add_argument("results", help="a results folder (polyfloe run -o DIR)")
    ap.add_argument("-o", "--output", help="where the pictures go (default: RESULTS/paraview)")
    ap.add_argument("-t", "--time", type=float, help=time_help)
    ap.add_argument("--size", type=int, nargs=2, default=[1600, 900], metavar=("W", "H"),
                    help="picture size in pixels (default 1600 900)")
    ap.add_argument("--animation", action="store_true",
                    help="also every frame as PNG (NAME_frames/) and, where ParaView can encode it, NAME.avi")
    ap.add_argument("--name", help="the pictures' base name (default: the script's)")
    if extra:
        extra(ap)
    a = ap.parse_args()
    if not os.path.isdir(a.results):
        fail(script, f"{a.results} is not a folder (a results folder: polyfloe run SCENE -o DIR)")
    if a.size[0] < 16 or a.size[1] < 16 or a.size[0] > 8192 or a.size[1] > 8192:
        fail(script, f"--size {a.size[0]} {a.size[1]}: each side must be 16 to 8192 pixels")
    a.output = a.output or os.path.join(a.results, "paraview")
    os.makedirs(a.output, exist_ok=True)
    return a


def open_series(script, results, name, what):
    """A .pvd series of the results folder as a reader named `name`; exits naming the file when it is missing."""
    path = os.path.join(results, name + ".pvd")
    if not os.path.isfile(path):
        fail(script, f"{path} not found: {what}")
    reader = pv.PVDReader(registrationName=name, FileName=os.path.abspath(path))
    reader.UpdatePipelineInformation()
    return reader


def times(source):
    """The frame times of a reader, or of the reader a filter reads from."""
    while not hasattr(source, "TimestepValues") or source.GetProperty("TimestepValues") is None:
        source = source.Input
    ts = source.TimestepValues
    return list(ts) if isinstance(ts, (list, tuple)) or hasattr(ts, "__len__") else [ts]


def pick_time(script, reader, wanted):
    """The frame time to draw: `wanted` when it is a frame time (to 1e-9 of the interval), else exits listing the
    frames; the last frame when `wanted` is None."""
    ts = times(reader)
    if wanted is None:
        return ts[-1]
    step = (ts[-1] - ts[0]) / max(len(ts) - 1, 1) or 1.0
    for t in ts:
        if abs(t - wanted) <= 1e-9 * step:
            return t
    fail(script, f"--time {wanted:g}: no frame at that time; the frames are at {ts[0]:g} ... {ts[-1]:g} s "
                 f"({len(ts)} frames, every {step:g} s)")


def go_to(t):
    """Sets the animation to time t (so that the displays made next see that frame's arrays)."""
    scene = pv.GetAnimationScene()
    scene.UpdateAnimationUsingDataTimeSteps()
    scene.AnimationTime = t


def array_range(source, association, array, component=-1):
    """(lo, hi) of an array over every frame of a series (NaN ignored), or None when no frame has a value: a
    colour range fixed over the run, so that a frame's colour means the same speed in every frame."""
    lo, hi = math.inf, -math.inf
    for t in times(source):
        source.UpdatePipeline(t)
        info = source.GetDataInformation().DataInformation
        data = info.GetPointDataInformation() if association == "POINTS" else info.GetCellDataInformation()
        a = data.GetArrayInformation(array)
        if a is None:
            continue
        r = a.GetComponentRange(component)
        if r[0] <= r[1] and math.isfinite(r[0]) and math.isfinite(r[1]):
            lo, hi = min(lo, r[0]), max(hi, r[1])
    return (lo, hi) if lo <= hi else None


def values(source, association, array, t):
    """The values of a scalar array at time t, as a list (small series: contacts of one frame)."""
    source.UpdatePipeline(t)
    data = servermanager.Fetch(source)
    out = []
    blocks = [data]
    if data.IsA("vtkMultiBlockDataSet"):
        blocks = [data.GetBlock(i) for i in range(data.GetNumberOfBlocks())]
    for b in blocks:
        if b is None:
            continue
        fields = b.GetPointData() if association == "POINTS" else b.GetCellData()
        a = fields.GetArray(array)
        if a is not None:
            out += [a.GetTuple1(i) for i in range(a.GetNumberOfTuples())]
    return out


def view(size):
    """A render view looking down on the sea surface (x right, y up), parallel projection, white background."""
    v = pv.CreateView("RenderView")
    v.ViewSize = list(size)
    v.OrientationAxesVisibility = 0
    v.UseColorPaletteForBackground = 0
    v.Background = [1.0, 1.0, 1.0]
    v.CameraParallelProjection = 1
    pv.SetActiveView(v)
    return v


def look_down(v, bounds, margin=0.06):
    """Fits the view onto the x-y extent `bounds` (xmin, xmax, ymin, ymax, ...) seen from above, leaving a band at
    the bottom for the colour legend."""
    cx, cy = 0.5 * (bounds[0] + bounds[1]), 0.5 * (bounds[2] + bounds[3])
    w, h = bounds[1] - bounds[0], bounds[3] - bounds[2]
    aspect = v.ViewSize[0] / v.ViewSize[1]
    v.CameraFocalPoint = [cx, cy, 0.0]
    v.CameraPosition = [cx, cy, 10.0 * max(w, h, 1.0)]
    v.CameraViewUp = [0.0, 1.0, 0.0]
    band = 0.14  # the bottom of the view, for the colour legend
    scale = 0.5 * (1.0 + 2.0 * margin) * max(h / (1.0 - band), w / aspect)
    v.CameraParallelScale = scale
    v.CameraFocalPoint = [cx, cy - scale * band, 0.0]
    v.CameraPosition = [cx, cy - scale * band, 10.0 * max(w, h, 1.0)]


def bounds_over_run(source):
    """The x-y box that holds the source in every frame."""
    b = [math.inf, -math.inf, math.inf, -math.inf]
    for t in times(source):
        source.UpdatePipeline(t)
        bb = source.GetDataInformation().GetBounds()
        if bb[0] <= bb[1]:
            b = [min(b[0], bb[0]), max(b[1], bb[1]), min(b[2], bb[2]), max(b[3], bb[3])]
    return b if b[0] <= b[1] else [0.0, 1.0, 0.0, 1.0]


def colour(display, v, association, array, rng, preset, title, log=False, invert=False):
    """Colours `display` by `array` on the fixed range `rng` (never rescaled by ParaView as time plays), with a
    colour legend titled `title`."""
    pv.ColorBy(display, (association, array))
    lut = pv.GetColorTransferFunction(array)
    lut.ApplyPreset(preset, True)
    if invert:
        lut.InvertTransferFunction()
    lut.AutomaticRescaleRangeMode = "Never"
    lo, hi = rng
    if log:
        lo = max(lo, hi * 1e-6)
    lut.RescaleTransferFunction(lo, hi)
    pv.GetOpacityTransferFunction(array).RescaleTransferFunction(lo, hi)
    if log:
        lut.MapControlPointsToLogSpace()
        lut.UseLogScale = 1
    display.SetScalarBarVisibility(v, True)
    bar = pv.GetScalarBar(lut, v)
    bar.Title = title
    bar.ComponentTitle = ""
    bar.TitleColor = TEXT
    bar.LabelColor = TEXT
    bar.TitleFontSize = 18
    bar.LabelFontSize = 16
    bar.WindowLocation = "Lower Center"
    bar.Orientation = "Horizontal"
    bar.ScalarBarLength = 0.5
    bar.RangeLabelFormat = "%-#.3g"
    return lut


def solid(display, rgb, edges=False):
    display.ColorArrayName = ["POINTS", ""]
    display.AmbientColor = rgb
    display.DiffuseColor = rgb
    if edges:
        display.SetRepresentationType("Surface With Edges")
        display.EdgeColor = [0.2, 0.2, 0.2]


def flat(display):
    """No shading: a map seen from above keeps its colours (the light would darken the prisms' top faces)."""
    display.Interpolation = "Flat"
    display.Ambient = 1.0
    display.Diffuse = 0.0
    display.Specular = 0.0


def by_motion(reader, name, motions):
    """The cells of the floes series whose `motion` (0 dynamic, 1 fixed, 2 kinematic) is one of `motions`."""
    lo, hi = min(motions), max(motions)
    return pv.Threshold(registrationName=name, Input=reader, Scalars=["CELLS", "motion"], LowerThreshold=lo,
                        UpperThreshold=hi, ThresholdMethod="Between")


def time_label(v, fmt="t = {time:.1f} s"):
    label = pv.AnnotateTime(registrationName="time label")
    label.Format = fmt
    d = pv.Show(label, v)
    d.Color = TEXT
    d.FontSize = 22
    d.WindowLocation = "Upper Left Corner"
    return label


def title(v, text):
    t = pv.Text(registrationName="title", Text=text)
    d = pv.Show(t, v)
    d.Color = TEXT
    d.FontSize = 22
    d.WindowLocation = "Upper Center"
    return t


def save(script, v, args, name, t, all_times, cameras):
    """NAME.png of the view or layout `v` at time t, NAME.pvsm, and with --animation the frames and a movie.
    `cameras`: (view, x-y box) pairs, each view fitted onto its box once the layout has its size. Prints what it
    wrote."""
    scene = pv.GetAnimationScene()
    scene.UpdateAnimationUsingDataTimeSteps()
    scene.AnimationTime = t
    if hasattr(v, "SetSize"):
        v.SetSize(args.size[0], args.size[1])
    pv.RenderAllViews()
    for view_, box in cameras:
        look_down(view_, box)
    pv.RenderAllViews()
    png = os.path.join(args.output, name + ".png")
    pv.SaveScreenshot(png, v, ImageResolution=list(args.size), TransparentBackground=0)
    written = [png]
    state = os.path.join(args.output, name + ".pvsm")
    pv.SaveState(state)
    written.append(state)
    if args.animation:
        frames = os.path.join(args.output, name + "_frames")
        os.makedirs(frames, exist_ok=True)
        for old in os.listdir(frames):
            if old.startswith(name + ".") and old.endswith(".png"):
                os.remove(os.path.join(frames, old))
        pv.SaveAnimation(os.path.join(frames, name + ".png"), v, ImageResolution=list(args.size),
                         FrameWindow=[0, len(all_times) - 1])
        written.append(frames + f"/ ({len(all_times)} frames)")
        movie = os.path.join(args.output, name + ".avi")
        try:
            pv.SaveAnimation(movie, v, ImageResolution=[args.size[0] // 2 * 2, args.size[1] // 2 * 2],
                             FrameRate=10, FrameWindow=[0, len(all_times) - 1])
            if os.path.isfile(movie) and os.path.getsize(movie) > 0:
                written.append(movie)
        except Exception as e:  # no encoder in this ParaView: the PNG frames are the animation
            sys.stderr.write(f"{script}: no movie ({e}); the frames are in {frames}\n")
        scene.AnimationTime = t
    for w in written:
        print(f"{script}: wrote {w}")
