#!/usr/bin/env bash
# Configures and builds PolyFloe (Release) into build/ (or $POLYFLOE_BUILD_DIR). Extra arguments go to cmake.
# $POLYFLOE_BUILD_TARGETS (space-separated, e.g. "polyfloe"; "all": the programs and tests without the benchmarks)
# builds only those targets (default: everything, the tests and the benchmarks of tests/bench included).
set -euo pipefail
cd "$(dirname "$0")/.."
BUILD_DIR="${POLYFLOE_BUILD_DIR:-build}"
cmake -S . -B "$BUILD_DIR" -G Ninja -DCMAKE_BUILD_TYPE="${POLYFLOE_BUILD_TYPE:-Release}" "$@" >/dev/null
targets=()
default="all"
if grep -q '^build benchmarks:' "$BUILD_DIR/build.ninja" 2>/dev/null; then default="all benchmarks"; fi
for t in ${POLYFLOE_BUILD_TARGETS:-$default}; do targets+=(--target "$t"); done
cmake --build "$BUILD_DIR" -j "$(nproc)" "${targets[@]}"
