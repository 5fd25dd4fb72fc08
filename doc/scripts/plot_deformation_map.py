#!/usr/bin/env python3
"""Plot the deformation and confinement map that
benchmarks/deformation_map.sh writes: the change of DM (solid) and DL
(dashed) from the cell's starting shape to its shape at the end of the run
(once DM changes by less than 0.1% in 3 ms, at most 60 ms; a run that
did not settle is circled: its drop is a lower bound), against
the capillary number μū/G in the 10 µm capillary (a colour per shear
modulus) and against the capillary's diameter (at two capillary numbers);
the paper's -13% in grey; the change axes reach up to 0 (no change). Below,
the cell's outline in the plane of the capillary's axis at the end, at
five points of the map, with the wall.

    /usr/bin/python3 doc/scripts/plot_deformation_map.py output/deformation_map doc/figures/deformation_map.png

Needs python3-matplotlib and python3-paraview (`scripts/install-packages.sh --docs`).
"""
import os
import sys

import plot_style
from rbc_ifem_run import Run, read_table

plt = plot_style.pyplot()

PAPER_DROP = -13.0  # An et al. 2022: the parachute's DM against the disc's
COLOUR = {2.5: "tab:red", 5.5: "tab:blue", 10.0: "tab:green"}
# (diameter, speed, shear modulus) of the outlines.
SHAPES = [(10, 500, 5.5), (10, 2000, 2.5), (8, 2000, 2.5), (7, 500, 5.5), (6, 500, 5.5)]


def percent(row, key):
    return 100 * row[key]


def circle_unsettled(axes, x, curve, colour):
    """Circle the DM points of CURVE (at X) whose run had not settled."""
    unsettled = [(xi, percent(r, "dm_change")) for xi, r in zip(x, curve)
                 if r.get("steady") != "true"]
    if unsettled:
        axes.plot(*zip(*unsettled), "o", ms=13, mfc="none", mec=colour, lw=0)


def against_capillary_number(axes, rows):
    tube = [r for r in rows if r["diameter"] == 10]
    for g in sorted({r["shear_modulus"] for r in tube}):
        curve = sorted((r for r in tube if r["shear_modulus"] == g),
                       key=lambda r: r["capillary_number"])
        ca = [r["capillary_number"] for r in curve]
        colour = COLOUR.get(g, "black")
        axes.plot(ca, [percent(r, "dm_change") for r in curve], "o-", color=colour,
                  label=f"G = {g:g} pN/µm")
        axes.plot(ca, [percent(r, "dl_change") for r in curve], "s--", color=colour, mfc="none")
        circle_unsettled(axes, ca, curve, colour)
    axes.axhline(PAPER_DROP, color="grey", lw=4, alpha=0.4, label="the paper's DM drop")
    axes.plot([], [], "k-", label="DM")
    axes.plot([], [], "k--", label="DL")
    if any(r.get("steady") != "true" for r in tube):
        axes.plot([], [], "ko", ms=13, mfc="none", label="not settled by 60 ms")
    axes.set_xscale("log")
    plot_style.plain_log_ticks(axes.xaxis)
    axes.set_xlabel("capillary number μū/G")
    axes.set_ylabel("change at the end [%]")
    plot_style.from_zero(axes)
    axes.set_title("10 µm capillary")
    axes.legend(loc="lower left")


def against_diameter(axes, rows):
    for (u, g), colour in (((500, 5.5), "tab:blue"), ((2000, 2.5), "tab:red")):
        curve = sorted((r for r in rows if r["mean_speed"] == u and r["shear_modulus"] == g),
                       key=lambda r: r["diameter"])
        if not curve:
            continue
        d = [r["diameter"] for r in curve]
        label = f"ū = {u / 1000:g} mm/s, G = {g:g} pN/µm (Ca = {curve[0]['capillary_number']:.2f})"
        axes.plot(d, [percent(r, "dm_change") for r in curve], "o-", color=colour, label=label)
        axes.plot(d, [percent(r, "dl_change") for r in curve], "s--", color=colour, mfc="none")
        circle_unsettled(axes, d, curve, colour)
    axes.axhline(PAPER_DROP, color="grey", lw=4, alpha=0.4)
    axes.axvline(7.5, color="black", ls=":", lw=1)
    axes.text(7.45, -6, "cell diameter", rotation=90, ha="right", va="center", fontsize=8)
    axes.set_xlabel("capillary diameter [µm]")
    axes.set_ylabel("change at the end [%]")
    axes.set_title("confinement (7.5 µm cell)")
    plot_style.from_zero(axes)
    low, high = axes.get_ylim()
    axes.set_ylim(low - 0.25 * (high - low), high)  # room for the legend
    axes.legend(loc="lower right")


def outline(run):
    """The membrane's intersection with the plane z = 0 at the last output,
    as line segments (x from the middle of the cell's extent, y)."""
    import vtk
    membrane = run.dataset(run.last("cell_0.pvd"))
    plane = vtk.vtkPlane()
    plane.SetOrigin(0, 0, 0)
    plane.SetNormal(0, 0, 1)
    cutter = vtk.vtkCutter()
    cutter.SetCutFunction(plane)
    cutter.SetInputData(membrane)
    cutter.Update()
    cut = cutter.GetOutput()
    points = cut.GetPoints()
    bounds = membrane.GetBounds()
    middle = 0.5 * (bounds[0] + bounds[1])
    segments = []
    for i in range(cut.GetNumberOfCells()):
        ids = cut.GetCell(i).GetPointIds()
        segments.append([(points.GetPoint(ids.GetId(k))[0] - middle,
                          points.GetPoint(ids.GetId(k))[1]) for k in range(ids.GetNumberOfIds())])
    return segments


def shapes(axes_list, directory, rows):
    from matplotlib.collections import LineCollection
    for axes, (d, u, g) in zip(axes_list, SHAPES):
        name = os.path.join(directory, f"D{d:g}_U{u:g}_G{g:g}")
        row = [r for r in rows if (r["diameter"], r["mean_speed"], r["shear_modulus"]) == (d, u, g)]
        axes.set_aspect("equal")
        axes.set_xlim(-6, 6)
        axes.set_ylim(-5.3, 5.3)
        axes.set_xticks([])
        axes.set_yticks([])
        if not row or not os.path.isdir(name):
            axes.set_title("not run", fontsize=8)
            continue
        axes.add_collection(LineCollection(outline(Run(name)), colors="black", linewidths=1.2))
        for side in (-1, 1):
            axes.axhline(side * d / 2, color="tab:brown", lw=2)
        r = row[0]
        axes.set_title(f"{d:g} µm, Ca = {r['capillary_number']:.2f}\n"
                       f"DM {percent(r, 'dm_change'):+.1f}%, DL {percent(r, 'dl_change'):+.1f}%",
                       fontsize=8)
    axes_list[0].annotate("flow", xy=(5.5, -4.5), xytext=(2.5, -4.5), fontsize=8, va="center",
                          arrowprops={"arrowstyle": "->"})


def main(directory, picture):
    rows = read_table(os.path.join(directory, "deformation_map.csv"))
    figure = plt.figure(figsize=(11, 7.2), layout="constrained")
    top, bottom = figure.subfigures(2, 1, height_ratios=[1.5, 1])
    left, right = top.subplots(1, 2)
    against_capillary_number(left, rows)
    against_diameter(right, rows)
    shapes(bottom.subplots(1, len(SHAPES)), directory, rows)
    bottom.suptitle("the cell at the end of its run, in the plane of the axis", fontsize=10)
    plot_style.save(figure, picture)


if __name__ == "__main__":
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    main(*sys.argv[1:])
