#!/usr/bin/env python3
"""Do clustered trains stay clustered in flow? The gaps of the clustered runs
of two flowing layouts studies, without and with aggregation
(prm/flowing_layouts_quick.prm, prm/flowing_layouts_aggregation.prm).

    /usr/bin/python3 doc/plot_clustering.py WITHOUT_DIRECTORY WITH_DIRECTORY PICTURE.png

One panel per study: for each clustered run of N > 1 cells, against time,
the smallest gap from a cell to its nearest neighbour (solid) and the
largest (dashed), from the run's cells.csv (min_gap). A cluster that holds
together keeps the largest near the starting gap; a cluster that comes
apart shows it growing. Needs python3-matplotlib
(`scripts/install-packages.sh --docs`).
"""
import glob
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt
from tables import read


def gaps_over_time(run):
    """Times [ms] and the smallest and largest nearest-neighbour gap then."""
    rows = read(run + "/cells.csv")
    times = sorted({r["time"] for r in rows})
    gaps = [[r["min_gap"] for r in rows if r["time"] == t] for t in times]
    return [1e3 * t for t in times], [min(g) for g in gaps], [max(g) for g in gaps]


def main(without, with_aggregation, picture):
    figure, panels = plt.subplots(1, 2, figsize=(11, 4.2), sharey=True, layout="constrained")
    for panel, directory, title in ((panels[0], without, "repulsion only"),
                                    (panels[1], with_aggregation, "with aggregation (Morse)")):
        runs = sorted(glob.glob(directory + "/clustered_*_*/"),
                      key=lambda d: int(d.rstrip("/").split("_")[-2]))
        for run in runs:
            n = int(run.rstrip("/").split("_")[-2])
            if n < 2:
                continue
            t, smallest, largest = gaps_over_time(run)
            line, = panel.plot(t, smallest, "-", label=f"{n} cells: nearest pair")
            panel.plot(t, largest, "--", color=line.get_color(), label=f"{n} cells: farthest neighbour")
        panel.set_title(title)
        panel.set_xlabel("time [ms]")
        panel.grid(alpha=0.3)
        panel.legend(fontsize=8)
    panels[0].set_ylabel("gap from a cell to its nearest neighbour [µm]")
    figure.savefig(picture, dpi=130)


if __name__ == "__main__":
    if len(sys.argv) != 4:
        sys.exit(__doc__)
    main(sys.argv[1], sys.argv[2], sys.argv[3])
