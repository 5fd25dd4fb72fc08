#!/usr/bin/env python3
"""Render the output of an `Experiment = geometry` run to a PNG.

    xvfb-run -a /usr/bin/python3 doc/scripts/render_geometry.py OUTPUT_DIRECTORY PICTURE.png

Shows the membranes in the capillary, each cell in one colour, dark to
light in the order of their numbers (viridis: the colours tell the cells
apart, they measure nothing), the back half of the diffusion
mesh's vessel wall (red) and gas layer (blue), cut open, with its cells'
edges, and the fluid mesh's wall as a light wireframe. Needs python3-paraview,
python3-matplotlib and, without a display, a virtual X server
(`scripts/install-packages.sh --docs`).
"""
import sys

import vtk

from rbc_ifem_run import Run
from vtk_picture import (actor, colours_of, label, outer_surface, parallel_camera, pointer,
                         save_png, scale_bar, smooth_surface)

SIZE = (1200, 720)
MATERIALS = {1: ("vessel wall", (0.85, 0.55, 0.55)), 2: ("gas layer", (0.72, 0.82, 0.98))}


def back_half(data):
    """The cells of DATA in y > 0, whole."""
    back = vtk.vtkExtractGeometry()
    back.SetInputData(data)
    plane = vtk.vtkPlane()
    # Just below y = 0: a cell with a vertex at y = -1e-15 (round-off of
    # the mesh's circles) is in the back half too, not a hole in the picture.
    plane.SetOrigin(0, -1e-6, 0)
    plane.SetNormal(0, -1, 0)
    back.SetImplicitFunction(plane)
    back.ExtractInsideOn()
    back.ExtractBoundaryCellsOff()
    return back


def material(source, material_id, rgb):
    """The surface of the cells of SOURCE with MATERIAL_ID, in RGB, edges drawn."""
    only = vtk.vtkThreshold()
    only.SetInputConnection(source.GetOutputPort())
    only.SetInputArrayToProcess(0, 0, 0, vtk.vtkDataObject.FIELD_ASSOCIATION_POINTS, "material_id")
    only.SetLowerThreshold(material_id - 0.5)
    only.SetUpperThreshold(material_id + 0.5)
    only.SetAllScalars(True)
    result = actor(outer_surface(only))
    result.GetProperty().SetColor(*rgb)
    result.GetProperty().EdgeVisibilityOn()
    result.GetProperty().SetEdgeColor(0.45, 0.45, 0.45)
    return result, only


def main(directory, picture):
    run = Run(directory)
    renderer = vtk.vtkRenderer()
    renderer.SetBackground(1, 1, 1)

    membranes = run.dataset("membranes.vtu")
    n_cells = int(membranes.GetPointData().GetArray("cell").GetRange()[1]) + 1
    colours = vtk.vtkLookupTable()  # one entry per cell number
    colours.SetNumberOfTableValues(n_cells)
    colours.SetRange(-0.5, n_cells - 0.5)
    for k, rgb in enumerate(colours_of(n_cells)):
        colours.SetTableValue(k, *rgb, 1.0)
    colours.Build()
    renderer.AddActor(actor(smooth_surface(membranes), "cell", (-0.5, n_cells - 0.5), colours))

    back = back_half(run.dataset(run.series("diffusion_mesh.pvd")[0][1]))
    held = []
    for material_id, (_, rgb) in MATERIALS.items():
        tissue, threshold = material(back, material_id, rgb)
        held.append(threshold)
        renderer.AddActor(tissue)

    fluid_wall = back_half(run.dataset(run.series("fluid_mesh_boundary.pvd")[0][1]))
    lumen = actor(outer_surface(fluid_wall))
    lumen.GetProperty().SetRepresentationToWireframe()
    lumen.GetProperty().SetColor(0.3, 0.3, 0.6)
    lumen.GetProperty().SetOpacity(0.25)
    renderer.AddActor(lumen)

    length = run.parameter("Capillary length")
    radius = run.parameter("Capillary radius")
    wall = radius + run.parameter("Wall thickness")
    outside = wall + run.parameter("Gas layer thickness")
    parallel_camera(renderer, (length / 2, 0, 0), (24, 30, -13), (0, 0, 1), 2 * outside + 3)
    # Names, pointing at the bands of the cut face y = 0 and at the lumen's end.
    pointer(renderer, "gas layer", (0.8 * length, 0, (wall + outside) / 2), (120, 40), 19)
    pointer(renderer, "vessel wall", (0.95 * length, 0, (radius + wall) / 2), (120, 10), 19)
    pointer(renderer, "lumen wall (fluid mesh)", (length, 0.8 * radius, 0.6 * radius), (120, -20), 19)
    x0, x1, *_ = membranes.GetBounds()
    pointer(renderer, f"{n_cells} red cells", (x1 - 1.5, 0, -2.5), (150, -40), 19)
    scale_bar(renderer, 5, SIZE, x=0.05, y=0.06)
    label(renderer, "the back half (y > 0) of the diffusion mesh, cut open", 0.02, 0.95, size=17)
    save_png([renderer], picture, SIZE)


if __name__ == "__main__":
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    main(sys.argv[1], sys.argv[2])
