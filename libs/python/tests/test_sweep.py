#!/usr/bin/env python3
"""shadowkit.sweep: the grid a specification expands to, its one-line errors before any cell
runs, rows carrying the recorded golden figures and equal to `shadowkit eval --json`, resuming after a kill, stale results refused, and
the Dask runners (a local cluster, a worker killed mid-sweep) giving the serial rows exactly
once. Run by CTest with PYTHONPATH at the package and SHADOWKIT at the command line."""
import contextlib
import io
import json
import os
import shutil
import signal
import socket
import subprocess
import sys
import tempfile
import time
import unittest

from shadowkit import sweep
from shadowkit.sweep import cli
from shadowkit.sweep.program import eval_options
from shadowkit.sweep.runners import Progress

CLI = os.environ["SHADOWKIT"]
SOURCE_DIR = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", "..", ".."))
SMALL = {"trees": 300, "terrain-size": 200, "terrain-resolution": 32, "size": "160x90"}
# Timings differ run to run; every other figure must not.
TIMINGS = {"seconds", "truth_seconds", "truth_rays_per_second"}


def write_spec(directory, spec, name="spec.json"):
    path = os.path.join(directory, name)
    with open(path, "w") as f:
        json.dump(spec, f)
    return path


def run_main(*argv):
    """cli.main's exit code and what it printed on stderr."""
    err = io.StringIO()
    with contextlib.redirect_stderr(err):
        code = cli.main(list(argv))
    return code, err.getvalue()


def records(out):
    with open(os.path.join(out, "cells.jsonl")) as f:
        return [json.loads(line) for line in f]


def lines_in(path):
    if not os.path.exists(path):
        return 0
    with open(path) as f:
        return sum(1 for _ in f)


def figures(out):
    """{(cell key, view, frame): figures without timings} of a finished sweep."""
    rows = {}
    for record in records(out):
        for row in record["rows"]:
            rows[(record["key"], row.get("view"), row.get("frame"))] = {k: v for k, v in row.items()
                                                                         if k not in TIMINGS}
    return rows


GRID = {"fixed": SMALL, "axes": {"technique": ["focused", "tsm", "lispsm"], "map-size": [512, 1024]},
        "where": ["not (technique == 'focused' and map_size == 512)"]}  # 5 cells


class ExpansionTest(unittest.TestCase):
    def setUp(self):
        self.options = eval_options(CLI)

    def test_a_grid_is_the_product_of_its_axes_in_order_less_what_where_removes(self):
        cells = sweep.expand(GRID, self.options)
        got = [(c.options["technique"], c.options["map-size"]) for c in cells]
        self.assertEqual(got, [("focused", 1024), ("tsm", 512), ("tsm", 1024), ("lispsm", 512), ("lispsm", 1024)])
        self.assertTrue(all(c.options["trees"] == 300 for c in cells))

    def test_bundles_and_derived_options(self):
        # An equal texel budget: the map size derived from the number of maps.
        spec = {"axes": {"set-up": [{"label": "one", "technique": "tsm", "cascades": 1},
                                    {"label": "four", "technique": "csm", "cascades": 4}]},
                "derive": {"map-size": "int(2048 / sqrt(cascades))"}}
        cells = sweep.expand(spec, self.options)
        self.assertEqual([c.labels["set-up"] for c in cells], ["one", "four"])
        self.assertEqual([c.options["map-size"] for c in cells], [2048, 1024])
        self.assertEqual(cells[1].arguments(self.options)[:2], ["--cascades", "4"])

    def test_the_example_specifications_expand(self):
        examples = os.path.join(os.path.dirname(__file__), "..", "..", "..", "data", "sweeps")
        budget = sweep.expand(sweep.load(os.path.join(examples, "texel-budget.toml")), self.options)
        self.assertEqual(len(budget), 4 * 4 * 2)
        for cell in budget:  # every set-up spends the same texels
            texels = cell.options["cascades"] * cell.options["map-size"] ** 2
            self.assertEqual(texels, cell.labels["budget"] ** 2, cell)
        readme = sweep.expand(sweep.load(os.path.join(examples, "readme.json")), self.options)
        self.assertEqual(len(readme), 13)
        oracle = sweep.expand(sweep.load(os.path.join(examples, "auto-oracle.json")), self.options)
        self.assertEqual(len(oracle), 5 + 10 + 24 + 1)  # the union of its four grids
        sizes = {c.options["cascades"]: c.options["map-size"] for c in oracle if c.options["technique"] == "csm"}
        self.assertEqual(sizes, {2: 1440, 3: 1168, 4: 1024})  # sqrt(4M / N), a multiple of 16 below
        self.assertTrue(all(c.options["views"] == "all" for c in oracle))

    def test_grids_are_concatenated_and_their_errors_name_the_grid(self):
        spec = {"fixed": {"trees": 10}, "where": ["map_size >= 1024"],
                "grids": [{"axes": {"technique": ["tsm", "lispsm"], "map-size": [512, 1024]}},
                          {"fixed": {"technique": "csm"}, "axes": {"cascades": [2, 4]},
                           "derive": {"map-size": "2048 // cascades"}}]}
        cells = sweep.expand(spec, self.options)
        self.assertEqual([(c.options["technique"], c.options["map-size"]) for c in cells],
                         [("tsm", 1024), ("lispsm", 1024), ("csm", 1024)])
        spec["grids"][1]["axes"]["cascades"] = []
        with self.assertRaises(sweep.SpecError) as caught:
            sweep.expand(spec, self.options)
        self.assertIn("grids[1].axes.cascades: is empty", str(caught.exception))

    def test_flags_are_present_or_absent(self):
        cells = sweep.expand({"axes": {"stabilize": [True, False]}}, self.options)
        self.assertIn("--stabilize", cells[0].arguments(self.options))
        self.assertNotIn("--stabilize", cells[1].arguments(self.options))

    def test_bad_specifications_name_their_key(self):
        cases = [
            ({"axes": {"technic": ["tsm"]}}, "axes.technic: not an option of shadowkit eval"),
            ({"axes": {"technique": []}}, "axes.technique: is empty"),
            ({"fixed": {"json": "x.json"}}, "fixed.json: not a cell's option"),
            ({"axes": {"serve": [True]}}, "axes.serve: not a cell's option"),
            ({"axes": {"map-size": [1024]}, "where": ["map_size > 4096"]}, "where[0]: 'map_size > 4096' leaves no cell"),
            ({"axes": {"map-size": [1024]}, "where": ["__import__('os')"]}, "where[0]:"),
            ({"axes": {"map-size": [1024]}, "where": ["cascades > 1"]}, "where[0]: 'cascades > 1': unknown name"),
            ({"fixed": {"stabilize": "yes"}}, "fixed.stabilize: --stabilize is a flag"),
            ({"fixed": {"view": "--json=x"}}, "fixed.view: '--json=x' is not a value"),
            ({"axes": {"view": ["noon"]}, "fixed": {"view": "paper"}}, "axes.view: also in fixed"),
            ({"axis": {}}, "unknown key 'axis'"),
            ({"parameters": {"map-size": [1]}}, "parameters.map-size: is an option"),
            ({"parameters": {"budget": []}}, "parameters.budget: expected a non-empty list"),
        ]
        for spec, message in cases:
            with self.subTest(spec=spec):
                with self.assertRaises(sweep.SpecError) as caught:
                    sweep.expand(spec, self.options)
                self.assertIn(message, str(caught.exception))
                self.assertNotIn("\n", str(caught.exception))


class HostileSpecificationTest(unittest.TestCase):
    """A specification is input from outside: thousands of mutations of the example grids must
    each expand or give a SpecError, never another exception, a hang or a huge allocation."""

    def test_mutated_specifications_expand_or_give_one_line(self):
        import random

        options = eval_options(CLI)
        examples = os.path.join(os.path.dirname(__file__), "..", "..", "..", "data", "sweeps")
        seeds = [sweep.load(os.path.join(examples, name)) for name in sorted(os.listdir(examples))] + [GRID]
        values = [None, True, -1, 0, 2.5, 1e308, "", "x", "-", "--json", "'", "a" * 300, [], [1, 2], {},
                  {"label": 1}, "map_size * 'x'", "10 ** 10 ** 10", "(" * 200 + "1" + ")" * 200, "[1] * 10",
                  "max()", "sqrt(-1)", "int('a')", "technique.upper()", "__import__('os')", "lambda: 1",
                  "budget // 0", "cascades if cascades else x", "'a' in 3", "[x for x in [1]]"]
        rng = random.Random(20261125)

        def mutate(node, depth=0):
            if isinstance(node, dict) and node and rng.random() < 0.7:
                key = rng.choice(list(node))
                if rng.random() < 0.15:
                    node.pop(key)
                elif rng.random() < 0.2:
                    node[rng.choice(["where", "derive", "axes", "fixed", "parameters", "label", "view", key + "x"])] = \
                        rng.choice(values)
                else:
                    node[key] = mutate(node[key], depth + 1)
                return node
            if isinstance(node, list) and node and rng.random() < 0.7:
                i = rng.randrange(len(node))
                node[i] = mutate(node[i], depth + 1)
                return node
            return rng.choice(values) if depth or rng.random() < 0.3 else node

        for trial in range(3000):
            spec = mutate(json.loads(json.dumps(rng.choice(seeds))))
            try:
                cells = sweep.expand(spec, options) if isinstance(spec, dict) else None
            except sweep.SpecError as e:
                self.assertNotIn("\n", str(e))
                continue
            except Exception as e:  # noqa: BLE001: the point of the test
                self.fail(f"trial {trial}: {type(e).__name__}: {e} for {json.dumps(spec)[:300]}")
            for cell in cells or []:
                args = cell.arguments(options)
                self.assertFalse(any(a.startswith("--") and a[2:] not in options for a in args), args)


class EstimateTest(unittest.TestCase):
    """The time a sweep says it will take, before and after some of its cells have run."""

    class Measured:  # a Store's measured cells, as estimate_seconds reads them
        def __init__(self, records):
            self.done = {str(i): record for i, record in enumerate(records)}

    @staticmethod
    def cell(**options):
        return sweep.Cell({"views": "all", **{k.replace("_", "-"): v for k, v in options.items()}}, {})

    def seconds(self, **options):
        return cli.cell_seconds(self.cell(**options))

    def test_leaves_the_suns_disk_pixels_and_trees_each_cost_time(self):
        plain = self.seconds(size="1280x720")
        self.assertGreater(self.seconds(size="1280x720", forest="leafy"), 2 * plain)
        self.assertGreater(self.seconds(size="1280x720", sun_angle=0.53), 2 * plain)
        # Under the sun's disk the truth's rays crowd into the leaves' penumbrae: the leafy forest's
        # soft truth costs more a pixel than the blob forest's.
        leafy_soft = self.seconds(size="1280x720", forest="leafy", sun_angle=0.53)
        self.assertGreater(leafy_soft - self.seconds(size="1280x720", forest="leafy"),
                           2 * (self.seconds(size="1280x720", sun_angle=0.53) - plain))
        self.assertLess(self.seconds(size="640x360", forest="leafy", sun_angle=0.53), leafy_soft)
        self.assertGreater(self.seconds(size="1280x720", trees=40000), plain)
        self.assertAlmostEqual(self.seconds(size="1280x720", sun_angle=0), plain)  # a point sun: no soft truth
        self.assertAlmostEqual(self.seconds(size="1280x720", views="paper"), plain / 6)
        self.assertGreater(self.seconds(size="640x360", forest="leafy", foliage_opacity=True),
                           self.seconds(size="640x360", forest="leafy"))
        # A loaded scene is not the forest the forest's options describe.
        self.assertAlmostEqual(self.seconds(size="1280x720", scene="m.glb", forest="leafy", trees=40000),
                               self.seconds(size="1280x720", scene="m.glb"))

    def test_measured_cells_scale_the_estimate_of_the_rest(self):
        todo = [self.cell(size="640x360", forest="leafy", technique=t) for t in ("tsm", "lispsm")]
        fresh = cli.estimate_seconds(todo, self.Measured([]))
        self.assertAlmostEqual(fresh, sum(cli.START_SECONDS + cli.cell_seconds(c) for c in todo))
        # Cells that took three times what the figures say (a slower machine): the rest will too.
        done = [self.cell(size="640x360", forest="leafy", technique="focused"), self.cell(size="160x90")]
        slow = self.Measured([{"options": c.options, "seconds": 3 * cli.cell_seconds(c)} for c in done])
        self.assertAlmostEqual(cli.estimate_seconds(todo, slow), len(todo) * cli.START_SECONDS +
                               3 * (fresh - len(todo) * cli.START_SECONDS))


    def test_the_time_left_weighs_the_cells_left_by_their_estimate(self):
        # A quick cell done in 5 s, a nine times slower one left: 45 s left, not 5.
        weighed = Progress(2, 0, stream=io.StringIO(), expected={"quick": 10.0, "slow": 90.0})
        weighed.step({"key": "quick", "host": "h"}, stored=True)
        self.assertAlmostEqual(weighed.seconds_left(5.0), 45.0)
        weighed.step({"key": "quick", "host": "h"}, stored=False)  # a duplicate changes nothing
        self.assertAlmostEqual(weighed.seconds_left(5.0), 45.0)
        counted = Progress(2, 0, stream=io.StringIO())
        counted.step({"key": "quick", "host": "h"}, stored=True)
        self.assertAlmostEqual(counted.seconds_left(5.0), 5.0)


class SweepTest(unittest.TestCase):
    def setUp(self):
        self.dir = tempfile.mkdtemp(prefix="shadowkit-sweep-test-")

    def tearDown(self):
        shutil.rmtree(self.dir, ignore_errors=True)

    def test_a_bad_value_stops_the_sweep_before_any_cell_runs(self):
        for axes, key in [({"view": ["noon", "nowhere"]}, "axes.view: --view: unknown view \"nowhere\""),
                          ({"filter": ["pcf:3", "pcf:40"]}, "axes.filter: --filter: expected")]:
            out = os.path.join(self.dir, "bad")
            spec = write_spec(self.dir, {"fixed": SMALL, "axes": axes})
            code, err = run_main(spec, "--out", out)
            self.assertEqual(code, 1)
            self.assertIn(key, err)
            self.assertEqual(len(err.strip().splitlines()), 1, err)
            self.assertFalse(os.path.exists(os.path.join(out, "cells.jsonl")))

    def test_a_cells_rows_are_the_recorded_golden_figures_and_what_eval_reports(self):
        # The configuration of data/golden/small-forest.json (each view's size / 4): the rows must
        # carry the figures recorded there (an independent reference, within the golden test's
        # tolerances), and every field eval reports for the same options.
        golden = json.load(open(os.path.join(SOURCE_DIR, "data", "golden", "small-forest.json")))
        config = golden["config"]
        options = {"trees": config["trees"], "terrain-size": config["terrain_size"],
                   "terrain-resolution": config["terrain_resolution"], "map-size": config["map_size"],
                   "size": f"{1280 // config['image_divisor']}x{720 // config['image_divisor']}"}
        spec = write_spec(self.dir, {"fixed": {**options, "views": "perpendicular,noon"},
                                     "axes": {"technique": ["lispsm", "tsm"]}})
        out = os.path.join(self.dir, "out")
        self.assertEqual(run_main(spec, "--out", out)[0], 0)
        rows = figures(out)
        self.assertEqual(len(rows), 4)
        for (_, view, _), row in rows.items():
            recorded = golden["figures"][row["technique"]][view]
            for key in ["wrong_pct", "false_shadow_pct", "false_lit_pct"]:
                self.assertAlmostEqual(row[key], recorded[key], delta=0.05, msg=f"{row['technique']} {view} {key}")
            self.assertAlmostEqual(row["pixels_per_texel_p50"], recorded["pixels_per_texel_p50"],
                                   delta=0.02 * recorded["pixels_per_texel_p50"], msg=f"{row['technique']} {view}")
            self.assertEqual(row["valid_px"], recorded["valid_px"])
        for technique in ["lispsm", "tsm"]:
            report = os.path.join(self.dir, f"{technique}.json")
            subprocess.run([CLI, "eval", "--technique", technique, "--views", "perpendicular,noon", "--json", report,
                            *[str(x) for k, v in options.items() for x in (f"--{k}", v)]], check=True,
                           capture_output=True)
            with open(report) as f:
                expected = json.load(f)["views"]
            for view in expected:
                got = next(r for (_, v, _), r in rows.items() if v == view["view"] and r["technique"] == technique)
                want = {k: v for k, v in sweep.rows_of({"views": [view]})[0].items() if k not in TIMINGS}
                self.assertEqual({k: got[k] for k in want}, want)
        with open(os.path.join(out, "results.csv")) as f:
            self.assertEqual(len(f.read().strip().splitlines()), 1 + 4)
        for name in ["summary.md", "summary.html", "pareto.png"]:
            self.assertTrue(os.path.getsize(os.path.join(out, name)) > 0, name)

    def test_cells_served_by_one_process_equal_cells_in_processes_of_their_own(self):
        # One `eval --serve` keeps the scene, GL context and truths between cells: nothing of one
        # cell (virtual pages, CHC++'s or the GPU culling's last frame, cascades' layers, another
        # forest) may reach the next one's figures.
        spec = write_spec(self.dir, {
            "fixed": {**{k: v for k, v in SMALL.items() if k != "trees"}, "views": "perpendicular,noon"},
            "axes": {"trees": [300, 200], "technique": ["virtual", "csm", "lispsm"], "visibility": ["chc", "gpu"]}})
        served, fresh = os.path.join(self.dir, "served"), os.path.join(self.dir, "fresh")
        self.assertEqual(run_main(spec, "--out", served)[0], 0)
        self.assertEqual(run_main(spec, "--out", fresh, "--fresh-processes")[0], 0)
        self.assertEqual(len(figures(served)), 24)
        self.assertEqual(figures(served), figures(fresh))

    def test_a_served_still_view_after_a_path_equals_a_fresh_one(self):
        # A path's cell measures with a GL context of its own: the still cells after it must not be
        # drawn into a context that is no longer current.
        spec = write_spec(self.dir, {"fixed": SMALL, "axes": {"what": [
            {"label": "still", "view": "noon"}, {"label": "path", "path": "flythrough", "frames": "0:2"},
            {"label": "still again", "view": "perpendicular"}]}})
        served, fresh = os.path.join(self.dir, "served"), os.path.join(self.dir, "fresh")
        code, err = run_main(spec, "--out", served)
        self.assertEqual(code, 0, err)
        self.assertEqual(run_main(spec, "--out", fresh, "--fresh-processes")[0], 0)
        self.assertEqual(figures(served), figures(fresh))

    def test_killed_and_resumed_every_cell_once_with_the_same_figures(self):
        spec = write_spec(self.dir, GRID)
        whole, cut = os.path.join(self.dir, "whole"), os.path.join(self.dir, "cut")
        self.assertEqual(run_main(spec, "--out", whole)[0], 0)
        process = subprocess.Popen([sys.executable, "-m", "shadowkit.sweep", spec, "--out", cut],
                                   stderr=subprocess.DEVNULL, start_new_session=True)
        jsonl = os.path.join(cut, "cells.jsonl")
        deadline = time.monotonic() + 120
        while time.monotonic() < deadline and process.poll() is None:
            if lines_in(jsonl) >= 2:
                break
            time.sleep(0.05)
        os.killpg(process.pid, signal.SIGKILL)
        process.wait()
        kept = len(records(cut))
        self.assertGreaterEqual(kept, 2)
        self.assertLess(kept, 5, "the sweep finished before it was killed: nothing to resume")
        with open(jsonl, "a") as f:
            f.write('{"key": "cut sho')  # a line a kill cut short is ignored
        code, err = run_main(spec, "--out", cut)
        self.assertEqual(code, 0, err)
        self.assertIn(f"{kept} measured before, {5 - kept} to run", err)
        keys = [r["key"] for r in records(cut)]
        self.assertEqual(len(keys), 5)
        self.assertEqual(len(set(keys)), 5)
        self.assertEqual(figures(cut), figures(whole))

    def test_a_changed_option_reruns_only_the_cells_it_changes(self):
        out = os.path.join(self.dir, "out")
        self.assertEqual(run_main(write_spec(self.dir, GRID), "--out", out)[0], 0)
        changed = json.loads(json.dumps(GRID))
        changed["axes"]["technique"] = ["focused", "tsm", "psm"]  # lispsm's two cells become psm's
        code, err = run_main(write_spec(self.dir, changed, "changed.json"), "--out", out, "--dry-run")
        self.assertEqual(code, 0)
        self.assertIn("3 measured before, 2 to run", err)

    def test_a_path_gives_a_row_per_frame_with_the_paths_summary(self):
        spec = write_spec(self.dir, {"fixed": {**SMALL, "path": "flythrough", "frames": "0:3"},
                                     "axes": {"technique": ["tsm"]}})
        out = os.path.join(self.dir, "out")
        code, err = run_main(spec, "--out", out)
        self.assertEqual(code, 0, err)
        rows = records(out)[0]["rows"]
        self.assertEqual([r["frame"] for r in rows], [0, 1, 2])
        self.assertTrue(all(r["path"] == "flythrough" and "flicker_pct_mean" in r for r in rows))
        with open(os.path.join(out, "summary.md")) as f:
            self.assertIn("## Paths", f.read())

    def test_a_worker_with_another_program_measures_nothing(self):
        cell = sweep.expand({"fixed": SMALL}, eval_options(CLI))[0]
        from shadowkit.sweep.cells import task_of
        from shadowkit.sweep.program import data_directory, fingerprint

        expected = dict(fingerprint(CLI, data_directory()), program="0123456789abcdef")
        record = sweep.run_cell(task_of(cell, "k", cell.arguments(eval_options(CLI)), CLI, data_directory(), expected))
        self.assertIn("runs another shadowkit or data", record["error"])
        self.assertNotIn("rows", record)

    def test_the_command_line_runs_the_package_with_itself(self):
        spec = write_spec(self.dir, GRID)
        env = {k: v for k, v in os.environ.items() if k not in ("PYTHONPATH", "SHADOWKIT")}
        done = subprocess.run([CLI, "sweep", spec, "--out", os.path.join(self.dir, "out"), "--dry-run"], env=env,
                              capture_output=True, text=True)
        self.assertEqual(done.returncode, 0, done.stderr)
        lines = done.stdout.strip().splitlines()
        self.assertEqual(len(lines), 5)
        self.assertTrue(all(line.startswith(os.path.basename(CLI) + " eval ") for line in lines), lines)
        self.assertIn("5 cells", done.stderr)

    def test_results_of_another_program_are_refused_not_mixed(self):
        out = os.path.join(self.dir, "out")
        spec = write_spec(self.dir, {"fixed": SMALL, "axes": {"map-size": [512]}})
        self.assertEqual(run_main(spec, "--out", out)[0], 0)
        with open(os.path.join(out, "cells.jsonl")) as f:
            record = json.loads(f.readline())
        record["fingerprint"]["program"] = "0123456789abcdef"
        with open(os.path.join(out, "cells.jsonl"), "w") as f:
            f.write(json.dumps(record) + "\n")
        code, err = run_main(spec, "--out", out)
        self.assertEqual(code, 1)
        self.assertIn("1 cells were measured by another shadowkit", err)
        code, err = run_main(spec, "--out", out, "--discard-stale")
        self.assertEqual(code, 0, err)
        self.assertEqual(len(records(out)), 1)
        self.assertTrue(os.path.exists(os.path.join(out, "cells.stale.jsonl")))


def free_port():
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


@unittest.skipUnless(shutil.which("dask-scheduler") and shutil.which("dask-worker"),
                     "Dask is not installed (Debian: python3-distributed)")
class DaskTest(unittest.TestCase):
    def setUp(self):
        self.dir = tempfile.mkdtemp(prefix="shadowkit-sweep-dask-")
        self.spec = write_spec(self.dir, {"fixed": SMALL, "axes": {"technique": ["focused", "tsm", "lispsm", "psm"],
                                                                      "map-size": [512, 1024]}})  # 8 cells
        self.serial = os.path.join(self.dir, "serial")
        self.assertEqual(run_main(self.spec, "--out", self.serial)[0], 0)
        self.processes = []

    def tearDown(self):
        for p in self.processes:
            with contextlib.suppress(ProcessLookupError):
                os.killpg(p.pid, signal.SIGKILL)
            p.wait()
        shutil.rmtree(self.dir, ignore_errors=True)

    def start(self, *command):
        p = subprocess.Popen(command, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL, start_new_session=True,
                             cwd=self.dir)
        self.processes.append(p)
        return p

    def test_a_local_cluster_gives_the_serial_rows(self):
        out = os.path.join(self.dir, "local")
        code, err = run_main(self.spec, "--out", out, "--local-workers", "2")
        self.assertEqual(code, 0, err)
        self.assertEqual(figures(out), figures(self.serial))

    def test_a_worker_killed_mid_sweep_loses_nothing_and_duplicates_nothing(self):
        address = f"tcp://127.0.0.1:{free_port()}"
        self.start("dask-scheduler", "--host", "127.0.0.1", "--port", address.rsplit(":", 1)[1],
                   "--dashboard-address", ":0")
        workers = [self.start("dask-worker", address, "--nthreads", "1", "--no-nanny", "--no-dashboard")
                   for _ in range(2)]
        out = os.path.join(self.dir, "dask")
        jsonl = os.path.join(out, "cells.jsonl")
        sweep_run = subprocess.Popen([sys.executable, "-m", "shadowkit.sweep", self.spec, "--out", out, "--scheduler",
                                      address], stderr=subprocess.PIPE, text=True)
        deadline = time.monotonic() + 120
        while time.monotonic() < deadline and sweep_run.poll() is None:
            if lines_in(jsonl) >= 1:
                break
            time.sleep(0.05)
        measured_before_the_kill = lines_in(jsonl)
        os.killpg(workers[0].pid, signal.SIGKILL)  # its cells in flight are Dask's to run again
        self.assertLess(measured_before_the_kill, 8, "the sweep finished before the worker was killed")
        _, err = sweep_run.communicate(timeout=300)
        self.assertEqual(sweep_run.returncode, 0, err)
        keys = [r["key"] for r in records(out)]
        self.assertEqual(sorted(keys), sorted(set(keys)))
        self.assertEqual(figures(out), figures(self.serial))


if __name__ == "__main__":
    unittest.main()
