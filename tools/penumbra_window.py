"""The window of a frame where a picture of soft shadows has the most to show: the one holding the
most penumbra pixels of the truth (visibility in (0.02, 0.98)), and that window enlarged without
smoothing. Shared by tools/soft_figure.py and tools/opacity_figure.py."""
import numpy as np


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
