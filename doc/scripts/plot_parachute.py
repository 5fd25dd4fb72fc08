#!/usr/bin/env python3
"""Plot how a red cell flowing in the capillary (`Experiment = flow` with
immersed cells) deforms and how its DM follows.

    /usr/bin/python3 doc/scripts/plot_parachute.py OUTPUT_DIRECTORY PICTURE.png

Three panels against time: (a) DM of the capillary from dm.csv, zoomed on
its change of a few per cent: the DM axis does not start at zero and is
marked broken, the right axis gives the change from t = 0 in per cent;
(b) the shape of cell 0 from cells.csv, its axial length and diameter
2 r_max on the left axis (from 0) and its deformation index on the right
(up to 0); (c) the change of its volume and area from the reference cell.
Needs python3-matplotlib (`scripts/install-packages.sh --docs`).
"""
import sys

import plot_style
from rbc_ifem_run import Run

plt = plot_style.pyplot()


def column(rows, name, scale=1.0):
    return [scale * r[name] for r in rows]


def leave_room_on_top(axes, fraction=0.3):
    """Raise the top of AXES so that a legend fits above the curves."""
    low, high = axes.get_ylim()
    axes.set_ylim(low, high + fraction * (high - low))


def main(directory, picture):
    run = Run(directory)
    dm = run.table("dm.csv")
    cell = run.table("cells.csv", cell=0)
    t_dm, t_cell = column(dm, "time", 1e3), column(cell, "time", 1e3)
    figure, (total, shape, conserved) = plt.subplots(1, 3, figsize=(14, 3.8),
                                                 layout="constrained")

    total.plot(t_dm, column(dm, "dm_total"), "o-", color="tab:blue")
    total.set_ylabel("DM [µm³ s⁻¹ Torr⁻¹], axis broken")
    total.set_title("(a) diffusing capacity")
    # From zero the 3.5% drop would be a flat line: zoomed, the axis marked
    # broken, and the change itself on the right.
    plot_style.mark_broken(total)
    start = dm[0]["dm_total"]
    change = total.secondary_yaxis("right", functions=(lambda d: 100 * (d / start - 1),
                                                       lambda p: start * (1 + p / 100)))
    change.set_ylabel("change from t = 0 [%]")

    shape.plot(t_cell, column(cell, "axial_length"), "o-", color="tab:red",
               label="axial length L")
    shape.plot(t_cell, column(cell, "max_radius", 2.0), "s-", color="tab:blue",
               label="diameter D = 2 r_max")
    shape.set_ylabel("length [µm]")
    index = shape.twinx()
    index.plot(t_cell, column(cell, "deformation_index"), "^--", color="tab:green",
               label="(L − D)/(L + D)")
    index.set_ylabel("deformation index", color="tab:green")
    index.tick_params(axis="y", colors="tab:green")
    plot_style.from_zero(shape)
    leave_room_on_top(shape)
    plot_style.from_zero(index)  # its top, 0, level with the legend: the curve stays below
    lines = shape.get_lines() + index.get_lines()
    shape.legend(lines, [line.get_label() for line in lines], loc="upper center", ncol=2)
    shape.set_title("(b) shape of cell 0")

    conserved.plot(t_cell, column(cell, "volume_change", 100.0), "o-", color="tab:purple",
                   label="volume")
    conserved.plot(t_cell, column(cell, "area_change", 100.0), "s-", color="tab:orange",
                   label="area")
    conserved.axhline(0, color="black", linewidth=0.8)
    conserved.set_ylabel("change from the reference cell [%]")
    conserved.legend()
    conserved.set_title("(c) volume and area of cell 0")

    index.grid(False)
    for axes in (total, shape, conserved):
        axes.set_xlabel("time [ms]")
    plot_style.save(figure, picture)


if __name__ == "__main__":
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    main(sys.argv[1], sys.argv[2])
