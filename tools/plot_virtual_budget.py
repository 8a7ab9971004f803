#!/usr/bin/env python3
"""Virtual shadow maps under a page budget along a camera path with the sun moving: pages drawn,
the sun's lag and wrong pixels per frame, one line per budget (docs/virtual-shadow-maps.md).

  tools/plot_virtual_budget.py OUT.png LABEL=EVAL.json [LABEL=EVAL.json ...]

Each JSON file is `shadowkit eval --path ... --technique virtual --json` of the same frames, with
its own `--virtual-page-budget` (LABEL names it: "none", "128"...). Prints, per file, the figures
the page's table quotes: medians after the first frame of pages drawn, shadow triangles and lag,
and the means of wrong_pct and flicker_pct.
"""
import json
import statistics
import sys

import matplotlib

matplotlib.use("Agg")
from matplotlib import pyplot as plt  # noqa: E402


def load(argument):
    label, sep, path = argument.partition("=")
    if not sep or not label or not path:
        sys.exit(f"plot_virtual_budget: '{argument}' is not LABEL=FILE")
    with open(path) as f:
        frames = json.load(f)["frames"]
    if any("virtual" not in f for f in frames):
        sys.exit(f"plot_virtual_budget: {path}: not an eval --path --technique virtual file")
    return label, frames


def main():
    if len(sys.argv) < 3:
        sys.exit(__doc__.strip().splitlines()[3].strip())
    runs = [load(a) for a in sys.argv[2:]]
    numbers = [f["frame"] for f in runs[0][1]]
    if any([f["frame"] for f in frames] != numbers for _, frames in runs):
        sys.exit("plot_virtual_budget: the files must hold the same frames")

    fig, (pages, lag, wrong) = plt.subplots(3, 1, figsize=(8, 7), sharex=True)
    for label, frames in runs:
        pages.plot(numbers, [f["virtual"]["pages_rendered"] for f in frames], label=f"budget {label}")
        lag.plot(numbers, [f["virtual"]["lag_frames"] for f in frames], label=f"budget {label}")
        wrong.plot(numbers, [f["wrong_pct"] for f in frames], label=f"budget {label}")
    pages.set_ylabel("pages drawn")
    pages.legend(loc="upper right", fontsize=8)
    lag.set_ylabel("sun shown: frames ago")
    wrong.set_ylabel("wrong_pct")
    wrong.set_xlabel("frame")
    fig.tight_layout()
    fig.savefig(sys.argv[1], dpi=110)

    for label, frames in runs:
        later = frames[1:]  # the first frame draws (or starts drawing) every page
        flicker = [f["flicker_pct"] for f in frames if "flicker_pct" in f]
        print(f"budget {label}: medians after the first frame: "
              f"{statistics.median(f['virtual']['pages_rendered'] for f in later)} pages drawn, "
              f"{statistics.median(f['virtual']['shadow_triangles'] for f in later) / 1e6:.2f} M triangles, "
              f"lag {statistics.median(f['virtual']['lag_frames'] for f in later)} frames "
              f"(max {max(f['virtual']['lag_frames'] for f in later)}); "
              f"means: wrong_pct {statistics.mean(f['wrong_pct'] for f in frames):.2f}, "
              f"flicker_pct {statistics.mean(flicker) if flicker else float('nan'):.3f}")


if __name__ == "__main__":
    main()
