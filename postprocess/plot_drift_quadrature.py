#!/usr/bin/python3
"""Torque error against cost of the bottom-drag quadrature rules (docs/figures/drift_quadrature.png).

Reads the JSON of tests/bench/bench_drift (BM_SkinDragQuadrature: counters ns_per_floe, torque_error, force_error;
label "<field> <rule>") and plots, for the sheared current and the Rankine vortex, the RMS relative torque error
against the CPU time per floe. Medians are used when the benchmark was repeated.

    ./build/tests/bench_drift --benchmark_filter=SkinDrag --benchmark_repetitions=5 \
        --benchmark_report_aggregates_only=true --benchmark_out=docs/data/drift_quadrature.json \
        --benchmark_out_format=json
    /usr/bin/python3 postprocess/plot_drift_quadrature.py docs/data/drift_quadrature.json \
        docs/figures/drift_quadrature.png
"""
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
from polyfloe_post.bench_json import quadrature_rows  # noqa: E402


def main(argv):
    if len(argv) != 3:
        sys.stderr.write(__doc__)
        return 2
    src, out = argv[1], argv[2]
    try:
        rows = quadrature_rows(src)
    except (OSError, ValueError) as e:
        sys.stderr.write(f"plot_drift_quadrature.py: cannot read {src}: {e}\n")
        return 1
    if not rows:
        sys.stderr.write(f"plot_drift_quadrature.py: no BM_SkinDragQuadrature results in {src}\n")
        return 1
    rules = ["centroid", "degree1", "degree2", "degree4", "degree5"]
    fig, ax = plt.subplots(figsize=(6.4, 4.4))
    for field, marker in (("shear", "o"), ("vortex", "s")):
        pts = [(rows[(field, r)], r) for r in rules if (field, r) in rows]
        xs = [p[0][0] for p in pts]
        ys = [max(p[0][1], 1e-6) for p in pts]
        ax.plot(xs, ys, marker=marker, label=f"{field}", linewidth=1)
        if field == "shear":  # one set of labels: the rules sit at the same cost in both fields
            for (vals, r), x, y in zip(pts, xs, ys):
                name = r + (" (default)" if r == "degree2" else "")
                ax.annotate(f"{name}\n{vals[3]:.0f} points", (x, y), textcoords="offset points", xytext=(-10, -22),
                            fontsize=7, ha="center")
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlabel("CPU time per floe, bottom drag incl. field sampling [ns]")
    ax.set_ylabel("RMS relative torque error [-]")
    ax.set_title("Skin-drag quadrature: torque error vs cost\n(~1.2k power-law floes; reference: degree 5 on 4^4 sub-triangles)",
                 fontsize=9)
    ax.grid(True, which="both", alpha=0.3)
    ax.set_ylim(1e-4, 2.0)
    ax.legend()
    fig.tight_layout()
    fig.savefig(out, dpi=150)
    print(f"wrote {out}")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
