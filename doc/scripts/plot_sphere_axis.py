#!/usr/bin/env python3
"""Plot the plasma's axial velocity along the capillary's axis through the
held sphere (doc/validation.md, Section 2), from the runs of
benchmarks/sphere_towed.sh.

    /usr/bin/python3 doc/scripts/plot_sphere_axis.py OUTPUT_DIRECTORY PICTURE.png

Two panels, (a) the towed sphere (walls moving past it at U = 1000 µm/s)
and (b) the sphere held in Poiseuille flow, each on the fluid meshes the
benchmark ran (OUTPUT_DIRECTORY/{towed,held}_{1,2,3}): the velocity u_x on the axis, from
the last file of flow.pvd, against the distance from the sphere's centre. The
sphere is held, so the plasma inside it should be at rest. Prints the mean
u_x over the inner half of the diameter and adds it to
doc/results/sphere_axis_velocity.csv (rbc_ifem_run.add_results). Needs python3-matplotlib and
python3-paraview (`scripts/install-packages.sh --docs`).
"""
import os
import sys

from vtkmodules.vtkFiltersCore import vtkProbeFilter
from vtkmodules.vtkFiltersSources import vtkLineSource
from vtkmodules.util.numpy_support import vtk_to_numpy

import plot_style
from rbc_ifem_run import Run, add_results

plt = plot_style.pyplot()

SAMPLES = 2001


def sphere(run):
    """Centre x and radius of the sphere at the end of a run (cells.csv)."""
    last = run.table("cells.csv")[-1]
    return last["frame_x"], last["max_radius"]


def axial_velocity(run, length):
    """x and u_x at SAMPLES points on the axis, from the run's last flow output."""
    line = vtkLineSource()
    line.SetPoint1(0., 0., 0.)
    line.SetPoint2(length, 0., 0.)
    line.SetResolution(SAMPLES - 1)
    probe = vtkProbeFilter()
    probe.SetInputConnection(line.GetOutputPort())
    probe.SetSourceData(run.dataset(run.last("flow.pvd")))
    probe.Update()
    data = probe.GetOutput()
    x = vtk_to_numpy(data.GetPoints().GetData())[:, 0]
    u = vtk_to_numpy(data.GetPointData().GetArray("velocity"))[:, 0]
    return x, u


def main(directory, picture):
    means = []
    figure, axes = plt.subplots(1, 2, figsize=(10, 3.8), sharey=False, layout="constrained")
    for axis, case, title in zip(axes, ("towed", "held"),
                                 ("(a) towed: walls moving past at U = 1000 µm/s",
                                  "(b) held in Poiseuille flow, U_c = 1000 µm/s")):
        for level, h in ((1, 0.625), (2, 0.3125), (3, 0.15625)):
            if not os.path.isdir(os.path.join(directory, f"{case}_{level}")):
                continue
            run = Run(os.path.join(directory, f"{case}_{level}"))
            centre, radius = sphere(run)
            x, u = axial_velocity(run, 2 * centre)
            s = (x - centre) / radius
            core = abs(s) < 0.5
            print(f"{case}_{level}: h = {h} µm, mean u_x over |x - c| < a/2 = {u[core].mean():.1f} µm/s")
            means.append([case, h, f"{u[core].mean():.1f}"])
            axis.plot(s, u, label=f"h = {h} µm")
        axis.axvspan(-1, 1, color="0.9", zorder=0)
        axis.axhline(0, color="0.5", linewidth=0.5)
        axis.set_xlim(-3, 3)
        axis.set_xlabel("(x − centre) / a")
        axis.set_title(title, fontsize=10)
        axis.legend()
    axes[0].set_ylabel("u_x on the axis [µm/s] (frame of the sphere)")
    plot_style.save(figure, picture)
    print("added to", add_results("sphere_axis_velocity",
                                  ["case", "fluid h at the sphere [µm]",
                                   "mean u_x over |x - c| < a/2 [µm/s]"], means))


if __name__ == "__main__":
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    main(*sys.argv[1:])
