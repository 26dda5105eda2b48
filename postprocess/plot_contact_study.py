#!/usr/bin/python3
"""The contact-model study's charts and verdicts (scripts/contact_model_study.sh writes RESULTS).

    /usr/bin/python3 postprocess/plot_contact_study.py RESULTS [-o FIGURES] [--json FILE]

For each scene member (channel: concentration 0.50 / 0.55 / 0.60; uniaxial: the sheet) and each observable:
  channel   area_passed(t)        ice area through the strait entrance [m^2] (/diagnostics/channel/area_passed)
            strait_mean_speed(t)  mean speed of the floes in the strait [m/s]
            first_jam             time the first jam forms [s] (/diagnostics/channel/jammed; no jam: the run's end)
            jam_length            how long that jam holds [s] (0 without one)
  uniaxial  stress(strain)        the plates' mean stress on a common strain grid [Pa]
            peak_stress           its largest value [Pa]
            fracture_angles       density of the broken faces' angle to the compression axis, 10-degree bins
the rule of docs/validation.md: a model passes where, at every reported time (strain, bin), its mean over the seeds
lies within the reference's minimum-maximum over the same seeds. The reference is the foundation model at a quarter
of its step. Writes contact_study_<observable>.png (difference of each model's mean from the reference's mean
against the wall time of a run, the reference's seed spread as a band) and, with --json, every verdict, difference,
spread and wall time. Runs still missing (no stamp) are left out and counted.
"""
import argparse
import glob
import json
import os
import sys

import h5py
import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from plot_uniaxial import load as load_uniaxial  # noqa: E402

MODELS = ["centroid", "gradient", "foundation", "reference"]
ANGLE_BINS = np.arange(0.0, 90.0 + 1e-9, 10.0)
STRAIN_POINTS = 60


def first_jam(t, jammed):
    """The first jam's start and how long it holds (jammed is 1 from when the jam window has passed)."""
    on = np.flatnonzero(jammed > 0)
    if len(on) == 0:
        return float(t[-1]), 0.0
    start = on[0]
    end = start
    while end + 1 < len(jammed) and jammed[end + 1] > 0:
        end += 1
    return float(t[start]), float(t[end] - t[start])


def channel_run(folder):
    with h5py.File(os.path.join(folder, "results.h5"), "r") as f:
        t = f["/time"][:]
        ch = f["/diagnostics/channel"]
        jam_start, jam_length = first_jam(t, ch["jammed"][:])
        return dict(t=t, area_passed=ch["area_passed"][:], strait_mean_speed=ch["strait_mean_speed"][:],
                    first_jam=jam_start, jam_length=jam_length)


def uniaxial_run(folder):
    d = load_uniaxial(folder)
    grid = np.linspace(0.0, float(np.max(d["strain"])), STRAIN_POINTS)
    order = np.argsort(d["strain"])
    stress = np.interp(grid, d["strain"][order], d["stress"][order])
    hist, _ = np.histogram(d["angle"], bins=ANGLE_BINS, density=True) if len(d["angle"]) else (
        np.zeros(len(ANGLE_BINS) - 1), None)
    return dict(t=grid, stress=stress, peak_stress=float(np.max(d["stress"])), fracture_angles=hist)


SCENES = {
    "channel": (channel_run, ["area_passed", "strait_mean_speed"], ["first_jam", "jam_length"]),
    "uniaxial": (uniaxial_run, ["stress", "fracture_angles"], ["peak_stress"]),
}


def runs_of(root, scene, model, member):
    """The finished runs (stamped) of one model and member: {seed: (folder, wall time)}; and the count missing."""
    out, missing = {}, 0
    for folder in sorted(glob.glob(os.path.join(root, scene, model, member, "s*"))):
        if not os.path.isdir(folder):
            continue
        stamp = folder + ".done"
        if os.path.isfile(stamp):
            out[os.path.basename(folder)] = (folder, float(open(stamp).read()))
        else:
            missing += 1
    return out, missing


def compare(ref, mine):
    """The rule on one observable: ref and mine are lists of per-seed arrays (or scalars) on the same points."""
    ref = np.array(ref, dtype=float)
    mine = np.array(mine, dtype=float)
    n = min(ref.shape[-1], mine.shape[-1]) if ref.ndim > 1 else None
    if n is not None:
        ref, mine = ref[:, :n], mine[:, :n]
    lo, hi, ref_mean = ref.min(axis=0), ref.max(axis=0), ref.mean(axis=0)
    mean = mine.mean(axis=0)
    inside = bool(np.all((mean >= lo) & (mean <= hi)))
    return dict(passes=inside, difference=float(np.max(np.abs(mean - ref_mean))),
                spread=float(np.max(hi - lo)), seeds=int(len(mine)))


def study(root):
    table, missing = {}, 0
    for scene, (read, curves, scalars) in SCENES.items():
        members = sorted({os.path.basename(p) for p in glob.glob(os.path.join(root, scene, "*", "*"))
                          if os.path.isdir(p)})
        for member in members:
            data, walls = {}, {}
            for model in MODELS:
                runs, miss = runs_of(root, scene, model, member)
                missing += miss
                data[model] = {seed: read(folder) for seed, (folder, _) in runs.items()}
                walls[model] = float(np.mean([w for _, w in runs.values()])) if runs else None
            ref = data["reference"]
            for model in MODELS[:-1]:
                seeds = sorted(set(ref) & set(data[model]))
                if not seeds:
                    continue
                entry = table.setdefault(f"{scene}/{member}", {}).setdefault(model, {"wall_s": walls[model]})
                entry["reference_wall_s"] = walls["reference"]
                for obs in curves + scalars:
                    entry[obs] = compare([ref[s][obs] for s in seeds], [data[model][s][obs] for s in seeds])
                entry["passes"] = all(entry[obs]["passes"] for obs in curves + scalars)
    return table, missing


def plot(table, out):
    observables = sorted({obs for models in table.values() for m in models.values() for obs in m
                          if isinstance(m[obs], dict)})
    colours = {"centroid": "tab:blue", "gradient": "tab:orange", "foundation": "tab:green"}
    members = sorted(table)
    shapes = "os^Dv<>pXh"
    for obs in observables:
        fig, ax = plt.subplots(figsize=(6.4, 4.2))
        spreads = []
        for k, member in enumerate(members):
            for model, m in table[member].items():
                if obs not in m or m["wall_s"] is None:
                    continue
                r = m[obs]
                spreads.append(r["spread"])
                ax.plot(m["wall_s"], r["difference"], shapes[k % len(shapes)], color=colours[model],
                        mfc=colours[model] if r["passes"] else "none",
                        label=f"{model}, {member}" + ("" if r["passes"] else " (outside: open marker)"))
        if spreads:
            ax.axhspan(0.0, max(spreads), color="0.85", label="reference's seed spread (largest)")
        ax.set_xscale("log")
        ax.set_xlabel("wall time of a run [s], one core")
        ax.set_ylabel(f"{obs}: largest |mean - reference mean|")
        ax.legend(fontsize=6)
        fig.tight_layout()
        fig.savefig(os.path.join(out, f"contact_study_{obs}.png"), dpi=120)
        plt.close(fig)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("results")
    ap.add_argument("-o", "--out", default=None, help="figures folder (default: RESULTS/figures)")
    ap.add_argument("--json", default=None)
    a = ap.parse_args()
    if not os.path.isdir(a.results):
        sys.exit(f"plot_contact_study: {a.results}: no such folder (run scripts/contact_model_study.sh first)")
    table, missing = study(a.results)
    if not table:
        sys.exit(f"plot_contact_study: {a.results}: no member has finished runs of the reference and another model")
    out = a.out or os.path.join(a.results, "figures")
    os.makedirs(out, exist_ok=True)
    plot(table, out)
    for member, models in sorted(table.items()):
        for model, m in models.items():
            verdicts = ", ".join(f"{k} {'in' if v['passes'] else 'OUT'}" for k, v in m.items() if isinstance(v, dict))
            print(f"{member:24s} {model:10s} {'passes' if m['passes'] else 'fails '} "
                  f"({m['wall_s']:.0f} s a run; reference {m['reference_wall_s']:.0f} s): {verdicts}")
    if missing:
        print(f"plot_contact_study: {missing} runs not finished yet (no stamp): left out")
    if a.json:
        with open(a.json, "w") as f:
            json.dump(dict(members=table, runs_missing=missing), f, indent=1)
    print(f"wrote contact_study_*.png in {out}")


if __name__ == "__main__":
    sys.exit(main())
