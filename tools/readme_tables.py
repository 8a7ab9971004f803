#!/usr/bin/env python3
"""The README's figure tables, generated from `shadowkit eval --json` reports so they cannot
drift from what the program measures.

  tools/readme_tables.py summary [--first-column NAME] LABEL=FILE.json ...
      wrong_pct (pixels_per_texel_p50) per view, and the mean
  tools/readme_tables.py details LABEL=FILE.json ...
      every figure, one row per technique and view

  tools/readme_tables.py visibility BENCH.json ...
      per `shadowkit bench --json` file: triangles and instances per pass, queries, waits,
      GPU ms, the culling's time in GL (pre-pass, masks) and its own thread CPU time
      (tools/measure-visibility.sh)

  tools/readme_tables.py scale CULLED.json FULL.json [CULLED.json FULL.json ...]
      per pair of `shadowkit bench --json` files (the same trees and views, with culling and levels of
      detail and with --no-cull --no-lod): triangles and instances per pass, GPU ms, and the CPU ms of
      the set-up's first frame and of culling, each as culled / full (tools/measure-scale.sh)

  tools/readme_tables.py dynamics LABEL=PATH.json ...
      per `shadowkit eval --path --json` file: flicker_pct and truth_change_pct (mean / p95 /
      max over the frames), mean wrong_pct and pixels_per_texel_p50 (tools/measure-dynamics.sh)

  tools/readme_tables.py model-paths LABEL=DEFAULT.json,FOCUSED.json[,STABILIZED.json] ...
      per model, `shadowkit eval --scene --path --json` files (the default set-up, `--technique
      focused` and optionally the default with `--stabilize`): wrong_pct mean and max, flicker_pct
      mean / p95, and the frames that compared no pixel (tools/measure-corpus-paths.sh)

  tools/readme_tables.py stable LABEL=PATH.json ...
      per `shadowkit eval --path --json` file: flicker_pct (mean / p95 / max), mean wrong_pct
      and pixels_per_texel_p50, and how many frames --stabilize refitted a map in

  tools/readme_tables.py oracle [--name COLUMN,...] FILE.json|results.csv ...
      per view, the lowest wrong_pct of the `shadowkit eval --views all --json` reports (or of a
      sweep's cells, each named by the values of --name's columns) and which one it was, and the
      mean of those (tools/measure-auto-oracle.sh)

  tools/readme_tables.py soft results.csv
      per filter of a sweep with --sun-angle (data/sweeps/soft-filters.json): penumbra_mae per view,
      soft_mae in brackets, and their means
  tools/readme_tables.py soft-summary results.csv
      the same sweep's means per set-up (rows) and filter (columns): the README's soft table
  tools/readme_tables.py soft-forests BLOB.csv LEAFY.csv
      two soft sweeps of the same cells, the blob and the leafy forest: per set-up and filter the
      means of wrong_pct (hard truth) and soft_mae, penumbra_mae, soft_wrong_pct (the sun's disk)
  tools/readme_tables.py soft-table results.csv
      one soft sweep's means per set-up and filter (rows): wrong_pct, soft_mae, penumbra_mae,
      soft_wrong_pct (a filter with --foliage-opacity is named "FILTER + opacity layers")
  tools/readme_tables.py soft-widths results.csv
      the same sweep's penumbra_width_ratio per set-up (rows) and filter (columns): mean (range)
  tools/readme_tables.py soft-disk results.csv
      the same means per set-up (rows) and filter (columns) as soft-summary, of soft_mae /
      soft_wrong_pct: the README's leafy table under the real sun
  tools/readme_tables.py soft-lamps results.csv
      per view and lamp of data/sweeps/soft-lamps.json, per filter: penumbra_mae / soft_mae

  tools/readme_tables.py setup BENCH.json
      per technique, the set-up's CPU µs along the moving camera, sun moving and sun held:
      median (min–max) of the repetitions in shadowkit_setup_bench's --benchmark_format=json
      output (tools/measure-perf.sh)

  tools/readme_tables.py culling BENCH.json
      per culling benchmark of shadowkit_culling_bench's JSON output: CPU ms median (min–max)
      of the repetitions, and what one iteration did (nodes, queries, casters)

  tools/readme_tables.py truth EVAL.json ...
      per view, over runs of `shadowkit eval --views all --json`: truth_seconds median (range),
      truth_rays_per_second median (tools/measure-perf.sh)

  tools/readme_tables.py wrong LABEL=FILE.json ...
      wrong_pct per view and the mean, FILE a `shadowkit eval --json` report or a glob of
      `shadowkit score --json` files (one mask each), e.g. 'out/engines/*-tsm.json'
      (tools/measure-engines.sh)

  tools/readme_tables.py scores FILE.json ...
      one row per `shadowkit score --json` file, named by the file: wrong_pct, false shadow and
      false lit (tools/measure-engines.sh)

  tools/readme_tables.py --into PAGE.md:NAME SUBCOMMAND ...
      any of the above, written into PAGE.md between its lines `<!-- table NAME: how it is measured -->` and
      `<!-- /table -->` (indented as the first marker is) instead of printed

LABEL is the row's name as printed (e.g. '`tsm`' or '`csm` 4 × 1024²'); FILE a `shadowkit eval --json`
report, or a sweep's results.csv with the configuration's rows chosen by COLUMN=VALUE
(`out/readme/results.csv#set-up=tsm`). tools/measure-readme.sh runs the sweep behind every table
(data/sweeps/readme.json) and writes them.
"""
import contextlib
import csv
import glob
import io
import json
import re
import sys

VIEWS = ["paper", "perpendicular", "into-sun", "sun-behind", "noon", "aerial"]


def number(text):
    """A CSV cell as the JSON report had it: int, float, or the text."""
    for kind in (int, float):
        try:
            return kind(text)
        except ValueError:
            pass
    return text


def load(arg):
    label, _, path = arg.partition("=")
    if not path:
        sys.exit(f"readme_tables: expected LABEL=FILE.json or LABEL=results.csv#COLUMN=VALUE, got '{arg}'")
    if "#" in path:  # a sweep's results.csv, the rows of one configuration
        path, _, selector = path.partition("#")
        column, _, value = selector.partition("=")
        with open(path, newline="") as f:
            chosen = [r for r in csv.DictReader(f) if r.get(column) == value]
        if not chosen:
            sys.exit(f"readme_tables: {path}: no row with {column} = {value}")
        rows = {r["view"]: {k: number(v) for k, v in r.items()} for r in chosen}
    else:
        rows = {}
        for file in sorted(glob.glob(path)) or [path]:
            with open(file) as f:
                report = json.load(f)
            # eval's report lists "views"; score's, one entry per mask under "scores".
            rows.update({v["view"]: v for v in report.get("views", report.get("scores", []))})
    missing = [v for v in VIEWS if v not in rows]
    if missing:
        sys.exit(f"readme_tables: {path}: no figures for view(s) {', '.join(missing)}")
    return label, rows


def summary(reports, first_column="technique"):
    print(f"| {first_column} | " + " | ".join(VIEWS) + " | mean |")
    print("|---|" + "---:|" * (len(VIEWS) + 1))
    for label, rows in reports:
        cells = [f"{rows[v]['wrong_pct']:.2f} ({rows[v]['pixels_per_texel_p50']:.1f})" for v in VIEWS]
        mean = sum(rows[v]["wrong_pct"] for v in VIEWS) / len(VIEWS)
        print(f"| {label} | " + " | ".join(cells) + f" | {mean:.2f} |")


def wrong(args):
    """wrong_pct per view and the mean, a row per LABEL=FILE (eval reports or score files)."""
    print("| set-up | " + " | ".join(VIEWS) + " | mean |")
    print("|---|" + "---:|" * (len(VIEWS) + 1))
    for label, rows in (load(a) for a in args):
        mean = sum(rows[v]["wrong_pct"] for v in VIEWS) / len(VIEWS)
        print(f"| {label} | " + " | ".join(f"{rows[v]['wrong_pct']:.2f}" for v in VIEWS) + f" | {mean:.2f} |")


def scores(paths):
    """One row per score file (its name without .json): wrong, false shadow and false lit %."""
    print("| mask | wrong % | false shadow % | false lit % |")
    print("|---|---:|---:|---:|")
    for path in paths:
        with open(path) as f:
            entry = json.load(f)["scores"][0]
        name = path.rsplit("/", 1)[-1].removesuffix(".json")
        print(f"| `{name}` | {entry['wrong_pct']:.2f} | {entry['false_shadow_pct']:.2f} | {entry['false_lit_pct']:.2f} |")


def forests(args):
    """LABEL=BLOB|LEAFY per set-up (each side as load() reads it): the same set-up's mean
    wrong_pct and median pixels per texel on the two forests, their ratio, and the leafy
    forest's worst view."""
    print("| set-up | blob forest: mean wrong% | leafy forest: mean wrong% | leafy / blob | leafy: worst view | "
          "leafy: ppt p50 (mean) |")
    print("|---|---:|---:|---:|---|---:|")
    for arg in args:
        label, _, sides = arg.partition("=")
        blob_source, _, leafy_source = sides.partition("|")
        if not leafy_source:
            sys.exit(f"readme_tables: forests: expected LABEL=BLOB|LEAFY, got '{arg}'")
        _, blob = load(f"{label}={blob_source}")
        _, leafy = load(f"{label}={leafy_source}")
        blob_mean = sum(blob[v]["wrong_pct"] for v in VIEWS) / len(VIEWS)
        leafy_mean = sum(leafy[v]["wrong_pct"] for v in VIEWS) / len(VIEWS)
        worst = max(VIEWS, key=lambda v: leafy[v]["wrong_pct"])
        ppt = sum(leafy[v]["pixels_per_texel_p50"] for v in VIEWS) / len(VIEWS)
        print(f"| {label} | {blob_mean:.2f} | {leafy_mean:.2f} | {leafy_mean / blob_mean:.1f}× | "
              f"{worst} ({leafy[worst]['wrong_pct']:.2f}) | {ppt:.1f} |")


def details(reports):
    print("| technique | view | valid_px | excluded_px | wrong_pct | false_shadow_pct | false_lit_pct | "
          "undersampled_pct | pixels_per_texel_p50 | p99 |")
    print("|---|---|" + "---:|" * 8)
    for label, rows in reports:
        for v in VIEWS:
            r = rows[v]
            print(f"| {label} | {v} | {r['valid_px']} | {r['excluded_px']} | {r['wrong_pct']:.2f} | "
                  f"{r['false_shadow_pct']:.2f} | {r['false_lit_pct']:.2f} | {r['undersampled_pct']:.2f} | "
                  f"{r['pixels_per_texel_p50']:.2f} | {r['pixels_per_texel_p99']:.0f} |")


def visibility(paths):
    print("| trees | visibility | casters | shadow pass: M triangles (instances) | main pass: M triangles (instances) | "
          "queries (waits: median; range) | shadow GPU ms | main GPU ms | culling ms: in GL (pre-pass, masks) | culling's own CPU ms | levels and lists CPU ms |")
    print("|---:|---|---|---:|---:|---:|---:|---:|---:|---:|---:|")
    for path in paths:
        with open(path) as f:
            for r in json.load(f)["runs"]:
                o = r["occlusion"]
                chc = r["visibility"] == "chc"
                waits = o['waits']
                queries = f"{o['queries']['median']:.0f} ({waits['median']:.0f}; {waits['min']:.0f}–{waits['max']:.0f})" if chc else "–"
                print(f"| {r['trees']:,} | {r['visibility']} | {'receivers' if r['receiver_mask'] else 'volume'} | "
                      f"{r['shadow']['triangles'] / 1e6:.2f} ({r['shadow']['instances']}) | "
                      f"{r['main']['triangles'] / 1e6:.2f} ({r['main']['instances']}) | {queries} | "
                      f"{r['shadow']['gpu_ms']['median']:.0f} | {r['main']['gpu_ms']['median']:.0f} | "
                      f"{r['cull_gl_ms']['median']:.1f} ({o['prepass_ms']['median']:.1f}, {r['receiver_mask_ms']['median']:.1f}) | "
                      f"{r['cull_own_ms']['median']:.2f} | {r['list_ms']['median']:.2f} |")


def scale(paths):
    if len(paths) % 2:
        sys.exit("readme_tables: scale takes pairs of files: CULLED.json FULL.json")
    print("| trees | terrain | view | shadow pass: M triangles (instances) | main pass: M triangles (instances) | "
          "shadow GPU ms | main GPU ms | CPU set-up + culling ms |")
    print("|---:|---:|---|---:|---:|---:|---:|---:|")
    for culled_path, full_path in zip(paths[0::2], paths[1::2]):
        with open(culled_path) as f:
            culled = json.load(f)["runs"]
        with open(full_path) as f:
            full = {(r["trees"], r["view"]): r for r in json.load(f)["runs"]}
        for c in culled:
            u = full.get((c["trees"], c["view"]))
            if u is None:
                sys.exit(f"readme_tables: {full_path} has no row for {c['trees']} trees, view {c['view']}")

            def both(f):
                return f"{f(c)} / {f(u)}"

            def tris(p):
                return lambda r: f"{r[p]['triangles'] / 1e6:.2f} ({r[p]['instances']})"

            def gpu(p):
                return lambda r: f"{r[p]['gpu_ms']['median']:.0f}"

            def cpu(r):
                return f"{r['setup_first_ms'] + r['cull_ms']['median']:.2f}"
            print(f"| {c['trees']:,} | {c['terrain_size']:.0f} m | {c['view']} | {both(tris('shadow'))} | "
                  f"{both(tris('main'))} | {both(gpu('shadow'))} | {both(gpu('main'))} | {both(cpu)} |")


def load_path_run(arg):
    """LABEL=FILE.json of `shadowkit eval --path --json` -> (label, path, run, mean pixels_per_texel_p50)."""
    label, _, path = arg.partition("=")
    if not path:
        sys.exit(f"readme_tables: expected LABEL=FILE.json, got '{arg}'")
    with open(path) as f:
        run = json.load(f)
    ppt = [r["pixels_per_texel_p50"] for r in run["frames"]]
    return label, path, run, sum(ppt) / len(ppt)


def dynamics(args):
    print("| technique | sun | flicker_pct mean / p95 / max | truth_change_pct mean / p95 / max | wrong_pct mean | "
          "pixels_per_texel_p50 mean |")
    print("|---|---|---:|---:|---:|---:|")
    for arg in args:
        label, path, run, ppt = load_path_run(arg)
        s = run["summary"]
        fl, tc = s["flicker_pct"], s["truth_change_pct"]
        sun = "held" if "sun-held" in path else "moving"
        print(f"| {label} | {sun} | {fl['mean']:.3f} / {fl['p95']:.3f} / {fl['max']:.3f} | "
              f"{tc['mean']:.3f} / {tc['p95']:.3f} / {tc['max']:.3f} | {s['wrong_pct']['mean']:.2f} | {ppt:.2f} |")


def model_paths(args):
    """Per model along a path: the default set-up's error and flicker beside `focused`'s."""
    names = ["default", "`focused`", "default `--stabilize`"]
    width = len(args[0].partition("=")[2].split(",")) if args else 2
    header = "".join(f" {n}: wrong_pct mean (max) | flicker_pct mean / p95 |" for n in names[:width])
    print(f"| model |{header} frames comparing no pixel |")
    print("|---|" + "---:|---:|" * width + "---:|")
    for arg in args:
        label, _, files = arg.partition("=")
        runs = files.split(",")
        if len(runs) != width or width not in (2, 3):
            sys.exit(f"readme_tables: model-paths: expected LABEL=DEFAULT.json,FOCUSED.json[,STABILIZED.json] "
                     f"alike in every row, got '{arg}'")
        cells, blind = [], []
        for path in runs:
            _, _, run, _ = load_path_run(f"{label}={path}")
            s = run["summary"]
            worst = max(r["wrong_pct"] for r in run["frames"])
            cells.append(f"{s['wrong_pct']['mean']:.2f} ({worst:.2f}) | "
                         f"{s['flicker_pct']['mean']:.3f} / {s['flicker_pct']['p95']:.3f}")
            blind.append(sum(1 for r in run["frames"] if r["valid_px"] == 0))
        print(f"| {label} | {' | '.join(cells)} | {' / '.join(map(str, blind))} of {len(run['frames'])} |")


def stable(args):
    """Flicker, error, texel density and refits along a path, one row per eval --path JSON."""
    print("| technique (sun held) | flicker_pct mean / p95 / max | wrong_pct mean | pixels_per_texel_p50 mean | frames refitted |")
    print("|---|---:|---:|---:|---:|")
    for arg in args:
        label, _, run, ppt = load_path_run(arg)
        s = run["summary"]
        fl = s["flicker_pct"]
        refits = "—" if run.get("refits") is None else f"{run['refits']} of {len(run['frames'])}"
        print(f"| {label} | {fl['mean']:.3f} / {fl['p95']:.3f} / {fl['max']:.3f} | {s['wrong_pct']['mean']:.2f} | "
              f"{ppt:.2f} | {refits} |")


def sweep_configurations(path, name_columns):
    """A sweep's results.csv as (name, {view: row}) per cell, named by the non-empty values of
    `name_columns` (e.g. technique,tsm_focus,cascades)."""
    cells = {}
    with open(path, newline="") as f:
        for r in csv.DictReader(f):
            cells.setdefault(r["cell"], {})[r["view"]] = {k: number(v) for k, v in r.items()}
    out = []
    for rows in cells.values():
        first = next(iter(rows.values()))
        out.append(("-".join(str(first[c]) for c in name_columns if first.get(c) not in (None, "")), rows))
    return out


def soft_rows(paths):
    """A soft sweep's results.csv rows (numbers parsed), its set-up labels and filters, in order."""
    rows = []
    for path in paths:
        with open(path, newline="") as f:
            rows += [{k: number(v) for k, v in r.items()} for r in csv.DictReader(f)]
    for r in rows:  # the seed's eye-space blur is a filter of its own here
        if r.get("blur_iterations") not in (None, "", 0):
            r["filter"] = f"{r['filter']} + blur {r['blur_iterations']}"
        if any(r.get(k) in (True, 1, "true", "True") for k in ("foliage_opacity", "foliage-opacity")):
            r["filter"] = f"{r['filter']} + opacity layers"  # leaves through opacity layers
    return rows, list(dict.fromkeys(r.get("set-up", "") for r in rows)), list(dict.fromkeys(r["filter"] for r in rows))


def soft(paths):
    """Per set-up (a sweep's `set-up` bundle, if it has one) and filter of a sweep's results.csv
    (eval --sun-angle): penumbra_mae per view (soft_mae in brackets) and the means."""
    rows, setups, filters = soft_rows(paths)
    labelled = setups != [""]
    print(("| set-up " if labelled else "") + "| filter | " + " | ".join(VIEWS) + " | mean penumbra_mae | mean soft_mae |")
    print(("|---" if labelled else "") + "|---|" + "---:|" * (len(VIEWS) + 2))
    for setup in setups:
        for name in filters:
            by_view = {r["view"]: r for r in rows if r["filter"] == name and r.get("set-up", "") == setup}
            if not by_view:
                continue
            cells = [f"{by_view[v]['penumbra_mae']:.3f} ({by_view[v]['soft_mae']:.4f})" for v in VIEWS]
            pen = sum(by_view[v]["penumbra_mae"] for v in VIEWS) / len(VIEWS)
            mae = sum(by_view[v]["soft_mae"] for v in VIEWS) / len(VIEWS)
            print((f"| {setup} " if labelled else "") + f"| `{name}` | " + " | ".join(cells) +
                  f" | {pen:.3f} | {mae:.4f} |")


def soft_summary(paths, figures=(("penumbra_mae", "{:.3f}"), ("soft_mae", "{:.4f}")), best_by="soft_mae"):
    """The README's soft-shadow tables: per set-up (rows) and filter (columns) of a sweep's
    results.csv, the means over the views of `figures` (by default penumbra_mae / soft_mae); the
    lowest `best_by` of each row bold."""
    rows, setups, filters = soft_rows(paths)
    keys = [k for k, _ in figures]
    cell = " / ".join(f for _, f in figures)
    print("| set-up | " + " | ".join(f"`{f}`" for f in filters) + " |")
    print("|---|" + "---:|" * len(filters))
    for setup in setups:
        means = {}
        for name in filters:
            by_view = {r["view"]: r for r in rows if r["filter"] == name and r.get("set-up", "") == setup}
            if by_view:  # a filter a set-up cannot take (msm on virtual pages) has none
                means[name] = [sum(by_view[v][k] for v in VIEWS) / len(VIEWS) for k in keys]
        best = min(means, key=lambda n: means[n][keys.index(best_by)])
        cells = [((f"**{cell}**" if n == best else cell).format(*means[n]) if n in means else "—") for n in filters]
        print(f"| {setup} | " + " | ".join(cells) + " |")


def soft_disk(paths):
    """The README's leafy lead: per set-up (rows) and filter (columns) of a soft sweep's
    results.csv, the means over the views of soft_mae / soft_wrong_pct against the sun disk's
    truth; the lowest soft_mae of each row bold."""
    soft_summary(paths, (("soft_mae", "{:.4f}"), ("soft_wrong_pct", "{:.2f} %")))


SOFT_MEANS = ("wrong_pct", "soft_mae", "penumbra_mae", "soft_wrong_pct")


def soft_means(rows, setup, name):
    """The means over the six views of SOFT_MEANS for one set-up and filter; None without all six."""
    by_view = {r["view"]: r for r in rows if r["filter"] == name and r.get("set-up", "") == setup}
    if len(by_view) != len(VIEWS):
        return None
    return [sum(by_view[v][k] for v in VIEWS) / len(VIEWS) for k in SOFT_MEANS]


def soft_table(paths):
    """Per set-up and filter of one soft sweep's results.csv, the means over the views of wrong_pct
    against the hard truth and soft_mae, penumbra_mae and soft_wrong_pct against the sun disk's;
    each set-up's best soft_mae bold where it has several filters."""
    rows, setups, filters = soft_rows(paths)
    print("| set-up | filter | wrong % | soft_mae | penumbra_mae | soft_wrong % |")
    print("|---|---|---:|---:|---:|---:|")
    for setup in setups:
        cells = {name: soft_means(rows, setup, name) for name in filters}
        cells = {name: c for name, c in cells.items() if c}
        best = min(cells, key=lambda n: cells[n][1]) if len(cells) > 1 else None  # one filter: nothing to single out
        for name, m in cells.items():
            mae = f"**{m[1]:.4f}**" if name == best else f"{m[1]:.4f}"
            print(f"| {setup} | `{name}` | {m[0]:.2f} | {mae} | {m[2]:.3f} | {m[3]:.2f} |")


def soft_forests(paths):
    """The two forests under the real sun, side by side: per set-up and filter of two soft sweeps'
    results.csv (the blob forest's first, the leafy forest's second, the same cells), the means
    over the views of wrong_pct against the hard truth and soft_mae, penumbra_mae and soft_wrong_pct
    against the sun disk's; the leafy forest's best soft_mae per set-up bold."""
    if len(paths) != 2:
        sys.exit("readme_tables: soft-forests takes two results.csv: the blob forest's, then the leafy forest's")
    (blob, setups, filters), (leafy, _, _) = soft_rows(paths[:1]), soft_rows(paths[1:])
    means = soft_means

    print("| set-up | filter | blob: wrong % | soft_mae | leafy: wrong % | soft_mae | penumbra_mae | soft_wrong % |")
    print("|---|---|---:|---:|---:|---:|---:|---:|")
    for setup in setups:
        cells = {name: (means(blob, setup, name), means(leafy, setup, name)) for name in filters}
        cells = {name: c for name, c in cells.items() if c[0] and c[1]}
        best = min(cells, key=lambda n: cells[n][1][1])
        for name, (b, l) in cells.items():
            soft = f"**{l[1]:.4f}**" if name == best else f"{l[1]:.4f}"
            print(f"| {setup} | `{name}` | {b[0]:.2f} | {b[1]:.4f} | {l[0]:.2f} | {soft} | {l[2]:.3f} | {l[3]:.2f} |")


def soft_widths(paths):
    """Per set-up (rows) and filter (columns) of a soft sweep's results.csv: the penumbra width
    ratio (rendered 10–90 % band over the true one), its mean over the views and, in brackets, its
    smallest and largest; views whose truth has no penumbra are left out."""
    rows, setups, filters = soft_rows(paths)
    print("| set-up | " + " | ".join(f"`{f}`" for f in filters) + " |")
    print("|---|" + "---:|" * len(filters))
    for setup in setups:
        cells = []
        for name in filters:
            ratios = [r["penumbra_width_ratio"] for r in rows if r["filter"] == name and r.get("set-up", "") == setup
                      and isinstance(r.get("penumbra_width_ratio"), (int, float))
                      and r["penumbra_width_ratio"] == r["penumbra_width_ratio"]]  # not NaN
            cells.append(f"{sum(ratios) / len(ratios):.2f} ({min(ratios):.2f}–{max(ratios):.2f})" if ratios else "—")
        print(f"| {setup} | " + " | ".join(cells) + " |")


def soft_lamps(paths):
    """Per view and lamp of a sweep over views with lamps of some size (data/sweeps/soft-lamps.json),
    per filter: penumbra_mae / soft_mae against the lamp's sphere, from each row's `lights` JSON."""
    rows = []
    for path in paths:
        with open(path, newline="") as f:
            rows += list(csv.DictReader(f))
    filters = list(dict.fromkeys(r["filter"] for r in rows))
    lamps = {}  # (view, light) -> {filter: light's figures}
    for r in rows:
        for light in json.loads(r["lights"]):
            if "soft_mae" in light:
                lamps.setdefault((r["view"], light["light"], light["radius_m"]), {})[r["filter"]] = light
    print("| view | lamp | " + " | ".join(f"`{f}`" for f in filters) + " | penumbra px |")
    print("|---|---|" + "---:|" * (len(filters) + 1))
    for (view, light, radius), by_filter in lamps.items():
        best = min(by_filter, key=lambda f: by_filter[f]["soft_mae"])
        cells = []
        for f in filters:
            text = f"{by_filter[f]['penumbra_mae']:.3f} / {by_filter[f]['soft_mae']:.4f}"
            cells.append(f"**{text}**" if f == best else text)
        penumbra = next(iter(by_filter.values()))["penumbra_px"]
        print(f"| {view} | {light}, {radius * 100:g} cm | " + " | ".join(cells) + f" | {penumbra} |")


def oracle(paths, name_columns=("technique",)):
    """Per view the best wrong_pct of many fixed configurations: what choosing with the truth gives."""
    import os
    reports = []
    for p in paths:
        if p.endswith(".csv"):
            reports += sweep_configurations(p, name_columns)
        else:
            reports.append((os.path.basename(p).removesuffix(".json"), load("x=" + p)[1]))
    print("| view | lowest wrong_pct | configuration | its pixels_per_texel_p95 |")
    print("|---|---:|---|---:|")
    best = []
    for v in VIEWS:
        wrong, name, rows = min((rows[v]["wrong_pct"], name, rows) for name, rows in reports)
        best.append(wrong)
        print(f"| {v} | {wrong:.2f} | {name} | {rows[v]['pixels_per_texel_p95']:.2f} |")
    print(f"| mean | {sum(best) / len(best):.3f} | over {len(reports)} configurations | |")


# Google Benchmark's own numbers in each run's record; the rest are the benchmark's counters.
BENCHMARK_OWN_KEYS = {"iterations", "real_time", "cpu_time", "family_index", "per_family_instance_index",
                      "repetitions", "repetition_index", "threads"}


def repetitions(path):
    """Google Benchmark JSON with --benchmark_repetitions: name -> (sorted times, unit, counters)."""
    with open(path) as f:
        report = json.load(f)
    runs = {}
    for b in report["benchmarks"]:
        if b.get("run_type") != "iteration" or b.get("error_occurred"):
            continue
        times, unit, counters = runs.setdefault(b["run_name"], ([], b["time_unit"], {}))
        times.append(b["cpu_time"])
        for key, value in b.items():
            if key not in BENCHMARK_OWN_KEYS and isinstance(value, (int, float)):
                counters.setdefault(key, []).append(value)
    if not runs:
        sys.exit(f"readme_tables: {path}: no benchmark repetitions (was it run with --benchmark_format=json?)")
    return {name: (sorted(t), unit, c) for name, (t, unit, c) in runs.items()}


def spread(times, scale=1.0, digits=1):
    """'median (min–max)' of a sorted list."""
    mid = times[len(times) // 2] if len(times) % 2 else 0.5 * (times[len(times) // 2 - 1] + times[len(times) // 2])
    return f"{mid * scale:.{digits}f} ({times[0] * scale:.{digits}f}–{times[-1] * scale:.{digits}f})"


def setup(paths):
    runs = repetitions(paths[0])
    to_us = {"ns": 1e-3, "us": 1.0, "ms": 1e3}
    print("| technique | sun moving (the path's) | sun held |")
    print("|---|---:|---:|")
    names = []
    for name in runs:  # benchmark order: the techniques as the bench registers them
        technique = name.split("/")[1]
        if not name.startswith("setup/") or name.startswith("setup/still-cached") or technique in names:
            continue
        names.append(technique)
    for technique in names:
        cells = []
        for where in ("flythrough", "flythrough-sun-held"):
            times, unit, _ = runs.get(f"setup/{technique}/{where}", ([], "us", {}))
            cells.append(spread(times, to_us[unit]) if times else "–")
        label = {"standard": "`standard` (no focus body)"}.get(technique, f"`{technique}`")
        if technique.startswith("csm-"):
            label = f"`csm`, {technique[4:]} splits"
        print(f"| {label} | " + " | ".join(cells) + " |")
    parts = {"visible": "the focus body's V ∩ S alone (`visibleSceneBody`)",
             "focus": "the whole focus body B alone (`computeFocusBody`)"}
    for part, label in parts.items():
        times, unit, _ = runs.get(f"body/{part}/flythrough", ([], "us", {}))
        if times:
            print(f"| {label} | {spread(times, to_us[unit])} | – |")


def culling(paths):
    runs = repetitions(paths[0])
    to_ms = {"ns": 1e-6, "us": 1e-3, "ms": 1.0}
    print("| benchmark | trees | camera | CPU ms: median (min–max) | per iteration |")
    print("|---|---:|---|---:|---|")
    for name, (times, unit, counters) in runs.items():
        _, kind, where, trees = name.split("/")
        did = ", ".join(f"{sorted(v)[len(v) // 2]:,.0f} {k.replace('_', ' ')}" for k, v in counters.items())
        print(f"| `{kind}` | {int(trees):,} | {'moving (flythrough)' if where == 'flythrough' else 'still (perpendicular)'} | "
              f"{spread(times, to_ms[unit], 2)} | {did} |")


def truth(paths):
    per_view = {}
    for path in paths:
        with open(path) as f:
            for v in json.load(f)["views"]:
                if "truth_seconds" not in v:
                    sys.exit(f"readme_tables: {path}: view {v['view']} has no truth_seconds")
                per_view.setdefault(v["view"], []).append((v["truth_seconds"], v["truth_rays_per_second"]))
    print(f"| view | truth seconds: median (range of {len(paths)} runs) | rays per second |")
    print("|---|---:|---:|")
    for view in VIEWS:
        runs = per_view.get(view)
        if not runs:
            sys.exit(f"readme_tables: no truth figures for view {view}")
        seconds = sorted(r[0] for r in runs)
        rays = sorted(r[1] for r in runs)[len(runs) // 2]
        print(f"| {view} | {spread(seconds, 1.0, 3)} | {rays / 1e6:.1f} M |")


def write_into(target, text):
    """Replaces the body of the table block NAME in PAGE (target 'PAGE:NAME') with `text`."""
    page, _, name = target.rpartition(":")
    if not page or not name:
        sys.exit(f"readme_tables: --into: expected PAGE.md:NAME, got '{target}'")
    lines = open(page, encoding="utf-8").read().split("\n")
    start = next((i for i, l in enumerate(lines) if re.match(rf"<!-- table {re.escape(name)}[: ]", l.strip())), None)
    if start is None:
        sys.exit(f"readme_tables: {page}: no line '<!-- table {name}: ... -->'")
    end = next((i for i in range(start + 1, len(lines)) if lines[i].strip() == "<!-- /table -->"), None)
    if end is None:
        sys.exit(f"readme_tables: {page}: table '{name}' has no closing '<!-- /table -->'")
    indent = lines[start][: len(lines[start]) - len(lines[start].lstrip())]
    # Blank lines around the table: Markdown readers differ on a table that touches an HTML comment.
    body = [""] + [indent + l if l else l for l in text.rstrip("\n").split("\n")] + [""]
    open(page, "w", encoding="utf-8").write("\n".join(lines[: start + 1] + body + lines[end:]))
    print(f"readme_tables: wrote table '{name}' into {page}", file=sys.stderr)


def run(argv):
    """Prints the table the arguments (argv[1:], as on the command line) ask for."""
    commands = {"forests": forests, "oracle": oracle, "soft": soft, "soft-summary": soft_summary, "soft-disk": soft_disk,
                "soft-forests": soft_forests, "soft-table": soft_table, "soft-widths": soft_widths, "soft-lamps": soft_lamps, "stable": stable, "model-paths": model_paths, "visibility": visibility, "dynamics": dynamics,
                "setup": setup, "culling": culling, "truth": truth, "scale": scale, "wrong": wrong, "scores": scores}
    if len(argv) >= 5 and argv[1] == "oracle" and argv[2] == "--name":
        oracle(argv[4:], argv[3].split(","))
        return
    if len(argv) >= 3 and argv[1] in commands:
        commands[argv[1]](argv[2:])
        return
    if len(argv) < 3 or argv[1] not in ("summary", "details"):
        sys.exit(__doc__)
    args = argv[2:]
    first_column = "technique"
    if args[:1] == ["--first-column"] and len(args) > 2:
        first_column, args = args[1], args[2:]
    reports = [load(a) for a in args]
    if argv[1] == "summary":
        summary(reports, first_column)
    else:
        details(reports)


if __name__ == "__main__":
    if len(sys.argv) >= 2 and sys.argv[1] == "--into":
        if len(sys.argv) < 5:
            sys.exit(__doc__)
        captured = io.StringIO()
        with contextlib.redirect_stdout(captured):
            run([sys.argv[0]] + sys.argv[3:])
        write_into(sys.argv[2], captured.getvalue())
    else:
        run(sys.argv)
