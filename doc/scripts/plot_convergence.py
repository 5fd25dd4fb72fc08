#!/usr/bin/env python3
"""Plot convergence.csv of an `Experiment = mesh convergence` run: the
difference of DM from its Richardson-extrapolated limit against the number
of mesh nodes, with the 2% and 0.5% lines.

    /usr/bin/python3 doc/scripts/plot_convergence.py output/mesh_convergence/convergence.csv doc/figures/mesh_convergence.png

Needs python3-matplotlib (`scripts/install-packages.sh --docs`).
"""
import sys

import plot_style
from rbc_ifem_run import read_table

plt = plot_style.pyplot()


def main(path, picture):
    rows = read_table(path)
    nodes = [r["n_nodes"] for r in rows]
    difference = [100 * r["difference_from_limit"] for r in rows]
    figure, axes = plt.subplots(figsize=(6, 4), layout="constrained")
    axes.loglog(nodes, difference, "o-", label="|DM − DM*| / DM*")
    for level, style in ((2, "--"), (0.5, ":")):
        axes.axhline(level, color="grey", linestyle=style, label=f"{level:g} %")
    for r, d in zip(rows, difference):
        axes.annotate(f"level {int(r['level'])}", (r["n_nodes"], d),
                      textcoords="offset points", xytext=(5, 5), fontsize=8)
    # Labels at 1, 2 and 5 of each decade: the decade and a half of D has
    # no other label on a log axis.
    plot_style.plain_log_ticks(axes.yaxis)
    low, high = min(difference + [0.5]), max(difference + [2])
    axes.set_ylim(low / 1.3, high * 1.3)
    axes.set_xlabel("nodes of the diffusion mesh")
    axes.set_ylabel("difference from the extrapolated DM* [%]")
    axes.grid(alpha=0.3, which="both")
    axes.legend()
    plot_style.save(figure, picture)


if __name__ == "__main__":
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    main(sys.argv[1], sys.argv[2])
