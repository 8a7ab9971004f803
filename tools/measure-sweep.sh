#!/usr/bin/env bash
# docs/sweeps.md's throughput figures: the example grid data/sweeps/texel-budget.toml (32 cells) run
# four ways on this machine, each into a fresh directory — its cells' command lines as bare
# `shadowkit eval` runs one after another (what a shell loop pays), `shadowkit sweep
# --fresh-processes` (the same processes, run by the sweep), `shadowkit sweep` (one `eval --serve`
# process keeping the scene, GL context and truths) and `shadowkit sweep --local-workers 2` (a local
# Dask cluster, a serving process per worker) — and the wall time and cells per minute of each.
set -euo pipefail
cd "$(dirname "$0")/.."
B=build/apps/shadowkit/shadowkit
spec=${SPEC:-data/sweeps/texel-budget.toml}
out=${OUT:-build/sweep-throughput}
rm -rf "$out" && mkdir -p "$out"
mapfile -t commands < <("$B" sweep "$spec" --out "$out/dry" --dry-run 2>/dev/null)
cells=${#commands[@]}
now() { date +%s.%N; }
start=$(now)
for c in "${commands[@]}"; do
  read -r -a words <<<"$c"
  "$B" "${words[@]:1}" --json "$out/bare.json" >/dev/null 2>&1
done
bare=$(echo "$(now) - $start" | bc)
# The sweep's last line: "sweep: checked N cells in A s, measured N in B s, wrote ... in C s".
sweep() { local start; start=$(now); "$B" sweep "$spec" "$@" 2>"$out/log"; echo "$(echo "$(now) - $start" | bc) $(tail -1 "$out/log")"; }
fresh=$(sweep --out "$out/fresh" --fresh-processes)
serial=$(sweep --out "$out/serial")
dask=$(sweep --out "$out/dask" --local-workers 2)
python3 - "$cells" "$bare" "$fresh" "$serial" "$dask" "$out" <<'PY'
import json, re, sys
cells, bare = int(sys.argv[1]), float(sys.argv[2])
def parse(text):
    wall = float(text.split()[0])
    check, measure, write = map(float, re.search(r"in ([\d.]+) s, measured \d+ in ([\d.]+) s, .* in ([\d.]+) s", text).groups())
    return wall, check, measure, write
def eval_seconds(run):  # what the cells' eval processes took, as the sweep timed them
    with open(f"{sys.argv[6]}/{run}/cells.jsonl") as f:
        return sum(json.loads(line)["seconds"] for line in f)
print(f"| run ({cells} cells) | wall s | of which: checks, cells, results and summary s | cells / min (cells phase) | "
      "against the bare runs (cells phase) | the sweep's own ms a cell |")
print("|---|---:|---:|---:|---:|---:|")
print(f"| bare `shadowkit eval` runs, one after another | {bare:.1f} | — | {cells / bare * 60:.1f} | — | — |")
for run, name, text in [("fresh", "`shadowkit sweep --fresh-processes`, serial", sys.argv[3]),
                        ("serial", "`shadowkit sweep`, serial (one `eval --serve`)", sys.argv[4]),
                        ("dask", "`shadowkit sweep --local-workers 2`", sys.argv[5])]:
    wall, check, measure, write = parse(text)
    against = f"{100 * (measure / bare - 1):+.1f} % time" if run == "fresh" else f"{bare / measure:.2f}× the throughput"
    # Serially: the cells phase less its evaluations' time is the sweep's own cost (the request, the record).
    own = f"{1000 * (measure - eval_seconds(run)) / cells:.0f}" if run != "dask" else "—"
    print(f"| {name} | {wall:.1f} | {check:.1f}, {measure:.1f}, {write:.1f} | {cells / measure * 60:.1f} | {against} | {own} |")
PY
