#!/usr/bin/env python3
"""Plot a train of cells flowing in a periodic capillary (prm/periodic_train.prm).

    /usr/bin/python3 doc/scripts/plot_train.py OUTPUT_DIRECTORY PICTURE.png

Three panels against time: (a) DM of the segment and DM per cell from
dm.csv, zoomed on their change of a few per cent: both DM axes do not
start at zero and are marked broken; (b) the deformation index of every
cell from cells.csv, its axis up to 0; (c) the smallest gap between cells
(min_gap) and to the wall (wall_gap), from 0. Needs python3-matplotlib
(`scripts/install-packages.sh --docs`).
"""
import sys

import plot_style
from rbc_ifem_run import Run

plt = plot_style.pyplot()


def main(directory, picture):
    run = Run(directory)
    dm = run.table("dm.csv")
    rows = run.table("cells.csv")
    cells = sorted({int(r["cell"]) for r in rows})
    figure, (uptake, shape, gaps) = plt.subplots(1, 3, figsize=(14, 3.8),
                                                 layout="constrained")

    t_dm = [1e3 * r["time"] for r in dm]
    uptake.plot(t_dm, [r["dm_total"] for r in dm], "o-", color="black", label="segment")
    uptake.set_ylabel("DM of the segment [µm³ s⁻¹ Torr⁻¹], axis broken")
    per_cell = uptake.twinx()
    for c in cells:
        per_cell.plot(t_dm, [r[f"dm_cell_{c}"] for r in dm], ".--", label=f"cell {c}")
    per_cell.set_ylabel("DM per cell [µm³ s⁻¹ Torr⁻¹], axis broken")
    per_cell.grid(False)
    lines = uptake.get_lines() + per_cell.get_lines()
    uptake.legend(lines, [line.get_label() for line in lines], fontsize=7, ncol=2)
    # From zero the change of a few per cent would be a flat line: zoomed,
    # both axes marked broken.
    plot_style.mark_broken(uptake, sides=("left", "right"))
    uptake.set_title("(a) diffusing capacity")

    for c in cells:
        mine = [r for r in rows if r["cell"] == c]
        shape.plot([1e3 * r["time"] for r in mine],
                   [r["deformation_index"] for r in mine], "o-", label=f"cell {c}")
    shape.set_ylabel("deformation index (L − D)/(L + D)")
    plot_style.from_zero(shape)
    shape.legend(fontsize=7, loc="upper left")
    shape.set_title("(b) shapes")

    times = sorted({r["time"] for r in rows})
    smallest = [min(r["min_gap"] for r in rows if r["time"] == t) for t in times]
    wall = [min(r["wall_gap"] for r in rows if r["time"] == t) for t in times]
    gaps.plot([1e3 * t for t in times], smallest, "o-", label="between cells")
    gaps.plot([1e3 * t for t in times], wall, "s-", label="to the wall")
    gaps.set_ylabel("smallest gap [µm]")
    plot_style.from_zero(gaps)
    gaps.legend()
    gaps.set_title("(c) gaps")
    for axes in (uptake, shape, gaps):
        axes.set_xlabel("time [ms]")
    plot_style.save(figure, picture)


if __name__ == "__main__":
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    main(sys.argv[1], sys.argv[2])
