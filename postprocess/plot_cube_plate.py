#!/usr/bin/python3
"""The cube-plate check, Fig. 3 of the paper (docs/figures/cube_plate.png), from tests/bench/bench_cube_plate.

    build/tests/bench_cube_plate -o docs/data/cube_plate.json
    /usr/bin/python3 postprocess/plot_cube_plate.py docs/data/cube_plate.json -o docs/figures/cube_plate.png

(a) v'/v0 and (b) w' r / v0 after the first impact against the strike angle alpha: Eq. 6-7 (dashed below 5 deg,
where the cube meets the plate nearly face-on and the one-edge formulas stop holding) and the simulation for each
narrow phase and contact-point model; libccd's own contact point is off the chart at most angles, so its worst
error is given in the legend. (c) the error of the default method against the contact stiffness: the formulas
assume an instantaneous impact; a finite contact lets the cube turn while it is pushed.
"""
import argparse
import json
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

STYLE = {
    "sat, witness": dict(marker="o", color="C0", ms=6, mfc="none"),
    "sat, manifold": dict(marker="s", color="C1", ms=4),
    "libccd gjk_epa_tiebreak, manifold": dict(marker="x", color="C2", ms=6),
    "libccd gjk_epa, its point": dict(marker="v", color="C3", ms=4, alpha=0.6),
    "libccd gjk_epa_tiebreak, its point": dict(marker="^", color="C4", ms=4, alpha=0.6),
    "libccd mpr, its point": dict(marker="d", color="C5", ms=4, alpha=0.6),
}


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("data")
    ap.add_argument("-o", "--out", default="docs/figures/cube_plate.png")
    a = ap.parse_args()
    try:
        with open(a.data) as f:
            d = json.load(f)
    except (OSError, json.JSONDecodeError) as e:
        sys.exit(f"plot_cube_plate.py: cannot read {a.data}: {e}")
    alpha = d["angles_deg"]
    ref = d["analytic"]
    fig, ax = plt.subplots(1, 3, figsize=(15, 4.6))
    for k, key, label in ((0, "v_ratio", "v'/v0 (Eq. 7)"), (1, "w_ratio", "ω' r / v0 (Eq. 6)")):
        edge = [i for i, x in enumerate(alpha) if x >= 5.0]
        face = [i for i, x in enumerate(alpha) if x <= 5.0]
        ax[k].plot([alpha[i] for i in edge], [ref[key][i] for i in edge], "k-", lw=1.5, label="Eq. 6-7")
        ax[k].plot([alpha[i] for i in face], [ref[key][i] for i in face], "k--", lw=1.0,
                   label="Eq. 6-7 (not valid: face-on)")
        for run in d["runs"]:
            st = STYLE.get(run["method"], dict(marker="."))
            worst = run["worst_error_5_45"]
            ax[k].plot(alpha, run[key], ls="none", label=f"{run['method']} (worst error {worst:.3f} v0)", **st)
        ax[k].set_xlabel("α [deg]")
        ax[k].set_ylabel(label)
        ax[k].set_ylim(-0.8, 1.0) if key == "v_ratio" else ax[k].set_ylim(-0.1, 1.6)
        ax[k].axvspan(0, 5, color="0.92", zorder=0)
        ax[k].grid(alpha=0.3)
    ax[0].set_title("(a) vertical velocity after the impact")
    ax[1].set_title("(b) spin after the impact")
    ax[1].legend(fontsize=7, loc="lower left")
    stiff = d["stiffness"]
    for alpha_deg, marker in ((15.0, "o"), (30.0, "s")):
        rows = [r for r in stiff if r["alpha_deg"] == alpha_deg]
        e = [r["youngs_modulus"] for r in rows]
        ax[2].loglog(e, [r["v_error"] for r in rows], marker + "-", color="C0", label=f"|Δv'|/v0, α = {alpha_deg:g}°")
        ax[2].loglog(e, [r["w_error"] for r in rows], marker + "--", color="C1", label=f"|Δω'| r/v0, α = {alpha_deg:g}°")
    ax[2].axhline(0.01, color="k", lw=0.8, ls=":", label="acceptance: 1 % of v0")
    ax[2].axvline(1e9, color="0.5", lw=0.8, label="scene default E = 1 GPa")
    ax[2].set_xlabel("Young's modulus E [Pa]")
    ax[2].set_ylabel("error against Eq. 6-7")
    ax[2].set_title("(c) sat, witness: error vs contact stiffness")
    ax[2].legend(fontsize=7)
    ax[2].grid(alpha=0.3, which="both")
    fig.suptitle("Cube (l = 2 m, ρ = 920 kg/m³, e = 0.5) striking a fixed plate at v0 = 1 m/s, turned by α about y")
    fig.tight_layout()
    fig.savefig(a.out, dpi=110)
    print(f"wrote {a.out}")


if __name__ == "__main__":
    main()
