"""Show a flowing run (`Experiment = flow` with immersed cells) in ParaView
in the laboratory frame, over all its time steps.

    xvfb-run -a -s -noreset pvbatch doc/scripts/paraview_lab_frame.py RUN_DIR --save picture.png [--time T]
    xvfb-run -a -s -noreset pvbatch doc/scripts/paraview_lab_frame.py RUN_DIR --save movie.avi
    xvfb-run -a -s -noreset pvbatch doc/scripts/paraview_lab_frame.py RUN_DIR --save frames.png --all-steps
    pvbatch doc/scripts/paraview_lab_frame.py RUN_DIR --print-centres     (no X server needed)

RUN_DIR: a run's Output directory, with flow.pvd and cell_C.pvd. The run
writes its meshes in the frame that moves along x with the cells
(doc/outputs.md, Section 1); here each time step is moved by its own
FRAME_OFFSET [µm] (the field data of its VTU), by a Programmable Filter
that follows the animation time, so the cells travel along a capillary
that moves with them. Shown: the plasma on the mid-plane z = 0 coloured by
the magnitude of `lab_velocity` [µm/s] (viridis, one scale for all steps)
and every membrane of cell_*.pvd, seen from +z with the flow to the right.

--save FILE: a picture (.png, .jpg, .tif) at the last step, or at the step
nearest --time T [s]; a movie (.avi, .ogv) over all steps; with --all-steps
a picture per step, FILE's name with the step's number (frames.0000.png,
...). --print-centres prints `time,cell,lab_x_centre` for every step and
cell: the centre in x [µm] of the moved membrane's bounding box, in the
laboratory frame (cells.csv's `x` is the volume centroid). pvbatch has no
window: give --save or --print-centres (or both).

Needs ParaView with its Python modules and, without a display, a virtual X
server: `apt-get install paraview python3-paraview xvfb xauth
fonts-dejavu-core` (`scripts/install-packages.sh --docs`). pvpython runs
it the same way. Give Xvfb -noreset: without it Xvfb resets whenever its
last client disconnects, and about one pvbatch in ten aborted here with
"bad X server connection" (none in 55 runs with it).
"""
import argparse
import glob
import os
import re
import sys
import time

from paraview import simple as pv

HEIGHT = 600  # of the pictures [pixels]
FONT = "/usr/share/fonts/truetype/dejavu/DejaVuSans.ttf"  # VTK's own fonts have no µ (vtk_picture.py)
MOVIES = (".avi", ".ogv")
# The Programmable Filter's script: run at every update, at the animation's
# time, on that step's data set; its output is the input, moved.
LAB_FRAME = """
offset = inputs[0].FieldData["FRAME_OFFSET"][0]
output.ShallowCopy(inputs[0].VTKObject)
output.Points = inputs[0].Points + numpy.array([offset, 0.0, 0.0])
"""


def arguments():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0],
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("run", metavar="RUN_DIR", help="the run's Output directory")
    parser.add_argument("--save", metavar="FILE", help="the picture, movie or frames to write")
    parser.add_argument("--time", type=float, metavar="T", help="the time [s] of the picture")
    parser.add_argument("--all-steps", action="store_true", help="a picture per step")
    parser.add_argument("--print-centres", action="store_true",
                        help="print time,cell,lab_x_centre for every step and cell")
    options = parser.parse_args()
    if not options.save and not options.print_centres:
        parser.error("give --save FILE or --print-centres (pvbatch has no window)")
    if not os.path.exists(os.path.join(options.run, "flow.pvd")):
        parser.error(f"no flow.pvd in {options.run}: not a flowing run's Output directory")
    return options


def cell_series(run):
    """The run's cell_C.pvd files, by C."""
    found = glob.glob(os.path.join(run, "cell_*.pvd"))
    return sorted(found, key=lambda p: int(re.sub(r"\D", "", os.path.basename(p)) or 0))


def steps(reader):
    """The times [s] of the .pvd READER's steps (ParaView gives one step as
    a number)."""
    times = reader.TimestepValues
    return list(times) if hasattr(times, "__len__") else [times]


def lab_frame(source):
    """SOURCE moved by each step's FRAME_OFFSET along x."""
    moved = pv.ProgrammableFilter(Input=source)
    moved.Script = LAB_FRAME
    return moved


def mid_plane(flow):
    plane = pv.Slice(Input=flow)
    plane.SliceType = "Plane"
    plane.SliceType.Origin = [0.0, 0.0, 1e-3]  # off the mesh faces in z = 0
    plane.SliceType.Normal = [0.0, 0.0, 1.0]
    return plane


def speed_range(plane, times):
    """The range of |lab_velocity| on PLANE over all TIMES."""
    low, high = float("inf"), 0.0
    for t in times:
        plane.UpdatePipeline(t)
        speed = plane.PointData["lab_velocity"].GetRange(-1)
        low, high = min(low, speed[0]), max(high, speed[1])
    return low, high


def print_centres(cells, times):
    print("time,cell,lab_x_centre")
    for t in times:
        for c, cell in enumerate(cells):
            cell.UpdatePipeline(t)
            bounds = cell.GetDataInformation().GetBounds()
            print(f"{t:.10g},{c},{0.5 * (bounds[0] + bounds[1]):.10g}")
    sys.stdout.flush()


def use_font(proxy, *prefixes):
    for prefix in prefixes:
        setattr(proxy, prefix + "FontFamily", "File")
        setattr(proxy, prefix + "FontFile", FONT)
        setattr(proxy, prefix + "Color", [0.0, 0.0, 0.0])


def show_flow(view, plane, times):
    display = pv.Show(plane, view)
    pv.ColorBy(display, ("POINTS", "lab_velocity", "Magnitude"))
    colours = pv.GetColorTransferFunction("lab_velocity")
    colours.ApplyPreset("Viridis (matplotlib)", True)
    colours.RescaleTransferFunction(*speed_range(plane, times))
    colours.AutomaticRescaleRangeMode = "Never"
    bar = pv.GetScalarBar(colours, view)
    bar.Title, bar.ComponentTitle = "lab_velocity magnitude [µm/s]", ""
    bar.Orientation, bar.WindowLocation = "Horizontal", "Any Location"
    bar.Position, bar.ScalarBarLength = [0.5, 0.03], 0.45
    bar.RangeLabelFormat = "%.0f"
    use_font(bar, "Title", "Label")
    display.SetScalarBarVisibility(view, True)


def show_cells(view, cells):
    for cell in cells:
        display = pv.Show(cell, view)
        display.ColorArrayName = ["POINTS", ""]
        display.AmbientColor = display.DiffuseColor = [0.85, 0.15, 0.1]
        display.Specular = 0.3


def show_time(view, flow):
    """The time and the frame's offset of the step shown, bottom left."""
    text = pv.PythonAnnotation(Input=flow)
    text.ArrayAssociation = "Field Data"
    text.Expression = ('"t = %.3f ms, frame offset %.2f µm, flow →" '
                       '% (1e3 * t_value, FRAME_OFFSET[0])')
    display = pv.Show(text, view)
    display.WindowLocation = "Lower Left Corner"
    display.FontSize = 20
    use_font(display, "")


def place_camera(view, plane, times):
    """From +z, x to the right, over the plane's first and last place, with
    room below it for the colour bar and the time. Returns the picture's
    size: HEIGHT high, as wide as that takes (at most 4 times as wide)."""
    xs, ys = [], []
    for t in (times[0], times[-1]):
        plane.UpdatePipeline(t)
        bounds = plane.GetDataInformation().GetBounds()
        xs += bounds[0:2]
        ys += bounds[2:4]
    length, diameter = max(xs) - min(xs) + 2.0, max(ys) - min(ys)
    height = 1.35 * diameter  # 0.05 of it above the capillary, 0.3 below
    size = [min(4 * HEIGHT, max(HEIGHT, round(HEIGHT * length / height))), HEIGHT]
    centre = [0.5 * (min(xs) + max(xs)), 0.5 * (min(ys) + max(ys)) - 0.125 * diameter, 0.0]
    view.ViewSize = size
    view.CameraFocalPoint = centre
    view.CameraPosition = [centre[0], centre[1], 100.0]
    view.CameraViewUp = [0.0, 1.0, 0.0]
    view.CameraParallelProjection = 1
    view.CameraParallelScale = 0.5 * max(height, length * size[1] / size[0])
    return size


def nearest(times, wanted):
    """The step of TIMES nearest WANTED, the last if WANTED is None."""
    return times[-1] if wanted is None else min(times, key=lambda t: abs(t - wanted))


def written(path, start):
    """Whether PATH was written since START (ParaView reports success even
    when its writer could not open the file)."""
    return os.path.exists(path) and os.path.getmtime(path) >= start - 1.0


def save(view, size, options, times):
    scene = pv.GetAnimationScene()
    scene.UpdateAnimationUsingDataTimeSteps()
    scene.PlayMode = "Snap To TimeSteps"
    os.makedirs(os.path.dirname(os.path.abspath(options.save)), exist_ok=True)
    start = time.time()
    stem, extension = os.path.splitext(options.save)
    if extension.lower() in MOVIES or options.all_steps:
        pv.SaveAnimation(options.save, view, ImageResolution=size, FrameRate=5)
        first = options.save if extension.lower() in MOVIES else f"{stem}.0000{extension}"
        what = f"{len(times)} steps, t = {times[0]:g} to {times[-1]:g} s"
    else:
        first = options.save
        scene.AnimationTime = nearest(times, options.time)
        pv.SaveScreenshot(options.save, view, ImageResolution=size)
        what = f"t = {scene.AnimationTime:g} s"
    if not written(first, start):
        sys.exit(f"paraview_lab_frame: could not write {first}")
    print(f"wrote {options.save}: {what}")


def main():
    options = arguments()
    flow = pv.PVDReader(FileName=os.path.join(options.run, "flow.pvd"))
    times = steps(flow)
    cells = [lab_frame(pv.PVDReader(FileName=p)) for p in cell_series(options.run)]
    if options.print_centres:
        print_centres(cells, times)
    if not options.save:
        return
    view = pv.CreateView("RenderView")
    view.OrientationAxesVisibility = 0
    view.Background = [1.0, 1.0, 1.0]
    if hasattr(view, "UseColorPaletteForBackground"):
        view.UseColorPaletteForBackground = 0
    plane = mid_plane(lab_frame(flow))
    show_flow(view, plane, times)
    show_cells(view, cells)
    show_time(view, flow)
    size = place_camera(view, plane, times)
    save(view, size, options, times)


if __name__ == "__main__":
    # A Programmable Filter runs `from numpy import *` in __main__ at each
    # update, which would replace min, max, save, ... here: run this file's
    # functions from it imported as a module.
    sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
    import paraview_lab_frame
    paraview_lab_frame.main()
