#!/usr/bin/python3
"""Pixel statistics of a rendered picture, for the ParaView tests: is it more than a blank background, and is it the
same picture as another.

    /usr/bin/python3 tests/paraview/check_image.py PICTURE.png [--coloured MIN] [--blue] [--same-as OTHER.png]

--coloured MIN  at least this fraction of the pixels are coloured (saturation: max - min channel > 0.15), i.e. not
                the white background, grey walls, black text or uncoloured floes
--blue          the coloured pixels are mostly the low end of the colour map (blue over red): floes at rest drawn on
                the run's speed range, not saturated by a first frame's own range
--same-as OTHER at most 0.1 % of the pixels differ (by more than 0.1 in a channel) from OTHER
The pixel statistics count the map only: the top 85 % of the picture (the scripts keep the colour legend in the
bottom band). Exit 0 when every check holds, 1 naming the failed one.
"""
import argparse
import sys

import matplotlib.image as mpimg
import numpy as np


def load(path):
    try:
        img = mpimg.imread(path)
    except (OSError, SyntaxError, ValueError) as e:
        sys.exit(f"check_image: cannot read {path}: {e}")
    return img[..., :3].astype(float)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("picture")
    ap.add_argument("--coloured", type=float)
    ap.add_argument("--blue", action="store_true")
    ap.add_argument("--same-as")
    a = ap.parse_args()
    img = load(a.picture)
    top = img[: int(0.85 * img.shape[0])]
    sat = top.max(axis=2) - top.min(axis=2)
    coloured = sat > 0.15
    frac = float(coloured.mean())
    failures = []
    print(f"check_image: {a.picture}: {img.shape[1]}x{img.shape[0]}, {100 * frac:.2f} % coloured pixels in the map")
    if a.coloured is not None and not frac >= a.coloured:
        failures.append(f"{100 * frac:.3f} % coloured pixels, fewer than {100 * a.coloured:.3f} %")
    if a.blue:
        px = top[coloured]
        blue = float((px[:, 2] > px[:, 0]).mean()) if len(px) else 0.0
        print(f"check_image: {100 * blue:.1f} % of the coloured pixels are bluer than red")
        if not blue >= 0.9:
            failures.append(f"only {100 * blue:.1f} % of the coloured pixels are blue (floes at rest should be the "
                            "map's low end)")
    if a.same_as:
        other = load(a.same_as)
        if other.shape != img.shape:
            failures.append(f"size {img.shape} differs from {a.same_as}'s {other.shape}")
        else:
            differ = float((np.abs(other - img).max(axis=2) > 0.1).mean())
            print(f"check_image: {100 * differ:.4f} % of the pixels differ from {a.same_as}")
            if not differ <= 1e-3:
                failures.append(f"{100 * differ:.3f} % of the pixels differ from {a.same_as} (at most 0.1 %)")
    for f in failures:
        print(f"check_image: {a.picture}: {f}", file=sys.stderr)
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
