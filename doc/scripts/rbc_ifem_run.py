"""Reading the output directory of an rbc-ifem run, for the plot and render
scripts beside this file.

A run (`build/rbc-ifem prm/X.prm`) writes into its `Output directory`:
CSV tables (dm.csv, cells.csv, shear.csv, ...), .pvd series that list the
VTU/PVTU files of a field against time (cell_0.pvd, flow.pvd,
diffusion_membranes.pvd, ...), and the parameters.prm it ran with. A study
(`Experiment = flowing layouts`, `shear`) keeps one such directory per run
below its own. Usage, from the repository's root:

    import sys; sys.path.insert(0, "doc/scripts")
    from rbc_ifem_run import Run

    run = Run("output/default")
    dm = run.table("dm.csv")                  # [{"time": 0.0, "dm_total": 4.3, ...}, ...]
    cell = run.table("cells.csv", cell=0)     # the rows of cell 0 only
    for time, path in run.series("cell_0.pvd"):
        ...                                   # (time [s], file of that time)
    membrane = run.dataset(run.last("diffusion_membranes.pvd"))  # a vtk data set
    print(run.parameter("Time step"))        # `set Time step = ...` of parameters.prm
    for case in Run("output/shear_capsule").runs("ca_*"):   # a study's runs, Ca in order
        print(case.name, case.table("shear.csv")[-1]["taylor_deformation"])

A script that computes a table the pages show adds it to doc/results/
with add_results(name, header, rows) (doc/results/README.md).

The same are functions of a path: read_table(path), read_series(path),
read_dataset(path), read_parameter(path, name); parse_table(text) reads a
table a program printed. Numbers in a table become floats, text (a
layout's name, a reference's source) stays text, and empty fields (min_gap of a lone cell, wall_gap in the shear box) are left
out of their row: test with `"min_gap" in row`. read_dataset needs
python3-paraview, the rest only Python (`scripts/install-packages.sh --docs`).
"""
import csv
import datetime
import glob
import io
import os
import re
import subprocess
import sys
import xml.etree.ElementTree as ElementTree

RESULTS = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "results")


def add_results(name, header, rows):
    """Append ROWS (lists of values, in the order of the list HEADER) to
    doc/results/NAME.csv, each after the commit of the repository, the date
    and time and the command that made it (the columns commit, date and
    source of doc/results/README.md); the file and its header row are
    created if missing. RBC_IFEM_RESULTS names another folder. Returns the
    file's path."""
    folder = os.environ.get("RBC_IFEM_RESULTS", RESULTS)
    root = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..")
    try:
        commit = subprocess.run(["git", "-C", root, "rev-parse", "--short", "HEAD"],
                                capture_output=True, text=True, check=True).stdout.strip()
    except (OSError, subprocess.CalledProcessError):
        commit = "unknown"
    date = datetime.datetime.now().strftime("%Y-%m-%d %H:%M")
    source = " ".join(["doc/scripts/" + os.path.basename(sys.argv[0])] + sys.argv[1:])
    path = os.path.join(folder, name + ".csv")
    os.makedirs(folder, exist_ok=True)
    new = not os.path.exists(path) or os.path.getsize(path) == 0
    with open(path, "a", newline="", encoding="utf-8") as f:
        writer = csv.writer(f, lineterminator="\n")
        if new:
            writer.writerow(["commit", "date", "source"] + list(header))
        for row in rows:
            writer.writerow([commit, date, source] + list(row))
    return path


def _value(text):
    try:
        return float(text)
    except ValueError:
        return text


def parse_table(text, cell=None):
    """The rows of a CSV table given as TEXT (a program's output), as
    read_table gives them."""
    rows = [{k: _value(v) for k, v in row.items() if v not in ("", None)}
            for row in csv.DictReader(io.StringIO(text))]
    return [r for r in rows if cell is None or r.get("cell") == cell]


def read_table(path, cell=None):
    """The rows of the CSV file PATH as dicts, numbers as floats, text as
    text, empty fields left out; only the rows of CELL if given."""
    with open(path, newline="") as f:
        return parse_table(f.read(), cell)


def read_series(path):
    """(time, file) of every data set of the .pvd file PATH, in its order;
    the files as paths (relative to the .pvd's folder in the file, joined
    here). `Experiment = stretching` writes the bead force as the time."""
    folder = os.path.dirname(path)
    root = ElementTree.parse(path).getroot()
    return [(float(entry.get("timestep")), os.path.join(folder, entry.get("file")))
            for entry in root.iter("DataSet")]


def read_dataset(path):
    """The vtk data set in the .vtu or .pvtu file PATH. deal.II writes every
    field, cell data too, as point data."""
    import vtk  # here: the CSV readers do without python3-paraview
    reader = vtk.vtkXMLGenericDataObjectReader()
    reader.SetFileName(path)
    reader.Update()
    if reader.GetOutput() is None:
        raise OSError(f"cannot read {path}")
    return reader.GetOutput()


def read_parameter(path, name):
    """The value of the first `set NAME = value` in the parameter file PATH,
    as a float if it is a number (deal.II's subsections are not told apart)."""
    pattern = re.compile(r"\s*set\s+" + re.escape(name) + r"\s*=\s*([^#]*)")
    with open(path) as f:
        for line in f:
            match = pattern.match(line)
            if match:
                return _value(match.group(1).strip())
    raise KeyError(f"{name} not in {path}")


class Run:
    """The output directory of one run."""

    def __init__(self, directory):
        self.directory = directory.rstrip("/") or "/"
        self.name = os.path.basename(self.directory)

    def path(self, name):
        return os.path.join(self.directory, name)

    def has(self, name):
        return os.path.exists(self.path(name))

    def table(self, name, cell=None):
        """The rows of the run's CSV table NAME (see read_table)."""
        return read_table(self.path(name), cell)

    def series(self, name):
        """(time, file) of the run's .pvd series NAME (see read_series)."""
        return read_series(self.path(name))

    def last(self, name):
        """The file of the last entry of the .pvd series NAME."""
        return self.series(name)[-1][1]

    def dataset(self, path_or_name):
        """The vtk data set of a file, given as a path or a name in the run."""
        path = path_or_name if os.path.exists(path_or_name) else self.path(path_or_name)
        return read_dataset(path)

    def parameter(self, name):
        """A value of the parameters.prm the run wrote (see read_parameter)."""
        return read_parameter(self.path("parameters.prm"), name)

    def runs(self, pattern="*"):
        """The runs of a study below this one whose folder names match
        PATTERN (glob), sorted by name with the numbers in it compared as
        numbers: ca_0.0125 before ca_0.1, uniform_5_1 before uniform_11_1."""
        def key(run):
            return [(0, float(p), "") if re.fullmatch(r"[0-9]+(\.[0-9]*)?", p) else (1, 0., p)
                    for p in run.name.split("_")]
        found = [Run(d) for d in glob.glob(self.path(pattern)) if os.path.isdir(d)]
        return sorted(found, key=key)

    def __repr__(self):
        return f"Run({self.directory!r})"
