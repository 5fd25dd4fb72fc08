#!/usr/bin/env python3
"""Render a red cell flowing in the capillary (`Experiment = flow` with
immersed cells) as it deforms into a parachute.

    xvfb-run -a /usr/bin/python3 doc/render_parachute.py OUTPUT_DIRECTORY PICTURE.png [N ...]

PICTURE: the shapes N of cell_0.pvd (default: the first, about one third, two
thirds and the last) seen from the side, the flow going to the right,
coloured by the membrane force; every view has the same camera distance, so
the sizes compare. If the run solved the CO diffusion, PICTURE_flux.png next
to it: the last membrane of diffusion_membranes.pvd seen obliquely from
behind, coloured by the CO flux into the cell, with arrows of the flux (the
paper's Fig. 4f). Needs python3-vtk9 (`scripts/install-packages.sh --docs`).
"""
import math
import os
import re
import sys

import vtk

from vtk_picture import actor, outer_surface, point_camera, read, save_png, scalar_bar

# VTK's own font has no →, no superscript minus and draws [ ] as ( ).
FONT = "/usr/share/fonts/truetype/dejavu/DejaVuSans.ttf"


def entries(directory, name):
    """(time [s], file) of every entry of DIRECTORY/NAME."""
    with open(directory + "/" + name) as pvd:
        found = re.findall(r'timestep="([^"]+)"[^>]*file="([^"]+)"', pvd.read())
    return [(float(time), directory + "/" + file) for time, file in found]


def smooth_surface(data):
    """The membrane DATA as one surface with smooth normals (deal.II writes
    the vertices of every cell separately)."""
    surface = outer_surface(data)  # held: VTK does not keep it until connected
    merged = vtk.vtkCleanPolyData()
    merged.SetInputConnection(surface.GetOutputPort())
    normals = vtk.vtkPolyDataNormals()
    normals.SetInputConnection(merged.GetOutputPort())
    normals.SplittingOff()
    return normals


def rainbow(low, high):
    colours = vtk.vtkLookupTable()
    colours.SetHueRange(0.667, 0.0)
    colours.SetRange(low, high)
    colours.Build()
    return colours


def use_font(*text_properties):
    for text in text_properties:
        text.SetFontFamily(vtk.VTK_FONT_FILE)
        text.SetFontFile(FONT)


def legend(colours, title, height, width, label_format="%-#6.3g"):
    """A renderer of the bottom HEIGHT of the picture holding a colour bar
    WIDTH wide."""
    bar = scalar_bar(colours, title, left=(1 - width) / 2, width=width)
    bar.SetLabelFormat(label_format)
    bar.SetPosition((1 - width) / 2, 0.1)  # in its own, low viewport: use its height
    bar.SetHeight(0.75)
    use_font(bar.GetTitleTextProperty(), bar.GetLabelTextProperty())
    renderer = vtk.vtkRenderer()
    renderer.SetBackground(1, 1, 1)
    renderer.SetViewport(0, 0, 1, height)
    renderer.AddActor2D(bar)
    return renderer


def label(renderer, text, x, y):
    """Black text at (X, Y) in the renderer's viewport, both from 0 to 1."""
    caption = vtk.vtkTextActor()
    caption.SetInput(text)
    caption.GetTextProperty().SetColor(0, 0, 0)
    caption.GetTextProperty().SetFontSize(24)
    use_font(caption.GetTextProperty())
    caption.GetPositionCoordinate().SetCoordinateSystemToNormalizedViewport()
    caption.SetPosition(x, y)
    renderer.AddActor2D(caption)


def render_shapes(directory, picture, chosen):
    found = entries(directory, "cell_0.pvd")
    n = len(found)
    chosen = chosen or sorted({0, n // 3, 2 * n // 3, n - 1})
    shapes = [(found[k][0], read(found[k][1])) for k in chosen]
    largest = max(s.GetPointData().GetArray("force").GetMaxNorm() for _, s in shapes)
    colours = rainbow(0, largest)
    colours.SetVectorModeToMagnitude()
    # One camera distance for all: the largest shape fills 70 % of a view's height.
    size = max(max(b[1] - b[0], b[3] - b[2], b[5] - b[4])
               for b in (s.GetBounds() for _, s in shapes))
    distance = size / 0.7 / (2 * math.tan(math.radians(15)))  # 30° view angle

    renderers = []
    for k, (time, shape) in enumerate(shapes):
        membrane = actor(smooth_surface(shape), "force", (0, largest), colours)
        membrane.GetMapper().SetColorModeToMapScalars()
        renderer = vtk.vtkRenderer()
        renderer.SetBackground(1, 1, 1)
        renderer.SetViewport(k / len(shapes), 0.18, (k + 1) / len(shapes), 1)
        renderer.AddActor(membrane)
        label(renderer, f"t = {1e3 * time:g} ms", 0.05, 0.9)
        x, y, z = shape.GetCenter()  # of the bounds: the cells drift in the frame
        camera = renderer.GetActiveCamera()  # from -y, so x runs to the right
        camera.SetFocalPoint(x, y, z)
        camera.SetPosition(x, y - distance, z)
        camera.SetViewUp(0, 0, 1)
        renderer.ResetCameraClippingRange()
        renderers.append(renderer)
    label(renderers[0], "flow →", 0.05, 0.04)

    bottom = legend(colours, "membrane force [pN]", 0.18, 0.5)
    save_png(renderers + [bottom], picture, (400 * len(shapes), 520))


def flux_arrows(membrane, length):
    """Arrows of co_flux_vector at about 120 points of the MEMBRANE, the
    largest LENGTH long, each ending on the membrane where the flux enters."""
    membrane.GetPointData().SetActiveVectors("co_flux_vector")
    surface = smooth_surface(membrane)
    surface.Update()
    mask = vtk.vtkMaskPoints()
    mask.SetInputConnection(surface.GetOutputPort())
    mask.SetOnRatio(max(1, surface.GetOutput().GetNumberOfPoints() // 120))
    mask.SetMaximumNumberOfPoints(surface.GetOutput().GetNumberOfPoints())
    arrow = vtk.vtkArrowSource()
    behind = vtk.vtkTransform()  # the arrow from -1 to 0 instead of 0 to 1
    behind.Translate(-1, 0, 0)
    moved = vtk.vtkTransformPolyDataFilter()
    moved.SetInputConnection(arrow.GetOutputPort())
    moved.SetTransform(behind)
    glyphs = vtk.vtkGlyph3D()
    glyphs.SetInputConnection(mask.GetOutputPort())
    glyphs.SetSourceConnection(moved.GetOutputPort())
    glyphs.SetVectorModeToUseVector()
    glyphs.SetScaleModeToScaleByVector()
    glyphs.SetScaleFactor(length / membrane.GetPointData().GetArray("co_flux_vector").GetMaxNorm())
    result = actor(glyphs)
    result.GetProperty().SetColor(0.15, 0.15, 0.15)
    return result


def render_flux(directory, picture):
    time, file = entries(directory, "diffusion_membranes.pvd")[-1]
    membrane = read(file)
    flux_range = membrane.GetPointData().GetArray("co_flux").GetRange()
    colours = rainbow(*flux_range)

    renderer = vtk.vtkRenderer()
    renderer.SetBackground(1, 1, 1)
    renderer.SetViewport(0, 0.16, 1, 1)
    renderer.AddActor(actor(smooth_surface(membrane), "co_flux", flux_range, colours))
    renderer.AddActor(flux_arrows(membrane, 0.9))
    label(renderer, f"t = {1e3 * time:g} ms", 0.04, 0.92)
    x, y, z = membrane.GetCenter()
    point_camera(renderer, (x, y, z), (x - 16, y - 12, z + 7), (0, 0, 1), 1.2)

    bottom = legend(colours, "CO flux into the cell [µm³ µm⁻² s⁻¹]", 0.16, 0.7, "%.3f")
    save_png([renderer, bottom], picture, (900, 900))


def main(directory, picture, chosen):
    render_shapes(directory, picture, chosen)
    if os.path.exists(directory + "/diffusion_membranes.pvd"):
        render_flux(directory, os.path.splitext(picture)[0] + "_flux.png")


if __name__ == "__main__":
    if len(sys.argv) < 3:
        sys.exit(__doc__)
    main(sys.argv[1], sys.argv[2], [int(n) for n in sys.argv[3:]])
