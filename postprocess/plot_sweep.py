#!/usr/bin/python3
"""Figures of the paper's channel families (scripts/sweep.sh): flow against time and the initial fields.

    /usr/bin/python3 postprocess/plot_sweep.py results/sweep -o docs/figures [--summary docs/data/sweep.json]

Reads <family>/<member>/s<seed>/results.h5 under the sweep folder (families concentration, exponent, corners) and
writes:
  sweep_flow.png     per family: the mean speed of all floes, the mean speed of the floes in the strait, and the
                     ice area passed through the strait entrance, against time (/diagnostics, /diagnostics/channel):
                     the mean over seeds as a line, the range over seeds as a band
  sweep_fields.png   the initial fields: size distribution (area-equivalent diameter, log bins, per member of the
                     exponent family, all seeds pooled) and circularity histograms (corners family)
  sweep_maps_<family>.png  floes coloured by speed at t = 170 s and 200 s for each member, first seed, and the
                     ice speed on the velocity grid averaged over the output interval (paper Fig. 11 style)
  --summary FILE     per member: seeds, floe count, area passed at the end, mean speeds at 170 s / 200 s / the end,
                     jams (mean and standard deviation over seeds); also printed as a table
"""
import json
import argparse
import os
import sys

import h5py
import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
from matplotlib.collections import PolyCollection  # noqa: E402

from polyfloe_post.frames import frame_polygons  # noqa: E402

FAMILIES = {
    "concentration": "concentration",
    "exponent": "FSD exponent",
    "corners": "corners (circularity)",
}


def members(root, family):
    """[(member, [results.h5 of each seed, by seed])] of one family."""
    d = os.path.join(root, family)
    if not os.path.isdir(d):
        return []
    out = []
    for m in sorted(os.listdir(d)):
        md = os.path.join(d, m)
        if not os.path.isdir(md):
            continue
        seeds = sorted((int(s[1:]), os.path.join(md, s, "results.h5")) for s in os.listdir(md)
                       if s.startswith("s") and s[1:].isdigit() and os.path.isfile(os.path.join(md, s, "results.h5")))
        if seeds:
            out.append((m, [p for _, p in seeds]))
    return out


def frame_near(t, want):
    """The frame nearest to time `want`, or None when no frame lies within half a frame interval of it (the run
    ended before `want`, or started after it)."""
    k = int(np.argmin(np.abs(t - want)))
    step = float(np.median(np.diff(t))) if len(t) > 1 else 0.0
    return k if abs(float(t[k]) - want) <= 0.5 * step + 1e-9 * max(1.0, abs(want)) else None


def at(t, y, want):
    """y at the frame nearest to time `want`; NaN when the run has no frame there."""
    k = frame_near(t, want)
    return float("nan") if k is None else float(y[k])


def legend_if_labelled(ax, **kw):
    """A legend only where something carries a label (matplotlib warns otherwise)."""
    if ax.get_legend_handles_labels()[0]:
        ax.legend(**kw)


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
        for k, (name, paths) in enumerate(members(root, fam)):
            curves = [[], [], []]
            t = None
            for path in paths:
                with h5py.File(path, "r", swmr=True) as f:
                    tt = f["/time"][:]
                    ch = f["/diagnostics/channel"]
                    ys = [f["/diagnostics/mean_speed"][:], ch["strait_mean_speed"][:], ch["area_passed"][:] / 1e3]
                if t is None or len(tt) < len(t):
                    t = tt
                for c, y in zip(curves, ys):
                    c.append(y)
            n = len(t)
            colour = f"C{k}"
            for ax, c in zip(axes[row], curves):
                y = np.array([v[:n] for v in c])
                ax.plot(t, y.mean(axis=0), color=colour, label=f"{name} ({len(paths)} seeds)")
                if len(paths) > 1:
                    ax.fill_between(t, y.min(axis=0), y.max(axis=0), color=colour, alpha=0.2, linewidth=0)
        axes[row, 0].set_ylabel(f"{FAMILIES[fam]}\nmean floe speed [m/s]")
        axes[row, 1].set_ylabel("mean speed in the strait [m/s]")
        axes[row, 2].set_ylabel("ice area through the strait [10³ m²]")
        for ax in axes[row]:
            ax.set_xlabel("t [s]")
            ax.grid(alpha=0.3)
            legend_if_labelled(ax, fontsize=8)
    fig.tight_layout()
    path = os.path.join(out, "sweep_flow.png")
    fig.savefig(path, dpi=120)
    print(f"wrote {path}")


def summarise(root, fams):
    """Per family and member: statistics over seeds of the flow measures."""
    table = {}
    for fam in fams:
        table[fam] = {}
        for name, paths in members(root, fam):
            rows = []
            for path in paths:
                with h5py.File(path, "r", swmr=True) as f:
                    t = f["/time"][:]
                    ch = f["/diagnostics/channel"]
                    motion = f["/floes/motion"][:]
                    jammed = ch["jammed"][:]
                    rows.append({
                        "floes": int(np.sum(motion == 0)),
                        "end_time": float(t[-1]),
                        "area_passed": float(ch["area_passed"][-1]),
                        "mean_speed_170": at(t, f["/diagnostics/mean_speed"][:], 170.0),
                        "mean_speed_200": at(t, f["/diagnostics/mean_speed"][:], 200.0),
                        "strait_speed_200": at(t, ch["strait_mean_speed"][:], 200.0),
                        "mean_speed_end": float(f["/diagnostics/mean_speed"][-1]),
                        "jammed": bool(jammed[-1] > 0),
                        "jam_time": float(t[int(np.argmax(jammed > 0))]) if np.any(jammed > 0) else None,
                    })
            entry = {"seeds": len(rows), "jammed_runs": sum(r["jammed"] for r in rows),
                     "jam_times": [r["jam_time"] for r in rows]}
            for key in ("floes", "end_time", "area_passed", "mean_speed_170", "mean_speed_200", "strait_speed_200",
                        "mean_speed_end"):
                v = np.array([r[key] for r in rows], dtype=float)
                # A run without a frame at the time (NaN) makes the statistic n/a: null in the JSON summary.
                finite = bool(np.all(np.isfinite(v)))
                entry[key] = {"mean": float(v.mean()) if finite else None,
                              "std": (float(v.std(ddof=1)) if len(v) > 1 else 0.0) if finite else None,
                              "values": [float(x) if np.isfinite(x) else None for x in v]}
            table[fam][name] = entry
    return table


def print_summary(table):
    ends = [v for ms in table.values() for e in ms.values() for v in e["end_time"]["values"] if v is not None]
    if ends and min(ends) < 200.0 - 1e-9:
        print(f"plot_sweep: note: the shortest run ends at t = {min(ends):g} s; columns at 170 s and 200 s are "
              "n/a where a run has no frame there", file=sys.stderr)
    print("| family | member | seeds | floes | area passed at end [10³ m²] | mean speed 170 s [m/s] | "
          "mean speed 200 s [m/s] | strait speed 200 s [m/s] | jammed |")
    print("|---|---|---|---|---|---|---|---|---|")
    for fam, ms in table.items():
        for name, e in ms.items():
            def ms_(key, scale=1.0, digits=2):
                if e[key]["mean"] is None:
                    return "n/a"
                return f"{e[key]['mean'] / scale:.{digits}f} ± {e[key]['std'] / scale:.{digits}f}"
            print(f"| {fam} | {name} | {e['seeds']} | {ms_('floes', digits=0)} | {ms_('area_passed', 1e3, 1)} | "
                  f"{ms_('mean_speed_170')} | {ms_('mean_speed_200')} | {ms_('strait_speed_200')} | "
                  f"{e['jammed_runs']} of {e['seeds']} |")


def plot_fields(root, out):
    fig, axes = plt.subplots(1, 2, figsize=(11, 4))
    bins = np.logspace(np.log10(5), np.log10(100), 16)
    for name, paths in members(root, "exponent") or members(root, "concentration"):
        a = []
        for path in paths:
            with h5py.File(path, "r", swmr=True) as f:
                a.append(floe_shapes(f)[0])
        a = np.concatenate(a)
        d = np.sqrt(4 * a / np.pi)
        h, e = np.histogram(d, bins=bins, density=True)
        axes[0].loglog(np.sqrt(e[1:] * e[:-1]), h, "o-", label=f"{name} ({len(d) / len(paths):.0f} floes per field)")
    axes[0].set_xlabel("size (area-equivalent diameter) [m]")
    axes[0].set_ylabel("probability density [1/m]")
    axes[0].set_title("initial size distributions")
    for name, paths in members(root, "corners"):
        c = []
        for path in paths:
            with h5py.File(path, "r", swmr=True) as f:
                a, p = floe_shapes(f)
            c.append(np.sqrt(4 * np.pi * a) / p)
        c = np.concatenate(c)
        axes[1].hist(c, bins=np.linspace(0.6, 1.0, 41), histtype="step", density=True,
                     label=f"{name}: mean {c.mean():.3f}")
    axes[1].set_xlabel("circularity (Eq. 17) [-]")
    axes[1].set_ylabel("probability density")
    axes[1].set_title("initial circularity")
    for ax in axes:
        legend_if_labelled(ax, fontsize=8)
        ax.grid(alpha=0.3, which="both")
    fig.tight_layout()
    path = os.path.join(out, "sweep_fields.png")
    fig.savefig(path, dpi=120)
    print(f"wrote {path}")


def plot_maps(root, fam, out, times=(170.0, 200.0)):
    """Floes coloured by speed (first seed) and, where the runs wrote it, the gridded ice speed averaged over the
    output interval ending at that time (/diagnostics/velocity_grid; first seed that has it)."""
    ms = members(root, fam)
    if not ms:
        return
    with h5py.File(ms[0][1][0], "r", swmr=True) as f:
        t = f["/time"][:]
    missing = [want for want in times if frame_near(t, want) is None]
    if missing:
        print(f"plot_sweep: {fam}: no maps at t = {', '.join(f'{w:g}' for w in missing)} s: the runs end at "
              f"t = {t[-1]:g} s (maps show the frames at 170 s and 200 s of the paper's runs)", file=sys.stderr)
        times = tuple(w for w in times if w not in missing)
        if not times:
            return
    grids = {}
    for name, paths in ms:
        for path in paths:
            with h5py.File(path, "r", swmr=True) as f:
                if "/diagnostics/velocity_grid" in f:
                    grids[name] = path
                    break
    cols = len(times) * (2 if grids else 1)
    fig, axes = plt.subplots(len(ms), cols, figsize=(5.0 * cols, 2.6 * len(ms)), squeeze=False)
    pc = None
    for r, (name, paths) in enumerate(ms):
        for c, want in enumerate(times):
            with h5py.File(paths[0], "r", swmr=True) as f:
                t = f["/time"][:]
                motion = f["/floes/motion"][:]
                k = int(np.argmin(np.abs(t - want)))
                polys = frame_polygons(f, k)
                v = np.linalg.norm(f["/state/velocity"][k][:, :2], axis=1)
            walls = [p for p, m in zip(polys, motion) if m != 0]
            ax = axes[r, c]
            ax.add_collection(PolyCollection(walls, facecolor="0.6", edgecolor="none"))
            pc = PolyCollection([p for p, m in zip(polys, motion) if m == 0], array=v[motion == 0], cmap="viridis",
                                edgecolor="k", linewidth=0.1)
            pc.set_clim(0, 5)
            ax.add_collection(pc)
            ax.set_title(f"{name} ({os.path.basename(os.path.dirname(paths[0]))}): floes, t = {t[k]:.0f} s",
                         fontsize=8)
            if name in grids:
                with h5py.File(grids[name], "r", swmr=True) as f:
                    tg = f["/time"][:]
                    kg = int(np.argmin(np.abs(tg - want)))
                    g = f["/diagnostics/velocity_grid"]
                    x0, y0, cell = g.attrs["x0"], g.attrs["y0"], g.attrs["cell"]
                    nx, ny = int(g.attrs["nx"]), int(g.attrs["ny"])
                    vel = g["velocity"][kg]
                    polys_g = frame_polygons(f, kg)
                    motion_g = f["/floes/motion"][:]
                    interval = tg[kg] - tg[kg - 1] if kg > 0 else 0.0
                speed = np.hypot(vel[..., 0], vel[..., 1])
                ax = axes[r, len(times) + c]
                ax.imshow(np.ma.masked_invalid(speed), origin="lower", cmap="viridis", vmin=0, vmax=5,
                          extent=(x0, x0 + nx * cell, y0, y0 + ny * cell), interpolation="nearest")
                ax.add_collection(PolyCollection([p for p, m in zip(polys_g, motion_g) if m != 0], facecolor="0.6",
                                                 edgecolor="none"))
                ax.set_title(f"{name} ({os.path.basename(os.path.dirname(grids[name]))}): {cell:.0f} m grid, "
                             f"mean over {tg[kg] - interval:.0f}–{tg[kg]:.0f} s", fontsize=8)
        for ax in axes[r]:
            ax.set_xlim(0, 2000)
            ax.set_ylim(-50, 1050)
            ax.set_aspect("equal")
        fig.colorbar(pc, ax=axes[r, :].tolist(), label="speed [m/s]", shrink=0.8)
    path = os.path.join(out, f"sweep_maps_{fam}.png")
    fig.savefig(path, dpi=100)
    print(f"wrote {path}")


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("sweep", help="the folder scripts/sweep.sh wrote (results/sweep)")
    ap.add_argument("-o", "--out", default="docs/figures", help="output folder (default docs/figures)")
    ap.add_argument("--summary", help="write the per-member statistics over seeds to this JSON file")
    a = ap.parse_args()
    fams = [f for f in FAMILIES if members(a.sweep, f)]
    if not fams:
        sys.stderr.write(f"plot_sweep.py: no <family>/<member>/s<seed>/results.h5 under {a.sweep}\n")
        return 1
    os.makedirs(a.out, exist_ok=True)
    plot_flow(a.sweep, fams, a.out)
    plot_fields(a.sweep, a.out)
    for fam in fams:
        plot_maps(a.sweep, fam, a.out)
    table = summarise(a.sweep, fams)
    print_summary(table)
    if a.summary:
        os.makedirs(os.path.dirname(os.path.abspath(a.summary)), exist_ok=True)
        with open(a.summary, "w") as fh:
            json.dump(table, fh, indent=1)
        print(f"wrote {a.summary}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
