"""Side-by-side pictures drawn by `shadowkit render` for the docs (tools/sky_figure.py,
tools/glass_figure.py): each run's picture under its caption, written whole to the target."""
import os
import subprocess
import sys
import tempfile

import matplotlib

matplotlib.use("Agg")
import matplotlib.image as mpimg  # noqa: E402
import matplotlib.pyplot as plt  # noqa: E402


def render_panels(shadowkit, runs, target, name):
    """`runs`: (arguments of `shadowkit render`, caption) pairs, drawn left to right into `target` (a
    PNG: a temporary beside it, renamed over it); a failed render or write is one line naming `name` and
    exit 1, leaving nothing under the target's name."""
    panels = []
    with tempfile.TemporaryDirectory() as scratch:
        for k, (args, caption) in enumerate(runs):
            out = os.path.join(scratch, f"{k}.png")
            done = subprocess.run([shadowkit, "render", *args, "--out", out], capture_output=True, text=True)
            if done.returncode != 0:
                lines = done.stderr.strip().splitlines() or ["no message"]
                sys.exit(f"{name}: shadowkit render {' '.join(args)} failed: {lines[-1]}")
            panels.append((mpimg.imread(out), caption))
    figure, axes = plt.subplots(1, len(panels), figsize=(4.8 * len(panels), 3.3), dpi=100)
    for axis, (image, caption) in zip(axes, panels):
        axis.imshow(image, interpolation="nearest")
        axis.set_title(caption, fontsize=9)
        axis.axis("off")
    figure.tight_layout()
    temporary = target + ".tmp.png"
    try:
        figure.savefig(temporary, bbox_inches="tight", pad_inches=0.08)
        os.replace(temporary, target)
    except OSError as e:
        if os.path.exists(temporary):
            os.remove(temporary)
        sys.exit(f"{name}: {target}: cannot write ({e.strerror})")
