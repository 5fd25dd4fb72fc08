#!/usr/bin/env python3
"""Render one DM instant of a run that solved the CO uptake (`Experiment =
diffusion`, or a flowing run's diffusion.pvd and diffusion_membranes.pvd)
to a PNG.

    xvfb-run -a /usr/bin/python3 doc/scripts/render_diffusion.py OUTPUT_DIRECTORY PICTURE.png [--time T]

T [s, as the .pvd files list it: 0.012 for 12 ms]: the DM instant to draw,
the one nearest T (within a tenth of the instants' spacing); a T farther
from every instant stops the script with the instants the run has. Without
it, the last instant (the only one, t = 0, of `Experiment = diffusion`). The script prints which instant it draws, and
the picture's title says it.

Left: the CO partial pressure P on the mid-plane z = 0 of the capillary,
wall and gas layer (P = P_A on the outside, 0 on the membranes), the
regions named and their borders drawn, the membranes outlined in white and
their inside grey. On cut cells (`Diffusion/Method = cut cell`) the mesh
cells inside a red cell have no unknowns and are not in diffusion.pvd;
the cut cells are drawn whole, so P's smooth continuation across the
membrane shows as a stair-stepped fringe inside the white outline.
Right: the membranes coloured by the CO flux density λ into each cell
(doc/diffusion.md), the paper's Fig. 4f. Both colour scales (viridis)
start at 0: P and λ are ≥ 0, their small negative values are undershoot
of the discretisation. Needs python3-paraview and python3-matplotlib
(`scripts/install-packages.sh --docs`).
"""
import argparse
import sys

import vtk

from rbc_ifem_run import Run
from vtk_picture import (FLUX_UNIT, actor, colour_map, label, legend, non_negative_range,
                         parallel_camera, save_png, scale_bar, smooth_surface, solid_actor,
                         world_label)

SIZE = (1600, 720)
LEGEND = 0.19  # of the window's height, under both views
TITLE = 0.06  # of the window's height, above both views
INSIDE = (0.72, 0.72, 0.72)  # the cells' inside, which the cut-cell solve leaves out


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


def inside_of(outline):
    """The regions the cut OUTLINE of the membranes encloses, filled grey a
    little behind the mid-plane: the field drawn over it hides it wherever
    the mesh has cells, so it shows where the solve has none."""
    fill = vtk.vtkContourTriangulator()
    fill.SetInputConnection(outline.GetOutputPort())
    behind = vtk.vtkTransform()
    behind.Translate(0, 0, -0.01)
    moved = vtk.vtkTransformPolyDataFilter()
    moved.SetInputConnection(fill.GetOutputPort())
    moved.SetTransform(behind)
    result = solid_actor(moved, INSIDE)
    result.GetProperty().LightingOff()
    result.held = (fill, behind, moved)  # VTK frees a filter whose Python object goes
    return result


def pressure_view(run, field, membranes, p_alveolar):
    length = run.parameter("Capillary length")
    lumen = run.parameter("Capillary radius")
    wall = lumen + run.parameter("Wall thickness")
    outside = wall + run.parameter("Gas layer thickness")
    colours = colour_map(0, p_alveolar)

    cut = vtk.vtkCutter()
    cut.SetInputData(field)
    cut.SetCutFunction(mid_plane())
    outline = vtk.vtkCutter()
    outline.SetInputData(membranes)
    outline.SetCutFunction(mid_plane())
    outline_actor = solid_actor(outline, (1, 1, 1), line_width=2)

    renderer = vtk.vtkRenderer()
    renderer.SetViewport(0, LEGEND, 0.5, 1 - TITLE)
    renderer.SetBackground(1, 1, 1)
    renderer.AddActor(actor(cut, "co_pressure", (0, p_alveolar), colours, flat=True))
    renderer.AddActor(inside_of(outline))
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
    colours = colour_map(low, high)
    renderer = vtk.vtkRenderer()
    renderer.SetViewport(0.5, LEGEND, 1, 1 - TITLE)
    renderer.SetBackground(1, 1, 1)
    renderer.AddActor(actor(smooth_surface(membranes), "co_flux", (low, high), colours))
    x0, x1, *_ = membranes.GetBounds()
    parallel_camera(renderer, ((x0 + x1) / 2, 0, 0), (18, -14, -22), (0, 1, 0), 14)
    scale_bar(renderer, 5, SIZE, x=0.72, y=0.04)
    bar = legend(colours, f"CO flux density λ into the cell [{FLUX_UNIT}], P_A = {p_alveolar:g} Torr",
                 (0.5, 0, 1, LEGEND), 0.7, "%.2g")
    return renderer, bar


def instant(run, wanted):
    """(time, membranes file, field file) of the DM instant nearest WANTED
    [s] (the last if None), and a phrase that says which it is. A WANTED
    farther from every instant than a tenth of their spacing is an error
    that lists them."""
    series = run.series("diffusion_membranes.pvd")
    fields = dict(run.series("diffusion.pvd"))
    times = [t for t, _ in series]
    listed = ", ".join(f"{t:g}" for t in times)
    if wanted is None:
        k = len(series) - 1
        which = ("the run's only DM instant" if k == 0
                 else f"the last of its {len(series)} DM instants")
    else:
        k = min(range(len(times)), key=lambda i: abs(times[i] - wanted))
        spacing = min((b - a for a, b in zip(times, times[1:])), default=0.0)
        if abs(times[k] - wanted) > max(0.1 * spacing, 1e-9 * max(1.0, abs(wanted))):
            sys.exit(f"no DM instant at t = {wanted:g} s in {run.directory}; "
                     f"its instants [s]: {listed}")
        which = f"DM instant {k + 1} of {len(series)}"
    time, membranes = series[k]
    if time not in fields:
        sys.exit(f"diffusion.pvd of {run.directory} has no t = {time:g} s; its instants [s]: "
                 + ", ".join(f"{t:g}" for t in fields))
    return time, membranes, fields[time], which


def main(directory, picture, wanted):
    run = Run(directory)
    time, membranes_file, field_file, which = instant(run, wanted)
    print(f"drawing t = {time:g} s ({1e3 * time:g} ms), {which}")
    field = run.dataset(field_file)
    membranes = run.dataset(membranes_file)
    p_alveolar = run.parameter("Alveolar pressure")
    left, left_bar = pressure_view(run, field, membranes, p_alveolar)
    right, right_bar = flux_view(membranes, p_alveolar)
    title = vtk.vtkRenderer()
    title.SetViewport(0, 1 - TITLE, 1, 1)
    title.SetBackground(1, 1, 1)
    label(title, f"{run.name}: t = {1e3 * time:g} ms, {which}", 0.01, 0.2)
    save_png([title, left, right, left_bar, right_bar], picture, SIZE)


if __name__ == "__main__":
    arguments = argparse.ArgumentParser(
        description=__doc__.split("\n\n")[0], usage=__doc__.split("\n\n")[1].strip())
    arguments.add_argument("directory")
    arguments.add_argument("picture")
    arguments.add_argument("--time", type=float, help="the DM instant [s] (default: the last)")
    given = arguments.parse_args()
    main(given.directory, given.picture, given.time)
