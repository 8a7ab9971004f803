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
import subprocess
import sys
import tempfile

import numpy as np
from matplotlib import pyplot as plt
from penumbra_window import densest_penumbra_window, enlarged  # the same tools/ folder

root = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
shadowkit = sys.argv[1] if len(sys.argv) > 1 else os.path.join(root, "build/apps/shadowkit/shadowkit")
setup = ["--forest", "leafy", "--view", "perpendicular", "--size", "640x360", "--sun-angle", "0.53",
         "--filter", "pcss", "--technique", "tsm", "--map-size", "4096"]
runs = [([], "PCSS, leaves in the depth map"), (["--foliage-opacity"], "PCSS + opacity layers")]

terms = []
with tempfile.TemporaryDirectory() as scratch:
    for i, (extra, _) in enumerate(runs):
        folder = os.path.join(scratch, str(i))
        subprocess.run([shadowkit, "eval", *setup, *extra, "--dump", folder], check=True, stdout=subprocess.DEVNULL)
        terms.append(np.load(os.path.join(folder, "shadow_term.npy")))
        truth = np.load(os.path.join(folder, "soft_visibility.npy"))

# The window (a third of the frame's height, 4:3) holding the most penumbra pixels.
h, w = truth.shape
wh, ww = h // 3, (h // 3) * 4 // 3
y0, x0 = densest_penumbra_window(truth, wh, ww)


def crop(image):
    return enlarged(image, (y0, x0), wh, ww)


valid = np.isfinite(truth)
band = valid & (truth > 0.02) & (truth < 0.98)
fig, axes = plt.subplots(2, len(runs) + 1, figsize=(3.4 * (len(runs) + 1), 5.6))
axes[0, 0].imshow(crop(np.where(valid, truth, 1.0)), cmap="gray", vmin=0, vmax=1, interpolation="nearest")
axes[0, 0].set_title("soft truth (the sun's disk, ray traced)", fontsize=9)
axes[1, 0].axis("off")
axes[1, 0].text(0.0, 0.5, "below: rendered − truth\nred: too dark, blue: too light\n\n"
                f"window {ww}×{wh} px at ({x0}, {y0})\nof perpendicular, {w}×{h},\n"
                "one 4096² TSM map; errors are\nmeans over the window", fontsize=9, va="center")
window = np.zeros_like(valid)
window[y0:y0 + wh, x0:x0 + ww] = True
for i, ((_, label), term) in enumerate(zip(runs, terms), start=1):
    error = np.where(valid, term - truth, 0.0)
    mean = np.abs(error[valid & window]).mean()
    penumbra_mean = np.abs(error[band & window]).mean()
    axes[0, i].imshow(crop(np.where(valid, term, 1.0)), cmap="gray", vmin=0, vmax=1, interpolation="nearest")
    axes[0, i].set_title(f"{label}\nmean |error| {mean:.3f} (in penumbrae {penumbra_mean:.3f})", fontsize=9)
    axes[1, i].imshow(crop(error), cmap="RdBu", vmin=-1, vmax=1, interpolation="nearest")
for ax in axes.flat:
    ax.set_xticks([])
    ax.set_yticks([])
fig.tight_layout()
out = os.path.join(root, "docs/foliage-opacity.png")
fig.savefig(out, dpi=100)
print(f"wrote {out}")
