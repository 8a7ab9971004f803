#!/usr/bin/env python3
"""Runs examples/python/map_size_sweep.py on a small forest, as a reader would, and checks what
it wrote: a row per cell, a picture, and the property the sweep is for — a larger map never
makes the median texel coarser (each doubling must lower pixels_per_texel_p50)."""
import csv
import os
import subprocess
import sys
import tempfile

here = os.path.dirname(os.path.abspath(__file__))
with tempfile.TemporaryDirectory() as out:
    subprocess.run([sys.executable, os.path.join(here, "map_size_sweep.py"), "--out", out, "--trees", "300",
                    "--size", "192x108", "--techniques", "focused,tsm", "--map-sizes", "256,512,1024"], check=True)
    rows = list(csv.DictReader(open(os.path.join(out, "sweep.csv"))))
    assert len(rows) == 2 * 2 * 3, f"expected 12 cells, got {len(rows)}"
    assert os.path.getsize(os.path.join(out, "sweep.png")) > 10000, "the plot is missing or empty"
    for view in ("paper", "perpendicular"):
        for technique in ("focused", "tsm"):
            ppt = [float(r["pixels_per_texel_p50"]) for r in rows if r["view"] == view and r["technique"] == technique]
            assert all(b < a for a, b in zip(ppt, ppt[1:])), f"{view} {technique}: p50 not falling with size: {ppt}"
print("map_size_sweep example: 12 cells, p50 falls with every doubling of the map")
