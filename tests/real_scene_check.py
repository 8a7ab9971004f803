#!/usr/bin/env python3
"""A loaded scene drawn with no flags must show the model and its shadows.

    real_scene_check.py FRAME.png DUMP_DIR

FRAME.png (`shadowkit render --scene FILE`): neither empty nor uniform -- at least 10 % of the
pixels differ from the sky in the top-left corner, in at least 10 shades. DUMP_DIR
(`shadowkit eval --scene FILE --dump DIR`): the frame has shadows where truth has them --
at least 2 % of the evaluated pixels are correctly shadowed -- and few errors (< 5 %)."""
import os
import struct
import sys

sys.path.insert(0, os.path.dirname(__file__))
from shadow_png_check import read_png  # noqa: E402  (the standard-library PNG reader)


def read_npy_bytes(path):
    """The data of a one-byte-per-element .npy file (class.npy), standard library only."""
    with open(path, "rb") as f:
        data = f.read()
    if data[:6] != b"\x93NUMPY":
        sys.exit(f"{path}: not a .npy file")
    major = data[6]
    header_length, start = (struct.unpack("<H", data[8:10])[0], 10) if major == 1 else (struct.unpack("<I", data[8:12])[0], 12)
    header = data[start:start + header_length].decode("latin1")
    if "|u1" not in header:
        sys.exit(f"{path}: expected one byte per pixel, got {header}")
    return data[start + header_length:]


width, height, luminance = read_png(sys.argv[1])
sky = luminance[0]
differs = sum(1 for v in luminance if abs(v - sky) > 6) / len(luminance)
colours = len(set(luminance))
classes = read_npy_bytes(os.path.join(sys.argv[2], "class.npy"))
evaluated = sum(1 for c in classes if c in (1, 2, 3, 4))
shadowed = sum(1 for c in classes if c == 2) / max(evaluated, 1)
wrong = sum(1 for c in classes if c in (3, 4)) / max(evaluated, 1)
print(f"{100 * differs:.0f} % of the frame is scene, {colours} shades; {evaluated} pixels evaluated, "
      f"{100 * shadowed:.1f} % correctly shadowed, {100 * wrong:.2f} % wrong")
if differs < 0.10 or colours < 10:
    sys.exit("the frame is empty or uniform: the scene is not in view")
if shadowed < 0.02 or wrong >= 0.05:
    sys.exit("the frame shows too few shadows or too many errors")
