#!/usr/bin/env python3
"""docs/performance.md's real-GPU tables, from what tools/measure-gpu.sh measured on the device.

Usage: gpu_tables.py RESULTS_DIR LLVMPIPE_DIR
  RESULTS_DIR   gpu-results.tgz unpacked: bench JSON per set-up (frame-*.json, path-*.json,
                tech-*.json, filter-*.json, lamp-*.json, leafy*.json, opacity-*.json, scaling-*.json), eval-*.json,
                summary.txt, alpha-tsm.log
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


def gpu_name(d):
    """The GPU's name as the run's summary recorded it ("NVIDIA H200"), for the tables' headers."""
    for line in (d / "summary.txt").read_text().splitlines()[1:3]:
        if line.startswith("NVIDIA"):
            return line.split(",")[0].replace("80GB HBM3", "").strip()
    return "GPU"


def per_texel(run):
    """Samples that passed the shadow pass's depth test per map texel: its overdraw (1 is none)."""
    return run["shadow"].get("samples_per_texel", 0.0)


def frame_table(d):
    """Per forest size and view: both passes' GPU ms, the frame's CPU ms and the shadow pass's
    samples per texel, GPU-driven culling (the default on a GPU) and CHC++."""
    gpu = {(r["trees"], r["view"]): r for r in runs(d / "frame-gpu.json")}
    chc = {(r["trees"], r["view"]): r for r in runs(d / "frame-chc.json")}
    out = ["| trees | view | shadow pass: M triangles (instances) | samples per texel | shadow GPU ms | main GPU ms "
           "| frame CPU ms | CHC++: shadow GPU ms | main GPU ms | frame CPU ms |",
           "|---:|---|---:|---:|---:|---:|---:|---:|---:|---:|"]
    for key, g in gpu.items():
        c = chc.get(key)
        if c is None:
            sys.exit(f"gpu_tables: frame-chc.json has no row for {key}")
        out.append(f"| {key[0]:,} | {key[1]} | {g['shadow']['triangles'] / 1e6:.2f} ({g['shadow']['instances']:,}) | "
                   f"{per_texel(g):.2f} | {ms(g, 'shadow'):.1f} | {ms(g, 'main'):.1f} | "
                   f"{g['frame_cpu_ms']['median']:.2f} | {ms(c, 'shadow'):.1f} | {ms(c, 'main'):.1f} | "
                   f"{c['frame_cpu_ms']['median']:.1f} |")
    return "\n".join(out)


def path_table(d):
    """The flythrough's 240 frames in order, GPU-driven and CHC++: the CPU side of a moving frame."""
    # No GPU times here: the GPU-driven frames run far ahead of the GPU, and the late figures of
    # most of them never come back (their ring slot is reused first), so a median would be over
    # the last few frames alone.
    # KiB moved a frame: uploaded / read back (bench's bytes_uploaded, bytes_read_back, medians;
    # – for runs before 478d2bf, which did not count them).
    def kib(r):
        if "bytes_uploaded" not in r:
            return "–"
        return f"{r['bytes_uploaded']['median'] / 1024:.1f} / {r['bytes_read_back']['median'] / 1024:.1f}"

    # Compute dispatches a frame and their work groups (medians; – for runs before b5ab21e).
    def dispatches(r):
        if "dispatches" not in r:
            return "–"
        return f"{r['dispatches']['median']:.0f} / {r['work_groups']['median']:,.0f}"
    # Draw calls of the last frame, shadow / main pass (API calls: a multi-draw counts once).
    def draws(r):
        return f"{r['shadow']['draw_calls']:,} / {r['main']['draw_calls']:,}"
    out = ["| trees | set-up and culling | frame CPU ms: median | max | synchronisations a frame | "
           "KiB up / read back a frame | dispatches / work groups a frame | draws: shadow / main (last frame) | "
           "shadow pass: M triangles (last frame) | main pass: M triangles (last frame) |",
           "|---:|---|---:|---:|---:|---:|---:|---:|---:|---:|"]
    # The virtual flythrough (sun moving) only where the run benched it (measure-gpu.sh's frame step
    # since 6824575).
    for name, label in (("gpu", "TSM, GPU-driven (default)"), ("chc", "TSM, CHC++"),
                        ("virtual-pages-gpu", "`virtual`, GPU-driven"), ("virtual-pages-chc", "`virtual`, CHC++")):
        path = d / f"path-{name}.json"
        if name.startswith("virtual") and not path.exists():
            continue
        for r in runs(path):
            out.append(f"| {r['trees']:,} | {label} | {r['frame_cpu_ms']['median']:.2f} | {r['frame_cpu_ms']['max']:.1f} | "
                       f"{r['read_backs']['median']:.0f} | {kib(r)} | {dispatches(r)} | {draws(r)} | "
                       f"{r['shadow']['triangles'] / 1e6:.2f} | {r['main']['triangles'] / 1e6:.2f} |")
    return "\n".join(out)


def limits_table(d):
    """The default shadow pass (CHC++'s run, which measured the limits) as a fraction of this GPU's
    triangle and depth-only fill rates, per forest size and view."""
    out = ["| trees | view | shadow pass GPU ms | M triangles | of the triangle rate | of the fill rate |",
           "|---:|---|---:|---:|---:|---:|"]
    for r in runs(d / "frame-chc.json"):
        rates = r["shadow_rates"]
        out.append(f"| {r['trees']:,} | {r['view']} | {ms(r, 'shadow'):.1f} | {r['shadow']['triangles'] / 1e6:.2f} | "
                   f"{100 * rates['of_triangles']:.0f} % | {100 * rates['of_fill']:.0f} % |")
    return "\n".join(out)


def limits_line(d):
    """The GPU's ceilings as bench --limits measured them in the frame section's run."""
    with open(d / "frame-chc.json") as f:
        l = json.load(f)["limits"]
    return (f"depth-only fill {l['fill_samples_per_s'] * 1e-9:.1f} G samples/s; "
            f"{l['small_triangles_per_s'] * 1e-6:.0f} M small triangles/s")


def depth_layout_table(d):
    """TSM's two depth layouts at 100,000 trees (`perpendicular`): the shadow pass's GPU ms and
    work, and every standard view's wrong_pct."""
    rows = [("linear (TSM's default)", runs(d / "scaling-default.json")[0], "eval-tsm.json"),
            ("hyperbolic", runs(d / "scaling-hyperbolic.json")[0], "eval-tsm-hyperbolic.json")]
    out = ["| depth layout | shadow GPU ms | samples per texel | M triangles | " +
           " | ".join(f"{v} wrong %" for v in VIEWS) + " |",
           "|---|---:|---:|---:|" + "---:|" * len(VIEWS)]
    for label, r, ev in rows:
        with open(d / ev) as f:
            wrong = {v["view"]: v["wrong_pct"] for v in json.load(f)["views"]}
        out.append(f"| {label} | {ms(r, 'shadow'):.1f} | {per_texel(r):.2f} | {r['shadow']['triangles'] / 1e6:.2f} | " +
                   " | ".join(f"{wrong[v]:.3f}" for v in VIEWS) + " |")
    return "\n".join(out)


SETUPS = [("standard", "`standard` 2048²"), ("focused", "`focused` 2048²"), ("psm", "`psm` 2048²"),
          ("tsm", "`tsm` 2048²"), ("lispsm", "`lispsm` 2048²"), ("csm4x1024", "`csm` 4 × 1024²"),
          ("csm4x2048-lispsm", "`csm` 4 × 2048², per-split LiSPSM"), ("virtual", "`virtual` 16k² clipmap")]


def setups_table(d):
    """Per set-up, 10,000 trees: each view's shadow pass (triangles, GPU ms) and camera pass."""
    views = [r["view"] for r in runs(d / "tech-tsm.json")]
    out = ["| set-up | " + " | ".join(f"{v}: shadow M triangles | samples per texel | shadow GPU ms | main GPU ms"
                                    for v in views) + " |",
           "|---|" + "---:|---:|---:|---:|" * len(views)]
    for name, label in SETUPS:
        rows = {r["view"]: r for r in runs(d / f"tech-{name}.json")}
        cells = []
        for v in views:
            r = rows[v]
            if name == "virtual":
                # A still camera keeps every page after the first frame, whose pass is the slowest
                # of the 11 (bench keeps no per-frame triangles): the median would time a cache.
                shadow = f"{r['shadow']['gpu_ms']['max']:.1f} first frame, then {ms(r, 'shadow'):.1f}"
                cells += ["all pages, then none", "–", shadow, f"{ms(r, 'main'):.1f}"]
            else:
                cells += [f"{r['shadow']['triangles'] / 1e6:.2f}", f"{per_texel(r):.2f}", f"{ms(r, 'shadow'):.1f}",
                          f"{ms(r, 'main'):.1f}"]
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
    """The leafy forest's frame beside the blob forest's (TSM 2048², 10,000 trees): with its
    levels of detail (the default), without them, and at 100,000 trees on the same density —
    the last two where the run has them (runs before 2026-11-29 do not)."""
    sets = [("blob", "tech-tsm.json"), ("leafy", "leafy.json"), ("leafy, `--no-lod`", "leafy-no-lod.json"),
            ("leafy, 100,000 trees", "leafy-100k.json")]
    out = ["| forest | view | shadow pass: M triangles | samples per texel | shadow GPU ms | main pass: M triangles "
           "| main GPU ms | frame CPU ms |",
           "|---|---|---:|---:|---:|---:|---:|---:|"]
    for label, name in sets:
        if not (d / name).exists():
            continue
        for r in runs(d / name):
            out.append(f"| {label} | {r['view']} | {r['shadow']['triangles'] / 1e6:.2f} | {per_texel(r):.2f} | "
                       f"{ms(r, 'shadow'):.1f} | {r['main']['triangles'] / 1e6:.2f} | {ms(r, 'main'):.1f} | "
                       f"{r['frame_cpu_ms']['median']:.2f} |")
    return "\n".join(out)


def work_table(d):
    """Each pass's work per fragment on the GPU: the samples its depth test passed and the
    fragments it shaded (bench's fragments_shaded, ARB_pipeline_statistics_query), the shadow
    pass's per map texel and the main pass's per pixel, for the blob and leafy forests' frames.
    A shaded fragment that wrote no sample was thrown away by a late depth test or an alpha test.
    None when the run predates the counter (326f753)."""
    sets = [("blob", "tech-tsm.json"), ("leafy", "leafy.json"), ("leafy, `--no-lod`", "leafy-no-lod.json")]
    rows = []
    for label, name in sets:
        if not (d / name).exists():
            continue
        for r in runs(d / name):
            shadow, main = r["shadow"], r["main"]
            if not shadow.get("fragments_shaded") or not main.get("fragments_shaded"):
                continue
            pixels = r["width"] * r["height"]
            rows.append(f"| {label} | {r['view']} | {per_texel(r):.2f} | "
                        f"{shadow['fragments_shaded'] / shadow['samples_passed']:.2f} | "
                        f"{main['samples_passed'] / pixels:.2f} | "
                        f"{main['fragments_shaded'] / main['samples_passed']:.2f} |")
    if not rows:
        return None
    return "\n".join(["| forest | view | shadow pass: samples per texel | fragments shaded per sample | "
                      "main pass: samples per pixel | fragments shaded per sample |",
                      "|---|---|---:|---:|---:|---:|"] + rows)


def opacity_table(d):
    """What the leaves' opacity layers cost (--foliage-opacity): the leafy forest under the real
    sun, each set-up with the hard test, PCSS, and PCSS with the layers; both passes' GPU ms per
    view, and the camera pass against PCSS's (the issue's ratio) and its lookup's share (what it
    adds to the hard test's pass) against PCSS's."""
    setups = [("tsm", "`tsm` 2048²"), ("csm4x2048-lispsm", "`csm` 4 × 2048² LiSPSM")]
    filters = [("hard", "`hard`"), ("pcss", "`pcss`"), ("layers", "`pcss` + opacity layers")]
    views = [r["view"] for r in runs(d / "opacity-tsm-hard.json")]
    out = ["| set-up | filter | " + " | ".join(f"{v}: shadow GPU ms | camera GPU ms" for v in views) +
           " | camera pass over PCSS's | lookup's share over PCSS's |",
           "|---|---|" + "---:|---:|" * len(views) + "---:|---:|"]
    for name, label in setups:
        data = {f: {r["view"]: r for r in runs(d / f"opacity-{name}-{f}.json")} for f, _ in filters}
        for f, flabel in filters:
            cells = " | ".join(f"{ms(data[f][v], 'shadow'):.1f} | {ms(data[f][v], 'main'):.1f}" for v in views)
            over, share = "–", "–"
            if f == "layers":
                over = " / ".join(f"×{ms(data['layers'][v], 'main') / ms(data['pcss'][v], 'main'):.2f}" for v in views)
                share = " / ".join(
                    f"×{(ms(data['layers'][v], 'main') - ms(data['hard'][v], 'main')) / (ms(data['pcss'][v], 'main') - ms(data['hard'][v], 'main')):.2f}"
                    for v in views)
            out.append(f"| {label} | {flabel} | {cells} | {over} | {share} |")
    return "\n".join(out)


def eval_table(d, local):
    """wrong_pct per view and set-up on the GPU beside llvmpipe's, the same program and scene."""
    names = [("tsm", "`tsm`"), ("csm4x2048-lispsm", "`csm` 4 × 2048² LiSPSM"), ("virtual", "`virtual`"),
             ("tsm-hyperbolic", "`tsm`, hyperbolic depth"), ("psm-receiver-plane", "`psm`, receiver plane, `pcf:3`")]
    gpu = gpu_name(d).replace("NVIDIA ", "")
    out = ["| view | " + " | ".join(f"{label}: {gpu} / llvmpipe" for _, label in names) + " |",
           "|---|" + "---:|" * len(names)]
    figures = {}
    for name, _ in names:
        for where, folder in (("gpu", d), ("cpu", local)):
            with open(folder / f"eval-{name}.json") as f:
                for v in json.load(f)["views"]:
                    figures[(name, where, v["view"])] = v["wrong_pct"]
    worst = {}
    for view in VIEWS:
        cells = []
        for name, _ in names:
            g, c = figures[(name, "gpu", view)], figures[(name, "cpu", view)]
            worst[name] = max(worst.get(name, 0.0), abs(g - c))
            cells.append(f"{g:.3f} / {c:.3f}")
        out.append(f"| {view} | " + " | ".join(cells) + " |")
    out.append("")
    out.append("Largest difference: " + "; ".join(f"{label} {worst[name]:.3f}" for name, label in names) +
               " points of `wrong_pct`.")
    return "\n".join(out)


def main(argv):
    if len(argv) != 3:
        sys.exit(__doc__)
    d, local = Path(argv[1]), Path(argv[2])
    summary = (d / "summary.txt").read_text()
    if "NVIDIA" not in summary and "via EGL device" not in summary:
        print("gpu_tables: warning: summary.txt names no GPU driver", file=sys.stderr)
    machine = [l for l in summary.splitlines()[:4] if not l.startswith("context ")] + [f"limits: {limits_line(d)}"]
    write_into(f"{PAGE}:gpu-machine", "\n".join(["```text"] + machine + ["```"]))
    write_into(f"{PAGE}:gpu-frame", frame_table(d))
    write_into(f"{PAGE}:gpu-limits", limits_table(d))
    write_into(f"{PAGE}:gpu-path", path_table(d))
    write_into(f"{PAGE}:gpu-depth-layout", depth_layout_table(d))
    write_into(f"{PAGE}:gpu-setups", setups_table(d))
    write_into(f"{PAGE}:gpu-filters", filters_table(d, "filter", FILTERS))
    write_into(f"{PAGE}:gpu-lamps", filters_table(d, "lamp", ["hard", "pcf2", "pcss"], shadow_column=False))
    write_into(f"{PAGE}:gpu-leafy", leafy_table(d))
    if (work := work_table(d)) is not None:
        write_into(f"{PAGE}:gpu-work", work)
    if (d / "opacity-tsm-hard.json").exists():
        write_into(f"{PAGE}:gpu-opacity", opacity_table(d))
    write_into(f"{PAGE}:gpu-eval", eval_table(d, local))
    alpha = (d / "alpha-tsm.log").read_text()
    ratio = re.search(r"alpha-tested / opaque: shadow pass ([0-9.]+)×, main pass ([0-9.]+)×", alpha)
    lines = [l for l in alpha.splitlines() if l.startswith(("MASK", "OPAQUE"))]
    if not ratio or len(lines) != 2:
        sys.exit(f"gpu_tables: {d / 'alpha-tsm.log'}: no ratio line")
    write_into(f"{PAGE}:gpu-alpha", "\n".join(["```text"] + lines + [ratio.group(0), "```"]))


if __name__ == "__main__":
    main(sys.argv)
