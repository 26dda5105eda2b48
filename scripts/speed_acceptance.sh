#!/usr/bin/env bash
# The [speed] acceptance points measured and checked in one go (docs/performance.md, "The [speed] acceptance
# points"): the narrow phase on 12-vertex pairs, the dense packs at 1.5k to 1.5M floes on one and two threads,
# LAMMPS's disk pack side by side (scripts/bench_lammps.sh) and, with --channel, the paper's channel run.
#
#   bash scripts/speed_acceptance.sh             # about 15 min once built
#   bash scripts/speed_acceptance.sh --channel   # and the 60 % channel run, 300 s on 2 threads (about 2 min more)
#
# Prints each point with its bar, the figures measured and whether the bar is met, and writes
# results/bench/speed_acceptance.json beside the benchmarks' JSON and bench_lammps.sh's CSV files. Timings on
# a shared machine spread (docs/performance.md, "Machine and build"): a point near its bar can be met in one run
# and missed in the next. Exit status 0 whether or not the bars are met; non-zero when a measurement failed.
set -euo pipefail
cd "$(dirname "$0")/.."

OUT=results/bench  # where scripts/bench_lammps.sh writes its CSV files too
CHANNEL=0
while [[ $# -gt 0 ]]; do
  case "$1" in
    --channel) CHANNEL=1; shift ;;
    -h|--help) sed -n '2,12p' "$0"; exit 0 ;;
    *) echo "speed_acceptance.sh: unknown argument '$1' (try -h)" >&2; exit 2 ;;
  esac
done
BUILD_DIR=build-bench
mkdir -p "$OUT"

run() {
  echo "+ $*"
  "$@"
}

bash scripts/setup.sh bench  # Google Benchmark, LAMMPS
source scripts/bench_build.sh
bench_build "$BUILD_DIR" bench_narrow_phase bench_step polyfloe

aggregates=(--benchmark_report_aggregates_only=true --benchmark_enable_random_interleaving=true)
run "$BUILD_DIR/tests/bench_narrow_phase" \
  --benchmark_filter='BM_PlanarOverlap(Kept)?/12/|BM_PlanarSeparated/12/|BM_Method/[03]/12/' \
  --benchmark_repetitions=5 "${aggregates[@]}" \
  --benchmark_out="$OUT/acceptance_narrow_phase.json" --benchmark_out_format=json >/dev/null
# The dense packs (random order only at 150k: the sizes in random order are the same-run case's, below).
run "$BUILD_DIR/tests/bench_step" \
  --benchmark_filter='^BM_DensePack(Sorted|Foundation)?/|^BM_DensePackContactOnlySorted/|^BM_DensePackContactOnly/150000/' \
  --benchmark_repetitions=3 "${aggregates[@]}" \
  --benchmark_out="$OUT/acceptance_step.json" --benchmark_out_format=json >/dev/null
# Random against lattice order and the sizes, each measured by turns of steps within one run (bench_step.cpp's
# *SameRun cases), three repetitions (the Worlds built anew each time).
run "$BUILD_DIR/tests/bench_step" --benchmark_filter='SameRun' --benchmark_repetitions=3 "${aggregates[@]}" \
  --benchmark_out="$OUT/acceptance_same_run.json" --benchmark_out_format=json >/dev/null
run bash scripts/bench_lammps.sh >"$OUT/acceptance_lammps.log"

channel_wall=""
if [[ "$CHANNEL" == 1 ]]; then
  tmp=$(mktemp -d)
  trap 'rm -rf "$tmp"' EXIT
  run /usr/bin/time -f "%e" -o "$tmp/wall" "$BUILD_DIR/polyfloe" run dem/scenes/channel.yaml -o "$tmp/run" \
    --set floe_field.concentration=0.6 --threads 2 >"$tmp/log" 2>&1 ||
    { echo "speed_acceptance.sh: the channel run failed:" >&2; tail -5 "$tmp/log" >&2; exit 1; }
  channel_wall=$(cat "$tmp/wall")
fi

/usr/bin/python3 - "$OUT" "$channel_wall" <<'PY'
import csv, json, sys

out, channel_wall = sys.argv[1], sys.argv[2]


def medians(path):
    with open(path) as f:
        data = json.load(f)
    result = {}
    for b in data["benchmarks"]:
        if b.get("aggregate_name") == "median":
            result[b["run_name"]] = b
    return result


def find(table, prefix):
    hits = [b for name, b in table.items() if name.startswith(prefix)]
    if len(hits) != 1:
        sys.exit(f"speed_acceptance.sh: expected one median of {prefix}, found {len(hits)}")
    return hits[0]


np = medians(f"{out}/acceptance_narrow_phase.json")
st = medians(f"{out}/acceptance_step.json")
points = []


def point(name, bar, measured, met):
    points.append({"point": name, "bar": bar, "measured": measured, "met": bool(met)})


kept = find(np, "BM_PlanarOverlapKept/12/")["ns_per_pair"]
new = find(np, "BM_PlanarOverlap/12/")["ns_per_pair"]
planar = find(np, "BM_Method/0/12/")
ccd = find(np, "BM_Method/3/12/")
point("narrow phase, 12-vertex pairs: depth and normal", "<= 160 ns per pair",
      f"persisting contact (kept topology) {kept:.1f} ns; new pair {new:.0f} ns", kept <= 160)
point("full contact with overlap patch, zero failures", "<= 350 ns per pair",
      f"{planar['ns_per_pair']:.0f} ns, contact found for {100 * planar['contact_fraction']:.1f} % of the pairs",
      planar["ns_per_pair"] <= 350 and planar["contact_fraction"] == 1.0)
point("against libccd GJK-EPA, same run", ">= 10x faster",
      f"libccd {ccd['ns_per_pair']:.0f} ns: {ccd['ns_per_pair'] / planar['ns_per_pair']:.1f}x",
      ccd["ns_per_pair"] >= 10 * planar["ns_per_pair"])


def us(case):
    return find(st, case + "/")["us_per_floe_step"]


sizes = [1500, 15000, 150000, 1500000]
c150 = {order: us(f"BM_DensePackContactOnly{order}/150000/1") for order in ("", "Sorted")}
d150 = {order: us(f"BM_DensePack{order}/150000/1") for order in ("", "Sorted")}
point("dense pack at 150k floes, one core", "<= 0.3 us per floe-step",
      f"contact only {c150['']:.3f} (random order) / {c150['Sorted']:.3f} (lattice order); "
      f"every drift term {d150['']:.3f} / {d150['Sorted']:.3f}", min(c150.values()) <= 0.3)

with open(f"{out}/polyfloe_vs_lammps.csv") as f:
    rows = [r for r in csv.DictReader(f) if r["case"] == "DensePackContactOnly" and r["floes"] != "1500000"]
with open(f"{out}/lammps.csv") as f:
    disks = list(csv.DictReader(f))
ratios = [float(r["polyfloe_over_lammps"]) for r in rows]
point("against LAMMPS disks, same run", "<= 2x",
      "LAMMPS " + " / ".join(d["lammps_ns_per_particle_step"] for d in disks) + " ns; contact only " +
      " / ".join(f"{x:.2f}x" for x in ratios), max(ratios) <= 2)

series = [us(f"BM_DensePackContactOnlySorted/{n}/1") for n in sizes]
spread = (max(series) - min(series)) / (max(series) + min(series))
point("flat from 1.5k to 1.5M floes, contact only, lattice order", "+-20 %",
      " / ".join(f"{x:.3f}" for x in series) + f": +-{100 * spread:.1f} %", spread <= 0.2)

# The two points measured within one run, by turns of steps (medians of three repetitions).
same = medians(f"{out}/acceptance_same_run.json")
sizes_run = find(same, "BM_ContactOnlySizesSameRun/")
series = [sizes_run[f"us_{n}"] for n in sizes]  # each size's median of the repetitions' medians
spread = 100 * (max(series) - min(series)) / (max(series) + min(series))
point("flat from 1.5k to 1.5M floes, contact only, random order, same run", "+-20 %",
      " / ".join(f"{x:.3f}" for x in series) + f": +-{spread:.1f} %", spread <= 20)
for n in (150000, 1500000):
    b = find(same, f"BM_ContactOnlyOrderSameRun/{n}/")
    point(f"random order against lattice order, contact only, {n} floes, same run", "<= 1.1x",
          f"{b['random_us']:.3f} / {b['lattice_us']:.3f}; turn by turn {b['ratio']:.2f}x", b["ratio"] <= 1.1)

for case in ("BM_DensePack/15000", "BM_DensePack/150000", "BM_DensePackSorted/15000", "BM_DensePackSorted/150000",
             "BM_DensePackContactOnly/150000"):
    one, two = us(case + "/1"), us(case + "/2")
    point(f"2 threads, {case[3:]}", ">= 1.7x one thread", f"{one:.3f} / {two:.3f} = {one / two:.2f}x",
          one / two >= 1.7)

if channel_wall:
    wall = float(channel_wall)
    point("the paper's channel run (60 %, 300 s), 2 threads", "<= 60 s", f"{wall:.1f} s", wall <= 60)

with open(f"{out}/speed_acceptance.json", "w") as f:
    json.dump(points, f, indent=1)
width = max(len(p["point"]) for p in points)
for p in points:
    print(f"{'met' if p['met'] else 'NOT met':8} {p['point']:{width}}  bar {p['bar']}: {p['measured']}")
print(f"{sum(p['met'] for p in points)} of {len(points)} met; written: {out}/speed_acceptance.json")
PY
