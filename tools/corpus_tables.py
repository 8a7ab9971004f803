#!/usr/bin/env python3
"""docs/reliability.md's table of the default set-up on the whole public corpus.

Usage: corpus_tables.py RESULTS_DIR [TABLE [FLAGS [DEFAULT_DIR]]]
  RESULTS_DIR  what tools/measure-corpus.sh leaves: NAME.default.json and NAME.focused.json
               (`shadowkit eval --scene FILE --views all --size 640x360 [--technique focused]`)
               for each file that loads, names.tsv (NAME, the file under the corpus) and
               refused.txt (each file shadowkit refused, and its one-line reason)
  TABLE        the table's name in docs/reliability.md (default corpus-bound)
  FLAGS        the flags a candidate added to the default set-up (measure-corpus.sh's CANDIDATE)
  DEFAULT_DIR  the default's own results (tools/measure-corpus.sh's out/corpus), against which a
               candidate's views are counted: the same within 0.005 points, better, worse, and
               the largest change each way

Writes the table between `<!-- table TABLE: tools/measure-corpus.sh -->` and
`<!-- /table -->`: a line counting the files, those refused, those no sunlit view shows, and
those on which the default holds issue 49's bound (wrong_pct at most 1.5 × focused's + 0.1
points) on every view; then a row per model on which it does not, `wrong_pct` default
(focused) on each view, the views outside the bound in bold.
"""
import json
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
from readme_tables import VIEWS, write_into  # noqa: E402

PAGE = "docs/reliability.md"
RATIO, SLACK = 1.5, 0.1


def plural(count, noun):
    return f"{count} {noun}" + ("" if count == 1 else "s")


def views(path):
    with open(path) as f:
        return {v["view"]: v for v in json.load(f)["views"]}


def main(argv):
    if not 2 <= len(argv) <= 5:
        sys.exit(__doc__)
    results = Path(argv[1])
    table = argv[2] if len(argv) > 2 else "corpus-bound"
    setup = f"the default with `{argv[3]}`" if len(argv) > 3 and argv[3] else "the default"
    refused_file = results / "refused.txt"
    refused = refused_file.read_text().split("\n") if refused_file.exists() else []
    refused = [r for r in refused if r]
    names = dict(line.split("\t", 1) for line in (results / "names.tsv").read_text().splitlines() if line)
    rows, unseen, held = [], 0, 0
    for default_path in sorted(results.glob("*.default.json")):
        name = default_path.name[: -len(".default.json")]
        focused_path = results / f"{name}.focused.json"
        if not focused_path.exists():
            sys.exit(f"corpus_tables: {focused_path} is missing: run tools/measure-corpus.sh again")
        default, focused = views(default_path), views(focused_path)
        if all(default[v]["valid_px"] == 0 for v in VIEWS):
            unseen += 1
            continue
        cells, misses = [], 0
        for v in VIEWS:
            d, f = default[v]["wrong_pct"], focused[v]["wrong_pct"]
            outside = d > RATIO * f + SLACK
            misses += outside
            cell = f"{d:.2f} ({f:.2f})"
            cells.append(f"**{cell}**" if outside else cell)
        if misses == 0:
            held += 1
        else:
            rows.append((names[name], misses, f"| `{names[name]}` | " + " | ".join(cells) + " |"))
    measured = held + len(rows)
    total = measured + unseen + len(refused)
    missed = sum(misses for _, misses, _ in rows)
    counted = f"{total} files: {len(refused)} refused in one line, {unseen} that no sunlit view shows, {measured} measured; "
    if not rows:
        lines = [counted + f"{setup} holds the bound on every view of every one."]
    else:
        lines = [
            counted + f"{setup} holds the bound on every view of {held} and misses it "
            f"on {plural(missed, 'view')} of {len(rows)}:",
            "",
            "| model | " + " | ".join(VIEWS) + " |",
            "|---|" + "---:|" * len(VIEWS),
        ] + [row for _, _, row in sorted(rows)]
    if len(argv) > 4 and Path(argv[4]).is_dir() and Path(argv[4]).resolve() != results.resolve():
        lines += ["", against_default(results, Path(argv[4]))]
    write_into(f"{PAGE}:{table}", "\n".join(lines) + "\n")


def against_default(results, default_dir):
    """A candidate's views against the default's: how many are the same within 0.005 points of
    wrong_pct, better and worse, and the largest change each way."""
    same = better = worse = 0
    gain = loss = 0.0
    for path in sorted(results.glob("*.default.json")):
        before_path = default_dir / path.name
        if not before_path.exists():
            continue
        now, before = views(path), views(before_path)
        if all(now[v]["valid_px"] == 0 for v in VIEWS):
            continue  # no sunlit view shows it
        for v in VIEWS:
            change = now[v]["wrong_pct"] - before[v]["wrong_pct"]
            if abs(change) < 0.005:
                same += 1
            elif change < 0:
                better, gain = better + 1, max(gain, -change)
            else:
                worse, loss = worse + 1, max(loss, change)
    return (f"Against the default's last run ({default_dir}), of the {same + better + worse} views: {same} the same "
            f"within 0.005 points, {better} better (by up to {gain:.2f}), {worse} worse (by up to {loss:.2f}).")


if __name__ == "__main__":
    main(sys.argv)
