#!/usr/bin/env bash
# Builds with AddressSanitizer + UndefinedBehaviorSanitizer into build-asan/ and runs the tests (all but the slow
# label, which takes minutes under the sanitizers). Extra arguments go to ctest.
set -euo pipefail
cd "$(dirname "$0")/.."
POLYFLOE_BUILD_DIR=build-asan POLYFLOE_BUILD_TYPE=RelWithDebInfo bash scripts/build.sh -DPOLYFLOE_SANITIZE=ON -DPOLYFLOE_WERROR=ON
export ASAN_OPTIONS=detect_leaks=1:abort_on_error=1
export UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1
ctest --test-dir build-asan --output-on-failure -j "$(nproc)" -LE slow "$@"
