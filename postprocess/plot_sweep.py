#!/usr/bin/python3
"""Figures of the paper's channel families (scripts/sweep.sh): flow against time and the initial fields.

    /usr/bin/python3 postprocess/plot_sweep.py results/sweep -o docs/figures

Writes, for the families found under the sweep folder (concentration, exponent, corners; members in sub-folders
holding results.h5):
  sweep_flow.png     per family: the mean speed of all floes, the mean speed of the floes in the strait, and the
                     ice area passed through the strait entrance, against time (/diagnostics, /diagnostics/channel)
  sweep_fields.png   the initial fields: size distribution (area-equivalent diameter, log bins, per family member
                     of the exponent family) and circularity histograms (corners family)
  sweep_maps_<family>.png  floes coloured by speed at t = 170 s and 200 s for each member (paper Fig. 11 style)
"""
import argparse
import os
import sys

import h5py
import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
from matplotlib.collections import PolyCollection  # noqa: E402

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from plot_frames import frame_polygons  # noqa: E402  (world-frame polygons of one frame)

FAMILIES = {
    "concentration": "concentration",
    "exponent": "FSD exponent",
    "corners": "corners (circularity)",
}


def members(root, family):
    d = os.path.join(root, family)
    if not os.path.isdir(d):
        return []
    out = []
    for m in sorted(os.listdir(d)):
        h5 = os.path.join(d, m, "results.h5")
        if os.path.isfile(h5):
            out.append((m, h5))
    return out


def floe_shapes(f):
    """Area and perimeter of each dynamic floe (body frame)."""
    off = f["/floes/polygon_offsets"][:]
    xy = f["/floes/polygon_xy"][:]
    motion = f["/floes/motion"][:]
    areas, perims = [], []
    for i in range(len(off) - 1):
        if motion[i] != 0:
            continue
        p = xy[off[i]:off[i + 1]]
        q = np.roll(p, -1, axis=0)
        areas.append(0.5 * np.sum(p[:, 0] * q[:, 1] - q[:, 0] * p[:, 1]))
        perims.append(np.sum(np.hypot(*(q - p).T)))
    return np.array(areas), np.array(perims)


def plot_flow(root, fams, out):
    fig, axes = plt.subplots(len(fams), 3, figsize=(13, 3.2 * len(fams)), squeeze=False)
    for row, fam in enumerate(fams):
        for name, path in members(root, fam):
            with h5py.File(path, "r") as f:
                t = f["/time"][:]
                axes[row, 0].plot(t, f["/diagnostics/mean_speed"][:], label=name)
                ch = f["/diagnostics/channel"]
                axes[row, 1].plot(t, ch["strait_mean_speed"][:], label=name)
                axes[row, 2].plot(t, ch["area_passed"][:] / 1e3, label=name)
        axes[row, 0].set_ylabel(f"{FAMILIES[fam]}\nmean floe speed [m/s]")
        axes[row, 1].set_ylabel("mean speed in the strait [m/s]")
        axes[row, 2].set_ylabel("ice area through the strait [10³ m²]")
        for ax in axes[row]:
            ax.set_xlabel("t [s]")
            ax.grid(alpha=0.3)
            ax.legend(fontsize=8)
    fig.tight_layout()
    path = os.path.join(out, "sweep_flow.png")
    fig.savefig(path, dpi=120)
    print(f"wrote {path}")


def plot_fields(root, out):
    fig, axes = plt.subplots(1, 2, figsize=(11, 4))
    bins = np.logspace(np.log10(5), np.log10(100), 16)
    for name, path in members(root, "exponent") or members(root, "concentration"):
        with h5py.File(path, "r") as f:
            a, _ = floe_shapes(f)
        d = np.sqrt(4 * a / np.pi)
        h, e = np.histogram(d, bins=bins, density=True)
        axes[0].loglog(np.sqrt(e[1:] * e[:-1]), h, "o-", label=f"{name} ({len(d)} floes)")
    axes[0].set_xlabel("size (area-equivalent diameter) [m]")
    axes[0].set_ylabel("probability density [1/m]")
    axes[0].set_title("initial size distributions")
    for name, path in members(root, "corners"):
        with h5py.File(path, "r") as f:
            a, p = floe_shapes(f)
        c = np.sqrt(4 * np.pi * a) / p
        axes[1].hist(c, bins=np.linspace(0.6, 1.0, 41), histtype="step", density=True,
                     label=f"{name}: mean {c.mean():.3f}")
    axes[1].set_xlabel("circularity (Eq. 17) [-]")
    axes[1].set_ylabel("probability density")
    axes[1].set_title("initial circularity")
    for ax in axes:
        ax.legend(fontsize=8)
        ax.grid(alpha=0.3, which="both")
    fig.tight_layout()
    path = os.path.join(out, "sweep_fields.png")
    fig.savefig(path, dpi=120)
    print(f"wrote {path}")


def plot_maps(root, fam, out, times=(170.0, 200.0)):
    ms = members(root, fam)
    if not ms:
        return
    fig, axes = plt.subplots(len(ms), len(times), figsize=(5.5 * len(times), 2.8 * len(ms)), squeeze=False)
    for r, (name, path) in enumerate(ms):
        with h5py.File(path, "r") as f:
            t = f["/time"][:]
            motion = f["/floes/motion"][:]
            for c, want in enumerate(times):
                k = int(np.argmin(np.abs(t - want)))
                polys = frame_polygons(f, k)
                v = np.linalg.norm(f["/state/velocity"][k][:, :2], axis=1)
                ax = axes[r, c]
                walls = [p for p, m in zip(polys, motion) if m != 0]
                floes = [p for p, m in zip(polys, motion) if m == 0]
                ax.add_collection(PolyCollection(walls, facecolor="0.6", edgecolor="none"))
                pc = PolyCollection(floes, array=v[motion == 0], cmap="viridis", edgecolor="k", linewidth=0.1)
                pc.set_clim(0, 5)
                ax.add_collection(pc)
                ax.set_xlim(0, 2000)
                ax.set_ylim(-50, 1050)
                ax.set_aspect("equal")
                ax.set_title(f"{name}, t = {t[k]:.0f} s", fontsize=9)
        fig.colorbar(pc, ax=axes[r, :].tolist(), label="speed [m/s]", shrink=0.8)
    path = os.path.join(out, f"sweep_maps_{fam}.png")
    fig.savefig(path, dpi=110)
    print(f"wrote {path}")


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("sweep", help="the folder scripts/sweep.sh wrote (results/sweep)")
    ap.add_argument("-o", "--out", default="docs/figures", help="output folder (default docs/figures)")
    a = ap.parse_args()
    fams = [f for f in FAMILIES if members(a.sweep, f)]
    if not fams:
        sys.stderr.write(f"plot_sweep.py: no <family>/<member>/results.h5 under {a.sweep}\n")
        return 1
    os.makedirs(a.out, exist_ok=True)
    plot_flow(a.sweep, fams, a.out)
    plot_fields(a.sweep, a.out)
    for fam in fams:
        plot_maps(a.sweep, fam, a.out)
    return 0


if __name__ == "__main__":
    sys.exit(main())
