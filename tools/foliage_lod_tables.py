#!/usr/bin/env python3
"""docs/materials.md's foliage levels-of-detail tables, from what tools/measure-foliage-lod.sh measured.

Usage: foliage_lod_tables.py RESULTS_DIR
  RESULTS_DIR  eval-{lod,no-lod,VARIANT}.json and soft-{lod,no-lod,VARIANT}.json (`shadowkit eval
               --forest leafy --views all`, hard and with `--sun-angle 0.53 --filter pcss`), bench
               leafy{,-no-lod,-VARIANT}.json (10,000 trees) and leafy-100k{,-no-lod,-VARIANT}.json
               (100,000 trees, --same-density), fly-{no-lod,lod,VARIANT}.log (`eval --path
               flythrough`, each optional), summary.txt (the commit and the machine); VARIANT is s4
               or s8 (--lod-foliage-scale 4 or 8) and imp (--impostors), whichever the run has

Writes the tables between `<!-- table foliage-lod...: tools/measure-foliage-lod.sh -->` and
`<!-- /table -->`: the error of the levels against the full geometry's truth, view by view, and
the work and GPU time they save. "lod" is the default (--lod-foliage-scale 6), "no-lod" every
tree at full detail, the variants a stricter scale (s4, today's runs) or a looser one (s8, the
runs kept from the chain of 16, 8 and 4 slabs), and the shadow passes' farthest level an
octahedral impostor (imp).
"""
import json
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
from readme_tables import VIEWS, write_into  # noqa: E402

PAGE = "docs/materials.md"
BASE_SETS = [("no-lod", "`--no-lod`"), ("lod", "levels (default, scale 6)")]
VARIANTS = [("s4", "`--lod-foliage-scale 4`"), ("s8", "`--lod-foliage-scale 8`"), ("imp", "`--impostors` (scale 6)")]
SETS = list(BASE_SETS)  # with the variant the results hold, set by main()


def views(path):
    with open(path) as f:
        return {v["view"]: v for v in json.load(f)["views"]}


def runs(path):
    if not path.exists():
        return {}
    with open(path) as f:
        return {r["view"]: r for r in json.load(f)["runs"]}


def machine(d):
    lines = (d / "summary.txt").read_text().splitlines() if (d / "summary.txt").exists() else []
    gpu = next((l.split(",")[0] for l in lines if l.startswith("NVIDIA")), None)
    # The bench's renderer line: "GL version, renderer via EGL ..."
    drawn = next((l.split(" via ")[0].split(", ", 1)[-1] for l in lines if " via " in l), None)
    return gpu or drawn or "this machine"


def flicker(d, s):
    """flicker_pct p95 of the flythrough run `s` (its log's last line), or None."""
    log = d / f"fly-{s}.log"
    if not log.exists():
        return None
    for line in reversed(log.read_text().splitlines()):
        if "flicker_pct" in line and " p95 " in line:
            return float(line.split("flicker_pct")[1].split(" p95 ")[1].split()[0])
    return None


def error_table(d):
    hard = {s: views(d / f"eval-{s}.json") for s, _ in SETS}
    soft = {s: views(d / f"soft-{s}.json") for s, _ in SETS}
    out = ["| view | " + " | ".join(f"{label}: wrong % / soft_mae" for _, label in SETS) + " | valid pixels, levels / none |",
           "|---|" + "---:|" * (len(SETS) + 1)]
    for view in VIEWS:
        cells = [f"{hard[s][view]['wrong_pct']:.2f} / {soft[s][view]['soft_mae']:.4f}" for s, _ in SETS]
        valid = hard["lod"][view]["valid_px"] / hard["no-lod"][view]["valid_px"]
        out.append(f"| {view} | " + " | ".join(cells) + f" | {valid:.3f} |")
    worst = {s: max(hard[s][v]["wrong_pct"] - hard["no-lod"][v]["wrong_pct"] for v in VIEWS) for s, _ in SETS[1:]}
    ratio = {s: max(soft[s][v]["soft_mae"] / soft["no-lod"][v]["soft_mae"] for v in VIEWS) for s, _ in SETS[1:]}
    out.append("")
    out.append("Worst view against `--no-lod`: " + "; ".join(
        f"{label} {worst[s]:+.2f} points of `wrong_pct`, `soft_mae` ×{ratio[s]:.3f}" for s, label in SETS[1:]) + ".")
    without = flicker(d, "no-lod")
    measured = [(label, flicker(d, s)) for s, label in SETS[1:] if flicker(d, s) is not None]
    if without is not None and measured:
        out.append("")
        out.append(f"Along `flythrough` (its first 48 frames, sun held): `flicker_pct` p95 {without:.3f} with `--no-lod`; "
                   + "; ".join(f"{value:.3f} with {label} (×{value / without:.3f})" for label, value in measured) + ".")
    return "\n".join(out)


def work_table(d):
    # A software rasteriser's milliseconds are the CPU drawing, shared with whatever else ran:
    # its triangle counts are the work, its times are left out.
    timed = "llvmpipe" not in machine(d)
    ms = (lambda v: f" {v:.1f} |") if timed else (lambda v: "")
    out = ["| trees | view | set | shadow pass: M triangles |" + (" shadow GPU ms |" if timed else "")
           + " main pass: M triangles |" + (" main GPU ms | frame CPU ms |" if timed else ""),
           "|---:|---|---|---:|" + ("---:|" if timed else "") + "---:|" + ("---:|---:|" if timed else "")]
    for trees, suffix in (("10,000", ""), ("100,000", "-100k")):
        for s, label in SETS:
            name = "leafy" + suffix + ("" if s == "lod" else f"-{s}")
            for view, r in runs(d / f"{name}.json").items():
                out.append(f"| {trees} | {view} | {label} | {r['shadow']['triangles'] / 1e6:.2f} |"
                           + ms(r['shadow']['gpu_ms']['median']) + f" {r['main']['triangles'] / 1e6:.2f} |"
                           + ms(r['main']['gpu_ms']['median'])
                           + (f" {r['frame_cpu_ms']['median']:.2f} |" if timed else ""))
    return "\n".join(out)


def main(argv):
    if len(argv) != 2:
        sys.exit(__doc__)
    d = Path(argv[1])
    SETS.extend(v for v in VARIANTS if (d / f"eval-{v[0]}.json").exists())
    write_into(f"{PAGE}:foliage-lod", error_table(d))
    write_into(f"{PAGE}:foliage-lod-work", work_table(d))
    print(f"foliage_lod_tables: figures of {machine(d)}", file=sys.stderr)


if __name__ == "__main__":
    main(sys.argv)
