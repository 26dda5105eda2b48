#!/usr/bin/env bash
# Builds with AddressSanitizer + UndefinedBehaviorSanitizer into build-asan/ and runs the tests under them.
#   bash scripts/sanitize.sh            every test but the slow label (the validation tests take ~7 min here)
#   bash scripts/sanitize.sh --ci       unit and regression tests (the CI step: ~3 min of tests after the build)
# Other arguments go to ctest.
set -euo pipefail
cd "$(dirname "$0")/.."
labels=(-LE slow)
if [[ "${1:-}" == "--ci" ]]; then
  labels=(-LE "slow|validation")
  shift
fi
POLYFLOE_BUILD_DIR=build-asan POLYFLOE_BUILD_TYPE=RelWithDebInfo bash scripts/build.sh -DPOLYFLOE_SANITIZE=ON -DPOLYFLOE_WERROR=ON
export ASAN_OPTIONS=detect_leaks=1:abort_on_error=1
export UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1
ctest --test-dir build-asan --output-on-failure -j "$(nproc)" "${labels[@]}" "$@"
