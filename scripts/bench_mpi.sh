#!/usr/bin/env bash
# The World cut among MPI ranks against threads and one core, on the dense pack of bench_step (tests/bench/bench_mpi.cpp),
# with LAMMPS on the same machine as the anchor (its disk pack of tests/bench/lammps/disk_pack.in on 1 and 2 ranks):
#
#   bash scripts/bench_mpi.sh            # 150k floes: 1 rank x 1 thread, 1 x 2, 2 x 1, every drift term and contact
#                                        # only; weak scaling 1 x 75k and 2 x 75k; LAMMPS 160k disks on 1 and 2 ranks
#   bash scripts/bench_mpi.sh -n 15000   # a smaller pack (and 7.5k per rank for the weak scaling)
#   bash scripts/bench_mpi.sh -r 3       # medians of 3 repetitions
#   bash scripts/bench_mpi.sh -c         # the 60 % channel only: `polyfloe run` (outputs included, rank 0 gathering
#                                        # the ice for each frame) over its first 60 s, 1 x 1 and 1 x 2 (no mpirun)
#                                        # and 2 x 1
#
# Prints each run's table (bench_mpi: wall per step, core-us per floe-step, each rank's owned floes, ghosts, bytes
# and messages per step, seconds per step in the step's exchanges, in renewals and in the test for one) and writes
# results/bench/mpi/*.json and results/bench/mpi.csv; the channel's runs: results/bench/mpi_channel.csv (the wall
# time of the run's steps and outputs, from its "Done:" line, medians of -r). On a 2-core machine ranks x threads <= 2 only: the runs are one
# after the other, nothing else should run. Installs lammps through scripts/setup.sh bench.
set -euo pipefail
cd "$(dirname "$0")/.."

N=150000
REPS=1
STEPS=30
CHANNEL_ONLY=0
while [[ $# -gt 0 ]]; do
  case "$1" in
    -c) CHANNEL_ONLY=1; shift ;;
    -n) N="$2"; shift 2 ;;
    -r) REPS="$2"; shift 2 ;;
    -h|--help) sed -n '2,17p' "$0"; exit 0 ;;
    *) echo "bench_mpi.sh: unknown argument '$1' (try -h)" >&2; exit 2 ;;
  esac
done
[[ "$N" =~ ^[1-9][0-9]*$ && "$N" -ge 100 ]] || { echo "bench_mpi.sh: -n expects floes >= 100, got '$N'" >&2; exit 2; }
[[ "$REPS" =~ ^[1-9][0-9]*$ ]] || { echo "bench_mpi.sh: -r expects a positive integer, got '$REPS'" >&2; exit 2; }

bash scripts/setup.sh bench
BUILD_DIR=build-bench
source scripts/bench_build.sh
bench_build "$BUILD_DIR" bench_mpi polyfloe >/dev/null

OUT=results/bench/mpi
mkdir -p "$OUT"
WORK=$(mktemp -d "${TMPDIR:-/tmp}/polyfloe-mpi.XXXXXX")
trap 'rm -rf "$WORK"' EXIT
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMP_WAIT_POLICY=passive
MPIRUN=(mpirun --oversubscribe --bind-to none)

median() { sort -g | awk '{ v[NR] = $1 } END { print (NR % 2) ? v[(NR + 1) / 2] : (v[NR / 2] + v[NR / 2 + 1]) / 2 }'; }
json_value() { /usr/bin/python3 -c "import json,sys; print(json.load(open(sys.argv[1]))[sys.argv[2]])" "$1" "$2"; }

# The 60 % channel through the command line: the median wall time of REPS runs of its first 60 s, per layout.
channel() {
  local csv="$OUT/../mpi_channel.csv" ranks threads k walls
  echo "ranks,threads,wall_s,speedup" >"$csv"
  local base=""
  for layout in "1 1" "1 2" "2 1"; do
    read -r ranks threads <<<"$layout"
    walls=()
    for ((k = 0; k < REPS; ++k)); do
      rm -rf "$WORK/channel"
      # (one rank: the plain command, without mpirun, with OpenMP's default wait policy, as a user runs threads)
      local launch=(env -u OMP_WAIT_POLICY)
      [[ "$ranks" == 1 ]] || launch=("${MPIRUN[@]}" -np "$ranks")
      "${launch[@]}" "$BUILD_DIR/polyfloe" run dem/scenes/channel.yaml -o "$WORK/channel" \
        --threads "$threads" --set floe_field.concentration=0.6 --set run.duration=60 >"$WORK/channel.txt" 2>/dev/null
      walls+=("$(sed -n 's/^Done: .* simulated in \([0-9.e+-]*\) s wall.*/\1/p' "$WORK/channel.txt")")
    done
    local wall
    wall=$(printf '%s\n' "${walls[@]}" | median)
    base=${base:-$wall}
    printf 'channel 60 %%, first 60 s: %d rank(s) x %d thread(s): %s s wall (runs: %s)\n' "$ranks" "$threads" "$wall" \
      "${walls[*]}"
    echo "$ranks,$threads,$wall,$(awk -v b="$base" -v w="$wall" 'BEGIN { printf "%.3f", b / w }')" >>"$csv"
  done
  echo "written: $csv"
}
if [[ "$CHANNEL_ONLY" == 1 ]]; then
  channel
  exit 0
fi

echo "case,floes,ranks,threads,core_us_per_floe_step,wall_ms_per_step,max_halo_bytes_per_step,max_halo_ms_per_step" \
  >"$OUT/../mpi.csv"
# One configuration, REPS times: the median core-us per floe-step (and the JSON of the median run).
polyfloe() {
  local name="$1" ranks="$2" threads="$3"
  shift 3
  local values=() k
  for ((k = 0; k < REPS; ++k)); do
    OMP_NUM_THREADS="$threads" "${MPIRUN[@]}" -np "$ranks" "$BUILD_DIR/tests/bench_mpi" --threads "$threads" \
      --steps "$STEPS" "$@" -o "$WORK/$name.$k.json" | tee "$WORK/$name.$k.txt"
    values+=("$(json_value "$WORK/$name.$k.json" core_us_per_floe_step) $k")
  done
  local best
  best=$(printf '%s\n' "${values[@]}" | sort -g | awk -v n="${#values[@]}" 'NR == int((n + 1) / 2) { print $2 }')
  cp "$WORK/$name.$best.json" "$OUT/$name.json"
  /usr/bin/python3 - "$OUT/$name.json" "$name" >>"$OUT/../mpi.csv" <<'EOF'
import json, sys
j = json.load(open(sys.argv[1]))
rows = j["ranks_rows"]
print(f'{sys.argv[2]},{j["floes"]},{j["ranks"]},{j["threads"]},{j["core_us_per_floe_step"]:.4f},'
      f'{1e3 * j["wall_s_per_step"]:.3f},{max(r["halo_bytes_per_step"] for r in rows):.0f},'
      f'{max(1e3 * r["halo_s_per_step"] for r in rows):.3f}')
EOF
}

for drift in all contact; do
  extra=()
  [[ "$drift" == contact ]] && extra=(--contact-only)
  polyfloe "pack_${drift}_1x1" 1 1 --floes "$N" "${extra[@]}"
  polyfloe "pack_${drift}_1x2" 1 2 --floes "$N" "${extra[@]}"
  polyfloe "pack_${drift}_2x1" 2 1 --floes "$N" "${extra[@]}"
done
half=$((N / 2))
polyfloe "weak_1x1" 1 1 --floes "$half" --per-rank
polyfloe "weak_2x1" 2 1 --floes "$half" --per-rank

# LAMMPS's disks on 1 and 2 ranks: the 10 x 10 replication of the 1.6k pack (160k disks), as bench_lammps.sh.
for ranks in 1 2; do
  values=()
  for ((k = 0; k < REPS; ++k)); do
    OMP_NUM_THREADS=1 "${MPIRUN[@]}" -np "$ranks" lmp -in tests/bench/lammps/disk_pack.in -var rep 10 -var steps 50 \
      -var data "$WORK/base.data" -log none -screen "$WORK/lmp.out" >/dev/null
    loop=$(grep "^Loop time" "$WORK/lmp.out" | tail -1)
    atoms=$(awk '{ print $(NF - 1) }' <<<"$loop")
    secs=$(awk '{ print $4 }' <<<"$loop")
    values+=("$(awk -v s="$secs" -v a="$atoms" -v r="$ranks" 'BEGIN { printf "%.4f", s / 50 / a * 1e6 * r }')")
  done
  us=$(printf '%s\n' "${values[@]}" | median)
  printf 'LAMMPS  %d disks on %d ranks: %s core-us per particle-step\n' "$atoms" "$ranks" "$us"
  echo "lammps_${ranks}x1,$atoms,$ranks,1,$us,,," >>"$OUT/../mpi.csv"
done
channel
echo "written: $OUT/../mpi.csv, $OUT/*.json"
