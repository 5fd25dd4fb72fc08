#!/usr/bin/env python3
"""Plot the axial and transverse diameters of stretched cells against the
bead force, one pair of curves per stretch.csv of `Experiment = stretching`,
over the optical-tweezers measurements of Mills et al. (2004) when a file of
them is given with --experiment. The diameter axis starts at 0.

    /usr/bin/python3 doc/scripts/plot_stretch.py PICTURE.png [--experiment mills.csv] LABEL=stretch.csv ...

The experiment file has the columns force, transverse_diameter,
axial_diameter and their low/high ends (doc/results/mills2004_stretching.csv).
Needs python3-matplotlib (`scripts/install-packages.sh --docs`).
"""
import sys

import plot_style
from rbc_ifem_run import read_table

plt = plot_style.pyplot()


def plot_experiment(axes, path):
    rows = read_table(path)
    force = [r["force"] for r in rows]
    for name, marker in (("axial", "s"), ("transverse", "o")):
        mean = [r[f"{name}_diameter"] for r in rows]
        low = [m - r[f"{name}_low"] for m, r in zip(mean, rows)]
        high = [r[f"{name}_high"] - m for m, r in zip(mean, rows)]
        axes.errorbar(force, mean, yerr=[low, high], fmt=marker, color="black",
                      mfc="white", capsize=3,
                      label=f"Mills et al. 2004: {name}")


def main(picture, experiment, runs):
    figure, axes = plt.subplots(figsize=(6.5, 4.8), layout="constrained")
    if experiment:
        plot_experiment(axes, experiment)
    for (label, path), colour in zip(runs, ("tab:red", "tab:blue", "tab:green")):
        rows = read_table(path)
        force = [r["force"] for r in rows]
        axes.plot(force, [r["axial_diameter"] for r in rows], "-", color=colour,
                  label=f"{label}: axial")
        axes.plot(force, [r["transverse_diameter"] for r in rows], "--", color=colour,
                  label=f"{label}: transverse")
    axes.set_xlabel("force on each bead F [pN]")
    axes.set_ylabel("diameter [µm]")
    plot_style.from_zero(axes)
    axes.legend()
    plot_style.save(figure, picture)


if __name__ == "__main__":
    arguments = sys.argv[1:]
    experiment = None
    if "--experiment" in arguments:
        k = arguments.index("--experiment")
        experiment = arguments[k + 1]
        del arguments[k:k + 2]
    if len(arguments) < 2 or any("=" not in a for a in arguments[1:]):
        sys.exit(__doc__)
    main(arguments[0], experiment, [a.split("=", 1) for a in arguments[1:]])
