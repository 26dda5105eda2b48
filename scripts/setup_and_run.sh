#!/usr/bin/env bash
# The main job on a fresh Debian 12 machine: install dependencies, build, run the default channel scene.
# Extra arguments go to `polyfloe run` (e.g. --set run.duration=60).
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
POLYFLOE_BUILD_TARGETS=polyfloe bash scripts/build.sh  # the program only: the tests build with the test command
out="results/channel"
./build/polyfloe run dem/scenes/channel.yaml -o "$out" "$@"
echo
echo "Open $(pwd)/$out/floes.pvd in ParaView (File > Open), or read $(pwd)/$out/results.h5 with h5py."
