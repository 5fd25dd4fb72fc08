#!/usr/bin/env python3
"""Plot the capsule-in-shear validation (`Experiment = shear`).

    /usr/bin/python3 doc/scripts/plot_shear.py OUTPUT_DIRECTORY PICTURE.png

Three panels: (a) the Taylor deformation D against the strain γ̇t of every
run, from OUTPUT_DIRECTORY/ca_<Ca>/shear.csv; (b) the steady D against the
capillary number Ca = μaγ̇/G from shear_summary.csv, beside the published
values in doc/results/shear_references.csv and the small-deformation theory
D = 25/12 Ca; (c) the steady shapes: the cut of each capsule's last membrane
(the last file of cell_0.pvd) by the shear plane z = 0, one colour per Ca
as in (a), keyed by the colour bar. Needs python3-matplotlib and
python3-paraview (`scripts/install-packages.sh --docs`).
"""
import os
import sys

from matplotlib.cm import ScalarMappable
from matplotlib.colors import BoundaryNorm, ListedColormap
from vtkmodules.vtkCommonDataModel import vtkPlane
from vtkmodules.vtkFiltersCore import vtkCutter, vtkStripper
from vtkmodules.vtkFiltersGeometry import vtkGeometryFilter

import plot_style
from rbc_ifem_run import Run, read_dataset, read_table

plt = plot_style.pyplot()
HERE = os.path.dirname(os.path.abspath(__file__))


def shear_plane_cut(vtu):
    """The polylines where the membrane in VTU crosses z = 0, as (x, y) lists."""
    surface = vtkGeometryFilter()
    surface.SetInputData(read_dataset(vtu))
    plane = vtkPlane()
    plane.SetOrigin(0.0, 0.0, 0.0)
    plane.SetNormal(0.0, 0.0, 1.0)
    cutter = vtkCutter()
    cutter.SetCutFunction(plane)
    cutter.SetInputConnection(surface.GetOutputPort())
    stripper = vtkStripper()
    stripper.SetInputConnection(cutter.GetOutputPort())
    stripper.Update()
    lines, points = stripper.GetOutput(), stripper.GetOutput().GetPoints()
    cuts = []
    for i in range(lines.GetNumberOfCells()):
        ids = lines.GetCell(i).GetPointIds()
        xy = [points.GetPoint(ids.GetId(k))[:2] for k in range(ids.GetNumberOfIds())]
        cuts.append(([p[0] for p in xy], [p[1] for p in xy]))
    return cuts


def main(directory, picture):
    study = Run(directory)
    summary = study.table("shear_summary.csv")
    references = read_table(os.path.join(HERE, "..", "results", "shear_references.csv"))
    rate = study.parameter("Shear rate")
    ca = [r["capillary_number"] for r in summary]
    colours = plt.cm.viridis([i / max(1, len(summary) - 1) for i in range(len(summary))])

    figure, (history, steady, shapes) = plt.subplots(1, 3, figsize=(14, 4.4),
                                                    layout="constrained")
    for row, colour in zip(summary, colours):
        run = Run(study.path("ca_%g" % row["capillary_number"]))
        rows = run.table("shear.csv")
        history.plot([rate * r["time"] for r in rows], [r["taylor_deformation"] for r in rows],
                     "o-", ms=2.5, color=colour, label="Ca = %g" % row["capillary_number"])
        for xs, ys in shear_plane_cut(run.last("cell_0.pvd")):
            shapes.plot(xs, ys, "-", color=colour)
    history.set_xlabel("strain γ̇t")
    history.set_ylabel("Taylor deformation D")
    history.set_title("(a) D(t), each Ca")
    # The curves rise at small strain and stay flat: the legend right of
    # them, in room made above the largest D.
    strain = max(history.get_xlim())
    ticks = [t for t in history.get_xticks() if 0 <= t <= strain]
    history.set_xlim(right=1.55 * strain)
    history.set_xticks(ticks)
    history.legend(loc="center right")

    steady.plot(ca, [r["steady_deformation"] for r in summary], "o-", color="black",
                label="rbc-ifem")
    markers = {"Doddi & Bagchi 2008": "s", "Ramanujan & Pozrikidis 1998": "^",
               "Pozrikidis 1995": "v"}
    for source, marker in markers.items():
        rows = [r for r in references if r["source"] == source and r["capillary_number"] <= 1.1 * max(ca)]
        steady.plot([r["capillary_number"] for r in rows],
                    [r["steady_deformation"] for r in rows], marker, mfc="none", ms=8,
                    label=source)
    small = [0.0, 0.5 * max(ca)]
    steady.plot(small, [25.0 / 12.0 * c for c in small], "--", color="grey",
                label="small deformation, 25/12 Ca")
    steady.set_xlabel("capillary number Ca = μaγ̇/G")
    steady.set_ylabel("steady D")
    steady.set_title("(b) steady deformation")
    steady.legend(loc="upper left")

    shapes.set_aspect("equal")
    shapes.set_xlabel("x [µm]")
    shapes.set_ylabel("y [µm]")
    shapes.set_title("(c) steady shapes, cut z = 0")
    # A key of the colours: one band per Ca, as in (a).
    key = ScalarMappable(BoundaryNorm(range(len(ca) + 1), len(ca)), ListedColormap(colours))
    bar = figure.colorbar(key, ax=shapes, ticks=[k + 0.5 for k in range(len(ca))],
                          fraction=0.05, pad=0.03)
    bar.ax.set_yticklabels(["%g" % c for c in ca])
    bar.set_label("capillary number Ca")
    plot_style.save(figure, picture)


if __name__ == "__main__":
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    main(sys.argv[1], sys.argv[2])
