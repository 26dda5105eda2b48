#!/usr/bin/python3
"""Field-sampling error against cost: the chart of docs/figures/field_sampling.png.

    /usr/bin/python3 postprocess/plot_field_sampling.py docs/data/field_sampling.json docs/figures/field_sampling.png

Reads Google Benchmark JSON from tests/bench/bench_field_sampling.cpp (medians when repeated): for each way of
sampling the OpenFOAM strait current (a field-file grid of 40 ... 2.5 m, or the mesh probed directly) and each
bottom-quadrature rule, the ocean-drag force and torque error on floes in the strait against the CPU time per floe.
The default (grid = the mesh's finest cell, 5 m on the CI mesh; degree2) is ringed.
"""
import argparse

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
from polyfloe_post.bench_json import field_sampling_rows  # noqa: E402

RULES = ["centroid", "degree1", "degree2", "degree4"]
MARKERS = {"centroid": "o", "degree1": "s", "degree2": "D", "degree4": "^"}


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("data")
    ap.add_argument("output")
    ap.add_argument("--default", default="grid 5 m degree2", help="the default's label")
    a = ap.parse_args()
    rows = field_sampling_rows(a.data)
    sources = sorted({s for s, _ in rows}, key=lambda s: (s == "direct", -float(s.split()[1]) if s != "direct" else 0))
    fig, axes = plt.subplots(1, 2, figsize=(11, 4.4))
    cmap = plt.get_cmap("viridis")
    for ax, k, name in ((axes[0], 1, "force"), (axes[1], 2, "torque")):
        for j, src in enumerate(sources):
            pts = [(rows[(src, r)][0], rows[(src, r)][k], r) for r in RULES if (src, r) in rows]
            color = "crimson" if src == "direct" else cmap(j / max(1, len(sources) - 2))
            ax.plot([p[0] for p in pts], [p[1] for p in pts], "-", color=color, lw=1, label=src)
            for x, y, r in pts:
                ax.plot(x, y, MARKERS[r], color=color, ms=5)
        if tuple(a.default.rsplit(" ", 1)) in rows:
            x, y = rows[tuple(a.default.rsplit(" ", 1))][0], rows[tuple(a.default.rsplit(" ", 1))][k]
            ax.plot(x, y, "o", ms=14, mfc="none", mec="k", mew=1.5, label=f"default ({a.default})")
        ax.set_xscale("log")
        ax.set_yscale("log")
        ax.set_xlabel("CPU time per floe: ocean drag with the field sampled [ns]")
        ax.set_ylabel(f"RMS {name} error / RMS {name}")
        ax.grid(True, which="both", alpha=0.3)
        ax.set_title(f"ocean-drag {name} on floes in the OpenFOAM strait")
    for r, m in MARKERS.items():
        axes[1].plot([], [], m, color="0.4", label=r)
    axes[1].legend(fontsize=7, loc="upper right", ncol=2)
    fig.tight_layout()
    fig.savefig(a.output, dpi=130)
    print(f"wrote {a.output}")


if __name__ == "__main__":
    main()
