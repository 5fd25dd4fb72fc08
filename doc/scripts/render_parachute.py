#!/usr/bin/env python3
"""Render a red cell flowing in the capillary (`Experiment = flow` with
immersed cells) as it deforms into a parachute.

    xvfb-run -a /usr/bin/python3 doc/scripts/render_parachute.py OUTPUT_DIRECTORY PICTURE.png [N ...]

PICTURE: the shapes N of cell_0.pvd (default: the first, about one third, two
thirds and the last) seen from the side, the flow going to the right,
coloured by the magnitude of the membrane force per unit area,
|force_density| [pN/µm²]: the nodal force over the node's lumped area,
which unlike the nodal force (`force`, pN per node) does not shrink as the
membrane is refined (doc/outputs.md). One colour scale (viridis, from 0)
for all; every view has the same scale of length (the 5 µm bar), so the
sizes compare. If the run solved the CO diffusion, PICTURE_flux.png next
to it: the last membrane of diffusion_membranes.pvd seen obliquely from
behind, coloured by the CO flux density λ into the cell (doc/diffusion.md;
the scale starts at 0, λ's small negative values are undershoot), with
arrows of the flux -λn (the paper's Fig. 4f). Needs python3-paraview and
python3-matplotlib (`scripts/install-packages.sh --docs`).
"""
import os
import sys

import vtk

from rbc_ifem_run import Run
from vtk_picture import (FLUX_UNIT, actor, colour_map, label, legend, non_negative_range,
                         parallel_camera, save_png, scale_bar, smooth_surface)

# The membrane force per unit area [pN/µm²], mesh independent (Membrane::force_densities()).
FORCE = "force_density"


def render_shapes(run, picture, chosen):
    found = run.series("cell_0.pvd")
    n = len(found)
    chosen = chosen or sorted({0, n // 3, 2 * n // 3, n - 1})
    shapes = [(found[k][0], run.dataset(found[k][1])) for k in chosen]
    largest = max(s.GetPointData().GetArray(FORCE).GetMaxNorm() for _, s in shapes)
    colours = colour_map(0, largest, vector=True)
    # One scale for all: the largest shape fills 70 % of a view's height.
    size = max(max(b[1] - b[0], b[3] - b[2], b[5] - b[4])
               for b in (s.GetBounds() for _, s in shapes))
    window = (400 * len(shapes), 540)
    legend_height = 0.2

    renderers = []
    for k, (time, shape) in enumerate(shapes):
        renderer = vtk.vtkRenderer()
        renderer.SetBackground(1, 1, 1)
        renderer.SetViewport(k / len(shapes), legend_height, (k + 1) / len(shapes), 1)
        renderer.AddActor(actor(smooth_surface(shape), FORCE, (0, largest), colours))
        label(renderer, f"t = {1e3 * time:g} ms", 0.05, 0.9)
        # From -y, so x (the flow) runs to the right; centred on each shape,
        # the cells drift in the frame.
        parallel_camera(renderer, shape.GetCenter(), (0, 1, 0), (0, 0, 1), size / 0.7)
        renderers.append(renderer)
    scale_bar(renderers[0], 5, window, x=0.06, y=0.05)
    label(renderers[-1], "flow →", 0.95, 0.05, justify="right")

    bottom = legend(colours, "magnitude of the membrane force per unit area [pN/µm²]",
                    (0, 0, 1, legend_height), 0.5)
    save_png(renderers + [bottom], picture, window)


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


def render_flux(run, picture):
    time, file = run.series("diffusion_membranes.pvd")[-1]
    membrane = run.dataset(file)
    low, high = non_negative_range(membrane.GetPointData().GetArray("co_flux"))
    colours = colour_map(low, high)
    window = (900, 900)

    renderer = vtk.vtkRenderer()
    renderer.SetBackground(1, 1, 1)
    renderer.SetViewport(0, 0.16, 1, 1)
    renderer.AddActor(actor(smooth_surface(membrane), "co_flux", (low, high), colours))
    renderer.AddActor(flux_arrows(membrane, 0.9))
    label(renderer, f"t = {1e3 * time:g} ms, seen from behind, the flow away from the viewer",
          0.04, 0.93, size=18)
    parallel_camera(renderer, membrane.GetCenter(), (16, 12, -7), (0, 0, 1), 10)
    scale_bar(renderer, 2, window, x=0.06, y=0.04)

    p_alveolar = run.parameter("Alveolar pressure")
    bottom = legend(colours, f"CO flux density λ into the cell [{FLUX_UNIT}], P_A = {p_alveolar:g} Torr",
                    (0, 0, 1, 0.16), 0.7)
    save_png([renderer, bottom], picture, window)


def main(directory, picture, chosen):
    run = Run(directory)
    render_shapes(run, picture, chosen)
    if run.has("diffusion_membranes.pvd"):
        render_flux(run, os.path.splitext(picture)[0] + "_flux.png")


if __name__ == "__main__":
    if len(sys.argv) < 3:
        sys.exit(__doc__)
    main(sys.argv[1], sys.argv[2], [int(n) for n in sys.argv[3:]])
