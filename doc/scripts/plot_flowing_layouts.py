#!/usr/bin/env python3
"""Plot an `Experiment = flowing layouts` run (prm/flowing_layouts*.prm).

    /usr/bin/python3 doc/scripts/plot_flowing_layouts.py OUTPUT_DIRECTORY PREFIX [N]

Writes two pictures:
  PREFIX_dm.png    DM of the segment and DM per cell against the number of
                   cells for each layout, the rigid cells at t = 0 (open
                   markers, dashed) beside the steady DM of the cells after
                   flow (filled, solid): the paper's Figs. 7 and 8 with
                   deforming cells. Random layouts show the mean and ± one
                   standard deviation over their seeds. DM axes from 0.
  PREFIX_time.png  for N cells (default: the largest N below 7 of the study,
                   or 7), DM(t) and the smallest gap between cells against
                   time for each layout (every seed of the random ones).
                   The DM axis is zoomed on its change of a few per cent,
                   does not start at zero and is marked broken; the gaps
                   are on a log axis.
Needs python3-matplotlib (`scripts/install-packages.sh --docs`).
"""
import statistics
import sys

import plot_style
from rbc_ifem_run import Run

plt = plot_style.pyplot()

STYLE = {"uniform": ("o", "tab:blue"), "random": ("s", "tab:orange"),
         "clustered": ("^", "tab:green")}


def by_layout_and_n(summary, column):
    """{layout: [(N, mean, std over the seeds)]} of COLUMN."""
    groups = {}
    for row in summary:
        groups.setdefault(row["layout"], {}).setdefault(int(row["n_cells"]), []).append(row[column])
    return {layout: [(n, statistics.mean(v), statistics.stdev(v) if len(v) > 1 else 0.)
                     for n, v in sorted(per_n.items())]
            for layout, per_n in groups.items()}


def plot_dm(summary, picture):
    figure, axes = plt.subplots(1, 2, figsize=(11, 4.2), layout="constrained")
    for panel, suffix, label in ((axes[0], "dm_total", "DM of the segment"),
                                 (axes[1], "dm_per_cell", "DM per cell")):
        for state, filled, line in (("static", False, "--"), ("steady", True, "-")):
            for layout, points in by_layout_and_n(summary, f"{state}_{suffix}").items():
                marker, colour = STYLE.get(layout, ("x", "black"))
                n, mean, std = zip(*points)
                panel.errorbar(n, mean, yerr=std, fmt=marker + line, color=colour, capsize=3,
                               markerfacecolor=colour if filled else "white",
                               label=f"{layout}, {'after flow' if filled else 'rigid, t = 0'}")
        panel.set_xlabel("number of red cells in the segment")
        panel.set_ylabel(label + " [µm³ s⁻¹ Torr⁻¹]")
        plot_style.from_zero(panel)
    axes[0].legend(loc="lower right")
    plot_style.save(figure, picture)


def plot_time(history, n_cells, picture):
    figure, (uptake, gaps) = plt.subplots(1, 2, figsize=(11, 4.2), layout="constrained")
    runs = {}
    for row in history:
        if int(row["n_cells"]) == n_cells:
            runs.setdefault((row["layout"], int(row["seed"])), []).append(row)
    for (layout, seed), rows in runs.items():
        marker, colour = STYLE.get(layout, ("x", "black"))
        label = layout if layout != "random" else f"random, seed {seed}"
        t = [1e3 * r["time"] for r in rows]
        uptake.plot(t, [r["dm_total"] for r in rows], marker + "-", color=colour,
                    alpha=1 if layout != "random" or seed == min(s for l, s in runs if l == layout) else 0.5,
                    label=label)
        if all("min_gap" in r for r in rows):  # a lone cell has none
            gaps.plot(t, [r["min_gap"] for r in rows], marker + "-", color=colour, label=label)
    uptake.set_ylabel(f"DM of the segment, {n_cells} cells\n[µm³ s⁻¹ Torr⁻¹], axis broken")
    # From zero the change of a few per cent with time would be flat lines.
    plot_style.mark_broken(uptake)
    gaps.set_ylabel("smallest gap between two cells [µm] (log scale)")
    gaps.set_yscale("log")
    plot_style.plain_log_ticks(gaps.yaxis)
    for axes in (uptake, gaps):
        axes.set_xlabel("time [ms]")
        axes.legend()
    plot_style.save(figure, picture)


def main(directory, prefix, n_cells=None):
    study = Run(directory)
    summary = study.table("flowing_layouts_summary.csv")
    history = study.table("flowing_layouts.csv")
    numbers = sorted({int(r["n_cells"]) for r in summary})
    if n_cells is None:
        below = [n for n in numbers if 1 < n < 7]
        n_cells = below[-1] if below else numbers[-1]
    plot_dm(summary, prefix + "_dm.png")
    plot_time(history, n_cells, prefix + "_time.png")


if __name__ == "__main__":
    if len(sys.argv) not in (3, 4):
        sys.exit(__doc__)
    main(sys.argv[1], sys.argv[2], int(sys.argv[3]) if len(sys.argv) == 4 else None)
