#!/usr/bin/env python3
"""Render stretched cells of an `Experiment = stretching` run side by side.

    xvfb-run -a /usr/bin/python3 doc/render_stretch.py OUTPUT_DIRECTORY PICTURE.png [N ...]

Shows the equilibria N (default: the first, middle and last of stretch.pvd)
seen obliquely from above, the beads pulling along x, coloured by the
displacement from the reference shape. Needs python3-vtk9
(`scripts/install-packages.sh --docs`).
"""
import re
import sys

import vtk

from vtk_picture import actor, outer_surface, point_camera, read, save_png, scalar_bar


def equilibria(directory):
    """(force, file) of every entry of DIRECTORY/stretch.pvd."""
    with open(directory + "/stretch.pvd") as pvd:
        entries = re.findall(r'timestep="([^"]+)"[^>]*file="([^"]+)"', pvd.read())
    return [(float(force), directory + "/" + name) for force, name in entries]


def main(directory, picture, chosen):
    entries = equilibria(directory)
    if not chosen:
        chosen = [0, len(entries) // 2, len(entries) - 1]
    shapes = [(entries[k][0], read(entries[k][1])) for k in chosen]
    largest = max(s.GetPointData().GetArray("displacement").GetMaxNorm() for _, s in shapes)

    colours = vtk.vtkLookupTable()
    colours.SetHueRange(0.667, 0.0)
    colours.SetVectorModeToMagnitude()
    colours.SetRange(0, largest)
    colours.Build()

    renderers, keep = [], []
    for k, (force, shape) in enumerate(shapes):
        shape.GetPointData().SetActiveVectors("displacement")
        surface = outer_surface(shape)
        keep.append(surface)
        membrane = actor(surface, "displacement", (0, largest), colours)
        membrane.GetMapper().SetColorModeToMapScalars()
        membrane.GetMapper().GetLookupTable().SetVectorModeToMagnitude()
        renderer = vtk.vtkRenderer()
        renderer.SetBackground(1, 1, 1)
        renderer.SetViewport(k / len(shapes), 0.18, (k + 1) / len(shapes), 1)
        renderer.AddActor(membrane)
        label = vtk.vtkTextActor()
        label.SetInput(f"F = {force:g} pN")
        label.GetTextProperty().SetColor(0, 0, 0)
        label.GetTextProperty().SetFontSize(20)
        label.SetPosition(20, 20)
        renderer.AddActor2D(label)
        point_camera(renderer, (0, 0, 0), (0, -12, 16), (0, 0, 1), 1.0)
        renderers.append(renderer)
    # The same distance for every view, so that the sizes compare.
    for renderer in renderers[1:]:
        renderer.SetActiveCamera(renderers[-1].GetActiveCamera())
    renderers[0].SetActiveCamera(renderers[-1].GetActiveCamera())

    legend = vtk.vtkRenderer()
    legend.SetBackground(1, 1, 1)
    legend.SetViewport(0, 0, 1, 0.18)
    bar = scalar_bar(colours, "displacement [µm]", left=0.25, width=0.5)
    bar.SetPosition(0.25, 0.1)  # the legend's own viewport is low: use its height
    bar.SetHeight(0.8)
    legend.AddActor2D(bar)
    save_png(renderers + [legend], picture, (1200, 460))


if __name__ == "__main__":
    if len(sys.argv) < 3:
        sys.exit(__doc__)
    main(sys.argv[1], sys.argv[2], [int(n) for n in sys.argv[3:]])
