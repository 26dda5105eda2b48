#!/usr/bin/env bash
# Regenerates docs/figures/channel.png (the README picture) from a run of the default channel scene.
set -euo pipefail
cd "$(dirname "$0")/.."
[ -x build/polyfloe ] || bash scripts/build.sh
./build/polyfloe run dem/scenes/channel.yaml -o results/channel
/usr/bin/python3 postprocess/plot_frames.py results/channel/results.h5 -t 0 150 300 -o docs/figures/channel.png
