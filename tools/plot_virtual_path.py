#!/usr/bin/env python3
"""Virtual shadow maps along a camera path: pages and shadow triangles per frame, beside another
technique's shadow triangles on the same frames (docs/virtual-shadow-maps.md).

  tools/plot_virtual_path.py VIRTUAL.json OTHER.json OUT.png

Both JSON files are `shadowkit eval --path ... --json` of the same frames: the first with
`--technique virtual` (each frame has "virtual": pages requested, rendered, resident), the other
any technique (its frames' "shadow_triangles"). Prints the medians the page quotes.
"""
import json
import statistics
import sys

import matplotlib

matplotlib.use("Agg")
from matplotlib import pyplot as plt  # noqa: E402


def frames(path):
    with open(path) as f:
        return json.load(f)["frames"]


def main():
    if len(sys.argv) != 4:
        sys.exit(__doc__.strip().splitlines()[2].strip())
    virtual, other = frames(sys.argv[1]), frames(sys.argv[2])
    if len(virtual) != len(other) or any(a["frame"] != b["frame"] for a, b in zip(virtual, other)):
        sys.exit("plot_virtual_path: the two files must hold the same frames")
    if any("virtual" not in f for f in virtual):
        sys.exit(f"plot_virtual_path: {sys.argv[1]}: not an eval --path --technique virtual file")
    with open(sys.argv[2]) as f:
        other_name = json.load(f)["technique"]
    n = [f["frame"] for f in virtual]
    requested = [f["virtual"]["pages_requested"] for f in virtual]
    rendered = [f["virtual"]["pages_rendered"] for f in virtual]
    resident = [f["virtual"]["pages_resident"] for f in virtual]
    tri_v = [f["virtual"]["shadow_triangles"] / 1e6 for f in virtual]
    tri_o = [f["shadow_triangles"] / 1e6 for f in other]

    fig, (pages, tris) = plt.subplots(2, 1, figsize=(8, 5.5), sharex=True)
    pages.plot(n, resident, label="resident")
    pages.plot(n, requested, label="requested")
    pages.plot(n, rendered, label="rendered this frame")
    pages.set_ylabel("pages")
    pages.legend(loc="upper left", fontsize=8)
    tris.plot(n, tri_v, label="virtual")
    tris.plot(n, tri_o, label=other_name)
    tris.set_ylabel("shadow triangles (M)")
    tris.set_xlabel("frame")
    tris.set_yscale("log")
    tris.legend(loc="upper right", fontsize=8)
    fig.tight_layout()
    fig.savefig(sys.argv[3], dpi=110)

    later = slice(1, None)  # after the first frame, which draws every page it requests
    share = [r / max(s, 1) for r, s in zip(rendered[later], resident[later])]
    ratio = [v / max(o, 1e-9) for v, o in zip(tri_v[later], tri_o[later])]
    print(f"frames {len(n)}: first frame {rendered[0]} pages, {tri_v[0]:.2f} M triangles ({other_name} {tri_o[0]:.2f} M)")
    print(f"after it, medians: {statistics.median(rendered[later])} pages rendered of "
          f"{statistics.median(resident[later])} resident ({100 * statistics.median(share):.1f} %), "
          f"{statistics.median(tri_v[later]):.3f} M triangles against {statistics.median(tri_o[later]):.3f} M "
          f"(ratio {statistics.median(ratio):.2f})")


if __name__ == "__main__":
    main()
