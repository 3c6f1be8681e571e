#!/usr/bin/python3
"""The files of impactlab's figures: the CSV tables the program writes, read
as columns by name, and a figure written whole or not at all.

    plot_files.py TABLE.csv     prints each column's name, kind and length

The drawing functions of the plot scripts take tables as columns by name (a
dict of arrays): from a CSV file here (`read_columns`), or from a result of
the Python package (its Tables, structured arrays and dicts of lists,
`as_columns`), so that the CLI's --plot and the package's result.plot() draw
the same figure from the same numbers.
"""
import csv
import io
import os
import sys

import numpy as np


def as_columns(table):
    """{name: NumPy array} of a table: a dict of arrays or lists, or a
    structured array (its fields)."""
    if table is None:
        return None
    names = getattr(getattr(table, "dtype", None), "names", None)
    if names:
        return {name: np.asarray(table[name]) for name in names}
    return {name: np.asarray(values) for name, values in table.items()}


def _parsed(text):
    """A CSV text's columns: numbers as floats (an empty field: NaN), a
    column with any other word as words."""
    rows = list(csv.reader(io.StringIO(text)))
    if not rows:
        return {}
    header, body = rows[0], rows[1:]
    columns = {}
    for index, name in enumerate(header):
        words = [row[index] if index < len(row) else "" for row in body]
        try:
            columns[name] = np.array([float(word) if word != "" else np.nan for word in words],
                                     dtype=float)
        except ValueError:
            columns[name] = np.array(words, dtype=str)
    return columns


def read_columns(path, comment_lines=0):
    """The columns of a CSV file impactlab wrote, by name as its header
    spells them ("initial.theta" stays so); `comment_lines` lines before the
    header are skipped (lyapunov.csv's one)."""
    with open(path, newline="", encoding="utf-8") as handle:
        for _ in range(comment_lines):
            handle.readline()
        return _parsed(handle.read())


def parse_columns(text):
    """The columns of CSV text (the Python package's compare tables)."""
    return _parsed(text)


def rows_where(columns, mask):
    """The rows of `columns` where `mask` holds, as columns."""
    return {name: values[mask] for name, values in columns.items()}


def rows_of(columns):
    """The rows of `columns`, each a dict by column name."""
    count = len(next(iter(columns.values()))) if columns else 0
    return [{name: values[index] for name, values in columns.items()} for index in range(count)]


def save_figure(figure, path, dpi=150):
    """Writes the figure to `path` through a temporary file renamed when
    complete, so that a failed drawing leaves no half-written picture."""
    root, extension = os.path.splitext(path)
    temporary = f"{root}.tmp{extension or '.png'}"
    try:
        figure.savefig(temporary, dpi=dpi)
        os.replace(temporary, path)
    finally:
        if os.path.exists(temporary):
            os.remove(temporary)


def main(argv):
    if len(argv) != 2 or argv[1] in ("-h", "--help"):
        print(__doc__)
        return 0 if len(argv) == 2 else 2
    for name, values in read_columns(argv[1]).items():
        kind = "numbers" if values.dtype.kind == "f" else "words"
        print(f"{name}: {len(values)} {kind}")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
