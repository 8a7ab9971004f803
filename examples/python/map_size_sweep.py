#!/usr/bin/env python3
"""A researcher's sweep with the Python module: techniques × shadow-map sizes on standard
views, each cell measured against ray-traced truth, written as CSV and plotted with matplotlib.

  PYTHONPATH=build/libs/python python3 examples/python/map_size_sweep.py --out sweep

The defaults measure the full forest (10,000 trees) at 640 × 360 on two views: 4 techniques ×
4 sizes × 2 views = 32 cells, about 20 s on a 2-core CPU (the truth is ray-traced once per view). `--trees 300 --size 160x90`
makes it a test. Writes OUT/sweep.csv (one row per cell) and OUT/sweep.png: per view,
`wrong_pct` and the median pixels per texel against the map size, one line per technique.
"""
import argparse
import csv
import os
import sys
import time

import matplotlib

matplotlib.use("Agg")  # no display: write files only
import matplotlib.pyplot as plt

import shadowkit

FIGURES = ["wrong_pct", "false_shadow_pct", "false_lit_pct", "pixels_per_texel_p50", "pixels_per_texel_p95"]


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--out", default="sweep", help="directory for sweep.csv and sweep.png")
    parser.add_argument("--views", default="paper,perpendicular", help="standard views, comma-separated")
    parser.add_argument("--techniques", default="focused,tsm,lispsm,csm")
    parser.add_argument("--map-sizes", default="512,1024,2048,4096")
    parser.add_argument("--trees", type=int, default=10000)
    parser.add_argument("--size", default="640x360", help="image size WxH")
    args = parser.parse_args()
    views, techniques = args.views.split(","), args.techniques.split(",")
    sizes = [int(s) for s in args.map_sizes.split(",")]
    width, height = (int(v) for v in args.size.split("x"))
    os.makedirs(args.out, exist_ok=True)

    evaluator = shadowkit.Evaluator(trees=args.trees)  # one forest, one GL context, truth cached per view
    rows, cells, start = [], len(views) * len(techniques) * len(sizes), time.time()
    for view in views:
        for technique in techniques:
            for map_size in sizes:
                result = evaluator.evaluate(view=view, technique=technique, map_size=map_size, size=(width, height))
                rows.append({"view": view, "technique": technique, "map_size": map_size,
                             **{f: result["figures"][f] for f in FIGURES}})
                done = len(rows)
                eta = (time.time() - start) / done * (cells - done)
                print(f"\r{done}/{cells} cells, {eta:.0f} s left", end="", file=sys.stderr, flush=True)
    print(file=sys.stderr)

    with open(os.path.join(args.out, "sweep.csv"), "w", newline="") as f:
        writer = csv.DictWriter(f, fieldnames=list(rows[0]))
        writer.writeheader()
        writer.writerows(rows)

    fig, axes = plt.subplots(2, len(views), figsize=(5 * len(views), 7), squeeze=False)
    for column, view in enumerate(views):
        for technique in techniques:
            cells_of = [r for r in rows if r["view"] == view and r["technique"] == technique]
            x = [r["map_size"] for r in cells_of]
            label = "csm (4 maps of the size)" if technique == "csm" else technique
            axes[0][column].plot(x, [r["wrong_pct"] for r in cells_of], marker="o", label=label)
            axes[1][column].plot(x, [r["pixels_per_texel_p50"] for r in cells_of], marker="o", label=technique)
        axes[0][column].set_title(view)
        axes[0][column].set_ylabel("wrong_pct (% of valid pixels)")
        axes[1][column].set_ylabel("pixels per texel, median")
        axes[1][column].axhline(1.0, color="grey", linewidth=0.8)  # one texel per pixel
        for axis in (axes[0][column], axes[1][column]):
            axis.set_xscale("log", base=2)
            axis.set_xlabel("map size (texels per side)")
            axis.grid(True, alpha=0.3)
        axes[1][column].set_yscale("log")
    axes[0][0].legend()
    fig.suptitle(f"shadowkit: techniques × map sizes against ray-traced truth ({args.trees} trees, {args.size})")
    fig.tight_layout()
    fig.savefig(os.path.join(args.out, "sweep.png"), dpi=90)
    print(f"wrote {args.out}/sweep.csv ({len(rows)} cells) and {args.out}/sweep.png")


if __name__ == "__main__":
    main()
