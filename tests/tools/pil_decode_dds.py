#!/usr/bin/python3
"""Decode a DDS file with Pillow (Debian python3-pil, PIL.DdsImagePlugin) and write the pixels as raw RGBA8.

Usage: pil_decode_dds.py in.dds out.rgba
Writes width*height*4 bytes (RGBA, row-major, top row first) and prints "WIDTH HEIGHT MODE" on stdout.
Used by tests/golden/test_s3tc_independent_decoders.cpp as an independent BC1/BC3/BC4/BC7 decoder.
Exit status 2 on a usage error, 3 when Pillow cannot decode the file.
"""
import sys

from PIL import Image


def main():
    if len(sys.argv) != 3:
        sys.stderr.write(__doc__)
        return 2
    try:
        image = Image.open(sys.argv[1])
        image.load()
    except Exception as error:  # Pillow raises several types for unsupported or broken files
        sys.stderr.write("pillow could not decode %s: %s\n" % (sys.argv[1], error))
        return 3
    mode = image.mode
    rgba = image.convert("RGBA")  # "L" (BC4) becomes grey with alpha 255
    with open(sys.argv[2], "wb") as out:
        out.write(rgba.tobytes())
    print(image.size[0], image.size[1], mode)
    return 0


if __name__ == "__main__":
    sys.exit(main())
