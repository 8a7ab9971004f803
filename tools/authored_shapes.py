#!/usr/bin/env python3
"""The shapes that broke the default technique on public models, authored here for the corpus.

  tools/authored_shapes.py [DIR]     (default tests/data/shapes; deterministic: the same bytes every run)

Writes five scenes, each framed by the standard views as a loaded model is (no terrain to stand on):
  ship.obj   thin ropes (3 cm) and masts (40 cm, 22 m tall) over a hull on a 300 m sea;
  town.obj   a wide flat town: 17 x 17 houses, 5-9 m high, 50 m apart, on a 1.2 km ground;
  tree.gltf  a single tree: a trunk and 60 alpha-cut leaf cards (MASK, a 32 x 32 texture of round
             leaves in a data URI) over a 40 m ground;
  sky.gltf   a pavilion on a 30 m ground under the sky sphere it ships with (1.2 km across, facing in,
             unlit), which hides every sun from it unless it is left out (scene/sky_enclosure.h);
  glasshouse.gltf  an iron frame and a table under walls and a roof of glass (KHR_materials_transmission),
             which shadows let the sun through (gltf_transmission.cpp).
docs/reliability.md ("Models we did not make") measures the default against `focused` on them;
tests/corpus_defaults_test.cpp holds the ship to it.
"""
import base64
import json
import math
import os
import random
import struct
import sys
import zlib


def write_whole(path, text):
    """`text` to `path` whole or not at all: a temporary beside it, flushed, renamed over it; a failure
    (a full disk, a missing folder) is one line and a non-zero exit, as for the project's own writers."""
    temporary = path + ".tmp"
    try:
        with open(temporary, "w") as f:
            f.write(text)
            f.flush()
            os.fsync(f.fileno())
        os.replace(temporary, path)
    except OSError as e:
        if os.path.exists(temporary):
            os.remove(temporary)
        sys.exit(f"authored_shapes: {path}: cannot write ({e.strerror})")


class Obj:
    """Quads of a Wavefront OBJ, counter-clockwise seen from outside."""

    def __init__(self):
        self.vertices, self.faces = [], []

    def box(self, lo, hi):
        first = len(self.vertices) + 1
        for x in (lo[0], hi[0]):
            for y in (lo[1], hi[1]):
                for z in (lo[2], hi[2]):
                    self.vertices.append((x, y, z))

        def at(x, y, z):
            return first + x * 4 + y * 2 + z

        self.faces += [(at(0, 0, 0), at(0, 0, 1), at(0, 1, 1), at(0, 1, 0)), (at(1, 0, 0), at(1, 1, 0), at(1, 1, 1), at(1, 0, 1)),
                       (at(0, 0, 0), at(1, 0, 0), at(1, 0, 1), at(0, 0, 1)), (at(0, 1, 0), at(0, 1, 1), at(1, 1, 1), at(1, 1, 0)),
                       (at(0, 0, 0), at(0, 1, 0), at(1, 1, 0), at(1, 0, 0)), (at(0, 0, 1), at(1, 0, 1), at(1, 1, 1), at(0, 1, 1))]

    def beam(self, a, b, half):
        """A square prism of half-width `half` from a to b."""
        axis = [b[i] - a[i] for i in range(3)]
        length = math.sqrt(sum(c * c for c in axis))
        d = [c / length for c in axis]
        up = (0, 1, 0) if abs(d[1]) < 0.9 else (1, 0, 0)
        u = [d[1] * up[2] - d[2] * up[1], d[2] * up[0] - d[0] * up[2], d[0] * up[1] - d[1] * up[0]]
        norm = math.sqrt(sum(c * c for c in u))
        u = [c / norm for c in u]
        w = [d[1] * u[2] - d[2] * u[1], d[2] * u[0] - d[0] * u[2], d[0] * u[1] - d[1] * u[0]]
        first = len(self.vertices) + 1
        for end in (a, b):
            for su, sw in ((-1, -1), (1, -1), (1, 1), (-1, 1)):
                self.vertices.append(tuple(end[i] + half * (su * u[i] + sw * w[i]) for i in range(3)))
        for k in range(4):
            k2 = (k + 1) % 4
            self.faces.append((first + k, first + k2, first + 4 + k2, first + 4 + k))
        self.faces += [(first + 3, first + 2, first + 1, first), (first + 4, first + 5, first + 6, first + 7)]

    def ground(self, half):
        first = len(self.vertices) + 1
        self.vertices += [(-half, 0, -half), (half, 0, -half), (half, 0, half), (-half, 0, half)]
        self.faces.append((first, first + 3, first + 2, first + 1))

    def write(self, path, comment):
        write_whole(path, f"# {comment} (tools/authored_shapes.py)\n" +
                    "".join("v %g %g %g\n" % v for v in self.vertices) +
                    "".join("f " + " ".join(str(i) for i in face) + "\n" for face in self.faces))


def ship(path):
    o = Obj()
    o.ground(150)
    o.box((-15, 0, -4), (15, 4, 4))
    masts = [(-9, 4, 0), (0, 4, 0), (9, 4, 0)]
    for x, y, z in masts:
        o.beam((x, y, z), (x, y + 22, z), 0.2)
        o.beam((x - 4, y + 15, z), (x + 4, y + 15, z), 0.1)  # a yard
    for x, y, z in masts:
        for end in ((-15, 4, -4), (-15, 4, 4), (15, 4, -4), (15, 4, 4), (x, 4, -4), (x, 4, 4)):
            o.beam((x, y + 22, z), end, 0.015)  # ropes 3 cm thick
    o.write(path, "thin ropes and masts over a hull on a 300 m sea")


def town(path):
    o = Obj()
    o.ground(450)
    for i in range(-8, 9):
        for j in range(-8, 9):
            x, z, height = i * 50, j * 50, 5 + (i * 7 + j * 13) % 5
            o.box((x - 6, 0, z - 5), (x + 6, height, z + 5))
    o.write(path, "a wide flat town: 17 x 17 houses on a 900 m ground")


def png_rgba(width, height, pixel):
    rows = b"".join(b"\0" + b"".join(bytes(pixel(x, y)) for x in range(width)) for y in range(height))

    def chunk(kind, data):
        return struct.pack(">I", len(data)) + kind + data + struct.pack(">I", zlib.crc32(kind + data) & 0xFFFFFFFF)

    return (b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", width, height, 8, 6, 0, 0, 0)) +
            chunk(b"IDAT", zlib.compress(rows, 9)) + chunk(b"IEND", b""))


def tree(path):
    def leaf(x, y):  # four round leaves on a 32 x 32 texture
        cx, cy = x % 16 - 7.5, y % 16 - 7.5
        return (40, 110, 30, 255 if cx * cx + cy * cy < 36 else 0)

    rng = random.Random(7)
    positions, uvs, indices = [], [], []

    def quad(centre, u, v, corners_uv):
        first = len(positions)
        for (su, sv), uv in zip(((-1, -1), (1, -1), (1, 1), (-1, 1)), corners_uv):
            positions.append(tuple(centre[i] + su * u[i] + sv * v[i] for i in range(3)))
            uvs.append(uv)
        indices.extend([first, first + 1, first + 2, first, first + 2, first + 3])

    plain = ((0, 0),) * 4
    quad((0, 0, -15), (20, 0, 0), (0, 0, -20), plain)  # ground
    for u, v, centre in (((0.15, 0, 0), (0, 3, 0), (0, 3, -15.15)), ((0.15, 0, 0), (0, 3, 0), (0, 3, -14.85)),
                         ((0, 0, 0.15), (0, 3, 0), (-0.15, 3, -15)), ((0, 0, 0.15), (0, 3, 0), (0.15, 3, -15))):
        quad(centre, u, v, plain)  # the trunk's four sides
    opaque = len(indices)
    for _ in range(60):  # leaf cards 1.2 m across, a crown 4-9 m up
        centre = (rng.uniform(-2.5, 2.5), rng.uniform(4, 9), -15 + rng.uniform(-2.5, 2.5))
        a, e = rng.uniform(0, math.pi), rng.uniform(-0.6, 0.6)
        u = (0.6 * math.cos(a), 0, 0.6 * math.sin(a))
        v = (-0.6 * math.sin(a) * math.sin(e), 0.6 * math.cos(e), 0.6 * math.cos(a) * math.sin(e))
        quad(centre, u, v, ((0, 1), (1, 1), (1, 0), (0, 0)))
    views = [b"".join(struct.pack("<3f", *p) for p in positions), b"".join(struct.pack("<2f", *t) for t in uvs),
             b"".join(struct.pack("<I", i) for i in indices[:opaque]), b"".join(struct.pack("<I", i) for i in indices[opaque:])]
    offsets = [sum(len(v) for v in views[:k]) for k in range(4)]
    scene = {
        "asset": {"version": "2.0", "generator": "shadowkit tools/authored_shapes.py"},
        "scene": 0, "scenes": [{"nodes": [0]}], "nodes": [{"mesh": 0, "name": "tree"}],
        "meshes": [{"primitives": [{"attributes": {"POSITION": 0, "TEXCOORD_0": 1}, "indices": 2, "material": 0},
                                   {"attributes": {"POSITION": 0, "TEXCOORD_0": 1}, "indices": 3, "material": 1}]}],
        "materials": [{"name": "bark and ground", "pbrMetallicRoughness": {"baseColorFactor": [0.5, 0.45, 0.35, 1]}},
                      {"name": "leaves", "alphaMode": "MASK", "doubleSided": True,
                       "pbrMetallicRoughness": {"baseColorTexture": {"index": 0}}}],
        "textures": [{"source": 0}],
        "images": [{"uri": "data:image/png;base64," + base64.b64encode(png_rgba(32, 32, leaf)).decode()}],
        "accessors": [{"bufferView": 0, "componentType": 5126, "count": len(positions), "type": "VEC3",
                       "min": [min(p[i] for p in positions) for i in range(3)],
                       "max": [max(p[i] for p in positions) for i in range(3)]},
                      {"bufferView": 1, "componentType": 5126, "count": len(uvs), "type": "VEC2"},
                      {"bufferView": 2, "componentType": 5125, "count": opaque, "type": "SCALAR"},
                      {"bufferView": 3, "componentType": 5125, "count": len(indices) - opaque, "type": "SCALAR"}],
        "bufferViews": [{"buffer": 0, "byteOffset": offsets[k], "byteLength": len(views[k])} for k in range(4)],
        "buffers": [{"byteLength": sum(len(v) for v in views),
                     "uri": "data:application/octet-stream;base64," + base64.b64encode(b"".join(views)).decode()}],
    }
    write_whole(path, json.dumps(scene))


def box_triangles(positions, indices, lo, hi):
    """A box's 12 triangles, counter-clockwise seen from outside."""
    first = len(positions)
    positions += [(x, y, z) for x in (lo[0], hi[0]) for y in (lo[1], hi[1]) for z in (lo[2], hi[2])]
    for a, b, c, d in ((0, 1, 3, 2), (4, 6, 7, 5), (0, 4, 5, 1), (2, 3, 7, 6), (0, 2, 6, 4), (1, 5, 7, 3)):
        indices += [first + a, first + b, first + c, first + a, first + c, first + d]


def sky(path):
    """A pavilion under the sky sphere it ships with, as game and web assets do: the sky a mesh 1.2 km
    across, single-sided, facing in, unlit (KHR_materials_unlit) — and, to a shadow map, a caster round
    everything."""
    model_positions, model_indices = [], []
    box_triangles(model_positions, model_indices, (-15, -0.2, -15), (15, 0, 15))  # the ground
    for x in (-3, 3):
        for z in (-3, 3):
            box_triangles(model_positions, model_indices, (x - 0.2, 0, z - 0.2), (x + 0.2, 3, z + 0.2))  # columns
    box_triangles(model_positions, model_indices, (-3.6, 3, -3.6), (3.6, 3.3, 3.6))  # the roof
    box_triangles(model_positions, model_indices, (-1.5, 0, -0.3), (1.5, 0.45, 0.3))  # a bench under it
    sky_positions, sky_indices = [], []
    rings, segments, radius = 16, 32, 600.0
    for j in range(rings + 1):
        polar = math.pi * j / rings
        for i in range(segments + 1):
            azimuth = 2 * math.pi * i / segments
            sky_positions.append((round(radius * math.sin(polar) * math.cos(azimuth), 4), round(radius * math.cos(polar), 4),
                                  round(radius * math.sin(polar) * math.sin(azimuth), 4)))
    for j in range(rings):
        for i in range(segments):
            a, b = j * (segments + 1) + i, (j + 1) * (segments + 1) + i
            sky_indices += [a, a + 1, b, a + 1, b + 1, b]  # counter-clockwise seen from inside
    views = [b"".join(struct.pack("<3f", *p) for p in sky_positions), b"".join(struct.pack("<I", i) for i in sky_indices),
             b"".join(struct.pack("<3f", *p) for p in model_positions), b"".join(struct.pack("<I", i) for i in model_indices)]
    offsets = [sum(len(v) for v in views[:k]) for k in range(4)]

    def positions_accessor(view, positions):
        return {"bufferView": view, "componentType": 5126, "count": len(positions), "type": "VEC3",
                "min": [min(p[i] for p in positions) for i in range(3)], "max": [max(p[i] for p in positions) for i in range(3)]}

    scene = {
        "asset": {"version": "2.0", "generator": "shadowkit tools/authored_shapes.py"},
        "extensionsUsed": ["KHR_materials_unlit"],
        "scene": 0, "scenes": [{"nodes": [0, 1]}], "nodes": [{"mesh": 0, "name": "sky"}, {"mesh": 1, "name": "pavilion"}],
        "meshes": [{"name": "sky", "primitives": [{"attributes": {"POSITION": 0}, "indices": 1, "material": 0}]},
                   {"name": "pavilion", "primitives": [{"attributes": {"POSITION": 2}, "indices": 3, "material": 1}]}],
        "materials": [{"name": "sky", "extensions": {"KHR_materials_unlit": {}},
                       "pbrMetallicRoughness": {"baseColorFactor": [0.45, 0.65, 0.95, 1], "metallicFactor": 0}},
                      {"name": "stone", "pbrMetallicRoughness": {"baseColorFactor": [0.7, 0.68, 0.62, 1]}}],
        "accessors": [positions_accessor(0, sky_positions),
                      {"bufferView": 1, "componentType": 5125, "count": len(sky_indices), "type": "SCALAR"},
                      positions_accessor(2, model_positions),
                      {"bufferView": 3, "componentType": 5125, "count": len(model_indices), "type": "SCALAR"}],
        "bufferViews": [{"buffer": 0, "byteOffset": offsets[k], "byteLength": len(views[k])} for k in range(4)],
        "buffers": [{"byteLength": sum(len(v) for v in views),
                     "uri": "data:application/octet-stream;base64," + base64.b64encode(b"".join(views)).decode()}],
    }
    write_whole(path, json.dumps(scene))


def glasshouse(path):
    """A glasshouse as Blender writes glass: panes with KHR_materials_transmission (all of the light
    through, tinted a little green), an opaque material's alpha untouched — which, read without the
    extension, kept the sun out of the whole house. Its roof is a grid of 16 x 16 panes (1,024
    triangles), so a pane mesh is as large as one the loader gives foliage levels to."""
    positions, indices = {}, {}

    def box(part, lo, hi):
        box_triangles(positions.setdefault(part, []), indices.setdefault(part, []), lo, hi)

    box("ground", (-15, -0.2, -15), (15, 0, 15))
    for x in (-4, 4):
        for z in (-3, 3):
            box("frame", (x - 0.08, 0, z - 0.08), (x + 0.08, 3, z + 0.08))  # corner posts
    for z in (-3, 3):
        box("frame", (-4.08, 2.92, z - 0.08), (4.08, 3.08, z + 0.08))  # eaves beams
    box("frame", (-4, 0, -3), (4, 0.6, -2.9))  # low walls the panes stand on
    box("frame", (-4, 0, 2.9), (4, 0.6, 3))
    box("table", (-2.5, 0.8, -1), (2.5, 0.9, 1))
    for x in (-2.3, 2.2):
        for z in (-0.8, 0.7):
            box("table", (x, 0, z), (x + 0.1, 0.8, z + 0.1))
    box("glass", (-4, 0.6, -2.99), (4, 3, -2.97))  # long walls
    box("glass", (-4, 0.6, 2.97), (4, 3, 2.99))
    box("glass", (-4.01, 0, -3), (-3.99, 3, 3))  # gable walls
    box("glass", (3.99, 0, -3), (4.01, 3, 3))
    for i in range(16):  # the roof's panes
        for k in range(16):
            x0, z0 = -4 + 8 * i / 16, -3 + 6 * k / 16
            box("glass", (x0 + 0.01, 3.0, z0 + 0.01), (x0 + 0.49, 3.02, z0 + 0.365))
    parts = ["ground", "frame", "table", "glass"]
    materials = [{"name": "lawn", "pbrMetallicRoughness": {"baseColorFactor": [0.35, 0.5, 0.25, 1]}},
                 {"name": "iron", "pbrMetallicRoughness": {"baseColorFactor": [0.2, 0.22, 0.24, 1], "metallicFactor": 1}},
                 {"name": "wood", "pbrMetallicRoughness": {"baseColorFactor": [0.55, 0.4, 0.25, 1]}},
                 {"name": "glass", "doubleSided": True,
                  "pbrMetallicRoughness": {"baseColorFactor": [0.92, 0.97, 0.94, 1], "metallicFactor": 0, "roughnessFactor": 0},
                  "extensions": {"KHR_materials_transmission": {"transmissionFactor": 1}}}]
    views, accessors = [], []
    for part in parts:
        points = positions[part]
        views += [b"".join(struct.pack("<3f", *p) for p in points), b"".join(struct.pack("<I", i) for i in indices[part])]
        accessors += [{"bufferView": len(views) - 2, "componentType": 5126, "count": len(points), "type": "VEC3",
                       "min": [min(p[c] for p in points) for c in range(3)], "max": [max(p[c] for p in points) for c in range(3)]},
                      {"bufferView": len(views) - 1, "componentType": 5125, "count": len(indices[part]), "type": "SCALAR"}]
    offsets = [sum(len(v) for v in views[:k]) for k in range(len(views))]
    scene = {
        "asset": {"version": "2.0", "generator": "shadowkit tools/authored_shapes.py"},
        "extensionsUsed": ["KHR_materials_transmission"],
        "scene": 0, "scenes": [{"nodes": list(range(len(parts)))}],
        "nodes": [{"mesh": k, "name": part} for k, part in enumerate(parts)],
        "meshes": [{"name": part, "primitives": [{"attributes": {"POSITION": 2 * k}, "indices": 2 * k + 1, "material": k}]}
                   for k, part in enumerate(parts)],
        "materials": materials,
        "accessors": accessors,
        "bufferViews": [{"buffer": 0, "byteOffset": offsets[k], "byteLength": len(views[k])} for k in range(len(views))],
        "buffers": [{"byteLength": sum(len(v) for v in views),
                     "uri": "data:application/octet-stream;base64," + base64.b64encode(b"".join(views)).decode()}],
    }
    write_whole(path, json.dumps(scene))


def main(args):
    directory = args[0] if args else os.path.join(os.path.dirname(__file__), "..", "tests", "data", "shapes")
    try:
        os.makedirs(directory, exist_ok=True)
    except OSError as e:
        sys.exit(f"authored_shapes: {directory}: cannot create it ({e.strerror})")
    ship(os.path.join(directory, "ship.obj"))
    town(os.path.join(directory, "town.obj"))
    tree(os.path.join(directory, "tree.gltf"))
    sky(os.path.join(directory, "sky.gltf"))
    glasshouse(os.path.join(directory, "glasshouse.gltf"))


if __name__ == "__main__":
    main(sys.argv[1:])
