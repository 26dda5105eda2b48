#!/usr/bin/env bash
# Builds with AddressSanitizer + UndefinedBehaviorSanitizer into build-asan/ and runs the tests under them.
#   bash scripts/sanitize.sh            every test but the slow label (the validation tests take ~7 min here)
#   bash scripts/sanitize.sh --ci       unit and regression tests (the CI step): builds only those folders and no
#                                       benchmarks, and leaves out three of the five kill-and-restart runs and the
#                                       two 2-thread runs (1.5-2.5 min each under the sanitizers; the test step runs
#                                       them; their code runs here through the channel's kill-and-restart, the
#                                       restart and state tests and the 2-thread unit tests)
# Other arguments go to ctest.
# The sanitizer build compiles at -O1 with line tables only (-g1): reports keep function names, files and lines,
# and the build takes about half the time of -O2 -g.
set -euo pipefail
cd "$(dirname "$0")/.."
labels=(-LE slow)
kinds="unit;validation;regression"
benchmarks=ON
if [[ "${1:-}" == "--ci" ]]; then
  labels=(-LE "slow|validation" -E '^(Threads\.TwoThreadsGiveTheOneThread|Restart\.Killed(FrozenSheet|FoundationForceModel|Spatial))')
  kinds="unit;regression"
  benchmarks=OFF
  shift
fi
flags="-O1 -g1 -DNDEBUG"
POLYFLOE_BUILD_DIR=build-asan POLYFLOE_BUILD_TYPE=RelWithDebInfo bash scripts/build.sh -DPOLYFLOE_SANITIZE=ON \
  -DPOLYFLOE_WERROR=ON "-DCMAKE_CXX_FLAGS_RELWITHDEBINFO=$flags" "-DCMAKE_C_FLAGS_RELWITHDEBINFO=$flags" \
  "-DPOLYFLOE_TEST_KINDS=$kinds" -DPOLYFLOE_BENCHMARKS=$benchmarks
export ASAN_OPTIONS=detect_leaks=1:abort_on_error=1
export UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1
ctest --test-dir build-asan --output-on-failure -j "$(nproc)" "${labels[@]}" "$@"
