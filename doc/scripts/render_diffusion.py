#!/usr/bin/env python3
"""Render an `Experiment = diffusion` run to a PNG.

    xvfb-run -a /usr/bin/python3 doc/scripts/render_diffusion.py OUTPUT_DIRECTORY PICTURE.png

Left: the CO partial pressure P on the mid-plane z = 0 of the capillary,
wall and gas layer (P = P_A on the outside, 0 on the membranes), the
regions named and their borders drawn, the membranes outlined in white.
Right: the membranes coloured by the CO flux density λ into each cell
(doc/diffusion.md), the paper's Fig. 4f. Both colour scales start at 0:
P and λ are ≥ 0, their small negative values are undershoot of the
discretisation. Needs python3-vtk9 (`scripts/install-packages.sh --docs`).
"""
import sys

import vtk

from rbc_ifem_run import Run
from vtk_picture import (FLUX_UNIT, actor, solid_actor, legend, non_negative_range, parallel_camera,
                         rainbow, save_png, scale_bar, smooth_surface, world_label)

SIZE = (1600, 680)
LEGEND = 0.2  # of the window's height, under both views


def mid_plane():
    plane = vtk.vtkPlane()
    plane.SetOrigin(0, 0, 1e-3)  # off the mesh faces that lie in z = 0
    plane.SetNormal(0, 0, 1)
    return plane


def lines(segments, colour, width):
    """An actor of straight SEGMENTS ((x, y, z), (x, y, z)) in the scene."""
    points, cells = vtk.vtkPoints(), vtk.vtkCellArray()
    for a, b in segments:
        cells.InsertNextCell(2)
        cells.InsertCellPoint(points.InsertNextPoint(*a))
        cells.InsertCellPoint(points.InsertNextPoint(*b))
    data = vtk.vtkPolyData()
    data.SetPoints(points)
    data.SetLines(cells)
    mapper = vtk.vtkPolyDataMapper()
    mapper.SetInputData(data)
    result = vtk.vtkActor()
    result.SetMapper(mapper)
    result.GetProperty().SetColor(*colour)
    result.GetProperty().SetLineWidth(width)
    return result


def pressure_view(run, field, membranes, p_alveolar):
    length = run.parameter("Capillary length")
    lumen = run.parameter("Capillary radius")
    wall = lumen + run.parameter("Wall thickness")
    outside = wall + run.parameter("Gas layer thickness")
    colours = rainbow(0, p_alveolar)

    cut = vtk.vtkCutter()
    cut.SetInputData(field)
    cut.SetCutFunction(mid_plane())
    outline = vtk.vtkCutter()
    outline.SetInputData(membranes)
    outline.SetCutFunction(mid_plane())
    outline_actor = solid_actor(outline, (1, 1, 1), line_width=2)

    renderer = vtk.vtkRenderer()
    renderer.SetViewport(0, LEGEND, 0.5, 1)
    renderer.SetBackground(1, 1, 1)
    renderer.AddActor(actor(cut, "co_pressure", (0, p_alveolar), colours, flat=True))
    renderer.AddActor(outline_actor)
    # The borders of lumen, wall and gas layer, and names beside them.
    z = 0.01
    renderer.AddActor(lines([((0, s * r, z), (length, s * r, z)) for s in (-1, 1) for r in (lumen, wall)],
                            (0.15, 0.15, 0.15), 1.5))
    for s in (-1, 1):
        world_label(renderer, "gas layer", (length + 0.5, s * (wall + outside) / 2, z), 18, "left")
        world_label(renderer, "vessel wall", (length + 0.5, s * (lumen + wall) / 2, z), 18, "left")
    world_label(renderer, "plasma and", (length + 0.5, 0.7, z), 18, "left")
    world_label(renderer, "red cells", (length + 0.5, -0.7, z), 18, "left")
    parallel_camera(renderer, (length / 2 + 3.6, 0, 0), (0, 0, -1), (0, 1, 0), 2 * outside + 2)
    scale_bar(renderer, 5, SIZE, x=0.78, y=0.04)
    bar = legend(colours, "CO partial pressure P [Torr]", (0, 0, 0.5, LEGEND), 0.7, "%.2g")
    return renderer, bar


def flux_view(membranes, p_alveolar):
    low, high = non_negative_range(membranes.GetPointData().GetArray("co_flux"))
    colours = rainbow(low, high)
    renderer = vtk.vtkRenderer()
    renderer.SetViewport(0.5, LEGEND, 1, 1)
    renderer.SetBackground(1, 1, 1)
    renderer.AddActor(actor(smooth_surface(membranes), "co_flux", (low, high), colours))
    x0, x1, *_ = membranes.GetBounds()
    parallel_camera(renderer, ((x0 + x1) / 2, 0, 0), (18, -14, -22), (0, 1, 0), 14)
    scale_bar(renderer, 5, SIZE, x=0.72, y=0.04)
    bar = legend(colours, f"CO flux density λ into the cell [{FLUX_UNIT}], P_A = {p_alveolar:g} Torr",
                 (0.5, 0, 1, LEGEND), 0.7, "%.2g")
    return renderer, bar


def main(directory, picture):
    run = Run(directory)
    field = run.dataset(run.series("diffusion.pvd")[0][1])
    membranes = run.dataset(run.series("diffusion_membranes.pvd")[0][1])
    p_alveolar = run.parameter("Alveolar pressure")
    left, left_bar = pressure_view(run, field, membranes, p_alveolar)
    right, right_bar = flux_view(membranes, p_alveolar)
    save_png([left, right, left_bar, right_bar], picture, SIZE)


if __name__ == "__main__":
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    main(sys.argv[1], sys.argv[2])
