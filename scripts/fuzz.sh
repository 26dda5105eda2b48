#!/usr/bin/env bash
# Fuzzes the scene reader and polygon validation / the planar narrow phase with libFuzzer, AddressSanitizer (leak
# detection on) and UndefinedBehaviorSanitizer: installs clang if missing (scripts/setup.sh fuzz), builds the
# targets of tests/fuzz into build-fuzz/ (clang, -O1 -g1, warnings as errors) and runs each target, as many
# side by side as there are cores.
#
#   bash scripts/fuzz.sh                 # = --smoke: 60 s per target (the CI step)
#   bash scripts/fuzz.sh --time 600      # 600 s per target
#   bash scripts/fuzz.sh --runs 1000000  # 10^6 executions per target (docs/validation.md, Fuzzing)
#   bash scripts/fuzz.sh --runs 1000 fuzz_polygon   # only the named targets
#   bash scripts/fuzz.sh --smoke --build build-asan  # the targets of the sanitizer build (scripts/sanitize.sh builds
#                                                    # them; the CI step), instead of building build-fuzz/
#
# The corpus grows in a work directory outside the source tree ($POLYFLOE_FUZZ_DIR, default a new directory under
# ${TMPDIR:-/tmp}), seeded with dem/scenes/*.yaml and tests/bad_input/*.yaml (scene target) and the inputs saved
# under tests/fuzz/regressions/<target>/ (inputs that once failed; every run replays them). Crashes, sanitizer reports, leaks, time-outs (an
# input running over 10 s) and memory blow-ups (over 2 GB) are saved in <work>/artifacts/ and make the script exit
# non-zero. Reproduce one with: build-fuzz/fuzz/<target> <artifact>. $POLYFLOE_FUZZ_FLAGS adds libFuzzer flags
# (e.g. -seed=1).
set -euo pipefail
cd "$(dirname "$0")/.."

usage() { sed -n '2,/^set -euo/p' "$0" | sed '$d; s/^# \{0,1\}//'; }

limit=(-max_total_time=60)
what="60 s"
targets=()
BUILD_DIR=""
while [ $# -gt 0 ]; do
  case "$1" in
    --smoke) limit=(-max_total_time=60); what="60 s" ;;
    --time) limit=(-max_total_time="${2:?--time needs seconds}"); what="$2 s"; shift ;;
    --runs) limit=(-runs="${2:?--runs needs a count}"); what="$2 executions"; shift ;;
    --build) BUILD_DIR="${2:?--build needs the sanitizer build folder}"; shift ;;
    -h|--help) usage; exit 0 ;;
    fuzz_*) targets+=("$1") ;;
    *) echo "fuzz: unknown argument '$1'" >&2; usage >&2; exit 2 ;;
  esac
  shift
done
[ ${#targets[@]} -gt 0 ] || targets=(fuzz_scene_parser fuzz_polygon fuzz_yaml_aliases fuzz_checkpoint)

bash scripts/setup.sh fuzz

t0=$(date +%s)
if [ -n "$BUILD_DIR" ]; then
  # An existing build configured with -DPOLYFLOE_FUZZ=ON (scripts/sanitize.sh): only what the targets lack is built.
  if ! grep -q '^POLYFLOE_FUZZ:BOOL=ON' "$BUILD_DIR/CMakeCache.txt" 2>/dev/null; then
    echo "fuzz: $BUILD_DIR is not a build with -DPOLYFLOE_FUZZ=ON (bash scripts/sanitize.sh makes build-asan)" >&2
    exit 2
  fi
  cmake --build "$BUILD_DIR" -j "$(nproc)" --target "${targets[@]}"
else
  BUILD_DIR=build-fuzz
  # -O1 with line tables only (-g1): reports keep function names, files and lines, and clang spends less on
  # optimisation and debug information than at -O2 -g (not timed for this standalone build).
  flags="-O1 -g1 -DNDEBUG"
  cmake -S . -B "$BUILD_DIR" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCMAKE_C_COMPILER=clang \
    -DCMAKE_CXX_COMPILER=clang++ -DPOLYFLOE_FUZZ=ON -DPOLYFLOE_WERROR=ON -DBUILD_TESTING=OFF \
    "-DCMAKE_CXX_FLAGS_RELWITHDEBINFO=$flags" "-DCMAKE_C_FLAGS_RELWITHDEBINFO=$flags" >/dev/null
  cmake --build "$BUILD_DIR" -j "$(nproc)" --target "${targets[@]}"
fi
echo "fuzz: built ${targets[*]} in $(( $(date +%s) - t0 )) s"

WORK="${POLYFLOE_FUZZ_DIR:-$(mktemp -d "${TMPDIR:-/tmp}/polyfloe-fuzz.XXXXXX")}"
mkdir -p "$WORK/artifacts" "$WORK/seeds/fuzz_scene_parser"
cp dem/scenes/*.yaml tests/bad_input/*.yaml "$WORK/seeds/fuzz_scene_parser/"
# A 64 MB quarantine (use-after-free detection window) instead of 256 MB keeps long runs well under the RSS limit.
export ASAN_OPTIONS="detect_leaks=1:abort_on_error=1:quarantine_size_mb=64:${ASAN_OPTIONS:-}"
export UBSAN_OPTIONS="print_stacktrace=1:halt_on_error=1:${UBSAN_OPTIONS:-}"
export LSAN_OPTIONS="suppressions=$PWD/tests/support/lsan.supp:${LSAN_OPTIONS:-}"

# Arguments of one target: its own options, then the corpus directories (the first one receives new inputs).
target_args() {
  local t=$1
  local -a a=(-timeout=10 -rss_limit_mb=2048 -detect_leaks=1 -print_final_stats=1 "${limit[@]}"
              -artifact_prefix="$WORK/artifacts/$t-")
  case "$t" in
    fuzz_scene_parser) a+=(-max_len=8192 -dict=tests/fuzz/scene.dict) ;;
    fuzz_yaml_aliases|fuzz_checkpoint) a+=(-max_len=512) ;;
    *) a+=(-max_len=4096) ;;
  esac
  mkdir -p "$WORK/corpus/$t"
  a+=("$WORK/corpus/$t")
  [ -d "$WORK/seeds/$t" ] && a+=("$WORK/seeds/$t")
  [ -d "tests/fuzz/regressions/$t" ] && a+=("tests/fuzz/regressions/$t")
  printf '%s\n' "${a[@]}"
}

echo "fuzz: ${targets[*]}, $what each, work directory $WORK"
# Side by side, as many at once as there are cores (2 cores: two batches of two). Each run records its start and
# end time.
cores=$(nproc)
declare -A pid rc
run_one() {
  local t=$1 status=0
  local -a args
  mapfile -t args < <(target_args "$t")
  date +%s.%N >"$WORK/$t.time"
  # shellcheck disable=SC2086  # POLYFLOE_FUZZ_FLAGS: extra libFuzzer flags, split on spaces
  "$BUILD_DIR/fuzz/$t" "${args[@]}" ${POLYFLOE_FUZZ_FLAGS:-} >"$WORK/$t.log" 2>&1 || status=$?
  date +%s.%N >>"$WORK/$t.time"
  return "$status"
}
for ((b = 0; b < ${#targets[@]}; b += cores)); do
  batch=("${targets[@]:b:cores}")
  for t in "${batch[@]}"; do run_one "$t" & pid[$t]=$!; done
  for t in "${batch[@]}"; do rc[$t]=0; wait "${pid[$t]}" || rc[$t]=$?; done
done

failed=0
printf '%-20s %12s %10s %10s  %s\n' target executions exec/s wall result
for t in "${targets[@]}"; do
  log="$WORK/$t.log"
  runs=$(sed -n 's/^stat::number_of_executed_units: *//p' "$log" | tail -1)
  rate=$(sed -n 's/^stat::average_exec_per_sec: *//p' "$log" | tail -1)
  wall=$(awk 'NR == 1 { s = $1 } NR == 2 { e = $1 } END { printf "%.0f s", e - s }' "$WORK/$t.time")
  if [ "${rc[$t]}" = 0 ]; then
    result="ok: no crash, leak or time-out"
  else
    failed=1
    result="FAILED (exit ${rc[$t]}): $(grep -m1 -E 'ERROR: |SUMMARY: |fuzz_[a-z_]+: ' "$log" || echo 'see the log')"
  fi
  printf '%-20s %12s %10s %10s  %s\n' "$t" "${runs:-?}" "${rate:-?}" "$wall" "$result"
done
if [ "$failed" = 1 ]; then
  echo "fuzz: logs in $WORK/*.log; saved inputs:" >&2
  ls -1 "$WORK/artifacts/" >&2 || true
  for t in "${targets[@]}"; do grep -h -A40 -E '==[0-9]+==ERROR|fuzz_[a-z_]+: ' "$WORK/$t.log" | head -60 >&2 || true; done
  exit 1
fi
echo "fuzz: corpus in $WORK/corpus"
