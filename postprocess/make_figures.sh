#!/usr/bin/env bash
# Regenerates the figures in docs/figures/ from their runs and benchmarks:
#   channel.png           the README picture, from a run of the default channel scene (~5 min);
#   drift_quadrature.png  skin-drag torque error vs cost per quadrature rule, from tests/bench/bench_drift (~1 min),
#                         with its data in docs/data/drift_quadrature.json;
#   channel_geometry.png  the channel scene's walls, ice region and dimensions (seconds);
#   stability_map.png, speed_accuracy.png  from tests/bench/bench_stability (~9 min, one core), with their data in
#                         docs/data/stability_map.json and step_cost.json (and drift_quadrature.json above).
#   cube_plate.png        the paper's Fig. 3: tests/bench/bench_cube_plate (~10 s), data docs/data/cube_plate.json;
#   failure_map.png       contact methods' failures and cost: tests/bench/bench_failure_map, data
#                         docs/data/failure_map.json.
#   strait_openfoam_vs_uniform.png  of_cases/strait/Allrun --uniform: OpenFOAM, import, two 600 s ice runs (~5 min).
#   field_sampling.png    field-sampling error vs cost: tests/bench/bench_field_sampling on the strait case (~1 min),
#                         data docs/data/field_sampling.json.
#   paraview_*.png        ParaView's pictures (postprocess/paraview/, rendered by pvbatch; installs ParaView with
#                         scripts/setup.sh paraview): the channel scene (floes by speed, velocity grid), its contacts,
#                         the uniaxial compression's cracks, the ice over the OpenFOAM strait (~5 min); their state
#                         files go to postprocess/paraview/states/, the animations to results/paraview/.
#   (The sweep figures come from scripts/sweep.sh and postprocess/plot_sweep.py: docs/validation.md.)
#   bash postprocess/make_figures.sh [channel|drift|geometry|stability|cube_plate|failure_map|strait|field_sampling|
#                                     paraview]...   (default: all)
set -euo pipefail
cd "$(dirname "$0")/.."
which=("$@")
[ ${#which[@]} -gt 0 ] || which=(channel drift geometry stability cube_plate failure_map strait field_sampling paraview)
for w in "${which[@]}"; do
  case "$w" in
    channel)
      [ -x build/polyfloe ] || bash scripts/build.sh
      ./build/polyfloe run dem/scenes/channel.yaml -o results/channel
      /usr/bin/python3 postprocess/plot_frames.py results/channel/results.h5 -t 0 150 300 -o docs/figures/channel.png
      ;;
    strait)
      bash of_cases/strait/Allrun --uniform
      cp of_cases/strait/compare.png docs/figures/strait_openfoam_vs_uniform.png
      ;;
    field_sampling)
      [ -f of_cases/strait/field.h5 ] || bash of_cases/strait/Allrun --quick
      cmake -S . -B build-bench -DCMAKE_BUILD_TYPE=Release >/dev/null
      cmake --build build-bench --target bench_field_sampling -j "$(nproc)"
      build-bench/tests/bench_field_sampling --case of_cases/strait --benchmark_repetitions=3 \
        --benchmark_report_aggregates_only=true --benchmark_enable_random_interleaving=true \
        --benchmark_out=docs/data/field_sampling.json --benchmark_out_format=json
      /usr/bin/python3 postprocess/plot_field_sampling.py docs/data/field_sampling.json docs/figures/field_sampling.png
      ;;
    drift)
      cmake -S . -B build-bench -DCMAKE_BUILD_TYPE=Release >/dev/null
      cmake --build build-bench --target bench_drift -j "$(nproc)"
      build-bench/tests/bench_drift --benchmark_filter=SkinDrag --benchmark_repetitions=5 \
        --benchmark_report_aggregates_only=true --benchmark_enable_random_interleaving=true \
        --benchmark_out=docs/data/drift_quadrature.json --benchmark_out_format=json
      /usr/bin/python3 postprocess/plot_drift_quadrature.py docs/data/drift_quadrature.json \
        docs/figures/drift_quadrature.png
      ;;
    geometry)
      [ -x build/polyfloe ] || bash scripts/build.sh
      ./build/polyfloe run dem/scenes/channel.yaml -o results/channel_geometry --set run.duration=0.001 \
        --set output.vtk=false >/dev/null 2>&1
      /usr/bin/python3 postprocess/plot_channel_geometry.py results/channel_geometry -o docs/figures/channel_geometry.png
      ;;
    stability)
      cmake -S . -B build-bench -DCMAKE_BUILD_TYPE=Release >/dev/null
      cmake --build build-bench --target bench_stability -j "$(nproc)"
      build-bench/tests/bench_stability --only impacts --only packs -o docs/data/stability_map.json
      build-bench/tests/bench_stability --only cost -o docs/data/step_cost.json
      /usr/bin/python3 postprocess/plot_stability.py docs/data/stability_map.json docs/data/step_cost.json \
        --quadrature docs/data/drift_quadrature.json --field docs/data/field_sampling.json --out docs/figures
      ;;
    cube_plate)
      cmake -S . -B build-bench -DCMAKE_BUILD_TYPE=Release >/dev/null
      cmake --build build-bench --target bench_cube_plate -j "$(nproc)"
      build-bench/tests/bench_cube_plate -o docs/data/cube_plate.json
      /usr/bin/python3 postprocess/plot_cube_plate.py docs/data/cube_plate.json -o docs/figures/cube_plate.png
      ;;
    failure_map)
      cmake -S . -B build-bench -DCMAKE_BUILD_TYPE=Release >/dev/null
      cmake --build build-bench --target bench_failure_map -j "$(nproc)"
      build-bench/tests/bench_failure_map -o docs/data/failure_map.json
      /usr/bin/python3 postprocess/plot_failure_map.py docs/data/failure_map.json -o docs/figures/failure_map.png
      ;;
    paraview)
      bash scripts/setup.sh paraview
      [ -x build/polyfloe ] || bash scripts/build.sh
      runs=results/paraview
      mkdir -p postprocess/paraview/states
      ./build/polyfloe run dem/scenes/channel.yaml -o "$runs/channel"
      ./build/polyfloe run dem/scenes/uniaxial_compression.yaml -o "$runs/uniaxial"
      bash of_cases/strait/Allrun  # renders of_cases/strait/paraview/ice_over_field.png itself
      pv() { bash scripts/pvbatch.sh "postprocess/paraview/$1" "${@:2}" --size 1200 675; }
      pv channel.py "$runs/channel" -o "$runs/pictures" --animation
      pv contacts.py "$runs/channel" -o "$runs/pictures"
      pv cracks.py "$runs/uniaxial" -o "$runs/pictures" --animation
      pv ice_over_field.py of_cases/strait/ice/openfoam --field of_cases/strait/field.pvd -o "$runs/pictures" \
        --animation
      for k in channel contacts cracks ice_over_field; do
        cp "$runs/pictures/$k.png" "docs/figures/paraview_$k.png"
        cp "$runs/pictures/$k.pvsm" "postprocess/paraview/states/$k.pvsm"
      done
      ;;
    *) echo "make_figures.sh: unknown figure '$w' (channel, drift, geometry, stability, cube_plate, failure_map, strait," \
            "field_sampling, paraview)" >&2
       exit 2 ;;
  esac
done
