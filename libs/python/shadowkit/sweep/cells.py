"""Measuring one cell: `shadowkit eval` with the cell's options and --json, run where the cell
is measured (this process, or a Dask worker), and its report turned into rows.

A cell is a request to the command line, not a call into the compiled module, so every option
of `eval` (local lights, paths, virtual maps, culling, any the program gains) is a sweep option
and a row holds exactly what `shadowkit eval --json` reports for the same options. By default
the request goes to a `shadowkit eval --serve` process this process keeps (serve.py), which
keeps the scene, GL context and truths between cells; `fresh` runs a process per cell.
"""
import json
import os
import socket
import subprocess
import tempfile
import time

from . import serve
from .program import ProgramError, data_directory, find_program, fingerprint


def task_of(cell, key, arguments, program, data_dir, expected, timeout=None, fresh=False):
    """What a worker needs to measure a cell (plain data: it travels to Dask workers). A timeout
    needs a process of its own per cell (`fresh`), which can be killed alone."""
    return {"key": key, "arguments": arguments, "program": program, "data_dir": data_dir,
            "fingerprint": expected, "timeout": timeout, "fresh": fresh or timeout is not None,
            "options": cell.options, "labels": cell.labels}


def _last_error(stderr):
    lines = [line.strip() for line in stderr.replace("\r", "\n").splitlines() if line.strip()]
    errors = [line for line in lines if "error" in line]
    return (errors or lines or ["no message"])[-1]


def flatten(value, prefix=""):
    """A report's nested objects as columns (`refits.to_cover` → `refits_to_cover`); lists as JSON."""
    out = {}
    for k, v in value.items():
        name = f"{prefix}{k}"
        if isinstance(v, dict):
            out.update(flatten(v, name + "_"))
        elif isinstance(v, list):
            out[name] = json.dumps(v, separators=(",", ":"))
        else:
            out[name] = v
    return out


def rows_of(report):
    """One row per view of a still evaluation, one per frame of a path's (with the path's summary)."""
    if "views" in report:
        return [flatten(view) for view in report["views"]]
    if "frames" in report:
        shared = flatten({k: v for k, v in report.items() if k not in ("frames", "summary")})
        shared.update(flatten(report.get("summary") or {}))
        return [{**shared, **flatten(frame)} for frame in report["frames"]]
    raise ValueError("the report has neither views nor frames")


def run_cell(task):
    """Measures a cell; returns {key, rows, seconds, host, fingerprint} or {key, error, host}.
    Never raises for a cell's own failure (a bad combination of options is a failed cell, not
    a failed sweep)."""
    host = socket.gethostname()
    base = {"key": task["key"], "host": host, "options": task["options"], "labels": task["labels"]}
    try:
        program = task["program"] if os.path.isfile(task["program"]) else find_program()
        data_dir = task["data_dir"] if os.path.isdir(task["data_dir"]) else data_directory()
        mine = fingerprint(program, data_dir)
    except ProgramError as e:
        return {**base, "error": str(e)}
    if mine != task["fingerprint"]:
        return {**base, "error": f"{host} runs another shadowkit or data ({mine}, the sweep's {task['fingerprint']})"}
    with tempfile.TemporaryDirectory(prefix="shadowkit-cell-") as tmp:
        report_path = os.path.join(tmp, "report.json")
        arguments = [*task["arguments"], "--json", report_path]
        start = time.monotonic()
        if task.get("fresh"):
            try:
                done = subprocess.run([program, "eval", *arguments], stdin=subprocess.DEVNULL, stdout=subprocess.DEVNULL,
                                      stderr=subprocess.PIPE,
                                      text=True, env={**os.environ, "SHADOWKIT_DATA_DIR": data_dir},
                                      timeout=task["timeout"])
            except subprocess.TimeoutExpired:
                return {**base, "error": f"ran past --cell-timeout ({task['timeout']} s)"}
            code, stderr = done.returncode, done.stderr
        else:
            try:
                code, stderr = serve.server(program, data_dir).evaluate(arguments)
            except serve.ServerEnded as e:
                serve.drop(program, data_dir)
                return {**base, "error": str(e)}
        seconds = time.monotonic() - start
        if code != 0:
            return {**base, "error": _last_error(stderr)}
        try:
            with open(report_path) as f:
                report = json.load(f)
            rows = rows_of(report)
        except (OSError, ValueError) as e:
            return {**base, "error": f"eval wrote no readable report ({e})"}
    return {**base, "rows": rows, "seconds": seconds, "fingerprint": mine}
