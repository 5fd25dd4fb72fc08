#!/usr/bin/env python3
"""Draw a flowing run (`Experiment = flow` with `Immersed cells/Enabled`, or
one run folder of a `flowing layouts` or `shear` study), any number of
cells, from its output directory:

    /usr/bin/python3 doc/scripts/plot_run.py RUN [--save PICTURE.png] [--time T]

Panels against time [ms]: (a) DM of the segment and (b) DM of each cell
(dm.csv); (c) the smallest gap of each cell to another cell (solid) and to
the capillary wall (dashed) (cells.csv min_gap, wall_gap); (d) each cell's
deformation index; (e) each cell's volume and area change from its
reference cell; (f) the largest local area change on each membrane, a check
of the membrane mesh (cells.csv). With --time T [s, as the tables: 0.006
for 6 ms] a last row shows the membranes at the output time nearest T,
seen from +z (the side view of the x-y plane, in the moving frame of the
run), each membrane element coloured by its force density |f| [pN/µm²]
(cell_C.pvd). The picture goes to --save, by default RUN/run.png.

An axis that does not start at zero has the break marked on it (//) and
says so in its label. Needs python3-matplotlib, and python3-paraview for --time
(`scripts/install-packages.sh --docs`).
"""
import argparse
import math
import os
import sys

import plot_style
from rbc_ifem_run import Run

# An axis starts at zero unless its data span less than this fraction of
# their largest magnitude; then it shows the data's range and is marked.
ZOOM_BELOW = 0.3


class NotAFlowingRun(Exception):
    pass


def fail(message):
    sys.exit(f"plot_run.py: error: {message}")


def is_flowing(run):
    """Whether RUN's cells.csv is a flowing run's (its first column time)."""
    try:
        with open(run.path("cells.csv")) as f:
            return f.readline().startswith("time,")
    except OSError:
        return False


def cell_tables(run):
    """{cell: rows of cells.csv} of a flowing run, or NotAFlowingRun naming
    the file that is missing or of another experiment."""
    path = run.path("cells.csv")
    if not os.path.isdir(run.directory):
        raise NotAFlowingRun(f"{run.directory} is not a directory")
    if not os.path.exists(path):
        below = [r for r in run.runs() if is_flowing(r)]
        hint = (f"; the runs of a study are in the folders below it: give one, such as "
                f"{below[0].directory}" if below else
                "; plot_run.py draws the output directory of a flowing run "
                "(Experiment = flow with Immersed cells/Enabled = true)")
        raise NotAFlowingRun(f"{path} does not exist{hint}")
    with open(path) as f:
        header = f.readline().strip().split(",")
    needed = ["time", "cell", "deformation_index", "volume_change", "area_change"]
    if not all(name in header for name in needed):
        raise NotAFlowingRun(
            f"{path} is not the cells.csv of a flowing run (its columns "
            f"{','.join(header)} lack {', '.join(n for n in needed if n not in header)}): "
            "the run is not Experiment = flow with Immersed cells/Enabled = true")
    rows = run.table("cells.csv")
    if not rows:
        raise NotAFlowingRun(f"{path} has no rows")
    cells = {}
    for row in rows:
        cells.setdefault(int(row["cell"]), []).append(row)
    return cells


def dm_table(run):
    """The rows of dm.csv, or None (a run without a Diffusion interval)."""
    if not run.has("dm.csv"):
        return None
    rows = run.table("dm.csv")
    path = run.path("dm.csv")
    if rows and ("time" not in rows[0] or "dm_total" not in rows[0]):
        raise NotAFlowingRun(f"{path} has no columns time and dm_total: "
                             "not the dm.csv of a flowing run")
    return rows


def colours(n):
    """One colour per cell: tab10 up to ten cells, else viridis sampled."""
    from matplotlib import colormaps
    if n <= 10:
        return [colormaps["tab10"](i) for i in range(n)]
    return [colormaps["viridis"](i / (n - 1)) for i in range(n)]


def set_y_range(axes, values, label, include=(0.0,)):
    """Let the y axis of AXES show zero (and INCLUDE) unless VALUES span so
    little of their magnitude that the change would not show; then zoom in
    on them, mark the break and say so in LABEL."""
    values = [v for v in values if math.isfinite(v)]
    if not values:
        axes.set_ylabel(label)
        return
    low, high = min(values), max(values)
    magnitude = max(abs(low), abs(high))
    if magnitude > 0 and (high - low) < ZOOM_BELOW * magnitude and low * high > 0:
        pad = 0.15 * (high - low) if high > low else 0.01 * magnitude
        axes.set_ylim(low - pad, high + 2 * pad)
        plot_style.mark_broken(axes)
        axes.set_ylabel(label + "\n(axis not from 0)")
    else:
        low, high = min([low] + list(include)), max([high] + list(include))
        pad = 0.06 * (high - low) if high > low else 1.0
        axes.set_ylim(low - (pad if low < 0 else 0), high + 2 * pad)
        axes.set_ylabel(label)


def change_text(first, last):
    return f"{first:.4g} → {last:.4g} ({100 * (last / first - 1):+.1f}%)" if first else ""


def plot_dm(total_axes, cell_axes, dm, n_cells, palette):
    if not dm:
        for axes in (total_axes, cell_axes):
            axes.text(0.5, 0.5, "no dm.csv:\nthe run had\nImmersed cells/Diffusion interval = 0",
                      ha="center", va="center", transform=axes.transAxes)
        total_axes.set_ylabel("DM [µm³ s⁻¹ Torr⁻¹]")
        cell_axes.set_ylabel("DM per cell [µm³ s⁻¹ Torr⁻¹]")
        return
    time = [1e3 * r["time"] for r in dm]
    total = [r["dm_total"] for r in dm]
    total_axes.plot(time, total, "o-", color="black",
                    label="segment: " + change_text(total[0], total[-1]))
    set_y_range(total_axes, total, "DM [µm³ s⁻¹ Torr⁻¹]")
    total_axes.legend(loc="upper right")
    values = []
    for c in range(n_cells):
        column = f"dm_cell_{c}"
        points = [(1e3 * r["time"], r[column]) for r in dm if column in r]
        if not points:
            continue
        values += [v for _, v in points]
        cell_axes.plot([p[0] for p in points], [p[1] for p in points], "o-",
                       color=palette[c],
                       label=f"cell {c}: " + change_text(points[0][1], points[-1][1]))
    set_y_range(cell_axes, values, "DM per cell [µm³ s⁻¹ Torr⁻¹]")
    cell_axes.legend(loc="upper right", ncol=1 if n_cells <= 4 else 2)


def plot_cells(axes, cells, palette):
    gaps, shape, change, local = axes
    gap_values, index_values, change_values, local_values = [], [], [], []
    for c, rows in sorted(cells.items()):
        time = [1e3 * r["time"] for r in rows]
        colour = palette[c]
        for name, style in (("min_gap", "-"), ("wall_gap", "--")):
            points = [(1e3 * r["time"], r[name]) for r in rows if name in r]
            if points:
                gaps.plot([p[0] for p in points], [p[1] for p in points], style,
                          color=colour)
                gap_values += [p[1] for p in points]
        index = [r["deformation_index"] for r in rows]
        shape.plot(time, index, "o-", color=colour, label=f"cell {c}")
        index_values += index
        volume = [100 * r["volume_change"] for r in rows]
        area = [100 * r["area_change"] for r in rows]
        change.plot(time, volume, "-", color=colour)
        change.plot(time, area, "--", color=colour)
        change_values += volume + area
        if "local_area_change" in rows[0]:
            values = [100 * r["local_area_change"] for r in rows]
            local.plot(time, values, "o-", color=colour)
            local_values += values
    gaps.plot([], [], "-", color="grey", label="to the nearest cell (min_gap)")
    gaps.plot([], [], "--", color="grey", label="to the wall (wall_gap)")
    if gap_values:
        gaps.legend(loc="best")
    else:
        gaps.text(0.5, 0.5, "no gaps: one cell,\nand no wall (the shear box)",
                  ha="center", va="center", transform=gaps.transAxes)
    set_y_range(gaps, gap_values, "smallest gap [µm]")
    gaps.set_title("(c) gaps")
    set_y_range(shape, index_values, "deformation index (L − 2r)/(L + 2r)")
    shape.set_title("(d) shape: −0.51 the disc facing the flow")
    change.plot([], [], "-", color="grey", label="volume")
    change.plot([], [], "--", color="grey", label="area")
    change.axhline(0, color="black", linewidth=0.8)
    change.legend(loc="best")
    set_y_range(change, change_values, "change from the reference cell [%]")
    change.set_title("(e) volume and area of each cell")
    if local_values:
        set_y_range(local, local_values, "largest local area change [%]")
    else:
        local.text(0.5, 0.5, "no local_area_change column", ha="center",
                   va="center", transform=local.transAxes)
    local.set_title("(f) local area change (mesh check)")


def membrane_polygons(dataset):
    """The membrane elements of a vtk data set as (polygons in x-y, depth z
    of each, |force_density| of each [pN/µm²])."""
    points = dataset.GetPoints()
    forces = dataset.GetPointData().GetArray("force_density")
    if forces is None:
        forces = dataset.GetPointData().GetArray("force")
        if forces is None:
            raise NotAFlowingRun("the membranes carry no force_density")
    polygons, depths, magnitudes = [], [], []
    for i in range(dataset.GetNumberOfCells()):
        ids = dataset.GetCell(i).GetPointIds()
        # VTK's order: around the element.
        corners = [points.GetPoint(ids.GetId(k)) for k in range(ids.GetNumberOfIds())]
        polygons.append([(p[0], p[1]) for p in corners])
        depths.append(sum(p[2] for p in corners) / len(corners))
        magnitudes.append(sum(math.sqrt(sum(forces.GetComponent(ids.GetId(k), j) ** 2
                                            for j in range(forces.GetNumberOfComponents())))
                              for k in range(ids.GetNumberOfIds())) / ids.GetNumberOfIds())
    return polygons, depths, magnitudes


def plot_membranes(figure, axes, run, cells, time):
    """The membranes at the output time nearest TIME [s], side view."""
    from matplotlib.collections import PolyCollection
    import matplotlib.colors

    series = {}
    for c in sorted(cells):
        name = f"cell_{c}.pvd"
        if not run.has(name):
            raise NotAFlowingRun(f"{run.path(name)} does not exist: the run wrote no membranes "
                                 "of cell {c} (needed for --time)")
        series[c] = run.series(name)
    first = series[min(series)]
    start, end = first[0][0], first[-1][0]
    spacing = max((b[0] - a[0] for a, b in zip(first, first[1:])), default=0.0)
    slack = 1e-9 * max(abs(end), 1e-3)
    if not start - slack <= time <= end + slack:
        fail(f"--time {time:g} s is outside the run: its membranes "
             f"({run.path(f'cell_{min(series)}.pvd')}) run from {start:g} to {end:g} s")
    polygons, depths, magnitudes = [], [], []
    shown = None
    for c, entries in series.items():
        shown, path = min(entries, key=lambda entry: abs(entry[0] - time))
        p, d, m = membrane_polygons(run.dataset(path))
        polygons += p
        depths += d
        magnitudes += m
    if abs(shown - time) > 1e-12:
        print(f"plot_run.py: the membranes are written every {1e3 * spacing:g} ms: "
              f"showing t = {shown:g} s, the output nearest {time:g} s")
    data = run.dataset(series[min(series)][[e[0] for e in first].index(shown)][1])
    offset_array = data.GetFieldData().GetArray("FRAME_OFFSET")
    offset = offset_array.GetValue(0) if offset_array is not None else 0.0

    length = float(run.parameter("Capillary length"))
    radius = float(run.parameter("Capillary radius"))
    periodic = str(run.parameter("Periodic")) == "true"
    # Painter's algorithm: the elements farthest from the viewer (at +z) first.
    order = sorted(range(len(polygons)), key=lambda i: depths[i])
    values = sorted(magnitudes)
    top = values[min(len(values) - 1, int(0.99 * len(values)))]
    norm = matplotlib.colors.Normalize(vmin=0.0, vmax=top)
    shifts = (-length, 0.0, length) if periodic else (0.0,)
    for shift in shifts:  # a periodic segment shows the images across its ends
        collection = PolyCollection(
            [[(x + shift, y) for x, y in polygons[i]] for i in order],
            array=[magnitudes[i] for i in order], cmap="viridis", norm=norm,
            edgecolors="face", linewidths=0.1)
        axes.add_collection(collection)
    for y in (-radius, radius):
        axes.axhline(y, color="black", linewidth=1.5)
    axes.set_xlim(0.0, length)
    axes.set_ylim(-radius * 1.08, radius * 1.08)
    axes.set_aspect("equal")
    axes.grid(False)
    axes.set_xlabel("x in the moving frame [µm] (laboratory x = this + "
                    f"{offset:.2f} µm)")
    axes.set_ylabel("y [µm]")
    axes.set_title(f"(g) the membranes at t = {1e3 * shown:g} ms, seen from +z; the flow "
                   f"goes to +x{' (a periodic segment: a cell across an end shows on both sides)' if periodic else ''}")
    clipped = top < values[-1]
    bar = figure.colorbar(collection, ax=axes, location="right", shrink=0.9,
                          extend="max" if clipped else "neither", pad=0.01,
                          panchor=(0.5, 0.5))
    bar.set_label("force density |f| [pN/µm²]" +
                  (f"\n(above {top:.3g}: the top 1%)" if clipped else ""))


def main():
    parser = argparse.ArgumentParser(
        description="Draw a flowing run of rbc-ifem: DM, gaps, shape and volume "
                    "against time, and with --time the membranes.")
    parser.add_argument("run", metavar="RUN", help="the run's output directory")
    parser.add_argument("--save", metavar="PICTURE",
                        help="the picture to write (default RUN/run.png)")
    parser.add_argument("--time", metavar="T", type=float,
                        help="also draw the membranes at the output time nearest T [s]")
    arguments = parser.parse_args()
    run = Run(arguments.run)
    picture = arguments.save or run.path("run.png")
    try:
        cells = cell_tables(run)
        dm = dm_table(run)
        if arguments.time is not None and not run.has("parameters.prm"):
            raise NotAFlowingRun(f"{run.path('parameters.prm')} does not exist (needed for --time)")
    except (NotAFlowingRun, OSError, KeyError, ValueError) as error:
        fail(str(error))

    plt = plot_style.pyplot()
    rows = 3 if arguments.time is not None else 2
    figure = plt.figure(figsize=(14, 7.2 if rows == 2 else 12.5), layout="constrained")
    grid = figure.add_gridspec(rows, 3, height_ratios=[1, 1, 1.6][:rows])
    panels = [figure.add_subplot(grid[r, c]) for r in range(2) for c in range(3)]
    palette = colours(max(cells) + 1)
    plot_dm(panels[0], panels[1], dm, max(cells) + 1, palette)
    panels[0].set_title("(a) DM of the segment")
    panels[1].set_title("(b) DM of each cell")
    plot_cells(panels[2:], cells, palette)
    end = 1e3 * max(r["time"] for rows in cells.values() for r in rows)
    for axes in panels:
        axes.set_xlabel("time [ms]")
        axes.set_xlim(0.0, 1.02 * end if end > 0 else 1.0)
    if arguments.time is not None:
        try:
            plot_membranes(figure, figure.add_subplot(grid[2, :]), run, cells, arguments.time)
        except (NotAFlowingRun, OSError, KeyError) as error:
            fail(str(error))
    figure.suptitle(f"{run.name}: {len(cells)} cell{'s' if len(cells) > 1 else ''}, "
                    f"to t = {end:g} ms")
    plot_style.save(figure, picture)


if __name__ == "__main__":
    main()
