#!/usr/bin/env bash
# The test job on a fresh Debian 12 machine: install dependencies (ParaView's pvbatch included), build, run every
# test of CI (CTest labels unit, validation, regression; the slow channel-scene test and the ParaView pictures
# included). The study tier (label study: the long runs behind docs' figures, each property asserted here by a
# shorter test) is left out: `ctest --test-dir build -L study` runs it. Extra arguments go to ctest.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh paraview  # everything, and ParaView for the picture tests (tests/paraview/)
# The programs and the tests; not the benchmark drivers of tests/bench, which no test runs (`bash scripts/build.sh`
# builds them too; CI builds them after this command).
POLYFLOE_BUILD_DIR="${POLYFLOE_BUILD_DIR:-build}" POLYFLOE_BUILD_TARGETS=all bash scripts/build.sh -DPOLYFLOE_WERROR=ON
ctest --test-dir "${POLYFLOE_BUILD_DIR:-build}" --output-on-failure -j "$(nproc)" -LE study "$@"
