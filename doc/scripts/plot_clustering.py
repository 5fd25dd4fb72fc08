#!/usr/bin/env python3
"""Do clustered trains stay clustered in flow? The gaps of the clustered runs
of two flowing layouts studies, without and with aggregation
(prm/flowing_layouts_quick.prm, prm/flowing_layouts_aggregation.prm).

    /usr/bin/python3 doc/scripts/plot_clustering.py WITHOUT_DIRECTORY WITH_DIRECTORY PICTURE.png

One panel per study: for each clustered run of N > 1 cells, against time,
the smallest gap from a cell to its nearest neighbour (solid) and the
largest (dashed), from the run's cells.csv (min_gap). A cluster that holds
together keeps the largest near the starting gap; a cluster that comes
apart shows it growing. The gap axis starts at 0 (contact). Needs
python3-matplotlib (`scripts/install-packages.sh --docs`).
"""
import sys

from matplotlib.lines import Line2D

import plot_style
from rbc_ifem_run import Run

plt = plot_style.pyplot()


def gaps_over_time(run):
    """Times [ms] and the smallest and largest nearest-neighbour gap then."""
    rows = run.table("cells.csv")
    times = sorted({r["time"] for r in rows})
    gaps = [[r["min_gap"] for r in rows if r["time"] == t] for t in times]
    return [1e3 * t for t in times], [min(g) for g in gaps], [max(g) for g in gaps]


def main(without, with_aggregation, picture):
    figure, panels = plt.subplots(1, 2, figsize=(11, 4.2), sharey=True, layout="constrained")
    for panel, directory, title in ((panels[0], without, "repulsion only"),
                                    (panels[1], with_aggregation, "with aggregation (Morse)")):
        for run in Run(directory).runs("clustered_*_*"):
            n = int(run.name.split("_")[1])
            if n < 2:
                continue
            t, smallest, largest = gaps_over_time(run)
            line, = panel.plot(t, smallest, "-", label=f"{n} cells")
            panel.plot(t, largest, "--", color=line.get_color())
        panel.set_title(title)
        panel.set_xlabel("time [ms]")
    panels[0].set_ylabel("gap from a cell to its nearest neighbour [µm]")
    # One key for both panels, in room made above the curves: the colour
    # is the train, the style the gap.
    handles, labels = panels[0].get_legend_handles_labels()
    handles += [Line2D([], [], color="grey", linestyle="-"), Line2D([], [], color="grey", linestyle="--")]
    labels += ["nearest pair (smallest gap)", "farthest neighbour (largest)"]
    _, high = panels[0].get_ylim()
    panels[0].set_ylim(0, 1.35 * high)
    panels[0].legend(handles, labels, loc="upper left", ncol=2)
    plot_style.save(figure, picture)


if __name__ == "__main__":
    if len(sys.argv) != 4:
        sys.exit(__doc__)
    main(sys.argv[1], sys.argv[2], sys.argv[3])
