#!/usr/bin/env python3
"""docs/model-in-its-sky.png: a pavilion under the sky sphere it ships with (tests/data/shapes/sky.gltf,
tools/authored_shapes.py), drawn by `shadowkit render` with the sky kept (`--keep-sky`: every sun is
behind it, and everything lies in its shadow) and as shadowkit loads it (the sky left out, named in a
warning: scene/sky_enclosure.h).

  tools/sky_figure.py [SHADOWKIT]    (default build/apps/shadowkit/shadowkit; /usr/bin/python3; a few seconds)
"""
import os
import sys

from render_panels import render_panels

root = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
shadowkit = sys.argv[1] if len(sys.argv) > 1 else os.path.join(root, "build/apps/shadowkit/shadowkit")
# From inside the sky, under the view `paper`'s sun: the eye 20 m from the pavilion, 7 m up.
camera = ["--scene", os.path.join(root, "tests/data/shapes/sky.gltf"), "--view", "paper", "--eye", "14,7,16",
          "--dir", "-0.62,-0.32,-0.72", "--size", "480x288"]
target = os.path.join(root, "docs/model-in-its-sky.png")
render_panels(shadowkit, [([*camera, "--keep-sky"], "the file as it is: its sky sphere (1.2 km)\nhides every sun, all of it is in shadow"),
                          (camera, "as shadowkit loads it: the sky left out\n(one warning names it), the sun gets in")],
              target, "sky_figure")
print(f"wrote {os.path.relpath(target, root)}")
