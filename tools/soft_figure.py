#!/usr/bin/env python3
"""docs/soft-penumbrae.png: penumbrae under the real sun (0.53°), the ray-traced soft truth beside
what the hard test, 3 × 3 PCF and PCSS draw, with each one's signed error below it.

  tools/soft_figure.py [SHADOWKIT]    (default build/apps/shadowkit/shadowkit; /usr/bin/python3)

Runs `shadowkit eval --view perpendicular --sun-angle 0.53 --dump DIR` once per filter (four
2048² cascades with per-split LiSPSM, the README's set-up) and crops the window of the frame
with the most penumbra pixels (true visibility in (0.02, 0.98)), enlarged 3× without smoothing.
"""
import os
import subprocess
import sys
import tempfile

import numpy as np
from matplotlib import pyplot as plt
from penumbra_window import densest_penumbra_window, enlarged  # the same tools/ folder

root = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
shadowkit = sys.argv[1] if len(sys.argv) > 1 else os.path.join(root, "build/apps/shadowkit/shadowkit")
setup = ["--view", "perpendicular", "--technique", "csm", "--cascades", "4", "--cascade-warp", "lispsm",
         "--map-size", "2048", "--sun-angle", "0.53"]
filters = [("hard", "hard test"), ("pcf:3", "3 × 3 PCF"), ("pcss", "PCSS")]

terms = {}
with tempfile.TemporaryDirectory() as scratch:
    for name, _ in filters:
        folder = os.path.join(scratch, name.replace(":", "-"))
        subprocess.run([shadowkit, "eval", *setup, "--filter", name, "--dump", folder], check=True,
                       stdout=subprocess.DEVNULL)
        terms[name] = np.load(os.path.join(folder, "shadow_term.npy"))
        truth = np.load(os.path.join(folder, "soft_visibility.npy"))

# The window (a quarter of the frame's height, 4:3) holding the most penumbra pixels.
h, w = truth.shape
wh, ww = h // 4, h // 3
y0, x0 = densest_penumbra_window(truth, wh, ww)


def crop(image):
    return enlarged(image, (y0, x0), wh, ww)


valid = np.isfinite(truth)
fig, axes = plt.subplots(2, len(filters) + 1, figsize=(3.2 * (len(filters) + 1), 5.4))
axes[0, 0].imshow(crop(np.where(valid, truth, 1.0)), cmap="gray", vmin=0, vmax=1, interpolation="nearest")
axes[0, 0].set_title("soft truth (256 rays in penumbrae)", fontsize=9)
axes[1, 0].axis("off")
axes[1, 0].text(0.0, 0.5, "below: rendered − truth\nred: too dark, blue: too light\n\n"
                f"window {ww}×{wh} px at ({x0}, {y0})\nof perpendicular, {w}×{h}", fontsize=9, va="center")
for i, (name, label) in enumerate(filters, start=1):
    term = terms[name]
    error = np.where(valid, term - truth, 0.0)
    mae = np.abs(error[valid & (truth > 0.02) & (truth < 0.98)]).mean()
    axes[0, i].imshow(crop(np.where(valid, term, 1.0)), cmap="gray", vmin=0, vmax=1, interpolation="nearest")
    axes[0, i].set_title(f"{label}: view's penumbra_mae {mae:.3f}", fontsize=9)
    axes[1, i].imshow(crop(error), cmap="RdBu", vmin=-1, vmax=1, interpolation="nearest")
for ax in axes.flat:
    ax.set_xticks([])
    ax.set_yticks([])
fig.tight_layout()
out = os.path.join(root, "docs/soft-penumbrae.png")
fig.savefig(out, dpi=100)
print(f"wrote {out}")
