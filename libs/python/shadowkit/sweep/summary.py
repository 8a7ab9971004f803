"""A sweep's summary, beside its CSV: summary.md (and summary.html) with the best configuration
per view (or per path) and the Pareto front of error against shadow-map texels, and pareto.png,
one panel per view (matplotlib, written without a display)."""
import html
import math
import os
import sys

DEFAULT_PAGE_TEXELS = 128  # eval's --virtual-page-texels default


def texels(row):
    """Shadow-map texels the configuration pays for: maps × map_size², a virtual map's pool pages ×
    page texels²; None when the report does not say."""
    if row.get("virtual_pool_pages") not in (None, ""):
        side = int(row.get("virtual_page_texels") or DEFAULT_PAGE_TEXELS)
        return int(row["virtual_pool_pages"]) * side * side
    if row.get("maps") not in (None, "") and row.get("map_size") not in (None, ""):
        return int(row["maps"]) * int(row["map_size"]) ** 2
    return None


def pareto_front(points):
    """The (cost, error, item) points no other point beats in both, by increasing cost."""
    front, best = [], math.inf
    for cost, error, item in sorted(points, key=lambda p: (p[0], p[1])):
        if error < best:
            front.append((cost, error, item))
            best = error
    return front


def _texels_text(n):
    return f"{n / (1 << 20):.1f} M" if n is not None else "—"


def _table(header, rows):
    lines = ["| " + " | ".join(header) + " |", "|" + "---|" * len(header)]
    lines += ["| " + " | ".join(str(c) for c in row) + " |" for row in rows]
    return lines


def write_summary(rows, directory, varying, title, named=None):
    """Writes summary.md, summary.html and pareto.png; returns summary.md's path. `varying` are the
    columns that tell the configurations apart (parameters, axes, derived options); `named` those
    of them that name a configuration on the plot (default: all)."""
    named = [k for k in (named or varying) if k not in ("view", "views", "path")]

    def short(row):  # the plot's labels: values only
        return " ".join(str(row[k]) for k in named if k in row and row[k] != "")

    def describe(row):  # the view (or path) is the table's own column
        return ", ".join(f"{k}={row[k]}" for k in varying
                         if k not in ("view", "views", "path") and k in row and row[k] != "") or "(one configuration)"

    still = [r for r in rows if "view" in r and "frame" not in r]
    frames = [r for r in rows if "frame" in r]
    md = [f"# {title}", "", f"{len({r['cell'] for r in rows})} cells, {len(rows)} rows (results.csv).", ""]
    views = list(dict.fromkeys(r["view"] for r in still))
    fronts = {}
    if still:
        md += ["## Best configuration per view (lowest wrong_pct)", ""]
        best_rows = []
        for view in views:
            mine = [r for r in still if r["view"] == view]
            best = min(mine, key=lambda r: r["wrong_pct"])
            best_rows.append([view, describe(best), f"{best['wrong_pct']:.2f}", f"{best['pixels_per_texel_p50']:.2f}",
                              _texels_text(texels(best)), f"{best['seconds']:.2f}"])
            fronts[view] = pareto_front([(texels(r), r["wrong_pct"], r) for r in mine if texels(r) is not None])
        md += _table(["view", "configuration", "wrong_pct", "pixels_per_texel_p50", "texels", "eval s"], best_rows)
        md += ["", "## Pareto front: wrong_pct against texels", "",
               "Per view, the configurations no other beats in both (fewer texels and less error).", ""]
        front_rows = [[view, _texels_text(c), f"{e:.2f}", describe(r)] for view in views for c, e, r in fronts[view]]
        md += _table(["view", "texels", "wrong_pct", "configuration"], front_rows)
    if frames:
        md += ["", "## Paths: mean over the frames (lowest mean wrong_pct first)", ""]
        groups = {}
        for r in frames:
            groups.setdefault((r.get("path", ""), r["cell"]), []).append(r)
        path_rows = []
        for (path, _), members in groups.items():
            mean = sum(m["wrong_pct"] for m in members) / len(members)
            flicker = members[0].get("flicker_pct_mean", "")
            path_rows.append((path, mean, flicker, len(members), describe(members[0])))
        path_rows.sort(key=lambda p: (p[0], p[1]))
        md += _table(["path", "configuration", "frames", "mean wrong_pct", "flicker_pct mean"],
                     [[p, d, n, f"{m:.3f}", f"{f:.3f}" if f != "" else "—"] for p, m, f, n, d in path_rows])
    plot = _plot(fronts, still, directory, short, named) if still else None
    if plot:
        md += ["", f"![wrong_pct against texels per view, Pareto front joined]({os.path.basename(plot)})"]
    md_path = os.path.join(directory, "summary.md")
    with open(md_path, "w") as f:
        f.write("\n".join(md) + "\n")
    _write_html(md, directory, title)
    return md_path


def _plot(fronts, still, directory, short, named):
    try:
        import matplotlib
    except ImportError:  # the tables do not need it
        print("summary: no plot (matplotlib is not installed; Debian: python3-matplotlib)", file=sys.stderr)
        return None

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    views = [v for v in fronts if any(texels(r) is not None for r in still if r["view"] == v)]
    if not views:
        return None
    columns = min(3, len(views))
    lines = math.ceil(len(views) / columns)
    figure, axes = plt.subplots(lines, columns, figsize=(4.8 * columns, 3.6 * lines), squeeze=False)
    for ax, view in zip(axes.flat, views):
        mine = [r for r in still if r["view"] == view and texels(r) is not None]
        ax.scatter([texels(r) / (1 << 20) for r in mine], [r["wrong_pct"] for r in mine], s=14, color="0.6",
                   label="configurations")
        front = fronts[view]
        ax.plot([c / (1 << 20) for c, _, _ in front], [e for _, e, _ in front], "o-", color="C3", ms=4,
                label="Pareto front")
        for c, e, r in front:
            ax.annotate(short(r), (c / (1 << 20), e), fontsize=6, xytext=(3, 3), textcoords="offset points")
        ax.set_xscale("log", base=2)
        ax.margins(x=0.25)
        ax.set_title(f"{view} (front labelled: {' '.join(named)})", fontsize=8)
        ax.set_xlabel("M texels", fontsize=8)
        ax.set_ylabel("wrong_pct", fontsize=8)
        ax.tick_params(labelsize=7)
    for ax in list(axes.flat)[len(views):]:
        ax.axis("off")
    axes.flat[0].legend(fontsize=6)
    figure.tight_layout()
    path = os.path.join(directory, "pareto.png")
    figure.savefig(path, dpi=110)
    plt.close(figure)
    return path


def _write_html(md, directory, title):
    """The summary as a page: its tables as tables, the plot as an image (no Markdown library)."""
    body, table = [], []

    def flush():
        if table:
            cells = [[c.strip() for c in line.strip("|").split("|")] for line in table if not line.startswith("|---")]
            body.append("<table><tr>" + "".join(f"<th>{html.escape(c)}</th>" for c in cells[0]) + "</tr>" +
                        "".join("<tr>" + "".join(f"<td>{html.escape(c)}</td>" for c in r) + "</tr>"
                                for r in cells[1:]) + "</table>")
            table.clear()

    for line in md:
        if line.startswith("|"):
            table.append(line)
            continue
        flush()
        if line.startswith("## "):
            body.append(f"<h2>{html.escape(line[3:])}</h2>")
        elif line.startswith("# "):
            body.append(f"<h1>{html.escape(line[2:])}</h1>")
        elif line.startswith("!["):
            alt, _, src = line[2:].partition("](")
            body.append(f'<img src="{html.escape(src.rstrip(")"))}" alt="{html.escape(alt)}">')
        elif line:
            body.append(f"<p>{html.escape(line)}</p>")
    flush()
    style = ("body{font-family:sans-serif;margin:2em;max-width:70em}table{border-collapse:collapse;margin:1em 0}"
             "td,th{border:1px solid #ccc;padding:.2em .6em;font-size:90%}img{max-width:100%}")
    with open(os.path.join(directory, "summary.html"), "w") as f:
        f.write(f"<!doctype html><meta charset=utf-8><title>{html.escape(title)}</title><style>{style}</style>" +
                "\n".join(body) + "\n")
