#!/usr/bin/env python3
"""A skinned glTF of chosen size, for timing what a deformed mesh costs a frame.

A flag of n × n vertices (2 (n − 1)² triangles), 8 m wide and 5 m tall, on a plate, skinned to a
chain of eight joints along its width, each turning ±12° about the vertical on a one-second loop
a little behind the one before it, so the cloth waves; every vertex weighted to the two joints
nearest it. The file's camera and sun look at it from 12 m. Written as one .gltf with its
buffer embedded (base64): `python3 tools/make_skinned_flag.py OUT.gltf [n]` (n defaults to 160:
25,600 vertices, 50,562 triangles).

Used by docs/reliability.md ("Its own animations") to time scene::animate on a deformed mesh:
`shadowkit render --scene OUT.gltf --path flythrough --frames 0:24 --size 320x180` prints each
frame's `animate` milliseconds.
"""
import base64
import json
import math
import os
import struct
import sys
import tempfile

JOINTS = 8
WIDTH, HEIGHT, LIFT = 8.0, 5.0, 1.0


def main():
    if len(sys.argv) not in (2, 3):
        sys.exit("usage: make_skinned_flag.py OUT.gltf [n]")
    out = sys.argv[1]
    n = int(sys.argv[2]) if len(sys.argv) == 3 else 160
    if not 2 <= n <= 2048:
        sys.exit("make_skinned_flag.py: n must lie in [2, 2048]")
    spacing = WIDTH / JOINTS
    positions, normals, joints, weights = [], [], [], []
    for j in range(n):
        for i in range(n):
            x = WIDTH * i / (n - 1)
            positions += [x, LIFT + HEIGHT * j / (n - 1), 0.0]
            normals += [0.0, 0.0, 1.0]
            # The two joints whose segments lie nearest, weighted by distance along the chain.
            s = min(max(x / spacing - 0.5, 0.0), JOINTS - 1.0)
            a = min(int(s), JOINTS - 2)
            f = s - a
            joints += [a, a + 1, 0, 0]
            weights += [1.0 - f, f, 0.0, 0.0]
    indices = []
    for j in range(n - 1):
        for i in range(n - 1):
            v = j * n + i
            indices += [v, v + 1, v + n, v + 1, v + n + 1, v + n]
    plate = [-4.0, 0.0, -6.0, 12.0, 0.0, -6.0, 12.0, 0.0, 6.0, -4.0, 0.0, 6.0]
    plate_normals = [0.0, 1.0, 0.0] * 4
    plate_indices = [0, 2, 1, 0, 3, 2]
    # Joint k stands at x = k · spacing, a child of joint k − 1 (the first of the root); each
    # bind matrix is the inverse of its rest global: a translation by −k · spacing.
    inverse_bind = []
    for k in range(JOINTS):
        inverse_bind += [1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, -k * spacing, 0, 0, 1]
    keys = [i / 8.0 for i in range(9)]
    rotations = []
    for k in range(JOINTS):
        row = []
        for t in keys:
            angle = math.radians(12.0) * math.sin(2 * math.pi * (t - 0.08 * k))
            row += [0.0, math.sin(angle / 2), 0.0, math.cos(angle / 2)]
        rotations.append(row)

    blob = bytearray()
    views, accessors = [], []

    def add(data, fmt, component, kind, count, target=None, minmax=None):
        while len(blob) % 4:
            blob.append(0)
        offset = len(blob)
        blob.extend(struct.pack("<%d%s" % (len(data), fmt), *data))
        view = {"buffer": 0, "byteOffset": offset, "byteLength": len(blob) - offset}
        if target:
            view["target"] = target
        views.append(view)
        accessor = {"bufferView": len(views) - 1, "componentType": component, "count": count, "type": kind}
        if minmax:
            accessor["min"], accessor["max"] = minmax
        accessors.append(accessor)
        return len(accessors) - 1

    vertices = n * n
    xs, ys = positions[0::3], positions[1::3]
    pos = add(positions, "f", 5126, "VEC3", vertices, 34962, ([min(xs), min(ys), 0.0], [max(xs), max(ys), 0.0]))
    nor = add(normals, "f", 5126, "VEC3", vertices, 34962)
    jnt = add(joints, "H", 5123, "VEC4", vertices, 34962)
    wgt = add(weights, "f", 5126, "VEC4", vertices, 34962)
    idx = add(indices, "I", 5125, "SCALAR", len(indices), 34963)
    ppos = add(plate, "f", 5126, "VEC3", 4, 34962, ([-4.0, 0.0, -6.0], [12.0, 0.0, 6.0]))
    pnor = add(plate_normals, "f", 5126, "VEC3", 4, 34962)
    pidx = add(plate_indices, "I", 5125, "SCALAR", 6, 34963)
    ibm = add(inverse_bind, "f", 5126, "MAT4", JOINTS)
    times = add(keys, "f", 5126, "SCALAR", len(keys), minmax=([0.0], [1.0]))
    outputs = [add(r, "f", 5126, "VEC4", len(keys)) for r in rotations]

    nodes = [{"name": "flag", "mesh": 0, "skin": 0}, {"name": "plate", "mesh": 1}]
    first_joint = len(nodes)
    for k in range(JOINTS):
        node = {"name": "joint %d" % k, "translation": [0.0 if k == 0 else spacing, 0.0, 0.0]}
        if k + 1 < JOINTS:
            node["children"] = [first_joint + k + 1]
        nodes.append(node)
    camera_node = len(nodes)
    # 12 m off the flag's middle along +z and 6 m up, looking down at it (−z turned 25° down).
    pitch = math.radians(-25.0)
    nodes.append({"name": "camera", "camera": 0, "translation": [4.0, 7.0, 12.0],
                  "rotation": [math.sin(pitch / 2), 0.0, 0.0, math.cos(pitch / 2)]})
    sun_node = len(nodes)
    # The sun from the front-left, 40° up: −z turned 40° down then 30° about the vertical.
    down, turn = math.radians(-40.0), math.radians(-30.0)
    qa = [math.sin(down / 2), 0.0, 0.0, math.cos(down / 2)]
    qb = [0.0, math.sin(turn / 2), 0.0, math.cos(turn / 2)]
    q = [qb[3] * qa[0] + qb[0] * qa[3] + qb[1] * qa[2] - qb[2] * qa[1],
         qb[3] * qa[1] - qb[0] * qa[2] + qb[1] * qa[3] + qb[2] * qa[0],
         qb[3] * qa[2] + qb[0] * qa[1] - qb[1] * qa[0] + qb[2] * qa[3],
         qb[3] * qa[3] - qb[0] * qa[0] - qb[1] * qa[1] - qb[2] * qa[2]]
    nodes.append({"name": "sun", "rotation": q, "extensions": {"KHR_lights_punctual": {"light": 0}}})
    gltf = {
        "asset": {"version": "2.0", "generator": "shadowkit tools/make_skinned_flag.py"},
        "extensionsUsed": ["KHR_lights_punctual"],
        "extensions": {"KHR_lights_punctual": {"lights": [{"type": "directional", "intensity": 3.0}]}},
        "scene": 0,
        "scenes": [{"nodes": [0, 1, first_joint, camera_node, sun_node]}],
        "nodes": nodes,
        "cameras": [{"type": "perspective", "perspective": {"yfov": 0.9, "znear": 0.5, "zfar": 100.0}}],
        "skins": [{"joints": list(range(first_joint, first_joint + JOINTS)), "inverseBindMatrices": ibm}],
        "meshes": [
            {"name": "flag", "primitives": [{"attributes": {"POSITION": pos, "NORMAL": nor, "JOINTS_0": jnt,
                                                            "WEIGHTS_0": wgt}, "indices": idx}]},
            {"name": "plate", "primitives": [{"attributes": {"POSITION": ppos, "NORMAL": pnor}, "indices": pidx}]},
        ],
        "animations": [{"name": "Wave",
                        "samplers": [{"input": times, "output": o, "interpolation": "LINEAR"} for o in outputs],
                        "channels": [{"sampler": k, "target": {"node": first_joint + k, "path": "rotation"}}
                                     for k in range(JOINTS)]}],
        "accessors": accessors,
        "bufferViews": views,
        "buffers": [{"byteLength": len(blob),
                     "uri": "data:application/octet-stream;base64," + base64.b64encode(bytes(blob)).decode()}],
    }
    # Whole or not at all, as the program writes its files: a temporary beside the target,
    # flushed to the disk and renamed over it; a failure is one line and a non-zero exit.
    folder = os.path.dirname(os.path.abspath(out))
    temporary = None
    try:
        if os.path.exists(out) and not os.path.isfile(out):  # a device or a pipe: written in place
            with open(out, "w") as f:
                json.dump(gltf, f)
            print("wrote %s" % out)
            return
        os.makedirs(folder, exist_ok=True)
        with tempfile.NamedTemporaryFile("w", dir=folder, prefix=".flag-", delete=False) as f:
            temporary = f.name
            json.dump(gltf, f)
            f.flush()
            os.fsync(f.fileno())
        os.replace(temporary, out)
    except OSError as e:
        if temporary and os.path.exists(temporary):
            os.unlink(temporary)
        sys.exit("make_skinned_flag.py: %s: cannot write (%s)" % (out, e.strerror or e))
    print("wrote %s: %d vertices, %d triangles skinned to %d joints" % (out, vertices, len(indices) // 3, JOINTS))


if __name__ == "__main__":
    main()
