#!/usr/bin/python3
"""Draw the channel geometry of a run: walls, the ice region with its floes at t = 0, and the dimensions.

    ./build/polyfloe run dem/scenes/channel.yaml -o results/channel_geometry --set run.duration=0.001 \
        --set output.vtk=false
    /usr/bin/python3 postprocess/plot_channel_geometry.py results/channel_geometry -o docs/figures/channel_geometry.png

Reads RUN/results.h5 (frame 0: walls are the bodies with motion != 0) and the `channel` and `floe_field` blocks of
RUN/scene.resolved.yaml (every key resolved by polyfloe). Marks the strait entrance (the gate x = basin_x_max +
funnel_length through which /diagnostics/channel counts the ice area), the funnel and the strait.
"""
import argparse
import os
import re
import sys

import h5py
import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
from matplotlib.collections import PolyCollection  # noqa: E402
from matplotlib.patches import Rectangle  # noqa: E402

from polyfloe_post.frames import frame_polygons  # noqa: E402


def resolved_block(path, block):
    """{key: text} of one top-level block of a scene.resolved.yaml (flat 'key: value  # comment' lines)."""
    out, inside = {}, False
    with open(path) as fh:
        for line in fh:
            if re.match(r"^\S", line):
                inside = line.startswith(block + ":")
                continue
            m = re.match(r"^  (\w+): ([^#]*)", line)
            if inside and m:
                out[m.group(1)] = m.group(2).strip()
    return out


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("run", help="output folder of a polyfloe run of a scene with a channel")
    ap.add_argument("-o", "--output", required=True, help="PNG file")
    a = ap.parse_args()
    resolved = os.path.join(a.run, "scene.resolved.yaml")
    ch = {k: float(v) for k, v in resolved_block(resolved, "channel").items()}
    if not ch:
        sys.stderr.write(f"plot_channel_geometry.py: {resolved} has no channel block\n")
        return 1
    region = [float(x) for x in re.findall(r"-?[\d.e+]+", resolved_block(resolved, "floe_field").get("region", ""))]

    with h5py.File(os.path.join(a.run, "results.h5"), "r", swmr=True) as f:
        polys = frame_polygons(f, 0)
        motion = f["/floes/motion"][:]
    fig, ax = plt.subplots(figsize=(11, 5.6))
    ax.add_collection(PolyCollection([p for p, m in zip(polys, motion) if m != 0], facecolor="0.55", edgecolor="k",
                                     linewidth=0.5, label="walls (fixed polygons)"))
    ax.add_collection(PolyCollection([p for p, m in zip(polys, motion) if m == 0], facecolor="#9cc8e8",
                                     edgecolor="#3a6f96", linewidth=0.2))
    if len(region) == 4:
        ax.add_patch(Rectangle((region[0], region[1]), region[2] - region[0], region[3] - region[1], fill=False,
                               linestyle="--", edgecolor="#1f4e79", linewidth=1.2))
        ax.text(region[0] + 10, region[3] - 40,
                f"ice region {region[2] - region[0]:.0f} m × {region[3] - region[1]:.0f} m (floe_field.region)",
                fontsize=8, color="#1f4e79")
    x1, fl, op, sl = ch["basin_x_max"], ch["funnel_length"], ch["opening"], ch["strait_length"]
    ylo, yhi = ch["basin_y_min"], ch["basin_y_max"]
    yc = 0.5 * (ylo + yhi)
    wt = ch["wall_thickness"]
    gate = x1 + fl
    ax.axvline(gate, color="C3", linestyle="--", linewidth=1)
    ax.text(gate + 8, yc + 0.5 * op + wt + 40, f"strait entrance x = {gate:.0f} m\n(ice area passed is counted here)", color="C3",
            fontsize=8)
    ax.axvline(x1, color="0.4", linestyle=":", linewidth=1)
    ax.text(x1 + 8, ylo - 95, f"funnel starts\nx = basin_x_max = {x1:.0f} m", color="0.3", fontsize=8)

    def dim(xa, ya, xb, yb, text, off=(0, 0), rot=0):
        ax.annotate("", xy=(xa, ya), xytext=(xb, yb), arrowprops=dict(arrowstyle="<->", color="k", linewidth=0.8))
        ax.text(0.5 * (xa + xb) + off[0], 0.5 * (ya + yb) + off[1], text, ha="center", va="center", fontsize=8,
                rotation=rot, bbox=dict(facecolor="white", edgecolor="none", alpha=0.8, pad=1))

    dim(gate + 0.5 * sl, yc - 0.5 * op, gate + 0.5 * sl, yc + 0.5 * op, f"opening\n{op:.0f} m")
    dim(x1, yhi + wt + 25, gate, yhi + wt + 25, f"funnel_length\n{fl:.0f} m", off=(0, 28))
    dim(gate, yc - 0.5 * op - wt - 25, gate + sl, yc - 0.5 * op - wt - 25, f"strait_length {sl:.0f} m", off=(0, -22))
    dim(ch["basin_x_min"], yhi + wt + 25, x1, yhi + wt + 25,
        f"basin {x1 - ch['basin_x_min']:.0f} m (basin_x_min … basin_x_max)", off=(0, 22))
    dim(ch["basin_x_min"] - 40, ylo, ch["basin_x_min"] - 40, yhi, f"{yhi - ylo:.0f} m", rot=90)
    ax.text(x1 + 0.5 * fl, yc, "funnel", ha="center", fontsize=9, color="0.2")
    ax.text(gate + 0.5 * sl, yc + 0.5 * op - 30, "strait", ha="center", fontsize=9, color="0.2")
    ax.set_xlim(ch["basin_x_min"] - 120, gate + sl + 60)
    ax.set_ylim(ylo - wt - 90, yhi + wt + 130)
    ax.set_aspect("equal")
    ax.set_xlabel("x [m] (current and wind along +x)")
    ax.set_ylabel("y [m]")
    ax.set_title(f"channel geometry ({sum(motion == 0)} floes at t = 0; walls {ch['wall_thickness']:.0f} m thick)")
    fig.tight_layout()
    fig.savefig(a.output, dpi=130)
    print(f"wrote {a.output}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
