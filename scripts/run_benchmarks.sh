#!/usr/bin/env bash
# Builds the benchmarks (Release) and runs them: the planar narrow phase (tests/bench/bench_narrow_phase.cpp), the
# whole World::step (tests/bench/bench_step.cpp) and the drift forcing (tests/bench/bench_drift.cpp: quadrature
# accuracy vs cost, the drift stage per floe), floe-field generation (tests/bench/bench_floe_field.cpp) and frozen
# sheets under compression (tests/bench/bench_bonds.cpp). Console output on the terminal, JSON in the results folder.
#
#   bash scripts/run_benchmarks.sh [-b BUILD_DIR] [-o RESULTS_DIR] [-r REPETITIONS] [-- EXTRA_BENCHMARK_ARGS...]
#
#   -b  build folder (default build-bench; configured as Release with Ninja when new)
#   -o  results folder (default results/bench): bench_narrow_phase.json, bench_step.json, bench_drift.json,
#       machine.txt
#   -r  repetitions; > 1 adds --benchmark_repetitions=N --benchmark_report_aggregates_only=true (mean, median,
#       stddev, cv) and --benchmark_enable_random_interleaving=true (repetitions of different cases are shuffled,
#       so a burst of load elsewhere on the machine does not land on one case); docs/performance.md quotes the
#       medians of -r 5
#   after --: passed to both executables (e.g. --benchmark_filter=DensePack)
#
# Run time once built, on the 2-core reference machine: several minutes a repetition (bench_step's 1.5M-floe
# and same-run cases take most of it; docs/performance.md, "How to rerun").
set -euo pipefail
cd "$(dirname "$0")/.."

BUILD_DIR="build-bench"
OUT_DIR="results/bench"
REPS=1
while [[ $# -gt 0 ]]; do
  case "$1" in
    -b) BUILD_DIR="$2"; shift 2 ;;
    -o) OUT_DIR="$2"; shift 2 ;;
    -r) REPS="$2"; shift 2 ;;
    -h|--help) sed -n '2,15p' "$0"; exit 0 ;;
    --) shift; break ;;
    *) echo "run_benchmarks.sh: unknown argument '$1' (try -h)" >&2; exit 2 ;;
  esac
done
if ! [[ "$REPS" =~ ^[1-9][0-9]*$ ]]; then
  echo "run_benchmarks.sh: -r expects a positive integer, got '$REPS'" >&2
  exit 2
fi

run() {
  echo "+ $*"
  "$@"
}

# Configure (Release) and build only the benchmark targets it runs.
source scripts/bench_build.sh
bench_build "$BUILD_DIR" bench_narrow_phase bench_step bench_drift bench_floe_field bench_bonds || exit 1

mkdir -p "$OUT_DIR"
{
  echo "date: $(date -u +%Y-%m-%dT%H:%M:%SZ)"
  echo "commit: $(git describe --always --dirty --tags 2>/dev/null || echo unknown)"
  echo "compiler: $(c++ --version | head -n 1)"
  echo "nproc: $(nproc)"
  lscpu 2>/dev/null | grep -E '^(Model name|CPU\(s\)|Thread|Core|Socket|CPU family|Model:|L1d|L2|L3|Hypervisor)' || true
} >"$OUT_DIR/machine.txt"

extra=()
if [[ "$REPS" -gt 1 ]]; then
  extra=(--benchmark_repetitions="$REPS" --benchmark_report_aggregates_only=true --benchmark_enable_random_interleaving=true)
fi

for b in bench_narrow_phase bench_step bench_drift bench_floe_field bench_bonds; do
  run "$BUILD_DIR/tests/$b" --benchmark_format=console --benchmark_counters_tabular=false \
    --benchmark_out="$OUT_DIR/$b.json" --benchmark_out_format=json "${extra[@]}" "$@"
done
echo "JSON and machine description in $OUT_DIR/"

# Compact summary of the JSON (medians when repeated): what docs/performance.md tabulates.
if command -v python3 >/dev/null; then
  python3 - "$OUT_DIR" <<'PY'
import json, sys, os
out = sys.argv[1]
def rows(name):
    path = os.path.join(out, name)
    if not os.path.getsize(path):  # a --benchmark_filter that matched nothing in this executable
        return []
    with open(path) as f:
        data = json.load(f)
    runs = [b for b in data["benchmarks"] if b.get("run_type") != "aggregate" or b.get("aggregate_name") == "median"]
    runs = [b for b in runs if "error_occurred" not in b]
    def key(b):  # by case, then by its first argument (none: 0)
        parts = b["run_name"].split("/")
        return parts[0], int(parts[1]) if len(parts) > 1 and parts[1].isdigit() else 0
    return sorted(runs, key=key)
print("\nsummary (median over repetitions where repeated; CPU time)")
print("  narrow phase             ns/pair")
for b in rows("bench_narrow_phase.json"):
    print(f"  {b['run_name'].split('/min_time')[0]:<24} {b['ns_per_pair']:8.1f}")
print(f"  {'step':<42} us/floe-step  contacts/floe  candidates/floe  narrow_only ns/floe  narrow_law ns/floe")
for b in rows("bench_step.json"):
    name = b['run_name'].split('/iterations')[0]
    if "bytes_per_floe" in b:
        print(f"  {name:<42} {b['bytes_per_floe']:12.0f}  bytes per floe (heap)")
        continue
    if "ratio" in b:  # BM_ContactOnlyOrderSameRun: two Worlds by turns
        print(f"  {name:<42} random {b['random_us']:.3f}, lattice {b['lattice_us']:.3f} us/floe-step;"
              f" random / lattice turn by turn {b['ratio']:.3f}")
        continue
    if "spread_percent" in b:  # BM_ContactOnlySizesSameRun: four Worlds by turns
        sizes = sorted((int(k[3:]), v) for k, v in b.items() if k.startswith("us_") and k[3:].isdigit())
        print(f"  {name:<42} " + " / ".join(f"{v:.3f}" for _, v in sizes) +
              f" us/floe-step at {' / '.join(str(n) for n, _ in sizes)} floes: +-{b['spread_percent']:.1f} %")
        continue
    print(f"  {name:<42} {b['us_per_floe_step']:12.3f}  {b['contacts_per_floe']:13.3f}"
          f"  {b['candidates_per_floe']:15.3f}  {b['narrow_only_ns']:19.0f}  {b['narrow_law_ns']:18.0f}")
print("  drift                    ns/floe  torque error  force error  (label)")
for b in rows("bench_drift.json"):
    if "torque_error" in b:
        print(f"  {b['run_name'].split('/iterations')[0]:<24} {b['ns_per_floe']:7.0f}  {b['torque_error']:12.2e}"
              f"  {b['force_error']:11.2e}  ({b.get('label', '')})")
    else:
        print(f"  {b['run_name'].split('/iterations')[0]:<24} {b['drift_ns_per_floe']:7.0f}  (drift stage; whole step"
              f" {b['step_ns_per_floe']:.0f} ns/floe; {b.get('label', '')})")
PY
fi
