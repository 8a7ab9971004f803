#!/usr/bin/env python3
"""docs/glasshouse.png: a glasshouse (tests/data/shapes/glasshouse.gltf, tools/authored_shapes.py)
drawn by `shadowkit render` as it would be with its glass read as an opaque surface (the file with
KHR_materials_transmission taken out of its materials, in a temporary copy) and as shadowkit loads
it (the light the glass lets through taken out of its alpha: libs/scene/src/gltf_transmission.cpp).

  tools/glass_figure.py [SHADOWKIT]    (default build/apps/shadowkit/shadowkit; /usr/bin/python3; a few seconds)
"""
import json
import os
import sys
import tempfile

from authored_shapes import write_whole
from render_panels import render_panels

root = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
shadowkit = sys.argv[1] if len(sys.argv) > 1 else os.path.join(root, "build/apps/shadowkit/shadowkit")
source = os.path.join(root, "tests/data/shapes/glasshouse.gltf")
# Outside the house, 11 m from its middle and 6 m up, under the view `paper`'s sun.
camera = ["--view", "paper", "--eye", "7,6,8.5", "--dir", "-0.6,-0.45,-0.66", "--size", "480x288"]
target = os.path.join(root, "docs/glasshouse.png")
with tempfile.TemporaryDirectory() as scratch:
    with open(source) as f:
        opaque = json.load(f)
    for material in opaque["materials"]:
        material.pop("extensions", None)
    opaque["extensionsUsed"] = [e for e in opaque.get("extensionsUsed", []) if e != "KHR_materials_transmission"]
    opaque_file = os.path.join(scratch, "glasshouse-opaque.gltf")
    write_whole(opaque_file, json.dumps(opaque))  # a failure is one line and exit 1
    render_panels(shadowkit, [(["--scene", opaque_file, *camera], "its glass read as an opaque surface: one solid\n"
                                                                  "shadow on the lawn, the sun kept out of the house"),
                              (["--scene", source, *camera], "as shadowkit loads it (KHR_materials_transmission):\n"
                                                             "the sun through the glass; the frame and the table cast")],
                  target, "glass_figure")
print(f"wrote {os.path.relpath(target, root)}")
