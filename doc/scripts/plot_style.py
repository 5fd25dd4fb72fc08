"""The one matplotlib style of the doc/scripts/plot_*.py scripts: DejaVu Sans (it has
µ, ⁻, ³ and γ̇), text readable at the size the docs show the pictures, a
light grid, legends that let the curves show through, 150 dots per inch.

    import plot_style
    plt = plot_style.pyplot()      # matplotlib.pyplot on the Agg backend, styled
    ...
    plot_style.plain_log_ticks(axes.yaxis)   # for an axis set_yscale("log")
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


def save(figure, picture):
    """Write FIGURE to PICTURE and say so."""
    figure.savefig(picture)
    print("wrote", picture)
