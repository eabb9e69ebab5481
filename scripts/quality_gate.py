#!/usr/bin/env python3
"""Quality gate: compares a run's results.csv with a committed baseline CSV, metric by metric.

    quality_gate.py check  RESULTS.csv BASELINE.csv [--tolerances TOLERANCES.csv]
    quality_gate.py update RESULTS.csv BASELINE.csv

`check` exits 1 when any metric of any (label, image) row got worse than its baseline by more than the metric's
tolerance, or when a baseline row is missing from the run or a row failed; it exits 0 otherwise. Improvements
beyond the tolerance and encode-time changes beyond a factor of 1.5 are reported, never failed on: a better encoder
should update the baseline (`update`), and time depends on the machine.

Rows are keyed by (label, image); label is the config's label of the format variant (e.g. "munkberg/medium").
The baseline keeps only the key, the bit rate, the metrics and the encode time, written with 17 significant digits
so an unchanged encoder compares exactly (the invariant build gives the same bits on every machine).

Direction of each metric: values where higher is better end in "psnr" (psnr, psnr_luma, mpsnr, mpsnr_auto,
pu21_psnr); every other metric (log2rgb and its columns) is an error, lower is better.
Tolerances (TOLERANCES.csv: metric,absolute,relative; a metric may get worse by max(absolute, relative * |baseline|)):
the defaults below allow only rounding-level changes, so any real loss of quality fails.
"""
import argparse
import csv
import math
import sys

DEFAULT_TOLERANCE = (1e-9, 1e-9)   # (absolute, relative): bit-identical encoders pass, any real loss fails
TIME_FACTOR = 1.5                  # encode-time changes beyond this factor are reported
KEY_COLUMNS = ("label", "image")


def higher_is_better(metric):
    return metric.endswith("psnr")


def parse_number(text):
    """A metric cell as a float: '' is missing (None); inf, -inf and nan parse as floats."""
    text = text.strip()
    if text == "":
        return None
    return float(text)


def read_rows(path, metrics=None):
    """(rows keyed by (label, image), metric column names in file order)."""
    with open(path, newline="") as handle:
        reader = csv.DictReader(handle)
        if reader.fieldnames is None:
            raise SystemExit(f"{path}: empty CSV (no header)")
        for column in KEY_COLUMNS:
            if column not in reader.fieldnames:
                raise SystemExit(f"{path}: no '{column}' column")
        if metrics is None:
            metrics = metric_columns(reader.fieldnames)
        rows = {}
        for line, record in enumerate(reader, start=2):
            key = tuple(record[c] for c in KEY_COLUMNS)
            if key in rows:
                raise SystemExit(f"{path}:{line}: row {key} appears twice")
            rows[key] = record
    return rows, metrics


def metric_columns(fieldnames):
    """The metric columns: in a results.csv those after its fixed columns (which end with 'mode_shares'), in a
    baseline those after 'encode_seconds'."""
    for last_fixed in ("mode_shares", "encode_seconds"):
        if last_fixed in fieldnames:
            return fieldnames[fieldnames.index(last_fixed) + 1:]
    raise SystemExit("cannot tell the metric columns: neither a baseline nor a results.csv header")


def read_tolerances(path):
    tolerances = {}
    if path is None:
        return tolerances
    with open(path, newline="") as handle:
        for line, record in enumerate(csv.DictReader(handle), start=2):
            try:
                tolerances[record["metric"]] = (float(record["absolute"]), float(record["relative"]))
            except (KeyError, ValueError) as error:
                raise SystemExit(f"{path}:{line}: expected metric,absolute,relative ({error})")
    return tolerances


def compare_value(metric, base, now, tolerance):
    """'worse', 'better' or 'same' for one metric value (inf and nan compare as values: an error that becomes
    nan or a PSNR that drops from inf is worse)."""
    absolute, relative = tolerance
    if base is None and now is None:
        return "same"
    if now is None or (now != now and base == base):   # missing or newly nan
        return "worse"
    if base is None or base != base:
        return "better" if now == now else "same"
    if base == now:
        return "same"
    gain = (now - base) if higher_is_better(metric) else (base - now)
    if math.isinf(base) or math.isinf(now):
        return "better" if gain > 0 else "worse"
    allowed = max(absolute, relative * abs(base))
    if gain < -allowed:
        return "worse"
    if gain > allowed:
        return "better"
    return "same"


def check(results_path, baseline_path, tolerances_path):
    baseline, metrics = read_rows(baseline_path)
    results, _ = read_rows(results_path, metrics)
    tolerances = read_tolerances(tolerances_path)
    worse, better, timing = [], [], []
    for key, base in baseline.items():
        label = f"{key[0]} on {key[1]}"
        row = results.get(key)
        if row is None:
            worse.append(f"{label}: missing from the run")
            continue
        if row.get("status", "ok") != "ok":
            worse.append(f"{label}: failed ({row.get('error', '')})")
            continue
        for metric in metrics:
            if metric not in row:
                worse.append(f"{label}: metric column '{metric}' missing from the run")
                continue
            b, n = parse_number(base[metric]), parse_number(row[metric])
            verdict = compare_value(metric, b, n, tolerances.get(metric, DEFAULT_TOLERANCE))
            if verdict == "worse":
                worse.append(f"{label}: {metric} {b!r} -> {n!r} (worse)")
            elif verdict == "better":
                better.append(f"{label}: {metric} {b!r} -> {n!r} (better)")
        b_time, n_time = parse_number(base["encode_seconds"]), parse_number(row["encode_seconds"])
        if b_time and n_time and b_time > 0.01 and max(n_time / b_time, b_time / n_time) > TIME_FACTOR:
            timing.append(f"{label}: encode {b_time:.3g} s -> {n_time:.3g} s")
    for key in results:
        if key not in baseline:
            better.append(f"{key[0]} on {key[1]}: new row, not in the baseline (run `update` to add it)")
    for title, lines in (("improved (update the baseline to keep it)", better), ("encode time changed", timing),
                         ("WORSE than the baseline", worse)):
        if lines:
            print(f"quality gate: {len(lines)} {title}:")
            for line in lines:
                print(f"  {line}")
    print(f"quality gate: {len(baseline)} baseline rows x {len(metrics)} metrics, {len(worse)} worse, "
          f"{len(better)} improved")
    return 1 if worse else 0


def update(results_path, baseline_path):
    results, metrics = read_rows(results_path)
    failed = [key for key, row in results.items() if row.get("status", "ok") != "ok"]
    if failed:
        raise SystemExit(f"{results_path}: failed rows {failed}; not writing a baseline from a failed run")
    with open(baseline_path, "w", newline="") as handle:
        writer = csv.writer(handle, lineterminator="\n")
        writer.writerow(list(KEY_COLUMNS) + ["bpp", "encode_seconds"] + metrics)
        for key, row in results.items():
            writer.writerow(list(key) + [row["bpp"], row["encode_seconds"]] + [row[m] for m in metrics])
    print(f"quality gate: wrote {len(results)} rows x {len(metrics)} metrics to {baseline_path}")
    return 0


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("action", choices=["check", "update"])
    parser.add_argument("results", help="results.csv of a `blocklab run`")
    parser.add_argument("baseline", help="the committed baseline CSV")
    parser.add_argument("--tolerances", help="CSV metric,absolute,relative (check only)")
    args = parser.parse_args()
    if args.action == "check":
        return check(args.results, args.baseline, args.tolerances)
    return update(args.results, args.baseline)


if __name__ == "__main__":
    sys.exit(main())
