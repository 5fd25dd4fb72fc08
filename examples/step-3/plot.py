"""The figure of examples/step-3/README.md: DM and the deformation index of
the cell against time, from the step-3.csv the program writes.

    /usr/bin/python3 examples/step-3/plot.py step-3-build/output/step-3.csv examples/step-3/step-3.png

Run from rbc-ifem's clone: it uses doc/scripts/rbc_ifem_run.py and doc/scripts/plot_style.py
(python3-matplotlib: scripts/install-packages.sh --docs)."""
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "doc", "scripts"))
import plot_style  # noqa: E402
from rbc_ifem_run import read_table  # noqa: E402


def main(table, picture):
    rows = read_table(table)
    time = [1e3 * row["time"] for row in rows]
    plt = plot_style.pyplot()
    figure, (dm, shape) = plt.subplots(1, 2, figsize=(9, 3.4), gridspec_kw={"wspace": 0.35})
    dm.plot(time, [row["dm_total"] for row in rows], "o-")
    dm.set_xlabel("t [ms]")
    dm.set_ylabel("DM [µm³ s⁻¹ Torr⁻¹]")
    shape.plot(time, [row["deformation_index"] for row in rows], "o-")
    shape.set_xlabel("t [ms]")
    shape.set_ylabel("deformation index")
    plot_style.save(figure, picture)


if __name__ == "__main__":
    main(*sys.argv[1:3])
