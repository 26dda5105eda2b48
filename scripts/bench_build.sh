# Sourced by the benchmark scripts (run_benchmarks.sh, speed_acceptance.sh, bench_lammps.sh,
# count_instructions.sh), from the repository root:
#
#   bench_build DIR TARGET...
#
# configures DIR as a Release build with the tests and benchmarks where it is not one yet (with Ninja where DIR is
# new and ninja is installed; an existing DIR keeps its generator; a configured one is left to cmake --build, which
# reconfigures when the CMake files change), then builds the targets on every core. A failed configuration or build
# prints the end of its output, says what the benchmarks need and returns non-zero.
bench_build() {
  local dir="$1"
  shift
  local generator=() configure=() log
  if [[ ! -f "$dir/CMakeCache.txt" ]] && command -v ninja >/dev/null; then generator=(-G Ninja); fi
  if ! grep -qx 'CMAKE_BUILD_TYPE:STRING=Release' "$dir/CMakeCache.txt" 2>/dev/null ||
     ! grep -qx 'BUILD_TESTING:BOOL=ON' "$dir/CMakeCache.txt"; then
    configure=(cmake -S . -B "$dir" "${generator[@]}" -DCMAKE_BUILD_TYPE=Release -DBUILD_TESTING=ON)
    echo "+ ${configure[*]}"
  fi
  log=$(mktemp)
  echo "+ cmake --build $dir --target $* -j $(nproc)"
  if ! { { [[ ${#configure[@]} -eq 0 ]] || "${configure[@]}"; } &&
         cmake --build "$dir" --target "$@" -j "$(nproc)"; } >"$log" 2>&1; then
    tail -n 30 "$log" >&2
    rm -f "$log"
    echo "bench_build: building $* in $dir failed (the benchmarks need Google Benchmark and the project's" \
      "packages: bash scripts/setup.sh bench installs them)" >&2
    return 1
  fi
  rm -f "$log"
}
