#!/usr/bin/env python3
"""flicker_pct per frame for several `shadowkit eval --path --csv` runs, as one SVG line plot.

  tools/plot_flicker.py OUT.svg "TITLE" LABEL=RUN.csv ...

Written by hand (no plotting package is a dependency): axes, ticks, a legend, one polyline
per run. tools/measure-dynamics.sh writes the CSVs.
"""
import csv
import sys

COLOURS = ["#c0392b", "#2471a3", "#229954", "#7d3c98", "#d68910", "#17a589", "#34495e", "#a04000"]
W, H, LEFT, RIGHT, TOP, BOTTOM = 900, 480, 70, 190, 40, 50


def load(arg):
    label, _, path = arg.partition("=")
    if not path:
        sys.exit(f"plot_flicker: expected LABEL=RUN.csv, got '{arg}'")
    xs, ys = [], []
    with open(path) as f:
        for row in csv.DictReader(f):
            if row["flicker_pct"]:
                xs.append(float(row["frame"]))
                ys.append(float(row["flicker_pct"]))
    return label, xs, ys


def nice_step(span, ticks=5):
    raw = span / ticks
    for m in (1, 2, 2.5, 5, 10):
        step = m * 10 ** __import__("math").floor(__import__("math").log10(raw))
        if step >= raw:
            return step
    return raw


def main():
    if len(sys.argv) < 4:
        sys.exit(__doc__)
    out, title, runs = sys.argv[1], sys.argv[2], [load(a) for a in sys.argv[3:]]
    x_max = max(max(xs) for _, xs, _ in runs if xs)
    y_max = max(max(ys) for _, _, ys in runs if ys) * 1.05 or 1.0
    y_step = nice_step(y_max)
    plot_w, plot_h = W - LEFT - RIGHT, H - TOP - BOTTOM
    sx = lambda x: LEFT + plot_w * x / x_max
    sy = lambda y: TOP + plot_h * (1.0 - y / y_max)
    parts = [f'<svg xmlns="http://www.w3.org/2000/svg" width="{W}" height="{H}" font-family="sans-serif" font-size="12">',
             f'<rect width="{W}" height="{H}" fill="white"/>',
             f'<text x="{W / 2}" y="22" text-anchor="middle" font-size="15">{title}</text>',
             f'<line x1="{LEFT}" y1="{TOP + plot_h}" x2="{LEFT + plot_w}" y2="{TOP + plot_h}" stroke="black"/>',
             f'<line x1="{LEFT}" y1="{TOP}" x2="{LEFT}" y2="{TOP + plot_h}" stroke="black"/>',
             f'<text x="{LEFT + plot_w / 2}" y="{H - 12}" text-anchor="middle">frame</text>',
             f'<text x="16" y="{TOP + plot_h / 2}" text-anchor="middle" transform="rotate(-90 16 {TOP + plot_h / 2})">'
             'flicker_pct (% of compared pixels)</text>']
    y = 0.0
    while y <= y_max + 1e-12:
        parts.append(f'<line x1="{LEFT}" y1="{sy(y):.1f}" x2="{LEFT + plot_w}" y2="{sy(y):.1f}" stroke="#e5e5e5"/>')
        parts.append(f'<text x="{LEFT - 6}" y="{sy(y) + 4:.1f}" text-anchor="end">{y:g}</text>')
        y += y_step
    x_step = nice_step(x_max, 6)
    x = 0.0
    while x <= x_max + 1e-9:
        parts.append(f'<text x="{sx(x):.1f}" y="{TOP + plot_h + 18}" text-anchor="middle">{x:g}</text>')
        x += x_step
    for k, (label, xs, ys) in enumerate(runs):
        colour = COLOURS[k % len(COLOURS)]
        points = " ".join(f"{sx(a):.1f},{sy(b):.1f}" for a, b in zip(xs, ys))
        parts.append(f'<polyline fill="none" stroke="{colour}" stroke-width="1.5" points="{points}"/>')
        ly = TOP + 10 + 20 * k
        parts.append(f'<line x1="{LEFT + plot_w + 15}" y1="{ly}" x2="{LEFT + plot_w + 40}" y2="{ly}" stroke="{colour}" stroke-width="3"/>')
        parts.append(f'<text x="{LEFT + plot_w + 46}" y="{ly + 4}">{label}</text>')
    parts.append("</svg>")
    with open(out, "w") as f:
        f.write("\n".join(parts) + "\n")


if __name__ == "__main__":
    main()
