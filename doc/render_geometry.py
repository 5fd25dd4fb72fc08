#!/usr/bin/env python3
"""Render the output of an `Experiment = geometry` run to a PNG.

    xvfb-run -a python3 doc/render_geometry.py OUTPUT_DIRECTORY PICTURE.png

Shows the membranes (coloured by cell) in the capillary: the back half of the
diffusion mesh's vessel wall (red) and gas layer (blue), cut open, and the
fluid mesh's wall as a light wireframe. Needs python3-vtk9 and, without a
display, a virtual X server (`scripts/install-packages.sh --docs`).
"""
import sys

import vtk

from vtk_picture import actor, outer_surface, point_camera, read, save_png


def main(directory, picture):
    renderer = vtk.vtkRenderer()
    renderer.SetBackground(1, 1, 1)

    membranes = read(directory + "/membranes.vtu")
    n_cells = int(membranes.GetPointData().GetArray("cell").GetRange()[1]) + 1
    rainbow = vtk.vtkLookupTable()
    rainbow.SetHueRange(0.0, 0.7)
    rainbow.Build()
    renderer.AddActor(actor(outer_surface(membranes), "cell", (0, max(n_cells - 1, 1)), rainbow))

    # Back half (y > 0) of the wall and gas layer: whole cells, by material id.
    back = vtk.vtkExtractGeometry()
    back.SetInputData(read(directory + "/diffusion_mesh_0000.pvtu"))
    plane = vtk.vtkPlane()
    plane.SetNormal(0, -1, 0)
    back.SetImplicitFunction(plane)
    back.ExtractInsideOn()
    back.ExtractBoundaryCellsOff()
    tissue = vtk.vtkThreshold()
    tissue.SetInputConnection(back.GetOutputPort())
    tissue.SetInputArrayToProcess(0, 0, 0, vtk.vtkDataObject.FIELD_ASSOCIATION_POINTS, "material_id")
    tissue.SetLowerThreshold(0.5)
    tissue.SetUpperThreshold(2.5)
    materials = vtk.vtkLookupTable()
    materials.SetNumberOfTableValues(3)
    for material_id, rgb in enumerate([(1.0, 0.9, 0.9), (0.85, 0.55, 0.55), (0.75, 0.85, 1.0)]):
        materials.SetTableValue(material_id, *rgb, 1)
    materials.Build()
    tissue_actor = actor(outer_surface(tissue), "material_id", (0, 2), materials)
    tissue_actor.GetProperty().EdgeVisibilityOn()
    tissue_actor.GetProperty().SetEdgeColor(0.5, 0.5, 0.5)
    renderer.AddActor(tissue_actor)

    lumen = actor(outer_surface(read(directory + "/fluid_mesh_boundary.pvtu")))
    lumen.GetProperty().SetRepresentationToWireframe()
    lumen.GetProperty().SetColor(0.3, 0.3, 0.6)
    lumen.GetProperty().SetOpacity(0.25)
    renderer.AddActor(lumen)

    point_camera(renderer, focal_point=(10, 0, 0), position=(-14, -30, 13),
             view_up=(0, 0, 1), zoom=1.5)
    save_png([renderer], picture, size=(1200, 700))

if __name__ == "__main__":
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    main(sys.argv[1], sys.argv[2])
