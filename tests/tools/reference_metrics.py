#!/usr/bin/python3
"""Independent reference for two blocklab metrics, written straight from SPECS.md (not from the C++ code).

    /usr/bin/python3 reference_metrics.py REFERENCE.pfm TEST.pfm [--start -10] [--stop 10] [--floor 2**-24]

prints {"log2rgb": ..., "mpsnr": ...} as JSON, computed in float64 with numpy:

  log2rgb (SPECS.md 1a, astcenc normalisation):
      sqrt( sum over pixels and R,G,B of (log2 a - log2 b)^2 / number of pixels )
      with the blocklab zero rule: every value v -> max(v, 2^-24), NaN -> 2^-24 as well.
  mpsnr (SPECS.md 1b, fixed stops start..stop, default -10..+10, astcenc normalisation):
      T(v, c) = clip(255 * (2^c * v)^(1/2.2), 0, 255), not rounded, negative and NaN values -> 0 first;
      MSE = sum over stops and pixels of (dR^2 + dG^2 + dB^2) / (stops * pixels);
      mpsnr = 10 log10(3 * 255^2 / MSE)   (+Infinity when MSE == 0).

Only PFM input (colour "PF" or grey "Pf", either byte order, rows stored bottom to top). Needs numpy only.
"""
import argparse
import json
import math
import sys

import numpy as np


def load_pfm(path):
    """Returns a float64 array of shape (height, width, 3), top row first."""
    with open(path, "rb") as handle:
        raw = handle.read()
    fields, cursor = [], 0
    while len(fields) < 4:  # magic, width, height, scale: whitespace-separated ASCII tokens
        while cursor < len(raw) and raw[cursor:cursor + 1].isspace():
            cursor += 1
        begin = cursor
        while cursor < len(raw) and not raw[cursor:cursor + 1].isspace():
            cursor += 1
        if begin == cursor:
            sys.exit(f"{path}: truncated PFM header")
        fields.append(raw[begin:cursor].decode("ascii"))
    cursor += 1  # exactly one whitespace byte separates the header from the raster
    magic, width, height, scale = fields[0], int(fields[1]), int(fields[2]), float(fields[3])
    planes = {"PF": 3, "Pf": 1}.get(magic)
    if planes is None:
        sys.exit(f"{path}: not a PFM file (magic {magic!r})")
    byte_order = "<" if scale < 0 else ">"  # negative scale = little endian
    count = width * height * planes
    if len(raw) - cursor < 4 * count:
        sys.exit(f"{path}: raster has {len(raw) - cursor} bytes, expected {4 * count}")
    raster = np.frombuffer(raw, dtype=np.dtype(byte_order + "f4"), count=count, offset=cursor)
    image = raster.reshape(height, width, planes)[::-1].astype(np.float64)
    if planes == 1:
        image = np.repeat(image, 3, axis=2)
    return image


def log2_rmse(a, b, floor):
    # np.fmax returns the non-NaN argument, so NaN samples become the floor as well.
    diff = np.log2(np.fmax(a, floor)) - np.log2(np.fmax(b, floor))
    pixels = a.shape[0] * a.shape[1]
    return math.sqrt(float(np.sum(diff * diff)) / pixels)


def multi_exposure_psnr(a, b, first_stop, last_stop):
    a = np.where(a > 0, a, 0.0)  # NaN > 0 is False: NaN and negatives both become 0
    b = np.where(b > 0, b, 0.0)
    stops = range(first_stop, last_stop + 1)
    total = 0.0
    for stop in stops:  # one stop at a time keeps memory at a few copies of the image
        exposure = 2.0 ** stop
        ta = np.clip(255.0 * np.power(exposure * a, 1.0 / 2.2), 0.0, 255.0)
        tb = np.clip(255.0 * np.power(exposure * b, 1.0 / 2.2), 0.0, 255.0)
        total += float(np.sum(np.square(ta - tb)))
    mse = total / (len(stops) * a.shape[0] * a.shape[1])
    return math.inf if mse == 0.0 else 10.0 * math.log10(3.0 * 255.0 ** 2 / mse)


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("reference")
    parser.add_argument("test")
    parser.add_argument("--start", type=int, default=-10)
    parser.add_argument("--stop", type=int, default=10)
    parser.add_argument("--floor", type=float, default=2.0 ** -24)
    args = parser.parse_args()
    a, b = load_pfm(args.reference), load_pfm(args.test)
    if a.shape != b.shape:
        sys.exit(f"size mismatch {a.shape[1]}x{a.shape[0]} vs {b.shape[1]}x{b.shape[0]}")
    print(json.dumps({"log2rgb": log2_rmse(a, b, args.floor),
                      "mpsnr": multi_exposure_psnr(a, b, args.start, args.stop)}))


if __name__ == "__main__":
    main()
