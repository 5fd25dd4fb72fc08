"""The one matplotlib style of the doc/scripts/plot_*.py scripts: DejaVu Sans (it has
µ, ⁻, ³ and γ̇), text readable at the size the docs show the pictures, a
light grid, legends that let the curves show through, 150 dots per inch.
A value axis starts at zero; where a change of a few per cent is the
point, it may start above, marked broken (the usual diagonal marks on the
spine at its foot), and the page's caption says so.

    import plot_style
    plt = plot_style.pyplot()      # matplotlib.pyplot on the Agg backend, styled
    ...
    plot_style.plain_log_ticks(axes.yaxis)   # for an axis set_yscale("log")
    plot_style.from_zero(axes)               # the y axis from 0 (or up to 0 if all < 0)
    plot_style.mark_broken(axes)             # a y axis that does not start at 0
    plot_style.save(figure, picture)

Needs python3-matplotlib (`scripts/install-packages.sh --docs`).
"""
import matplotlib

DPI = 150


def pyplot():
    """matplotlib.pyplot, drawing to files only, with the style set."""
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    plt.rcParams.update({
        "font.family": "DejaVu Sans",
        "font.size": 10,
        "axes.titlesize": 11,
        "axes.labelsize": 10,
        "legend.fontsize": 8,
        "legend.framealpha": 0.85,
        "xtick.labelsize": 9,
        "ytick.labelsize": 9,
        "axes.grid": True,
        "axes.grid.which": "major",
        "grid.alpha": 0.3,
        "lines.markersize": 4,
        "savefig.dpi": DPI,
        "savefig.bbox": "tight",
        "savefig.pad_inches": 0.05,
    })
    return plt


def plain_log_ticks(axis):
    """Label a log AXIS (axes.yaxis, axes.xaxis) at 1, 2 and 5 of each
    decade, as plain numbers (0.5, 1, 2) instead of powers of ten: an axis
    that spans a decade or less then still has labels."""
    from matplotlib.ticker import FuncFormatter, LogLocator, NullFormatter
    axis.set_major_locator(LogLocator(subs=(1.0, 2.0, 5.0)))
    axis.set_major_formatter(FuncFormatter(lambda value, _: f"{value:g}"))
    axis.set_minor_formatter(NullFormatter())


def from_zero(axes):
    """Stretch the y axis of AXES to take in zero: from 0 for values ≥ 0,
    up to 0 for values ≤ 0 (a change that is a loss)."""
    low, high = axes.get_ylim()
    if low > 0:
        axes.set_ylim(0, high)
    elif high < 0:
        axes.set_ylim(low, 0)


def mark_broken(axes, sides=("left",)):
    """The y axis of AXES does not start at zero: two short diagonal
    strokes across the foot of each spine of SIDES ("left", "right": a twin
    axis shares the lower corners), with the spine cut between them. The
    marks are Line2D artists: build a legend from axes.get_lines() first."""
    from matplotlib.lines import Line2D
    foot, gap, size = 0.045, 0.022, 9  # [of the axes' height], stroke [points]
    ends = [foot - gap / 2, foot + gap / 2]
    for side in sides:
        x = 0.0 if side == "left" else 1.0
        # The cut: a white stroke over the spine, under the diagonals.
        axes.add_artist(Line2D([x, x], ends, transform=axes.transAxes, color="white",
                               linewidth=3, clip_on=False, zorder=10))
        axes.add_artist(Line2D([x, x], ends, transform=axes.transAxes, linestyle="none",
                               marker=[(-1, -0.5), (1, 0.5)], markersize=size,
                               markeredgewidth=1, color="black", clip_on=False, zorder=11))


def save(figure, picture):
    """Write FIGURE to PICTURE and say so."""
    figure.savefig(picture)
    print("wrote", picture)
