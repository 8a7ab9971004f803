#!/usr/bin/env python3
"""The HTML reports opened in a real browser (headless Chromium): every picture loads, every
view and path is on the page, and the screenshot shows the pictures, not a blank page.

  report_browser_test.py SHADOWKIT_BINARY

Writes `eval --report` (two views), `compare --report` (two configurations),
`eval --path --report` (three frames) and `bench --report` (two views) of a small forest into a scratch directory. Exits 77
(skipped, with the reason) where Chromium is not installed: tools/install-deps.sh installs it.
"""
import os
import re
import shutil
import subprocess
import sys
import tempfile

SKIP = 77


def chromium():
    for name in ("chromium", "chromium-browser", "google-chrome"):
        if shutil.which(name):
            return shutil.which(name)
    return None


def run(cmd):
    result = subprocess.run(cmd, capture_output=True, text=True, timeout=300)
    if result.returncode != 0:
        sys.exit(f"FAIL: {' '.join(cmd)} exited {result.returncode}:\n{result.stderr}")
    return result


def browse(browser, page, profile, *extra):
    # --no-sandbox: CI runs as root; a profile of its own keeps runs apart; the virtual time
    # budget lets the page's load event (and its image count) run before the DOM is dumped.
    return run([browser, "--headless", "--no-sandbox", "--disable-gpu", f"--user-data-dir={profile}",
                "--virtual-time-budget=10000", "--hide-scrollbars", *extra, "file://" + page])


def check_page(browser, page, profile, sections, sky_pixels_at_least):
    html = open(page, encoding="utf-8").read()
    images_in_file = len(re.findall(r"<img ", html))
    dom = browse(browser, page, profile, "--dump-dom").stdout
    body = re.search(r"<body[^>]*>", dom)
    if not body:
        sys.exit(f"FAIL: {page}: the browser returned no <body>")
    loaded = re.search(r'data-images="(\d+)"', body.group(0))
    broken = re.search(r'data-broken-images="(\d+)"', body.group(0))
    if not loaded or not broken:
        sys.exit(f"FAIL: {page}: the page's load script did not run ({body.group(0)})")
    if int(loaded.group(1)) != images_in_file or images_in_file == 0:
        sys.exit(f"FAIL: {page}: the browser saw {loaded.group(1)} images, the file has {images_in_file}")
    if int(broken.group(1)) != 0:
        missing = re.search(r'<p id="broken">([^<]*)</p>', dom)
        sys.exit(f"FAIL: {page}: {broken.group(1)} images did not load: {missing.group(1) if missing else ''}")
    for section in sections:
        if f'id="{section}"' not in dom:
            sys.exit(f"FAIL: {page}: no section '{section}' in the rendered page")

    shot = os.path.join(os.path.dirname(page), os.path.basename(page) + ".png")
    browse(browser, page, profile, "--window-size=1400,3000", f"--screenshot={shot}")
    import numpy as np
    from matplotlib import image as mpimg
    pixels = (mpimg.imread(shot)[..., :3] * 255).round().astype(int)
    # The shadow pictures' sky is (150, 180, 215): it is on screen only if they were drawn.
    sky = np.all(np.abs(pixels - np.array([150, 180, 215])) <= 2, axis=-1).sum()
    white = np.all(pixels >= 250, axis=-1).mean()
    if sky < sky_pixels_at_least or white > 0.97:
        sys.exit(f"FAIL: {shot}: {sky} sky pixels (want >= {sky_pixels_at_least}), {100 * white:.1f} % white")
    print(f"{os.path.basename(page)}: {images_in_file} images loaded, sections {', '.join(sections)}; "
          f"screenshot {sky} sky pixels")


def main():
    if len(sys.argv) != 2:
        sys.exit(__doc__)
    shadowkit = sys.argv[1]
    browser = chromium()
    if not browser:
        print("SKIP: no Chromium (chromium) on this machine; tools/install-deps.sh installs it")
        sys.exit(SKIP)
    small = ["--trees", "200", "--terrain-size", "256"]
    with tempfile.TemporaryDirectory() as scratch:
        profile = os.path.join(scratch, "profile")
        run([shadowkit, "eval", *small, "--views", "paper,noon", "--size", "240x136",
             "--report", os.path.join(scratch, "eval.html")])
        check_page(browser, os.path.join(scratch, "eval.html"), profile, ["view-paper", "view-noon"], 2000)
        run([shadowkit, "compare", *small, "--view", "perpendicular", "--size", "240x136", "--configs",
             "technique=tsm;technique=lispsm", "--out", os.path.join(scratch, "compare.png"),
             "--report", os.path.join(scratch, "compare.html")])
        check_page(browser, os.path.join(scratch, "compare.html"), profile, ["view-perpendicular"], 2000)
        run([shadowkit, "eval", *small, "--path", "flythrough", "--frames", "0:3", "--size", "160x90",
             "--report", os.path.join(scratch, "path.html")])
        check_page(browser, os.path.join(scratch, "path.html"), profile, ["path-flythrough"], 0)
        run([shadowkit, "bench", "--trees", "200", "--terrain-size", "256", "--views", "paper,noon", "--frames", "2",
             "--size", "240x136", "--report", os.path.join(scratch, "bench.html")])
        check_page(browser, os.path.join(scratch, "bench.html"), profile, ["table-1"], 0)


if __name__ == "__main__":
    main()
