"""Shared fixtures: the CLI binary (IMPACTLAB_CLI, set by CTest) run into a
temporary directory, and exact parsing of the CSV files it writes."""
import csv
import json
import math
import os
import subprocess

import pytest


@pytest.fixture
def cli(tmp_path):
    binary = os.environ.get("IMPACTLAB_CLI")
    if not binary:
        pytest.fail("IMPACTLAB_CLI is not set (CTest sets it to the impactlab binary)")

    def run(*arguments):
        out = tmp_path / "cli"
        completed = subprocess.run([binary, *arguments, "--quiet", "--out", str(out)],
                                   capture_output=True, text=True, check=False)
        assert completed.returncode in (0, 3), completed.stderr
        return out

    return run


def read_csv(path):
    """Columns of a CSV file as lists; numbers parsed exactly (the writer
    prints 17 significant digits or the shortest round trip), empty -> nan."""
    with open(path, newline="") as handle:
        rows = list(csv.reader(handle))
    header, body = rows[0], rows[1:]
    columns = {}
    for index, name in enumerate(header):
        values = [row[index] for row in body]
        try:
            columns[name] = [float(v) if v != "" else math.nan for v in values]
        except ValueError:
            columns[name] = values
    return columns


def read_json(path):
    with open(path) as handle:
        return json.load(handle)


def same_numbers(expected, actual):
    """Bit-for-bit equality of two float sequences (nan equals nan)."""
    expected, actual = list(expected), [float(v) for v in actual]
    assert len(expected) == len(actual)
    for index, (e, a) in enumerate(zip(expected, actual)):
        assert (math.isnan(e) and math.isnan(a)) or e == a, (index, e, a)
    return True
