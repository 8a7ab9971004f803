#!/usr/bin/env python3
"""Compares a frame drawn with shadows against the same frame without: shadows must darken a
plausible share of the image (not none, not everything) and never brighten a pixel.

    shadow_png_check.py WITH.png WITHOUT.png
    shadow_png_check.py --same A.png B.png   the same frame drawn two ways (e.g. in two depth
                                             conventions): at most 0.5 % of the pixels differ by
                                             more than 2 % of the brightness range
    shadow_png_check.py --differ A.png B.png two frames that must not be one (more than 0.5 %)

Reads 8-bit RGB/RGBA non-interlaced PNGs with the standard library only (zlib)."""
import struct
import sys
import zlib


def decode_png(path):
    """(width, height, channels, rows): each row a bytearray of width × channels samples."""
    with open(path, "rb") as f:
        data = f.read()
    if data[:8] != b"\x89PNG\r\n\x1a\n":
        sys.exit(f"{path}: not a PNG")
    pos, idat, header = 8, b"", None
    while pos < len(data):
        length, kind = struct.unpack(">I4s", data[pos:pos + 8])
        body = data[pos + 8:pos + 8 + length]
        if kind == b"IHDR":
            header = struct.unpack(">IIBBBBB", body)
        elif kind == b"IDAT":
            idat += body
        pos += 12 + length
    width, height, depth, color, _, _, interlace = header
    channels = {2: 3, 6: 4}.get(color)
    if depth != 8 or channels is None or interlace:
        sys.exit(f"{path}: only 8-bit RGB(A) non-interlaced PNGs are read")
    raw, stride, rows, prev = zlib.decompress(idat), width * channels, [], bytearray(width * channels)
    for y in range(height):
        start = y * (stride + 1)
        kind, line = raw[start], bytearray(raw[start + 1:start + 1 + stride])
        for i in range(stride):  # undo the PNG row filter (none, sub, up, average, Paeth)
            a = line[i - channels] if i >= channels else 0
            b, c = prev[i], prev[i - channels] if i >= channels else 0
            if kind == 1:
                line[i] = (line[i] + a) & 255
            elif kind == 2:
                line[i] = (line[i] + b) & 255
            elif kind == 3:
                line[i] = (line[i] + (a + b) // 2) & 255
            elif kind == 4:
                p = a + b - c
                pa, pb, pc = abs(p - a), abs(p - b), abs(p - c)
                line[i] = (line[i] + (a if pa <= pb and pa <= pc else b if pb <= pc else c)) & 255
        rows.append(line)
        prev = line
    return width, height, channels, rows


def read_png(path):
    """(width, height, brightness): the sum of R, G and B per pixel, rows top first."""
    width, height, channels, rows = decode_png(path)
    return width, height, [sum(row[x * channels:x * channels + 3]) for row in rows for x in range(width)]


def differing_share(first, second):
    w1, h1, a = read_png(first)
    w2, h2, b = read_png(second)
    if (w1, h1) != (w2, h2):
        sys.exit("the two frames differ in size")
    return sum(1 for x, y in zip(a, b) if abs(x - y) > 0.02 * 3 * 255) / len(a)


def same(first, second):
    share = differing_share(first, second)
    print(f"{100 * share:.2f} % of the pixels differ")
    if share > 0.005:
        sys.exit(f"{second} is not the frame {first} is")


def differ(first, second):
    share = differing_share(first, second)
    print(f"{100 * share:.2f} % of the pixels differ")
    if share <= 0.005:
        sys.exit(f"{second} is the frame {first} is: it should not be")


def main():
    if sys.argv[1] in ("--same", "--differ"):
        return (same if sys.argv[1] == "--same" else differ)(sys.argv[2], sys.argv[3])
    w1, h1, shadowed = read_png(sys.argv[1])
    w2, h2, lit = read_png(sys.argv[2])
    if (w1, h1) != (w2, h2):
        sys.exit("the two frames differ in size")
    darker = sum(1 for s, l in zip(shadowed, lit) if s < 0.75 * l)
    brighter = sum(1 for s, l in zip(shadowed, lit) if s > l + 6)
    share = darker / len(lit)
    print(f"{100 * share:.1f} % of the pixels darkened by shadow, {brighter} brightened")
    if not 0.05 <= share <= 0.6 or brighter:
        sys.exit("shadows missing, everywhere, or brightening the image")


if __name__ == "__main__":
    main()
