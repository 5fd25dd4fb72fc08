#!/usr/bin/env python3
"""Render an `Experiment = diffusion` run to a PNG.

    xvfb-run -a python3 doc/render_diffusion.py OUTPUT_DIRECTORY PICTURE.png

Left: the CO partial pressure P on the mid-plane z = 0 of the capillary,
wall and gas layer (P = P_A on the outside, 0 on the membranes). Right: the
membranes coloured by the CO flux density into each cell, the paper's
Fig. 4f. Needs python3-vtk9 (`scripts/install-packages.sh --docs`).
"""
import sys

import vtk

from vtk_picture import actor, outer_surface, point_camera, read, save_png, scalar_bar


def main(directory, picture):
    field = read(directory + "/diffusion_0000.pvtu")
    membranes = read(directory + "/diffusion_membranes_0000.vtu")
    pressure_range = field.GetPointData().GetArray("co_pressure").GetRange()
    flux_range = membranes.GetPointData().GetArray("co_flux").GetRange()

    rainbow = vtk.vtkLookupTable()
    rainbow.SetHueRange(0.667, 0.0)
    rainbow.Build()

    plane = vtk.vtkPlane()
    plane.SetOrigin(0, 0, 1e-3)  # off the mesh faces that lie in z = 0
    plane.SetNormal(0, 0, 1)
    cut = vtk.vtkCutter()
    cut.SetInputData(field)
    cut.SetCutFunction(plane)
    membrane_source = vtk.vtkTrivialProducer()  # held: VTK does not keep it
    membrane_source.SetOutput(membranes)
    outline = vtk.vtkCutter()
    outline.SetInputConnection(membrane_source.GetOutputPort())
    outline.SetCutFunction(plane)
    outline_mapper = vtk.vtkPolyDataMapper()
    outline_mapper.SetInputConnection(outline.GetOutputPort())
    outline_mapper.ScalarVisibilityOff()
    outline_actor = vtk.vtkActor()
    outline_actor.SetMapper(outline_mapper)
    outline_actor.GetProperty().SetColor(1, 1, 1)
    outline_actor.GetProperty().SetLineWidth(2)

    left = vtk.vtkRenderer()
    left.SetViewport(0, 0, 0.5, 1)
    left.SetBackground(1, 1, 1)
    left.AddActor(actor(cut, "co_pressure", pressure_range, rainbow))
    left.AddActor(outline_actor)
    left.AddActor2D(scalar_bar(rainbow, "CO partial pressure P [Torr]"))

    right = vtk.vtkRenderer()
    right.SetViewport(0.5, 0, 1, 1)
    right.SetBackground(1, 1, 1)
    right.AddActor(actor(outer_surface(membranes), "co_flux", flux_range, rainbow))
    right.AddActor2D(scalar_bar(rainbow, "CO flux density into the cell [µm/s] at P_A = 1 Torr"))

    point_camera(left, focal_point=(10, 0, 0), position=(10, 0, 60), view_up=(0, 1, 0), zoom=1.25)
    point_camera(right, focal_point=(10, 0, 0), position=(-8, 14, 22), view_up=(0, 1, 0), zoom=1.15)
    save_png([left, right], picture, size=(1600, 560))


if __name__ == "__main__":
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    main(sys.argv[1], sys.argv[2])
