#!/usr/bin/env bash
# Instructions per floe-step, stage by stage, of a bench_step case or a stretch of a scene's run, counted by
# valgrind's callgrind: a figure that does not move with the machine's load (the same binary and input gave the
# same count per floe-step, to the instruction, in repeated runs), so that a change to the step can be judged on a
# shared machine where timings spread by 10 % or more. It counts work, not time: cache misses and the latencies of square roots and
# divisions are not in it (time the case with bench_step, or the run, too).
#
#   bash scripts/count_instructions.sh                                   # BM_DensePackContactOnlySorted/1500/1
#   bash scripts/count_instructions.sh -c BM_DensePackSorted/15000/1     # every drift term as well
#   bash scripts/count_instructions.sh -s dem/scenes/channel.yaml --from 300 --for 1 \
#       --set floe_field.concentration=0.6                               # the paper's channel run, jammed
#   bash scripts/count_instructions.sh -b build-bench -o results/bench   # build folder, where the JSON goes
#
# A bench_step case runs whole under callgrind (about 50 x slower than natively: half a minute for the default
# case). A scene (-s) runs natively to --from seconds [s] (writing its checkpoint there), then on one thread under
# callgrind for --for seconds more from that checkpoint (300 -> 301 s of the channel: 1,597 steps);
# --set overrides go to both runs. Only World::step is counted. Prints each stage's inclusive count per floe-step
# and its share of the step; writes OUT/instructions_<case or scene>.json. Installs valgrind (scripts/setup.sh
# bench).
set -euo pipefail
cd "$(dirname "$0")/.."
CASE="BM_DensePackContactOnlySorted/1500/1"
SCENE=""
FROM=""
FOR=""
SETS=()
BUILD_DIR=build-bench
OUT=results/bench
usage() { sed -n '2,19p' "$0"; }
while [[ $# -gt 0 ]]; do
  case "$1" in
    -c) CASE="$2"; shift 2 ;;
    -s) SCENE="$2"; shift 2 ;;
    --from) FROM="$2"; shift 2 ;;
    --for) FOR="$2"; shift 2 ;;
    --set) SETS+=(--set "$2"); shift 2 ;;
    -b) BUILD_DIR="$2"; shift 2 ;;
    -o) OUT="$2"; shift 2 ;;
    -h|--help) usage; exit 0 ;;
    *) echo "count_instructions.sh: unknown argument '$1' (try -h)" >&2; exit 2 ;;
  esac
done
number='^[0-9]+([.][0-9]+)?$'
if [[ -n "$SCENE" ]]; then
  [[ -f "$SCENE" ]] || { echo "count_instructions.sh: -s: no scene file '$SCENE'" >&2; exit 2; }
  [[ "$FROM" =~ $number ]] && [[ "$FOR" =~ $number ]] && awk -v d="$FOR" 'BEGIN { exit !(d > 0) }' ||
    { echo "count_instructions.sh: -s needs --from SECONDS (>= 0) and --for SECONDS (> 0), got '$FROM' and '$FOR'" >&2
      exit 2; }
else
  [[ -z "$FROM$FOR${SETS[*]:-}" ]] ||
    { echo "count_instructions.sh: --from, --for and --set go with -s SCENE" >&2; exit 2; }
  [[ "$CASE" =~ ^BM_[A-Za-z]+/[0-9]+/[12]$ ]] ||
    { echo "count_instructions.sh: -c expects a bench_step case like BM_DensePackSorted/15000/1, got '$CASE'" >&2
      exit 2; }
fi
bash scripts/setup.sh bench
source scripts/bench_build.sh
mkdir -p "$OUT"
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
toggle='polyfloe::dynamics::World::step(double)'
fail() { echo "count_instructions.sh: $1 (see below)" >&2; tail -20 "$2" >&2; exit 1; }
if [[ -n "$SCENE" ]]; then
  bench_build "$BUILD_DIR" polyfloe >/dev/null
  name=$(basename "$SCENE" .yaml)_${FROM}s
  until=$(awk -v a="$FROM" -v b="$FOR" 'BEGIN { printf "%.10g", a + b }')
  echo "native: $BUILD_DIR/polyfloe run $SCENE ${SETS[*]:-} --set run.duration=$FROM"
  "$BUILD_DIR/polyfloe" run "$SCENE" -o "$tmp/run" "${SETS[@]}" --set run.duration="$FROM" >"$tmp/native.log" 2>&1 ||
    fail "the run to $FROM s failed" "$tmp/native.log"
  echo "callgrind: the same from its checkpoint to $until s, one thread (counting inside World::step)"
  valgrind --tool=callgrind --callgrind-out-file="$tmp/callgrind.out" --toggle-collect="$toggle" \
    "$BUILD_DIR/polyfloe" run "$SCENE" -o "$tmp/run" --restart "$tmp/run" "${SETS[@]}" --set run.duration="$until" \
    --threads 1 --profile >/dev/null 2>"$tmp/valgrind.log" || fail "valgrind failed" "$tmp/valgrind.log"
  # The profile line names the bodies: "... (1432 bodies, 1597 steps)".
  bodies=$(sed -n 's/^profile (us per body-step):.*(\([0-9]*\) bodies, .*/\1/p' "$tmp/valgrind.log")
  [[ -n "$bodies" ]] || fail "the run printed no profile" "$tmp/valgrind.log"
  label="$SCENE${SETS[*]:+ ${SETS[*]}}: $FROM -> $until s"
  unit=body
else
  bench_build "$BUILD_DIR" bench_step >/dev/null
  if ! "$BUILD_DIR/tests/bench_step" --benchmark_list_tests --benchmark_filter="^$CASE/" | grep -q .; then
    echo "count_instructions.sh: bench_step has no case $CASE; its one-thread cases:" >&2
    "$BUILD_DIR/tests/bench_step" --benchmark_list_tests | sed -n 's|^\(BM_[A-Za-z]*/[0-9]*/1\)/.*|  \1|p' >&2
    exit 2
  fi
  name=${CASE//\//_}
  echo "callgrind: $BUILD_DIR/tests/bench_step --benchmark_filter='^$CASE/' (counting inside World::step)"
  valgrind --tool=callgrind --callgrind-out-file="$tmp/callgrind.out" --toggle-collect="$toggle" \
    "$BUILD_DIR/tests/bench_step" --benchmark_filter="^$CASE/" --benchmark_out="$tmp/bench.json" \
    --benchmark_out_format=json >/dev/null 2>"$tmp/valgrind.log" || fail "valgrind failed" "$tmp/valgrind.log"
  bodies=$(/usr/bin/python3 -c '
import json, sys
runs = [b for b in json.load(open(sys.argv[1]))["benchmarks"] if b.get("run_type", "iteration") == "iteration"]
print(runs[0]["floes"] if runs else "")' "$tmp/bench.json")
  [[ -n "$bodies" ]] || { echo "count_instructions.sh: bench_step ran no case matching $CASE" >&2; exit 1; }
  label="$CASE"
  unit=floe
fi
callgrind_annotate --inclusive=yes --tree=caller "$tmp/callgrind.out" >"$tmp/annotate.txt" 2>/dev/null
/usr/bin/python3 - "$tmp/annotate.txt" "$bodies" "$label" "$OUT/instructions_$name.json" "$unit" <<'EOF'
import json, re, sys

annotate, count, case, out, unit = sys.argv[1], float(sys.argv[2]), sys.argv[3], sys.argv[4], sys.argv[5]

# The stages, as the functions that hold them (inclusive counts; indented ones are inside the one above).
stages = [
    ("step", "polyfloe::dynamics::World::step(double)", 0),
    ("first kick + move + slot keys", "polyfloe::dynamics::World::kick_and_move(double)", 1),
    ("force evaluation", "polyfloe::dynamics::World::evaluate_forces(double, bool)", 1),
    ("world-frame shapes", "polyfloe::dynamics::World::update_shape(int)", 2),
    ("full drift evaluations", "polyfloe::dynamics::World::drift_forces(double)", 2),
    ("contact stage", "polyfloe::dynamics::World::contact_forces(double)", 2),
    ("candidate pairs", "polyfloe::dynamics::NeighbourLists::candidate_pairs(", 3),
    ("neighbour-list builds", "polyfloe::dynamics::NeighbourLists::build(", 4),
    ("narrow phase", "polyfloe::contact::planar_overlap(", 3),
    ("contact sums", "polyfloe::dynamics::World::sum_contacts(int)", 3),
    ("bonds", "polyfloe::dynamics::World::bond_forces(double)", 2),
    ("final kick", "polyfloe::dynamics::World::kick_implicit(double)", 1),
]
# callgrind_annotate --tree=caller: "  COST (PCT)  *  file:function [object]" opens each function's block (its
# inclusive cost), preceded by "  COST (PCT)  <  file:caller (Nx) [object]" lines (calls from each caller): those
# of World::step are the steps.
step_key = stages[0][1]
inclusive, steps = {}, 0
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
                if key == step_key:
                    steps = sum(pending)
        pending = []
if not steps or not inclusive.get(step_key):
    sys.exit("count_instructions.sh: World::step was not found in the profile")
total = inclusive[step_key]
rows = []
plural = "bodies" if unit == "body" else "floes"
print(f"{case}: {count:.0f} {plural}, {steps} steps, {total / (steps * count):.0f} instructions per {unit}-step")
print(f"{'stage':<40} {'per ' + unit + '-step':>14} {'share':>7}")
for label, key, depth in stages:
    if key not in inclusive:
        continue
    per = inclusive[key] / (steps * count)
    share = inclusive[key] / total
    rows.append({"stage": label, "function": key, f"instructions_per_{unit}_step": per, "share": share})
    print(f"{'  ' * depth + label:<40} {per:>14.0f} {100.0 * share:>6.1f}%")
json.dump({"case": case, plural: count, "steps": steps, "instructions": total, "stages": rows}, open(out, "w"),
          indent=1)
print(f"written: {out}")
EOF
