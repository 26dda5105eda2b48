# Sourced by the benchmark scripts (run_benchmarks.sh, speed_acceptance.sh, bench_lammps.sh,
# count_instructions.sh), from the repository root:
#
#   bench_build DIR TARGET...
#
# configures DIR as a Release build with the tests and benchmarks (with Ninja where DIR is new and ninja is
# installed; an existing DIR keeps its generator), then builds the targets on every core. A failed configuration
# or build prints the end of its output, says what the benchmarks need and returns non-zero.
bench_build() {
  local dir="$1"
  shift
  local generator=() log
  if [[ ! -f "$dir/CMakeCache.txt" ]] && command -v ninja >/dev/null; then generator=(-G Ninja); fi
  log=$(mktemp)
  echo "+ cmake -S . -B $dir${generator[*]:+ ${generator[*]}} -DCMAKE_BUILD_TYPE=Release -DBUILD_TESTING=ON"
  echo "+ cmake --build $dir --target $* -j $(nproc)"
  if ! { cmake -S . -B "$dir" "${generator[@]}" -DCMAKE_BUILD_TYPE=Release -DBUILD_TESTING=ON &&
         cmake --build "$dir" --target "$@" -j "$(nproc)"; } >"$log" 2>&1; then
    tail -n 30 "$log" >&2
    rm -f "$log"
    echo "bench_build: building $* in $dir failed (the benchmarks need Google Benchmark and the project's" \
      "packages: bash scripts/setup.sh bench installs them)" >&2
    return 1
  fi
  rm -f "$log"
}
