"""Pictures of soft shadows against their truth, shared by tools/soft_figure.py and
tools/opacity_figure.py: `eval --dump`'s terms and soft truth, the window of the frame where a
picture has the most to show — the one holding the most penumbra pixels of the truth (visibility
in (0.02, 0.98)) — enlarged without smoothing, and the figure of the truth beside each term over
its signed error."""
import os
import subprocess
import tempfile

import numpy as np
from matplotlib import pyplot as plt


def dumped_terms(shadowkit, setup, variants):
    """Runs `shadowkit eval SETUP VARIANT --dump DIR` once per option list in `variants`: each
    run's shadow term (shadow_term.npy) and the soft truth (soft_visibility.npy, the last run's:
    the same scene, view and sun in every run)."""
    terms = []
    with tempfile.TemporaryDirectory() as scratch:
        for i, variant in enumerate(variants):
            folder = os.path.join(scratch, str(i))
            subprocess.run([shadowkit, "eval", *setup, *variant, "--dump", folder], check=True,
                           stdout=subprocess.DEVNULL)
            terms.append(np.load(os.path.join(folder, "shadow_term.npy")))
            truth = np.load(os.path.join(folder, "soft_visibility.npy"))
    return terms, truth


def densest_penumbra_window(truth, height, width, step=8):
    """The corner (y, x), on a grid of `step` pixels, of the height × width window of `truth` (NaN
    where nothing was compared) holding the most penumbra pixels: window sums of a summed-area
    table."""
    penumbra = np.nan_to_num((truth > 0.02) & (truth < 0.98)).astype(np.int64)
    sums = np.pad(penumbra.cumsum(0).cumsum(1), ((1, 0), (1, 0)))
    h, w = truth.shape
    best, corner = -1, (0, 0)
    for y in range(0, h - height + 1, step):
        for x in range(0, w - width + 1, step):
            s = sums[y + height, x + width] - sums[y, x + width] - sums[y + height, x] + sums[y, x]
            if s > best:
                best, corner = s, (y, x)
    return corner


def enlarged(image, corner, height, width, factor=3):
    """The window of `image` at `corner`, each pixel a factor × factor block."""
    y0, x0 = corner
    return np.kron(image[y0:y0 + height, x0:x0 + width], np.ones((factor, factor)))


def truth_beside_errors(truth, crop, panels, truth_title, legend, panel_size, out):
    """Writes `out`: the truth over `legend`, then for each (term, title) of `panels` the term over
    its signed error (rendered − truth: red too dark, blue too light), each cropped by `crop`;
    `panel_size` the inches (width, height) of one column."""
    valid = np.isfinite(truth)
    columns = len(panels) + 1
    fig, axes = plt.subplots(2, columns, figsize=(panel_size[0] * columns, panel_size[1]))
    axes[0, 0].imshow(crop(np.where(valid, truth, 1.0)), cmap="gray", vmin=0, vmax=1, interpolation="nearest")
    axes[0, 0].set_title(truth_title, fontsize=9)
    axes[1, 0].axis("off")
    axes[1, 0].text(0.0, 0.5, legend, fontsize=9, va="center")
    for i, (term, title) in enumerate(panels, start=1):
        axes[0, i].imshow(crop(np.where(valid, term, 1.0)), cmap="gray", vmin=0, vmax=1, interpolation="nearest")
        axes[0, i].set_title(title, fontsize=9)
        axes[1, i].imshow(crop(np.where(valid, term - truth, 0.0)), cmap="RdBu", vmin=-1, vmax=1,
                          interpolation="nearest")
    for ax in axes.flat:
        ax.set_xticks([])
        ax.set_yticks([])
    fig.tight_layout()
    fig.savefig(out, dpi=100)
    print(f"wrote {out}")
