#!/usr/bin/env python3
"""Render stretched cells of an `Experiment = stretching` run side by side.

    xvfb-run -a /usr/bin/python3 doc/scripts/render_stretch.py OUTPUT_DIRECTORY PICTURE.png [N ...]

Shows the equilibria N of stretch.pvd (default: the first, middle and last)
seen obliquely from above, the beads pulling along x, coloured by the
magnitude of the displacement from the reference shape, all on one scale
of length (the 5 µm bar) and of colour (viridis, from 0). Needs
python3-paraview and python3-matplotlib (`scripts/install-packages.sh --docs`).
"""
import sys

import vtk

from rbc_ifem_run import Run
from vtk_picture import (actor, colour_map, label, legend, parallel_camera, save_png, scale_bar,
                         smooth_surface)

SIZE = (1350, 470)
LEGEND = 0.24  # of the window's height


def main(directory, picture, chosen):
    run = Run(directory)
    entries = run.series("stretch.pvd")  # (bead force [pN], file)
    if not chosen:
        chosen = [0, len(entries) // 2, len(entries) - 1]
    shapes = [(entries[k][0], run.dataset(entries[k][1])) for k in chosen]
    largest = max(s.GetPointData().GetArray("displacement").GetMaxNorm() for _, s in shapes)
    colours = colour_map(0, largest, vector=True)
    widest = max(s.GetBounds()[1] - s.GetBounds()[0] for _, s in shapes)

    renderers = []
    for k, (force, shape) in enumerate(shapes):
        renderer = vtk.vtkRenderer()
        renderer.SetBackground(1, 1, 1)
        renderer.SetViewport(k / len(shapes), LEGEND, (k + 1) / len(shapes), 1)
        renderer.AddActor(actor(smooth_surface(shape), "displacement", (0, largest), colours))
        label(renderer, f"F = {force:g} pN", 0.05, 0.88)
        # The same scale in every view: the widest shape fills 90 % of a view's width.
        aspect = (SIZE[1] * (1 - LEGEND)) / (SIZE[0] / len(shapes))
        parallel_camera(renderer, (0, 0, 0), (0, 12, -16), (0, 0, 1), widest / 0.9 * aspect)
        renderers.append(renderer)
    scale_bar(renderers[0], 5, SIZE, x=0.05, y=0.06)
    label(renderers[-1], "←  the beads pull along x  →", 0.95, 0.06, size=17, justify="right")

    bar = legend(colours, "displacement from the reference shape [µm]", (0, 0, 1, LEGEND), 0.5)
    save_png(renderers + [bar], picture, SIZE)


if __name__ == "__main__":
    if len(sys.argv) < 3:
        sys.exit(__doc__)
    main(sys.argv[1], sys.argv[2], [int(n) for n in sys.argv[3:]])
