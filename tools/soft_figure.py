#!/usr/bin/env python3
"""docs/soft-penumbrae.png: penumbrae under the real sun (0.53°), the ray-traced soft truth beside
what the hard test, 3 × 3 PCF and PCSS draw, with each one's signed error below it.

  tools/soft_figure.py [SHADOWKIT]    (default build/apps/shadowkit/shadowkit; /usr/bin/python3)

Runs `shadowkit eval --view perpendicular --sun-angle 0.53 --dump DIR` once per filter (four
2048² cascades with per-split LiSPSM, the README's set-up) and crops the window of the frame
with the most penumbra pixels (true visibility in (0.02, 0.98)), enlarged 3× without smoothing.
"""
import os
import sys

import numpy as np
from penumbra_window import densest_penumbra_window, dumped_terms, enlarged, truth_beside_errors  # tools/

root = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
shadowkit = sys.argv[1] if len(sys.argv) > 1 else os.path.join(root, "build/apps/shadowkit/shadowkit")
setup = ["--view", "perpendicular", "--technique", "csm", "--cascades", "4", "--cascade-warp", "lispsm",
         "--map-size", "2048", "--sun-angle", "0.53"]
filters = [("hard", "hard test"), ("pcf:3", "3 × 3 PCF"), ("pcss", "PCSS")]
terms, truth = dumped_terms(shadowkit, setup, [["--filter", name] for name, _ in filters])

# The window (a quarter of the frame's height, 4:3) holding the most penumbra pixels.
h, w = truth.shape
wh, ww = h // 4, h // 3
y0, x0 = densest_penumbra_window(truth, wh, ww)

valid = np.isfinite(truth)
panels = []
for (_, label), term in zip(filters, terms):
    error = np.where(valid, term - truth, 0.0)
    mae = np.abs(error[valid & (truth > 0.02) & (truth < 0.98)]).mean()
    panels.append((term, f"{label}: view's penumbra_mae {mae:.3f}"))
truth_beside_errors(truth, lambda image: enlarged(image, (y0, x0), wh, ww), panels,
                    "soft truth (256 rays in penumbrae)",
                    "below: rendered − truth\nred: too dark, blue: too light\n\n"
                    f"window {ww}×{wh} px at ({x0}, {y0})\nof perpendicular, {w}×{h}",
                    (3.2, 5.4), os.path.join(root, "docs/soft-penumbrae.png"))
