#!/usr/bin/env python3
"""Where a view's error against the sun disk's truth lies: on the ground or on what stands on it.

  tools/foliage_error_split.py [--into PAGE.md:NAME] LABEL=DUMP_DIR ...   (/usr/bin/python3: Debian's NumPy)

Each DUMP_DIR is what `shadowkit eval --view V --sun-angle A --dump DUMP_DIR` wrote for one view
of a built-in forest. Over the pixels `soft_mae` averages (classes 1-4 of class.npy), prints a
Markdown row per dump: soft_mae, then the share of it on the terrain (instance 0 of
`scene::makeForest`, surface id 1) and on everything else (trees, rocks, movers), and within the
latter the part where the truth is shadowed (< 0.02) but drawn lit, and lit (> 0.98) but drawn
shadowed. The shares add up to soft_mae: they say which surfaces the error is made on. Last, the
trees' mean error where the raster's facet and the ray's are one (normals within 8°) and where
they are not (another card of the same tree, which the comparison counts as one surface). With
--into, the table replaces the body of the block `<!-- table NAME -->` in PAGE.md instead.
"""
import sys

import numpy as np

TERRAIN = 1  # surface_id.npy: instance index + 1; the forest's terrain is its first instance


def compared_pixels(classes, truth):
    """The pixels soft_mae averages (eval::compareSoft): classes 1-4 of class.npy, a finite truth."""
    return (classes >= 1) & (classes <= 4) & np.isfinite(truth)


def split(directory):
    def load(name):
        return np.load(f"{directory}/{name}.npy")

    rendered, truth = load("shadow_term"), load("soft_visibility")
    classes, surface = load("class"), load("surface_id")
    # The raster's facet against the ray's: |cos| below 0.99 (8°) is another card of the tree.
    same_facet = np.abs((load("normal") * load("truth_normal")).sum(axis=-1)) >= 0.99
    compared = compared_pixels(classes, truth)
    n = compared.sum()
    if n == 0:
        sys.exit(f"foliage_error_split: {directory}: no compared pixels (a dump with --sun-angle?)")
    error = np.abs(rendered - truth)
    share = lambda mask: error[compared & mask].sum() / n  # noqa: E731
    standing = surface != TERRAIN
    mean = lambda mask: error[compared & mask].mean()  # noqa: E731
    return (error[compared].mean(), share(~standing), share(standing), share(standing & (truth < 0.02)),
            share(standing & (truth > 0.98)), 100.0 * (compared & standing).sum() / n,
            mean(standing & same_facet), mean(standing & ~same_facet))


def main(args):
    into = None
    if args[:1] == ["--into"] and len(args) > 1:
        into, args = args[1], args[2:]
    if not args:
        sys.exit(__doc__.strip())
    lines = ["| set-up | soft_mae | on the ground | on trees | trees: truth shadowed, drawn lighter | "
             "truth lit, drawn darker | trees' share of pixels | trees' mean error: raster and ray on one facet "
             "/ facets 8° or more apart |",
             "|---|---:|---:|---:|---:|---:|---:|---:|"]
    for arg in args:
        label, _, directory = arg.rpartition("=")
        mae, ground, trees, leak, dark, pixels, one, apart = split(directory)
        lines.append(f"| {label or directory} | {mae:.4f} | {ground:.4f} | {trees:.4f} | {leak:.4f} | {dark:.4f} | "
                     f"{pixels:.0f} % | {one:.3f} / {apart:.3f} |")
    if into:
        from readme_tables import write_into  # the same tools/ folder
        write_into(into, "\n".join(lines))
    else:
        print("\n".join(lines))


if __name__ == "__main__":
    main(sys.argv[1:])
