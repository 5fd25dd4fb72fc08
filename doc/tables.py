"""Reading rbc-ifem's CSV tables, for the plot scripts beside this file."""
import csv


def read(path, cell=None):
    """The rows of a CSV file as dicts of floats, only those of CELL if given.

    Empty fields (min_gap of a lone cell, wall_gap in the shear box) are left
    out of their row."""
    with open(path) as f:
        rows = [{k: float(v) for k, v in row.items() if v != ""}
                for row in csv.DictReader(f)]
    return [r for r in rows if cell is None or r["cell"] == cell]
