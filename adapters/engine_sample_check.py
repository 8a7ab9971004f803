#!/usr/bin/env python3
"""What an engine adapter's end-to-end test requires (engine_sample_test.cmake):

    engine_sample_check.py ADAPTER.png ADAPTER-score.json OWN-score.json EVAL.json

- the adapter's mask shows shadow: at least 5 % of the pixels the engine drew read shadowed (the
  sun's view looks down on a dense patch of trees, about a third of it in shadow; the spot
  light's test lights the patch from behind the camera, 7–8 % of it in shadow, the point light's
  from above and ahead of it, 30–38 % of it in shadow; an adapter
  that hands the engine a camera missing the view draws none);
- scored against the truth, it is within 0.5 points of `eval`'s wrong_pct for the same
  set-up (drawn by shadowkit's own renderer; the bias and filter differ):
  the engine's matrices read in the wrong order, or a light camera that does not hold the view
  (fitted to a scene box that holds the cameras' far planes), put shadows in the wrong places
  and cost far more, as does a receiver reading the wrong cascade's map. (A wrong depth range or flipped rows cancel inside an engine that derives
  its lookup from the same matrices: each adapter's shadow_camera_test.cpp holds those to the
  core's own set-up, texel for texel.)
The engine's own figure is printed beside them, not required."""
import json
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(__file__), "..", "tests"))
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
            if channels == 4 and row[x * 4 + 3] == 0:  # alpha 0: the engine drew nothing there
                continue
            drawn += 1
            shadowed += row[x * channels] < 128
    adapter, own, evaluated = score(sys.argv[2]), score(sys.argv[3]), score(sys.argv[4])
    share = 100.0 * shadowed / max(drawn, 1)
    print(f"adapter (in the engine): wrong {adapter:.2f} %, shadowed {share:.1f} % of {drawn} drawn pixels; "
          f"eval, the same set-up: {evaluated:.2f} %; the engine's own: {own:.2f} %")
    failures = []
    if share < 5.0:
        failures.append(f"the adapter's mask is shadowed on {share:.1f} % of its pixels, expected at least 5 %")
    if adapter > evaluated + 0.5:
        failures.append(f"the adapter's wrong_pct {adapter:.2f} is more than 0.5 points above eval's {evaluated:.2f}")
    if failures:
        sys.exit("engine_sample_check: " + "; ".join(failures))


if __name__ == "__main__":
    main()
