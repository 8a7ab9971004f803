#!/usr/bin/env python3
"""docs/materials.md's table of the levels of detail's cross-fade, from tools/measure-lod-fade.sh.

Usage: lod_fade_tables.py RESULTS_DIR
  RESULTS_DIR  eval-BAND.json and soft-BAND.json (`shadowkit eval --forest leafy --views all`, hard and
               with `--sun-angle 0.53 --filter pcss`), fly-BAND.json (`eval --path flythrough`, sun
               held), bench-BAND.json (`bench --forest leafy --trees 10000`) for BAND in 0, 0.25,
               0.5; summary.txt (the commit, the machine and the image size)

Writes the table between `<!-- table lod-fade: tools/measure-lod-fade.sh -->` and `<!-- /table -->`:
per band, every view's wrong_pct and soft_mae, the flythrough's flicker_pct, and the triangles
each pass submits on the two views that see most trees.
"""
import json
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
from readme_tables import VIEWS, write_into  # noqa: E402

PAGE = "docs/materials.md"
BANDS = [("0", "switch (`--lod-fade 0`, the default)"), ("0.25", "`--lod-fade 0.25`"), ("0.5", "`--lod-fade 0.5`")]


def load(path):
    with open(path) as f:
        return json.load(f)


def table(d):
    hard = {b: {v["view"]: v for v in load(d / f"eval-{b}.json")["views"]} for b, _ in BANDS}
    soft = {b: {v["view"]: v for v in load(d / f"soft-{b}.json")["views"]} for b, _ in BANDS}
    out = ["| view | " + " | ".join(f"{label}: wrong % / soft_mae" for _, label in BANDS) + " |",
           "|---|" + "---:|" * len(BANDS)]
    for view in VIEWS:
        out.append(f"| {view} | " + " | ".join(
            f"{hard[b][view]['wrong_pct']:.2f} / {soft[b][view]['soft_mae']:.4f}" for b, _ in BANDS) + " |")
    fly = {b: load(d / f"fly-{b}.json")["summary"]["flicker_pct"] for b, _ in BANDS}
    out.append("| flythrough, 48 frames, sun held: `flicker_pct` mean / p95 / max | " + " | ".join(
        f"{fly[b]['mean']:.3f} / {fly[b]['p95']:.3f} / {fly[b]['max']:.3f}" for b, _ in BANDS) + " |")
    bench = {b: {r["view"]: r for r in load(d / f"bench-{b}.json")["runs"]} for b, _ in BANDS}
    for view in ("perpendicular", "aerial"):
        out.append(f"| 10,000 trees, {view}: M triangles, shadow / camera pass | " + " | ".join(
            f"{bench[b][view]['shadow']['triangles'] / 1e6:.2f} / {bench[b][view]['main']['triangles'] / 1e6:.2f}"
            for b, _ in BANDS) + " |")
    out.append("")
    base = BANDS[0][0]
    out.append("Worst view against switching: " + "; ".join(
        f"{label} {max(hard[b][v]['wrong_pct'] - hard[base][v]['wrong_pct'] for v in VIEWS):+.2f} points of "
        f"`wrong_pct`, `soft_mae` ×{max(soft[b][v]['soft_mae'] / soft[base][v]['soft_mae'] for v in VIEWS):.3f}"
        for b, label in BANDS[1:]) + ".")
    return "\n".join(out)


def main(argv):
    if len(argv) != 2:
        sys.exit(__doc__)
    d = Path(argv[1])
    write_into(f"{PAGE}:lod-fade", table(d))
    summary = (d / "summary.txt").read_text().strip().replace("\n", "; ") if (d / "summary.txt").exists() else ""
    print(f"lod_fade_tables: {summary}", file=sys.stderr)


if __name__ == "__main__":
    main(sys.argv)
