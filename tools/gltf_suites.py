#!/usr/bin/env python3
"""Every glTF and GLB file (and with --obj, every OBJ file) under the given folders through
`shadowkit render`, as a new user would load them: each must load, or be refused in one line naming the file, with exit 1 —
never crash, hang, or fail another way. Prints a markdown table per folder and what did not
behave; where a file has the glTF Validator's report beside it (FILE.report.json, as in the
validator's own test files), also the files the validator finds valid that shadowkit refuses,
and those it finds in error that shadowkit loads.

    tools/gltf_suites.py [--binary B] [--jobs N] [--timeout S] [--bound [--candidate FLAGS]] [--obj] FOLDER...

With --bound, every file that loads is also evaluated on the six sunlit views at 640 × 360
with the default set-up and with `--technique focused`, and the views where the default errs
more than issue 49's bound (1.5 × focused's `wrong_pct` + 0.1 points) are listed. --candidate
holds a would-be default to it instead: the default set-up with these flags added (e.g.
"--normal-offset 0 --normal-offset-footprint 0.25"; write it --candidate="FLAGS", as its flags start with dashes).

The folders are checkouts of public repositories (docs/reliability.md names them and their
commits). Outputs go to build/gltf-suites/.
"""
import argparse
import collections
import concurrent.futures
import json
import os
import pathlib
import re
import subprocess
import sys
import tempfile


def find_files(folder, extensions):
    out = []
    for root, _, names in os.walk(folder):
        for name in names:
            if name.lower().endswith(extensions):
                out.append(pathlib.Path(root) / name)
    return sorted(out)


def run_one(binary, path, timeout, workdir):
    with tempfile.TemporaryDirectory(dir=workdir) as scratch:
        picture = pathlib.Path(scratch) / "x.png"
        try:
            done = subprocess.run([binary, "render", "--scene", str(path), "--size", "64x36", "--out", str(picture)],
                                  capture_output=True, text=True, errors="replace", timeout=timeout)
        except subprocess.TimeoutExpired:
            return {"path": path, "kind": "hang", "line": f"no answer in {timeout} s"}
        wrote = picture.is_file() and picture.stat().st_size > 0
    errors = [l for l in done.stderr.splitlines() if l.startswith("shadowkit: error:")]
    if done.returncode == 0:
        return {"path": path, "kind": "loaded" if wrote else "wrote nothing", "line": ""}
    if done.returncode < 0:
        return {"path": path, "kind": "crash", "line": f"signal {-done.returncode}"}
    other = [l for l in done.stderr.splitlines() if l and not l.startswith("shadowkit: warning:")]
    if done.returncode == 1 and len(errors) == 1 and len(other) == 1 and str(path) in errors[0]:
        return {"path": path, "kind": "refused", "line": errors[0].split(str(path) + ": ", 1)[-1]}
    return {"path": path, "kind": "other failure", "line": f"exit {done.returncode}: " + " | ".join(other)[:300]}


VIEWS = ["paper", "perpendicular", "into-sun", "sun-behind", "noon", "aerial"]


def wrong_by_view(binary, path, technique, timeout, workdir, flags=()):
    """`wrong_pct` per standard view (None where nothing was compared), or an error line."""
    with tempfile.TemporaryDirectory(dir=workdir) as scratch:
        report = pathlib.Path(scratch) / "eval.json"
        extra = (["--technique", technique] if technique != "default" else []) + list(flags)
        try:
            done = subprocess.run([binary, "eval", "--scene", str(path), "--views", "all", "--size", "640x360",
                                   "--json", str(report)] + extra,
                                  capture_output=True, text=True, errors="replace", timeout=timeout)
        except subprocess.TimeoutExpired:
            return f"eval {technique}: no answer in {timeout} s"
        if done.returncode != 0 or not report.is_file():
            return f"eval {technique}: exit {done.returncode}: " + done.stderr.strip().splitlines()[-1][:200]
        views = json.loads(report.read_text())["views"]
    return {v["view"]: (v["wrong_pct"] if v["valid_px"] > 0 else None) for v in views}


def bound_misses(binary, path, timeout, workdir, candidate=()):
    """The views where the default (with the candidate's flags) is outside 1.5 × focused + 0.1
    points, or an error line."""
    default = wrong_by_view(binary, path, "default", timeout, workdir, candidate)
    if isinstance(default, str):
        return default
    focused = wrong_by_view(binary, path, "focused", timeout, workdir)
    if isinstance(focused, str):
        return focused
    return [(view, default[view], focused[view]) for view in VIEWS
            if default.get(view) is not None and focused.get(view) is not None
            and default[view] > 1.5 * focused[view] + 0.1]


def validator_errors(path):
    report = pathlib.Path(str(path) + ".report.json")
    if not report.is_file():
        return None
    return json.loads(report.read_text())["issues"]["numErrors"]


def kind_of_reason(reason):
    """The refusal's kind: its message with numbers and names taken out."""
    reason = re.sub(r"'[^']*'", "'…'", reason)
    reason = re.sub(r"\d+", "N", reason)
    return reason[:110]


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("folders", nargs="+")
    parser.add_argument("--binary", default="build/apps/shadowkit/shadowkit")
    parser.add_argument("--jobs", type=int, default=2)
    parser.add_argument("--timeout", type=int, default=300)
    parser.add_argument("--bound", action="store_true", help="also hold each loaded file to issue 49's bound")
    parser.add_argument("--candidate", default="", metavar="FLAGS",
                        help="with --bound: flags added to the default set-up, a would-be default held to the bound")
    parser.add_argument("--obj", action="store_true", help="OBJ files too")
    args = parser.parse_args()
    if args.candidate and not args.bound:
        sys.exit("gltf_suites.py: --candidate: only with --bound (it is the set-up held to the bound)")
    candidate = args.candidate.split()
    binary = os.path.abspath(args.binary)
    if not os.access(binary, os.X_OK):
        sys.exit(f"gltf_suites.py: {args.binary}: no shadowkit binary there (build it first)")
    workdir = pathlib.Path("build/gltf-suites")
    workdir.mkdir(parents=True, exist_ok=True)
    bad = []
    for folder in args.folders:
        if not os.path.isdir(folder):
            sys.exit(f"gltf_suites.py: {folder}: not a folder")
        extensions = (".gltf", ".glb", ".obj") if args.obj else (".gltf", ".glb")
        files = find_files(folder, extensions)
        if not files:
            sys.exit(f"gltf_suites.py: {folder}: no {', '.join(extensions)} file under it")
        with concurrent.futures.ThreadPoolExecutor(max_workers=args.jobs) as pool:
            results = list(pool.map(lambda p: run_one(binary, p, args.timeout, workdir), files))
        counts = collections.Counter(r["kind"] for r in results)
        print(f"\n{folder}: {len(files)} files: " + ", ".join(f"{n} {k}" for k, n in counts.most_common()))
        reasons = collections.Counter(kind_of_reason(r["line"]) for r in results if r["kind"] == "refused")
        print("\n| refused because | files |\n|---|---:|")
        for reason, n in reasons.most_common():
            print(f"| {reason} | {n} |")
        for r in results:
            if r["kind"] not in ("loaded", "refused"):
                bad.append(r)
        loaded = [r["path"] for r in results if r["kind"] == "loaded"]
        if args.bound and loaded:
            with concurrent.futures.ThreadPoolExecutor(max_workers=args.jobs) as pool:
                held = list(pool.map(lambda p: bound_misses(binary, p, args.timeout, workdir, candidate), loaded))
            failed = [(p, h) for p, h in zip(loaded, held) if isinstance(h, str)]
            missed = [(p, h) for p, h in zip(loaded, held) if isinstance(h, list) and h]
            held_set_up = f"default {args.candidate}" if candidate else "default"
            print(f"\nIssue 49's bound ({held_set_up} wrong_pct <= 1.5 x focused's + 0.1, 640 x 360): "
                  f"{len(loaded) - len(failed) - len(missed)} of {len(loaded)} files hold it on every view")
            for path, views in missed:
                shown = ", ".join(f"{v} {d:.2f} ({f:.2f})" for v, d, f in views)
                print(f"- {os.path.relpath(path, folder)}: {shown}")
            for path, why in failed:
                bad.append({"path": path, "kind": "eval failure", "line": why})
        judged = [(r, validator_errors(r["path"])) for r in results]
        judged = [(r, e) for r, e in judged if e is not None]
        if judged:
            valid_refused = [r for r, e in judged if e == 0 and r["kind"] == "refused"]
            invalid_loaded = [r for r, e in judged if e > 0 and r["kind"] == "loaded"]
            print(f"\nAgainst the validator's reports ({len(judged)} files, "
                  f"{sum(1 for _, e in judged if e == 0)} without errors): "
                  f"{len(valid_refused)} valid files refused, {len(invalid_loaded)} files with errors loaded")
            if valid_refused:
                print("\n| valid, refused because | files |\n|---|---:|")
                for reason, n in collections.Counter(kind_of_reason(r["line"]) for r in valid_refused).most_common():
                    print(f"| {reason} | {n} |")
            for r in invalid_loaded:
                print(f"- errors, loaded: {os.path.relpath(r['path'], folder)}")
    print(f"\nNot loaded and not refused in one line: {len(bad)}")
    for r in bad:
        print(f"- {r['kind']}: {r['path']}: {r['line']}")
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main())
