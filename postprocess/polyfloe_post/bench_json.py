"""Readers of the Google Benchmark JSON that tests/bench writes, shared by the plotting scripts."""
import json
import sys


def quadrature_rows(src):
    """{(field, rule): (ns_per_floe, torque_error, force_error, points_per_floe)} of BM_SkinDragQuadrature (medians
    when repeated); raises OSError or ValueError (json.JSONDecodeError) when the file cannot be read."""
    with open(src) as f:
        data = json.load(f)
    rows = {}
    for b in data.get("benchmarks", []):
        if not b["name"].startswith("BM_SkinDragQuadrature") or "error_occurred" in b:
            continue
        if b.get("run_type") == "aggregate" and b.get("aggregate_name") != "median":
            continue
        field, rule = b["label"].split()
        rows[(field, rule)] = (b["ns_per_floe"], b["torque_error"], b["force_error"], b["points_per_floe"])
    return rows


def field_sampling_rows(path):
    """{(source, rule): (ns_per_floe, force_error, torque_error)} of BM_FieldSampling (medians when repeated); exits
    naming the file when it cannot be read or holds no such result."""
    try:
        with open(path) as f:
            data = json.load(f)
    except (OSError, json.JSONDecodeError) as e:
        sys.exit(f"plot_field_sampling: cannot read {path}: {e}")
    rows = {}
    for b in data.get("benchmarks", []):
        if b.get("run_type") == "aggregate" and b.get("aggregate_name") != "median":
            continue
        label = b.get("label", "")
        source, rule = label.rsplit(" ", 1)
        rows[(source, rule)] = (b["ns_per_floe"], b["force_error"], b["torque_error"])
    if not rows:
        sys.exit(f"plot_field_sampling: no BM_FieldSampling results in {path}")
    return rows
