#!/usr/bin/python3
"""The failure map of the contact methods (docs/figures/failure_map.png): error against cost.

Reads the JSON of tests/bench/bench_failure_map (docs/validation.md, "Failure map of the contact methods").

    build-h3/tests/bench_failure_map -o docs/data/failure_map.json
    /usr/bin/python3 postprocess/plot_failure_map.py docs/data/failure_map.json -o docs/figures/failure_map.png

x: ns per pair (one core, median of the timed passes), log. One colour per method.
(a) random set (filled) and the same pairs 10 km from the origin (open): the rate of wrong answers,
    (failed + missed + false contacts + wrong normals that are not ties) / pairs; a zero rate sits on the floor line.
    Exact planar: its chord normal is not the MTD direction by design, so it is drawn without those deviations
    (the "x" above it includes them).
(b) random set: relative depth error |depth - MTD| / MTD, median (marker) and maximum (end of the line); exact
    planar's area/chord is half the MTD for a vertex-into-face overlap, by design.
(c) degenerate sets, one marker shape per set: the same rate as (a). For "deep" the reference is the true 3-D MTD
    (vertical), so a vertical answer counts as right there.
"""
import argparse
import json
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
from matplotlib.ticker import NullFormatter  # noqa: E402

RATE_FLOOR = 1e-5
ERR_FLOOR = 1e-16
COLOURS = {"planar": "tab:blue", "gjk2d": "tab:cyan", "ccd_epa": "tab:red", "ccd_tie": "tab:orange",
           "ccd_mpr": "tab:purple", "sat": "tab:green"}
CASE_MARKERS = {"touching": "o", "separated": "s", "vertex": "^", "parallel": "D", "deep": "v", "mixed": "P"}


def load(path):
    try:
        with open(path) as f:
            return json.load(f)
    except (OSError, json.JSONDecodeError) as e:
        sys.exit(f"plot_failure_map.py: cannot read {path}: {e}")


def wrong_rate(r, with_definition=True):
    """(failed + missed + false + non-finite + wrong normals that are not ties) / pairs."""
    wrong = r["wrong_normal"] - r["wrong_normal_ties"] if with_definition else 0
    bad = r["failed"] + r["missed"] + r["false_contact"] + r["nonfinite"] + wrong
    return max(bad / r["pairs"], RATE_FLOOR)


def floor_line(ax, y, text):
    ax.axhline(y, color="0.6", ls=":", lw=1)
    ax.annotate(text, (0.01, y), xycoords=("axes fraction", "data"), textcoords="offset points", xytext=(2, 3),
                fontsize=7, color="0.4")


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("json", help="bench_failure_map JSON file")
    ap.add_argument("-o", "--out", default="docs/figures/failure_map.png", help="PNG file to write")
    a = ap.parse_args()
    d = load(a.json)
    labels = {m["name"]: m["label"] for m in d["methods"]}
    res = {(r["case"], r["method"]): r for r in d["results"]}
    methods = [m["name"] for m in d["methods"]]
    cases = [c["name"] for c in d["cases"]]

    fig, (ax1, ax2, ax3) = plt.subplots(1, 3, figsize=(16, 5.0))

    # (a) random and far sets.
    for m in methods:
        col = COLOURS.get(m, "k")
        for case, face in (("random", col), ("far", "none")):
            r = res.get((case, m))
            if r is None:
                continue
            planar = m == "planar"
            y = wrong_rate(r, with_definition=not planar)
            ax1.scatter(r["ns_per_pair"], y, s=70, marker="o", facecolor=face, edgecolor=col, lw=1.5, zorder=3,
                        label=f"{labels[m]}" if case == "random" else None)
            if planar:
                ax1.scatter(r["ns_per_pair"], wrong_rate(r), s=50, marker="x", color=col, zorder=3,
                            label="exact planar incl. chord-normal deviations (by design)" if case == "random" else None)
    ax1.scatter([], [], s=70, marker="o", facecolor="none", edgecolor="k", label="open: same pairs 10 km out")
    floor_line(ax1, RATE_FLOOR, "none wrong (0)")
    n_random = next((c["pairs"] for c in d["cases"] if c["name"] == "random"), 0)
    ax1.set_xscale("log")
    ax1.set_yscale("log")
    ax1.set_ylim(RATE_FLOOR / 3, 1.0)
    ax1.set_xlabel("ns per pair (one core)")
    ax1.set_ylabel("(failed + missed + false + wrong normal) / pairs")
    ax1.set_title(f"(a) random level floes, {n_random:,} pairs, MTD 1 mm - 10 cm")
    ax1.legend(fontsize=7, loc="upper left")

    # (b) depth error on the random set.
    for m in methods:
        r = res.get(("random", m))
        if r is None or r["depth_error_median"] is None:
            continue
        col = COLOURS.get(m, "k")
        med = max(r["depth_error_median"], ERR_FLOOR)
        mx = max(r["depth_error_max"], ERR_FLOOR)
        ax2.plot([r["ns_per_pair"]] * 2, [med, mx], color=col, lw=1.5)
        ax2.scatter(r["ns_per_pair"], med, s=70, color=col, zorder=3, label=labels[m])
        ax2.scatter(r["ns_per_pair"], mx, s=30, marker="_", color=col, zorder=3)
    planar = res.get(("random", "planar"))
    if planar is not None:
        ax2.annotate("area/chord: half the MTD\nfor a vertex into a face\n(by design)",
                     (planar["ns_per_pair"], planar["depth_error_median"]), textcoords="offset points",
                     xytext=(8, -30), fontsize=7)
    floor_line(ax2, ERR_FLOOR, f"floor {ERR_FLOOR:g}")
    ax2.set_xscale("log")
    ax2.set_yscale("log")
    ax2.set_ylim(ERR_FLOOR / 3, 10.0)
    ax2.set_xlabel("ns per pair (one core)")
    ax2.set_ylabel("|depth - MTD| / MTD  (marker: median, line: up to max)")
    ax2.set_title("(b) depth error, random set")
    ax2.legend(fontsize=7, loc="center left")

    # (c) degenerate sets; the zeros staggered below the floor line by set, so that the shapes stay apart.
    degenerate = [c for c in cases if c not in ("random", "far")]
    for k, case in enumerate(degenerate):
        for m in methods:
            r = res.get((case, m))
            if r is None:
                continue
            y = wrong_rate(r, with_definition=m != "planar")
            if y <= RATE_FLOOR:
                y = RATE_FLOOR / 1.3 ** k
            ax3.scatter(r["ns_per_pair"], y, marker=CASE_MARKERS.get(case, "*"), s=55, color=COLOURS.get(m, "k"),
                        alpha=0.8, zorder=3)
    for case, mk in CASE_MARKERS.items():
        if case in cases:
            ax3.scatter([], [], marker=mk, color="0.3", label=case)
    for m in methods:
        ax3.plot([], [], color=COLOURS.get(m, "k"), lw=6, label=m)
    floor_line(ax3, RATE_FLOOR, "none wrong (0; staggered below by set)")
    n_deg = next((c["pairs"] for c in d["cases"] if c["name"] == "touching"), 0)
    ax3.set_xscale("log")
    ax3.set_yscale("log")
    ax3.set_ylim(RATE_FLOOR / 1.3 ** len(degenerate) / 1.5, 1.5)
    ax3.set_xlabel("ns per pair (one core)")
    ax3.set_ylabel("(failed + missed + false + wrong normal) / pairs")
    ax3.set_title(f"(c) degenerate sets, {n_deg:,} pairs each")
    ax3.legend(fontsize=7, loc="center right", ncol=2)

    ticks = [100, 200, 500, 1000, 2000, 5000, 10000, 20000]
    for ax in (ax1, ax2, ax3):
        lo, hi = ax.get_xlim()
        ax.set_xticks([t for t in ticks if lo <= t <= hi])
        ax.set_xticklabels([f"{t:,}" for t in ticks if lo <= t <= hi])
        ax.xaxis.set_minor_formatter(NullFormatter())
    fig.tight_layout()
    out_dir = os.path.dirname(a.out)
    if out_dir:
        os.makedirs(out_dir, exist_ok=True)
    fig.savefig(a.out, dpi=130)
    print(f"wrote {a.out}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
