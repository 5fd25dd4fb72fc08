#!/usr/bin/env python3
"""Render the last field of an `Experiment = flow` run to a PNG.

    xvfb-run -a /usr/bin/python3 doc/scripts/render_flow.py OUTPUT_DIRECTORY PICTURE.png

Top: the axial velocity on the mid-plane z = 0 of the capillary, with
velocity arrows along three cross-sections: the Poiseuille parabola.
Bottom: the plasma pressure on the same plane, falling linearly along the
capillary (pN/µm² = Pa, doc/design.md), from 0 at the outlet. Both colour
scales are viridis from 0. Needs python3-paraview and python3-matplotlib
(`scripts/install-packages.sh --docs`).
"""
import sys

import vtk

from rbc_ifem_run import Run
from vtk_picture import (actor, colour_map, label, legend, non_negative_range, parallel_camera,
                         save_png, scale_bar, solid_actor)

SIZE = (1000, 900)
VIEW, BAR = 0.4, 0.1  # heights of each view and of its colour bar, of the window's


def mid_plane_cut(field):
    plane = vtk.vtkPlane()
    plane.SetOrigin(0, 0, 1e-3)  # off the mesh faces that lie in z = 0
    plane.SetNormal(0, 0, 1)
    cut = vtk.vtkCutter()
    cut.SetInputData(field)
    cut.SetCutFunction(plane)
    cut.Update()
    return cut


def arrows(field, radius, top, xs=(5.0, 10.0, 15.0)):
    """Velocity arrows on lines across the capillary at XS, the longest
    (TOP) 4 µm long."""
    append = vtk.vtkAppendPolyData()
    arrow = vtk.vtkArrowSource()  # held here: VTK does not keep it alive
    arrow.SetTipRadius(0.06)
    arrow.SetShaftRadius(0.02)
    for x in xs:
        line = vtk.vtkLineSource()
        line.SetPoint1(x, -0.998 * radius, 1e-3)
        line.SetPoint2(x, 0.998 * radius, 1e-3)
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
        append.AddInputData(glyph.GetOutput())
    append.Update()
    return solid_actor(append, (0, 0, 0))


def view(bottom, length, radius):
    renderer = vtk.vtkRenderer()
    renderer.SetBackground(1, 1, 1)
    renderer.SetViewport(0, bottom, 1, bottom + VIEW)
    parallel_camera(renderer, (length / 2, 0, 0), (0, 0, -1), (0, 1, 0), 2 * radius + 3)
    return renderer


def main(directory, picture):
    run = Run(directory)
    time, file = run.series("flow.pvd")[-1]
    field = run.dataset(file)
    field.GetPointData().SetActiveVectors("velocity")
    length, radius = run.parameter("Capillary length"), run.parameter("Capillary radius")
    cut = mid_plane_cut(field)
    data = cut.GetOutput().GetPointData()

    _, top = non_negative_range(data.GetArray("velocity"), 0)
    speed = colour_map(0, top)
    upper = view(BAR + VIEW + BAR, length, radius)
    upper.AddActor(actor(cut, "velocity", (0, top), speed, component=0, flat=True))
    upper.AddActor(arrows(field, radius, top))
    label(upper, f"axial velocity u_x, t = {1e3 * time:g} ms, flow →", 0.02, 0.92)
    upper.ResetCameraClippingRange()
    scale_bar(upper, 5, SIZE, x=0.02, y=0.05)

    low, high = non_negative_range(data.GetArray("pressure"))
    pressure = colour_map(low, high)
    lower = view(BAR, length, radius)
    lower.AddActor(actor(cut, "pressure", (low, high), pressure, flat=True))
    label(lower, "plasma pressure p", 0.02, 0.92)
    lower.ResetCameraClippingRange()
    scale_bar(lower, 5, SIZE, x=0.02, y=0.05)

    save_png([upper, legend(speed, "axial velocity u_x [µm/s]", (0, BAR + VIEW, 1, 2 * BAR + VIEW), 0.6),
              lower, legend(pressure, "plasma pressure p [Pa]", (0, 0, 1, BAR), 0.6)],
             picture, SIZE)


if __name__ == "__main__":
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    main(sys.argv[1], sys.argv[2])
