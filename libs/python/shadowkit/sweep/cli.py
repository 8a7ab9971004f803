"""python3 -m shadowkit.sweep SPEC --out DIR: expand a specification, check every cell, run the
ones not yet measured (here, or on a Dask cluster), and write results.csv, results.jsonl,
summary.md, summary.html and pareto.png into DIR. `shadowkit sweep` runs this."""
import argparse
import concurrent.futures
import os
import re
import subprocess
import sys
import time

from . import spec as specification
from .cells import task_of
from .program import ProgramError, data_directory, eval_options, find_program, fingerprint
from .runners import Progress, run_dask, run_serial
from .store import Store, StoreError, describe
from .summary import write_summary

# The estimate before any cell of this sweep has run. A view of `shadowkit eval` costs a part that
# follows the scene (drawing it: the passes, the levels, the culling) and a part that follows its
# pixels (the ray-traced truth, and under a sun of some size its soft truth, whose rays crowd into
# penumbrae: many more under leaves). Per scene: seconds a view, then seconds per million pixels
# for the point sun's truth and again for the sun's disk, on this project's 2-core machine with
# llvmpipe, from the sweeps' own cells of 2026-11-28/29 (docs/sweeps.md):
#   the default forest: soft-filters.json at 1280 x 720, about 1.3 s a view, 4 s under the sun;
#   the leafy forest: leafy-soft-setups.json at 640 x 360, about 7 s a view under the sun.
# A forest of N trees takes (N / 10,000)^0.7 times as long to draw (40,000 leafy trees: x2.6 a
# view, measured), and with the leaves' opacity layers (foliage-opacity) about twice as long
# (leafy-opacity.json's cells of 2026-11-28). Any other scene is taken as the default forest.
# Once cells of this directory have run, the estimate is scaled by how long they took against
# it: another machine, another scene.
START_SECONDS = 0.3
SCENE_SECONDS = {"forest": (1.0, 0.3, 3.0), "leafy": (3.5, 1.1, 15.0)}  # draw, truth s/M px, soft truth s/M px
TREES, TREES_EXPONENT = 10000, 0.7
OPACITY_FACTOR = 2.0
VIEW_PIXELS = 1280 * 720
STANDARD_VIEWS = {"all": 6, "local": 3}


def _parser():
    p = argparse.ArgumentParser(
        prog="shadowkit sweep",
        description="Expand a sweep specification, check every cell, run those not yet measured (here or on a Dask "
        "cluster) and write results.csv, results.jsonl, summary.md, summary.html and pareto.png into --out. "
        "Re-running resumes. docs/sweeps.md explains the specification.")
    p.add_argument("spec", help="the sweep specification (.json or .toml; data/sweeps/ has examples)")
    p.add_argument("--out", required=True, help="directory of the results (re-running with it resumes)")
    p.add_argument("--program", help="the shadowkit executable (default: $SHADOWKIT, else shadowkit on PATH)")
    where = p.add_mutually_exclusive_group()
    where.add_argument("--scheduler", metavar="ADDRESS", help="run the cells on this Dask scheduler (tcp://HOST:8786)")
    where.add_argument("--local-workers", type=int, metavar="N", help="run the cells on a local Dask cluster of N "
                       "worker processes")
    p.add_argument("--dry-run", action="store_true", help="expand and check the cells, print them and the estimate, "
                   "run none")
    p.add_argument("--discard-stale", action="store_true", help="move the cells another shadowkit or other data "
                   "measured in DIR aside (cells.stale.jsonl) instead of stopping")
    p.add_argument("--cell-timeout", type=float, metavar="S", help="a cell running longer fails (default: none; "
                   "implies --fresh-processes)")
    p.add_argument("--fresh-processes", action="store_true", help="run each cell's eval in a process of its own "
                   "(default: one `eval --serve` process per worker keeps the scene, GL context and truths between "
                   "cells)")
    return p


def _views_and_pixels(cell):
    o = cell.options
    if "path" in o:
        m = re.fullmatch(r"(\d*):(\d*)", str(o.get("frames", "")))
        views = int(m.group(2)) - int(m.group(1) or 0) if m and m.group(2) else 240
    else:
        views = STANDARD_VIEWS.get(str(o.get("views", "")), len(str(o.get("views", "")).split(",")))
    size = re.fullmatch(r"(\d+)x(\d+)", str(o.get("size", "")))
    pixels = int(size.group(1)) * int(size.group(2)) if size else VIEW_PIXELS
    return max(views, 1), pixels


def _number(value, default):
    try:
        return float(value)
    except (TypeError, ValueError):
        return default


def cell_seconds(cell):
    """What one cell should take by the figures above, without the process's start."""
    o = cell.options
    draw, truth, soft = SCENE_SECONDS["leafy" if o.get("forest") == "leafy" and "scene" not in o else "forest"]
    if "scene" not in o:
        draw *= (max(_number(o.get("trees"), TREES), 1.0) / TREES) ** TREES_EXPONENT
    if _number(o.get("sun-angle"), 0.0) > 0.0:
        truth += soft
    views, pixels = _views_and_pixels(cell)
    return views * (draw + truth * pixels / 1e6) * (OPACITY_FACTOR if o.get("foliage-opacity") else 1.0)


def estimate_seconds(cells, store):
    """Seconds the cells should take: the figures above, scaled by how long this directory's
    measured cells took against them when it has some."""
    scale = 1.0
    measured = [(r["seconds"], r["options"]) for r in store.done.values() if r.get("seconds")]
    if measured:
        predicted = sum(cell_seconds(specification.Cell(options, {})) for _, options in measured)
        scale = sum(seconds for seconds, _ in measured) / predicted if predicted > 0 else 1.0
    return sum(START_SECONDS + scale * cell_seconds(cell) for cell in cells)


def check_cells(cells, arguments, program, data_dir):
    """Every cell through `shadowkit eval --check` (which renders nothing) before any runs; the
    first failure, in grid order, as a one-line error naming the specification's key."""
    env = {**os.environ, "SHADOWKIT_DATA_DIR": data_dir}

    def check(args):
        done = subprocess.run([program, "eval", *args, "--check"], stdin=subprocess.DEVNULL, capture_output=True,
                              text=True, env=env)
        return done.returncode, done.stderr.strip().splitlines()[-1:] or ["(no message)"]

    distinct = list(dict.fromkeys(tuple(a) for a in arguments))
    with concurrent.futures.ThreadPoolExecutor(max_workers=8) as pool:
        results = dict(zip(distinct, pool.map(check, distinct)))
    for cell, args in zip(cells, arguments):
        code, message = results[tuple(args)]
        if code != 0:
            text = message[0].removeprefix("shadowkit: error: ").removesuffix(" (see shadowkit --help)")
            flag = re.match(r"--([a-z][a-z0-9-]*)", text)
            origin = cell.origins.get(flag.group(1)) if flag else None
            raise specification.SpecError(f"{origin or 'cell'}: {text}" + ("" if origin else f" ({cell.options})"))


def _minutes(seconds):
    return f"{seconds / 60:.1f} min" if seconds >= 60 else f"{seconds:.0f} s"


def main(argv=None):
    args = _parser().parse_args(argv)
    if args.local_workers is not None and args.local_workers < 1:
        print("shadowkit sweep: error: --local-workers: must be at least 1", file=sys.stderr)
        return 1
    store = None
    try:
        program = find_program(args.program)
        takes_value = eval_options(program)
        spec = specification.load(args.spec)
        cells = specification.expand(spec, takes_value, source=args.spec)
        data_dir = data_directory()
        print_ = fingerprint(program, data_dir)
        keys = [cell.key(print_, specification.files_named(cell)) for cell in cells]
        if len(set(keys)) != len(keys):
            first = next(i for i, k in enumerate(keys) if keys.index(k) != i)
            raise specification.SpecError(f"{args.spec}: cells {keys.index(keys[first]) + 1} and {first + 1} of the "
                                           f"grid have the same options ({cells[first].options})")
        arguments = [cell.arguments(takes_value) for cell in cells]
        started = time.monotonic()
        check_cells(cells, arguments, program, data_dir)
        timings = {"checked": time.monotonic() - started}
        store = Store(args.out, print_)
        store.refuse_stale(args.discard_stale)
        todo = [i for i, key in enumerate(keys) if key not in store.done]
        rows = sum(_views_and_pixels(c)[0] for c in cells)
        print(f"sweep {args.spec}: {len(cells)} cells ({rows} views or frames); {len(cells) - len(todo)} measured "
              f"before, {len(todo)} to run: about {_minutes(estimate_seconds([cells[i] for i in todo], store))} "
              f"serially ({describe(print_)})", file=sys.stderr)
        if store.cut_short:
            print(f"{args.out}: {store.cut_short} cell(s) cut short by an interrupted run will run again",
                  file=sys.stderr)
        if args.dry_run:
            for i in todo:
                print(" ".join([os.path.basename(program), "eval", *arguments[i]]))
            return 0
        tasks = [task_of(cells[i], keys[i], arguments[i], program, data_dir, print_, args.cell_timeout,
                         args.fresh_processes) for i in todo]
        progress = Progress(len(cells), len(cells) - len(todo),
                            expected={keys[i]: cell_seconds(cells[i]) for i in todo})
        started = time.monotonic()
        if args.scheduler or args.local_workers:
            run_dask(tasks, store, progress, scheduler=args.scheduler, local_workers=args.local_workers)
        else:
            run_serial(tasks, store, progress)
        progress.finish()
        timings["measured"] = time.monotonic() - started
    except (specification.SpecError, ProgramError, StoreError, RuntimeError, OSError) as e:
        print(f"shadowkit sweep: error: {e}", file=sys.stderr)
        return 1
    except KeyboardInterrupt:
        print(f"\nshadowkit sweep: interrupted: {len(store.done) if store else 0} cells kept in {args.out}; "
              "run again to go on", file=sys.stderr)
        if store:
            store.close()
            store.write_tables(keys)
        return 130
    finally:
        if store:
            store.close()
    started = time.monotonic()
    rows = store.write_tables(keys)
    if rows:
        title = spec.get("description") or os.path.basename(args.spec)
        summary = write_summary(rows, args.out, _varying(spec), title, named=_varying(spec, derived=False))
        print(f"results: {os.path.join(args.out, 'results.csv')} ({len(rows)} rows), summary: {summary}",
              file=sys.stderr)
    print(f"sweep: checked {len(cells)} cells in {timings['checked']:.2f} s, measured {len(todo)} in "
          f"{timings['measured']:.2f} s, wrote the results and summary in {time.monotonic() - started:.2f} s",
          file=sys.stderr)
    failed = len(cells) - sum(k in store.done for k in keys)
    if failed:
        print(f"shadowkit sweep: error: {failed} cells failed (errors in {os.path.join(args.out, 'failures.jsonl')})",
              file=sys.stderr)
        return 1
    return 0


def _varying(spec, derived=True):
    """The columns that tell a specification's configurations apart, its grids' too (with `derived`
    false, only those given: the plot's labels)."""
    names = []
    for grid in [spec, *spec.get("grids", [])]:
        axes = grid.get("axes", {})
        for n in [*grid.get("parameters", {}), *axes, *(grid.get("derive", {}) if derived else {})]:
            bundle = isinstance(axes.get(n), list) and axes[n] and isinstance(axes[n][0], dict)
            name = n if bundle else n.replace("-", "_")
            if name not in names:
                names.append(name)
    return names
