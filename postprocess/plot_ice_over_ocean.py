#!/usr/bin/python3
"""Draw floes over the ocean current that drives them (matplotlib, headless: no display, no ParaView needed).

    /usr/bin/python3 postprocess/plot_ice_over_ocean.py of_cases/strait/field.h5 \
        results/strait_openfoam/results.h5 -t 0 300 600 -o strait.png
    # the same times of a second run (e.g. the uniform current) as a second row:
    /usr/bin/python3 postprocess/plot_ice_over_ocean.py FIELD.h5 RUN_A/results.h5 --compare RUN_B/results.h5 \
        --labels "OpenFOAM current" "uniform current" -t 300 600 -o compare.png

The background is the field's speed |(u, v)| at the level nearest --z (default: the shallowest level) and the
snapshot nearest each time (clamped to the file's snapshots), land grey, with streamlines; floes are drawn as
white polygons with black edges, walls dark grey. Reads the field file (docs/scene-reference.md, "Field files") and
results.h5 (docs/user-guide.md).
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


def open_h5(path, what):
    try:
        return h5py.File(path, "r", swmr=True) if what == "results" else h5py.File(path, "r")
    except OSError as e:
        sys.exit(f"plot_ice_over_ocean: cannot open {path} ({what}): {e}")


def field_speed(field, t, z):
    """Speed [m/s] on the (y, x) grid at the snapshot nearest t and the level nearest z; NaN on land."""
    times = field["t"][:]
    k = int(np.argmin(np.abs(times - t)))
    levels = field["z"][:]
    iz = int(np.argmin(np.abs(levels - z))) if z is not None else len(levels) - 1
    u = field["U"][k, iz]
    wet = field["mask"][iz] == 1
    speed = np.where(wet, np.hypot(u[..., 0], u[..., 1]), np.nan)
    return speed, u, wet, times[k], levels[iz]


def draw(ax, field, results, t, z, vmax, uniform=None):
    x, y = field["x"][:], field["y"][:]
    speed, u, wet, t_field, z_level = field_speed(field, t, z)
    if uniform is not None:  # the run's current was uniform: draw that over the field's water
        u = np.zeros_like(u)
        u[..., 0], u[..., 1] = uniform
        speed = np.where(wet, np.hypot(*uniform), np.nan)
    mesh = ax.pcolormesh(x, y, speed, shading="gouraud", cmap="Blues", vmin=0.0, vmax=vmax)
    ax.contourf(x, y, (~wet).astype(float), levels=[0.5, 1.5], colors=["0.75"])
    ax.streamplot(x, y, np.where(wet, u[..., 0], 0.0), np.where(wet, u[..., 1], 0.0), color="0.35",
                  density=0.9, linewidth=0.4, arrowsize=0.6)
    times = results["/time"][:]
    k = int(np.argmin(np.abs(times - t)))
    polys = frame_polygons(results, k)
    motion = results["/floes/motion"][:]
    ax.add_collection(PolyCollection([p for p, m in zip(polys, motion) if m == 0], facecolors="white",
                                     edgecolors="k", linewidths=0.25))
    ax.add_collection(PolyCollection([p for p, m in zip(polys, motion) if m != 0], facecolors="0.3",
                                     edgecolors="0.2", linewidths=0.3))
    ax.set_xlim(x[0], x[-1])
    ax.set_ylim(y[0], y[-1])
    ax.set_aspect("equal")
    what = f"uniform {np.hypot(*uniform):g} m/s" if uniform is not None else f"snapshot {t_field:g} s, z = {z_level:g} m"
    ax.set_title(f"t = {times[k]:.0f} s (current: {what})", fontsize=9)
    ax.set_xlabel("x [m]")
    ax.set_ylabel("y [m]")
    return mesh


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("field", help="ocean field file (polyfloe field import)")
    ap.add_argument("results", help="results.h5 of a run driven by it")
    ap.add_argument("--compare", help="results.h5 of a second run, drawn as a second row over the same field")
    ap.add_argument("--labels", nargs=2, default=None, help="row labels for the two runs")
    ap.add_argument("--compare-uniform", type=float, nargs=2, metavar=("U", "V"), default=None,
                    help="the second run's current was uniform [m/s]: draw it instead of the field")
    ap.add_argument("-t", "--times", type=float, nargs="+", default=[0.0], help="times to draw [s] (nearest frame)")
    ap.add_argument("--z", type=float, default=None, help="field level to draw [m] (nearest; default the top)")
    ap.add_argument("--vmax", type=float, default=None, help="top of the current-speed colour scale [m/s]")
    ap.add_argument("-o", "--output", required=True, help="PNG file")
    a = ap.parse_args()
    field = open_h5(a.field, "field")
    if field.attrs.get("format") not in ("polyfloe-ocean-field", b"polyfloe-ocean-field"):
        sys.exit(f"plot_ice_over_ocean: {a.field} is not an ocean field file (no format = polyfloe-ocean-field)")
    runs = [open_h5(a.results, "results")] + ([open_h5(a.compare, "results")] if a.compare else [])
    vmax = a.vmax
    if vmax is None:
        u = field["U"][...]
        vmax = float(np.nanmax(np.hypot(u[..., 0], u[..., 1])))
    fig, axes = plt.subplots(len(runs), len(a.times), figsize=(5.0 * len(a.times) + 1.0, 2.9 * len(runs) + 0.4),
                             squeeze=False, constrained_layout=True)
    for row, results in enumerate(runs):
        for col, t in enumerate(a.times):
            uniform = a.compare_uniform if row == 1 else None
            mesh = draw(axes[row][col], field, results, t, a.z, vmax, uniform)
        if a.labels:
            axes[row][0].set_ylabel(f"{a.labels[row]}\ny [m]")
    fig.colorbar(mesh, ax=axes.ravel().tolist(), label="current speed [m/s]", shrink=0.8)
    fig.savefig(a.output, dpi=130)
    for f in runs + [field]:
        f.close()
    print(f"wrote {a.output}")


if __name__ == "__main__":
    main()
