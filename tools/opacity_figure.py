#!/usr/bin/env python3
"""docs/foliage-opacity.png: leaves under the real sun (0.53°) — the ray-traced soft truth beside what
PCSS draws with the leaves in the depth map and with their opacity layers (--foliage-opacity), each
with its signed error below it.

  tools/opacity_figure.py [SHADOWKIT]    (default build/apps/shadowkit/shadowkit; /usr/bin/python3)

Runs `shadowkit eval --forest leafy --view perpendicular --size 640x360 --sun-angle 0.53 --filter
pcss --dump DIR` twice, on one 4096² TSM map (the best set-up within 16 M texels,
docs/materials.md), and crops the window of the frame with the most penumbra pixels (true
visibility in (0.02, 0.98)), enlarged 3× without smoothing. About a minute and a half.
"""
import os
import sys

import numpy as np
from penumbra_window import densest_penumbra_window, dumped_terms, enlarged, truth_beside_errors  # tools/

root = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
shadowkit = sys.argv[1] if len(sys.argv) > 1 else os.path.join(root, "build/apps/shadowkit/shadowkit")
setup = ["--forest", "leafy", "--view", "perpendicular", "--size", "640x360", "--sun-angle", "0.53",
         "--filter", "pcss", "--technique", "tsm", "--map-size", "4096"]
runs = [([], "PCSS, leaves in the depth map"), (["--foliage-opacity"], "PCSS + opacity layers")]
terms, truth = dumped_terms(shadowkit, setup, [extra for extra, _ in runs])

# The window (a third of the frame's height, 4:3) holding the most penumbra pixels.
h, w = truth.shape
wh, ww = h // 3, (h // 3) * 4 // 3
y0, x0 = densest_penumbra_window(truth, wh, ww)

valid = np.isfinite(truth)
band = valid & (truth > 0.02) & (truth < 0.98)
window = np.zeros_like(valid)
window[y0:y0 + wh, x0:x0 + ww] = True
panels = []
for (_, label), term in zip(runs, terms):
    error = np.where(valid, term - truth, 0.0)
    mean = np.abs(error[valid & window]).mean()
    penumbra_mean = np.abs(error[band & window]).mean()
    panels.append((term, f"{label}\nmean |error| {mean:.3f} (in penumbrae {penumbra_mean:.3f})"))
truth_beside_errors(truth, lambda image: enlarged(image, (y0, x0), wh, ww), panels,
                    "soft truth (the sun's disk, ray traced)",
                    "below: rendered − truth\nred: too dark, blue: too light\n\n"
                    f"window {ww}×{wh} px at ({x0}, {y0})\nof perpendicular, {w}×{h},\n"
                    "one 4096² TSM map; errors are\nmeans over the window",
                    (3.4, 5.6), os.path.join(root, "docs/foliage-opacity.png"))
