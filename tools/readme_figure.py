#!/usr/bin/env python3
"""The README's first picture: the default set-up's shadows beside the ray-traced truth and the
error map, on the `perpendicular` view of the default forest (docs/readme-truth.png).

  tools/readme_figure.py [SHADOWKIT]    (default build/apps/shadowkit/shadowkit)

Runs `shadowkit eval --view perpendicular --report` into a scratch directory and sets three of
the report's pictures side by side, each cropped to the near field (the lower-left quarter of
the frame, where a shadow map's texels are the coarsest) so that stair steps are visible.
"""
import os
import subprocess
import sys
import tempfile

import numpy as np
from matplotlib import image as mpimg

root = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
shadowkit = sys.argv[1] if len(sys.argv) > 1 else os.path.join(root, "build/apps/shadowkit/shadowkit")
with tempfile.TemporaryDirectory() as scratch:
    page = os.path.join(scratch, "r.html")
    subprocess.run([shadowkit, "eval", "--view", "perpendicular", "--report", page], check=True)
    panels = []
    for suffix in ("rendered", "truth", "error"):
        image = mpimg.imread(os.path.join(scratch, f"r-perpendicular-{suffix}.png"))[..., :3]
        h, w = image.shape[:2]
        crop = image[h // 2:, : w // 2]  # the near field, lower left
        panels.append(crop)
        panels.append(np.ones((crop.shape[0], 8, 3)))  # a white gap
    strip = np.concatenate(panels[:-1], axis=1)
    out = os.path.join(root, "docs/readme-truth.png")
    mpimg.imsave(out, strip)
    print(f"wrote {out} ({strip.shape[1]} x {strip.shape[0]})")
