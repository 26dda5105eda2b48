#!/usr/bin/env bash
# Instructions per floe-step, stage by stage, of one bench_step case, counted by valgrind's callgrind: a figure that
# does not move with the machine's load (the same binary and case give the same count to a few parts in a million),
# so that a change to the step can be judged on a shared machine where timings spread by 10 % or more. It counts
# work, not time: cache misses and the instructions' latencies are not in it (time the case with bench_step too).
#
#   bash scripts/count_instructions.sh                                   # BM_DensePackContactOnlySorted/1500/1
#   bash scripts/count_instructions.sh -c BM_DensePackSorted/15000/1     # every drift term as well
#   bash scripts/count_instructions.sh -b build-bench -o results/bench   # build folder, where the JSON goes
#
# Runs the case under callgrind (about 50 x slower than natively: half a minute for the default case), counting only
# inside World::step, and prints each stage's inclusive count per floe-step and its share of the step; writes
# OUT/instructions_<case>.json. Installs valgrind through scripts/setup.sh bench.
set -euo pipefail
cd "$(dirname "$0")/.."
CASE="BM_DensePackContactOnlySorted/1500/1"
BUILD_DIR=build-bench
OUT=results/bench
while [[ $# -gt 0 ]]; do
  case "$1" in
    -c) CASE="$2"; shift 2 ;;
    -b) BUILD_DIR="$2"; shift 2 ;;
    -o) OUT="$2"; shift 2 ;;
    -h|--help) sed -n '2,13p' "$0"; exit 0 ;;
    *) echo "count_instructions.sh: unknown argument '$1' (try -h)" >&2; exit 2 ;;
  esac
done
[[ "$CASE" =~ ^BM_[A-Za-z]+/[0-9]+/[12]$ ]] ||
  { echo "count_instructions.sh: -c expects a bench_step case like BM_DensePackSorted/15000/1, got '$CASE'" >&2; exit 2; }
bash scripts/setup.sh bench
if [[ ! -f "$BUILD_DIR/CMakeCache.txt" ]]; then
  cmake -S . -B "$BUILD_DIR" -G Ninja -DCMAKE_BUILD_TYPE=Release -DBUILD_TESTING=ON >/dev/null
fi
cmake --build "$BUILD_DIR" --target bench_step >/dev/null
if ! "$BUILD_DIR/tests/bench_step" --benchmark_list_tests --benchmark_filter="^$CASE/" | grep -q .; then
  echo "count_instructions.sh: bench_step has no case $CASE; its one-thread cases:" >&2
  "$BUILD_DIR/tests/bench_step" --benchmark_list_tests | sed -n 's|^\(BM_[A-Za-z]*/[0-9]*/1\)/.*|  \1|p' >&2
  exit 2
fi
mkdir -p "$OUT"
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
name=${CASE//\//_}
echo "callgrind: $BUILD_DIR/tests/bench_step --benchmark_filter='^$CASE/' (counting inside World::step)"
valgrind --tool=callgrind --callgrind-out-file="$tmp/callgrind.out" --toggle-collect='polyfloe::dynamics::World::step(double)' \
  "$BUILD_DIR/tests/bench_step" --benchmark_filter="^$CASE/" --benchmark_out="$tmp/bench.json" \
  --benchmark_out_format=json >/dev/null 2>"$tmp/valgrind.log" ||
  { echo "count_instructions.sh: valgrind failed (see below)" >&2; tail -20 "$tmp/valgrind.log" >&2; exit 1; }
callgrind_annotate --inclusive=yes --tree=caller "$tmp/callgrind.out" >"$tmp/annotate.txt" 2>/dev/null
/usr/bin/python3 - "$tmp/annotate.txt" "$tmp/bench.json" "$CASE" "$OUT/instructions_$name.json" <<'EOF'
import json, re, sys

annotate, bench, case, out = sys.argv[1:5]
runs = [b for b in json.load(open(bench))["benchmarks"] if b.get("run_type", "iteration") == "iteration"]
if not runs:
    sys.exit(f"count_instructions.sh: bench_step ran no case matching {case}")
floes = float(runs[0]["floes"])

# The stages, as the functions that hold them (inclusive counts; indented ones are inside the one above).
stages = [
    ("step", "polyfloe::dynamics::World::step(double)", 0),
    ("first kick + drift + slot keys", "polyfloe::dynamics::World::kick_and_drift(double)", 1),
    ("force evaluation", "polyfloe::dynamics::World::evaluate_forces(double, bool)", 1),
    ("world-frame shapes", "polyfloe::dynamics::World::update_shape(int)", 2),
    ("full drift evaluations", "polyfloe::dynamics::World::drift_forces(double)", 2),
    ("contact stage", "polyfloe::dynamics::World::contact_forces(double)", 2),
    ("candidate pairs", "polyfloe::dynamics::World::candidate_pairs()", 3),
    ("neighbour-list builds", "polyfloe::dynamics::World::build_skin()", 4),
    ("narrow phase", "polyfloe::contact::planar_overlap(", 3),
    ("contact sums", "polyfloe::dynamics::World::sum_contacts(int)", 3),
    ("bonds", "polyfloe::dynamics::World::bond_forces(double)", 2),
    ("final kick", "polyfloe::dynamics::World::kick_implicit(double)", 1),
]
# callgrind_annotate --tree=caller: "  COST (PCT)  *  file:function [object]" opens each function's block (its
# inclusive cost), preceded by "  COST (PCT)  <  file:caller (Nx) [object]" lines (calls from each caller).
inclusive, calls = {}, {}
pending = []
line_re = re.compile(r"^\s*([\d,]+)\s+\([\d.\s]+%\)\s+([<*>])\s+(.*)$")
for line in open(annotate):
    m = line_re.match(line)
    if not m:
        pending = []
        continue
    cost, kind, rest = int(m.group(1).replace(",", "")), m.group(2), m.group(3)
    if kind == "<":
        n = re.search(r"\(([\d,]+)x\)", rest)
        pending.append(int(n.group(1).replace(",", "")) if n else 0)
    elif kind == "*":
        fn = rest.split(":", 1)[1] if ":" in rest else rest
        for _, key, _ in stages:
            # The function itself, not an OpenMP region outlined from it (its cost is in the function's). With
            # line information a function is listed once per source file its inlined code came from; the entry of
            # its own file holds the inclusive cost, the largest.
            if fn.startswith(key) and "._omp_fn" not in fn and cost > inclusive.get(key, 0):
                inclusive[key] = cost
                calls[key] = sum(pending)
        pending = []
step_key = stages[0][1]
steps = calls.get(step_key, 0)
if not steps or not inclusive.get(step_key):
    sys.exit("count_instructions.sh: World::step was not found in the profile")
total = inclusive[step_key]
rows = []
print(f"{case}: {floes:.0f} floes, {steps} steps, {total / (steps * floes):.0f} instructions per floe-step")
print(f"{'stage':<40} {'per floe-step':>14} {'share':>7}")
for label, key, depth in stages:
    if key not in inclusive:
        continue
    per = inclusive[key] / (steps * floes)
    rows.append({"stage": label, "function": key, "instructions_per_floe_step": per, "share": inclusive[key] / total})
    print(f"{'  ' * depth + label:<40} {per:>14.0f} {100.0 * inclusive[key] / total:>6.1f}%")
json.dump({"case": case, "floes": floes, "steps": steps, "instructions": total, "stages": rows}, open(out, "w"),
          indent=1)
print(f"written: {out}")
EOF
