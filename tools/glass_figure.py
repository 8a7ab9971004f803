#!/usr/bin/env python3
"""docs/glasshouse.png: a glasshouse (tests/data/shapes/glasshouse.gltf, tools/authored_shapes.py)
drawn by `shadowkit render` as it would be with its glass read as an opaque surface (the file with
KHR_materials_transmission taken out of its materials, in a temporary copy) and as shadowkit loads
it (the light the glass lets through taken out of its alpha: libs/scene/src/gltf_transmission.cpp).

  tools/glass_figure.py [SHADOWKIT]    (default build/apps/shadowkit/shadowkit; /usr/bin/python3; a few seconds)
"""
import json
import os
import subprocess
import sys
import tempfile

import matplotlib

matplotlib.use("Agg")
import matplotlib.image as mpimg  # noqa: E402
import matplotlib.pyplot as plt  # noqa: E402

root = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
shadowkit = sys.argv[1] if len(sys.argv) > 1 else os.path.join(root, "build/apps/shadowkit/shadowkit")
source = os.path.join(root, "tests/data/shapes/glasshouse.gltf")
# Outside the house, 11 m from its middle and 6 m up, under the view `paper`'s sun.
camera = ["--view", "paper", "--eye", "7,6,8.5", "--dir", "-0.6,-0.45,-0.66", "--size", "480x288"]
panels = []
with tempfile.TemporaryDirectory() as scratch:
    with open(source) as f:
        opaque = json.load(f)
    for material in opaque["materials"]:
        material.pop("extensions", None)
    opaque["extensionsUsed"] = [e for e in opaque.get("extensionsUsed", []) if e != "KHR_materials_transmission"]
    opaque_file = os.path.join(scratch, "glasshouse-opaque.gltf")
    with open(opaque_file, "w") as f:
        json.dump(opaque, f)
    runs = [(opaque_file, "its glass read as an opaque surface: one solid\nshadow on the lawn, the sun kept out of the house"),
            (source, "as shadowkit loads it (KHR_materials_transmission):\nthe sun through the glass; the frame and the table cast")]
    for k, (scene, label) in enumerate(runs):
        out = os.path.join(scratch, f"{k}.png")
        done = subprocess.run([shadowkit, "render", "--scene", scene, *camera, "--out", out], capture_output=True, text=True)
        if done.returncode != 0:
            sys.exit(f"glass_figure: shadowkit render {scene} failed: {done.stderr.strip().splitlines()[-1]}")
        panels.append((mpimg.imread(out), label))
figure, axes = plt.subplots(1, 2, figsize=(9.6, 3.3), dpi=100)
for axis, (image, label) in zip(axes, panels):
    axis.imshow(image, interpolation="nearest")
    axis.set_title(label, fontsize=9)
    axis.axis("off")
figure.tight_layout()
target = os.path.join(root, "docs/glasshouse.png")
figure.savefig(target + ".tmp.png", bbox_inches="tight", pad_inches=0.08)
os.replace(target + ".tmp.png", target)
print(f"wrote {os.path.relpath(target, root)}")
