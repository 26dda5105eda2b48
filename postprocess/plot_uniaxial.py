#!/usr/bin/python3
"""Uniaxial compression of a frozen sheet (dem/scenes/uniaxial_compression.yaml): stress-strain, broken bonds,
fracture angles and crack pictures from one or more runs.

    /usr/bin/python3 postprocess/plot_uniaxial.py RUN [RUN ...] -o docs/figures [--labels ...] [--json FILE]

Each RUN is an output folder (results.h5). From /diagnostics/boundary_force and /state/position of the two
kinematic plates (the bodies of /diagnostics/boundary_ids that move):
  stress  = mean of the plates' inward force / (sheet width x thickness)   [Pa]   (compression positive)
  strain  = (initial gap - gap) / initial gap, gap = distance between the plates' centres minus their width [-]
From /bonds: broken faces against strain; fracture angle of each failed face = angle between the face (the crack
segment) and the compression axis x, folded into [0, 90] deg.
Writes uniaxial_stress_strain.png (stress and broken faces vs strain, all runs), uniaxial_fracture_angles.png
(probability density of the fracture angle per run), uniaxial_cracks.png (intact and broken faces at the end of each
run) and, with --json, the curves' key numbers (peak stress, strain at peak, faces broken).
"""
import argparse
import json
import os
import sys

import h5py
import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
from matplotlib.collections import LineCollection, PolyCollection  # noqa: E402

from polyfloe_post.frames import frame_polygons  # noqa: E402


def load(run):
    path = os.path.join(run, "results.h5")
    with h5py.File(path, "r", swmr=True) as f:
        t = f["/time"][:]
        ids = f["/floes/id"][:]
        motion = f["/floes/motion"][:]
        bids = f["/diagnostics/boundary_ids"][:]
        force = f["/diagnostics/boundary_force"][:]  # [T, K, 2]
        pos = f["/state/position"][:, :, :2]
        vel = f["/state/velocity"][:, :, :2]
        index = {int(i): k for k, i in enumerate(ids)}
        plates = [k for k, b in enumerate(bids) if motion[index[int(b)]] == 2]
        if len(plates) != 2:
            raise SystemExit(f"plot_uniaxial.py: {path}: expected 2 kinematic plates, found {len(plates)}")
        ia, ib = (index[int(bids[k])] for k in plates)
        if pos[0, ia, 0] > pos[0, ib, 0]:
            ia, ib = ib, ia
            plates = plates[::-1]
        off = f["/floes/polygon_offsets"][:]
        xy = f["/floes/polygon_xy"][:]
        width = {i: np.ptp(xy[off[i]:off[i + 1], 0]) for i in (ia, ib)}
        sheet = motion == 0
        ys = []
        for i in np.nonzero(sheet)[0]:
            ys.append(xy[off[i]:off[i + 1], 1] + pos[0, i, 1])
        ys = np.concatenate(ys)
        height = ys.max() - ys.min()
        thickness = float(f["/floes/thickness"][np.nonzero(sheet)[0][0]])
        gap = (pos[:, ib, 0] - pos[:, ia, 0]) - 0.5 * (width[ia] + width[ib])
        strain = (gap[0] - gap) / gap[0]
        inward = 0.5 * (-force[:, plates[0], 0] + force[:, plates[1], 0])  # the ice pushes the left plate to -x
        stress = inward / (height * thickness)
        g = f["/bonds"]
        intact = g["intact_faces"][:]
        faces = len(g["face_length"][:])
        normal = g["face_normal"][:]
        mid = g["face_midpoint"][:]
        broken_last = g["face_intact"][-1] == 0
        polys_end = frame_polygons(f, len(t) - 1)
        strength = float(g.attrs["tensile_strength"])
    # The crack runs along the face: its direction is the normal turned by 90 deg; angle to the x axis in [0, 90].
    direction = np.arctan2(normal[:, 0], -normal[:, 1])
    angle = np.degrees(np.abs(np.arctan(np.tan(direction))))
    return dict(t=t, strain=strain, stress=stress, broken=faces - intact, faces=faces, angle=angle[broken_last],
                mid=mid, normal=normal, broken_last=broken_last, polys=[p for p, s in zip(polys_end, sheet) if s],
                strength=strength, label=f"σ̄n = {strength / 1e6:g} MPa")


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("runs", nargs="+")
    ap.add_argument("-o", "--out", default="docs/figures")
    ap.add_argument("--json", help="write the key numbers of each run here")
    a = ap.parse_args()
    data = [load(r) for r in a.runs]
    os.makedirs(a.out, exist_ok=True)

    fig, ax = plt.subplots(1, 2, figsize=(12, 4.5))
    for d in data:
        ax[0].plot(100 * d["strain"], d["stress"] / 1e3, label=d["label"])
        ax[1].plot(100 * d["strain"], d["broken"], label=d["label"])
    ax[0].set_xlabel("strain [%]")
    ax[0].set_ylabel("compressive stress [kPa] (plate force / cross-section)")
    ax[1].set_xlabel("strain [%]")
    ax[1].set_ylabel("broken bond faces")
    for x in ax:
        x.grid(alpha=0.3)
        x.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(os.path.join(a.out, "uniaxial_stress_strain.png"), dpi=120)

    fig, ax = plt.subplots(figsize=(6, 4.2))
    bins = np.linspace(0, 90, 19)
    for d in data:
        if len(d["angle"]):
            ax.hist(d["angle"], bins=bins, density=True, histtype="step", linewidth=1.5,
                    label=f"{d['label']} ({len(d['angle'])} faces)")
    ax.set_xlabel("fracture angle to the compression axis [deg]")
    ax.set_ylabel("probability density [1/deg]")
    ax.grid(alpha=0.3)
    ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(os.path.join(a.out, "uniaxial_fracture_angles.png"), dpi=120)

    fig, axes = plt.subplots(1, len(data), figsize=(4.2 * len(data), 4.4), squeeze=False)
    for x, d in zip(axes[0], data):
        x.add_collection(PolyCollection(d["polys"], facecolor="#cfe3f3", edgecolor="none"))
        half = np.column_stack([-d["normal"][:, 1], d["normal"][:, 0]]) * 3.0
        segs = np.stack([d["mid"] - half, d["mid"] + half], axis=1)[d["broken_last"]]
        x.add_collection(LineCollection(segs, colors="C3", linewidths=0.8))
        x.set_aspect("equal")
        x.autoscale()
        x.set_title(f"{d['label']}: {int(d['broken_last'].sum())} broken faces, strain {100 * d['strain'][-1]:.2f} %",
                    fontsize=8)
    fig.tight_layout()
    fig.savefig(os.path.join(a.out, "uniaxial_cracks.png"), dpi=120)
    print(f"wrote uniaxial_stress_strain.png, uniaxial_fracture_angles.png, uniaxial_cracks.png in {a.out}")

    summary = {}
    for d in data:
        k = int(np.argmax(d["stress"]))
        summary[d["label"]] = dict(peak_stress=float(d["stress"][k]), strain_at_peak=float(d["strain"][k]),
                                   faces=int(d["faces"]), broken_at_end=int(d["broken"][-1]),
                                   median_fracture_angle=float(np.median(d["angle"])) if len(d["angle"]) else None)
        print(f"{d['label']}: peak {d['stress'][k] / 1e3:.1f} kPa at strain {100 * d['strain'][k]:.3f} %, "
              f"{d['broken'][-1]} of {d['faces']} faces broken")
    if a.json:
        with open(a.json, "w") as fh:
            json.dump(summary, fh, indent=1)
    return 0


if __name__ == "__main__":
    sys.exit(main())
