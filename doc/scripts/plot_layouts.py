#!/usr/bin/env python3
"""Plot layouts.csv of an `Experiment = layouts` run: DM of the capillary and
DM per cell against the number of cells, one line per layout (the paper's
Figs. 7 and 8). Random layouts show their mean with ± one standard
deviation over the seeds. Both DM axes start at 0.

    /usr/bin/python3 doc/scripts/plot_layouts.py output/layouts/layouts.csv doc/figures/layouts.png

Needs python3-matplotlib (`scripts/install-packages.sh --docs`).
"""
import sys

import plot_style
from rbc_ifem_run import read_table

plt = plot_style.pyplot()

STYLE = {"uniform": ("o-", "tab:blue"), "random": ("s-", "tab:orange"),
         "clustered": ("^-", "tab:green")}


def by_layout(path):
    """{layout: its rows of the table PATH}, in the table's order."""
    table = {}
    for row in read_table(path):
        table.setdefault(row["layout"], []).append(row)
    return table


def main(path, picture):
    table = by_layout(path)
    figure, (total, per_cell) = plt.subplots(1, 2, figsize=(10, 4), layout="constrained")
    for layout, rows in table.items():
        marker, colour = STYLE.get(layout, ("x-", "black"))
        n = [r["n_cells"] for r in rows]
        dm = [r["dm_total"] for r in rows]
        spread = [r["dm_total_std"] for r in rows]
        total.errorbar(n, dm, yerr=spread, fmt=marker, color=colour, capsize=3, label=layout)
        per_cell.errorbar(n, [d / k for d, k in zip(dm, n)],
                          yerr=[s / k for s, k in zip(spread, n)],
                          fmt=marker, color=colour, capsize=3, label=layout)
    total.set_ylabel("DM of the capillary [µm³ s⁻¹ Torr⁻¹]")
    per_cell.set_ylabel("DM per cell [µm³ s⁻¹ Torr⁻¹]")
    for axes in (total, per_cell):
        axes.set_xlabel("number of red cells in the 20 µm segment")
        plot_style.from_zero(axes)
        axes.legend(loc="lower right" if axes is total else "lower left")
    plot_style.save(figure, picture)


if __name__ == "__main__":
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    main(sys.argv[1], sys.argv[2])
