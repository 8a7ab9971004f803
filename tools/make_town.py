#!/usr/bin/env python3
"""Writes a town as a city model or an engine exports it: a binary glTF of N box buildings on a
ground, each building a mesh of its own placed once (or, with --instanced, one box mesh placed N
times), for measuring what many meshes cost (docs/reliability.md, "Many meshes").

    python3 tools/make_town.py town.glb --buildings 20000 [--instanced] [--seed 1]

Buildings stand on a grid 30 m apart, 8-20 m wide and 5-40 m tall (seeded); no dependency beyond
the standard library."""
import argparse
import json
import math
import os
import random
import struct
import sys
import tempfile


def box_faces():
    """A unit box's outward faces (no floor), counter-clockwise: 20 corners, 30 indices."""
    corners, indices = [], []

    def quad(a, b, c, d):
        n = len(corners)
        corners.extend([a, b, c, d])
        indices.extend([n, n + 1, n + 2, n, n + 2, n + 3])

    quad((0, 1, 0), (0, 1, 1), (1, 1, 1), (1, 1, 0))  # roof
    quad((0, 0, 1), (1, 0, 1), (1, 1, 1), (0, 1, 1))  # +z
    quad((1, 0, 0), (0, 0, 0), (0, 1, 0), (1, 1, 0))  # -z
    quad((1, 0, 1), (1, 0, 0), (1, 1, 0), (1, 1, 1))  # +x
    quad((0, 0, 0), (0, 0, 1), (0, 1, 1), (0, 1, 0))  # -x
    return corners, indices


class GlbBuilder:
    def __init__(self):
        self.buffer = bytearray()
        self.views, self.accessors, self.meshes = [], [], []

    def _view(self, data):
        offset = len(self.buffer)
        self.buffer += data
        while len(self.buffer) % 4:
            self.buffer += b"\0"
        self.views.append({"buffer": 0, "byteOffset": offset, "byteLength": len(data)})
        return len(self.views) - 1

    def mesh(self, corners, indices):
        positions = b"".join(struct.pack("<3f", *c) for c in corners)
        lo = [min(c[i] for c in corners) for i in range(3)]
        hi = [max(c[i] for c in corners) for i in range(3)]
        self.accessors.append({"bufferView": self._view(positions), "componentType": 5126,
                               "count": len(corners), "type": "VEC3", "min": lo, "max": hi})
        self.accessors.append({"bufferView": self._view(struct.pack(f"<{len(indices)}H", *indices)),
                               "componentType": 5123, "count": len(indices), "type": "SCALAR"})
        self.meshes.append({"primitives": [{"attributes": {"POSITION": len(self.accessors) - 2},
                                            "indices": len(self.accessors) - 1}]})
        return len(self.meshes) - 1

    def write(self, path, nodes):
        doc = {"asset": {"version": "2.0", "generator": "shadowkit tools/make_town.py"}, "scene": 0,
               "scenes": [{"nodes": list(range(len(nodes)))}], "nodes": nodes, "meshes": self.meshes,
               "accessors": self.accessors, "bufferViews": self.views,
               "buffers": [{"byteLength": len(self.buffer)}]}
        text = json.dumps(doc, separators=(",", ":")).encode()
        text += b" " * (-len(text) % 4)
        total = 12 + 8 + len(text) + 8 + len(self.buffer)
        # Whole or not at all, as shadowkit writes its files: a temporary beside the target,
        # flushed to the disk, then renamed over it; missing folders made.
        if os.path.exists(path) and not os.path.isfile(path):
            raise IsADirectoryError(0, "a directory, device or pipe, not a file")
        folder = os.path.dirname(os.path.abspath(path))
        if os.path.exists(folder) and not os.path.isdir(folder):
            raise NotADirectoryError(0, f"{folder} is not a directory")
        os.makedirs(folder, exist_ok=True)
        handle, temporary = tempfile.mkstemp(prefix=".make_town.", dir=folder)
        try:
            umask = os.umask(0)
            os.umask(umask)
            os.chmod(temporary, 0o666 & ~umask)  # as a plain open would make it, not mkstemp's 0600
            with os.fdopen(handle, "wb") as out:
                out.write(struct.pack("<III", 0x46546C67, 2, total))
                out.write(struct.pack("<II", len(text), 0x4E4F534A) + text)
                out.write(struct.pack("<II", len(self.buffer), 0x004E4942) + bytes(self.buffer))
                out.flush()
                os.fsync(out.fileno())
            os.replace(temporary, path)
        except BaseException:
            os.unlink(temporary)
            raise


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("out", help="the .glb to write")
    parser.add_argument("--buildings", type=int, default=20000)
    parser.add_argument("--instanced", action="store_true", help="one box mesh placed per building")
    parser.add_argument("--seed", type=int, default=1)
    args = parser.parse_args()
    if not 1 <= args.buildings <= 1_000_000:
        sys.exit(f"--buildings: expected 1 to 1000000, got {args.buildings}")
    rng = random.Random(args.seed)
    corners, indices = box_faces()
    glb, nodes = GlbBuilder(), []
    side = math.isqrt(args.buildings - 1) + 1
    shared = glb.mesh(corners, indices) if args.instanced else None
    for k in range(args.buildings):
        size = (rng.uniform(8, 20), rng.uniform(5, 40), rng.uniform(8, 20))
        at = [30.0 * (k % side) - 15.0 * side, 0.0, 30.0 * (k // side) - 15.0 * side]
        if args.instanced:
            nodes.append({"mesh": shared, "translation": at, "scale": list(size)})
        else:
            scaled = [tuple(c[i] * size[i] for i in range(3)) for c in corners]
            nodes.append({"mesh": glb.mesh(scaled, indices), "translation": at})
    half = 16.0 * side
    ground = [(-half, 0, -half), (-half, 0, half), (half, 0, half), (half, 0, -half)]
    nodes.append({"mesh": glb.mesh(ground, [0, 1, 2, 0, 2, 3])})
    try:
        glb.write(args.out, nodes)
    except OSError as error:
        sys.exit(f"{args.out}: cannot write: {error.strerror}")
    print(f"wrote {args.out}: {args.buildings} buildings, {len(glb.meshes)} meshes")


if __name__ == "__main__":
    main()
