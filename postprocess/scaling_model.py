#!/usr/bin/python3
"""The scaling model of the World cut among MPI ranks, fitted to bench_mpi's runs (scripts/bench_mpi.sh), and its
projection to 8-1,024 ranks for 10^5-10^7 floes.

    /usr/bin/python3 postprocess/scaling_model.py [--runs results/bench/mpi] [--latency 2e-6] [--bandwidth 1e10]
                                                  [-o docs/data/scaling_model.json]

Per step, each of P ranks owns n = N / P floes of a square region and holds G ghosts along its edges:

    T(N, P) = f_imb * c_busy * (n + G) + m * alpha + B / beta + 2 log2(P) * alpha + r * n

    c      the one-core cost per floe-step [s] (the 1 x 1 run): the reference of the efficiency
    c_busy the cost per floe-step of a rank while every core computes (the 2-rank run: each rank's wall time per
           step less its time in the exchanges, in the renewal test and in renewals, over its owned floes and
           ghosts): what sharing the machine's memory and caches costs; a ghost is counted as a floe (an upper bound)
    G      = 4 * delta * sqrt(n) ghosts (a square region, 4 faces of sqrt(n) floes), delta the halo's depth in floes,
           fitted to the 2-rank run (its ghosts per rank over the cut's sqrt(N) floes)
    m      messages per step: 3 per neighbouring rank (poses, predicted velocities, pair forces), 8 neighbours
    B      bytes per step: G * b_g, b_g the bytes per ghost per step of the 2-rank run
    alpha  the network's latency [s], beta its bandwidth [B/s] (assumed: not measurable on one machine)
    r      the renewals' cost per owned floe per step [s] (the 2-rank run's renewal seconds per step over n)
    f_imb  1.1, the imbalance a renewal tolerates before Zoltan cuts the regions anew

The parallel efficiency is c * N / (P * T). LAMMPS on its disk pack, 1 and 2 ranks on the same machine, is the
anchor: its 2-rank efficiency against PolyFloe's.
"""
import argparse
import json
import math
import os
import sys


def load(folder, name):
    path = os.path.join(folder, name + ".json")
    if not os.path.exists(path):
        sys.exit(f"scaling_model: {path} is missing: run bash scripts/bench_mpi.sh first")
    with open(path) as f:
        return json.load(f)


def fit(folder, drift):
    one = load(folder, f"pack_{drift}_1x1")
    two = load(folder, f"pack_{drift}_2x1")
    n_floes = one["floes"]
    c = one["core_us_per_floe_step"] * 1e-6
    rows = two["ranks_rows"]
    n = sum(r["owned"] for r in rows) / len(rows)
    ghosts = sum(r["ghosts"] for r in rows) / len(rows)
    busy = [(two["wall_s_per_step"] - r["halo_s_per_step"] - r["check_s_per_step"] - r["renewal_s_per_step"]) /
            (r["owned"] + r["ghosts"]) for r in rows]
    return {
        "floes": n_floes,
        "c_s": c,
        "c_busy_s": sum(busy) / len(busy),
        "delta_floes": ghosts / math.sqrt(n_floes),
        "bytes_per_ghost": sum(r["halo_bytes_per_step"] for r in rows) / len(rows) / max(ghosts, 1.0),
        "renewal_s_per_floe": sum(r["renewal_s_per_step"] for r in rows) / len(rows) / n,
        "halo_s_per_step_2ranks": sum(r["halo_s_per_step"] for r in rows) / len(rows),
        "efficiency_2ranks": c * n_floes / (2 * two["wall_s_per_step"]),
    }


def project(m, n_floes, ranks, alpha, beta, neighbours=8, imbalance=1.1):
    n = n_floes / ranks
    faces = 1 if ranks == 2 else 4
    ghosts = faces * m["delta_floes"] * math.sqrt(n) if ranks > 1 else 0.0
    compute = imbalance * m["c_busy_s"] * (n + ghosts) if ranks > 1 else m["c_s"] * n
    comm = 0.0
    if ranks > 1:
        comm = (3 * min(neighbours, ranks - 1) * alpha + ghosts * m["bytes_per_ghost"] / beta +
                2 * math.log2(ranks) * alpha + m["renewal_s_per_floe"] * n)
    t = compute + comm
    return {"floes": n_floes, "ranks": ranks, "step_s": t, "comm_share": comm / t,
            "efficiency": m["c_s"] * n_floes / (ranks * t), "floe_steps_per_s": n_floes / t}


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--runs", default="results/bench/mpi", help="bench_mpi's JSON (scripts/bench_mpi.sh)")
    ap.add_argument("--latency", type=float, default=2e-6, help="network latency alpha [s] (assumed)")
    ap.add_argument("--bandwidth", type=float, default=1e10, help="network bandwidth beta [B/s] (assumed)")
    ap.add_argument("--lammps", default="results/bench/mpi.csv", help="bench_mpi.sh's CSV (LAMMPS rows)")
    ap.add_argument("-o", default="", help="JSON written")
    a = ap.parse_args()
    out = {"assumed": {"latency_s": a.latency, "bandwidth_B_per_s": a.bandwidth}, "fits": {}, "projection": {}}
    for drift in ("all", "contact"):
        m = fit(a.runs, drift)
        out["fits"][drift] = m
        print(f"fit ({'every drift term' if drift == 'all' else 'contact only'}, {m['floes']} floes): "
              f"c = {1e6 * m['c_s']:.3f} us/floe-step, halo depth {m['delta_floes']:.2f} floes, "
              f"c_busy = {1e6 * m['c_busy_s']:.3f} us, {m['bytes_per_ghost']:.0f} B/ghost/step, "
              f"renewals {1e9 * m['renewal_s_per_floe']:.2f} ns/floe-step; measured 2-rank efficiency "
              f"{m['efficiency_2ranks']:.2f}")
        rows = []
        print("| floes | ranks | step [ms] | communication share | efficiency | floe-steps/s |")
        print("|---:|---:|---:|---:|---:|---:|")
        for n_floes in (1e5, 1e6, 1e7):
            for ranks in (8, 64, 1024):
                p = project(m, n_floes, ranks, a.latency, a.bandwidth)
                rows.append(p)
                print(f"| {n_floes:.0e} | {ranks} | {1e3 * p['step_s']:.3f} | {100 * p['comm_share']:.1f} % | "
                      f"{p['efficiency']:.2f} | {p['floe_steps_per_s']:.3g} |")
        out["projection"][drift] = rows
    if os.path.exists(a.lammps):
        lmp = {}
        with open(a.lammps) as f:
            for line in f:
                cells = line.strip().split(",")
                if cells[0].startswith("lammps_"):
                    lmp[int(cells[2])] = float(cells[4])
        if 1 in lmp and 2 in lmp:
            out["lammps"] = {"core_us_1rank": lmp[1], "core_us_2ranks": lmp[2], "efficiency_2ranks": lmp[1] / lmp[2]}
            print(f"LAMMPS anchor: {lmp[1]:.4f} core-us per particle-step on 1 rank, {lmp[2]:.4f} on 2: "
                  f"2-rank efficiency {lmp[1] / lmp[2]:.2f}")
    if a.o:
        os.makedirs(os.path.dirname(a.o) or ".", exist_ok=True)
        with open(a.o, "w") as f:
            json.dump(out, f, indent=2)
        print(f"written: {a.o}")


if __name__ == "__main__":
    main()
