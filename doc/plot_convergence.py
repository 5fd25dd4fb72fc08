#!/usr/bin/env python3
"""Plot convergence.csv of an `Experiment = mesh convergence` run: the
difference of DM from its Richardson-extrapolated limit against the number
of mesh nodes, with the 2% and 0.5% lines.

    /usr/bin/python3 doc/plot_convergence.py output/mesh_convergence/convergence.csv doc/figures/mesh_convergence.png

Needs python3-matplotlib (`scripts/install-packages.sh --docs`).
"""
import csv
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt


def main(path, picture):
    with open(path) as f:
        rows = [{k: float(v) for k, v in row.items()} for row in csv.DictReader(f)]
    nodes = [r["n_nodes"] for r in rows]
    difference = [100 * r["difference_from_limit"] for r in rows]
    figure, axes = plt.subplots(figsize=(6, 4))
    axes.loglog(nodes, difference, "o-", label="|DM - DM*| / DM*")
    for level, style in ((2, "--"), (0.5, ":")):
        axes.axhline(level, color="grey", linestyle=style, label=f"{level}%")
    for r, d in zip(rows, difference):
        axes.annotate(f"level {int(r['level'])}", (r["n_nodes"], d),
                      textcoords="offset points", xytext=(5, 5), fontsize=8)
    axes.set_xlabel("nodes of the diffusion mesh")
    axes.set_ylabel("difference from the extrapolated DM* [%]")
    axes.grid(alpha=0.3, which="both")
    axes.legend()
    figure.tight_layout()
    figure.savefig(picture, dpi=120)


if __name__ == "__main__":
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    main(sys.argv[1], sys.argv[2])
