#!/usr/bin/env python3
"""docs/foliage-one-leaf.png: what `aerial`'s error on the canopies is made of. The signed error
against the sun disk's truth where eval compares a pixel, once with EVALUATION.md's agreement of
raster and ray (0.5 % of view depth) and once held to one leaf (`--depth-tolerance 0.0005`).

  tools/foliage_agreement_figure.py LOOSE_DUMP ONE_LEAF_DUMP    (/usr/bin/python3: Debian's NumPy)

Both are `shadowkit eval --view aerial --sun-angle A --dump DIR` of the same set-up
(tools/measure-foliage-resolution.sh writes them). The window is the quarter-height 4:3 crop with
the most pixels the tighter rule excludes, enlarged 3× without smoothing.
"""
import os
import sys

import numpy as np
from foliage_error_split import compared_pixels  # the same tools/ folder
from matplotlib import pyplot as plt

if len(sys.argv) != 3:
    sys.exit(__doc__.strip())
root = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


def load(directory):
    return {name: np.load(os.path.join(directory, f"{name}.npy"))
            for name in ("shadow_term", "soft_visibility", "class")}


loose, tight = load(sys.argv[1]), load(sys.argv[2])
truth = loose["soft_visibility"]
h, w = truth.shape
wh, ww = h // 4, h // 3
dropped = (compared_pixels(loose["class"], truth) & (tight["class"] == 5)).astype(np.int64)
sums = np.pad(dropped.cumsum(0).cumsum(1), ((1, 0), (1, 0)))
window = sums[wh:, ww:] - sums[:-wh, ww:] - sums[wh:, :-ww] + sums[:-wh, :-ww]
y0, x0 = np.unravel_index(np.argmax(window[::8, ::8]), window[::8, ::8].shape)
y0, x0 = 8 * y0, 8 * x0


def crop(image):
    return np.kron(image[y0:y0 + wh, x0:x0 + ww], np.ones((3, 3, 1) if image.ndim == 3 else (3, 3)))


def error_picture(d):
    """Signed error (red too dark, blue too light) where compared, yellow where excluded, grey elsewhere."""
    compared = compared_pixels(d["class"], truth)
    rgb = plt.get_cmap("RdBu")((np.nan_to_num(d["shadow_term"] - truth) + 1.0) / 2.0)[..., :3]
    rgb[~compared] = (0.55, 0.55, 0.55)
    rgb[d["class"] == 5] = (0.95, 0.85, 0.2)
    mae = np.abs(d["shadow_term"] - truth)[compared].mean()
    return rgb, mae, compared.sum()


fig, axes = plt.subplots(1, 3, figsize=(9.6, 3.4))
axes[0].imshow(crop(np.where(np.isfinite(truth), truth, 1.0)), cmap="gray", vmin=0, vmax=1,
               interpolation="nearest")
axes[0].set_title(f"soft truth\naerial, {ww}×{wh} px at ({x0}, {y0})", fontsize=9)
for ax, d, label in ((axes[1], loose, "raster and ray within 0.5 %"), (axes[2], tight, "within 0.05 % (one leaf)")):
    rgb, mae, n = error_picture(d)
    ax.imshow(crop(rgb), interpolation="nearest")
    ax.set_title(f"{label}\nsoft_mae {mae:.4f} over the view's {n:,} px", fontsize=9)
for ax in axes:
    ax.set_xticks([])
    ax.set_yticks([])
fig.text(0.5, 0.01, "rendered − truth: red too dark, blue too light; yellow: excluded (raster and ray on different "
         "surfaces); grey: not compared", ha="center", fontsize=8)
fig.tight_layout(rect=(0, 0.05, 1, 1))
out = os.path.join(root, "docs/foliage-one-leaf.png")
fig.savefig(out, dpi=100)
print(f"wrote {out}")
