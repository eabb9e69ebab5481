"""Shared by the plot scripts of configs/papers/*/plot_*.py: the command line (<analysis folder> [output.png]),
reading the CSV files `blocklab analyze` writes, and a headless matplotlib (Agg backend, no display needed).
Debian python3-matplotlib, run with /usr/bin/python3.
"""
import csv
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402,F401  (re-exported: `from plot_common import plt`)


def read_rows(path):
    """The rows of a CSV file with a header line, as dicts."""
    with open(path, newline="") as f:
        return list(csv.DictReader(f))


def metric_value(value):
    """A metric value from blocklab's JSON (results.jsonl, cell files, `compare --json`) or CSV as a float: numbers
    as they are, and the strings "inf", "-inf", "nan" that stand for the values JSON numbers cannot hold
    (experiments/results_writer.h). None or "" (no value: a failed cell) becomes nan."""
    if value is None or value == "":
        return float("nan")
    if isinstance(value, str) and value not in ("inf", "-inf", "nan"):
        raise ValueError(f"not a blocklab metric value: {value!r}")
    return float(value)


def folder_and_output(argv, usage, default_png):
    """(analysis folder, output PNG path) from `script <folder> [output.png]`; exits with `usage` otherwise."""
    if len(argv) not in (2, 3):
        sys.exit(usage)
    folder = argv[1].rstrip("/")
    return folder, (argv[2] if len(argv) == 3 else folder + "/" + default_png)
