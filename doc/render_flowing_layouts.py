#!/usr/bin/env python3
"""Render the cells of a flowing layouts study and their flux maps: the
paper's Fig. 6 with deforming cells.

    xvfb-run -a python3 doc/render_flowing_layouts.py OUTPUT_DIRECTORY N PICTURE.png

One row per layout of N cells (uniform, random with the first seed,
clustered): left the rigid cells at t = 0, right the cells at the end of
the run, each membrane coloured by the CO flux density into the cell, on
one colour scale for the whole picture. The view is from the side, the
flow from left to right. Needs python3-vtk9 (`scripts/install-packages.sh
--docs`).
"""
import glob
import sys

import vtk

from vtk_picture import actor, outer_surface, read, save_png, scalar_bar


def run_directories(directory, n_cells):
    """{layout: its first run of N cells}, in the order uniform, random, clustered."""
    runs = {}
    for layout in ("uniform", "random", "clustered"):
        found = sorted(glob.glob(f"{directory}/{layout}_{n_cells}_*/"),
                       key=lambda d: int(d.rstrip("/").rsplit("_", 1)[1]))
        if found:
            runs[layout] = found[0]
    return runs


def main(directory, n_cells, picture):
    runs = run_directories(directory, n_cells)
    if not runs:
        sys.exit(f"no run of {n_cells} cells in {directory}")
    # A layout run only once (its cells equal an earlier layout's) has no folder.
    membranes = {}
    for layout, run in runs.items():
        files = sorted(glob.glob(run + "diffusion_membranes_*.vtu"))
        membranes[layout] = (read(files[0]), read(files[-1]))
    low = min(m.GetPointData().GetArray("co_flux").GetRange()[0]
              for pair in membranes.values() for m in pair)
    high = max(m.GetPointData().GetArray("co_flux").GetRange()[1]
               for pair in membranes.values() for m in pair)
    rainbow = vtk.vtkLookupTable()
    rainbow.SetHueRange(0.667, 0.0)
    rainbow.Build()

    renderers = []
    rows = len(membranes)
    for row, (layout, pair) in enumerate(membranes.items()):
        for column, data in enumerate(pair):
            renderer = vtk.vtkRenderer()
            bottom = 0.14 + (rows - 1 - row) * 0.86 / rows
            renderer.SetViewport(0.5 * column, bottom, 0.5 * column + 0.5, bottom + 0.86 / rows)
            renderer.SetBackground(1, 1, 1)
            renderer.AddActor(actor(outer_surface(data), "co_flux", (low, high), rainbow))
            title = vtk.vtkTextActor()
            title.SetInput(f"{layout}, {'t = 0, rigid' if column == 0 else 'after flow'}")
            title.GetTextProperty().SetColor(0, 0, 0)
            title.GetTextProperty().SetFontSize(18)
            title.SetPosition(10, 10)
            renderer.AddActor2D(title)
            # One scale for every view: 22 µm across, centred on the cells.
            bounds = data.GetBounds()
            middle = [(bounds[2 * i] + bounds[2 * i + 1]) / 2 for i in range(3)]
            camera = renderer.GetActiveCamera()
            camera.ParallelProjectionOn()
            camera.SetFocalPoint(*middle)
            camera.SetPosition(middle[0], middle[1] - 50, middle[2] + 15)
            camera.SetViewUp(0, 0, 1)
            renderer.ResetCameraClippingRange()
            camera.SetParallelScale(4.5)
            renderers.append(renderer)
    legend = vtk.vtkRenderer()
    legend.SetViewport(0, 0, 1, 0.14)
    legend.SetBackground(1, 1, 1)
    bar = scalar_bar(rainbow, "CO flux density into the cell [µm³/(µm² s Torr)]",
                     left=0.2, width=0.6)
    bar.SetPosition(0.2, 0.1)
    bar.SetHeight(0.8)
    legend.AddActor2D(bar)
    renderers.append(legend)
    save_png(renderers, picture, size=(1400, 250 * rows + 120))


if __name__ == "__main__":
    if len(sys.argv) != 4:
        sys.exit(__doc__)
    main(sys.argv[1], int(sys.argv[2]), sys.argv[3])
