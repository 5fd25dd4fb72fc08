#!/usr/bin/env python3
"""Render the last field of an `Experiment = flow` run to a PNG.

    xvfb-run -a python3 doc/render_flow.py OUTPUT_DIRECTORY PICTURE.png

Shows the axial velocity on the mid-plane z = 0 of the capillary, with
velocity arrows along three cross-sections: the Poiseuille parabola. Needs
python3-vtk9 (`scripts/install-packages.sh --docs`).
"""
import re
import sys

import vtk

from vtk_picture import point_camera, read, save_png, scalar_bar


def last_field(directory):
    """The file of the last entry of DIRECTORY/flow.pvd."""
    with open(directory + "/flow.pvd") as pvd:
        files = re.findall(r'file="([^"]+)"', pvd.read())
    return directory + "/" + files[-1]


def main(directory, picture):
    field = read(last_field(directory))
    field.GetPointData().SetActiveVectors("velocity")

    plane = vtk.vtkPlane()
    plane.SetOrigin(0, 0, 1e-3)  # off the mesh faces that lie in z = 0
    plane.SetNormal(0, 0, 1)
    cut = vtk.vtkCutter()
    cut.SetInputData(field)
    cut.SetCutFunction(plane)

    cut.Update()
    top = cut.GetOutput().GetPointData().GetArray("velocity").GetRange(0)[1]

    colours = vtk.vtkLookupTable()
    colours.SetHueRange(0.667, 0.0)
    colours.Build()
    mapper = vtk.vtkDataSetMapper()
    mapper.SetInputConnection(cut.GetOutputPort())
    mapper.SetScalarModeToUsePointFieldData()
    mapper.ColorByArrayComponent("velocity", 0)
    mapper.SetScalarRange(0, top)
    mapper.SetLookupTable(colours)
    plane_actor = vtk.vtkActor()
    plane_actor.SetMapper(mapper)

    # Arrows on three lines across the capillary, at x = 5, 10, 15 µm.
    arrows = vtk.vtkAppendPolyData()
    arrow = vtk.vtkArrowSource()  # held here: VTK does not keep it alive
    arrow.SetTipRadius(0.06)
    arrow.SetShaftRadius(0.02)
    for x in (5.0, 10.0, 15.0):
        line = vtk.vtkLineSource()
        line.SetPoint1(x, -4.99, 1e-3)
        line.SetPoint2(x, 4.99, 1e-3)
        line.SetResolution(12)
        probe = vtk.vtkProbeFilter()
        probe.SetInputConnection(line.GetOutputPort())
        probe.SetSourceData(field)
        probe.Update()
        probe.GetOutput().GetPointData().SetActiveVectors("velocity")
        glyph = vtk.vtkGlyph3D()
        glyph.SetInputData(probe.GetOutput())
        glyph.SetSourceConnection(arrow.GetOutputPort())
        glyph.SetVectorModeToUseVector()
        glyph.SetScaleModeToScaleByVector()
        glyph.SetScaleFactor(4.0 / top)
        glyph.Update()
        arrows.AddInputData(glyph.GetOutput())
    arrow_mapper = vtk.vtkPolyDataMapper()
    arrow_mapper.SetInputConnection(arrows.GetOutputPort())
    arrow_mapper.ScalarVisibilityOff()
    arrow_actor = vtk.vtkActor()
    arrow_actor.SetMapper(arrow_mapper)
    arrow_actor.GetProperty().SetColor(0, 0, 0)

    renderer = vtk.vtkRenderer()
    renderer.SetBackground(1, 1, 1)
    renderer.AddActor(plane_actor)
    renderer.AddActor(arrow_actor)
    renderer.AddActor2D(scalar_bar(colours, "axial velocity [µm/s]", left=0.25, width=0.5))
    point_camera(renderer, focal_point=(10, 0, 0), position=(10, 0, 50),
             view_up=(0, 1, 0), zoom=1.3)
    save_png([renderer], picture, size=(1200, 600))

if __name__ == "__main__":
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    main(sys.argv[1], sys.argv[2])
