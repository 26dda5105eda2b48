#!/usr/bin/env bash
# Installs what PolyFloe needs from Debian 12's archive. Idempotent: when everything is present it only checks
# (well under a second). Run as root, or as a user with sudo.
#
#   bash scripts/setup.sh          # build, test, run, plot
#   bash scripts/setup.sh fuzz     # the same plus clang and its libFuzzer/sanitizer runtimes (scripts/fuzz.sh)
#   bash scripts/setup.sh bench    # the same plus LAMMPS (the disk-pack anchor of scripts/bench_lammps.sh) and
#                                  # valgrind (scripts/count_instructions.sh)
set -euo pipefail

PACKAGES=(
  g++ cmake ninja-build pkg-config git
  libeigen3-dev libccd-dev libvtk9-dev libhdf5-dev libyaml-cpp-dev libboost-dev
  libgtest-dev libbenchmark-dev
  python3-numpy python3-h5py python3-matplotlib python3-vtk9
  openfoam  # v1912: the of_cases (OpenFOAM flows that drive the ice; tests/validation/test_strait_openfoam.cpp)
  openfoam-examples  # its tutorials: users' kinds of case (of_cases/tutorials, test_openfoam_tutorials.cpp)
)
# Optional groups, named on the command line.
FUZZ_PACKAGES=(clang libclang-rt-dev)
BENCH_PACKAGES=(lammps valgrind)

for group in "$@"; do
  case "$group" in
    fuzz) PACKAGES+=("${FUZZ_PACKAGES[@]}") ;;
    bench) PACKAGES+=("${BENCH_PACKAGES[@]}") ;;
    *) echo "setup: unknown group '$group' (known: fuzz, bench)" >&2; exit 2 ;;
  esac
done

missing=()
for p in "${PACKAGES[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$p")
  fi
done

if [ ${#missing[@]} -eq 0 ]; then
  echo "setup: all ${#PACKAGES[@]} packages present"
else
  SUDO=""
  if [ "$(id -u)" -ne 0 ]; then SUDO="sudo"; fi
  echo "setup: installing ${missing[*]}"
  export DEBIAN_FRONTEND=noninteractive
  $SUDO apt-get update -qq
  $SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
  echo "setup: done"
fi
# Matplotlib builds its font cache on its first import. The tests run plot scripts side by side, and two first
# imports at once on a fresh machine race for the cache's lock (the loser gives up after 5 s): build it here, once.
/usr/bin/python3 -c "import matplotlib; matplotlib.use('Agg'); import matplotlib.pyplot" || true
