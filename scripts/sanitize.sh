#!/usr/bin/env bash
# Builds with AddressSanitizer + UndefinedBehaviorSanitizer into build-asan/ (or $POLYFLOE_ASAN_DIR) and runs the
# tests under them.
#   bash scripts/sanitize.sh            every test but the slow and study labels (the validation tests take ~7 min)
#   bash scripts/sanitize.sh --ci       unit and regression tests (the CI step): builds only those folders and no
#                                       benchmarks, and leaves out three of the five kill-and-restart runs and the
#                                       two 2-thread runs (1.5-2.5 min each under the sanitizers; the test step runs
#                                       them; their code runs here through the channel's kill-and-restart, the
#                                       restart and state tests and the 2-thread unit tests)
# Other arguments go to ctest.
# The sanitizer build is clang's (installed by scripts/setup.sh fuzz), at -O2 with line tables only (-g1): reports
# keep function names, files and lines; clang builds it in less than half the time GCC took at -O1, and the tests run
# faster than GCC's -O1 build ran them. The same build holds the libFuzzer targets of tests/fuzz
# (-DPOLYFLOE_FUZZ=ON: the libraries carry libFuzzer's coverage instrumentation as well, dem/CMakeLists.txt), which
# `bash scripts/fuzz.sh --build build-asan` runs without building the libraries a third time. The test files
# compile at -O2 as well: at clang's -O1 (or -O0), Eigen's small functions stay calls, and tests with loops of their
# own over Eigen ran 7-10 times longer.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh fuzz
labels=(-LE "slow|study")
kinds="unit;validation;regression"
benchmarks=ON
if [[ "${1:-}" == "--ci" ]]; then
  labels=(-LE "slow|validation|study" -E '^(Threads\.TwoThreadsGiveTheOneThread|Restart\.Killed(FrozenSheet|FoundationForceModel|Spatial))')
  kinds="unit;regression"
  benchmarks=OFF
  shift
fi
flags="-O2 -g1 -DNDEBUG"
POLYFLOE_BUILD_DIR="${POLYFLOE_ASAN_DIR:-build-asan}" POLYFLOE_BUILD_TYPE=RelWithDebInfo bash scripts/build.sh \
  -DCMAKE_C_COMPILER=clang -DCMAKE_CXX_COMPILER=clang++ -DPOLYFLOE_SANITIZE=ON -DPOLYFLOE_FUZZ=ON -DPOLYFLOE_WERROR=ON \
  "-DCMAKE_CXX_FLAGS_RELWITHDEBINFO=$flags" "-DCMAKE_C_FLAGS_RELWITHDEBINFO=$flags" \
  "-DPOLYFLOE_TEST_KINDS=$kinds" -DPOLYFLOE_BENCHMARKS=$benchmarks -DPOLYFLOE_TEST_OPTIMIZE=-O2
export ASAN_OPTIONS=detect_leaks=1:abort_on_error=1
export LSAN_OPTIONS="suppressions=$PWD/tests/support/lsan.supp"
export UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1
ctest --test-dir "${POLYFLOE_ASAN_DIR:-build-asan}" --output-on-failure -j "$(nproc)" "${labels[@]}" "$@"
