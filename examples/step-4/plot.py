"""The figure of examples/step-4/README.md: the cell's DM, its membrane area
and their ratio, each relative to its value at t = 0, from the
uptake_per_area.csv that step-4's observer writes.

    /usr/bin/python3 examples/step-4/plot.py step-4-build/output/uptake_per_area.csv examples/step-4/step-4.png

Run from rbc-ifem's clone: it uses doc/scripts/rbc_ifem_run.py and doc/scripts/plot_style.py
(python3-matplotlib: scripts/install-packages.sh --docs)."""
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "doc", "scripts"))
import plot_style  # noqa: E402
from rbc_ifem_run import read_table  # noqa: E402


def main(table, picture):
    rows = read_table(table, cell=0)
    time = [1e3 * row["time"] for row in rows]
    plt = plot_style.pyplot()
    figure, axes = plt.subplots(figsize=(5.5, 3.6))
    for column, label in (("dm", "DM of the cell"), ("area", "membrane area A"),
                          ("dm_per_area", "DM / A")):
        start = rows[0][column]
        axes.plot(time, [100 * (row[column] / start - 1) for row in rows], "o-", label=label)
    axes.set_xlabel("t [ms]")
    axes.set_ylabel("change from t = 0 [%]")
    axes.legend()
    plot_style.save(figure, picture)


if __name__ == "__main__":
    main(*sys.argv[1:3])
