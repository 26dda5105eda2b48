#!/usr/bin/python3
"""The stability map and the speed-accuracy chart (docs/figures/stability_map.png, docs/figures/speed_accuracy.png).

Reads the JSON of tests/bench/bench_stability (one file, or several whose sections - impacts, packs, step_cost -
are merged) and docs/data/drift_quadrature.json (tests/bench/bench_drift, BM_SkinDragQuadrature: the torque error
of each bottom-quadrature rule).

    build/tests/bench_stability -o docs/data/stability_map.json
    /usr/bin/python3 postprocess/plot_stability.py docs/data/stability_map.json \\
        --quadrature docs/data/drift_quadrature.json --field docs/data/field_sampling.json --out docs/figures

stability_map.png: (a) the smallest stable number of steps per contact duration t_c for binary impacts of random
floes, by mass ratio, stiffness and contact setting, against the Verlet prediction for an undamped Hertz impact
(t_c / dt = 2.015) and the run guard's floor (10); (b) jammed packs: kinetic-energy growth against steps per contact for
three pre-compressions, with the measured threshold and the run guard's estimate.

speed_accuracy.png: error against CPU time per floe to simulate one contact duration (the cost per floe-step
times the steps per contact). Time step: the energy-norm error of the velocities after binary impacts (median and
90th percentile over pairs, the scenes' contact setting, all stiffnesses and mass ratios) at n steps per contact,
at the default quadrature's step cost. Quadrature: the skin-drag torque error of each rule (sheared current) at
its step cost and the default 40 steps per contact. Ocean field (docs/data/field_sampling.json,
tests/bench/bench_field_sampling): the ocean-load torque error on floes in the OpenFOAM strait for each field-file
grid spacing and the direct probe of the mesh (degree2), at the default step cost plus that sampling's cost per
floe (an upper bound: the step's own uniform-current drag is counted too), times 40 steps per contact.
"""
import argparse
import json
import math
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
from polyfloe_post.bench_json import field_sampling_rows, quadrature_rows  # noqa: E402

GUARD_FLOOR = 10.0  # dynamics::kMinStepsPerContact (dem/dynamics/world.h): the run guard floor
DEFAULT_STEPS = 40.0
DEFAULT_RULE = "degree2"


def load(paths):
    merged = {}
    for p in paths:
        try:
            with open(p) as f:
                d = json.load(f)
        except (OSError, json.JSONDecodeError) as e:
            sys.exit(f"plot_stability.py: cannot read {p}: {e}")
        merged.update(d)
    return merged


def quadrature_errors(path):
    """{rule: torque error} for the sheared current."""
    try:
        rows = quadrature_rows(path)
    except (OSError, ValueError) as e:
        sys.exit(f"plot_stability.py: cannot read {path}: {e}")
    return {rule: r[1] for (field, rule), r in rows.items() if field == "shear"}


def log_axes(ax, xlabel, ylabel, title, legend_loc, below=False):
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlabel(xlabel)
    ax.set_ylabel(ylabel)
    ax.set_title(title)
    if below:  # under the axes, clear of the data
        ax.legend(fontsize=7, loc="upper center", bbox_to_anchor=(0.5, -0.12), ncol=1)
    else:
        ax.legend(fontsize=7, loc=legend_loc)


def save(fig, out, name):
    fig.tight_layout()
    fig.savefig(os.path.join(out, name), dpi=130, bbox_inches="tight")  # a legend below the axes included
    print(f"wrote {os.path.join(out, name)}")


def stability_map(d, out):
    fig, (ax1, ax2) = plt.subplots(1, 2, figsize=(11, 4.3))
    if "impacts" in d:
        markers = {1e7: "o", 1e8: "s", 1e9: "^", 1e10: "D"}
        colours = {"elastic": "tab:blue", "scenes": "tab:red"}
        shift = {"elastic": 0.93, "scenes": 1.07}
        seen = set()
        for c in d["impacts"]:
            n_c = c["critical_steps_per_contact"]
            if n_c <= 0:
                continue
            key = (c["setting"], c["youngs_modulus"])
            label_e = f"E = {c['youngs_modulus']:.0e} Pa" if c["setting"] == "elastic" else None
            ax1.scatter(c["mass_ratio"] * shift[c["setting"]] * (1 + 0.02 * math.log10(c["youngs_modulus"]) - 0.18),
                        n_c, marker=markers.get(c["youngs_modulus"], "x"), color=colours[c["setting"]],
                        label=label_e if key not in seen else None, s=36, alpha=0.8)
            seen.add(key)
        for s, col in colours.items():
            ax1.plot([], [], color=col, lw=6, label={"elastic": "e = 1, mu = 0", "scenes": "e = 0.5, mu = 0.3"}[s])
        ax1.axhline(d.get("predicted_steps_per_contact", 2.015), color="k", ls="--", lw=1,
                    label="Verlet limit, undamped central impact (2.015)")
        ax1.axhline(GUARD_FLOOR, color="tab:green", ls=":", lw=1.5, label="run guard floor = least steps_per_contact (10)")
        ax1.set_xscale("log")
        ax1.set_xlabel("mass ratio of the pair")
        ax1.set_ylabel("smallest stable steps per contact  t_c / dt")
        ax1.set_title("(a) binary impacts at 1 m/s, 24 random pairs per point")
        ax1.set_ylim(0, max(8.0, 1.6 * max(c["critical_steps_per_contact"] for c in d["impacts"])))
        ax1.legend(fontsize=7, loc="upper left", ncol=2)
    if "packs" in d:
        for p in d["packs"]:
            n = p["steps_per_contact"]
            g = [x if x >= 0 else float("nan") for x in p["energy_growth"]]
            line, = ax2.plot(n, [x if math.isfinite(x) and x > 0 else float("nan") for x in g], "o-",
                             label=f"overlap {1e3 * p['mean_overlap']:.0f} mm: unstable below "
                                   f"{p['critical_steps_per_contact']:g}; guard {p['guard_steps_per_contact']:.1f}")
            unstable = [x for x, s in zip(n, p["stable"]) if not s]
            ax2.scatter(unstable, [1e2] * len(unstable), marker="x", color=line.get_color(), s=40)
            ax2.axvline(p["guard_steps_per_contact"], color=line.get_color(), ls=":", lw=1)
        log_axes(ax2, "steps per contact t_c(1 m/s) / dt", "kinetic energy at the end / after 200 steps",
                 "(b) jammed packs, 2,500 floes (x: unstable)", "upper right")
    save(fig, out, "stability_map.png")


def field_grid_series(field, step_cost):
    """(x, y, names) of the ocean-field series: for each grid spacing (and the direct probe) with the default rule,
    the step cost plus the field's ocean-load evaluation per floe, times the default steps per contact, against the
    ocean-load torque error in the OpenFOAM strait."""
    pts = []
    for (source, rule), (ns, _force, torque) in field.items():
        if rule != DEFAULT_RULE:
            continue
        if source.startswith("grid "):
            spacing = float(source.split()[1])
            pts.append((-spacing, f"{spacing:g} m", ns, torque))
        elif source == "direct":
            pts.append((0.0, "direct", ns, torque))
    pts.sort()
    x = [(step_cost + ns / 1000.0) * DEFAULT_STEPS for _, _, ns, _ in pts]
    return x, [p[3] for p in pts], [p[1] for p in pts]


def speed_accuracy(d, quad, field, out):
    if "step_cost" not in d or "impacts" not in d:
        print("speed_accuracy.png needs the impacts and step_cost sections; skipped")
        return
    cost = {r["quadrature"]: r["us_per_floe_step"] for r in d["step_cost"]}
    fig, ax = plt.subplots(figsize=(8, 6))
    ns = d["steps_per_contact"]
    cells = [c for c in d["impacts"] if c["setting"] == "scenes"]

    def median(v):
        v = sorted(v)
        return v[len(v) // 2] if len(v) % 2 else 0.5 * (v[len(v) // 2 - 1] + v[len(v) // 2])

    keep = [k for k, n in enumerate(ns) if n >= 5]
    x = [cost[DEFAULT_RULE] * ns[k] for k in keep]
    p50 = [median([c["error_p50"][k] for c in cells]) for k in keep]
    p90 = [median([c["error_p90"][k] for c in cells]) for k in keep]
    ax.plot(x, p50, "o-", color="tab:red", label="time step, n = 5...160 steps per contact (impact error, median)")
    ax.plot(x, p90, "o--", color="tab:red", alpha=0.5, label="time step (90th percentile over pairs)")
    for k, xx, yy in zip(keep, x, p50):
        if ns[k] in (5, 10, 20, 40, 80, 160):
            ax.annotate(f"{ns[k]:g}", (xx, yy), textcoords="offset points", xytext=(4, -10), fontsize=7)
    qx, qy, names = [], [], []
    for rule in ("centroid", "degree1", "degree2", "degree4", "degree5"):
        if rule in cost and rule in quad:
            qx.append(cost[rule] * DEFAULT_STEPS)
            qy.append(quad[rule])
            names.append(rule)
    ax.plot(qx, qy, "s-", color="tab:blue", label="bottom quadrature at 40 steps per contact (skin-drag torque error)")
    for xx, yy, nm in zip(qx, qy, names):
        ax.annotate(nm, (xx, yy), textcoords="offset points", xytext=(4, 4), fontsize=7)
    if field:
        fx, fy, fnames = field_grid_series(field, cost[DEFAULT_RULE])
        ax.plot(fx, fy, "^-", color="tab:green",
                label="ocean-field grid and the direct probe, degree2 (ocean-load torque error, OpenFOAM strait)")
        for xx, yy, nm in zip(fx, fy, fnames):
            ax.annotate(nm, (xx, yy), textcoords="offset points", xytext=(4, 4), fontsize=7)
        if ("grid 5 m", DEFAULT_RULE) in field:
            ns5, _, t5 = field[("grid 5 m", DEFAULT_RULE)]
            ax.scatter([(cost[DEFAULT_RULE] + ns5 / 1000.0) * DEFAULT_STEPS], [t5], marker="*", s=220, color="gold",
                       edgecolor="k", zorder=5)
    i40 = ns.index(DEFAULT_STEPS)
    ax.scatter([cost[DEFAULT_RULE] * DEFAULT_STEPS], [median([c["error_p50"][i40] for c in cells])], marker="*",
               s=220, color="gold", edgecolor="k", zorder=5, label="defaults (40 steps per contact, degree2)")
    if DEFAULT_RULE in quad:
        ax.scatter([cost[DEFAULT_RULE] * DEFAULT_STEPS], [quad[DEFAULT_RULE]], marker="*", s=220, color="gold",
                   edgecolor="k", zorder=5)
    log_axes(ax, "CPU per floe per contact duration [us] (1,500-floe jammed pack, one core)",
             "relative error against a converged reference", "Speed against accuracy", "lower left", below=True)
    save(fig, out, "speed_accuracy.png")


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("json", nargs="+", help="bench_stability JSON file(s)")
    ap.add_argument("--quadrature", default="docs/data/drift_quadrature.json", help="bench_drift JSON")
    ap.add_argument("--field", default="docs/data/field_sampling.json",
                    help="bench_field_sampling JSON (the ocean-field grid series); '' for none")
    ap.add_argument("--out", default="docs/figures", help="folder for the PNG files")
    a = ap.parse_args()
    d = load(a.json)
    field = field_sampling_rows(a.field) if a.field else None
    os.makedirs(a.out, exist_ok=True)
    stability_map(d, a.out)
    speed_accuracy(d, quadrature_errors(a.quadrature), field, a.out)
    return 0


if __name__ == "__main__":
    sys.exit(main())
