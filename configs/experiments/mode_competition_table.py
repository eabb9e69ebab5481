#!/usr/bin/env python3
"""The tables of formats/compete/README.md ("Measured") from a run of configs/experiments/mode_competition.yaml and
(optionally) the CSV of its `blocklab bench formats` command.

    configs/experiments/mode_competition_table.py runs/mode_competition/results.csv [bench.csv]

Per-family win shares are sums of the cell's mode shares (the `mode_shares` column): shape = shape_ii + shape_i,
section6 = ext_s3tc + two_plane + dct, bc6h = the bc6h_mode* entries. "worth" is the mean log2[RGB] of the ablation
that removes the family minus the full competition's.
"""
import csv
import statistics
import sys

FAMILY = {"shape_ii": "shape", "shape_i": "shape", "ext_s3tc": "section6", "two_plane": "section6", "dct": "section6"}


def family_shares(text):
    shares = {"shape": 0.0, "section6": 0.0, "bc6h": 0.0}
    for item in filter(None, text.split(";")):
        mode, value = item.split("=")
        shares[FAMILY.get(mode, "bc6h")] += float(value)
    return shares


def variant(row):
    return row["label"] + ("" if row["ablation"] in ("", "baseline") else " +" + row["ablation"])


def main(results_path, bench_path=None):
    rows = [r for r in csv.DictReader(open(results_path)) if r["status"] == "ok"]
    print("| image | variant | log2[RGB] floor / skip | mPSNR | encode s (run) | wins shape / section6 / bc6h |")
    print("|---|---|---|---|---|---|")
    by_variant = {}
    for r in rows:
        v = variant(r)
        by_variant.setdefault(v, []).append(r)
        shares = family_shares(r["mode_shares"]) if r["label"] == "compete" else None
        share_text = " / ".join(f"{100 * shares[f]:.1f} %" for f in ("shape", "section6", "bc6h")) if shares else ""
        print(f"| {r['image']} | {v} | {float(r['log2rgb']):.4f} / {float(r['log2rgb_skip']):.4f} | "
              f"{float(r['mpsnr']):.2f} | {float(r['encode_seconds']):.1f} | {share_text} |")
    base = statistics.mean(float(r["log2rgb"]) for r in by_variant["compete"])
    print()
    print("| variant | mean log2[RGB] floor / skip | mean mPSNR | worth (removed family: mean log2[RGB] - compete's) |")
    print("|---|---|---|---|")
    for v, group in by_variant.items():
        floor = statistics.mean(float(r["log2rgb"]) for r in group)
        skip = statistics.mean(float(r["log2rgb_skip"]) for r in group)
        mpsnr = statistics.mean(float(r["mpsnr"]) for r in group)
        worth = f"{floor - base:+.4f} ({100 * (floor - base) / base:+.1f} %)" if v.startswith("compete +") else ""
        print(f"| {v} | {floor:.4f} / {skip:.4f} | {mpsnr:.2f} | {worth} |")
    if bench_path:
        bench = [r for r in csv.DictReader(open(bench_path)) if r["kind"] == "hdr"]
        print()
        print("| encoder (medium) | mean log2[RGB] floor / skip | mean mPSNR | encode s (sum, one core) | time vs astcenc 4x4 -medium |")
        print("|---|---|---|---|---|")
        names = []
        for r in bench:
            name = r["format"]
            if name not in names:
                names.append(name)
        for name in names:
            group = [r for r in bench if r["format"] == name]
            ratios = [float(r["speed_ratio"]) for r in group if r["speed_ratio"]]
            print(f"| {name} | {statistics.mean(float(r['log2rgb']) for r in group):.4f} / "
                  f"{statistics.mean(float(r['log2rgb_skip']) for r in group):.4f} | "
                  f"{statistics.mean(float(r['mpsnr']) for r in group):.2f} | "
                  f"{sum(float(r['encode_seconds']) for r in group):.2f} | "
                  f"{statistics.median(ratios):.2f}x |" if ratios else "|")


if __name__ == "__main__":
    main(*sys.argv[1:])
