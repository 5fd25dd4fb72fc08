#!/usr/bin/env python3
"""Write the pages' result tables from the CSV files in doc/results/.

    doc/scripts/tables.py            rewrite every generated table of the pages
    doc/scripts/tables.py --check    change nothing; fail (exit 1), naming the
                                     page, if a page differs from what it would
                                     write
    doc/scripts/tables.py PAGE.md    only these pages
    doc/scripts/tables.py --help     this text

A page (every Markdown file git tracks) marks a generated table so, each
comment at the start of a line (or indented by up to three spaces, in a
list item; the table gets the same indent):

    <!-- table: results/benchmarks/fluid.csv where ranks=2 date=2026-12-04 -->
    | refinements | DoFs | ... |
    |---|---|---|
    | 1 | 9236 | ... |
    <!-- end table -->

and everything between the two comments is this script's: edit the CSV
file or the marker, never the rows. The marker (one comment, which may span
lines) holds the CSV file's path, relative to the page as a Markdown link's
is, then any of

    where NAME=VALUE NAME!=VALUE ...  the rows to show: every condition holds;
                                      VALUE may list alternatives, a|b|c, and
                                      numbers compare as numbers (2 = 2.0);
                                      NAME>NUMBER and NAME<NUMBER too
    columns COLUMN ...                the columns, in order; a COLUMN that is no
                                      column's name is a Python expression of
                                      the columns (their names as variables,
                                      numbers as floats, or c("any name")),
                                      e.g. mean_speed/1000
    headers TEXT ...                  the table's header, one per column
                                      (default: the columns' names)
    formats FORMAT ...                one per column: - (as the file has it),
                                      a Python format spec (.4f  ,d  +.1%), a
                                      spec ending in g%, f% or e% for a
                                      percentage of the value (#.2g% turns
                                      0.0093 into 0.93%), each optionally
                                      after a scale, 1e3*.0f
    empty TEXT                        what an empty or nan value shows
                                      (default: nothing)

Words are split as a shell splits them, so quote a name or a header with
spaces: "peak memory [MB]". Without `columns` a table shows every column of
the file but commit, date and source (doc/results/README.md) and those a
`where NAME=VALUE` fixes. Needs only Python's standard library.
"""
import csv
import math
import os
import re
import shlex
import subprocess
import sys

OPEN = re.compile(r"^( {0,3})<!--\s*table:(.*?)-->", re.S | re.M)
CLOSE = re.compile(r"^ {0,3}<!-- end table -->", re.M)
KEYWORDS = ("where", "columns", "headers", "formats", "empty")
HIDDEN = ("commit", "date", "source")


class TableError(Exception):
    pass


def number(text):
    """The float a CSV field holds, or None."""
    try:
        value = float(text.replace("\u2212", "-"))
    except (AttributeError, ValueError):
        return None
    return value


def parse_marker(text):
    words = shlex.split(text)
    if not words:
        raise TableError("a table marker without a file")
    spec = {"file": words[0], "where": [], "columns": [], "headers": [], "formats": [],
            "empty": ""}
    key = None
    for word in words[1:]:
        if word in KEYWORDS:
            key = word
            continue
        if key is None:
            raise TableError(f"'{word}' after the file: expected one of {', '.join(KEYWORDS)}")
        if key == "empty":
            spec["empty"] = word
        elif key == "where":
            match = re.match(r"(.+?)(!=|=|>|<)(.*)$", word, re.S)
            if not match:
                raise TableError(f"where '{word}': expected NAME=VALUE, NAME!=VALUE, "
                                 "NAME>NUMBER or NAME<NUMBER")
            spec["where"].append((match.group(1), match.group(2), match.group(3).split("|")))
        else:
            spec[key].append(word)
    return spec


def same(field, wanted):
    a, b = number(field), number(wanted)
    if a is not None and b is not None:
        return a == b
    return field == wanted


def format_value(text, fmt, empty):
    value = number(text)
    if text is None or text.strip() == "" or (value is not None and math.isnan(value)):
        return empty
    if fmt in ("", "-") or value is None:
        return text
    scale = 1.0
    if "*" in fmt:
        factor, fmt = fmt.split("*", 1)
        scale = float(factor)
    value *= scale
    if len(fmt) >= 2 and fmt.endswith("%") and fmt[-2] in "gfe":
        return format(100 * value, fmt[:-1]) + "%"
    if fmt.endswith("d"):
        if value != int(value):
            raise TableError(f"'{text}' is no integer for format '{fmt}'")
        value = int(value)
    return format(value, fmt)


def evaluate(expression, row):
    names = {}
    for key, field in row.items():
        if key is not None and key.isidentifier():
            names[key] = number(field) if number(field) is not None else field
    def column(name):
        if name not in row:
            raise TableError(f"column '{expression}': no column '{name}'")
        return number(row[name]) if number(row[name]) is not None else row[name]

    try:
        value = eval(expression, {"__builtins__": {}, "abs": abs, "min": min, "max": max,
                                  "c": column}, names)
    except NameError as error:
        raise TableError(f"column '{expression}': {error}") from error
    except (TypeError, ZeroDivisionError):
        return ""
    return value if isinstance(value, str) else repr(float(value))


def render(spec, page):
    path = os.path.normpath(os.path.join(os.path.dirname(page), spec["file"]))
    if not os.path.isfile(path):
        raise TableError(f"no file {path}")
    with open(path, newline="", encoding="utf-8") as stream:
        reader = csv.DictReader(stream)
        names = reader.fieldnames or []
        rows = list(reader)
    for name, _, _ in spec["where"]:
        if name not in names:
            raise TableError(f"{path} has no column '{name}' (where)")
    def holds(row, name, op, values):
        if op in "<>":
            a, b = number(row[name]), number(values[0])
            return a is not None and b is not None and (a > b if op == ">" else a < b)
        return any(same(row[name], v) for v in values) == (op == "=")

    rows = [row for row in rows if all(holds(row, *condition) for condition in spec["where"])]
    if not rows:
        raise TableError(f"no row of {path} is where the marker asks")
    columns = spec["columns"]
    if not columns:
        fixed = {name for name, op, values in spec["where"] if op == "=" and len(values) == 1}
        columns = [n for n in names if n not in HIDDEN and n not in fixed]
    headers = spec["headers"] or columns
    formats = spec["formats"] or ["-"] * len(columns)
    if len(headers) != len(columns) or len(formats) != len(columns):
        raise TableError(f"{len(columns)} columns, {len(headers)} headers, {len(formats)} formats")

    def cell(text):
        return text.replace("|", "\\|")

    def line(values):
        return "|" + "|".join(f" {v} " if v else " " for v in values) + "|"

    lines = [line(cell(h) for h in headers), "|" + "---|" * len(columns)]
    for row in rows:
        values = []
        for column, fmt in zip(columns, formats):
            text = row[column] if column in names else evaluate(column, row)
            values.append(cell(format_value(text, fmt, spec["empty"])))
        lines.append(line(values))
    return "\n".join(lines) + "\n"


def generate(page, text):
    """The page's text with every marked table written anew."""
    out = []
    position = 0
    for count, match in enumerate(OPEN.finditer(text), start=1):
        if match.start() < position:
            continue
        close = CLOSE.search(text, match.end())
        if close is None:
            raise TableError(f"table {count}: no '<!-- end table -->' at the start of a line")
        try:
            table = render(parse_marker(match.group(2)), page)
        except TableError as error:
            raise TableError(f"table {count}: {error}") from error
        indent = match.group(1)
        out.append(text[position:match.end()])
        out.append("\n" + "".join(indent + line + "\n" for line in table.splitlines()) + indent)
        out.append(close.group(0).lstrip())
        position = close.end()
    out.append(text[position:])
    return "".join(out)


def main(arguments):
    if "--help" in arguments or "-h" in arguments:
        print(__doc__)
        return 0
    check = "--check" in arguments
    pages = [a for a in arguments if a != "--check"]
    root = os.path.normpath(os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", ".."))
    os.chdir(root)
    if not pages:
        listed = subprocess.run(["git", "ls-files", "*.md"], capture_output=True, text=True,
                                check=True).stdout.split()
        pages = [p for p in listed if os.path.isfile(p)]
    failed = False
    n_tables = 0
    for page in pages:
        with open(page, encoding="utf-8") as stream:
            text = stream.read()
        if not OPEN.search(text):
            continue
        try:
            new = generate(page, text)
        except TableError as error:
            print(f"tables: {page}: {error}", file=sys.stderr)
            failed = True
            continue
        n_tables += len(OPEN.findall(text))
        if new == text:
            continue
        if check:
            print(f"tables: {page} differs from what doc/scripts/tables.py writes "
                  "from doc/results/: run doc/scripts/tables.py", file=sys.stderr)
            failed = True
        else:
            with open(page, "w", encoding="utf-8") as stream:
                stream.write(new)
            print(f"tables: rewrote {page}")
    if failed:
        return 1
    print(f"tables: {n_tables} generated tables {'agree with' if check else 'written from'} "
          "doc/results/")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
