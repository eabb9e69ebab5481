#!/usr/bin/env python3
"""Munkberg et al. 2008, Figure 4: per-block mode usage of the `munkberg` format with every mode competing.

Encodes desk, memorial and cathedral with `blocklab encode --format munkberg --set modes=all` (plus any --set given
here), reads each .blk container (formats/common/container.h layout), takes every block's mode from its selector
(the prefix code of formats/munkberg/munkberg_layout.h: bit0 = 0 shape_ii; bits 1,0 shape_i; 1,1,0 ext_s3tc;
1,1,1 two_plane), prints the usage shares and writes a colour-coded PNG per image with the colours of
formats/munkberg/munkberg_mode_map.h (kModeMapColours; flat 4x4 patches, as munkberg::mode_map_image without an
underlay). This script exists only because the CLI cannot call munkberg::write_mode_map yet (see the README).

Usage: python3 configs/papers/munkberg2008/fig4_mode_maps.py --blocklab build/cli/blocklab --out runs/fig4_maps
       [--data-root ../shared/data] [--set ext_s3tc_space=logyuv] [--threads 0]
"""
import argparse
import json
import os
import struct
import subprocess
import sys
import zlib

IMAGES = [("desk", "hdr/Desk.exr"), ("memorial", "hdr/memorial.hdr"), ("cathedral", "hdr/dani_cathedral_oBBC.hdr")]
MODES = ["shape_ii", "shape_i", "ext_s3tc", "two_plane"]
# formats/munkberg/munkberg_mode_map.h kModeMapColours
COLOURS = [(0.20, 0.40, 1.00), (0.15, 0.80, 0.20), (0.95, 0.20, 0.15), (1.00, 0.85, 0.10)]


def block_mode(first_byte):
    if first_byte & 1 == 0:
        return 0
    if first_byte & 2 == 0:
        return 1
    return 2 if first_byte & 4 == 0 else 3


def read_blk(path):
    data = open(path, "rb").read()
    if data[:8] != b"BLKLAB\r\n":
        sys.exit(f"{path}: not a .blk container")
    (header_length,) = struct.unpack_from("<I", data, 12)
    header = json.loads(data[16:16 + header_length].decode("utf-8"))
    blocks = data[16 + header_length:]
    return header, blocks


def write_png(path, width, height, rgb_rows):
    raw = b"".join(b"\x00" + bytes(row) for row in rgb_rows)
    def chunk(kind, payload):
        return struct.pack(">I", len(payload)) + kind + payload + struct.pack(">I", zlib.crc32(kind + payload) & 0xFFFFFFFF)
    png = b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", width, height, 8, 2, 0, 0, 0))
    png += chunk(b"IDAT", zlib.compress(raw, 9)) + chunk(b"IEND", b"")
    open(path, "wb").write(png)


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--blocklab", required=True)
    parser.add_argument("--out", required=True)
    parser.add_argument("--data-root", default="../shared/data")
    parser.add_argument("--set", action="append", default=[], help="extra munkberg option key=value")
    parser.add_argument("--threads", default="0")
    args = parser.parse_args()
    os.makedirs(args.out, exist_ok=True)
    print("| image | " + " | ".join(MODES) + " |")
    print("|---|" + "---|" * len(MODES))
    for name, relative in IMAGES:
        blk = os.path.join(args.out, name + ".blk")
        command = [args.blocklab, "encode", "--format", "munkberg", "--set", "modes=all", "--input-policy", "clamp",
                   "-j", args.threads]
        for option in args.set:
            command += ["--set", option]
        subprocess.run(command + [os.path.join(args.data_root, relative), blk], check=True)
        header, blocks = read_blk(blk)
        width, height, block_bytes = header["width"], header["height"], header["block_bytes"]
        across = (width + 3) // 4
        modes = [block_mode(blocks[b * block_bytes]) for b in range(len(blocks) // block_bytes)]
        counts = [modes.count(m) for m in range(len(MODES))]
        print(f"| {name} | " + " | ".join(f"{100.0 * c / len(modes):.1f}%" for c in counts) + " |")
        rows = []
        for y in range(height):
            row = bytearray()
            for x in range(width):
                colour = COLOURS[modes[(y // 4) * across + x // 4]]
                row += bytes(int(round(c * 255.0)) for c in colour)
            rows.append(row)
        write_png(os.path.join(args.out, name + "_modes.png"), width, height, rows)


if __name__ == "__main__":
    main()
