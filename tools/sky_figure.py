#!/usr/bin/env python3
"""docs/model-in-its-sky.png: a pavilion under the sky sphere it ships with (tests/data/shapes/sky.gltf,
tools/authored_shapes.py), drawn by `shadowkit render` with the sky kept (`--keep-sky`: every sun is
behind it, and everything lies in its shadow) and as shadowkit loads it (the sky left out, named in a
warning: scene/sky_enclosure.h).

  tools/sky_figure.py [SHADOWKIT]    (default build/apps/shadowkit/shadowkit; /usr/bin/python3; a few seconds)
"""
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
# From inside the sky, under the view `paper`'s sun: the eye 20 m from the pavilion, 7 m up.
camera = ["--scene", os.path.join(root, "tests/data/shapes/sky.gltf"), "--view", "paper", "--eye", "14,7,16",
          "--dir", "-0.62,-0.32,-0.72", "--size", "480x288"]
runs = [(["--keep-sky"], "the file as it is: its sky sphere (1.2 km)\nhides every sun, all of it is in shadow"),
        ([], "as shadowkit loads it: the sky left out\n(one warning names it), the sun gets in")]
panels = []
with tempfile.TemporaryDirectory() as scratch:
    for k, (extra, label) in enumerate(runs):
        out = os.path.join(scratch, f"{k}.png")
        done = subprocess.run([shadowkit, "render", *camera, *extra, "--out", out], capture_output=True, text=True)
        if done.returncode != 0:
            sys.exit(f"sky_figure: shadowkit render {' '.join(extra)} failed: {done.stderr.strip().splitlines()[-1]}")
        panels.append((mpimg.imread(out), label))
figure, axes = plt.subplots(1, 2, figsize=(9.6, 3.3), dpi=100)
for axis, (image, label) in zip(axes, panels):
    axis.imshow(image, interpolation="nearest")
    axis.set_title(label, fontsize=9)
    axis.axis("off")
figure.tight_layout()
target = os.path.join(root, "docs/model-in-its-sky.png")
figure.savefig(target + ".tmp.png", bbox_inches="tight", pad_inches=0.08)
os.replace(target + ".tmp.png", target)
print(f"wrote {os.path.relpath(target, root)}")
