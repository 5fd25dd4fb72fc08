#!/usr/bin/env python3
"""Render the cells of a flowing layouts study and their flux maps: the
paper's Fig. 6 with deforming cells.

    xvfb-run -a /usr/bin/python3 doc/scripts/render_flowing_layouts.py OUTPUT_DIRECTORY N PICTURE.png

One row per layout of N cells (uniform, random with the first seed,
clustered): left the rigid cells at t = 0, right the cells at the end of
the run, each membrane coloured by the CO flux density λ into the cell
(doc/diffusion.md), on one colour scale (viridis) from 0 and one scale of
length for the whole picture. The view is from the side, the flow from
left to right. Needs python3-paraview and python3-matplotlib
(`scripts/install-packages.sh --docs`).
"""
import sys

import vtk

from rbc_ifem_run import Run
from vtk_picture import (FLUX_UNIT, actor, colour_map, label, legend, parallel_camera, save_png,
                         scale_bar, smooth_surface)

LAYOUTS = ("uniform", "random", "clustered")


def run_directories(study, n_cells):
    """{layout: its first run (lowest seed) of N cells}, in the order of LAYOUTS.
    A layout run only once (its cells equal an earlier layout's) has no folder."""
    runs = {}
    for layout in LAYOUTS:
        found = study.runs(f"{layout}_{n_cells}_*")
        if found:
            runs[layout] = found[0]
    return runs


def main(directory, n_cells, picture):
    study = Run(directory)
    runs = run_directories(study, n_cells)
    if not runs:
        sys.exit(f"no run of {n_cells} cells in {directory}")
    membranes = {}
    for layout, run in runs.items():
        series = run.series("diffusion_membranes.pvd")
        membranes[layout] = (run.dataset(series[0][1]), (series[-1][0], run.dataset(series[-1][1])))
    # One colour scale for every view, from 0: λ ≥ 0, its small negative
    # values are undershoot (doc/diffusion.md).
    high = max(m.GetPointData().GetArray("co_flux").GetRange()[1]
               for first, (_, last) in membranes.values() for m in (first, last))
    colours = colour_map(0, high)
    rows = len(membranes)
    size = (1400, 280 * rows + 130)
    bottom_of_views = 130 / size[1]

    renderers = []
    for row, (layout, (first, (time, last))) in enumerate(membranes.items()):
        for column, data in enumerate((first, last)):
            renderer = vtk.vtkRenderer()
            bottom = bottom_of_views + (rows - 1 - row) * (1 - bottom_of_views) / rows
            renderer.SetViewport(0.5 * column, bottom, 0.5 * column + 0.5,
                                 bottom + (1 - bottom_of_views) / rows)
            renderer.SetBackground(1, 1, 1)
            renderer.AddActor(actor(smooth_surface(data), "co_flux", (0, high), colours))
            label(renderer, f"{layout}, " + ("t = 0, rigid" if column == 0 else
                                              f"after {1e3 * time:g} ms of flow"), 0.02, 0.88, size=18)
            # One scale for every view, 11 µm high, on the cells, room for the
            # title above them; from the side (-y) and a little above, the
            # flow to the right.
            bounds = data.GetBounds()
            middle = [(bounds[2 * i] + bounds[2 * i + 1]) / 2 for i in range(3)]
            middle[2] += 1.0
            parallel_camera(renderer, middle, (0, 50, -15), (0, 0, 1), 11)
            renderers.append(renderer)
    scale_bar(renderers[-2], 5, size, x=0.03, y=0.06)
    label(renderers[-1], "flow →", 0.97, 0.06, justify="right")
    p_alveolar = study.parameter("Alveolar pressure")
    renderers.append(legend(colours, f"CO flux density λ into the cell [{FLUX_UNIT}], P_A = {p_alveolar:g} Torr",
                            (0, 0, 1, bottom_of_views), 0.6))
    save_png(renderers, picture, size)


if __name__ == "__main__":
    if len(sys.argv) != 4:
        sys.exit(__doc__)
    main(sys.argv[1], int(sys.argv[2]), sys.argv[3])
