#!/usr/bin/python3
"""Draw floes from a PolyFloe results.h5 at chosen times, coloured by speed (matplotlib, headless).

    /usr/bin/python3 postprocess/plot_frames.py results/channel/results.h5 -t 0 150 300 -o docs/figures/channel.png

Reads /floes/{polygon_offsets, polygon_xy, motion}, /state/{position, orientation, velocity} and /time.
"""
import argparse
import sys

import h5py
import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
from matplotlib.collections import PolyCollection  # noqa: E402
from polyfloe_post.frames import frame_polygons  # noqa: E402


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("results", help="results.h5 written by polyfloe run")
    ap.add_argument("-t", "--times", type=float, nargs="+", default=[0.0], help="times to draw [s] (nearest frame)")
    ap.add_argument("-o", "--output", required=True, help="PNG file")
    ap.add_argument("--vmax", type=float, default=None, help="top of the speed colour scale [m/s]")
    a = ap.parse_args()
    try:
        f = h5py.File(a.results, "r", swmr=True)
    except OSError as e:
        sys.exit(f"plot_frames: cannot open {a.results}: {e}")
    with f:
        times = f["/time"][:]
        motion = f["/floes/motion"][:]
        vel = f["/state/velocity"]
        vmax = a.vmax or max(float(np.max(np.linalg.norm(vel[k][:, :2], axis=1)[motion == 0])) for k in range(len(times)))
        step = float(np.median(np.diff(times))) if len(times) > 1 else 0.0
        for t in a.times:
            k = int(np.argmin(np.abs(times - t)))
            if abs(float(times[k]) - t) > 0.5 * step + 1e-9 * max(1.0, abs(t)):
                sys.exit(f"plot_frames: {a.results} has no frame at t = {t:g} s: its frames span "
                         f"{times[0]:g} to {times[-1]:g} s, every {step:g} s")
        fig, axes = plt.subplots(1, len(a.times), figsize=(5.0 * len(a.times), 4.2), squeeze=False, sharey=True,
                                 constrained_layout=True)
        for i, (ax, t) in enumerate(zip(axes[0], a.times)):
            k = int(np.argmin(np.abs(times - t)))
            polys = frame_polygons(f, k)
            speed = np.linalg.norm(vel[k][:, :2], axis=1)
            ice = [p for p, m in zip(polys, motion) if m == 0]
            walls = [p for p, m in zip(polys, motion) if m != 0]
            pc = PolyCollection(ice, array=speed[motion == 0], cmap="viridis", edgecolors="k", linewidths=0.15)
            pc.set_clim(0.0, vmax)
            ax.add_collection(pc)
            ax.add_collection(PolyCollection(walls, facecolors="0.55", edgecolors="0.3", linewidths=0.3))
            allxy = np.vstack(polys)
            ax.set_xlim(allxy[:, 0].min(), allxy[:, 0].max())
            ax.set_ylim(allxy[:, 1].min(), allxy[:, 1].max())
            ax.set_aspect("equal")
            ax.set_title(f"t = {times[k]:.0f} s")
            ax.set_xlabel("x [m]")
            if i == 0:  # the panels share y: one label, none overlapping the neighbour
                ax.set_ylabel("y [m]")
        fig.colorbar(pc, ax=axes[0].tolist(), label="floe speed [m/s]", shrink=0.8)
        fig.savefig(a.output, dpi=130, bbox_inches="tight")
    print(f"wrote {a.output}")


if __name__ == "__main__":
    main()
