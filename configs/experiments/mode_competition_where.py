#!/usr/bin/env python3
"""Where each family of `compete` wins (formats/compete/README.md, "Measured"): the family shares of a compete .blk
per quartile of the blocks' mean log2 luminance and per band of their in-block dynamic range, from the source image
as a PFM (any image through `blocklab encode --format fp16` and `blocklab decode ... .pfm`).

    blocklab encode --format compete IMAGE compete.blk
    blocklab encode --format fp16 IMAGE source.blk && blocklab decode source.blk source.pfm
    configs/experiments/mode_competition_where.py compete.blk source.pfm

The family of a block is read from its bits (formats/compete/compete_layout.h): bits 0, 1 = 1, 1 is a Munkberg
block, whose selector follows (0 shape II, 1 0 shape I, else section 6); anything else a BC6H block.
"""
import json
import math
import struct
import sys


def block_families(path):
    data = open(path, "rb").read()
    if data[:8] != b"BLKLAB\r\n":
        raise SystemExit(f"{path}: not a .blk file")
    (length,) = struct.unpack_from("<I", data, 12)
    header = json.loads(data[16:16 + length])
    if header["format"] != "compete":
        raise SystemExit(f"{path}: format {header['format']}, not compete")
    blocks = data[16 + length:]
    families = []
    for offset in range(0, len(blocks), 16):
        b0, b1 = blocks[offset], blocks[offset + 1]
        if b0 & 3 != 3:
            families.append("bc6h")
            continue
        selector = (b0 >> 2) | (b1 << 6)
        families.append("shape" if selector & 1 == 0 or selector & 2 == 0 else "section6")
    return header["width"], header["height"], families


def read_pfm(path):
    with open(path, "rb") as handle:
        kind = handle.readline().strip()
        width, height = map(int, handle.readline().split())
        scale = float(handle.readline())
        channels = 3 if kind == b"PF" else 1
        count = width * height * channels
        values = struct.unpack(("<" if scale < 0 else ">") + "f" * count, handle.read(4 * count))
    rows = [values[(height - 1 - y) * width * channels:(height - y) * width * channels] for y in range(height)]
    return width, height, lambda x, y: rows[y][x * channels:(x + 1) * channels] * (3 if channels == 1 else 1)


def main(blk_path, pfm_path):
    width, height, families = block_families(blk_path)
    image_width, image_height, texel = read_pfm(pfm_path)
    if (image_width, image_height) != (width, height):
        raise SystemExit(f"{pfm_path}: {image_width}x{image_height}, the .blk is {width}x{height}")
    blocks_x = (width + 3) // 4
    stats = []
    for index, family in enumerate(families):
        bx, by = index % blocks_x, index // blocks_x
        lums = []
        for y in range(4 * by, min(4 * by + 4, height)):
            for x in range(4 * bx, min(4 * bx + 4, width)):
                r, g, b = texel(x, y)[:3]
                lums.append(max(0.2126 * r + 0.7152 * g + 0.0722 * b, 2.0 ** -24))
        logs = [math.log2(v) for v in lums]
        stats.append((sum(logs) / len(logs), max(logs) - min(logs), family))
    order = sorted(s[0] for s in stats)
    quartiles = [order[len(order) * q // 4] for q in (1, 2, 3)]

    def table(title, key, labels):
        print(f"| {title} | blocks | shape | section6 | bc6h |")
        print("|---|---|---|---|---|")
        for band, label in enumerate(labels):
            group = [s[2] for s in stats if key(s) == band]
            if group:
                shares = " | ".join(f"{100 * group.count(f) / len(group):.1f} %" for f in ("shape", "section6", "bc6h"))
                print(f"| {label} | {len(group)} | {shares} |")
        print()

    table("mean log2 luminance quartile", lambda s: sum(s[0] >= q for q in quartiles),
          ["darkest 25 %", "second", "third", "brightest 25 %"])
    edges = [0.5, 2.0, 4.0]
    table("in-block dynamic range (stops)", lambda s: sum(s[1] >= e for e in edges),
          ["< 0.5", "0.5 - 2", "2 - 4", ">= 4"])


if __name__ == "__main__":
    main(*sys.argv[1:])
