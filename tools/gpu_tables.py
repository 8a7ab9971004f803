#!/usr/bin/env python3
"""docs/performance.md's real-GPU tables, from what tools/measure-gpu.sh measured on the device.

Usage: gpu_tables.py RESULTS_DIR LLVMPIPE_DIR
  RESULTS_DIR   gpu-results.tgz unpacked: bench JSON per set-up (frame-*.json, tech-*.json,
                filter-*.json, lamp-*.json, leafy.json), eval-*.json, summary.txt, alpha-tsm.log
  LLVMPIPE_DIR  the same eval-*.json taken on this machine (tools/gpu-tables.sh runs them)

Writes the tables between `<!-- table gpu-...: tools/gpu-tables.sh -->` and `<!-- /table -->` in
docs/performance.md. Figures are the median of the frames after the first (bench's 11 frames).
"""
import json
import re
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
from readme_tables import VIEWS, write_into  # noqa: E402

PAGE = "docs/performance.md"
PIXELS = 1280 * 720  # every bench view here is 1280 × 720


def runs(path):
    with open(path) as f:
        return json.load(f)["runs"]


def ms(run, pass_name):
    return run[pass_name]["gpu_ms"]["median"]


def frame_table(d):
    """Per forest size and view: both passes' GPU ms and the culling's CPU ms, CHC++ and GPU culling."""
    chc = {(r["trees"], r["view"]): r for r in runs(d / "frame-chc.json")}
    gpu = {(r["trees"], r["view"]): r for r in runs(d / "frame-gpu.json")}
    out = ["| trees | view | shadow pass: M triangles (instances) | shadow GPU ms | main GPU ms | culling CPU ms "
           "| GPU culling: shadow GPU ms | main GPU ms | culling CPU ms |",
           "|---:|---|---:|---:|---:|---:|---:|---:|---:|"]
    for key, c in chc.items():
        g = gpu.get(key)
        if g is None:
            sys.exit(f"gpu_tables: frame-gpu.json has no row for {key}")
        out.append(f"| {key[0]:,} | {key[1]} | {c['shadow']['triangles'] / 1e6:.2f} ({c['shadow']['instances']:,}) | "
                   f"{ms(c, 'shadow'):.1f} | {ms(c, 'main'):.1f} | {c['cull_ms']['median']:.1f} | "
                   f"{ms(g, 'shadow'):.1f} | {ms(g, 'main'):.1f} | {g['cull_ms']['median']:.1f} |")
    return "\n".join(out)


SETUPS = [("standard", "`standard` 2048²"), ("focused", "`focused` 2048²"), ("psm", "`psm` 2048²"),
          ("tsm", "`tsm` 2048²"), ("lispsm", "`lispsm` 2048²"), ("csm4x1024", "`csm` 4 × 1024²"),
          ("csm4x2048-lispsm", "`csm` 4 × 2048², per-split LiSPSM"), ("virtual", "`virtual` 16k² clipmap")]


def setups_table(d):
    """Per set-up, 10,000 trees: each view's shadow pass (triangles, GPU ms) and camera pass."""
    views = [r["view"] for r in runs(d / "tech-tsm.json")]
    out = ["| set-up | " + " | ".join(f"{v}: shadow M triangles | shadow GPU ms | main GPU ms" for v in views) + " |",
           "|---|" + "---:|---:|---:|" * len(views)]
    for name, label in SETUPS:
        rows = {r["view"]: r for r in runs(d / f"tech-{name}.json")}
        cells = []
        for v in views:
            r = rows[v]
            if name == "virtual":
                # A still camera keeps every page after the first frame, whose pass is the slowest
                # of the 11 (bench keeps no per-frame triangles): the median would time a cache.
                shadow = f"{r['shadow']['gpu_ms']['max']:.1f} first frame, then {ms(r, 'shadow'):.1f}"
                cells += ["all pages, then none", shadow, f"{ms(r, 'main'):.1f}"]
            else:
                cells += [f"{r['shadow']['triangles'] / 1e6:.2f}", f"{ms(r, 'shadow'):.1f}", f"{ms(r, 'main'):.1f}"]
        out.append(f"| {label} | " + " | ".join(cells) + " |")
    return "\n".join(out)


FILTERS = ["hard", "pcf2", "pcf:3", "pcf:5", "poisson:16", "pcss", "pcss:32", "msm"]


def filters_table(d, prefix, filters, shadow_column=True):
    """Per filter: the camera pass's GPU ms per view, ns a pixel, and the sun's shadow pass's GPU ms
    (the lamps' views have no sun: their maps are drawn in the local pass, which bench does not time)."""
    data = {f: {r["view"]: r for r in runs(d / f"{prefix}-{f.replace(':', '')}.json")} for f in filters}
    views = list(data[filters[0]])
    out = ["| filter | " + " | ".join(f"{v}: camera pass GPU ms" for v in views) +
           " | ns a pixel (mean) | over `hard` |" + (" shadow pass GPU ms (mean) |" if shadow_column else ""),
           "|---|" + "---:|" * len(views) + "---:|---:|" + ("---:|" if shadow_column else "")]
    base = sum(ms(data["hard"][v], "main") for v in views) / len(views)
    for f in filters:
        main = [ms(data[f][v], "main") for v in views]
        mean = sum(main) / len(main)
        shadow = sum(ms(data[f][v], "shadow") for v in views) / len(views)
        out.append(f"| `{f}` | " + " | ".join(f"{m:.2f}" for m in main) +
                   f" | {mean * 1e6 / PIXELS:.2f} | {100 * (mean / base - 1):+.0f} % |" +
                   (f" {shadow:.2f} |" if shadow_column else ""))
    return "\n".join(out)


def leafy_table(d):
    """The leafy forest's frame beside the blob forest's (TSM 2048², 10,000 trees)."""
    blob = {r["view"]: r for r in runs(d / "tech-tsm.json")}
    out = ["| forest | view | shadow pass: M triangles | shadow GPU ms | main pass: M triangles | main GPU ms | culling CPU ms |",
           "|---|---|---:|---:|---:|---:|---:|"]
    for label, rows in (("blob", blob), ("leafy", {r["view"]: r for r in runs(d / "leafy.json")})):
        for v, r in rows.items():
            out.append(f"| {label} | {v} | {r['shadow']['triangles'] / 1e6:.2f} | {ms(r, 'shadow'):.1f} | "
                       f"{r['main']['triangles'] / 1e6:.2f} | {ms(r, 'main'):.1f} | {r['cull_ms']['median']:.1f} |")
    return "\n".join(out)


def eval_table(d, local):
    """wrong_pct per view and set-up on the H100 beside llvmpipe's, the same program and scene."""
    names = [("tsm", "`tsm`"), ("csm4x2048-lispsm", "`csm` 4 × 2048² LiSPSM"), ("virtual", "`virtual`")]
    out = ["| view | " + " | ".join(f"{label}: H100 / llvmpipe" for _, label in names) + " |",
           "|---|" + "---:|" * len(names)]
    figures = {}
    for name, _ in names:
        for where, folder in (("gpu", d), ("cpu", local)):
            with open(folder / f"eval-{name}.json") as f:
                for v in json.load(f)["views"]:
                    figures[(name, where, v["view"])] = v["wrong_pct"]
    worst = 0.0
    for view in VIEWS:
        cells = []
        for name, _ in names:
            g, c = figures[(name, "gpu", view)], figures[(name, "cpu", view)]
            worst = max(worst, abs(g - c))
            cells.append(f"{g:.3f} / {c:.3f}")
        out.append(f"| {view} | " + " | ".join(cells) + " |")
    out.append("")
    out.append(f"Largest difference: {worst:.3f} points of `wrong_pct`.")
    return "\n".join(out)


def main(argv):
    if len(argv) != 3:
        sys.exit(__doc__)
    d, local = Path(argv[1]), Path(argv[2])
    summary = (d / "summary.txt").read_text()
    if "NVIDIA" not in summary and "via EGL device" not in summary:
        print("gpu_tables: warning: summary.txt names no GPU driver", file=sys.stderr)
    machine = [l for l in summary.splitlines()[:4] if not l.startswith("context ")]
    write_into(f"{PAGE}:gpu-machine", "\n".join(["```text"] + machine + ["```"]))
    write_into(f"{PAGE}:gpu-frame", frame_table(d))
    write_into(f"{PAGE}:gpu-setups", setups_table(d))
    write_into(f"{PAGE}:gpu-filters", filters_table(d, "filter", FILTERS))
    write_into(f"{PAGE}:gpu-lamps", filters_table(d, "lamp", ["hard", "pcf2", "pcss"], shadow_column=False))
    write_into(f"{PAGE}:gpu-leafy", leafy_table(d))
    write_into(f"{PAGE}:gpu-eval", eval_table(d, local))
    alpha = (d / "alpha-tsm.log").read_text()
    ratio = re.search(r"alpha-tested / opaque: shadow pass ([0-9.]+)×, main pass ([0-9.]+)×", alpha)
    lines = [l for l in alpha.splitlines() if l.startswith(("MASK", "OPAQUE"))]
    if not ratio or len(lines) != 2:
        sys.exit(f"gpu_tables: {d / 'alpha-tsm.log'}: no ratio line")
    write_into(f"{PAGE}:gpu-alpha", "\n".join(["```text"] + lines + [ratio.group(0), "```"]))


if __name__ == "__main__":
    main(sys.argv)
