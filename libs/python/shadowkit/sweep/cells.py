"""Measuring one cell: `shadowkit eval` with the cell's options and --json, run where the cell
is measured (this process, or a Dask worker), and its report turned into rows.

A cell is a run of the command line, not a call into the compiled module, so every option of
`eval` (local lights, paths, virtual maps, culling, any the program gains) is a sweep option
and a row holds exactly what `shadowkit eval --json` reports for the same options.
"""
import json
import os
import socket
import subprocess
import tempfile
import time

from .program import ProgramError, data_directory, find_program, fingerprint


def task_of(cell, key, arguments, program, data_dir, expected, timeout=None):
    """What a worker needs to measure a cell (plain data: it travels to Dask workers)."""
    return {"key": key, "arguments": arguments, "program": program, "data_dir": data_dir,
            "fingerprint": expected, "timeout": timeout, "options": cell.options, "labels": cell.labels}


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
        command = [program, "eval", *task["arguments"], "--json", report_path]
        start = time.monotonic()
        try:
            done = subprocess.run(command, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True,
                                  env={**os.environ, "SHADOWKIT_DATA_DIR": data_dir}, timeout=task["timeout"])
        except subprocess.TimeoutExpired:
            return {**base, "error": f"ran past --cell-timeout ({task['timeout']} s)"}
        seconds = time.monotonic() - start
        if done.returncode != 0:
            return {**base, "error": _last_error(done.stderr)}
        try:
            with open(report_path) as f:
                report = json.load(f)
            rows = rows_of(report)
        except (OSError, ValueError) as e:
            return {**base, "error": f"eval wrote no readable report ({e})"}
    return {**base, "rows": rows, "seconds": seconds, "fingerprint": mine}
