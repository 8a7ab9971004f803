#!/usr/bin/env python3
"""What the OSG adapter's end-to-end test requires (osg_sample_test.cmake):

    osg_sample_check.py ADAPTER.png ADAPTER-score.json OSG-score.json EVAL.json

- the adapter's mask shows shadow: at least 10 % of the pixels OSG drew read shadowed (the
  view looks down on a dense patch of trees, about a third of it in shadow; an
  adapter that hands OSG a camera missing the view draws none);
- scored against the truth, it is within 0.5 points of `eval`'s wrong_pct for the same
  technique (the same set-up drawn by shadowkit's own renderer; the bias and filter differ):
  OSG's matrices read in the wrong order, or a light camera that does not hold the view, put
  shadows in the wrong places and cost far more. (A wrong depth range or flipped rows cancel
  inside OSG, which derives its lookup from the same matrices: shadow_camera_test.cpp holds
  those to the core's own set-up, texel for texel.)
OSG's own figure is printed beside them, not required."""
import json
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(__file__), "..", "..", "..", "tests"))
from shadow_png_check import decode_png  # noqa: E402


def score(path):
    with open(path) as f:
        report = json.load(f)
    entry = (report.get("scores") or report.get("views"))[0]
    return entry["wrong_pct"]


def main():
    if len(sys.argv) != 5:
        sys.exit(__doc__)
    width, _, channels, rows = decode_png(sys.argv[1])
    drawn = shadowed = 0
    for row in rows:
        for x in range(width):
            if channels == 4 and row[x * 4 + 3] == 0:  # alpha 0: OSG drew nothing there
                continue
            drawn += 1
            shadowed += row[x * channels] < 128
    adapter, own, evaluated = score(sys.argv[2]), score(sys.argv[3]), score(sys.argv[4])
    share = 100.0 * shadowed / max(drawn, 1)
    print(f"adapter (tsm in OSG): wrong {adapter:.2f} %, shadowed {share:.1f} % of {drawn} drawn pixels; "
          f"eval tsm: {evaluated:.2f} %; OSG's own default: {own:.2f} %")
    failures = []
    if share < 10.0:
        failures.append(f"the adapter's mask is shadowed on {share:.1f} % of its pixels, expected at least 10 %")
    if adapter > evaluated + 0.5:
        failures.append(f"the adapter's wrong_pct {adapter:.2f} is more than 0.5 points above eval's {evaluated:.2f}")
    if failures:
        sys.exit("osg_sample_check: " + "; ".join(failures))


if __name__ == "__main__":
    main()
