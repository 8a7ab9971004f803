#!/usr/bin/env python3
"""Writes a field of leaf cards as glTF, for measuring what alpha testing costs.

tools/card_field.py OUT.gltf [--cards N] [--mode MASK|OPAQUE] [--seed S]

N upright double-sided cards of 1.5 × 1.5 m (two triangles each) scattered over 60 × 60 m above
a ground quad, all sharing one 256² leaf texture whose alpha covers about 30 % (round leaves).
The same file with --mode OPAQUE has the same triangles with the alpha ignored: the pair
measures the alpha-tested depth pass against the depth-only one at equal triangles
(docs/materials.md). The PNG is written with zlib alone; nothing but Python's standard library.
"""
import argparse
import base64
import json
import math
import random
import struct
import zlib
from pathlib import Path


def png(width, height, rgba_rows):
    def chunk(kind, data):
        return struct.pack(">I", len(data)) + kind + data + struct.pack(">I", zlib.crc32(kind + data) & 0xFFFFFFFF)
    raw = b"".join(b"\x00" + bytes(row) for row in rgba_rows)
    return (b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", width, height, 8, 6, 0, 0, 0))
            + chunk(b"IDAT", zlib.compress(raw, 9)) + chunk(b"IEND", b""))


def leaf_texture(rng, size=256, leaves=90, radius=9):
    alpha = [[0] * size for _ in range(size)]
    for _ in range(leaves):
        cx, cy = rng.uniform(0, size), rng.uniform(0, size)
        for y in range(max(0, int(cy - radius)), min(size, int(cy + radius) + 1)):
            for x in range(max(0, int(cx - radius)), min(size, int(cx + radius) + 1)):
                if (x - cx) ** 2 + (y - cy) ** 2 < radius * radius:
                    alpha[y][x] = 255
    rows = []
    for y in range(size):
        row = []
        for x in range(size):
            row += [60 + x // 8, 120 + y // 6, 40, alpha[y][x]]
        rows.append(row)
    return png(size, size, rows)


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("out", type=Path)
    parser.add_argument("--cards", type=int, default=5000)
    parser.add_argument("--mode", choices=["MASK", "OPAQUE"], default="MASK")
    parser.add_argument("--seed", type=int, default=1)
    args = parser.parse_args()
    if not 1 <= args.cards <= 1_000_000:
        parser.error("--cards: between 1 and 1000000")
    rng = random.Random(args.seed)
    positions, uvs, indices = [], [], []
    for c in range(args.cards):
        x, z, y = rng.uniform(-30, 30), rng.uniform(-30, 30), rng.uniform(0.5, 6.0)
        a = rng.uniform(0, math.pi)
        dx, dz = 0.75 * math.cos(a), 0.75 * math.sin(a)
        base = len(positions) // 3
        positions += [x - dx, y, z - dz, x + dx, y, z + dz, x + dx, y + 1.5, z + dz, x - dx, y + 1.5, z - dz]
        uvs += [0, 1, 1, 1, 1, 0, 0, 0]
        indices += [base, base + 1, base + 2, base, base + 2, base + 3]
    ground = [-35, 0, -35, 35, 0, -35, 35, 0, 35, -35, 0, 35]
    ground_indices = [0, 2, 1, 0, 3, 2]
    blobs = [struct.pack(f"<{len(positions)}f", *positions), struct.pack(f"<{len(uvs)}f", *uvs),
             struct.pack(f"<{len(indices)}I", *indices), struct.pack("<12f", *ground),
             struct.pack("<6I", *ground_indices)]
    views, offset = [], 0
    for blob in blobs:
        views.append({"buffer": 0, "byteOffset": offset, "byteLength": len(blob)})
        offset += len(blob)
    data = b"".join(blobs)
    image = leaf_texture(rng)
    xs, ys, zs = positions[0::3], positions[1::3], positions[2::3]
    gltf = {
        "asset": {"version": "2.0", "generator": "shadowkit tools/card_field.py"},
        "scene": 0, "scenes": [{"nodes": [0, 1]}], "nodes": [{"mesh": 0}, {"mesh": 1}],
        "meshes": [{"name": "cards", "primitives": [{"attributes": {"POSITION": 0, "TEXCOORD_0": 1}, "indices": 2, "material": 0}]},
                   {"name": "ground", "primitives": [{"attributes": {"POSITION": 3}, "indices": 4, "material": 1}]}],
        "accessors": [
            {"bufferView": 0, "componentType": 5126, "count": len(positions) // 3, "type": "VEC3",
             "min": [min(xs), min(ys), min(zs)], "max": [max(xs), max(ys), max(zs)]},
            {"bufferView": 1, "componentType": 5126, "count": len(uvs) // 2, "type": "VEC2"},
            {"bufferView": 2, "componentType": 5125, "count": len(indices), "type": "SCALAR"},
            {"bufferView": 3, "componentType": 5126, "count": 4, "type": "VEC3", "min": [-35, 0, -35], "max": [35, 0, 35]},
            {"bufferView": 4, "componentType": 5125, "count": 6, "type": "SCALAR"}],
        "bufferViews": views,
        "buffers": [{"byteLength": len(data), "uri": "data:application/octet-stream;base64," + base64.b64encode(data).decode()}],
        "materials": [{"name": "leaves", "alphaMode": args.mode, "alphaCutoff": 0.5, "doubleSided": True,
                       "pbrMetallicRoughness": {"baseColorTexture": {"index": 0}}},
                      {"name": "ground", "pbrMetallicRoughness": {"baseColorFactor": [0.45, 0.4, 0.3, 1]}}],
        "textures": [{"source": 0}],
        "images": [{"uri": "data:image/png;base64," + base64.b64encode(image).decode()}],
    }
    args.out.write_text(json.dumps(gltf, separators=(",", ":")))
    print(f"{args.out}: {args.cards} cards ({2 * args.cards} triangles), alpha {args.mode}")


if __name__ == "__main__":
    main()
