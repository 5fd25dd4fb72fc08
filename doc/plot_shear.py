#!/usr/bin/env python3
"""Plot the capsule-in-shear validation (`Experiment = shear`).

    /usr/bin/python3 doc/plot_shear.py OUTPUT_DIRECTORY PICTURE.png

Three panels: (a) the Taylor deformation D against the strain γ̇t of every
run, from OUTPUT_DIRECTORY/ca_<Ca>/shear.csv; (b) the steady D against the
capillary number Ca = μaγ̇/G from shear_summary.csv, beside the published
values in doc/results/shear_references.csv and the small-deformation theory
D = 25/12 Ca; (c) the steady shapes: the cut of each capsule's last membrane
(cell_0 VTU) by the shear plane z = 0. Needs python3-matplotlib and
python3-vtk9 (`scripts/install-packages.sh --docs`).
"""
import csv
import glob
import os
import sys
import xml.etree.ElementTree as ElementTree

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt
from vtkmodules.vtkCommonDataModel import vtkPlane
from vtkmodules.vtkFiltersCore import vtkCutter, vtkStripper
from vtkmodules.vtkFiltersGeometry import vtkGeometryFilter
from vtkmodules.vtkIOXML import vtkXMLUnstructuredGridReader

HERE = os.path.dirname(os.path.abspath(__file__))


def read(path):
    """The rows of a CSV file as dicts, numbers as floats."""
    def number(value):
        try:
            return float(value)
        except ValueError:
            return value
    with open(path) as f:
        return [{k: number(v) for k, v in row.items()} for row in csv.DictReader(f)]


def last_membrane(run):
    """The file of the last record of RUN/cell_0.pvd."""
    datasets = ElementTree.parse(os.path.join(run, "cell_0.pvd")).getroot().iter("DataSet")
    return os.path.join(run, list(datasets)[-1].get("file"))


def shear_plane_cut(vtu):
    """The polylines where the membrane in VTU crosses z = 0, as (x, y) lists."""
    reader = vtkXMLUnstructuredGridReader()
    reader.SetFileName(vtu)
    surface = vtkGeometryFilter()
    surface.SetInputConnection(reader.GetOutputPort())
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
    summary = read(os.path.join(directory, "shear_summary.csv"))
    references = read(os.path.join(HERE, "results", "shear_references.csv"))
    rate = None
    with open(os.path.join(directory, "parameters.prm")) as f:
        for line in f:
            if line.strip().startswith("set Shear rate"):
                rate = float(line.split("=")[1].split("#")[0])
    colours = plt.cm.viridis([i / max(1, len(summary) - 1) for i in range(len(summary))])

    figure, (history, steady, shapes) = plt.subplots(1, 3, figsize=(14, 4.2),
                                                    layout="constrained")
    for row, colour in zip(summary, colours):
        run = os.path.join(directory, "ca_%g" % row["capillary_number"])
        rows = read(os.path.join(run, "shear.csv"))
        history.plot([rate * r["time"] for r in rows], [r["taylor_deformation"] for r in rows],
                     "o-", ms=3, color=colour, label="Ca = %g" % row["capillary_number"])
        for xs, ys in shear_plane_cut(last_membrane(run)):
            shapes.plot(xs, ys, "-", color=colour)
    history.set_xlabel("strain γ̇t")
    history.set_ylabel("Taylor deformation D")
    history.set_title("(a) D(t), each Ca")
    history.legend(fontsize=7, ncol=2)

    ca = [r["capillary_number"] for r in summary]
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
    steady.legend(fontsize=7)

    shapes.set_aspect("equal")
    shapes.set_xlabel("x [µm]")
    shapes.set_ylabel("y [µm]")
    shapes.set_title("(c) steady shapes, cut z = 0")
    figure.savefig(picture, dpi=120)
    print("wrote", picture)


if __name__ == "__main__":
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    main(sys.argv[1], sys.argv[2])
