#!/usr/bin/env python3
"""Plot two cells pushed into each other (prm/cells_in_contact.prm).

    /usr/bin/python3 doc/scripts/plot_contact.py OUTPUT_DIRECTORY PICTURE.png

Two panels against time, from cells.csv: (a) the gap between the two
membranes (min_gap) with the repulsion range of the run's parameters.prm;
(b) the deformation index of each cell, its axis up to 0 (a disc is
−0.51, a sphere 0). Needs python3-matplotlib
(`scripts/install-packages.sh --docs`).
"""
import sys

import plot_style
from rbc_ifem_run import Run

plt = plot_style.pyplot()


def main(directory, picture):
    run = Run(directory)
    rows = run.table("cells.csv")
    cells = sorted({int(r["cell"]) for r in rows})
    figure, (gap, shape) = plt.subplots(1, 2, figsize=(10, 3.8), layout="constrained")

    first = [r for r in rows if r["cell"] == 0]
    gap.plot([1e3 * r["time"] for r in first], [r["min_gap"] for r in first], "o-",
             color="tab:blue", label="gap between the membranes")
    gap.axhline(run.parameter("Repulsion range"), color="tab:red",
                linestyle="--", label="repulsion range Δ")
    gap.axhline(0, color="black", linewidth=0.8)
    gap.set_ylabel("gap [µm]")
    gap.legend()
    gap.set_title("(a) the gap between the cells")

    for c in cells:
        mine = [r for r in rows if r["cell"] == c]
        shape.plot([1e3 * r["time"] for r in mine],
                   [r["deformation_index"] for r in mine], "o-", label=f"cell {c}")
    shape.set_ylabel("deformation index (L − D)/(L + D)")
    plot_style.from_zero(shape)
    shape.legend(loc="upper left")
    shape.set_title("(b) their shapes")
    for axes in (gap, shape):
        axes.set_xlabel("time [ms]")
    plot_style.save(figure, picture)


if __name__ == "__main__":
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    main(sys.argv[1], sys.argv[2])
