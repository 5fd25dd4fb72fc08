#!/usr/bin/env python3
"""Plot uptake.csv of an `Experiment = finite uptake` run: DL against θ_CO,
one panel per number of cells, a line per layout; Roughton and Forster's
lumped estimate 1/DL = 1/DM + 1/(θ V_c) dashed, DM (the membrane sink, θ → ∞)
dotted, the range of θ the cited formulas give at PO₂ 100 Torr shaded grey,
and the paper's one-cell DM of 1.03-1.18 µm³ s⁻¹ Torr⁻¹ shaded red. The
DL axes start at 0; θ is on a log axis.

    /usr/bin/python3 doc/scripts/plot_finite_uptake.py output/finite_uptake/uptake.csv doc/figures/finite_uptake.png

Needs python3-matplotlib (`scripts/install-packages.sh --docs`).
"""
import sys

import plot_style
from rbc_ifem_run import read_table

plt = plot_style.pyplot()

COLOUR = {"uniform": "tab:blue", "random": "tab:orange", "clustered": "tab:green"}
PAPER_ONE_CELL = (1.03, 1.18)  # An et al. 2022, one cell


def main(path, picture):
    rows = read_table(path)
    counts = sorted({int(r["n_cells"]) for r in rows})
    figure, panels = plt.subplots(1, len(counts), figsize=(5 * len(counts), 5),
                                  layout="constrained", squeeze=False)
    for axes, n in zip(panels[0], counts):
        mine = [r for r in rows if int(r["n_cells"]) == n]
        for layout in dict.fromkeys(r["layout"] for r in mine):
            curve = sorted((r for r in mine if r["layout"] == layout),
                           key=lambda r: r["theta"])
            theta = [r["theta"] for r in curve]
            colour = COLOUR.get(layout, "black") if n > 1 else "black"
            axes.plot(theta, [r["dl_total"] for r in curve], "o-", color=colour,
                      label=f"DL, {layout}" if n > 1 else "DL")
            axes.plot(theta, [r["roughton_forster_dl"] for r in curve], "--",
                      color=colour)
            axes.axhline(curve[0]["dm_total"], color=colour, ls=":")
        axes.plot([], [], "k--", label="lumped: 1/DM + 1/(θ V_c)")
        axes.plot([], [], "k:", label="DM (the membrane sink, θ → ∞)")
        cited = [r["theta"] for r in mine if r.get("oxygen_pressure") == 100]
        if cited:
            axes.axvspan(min(cited), max(cited), color="grey", alpha=0.25,
                         label="θ of the cited formulas, PO₂ 100 Torr")
        if n == 1:
            axes.axhspan(*PAPER_ONE_CELL, color="tab:red", alpha=0.15,
                         label="the paper's one-cell DM, 1.03-1.18")
        axes.set_xscale("log")
        plot_style.plain_log_ticks(axes.xaxis)
        axes.set_xlabel("θ_CO [mL CO min⁻¹ Torr⁻¹ per mL of blood]")
        axes.set_ylabel("DL [µm³ s⁻¹ Torr⁻¹]")
        # From 0, and DM's line inside the frame rather than on its edge.
        axes.set_ylim(0, 1.1 * max(r["dm_total"] for r in mine))
        axes.set_title(f"{n} cell{'s' if n > 1 else ''}")
        # Below the panel: inside, every place hides a curve or DM's line.
        axes.legend(loc="upper center", bbox_to_anchor=(0.5, -0.16), ncol=2)
    plot_style.save(figure, picture)


if __name__ == "__main__":
    main(*sys.argv[1:3])
