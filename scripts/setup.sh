#!/usr/bin/env bash
# Installs what PolyFloe needs from Debian 12's archive. Idempotent: when everything is present it only checks
# (well under a second). Run as root, or as a user with sudo.
#
#   bash scripts/setup.sh          # build, test, run, plot
#   bash scripts/setup.sh fuzz     # the same plus clang, its libFuzzer/sanitizer runtimes and OpenMP
#                                  # (scripts/sanitize.sh, scripts/fuzz.sh)
#   bash scripts/setup.sh bench    # the same plus LAMMPS (the disk-pack anchor of scripts/bench_lammps.sh) and
#                                  # valgrind (scripts/count_instructions.sh)
#   bash scripts/setup.sh paraview # the same plus ParaView's pvbatch (postprocess/paraview/, scripts/pvbatch.sh):
#                                  # Debian's paraview and python3-paraview unpacked into .paraview/ in the
#                                  # repository (POLYFLOE_PARAVIEW_DIR to put it elsewhere), since python3-paraview
#                                  # conflicts with python3-vtk9, which libvtk9-dev needs; their libraries and xvfb
#                                  # are installed as packages
set -euo pipefail

PACKAGES=(
  g++ cmake ninja-build pkg-config git clang-format
  libeigen3-dev libccd-dev libvtk9-dev libhdf5-dev libyaml-cpp-dev libboost-dev
  libgtest-dev libbenchmark-dev
  libcli11-dev  # the command line (dem/app)
  nlohmann-json3-dev  # the study drivers' JSON (tests/bench)
  libopenmpi-dev openmpi-bin libtrilinos-zoltan-dev  # MPI domain decomposition (dem/domain; tests/mpi)
  python3-numpy python3-h5py python3-matplotlib python3-vtk9
  openfoam  # v1912: the of_cases (OpenFOAM flows that drive the ice; tests/validation/test_strait_openfoam.cpp)
  openfoam-examples  # its tutorials: users' kinds of case (of_cases/tutorials, test_openfoam_tutorials.cpp)
)
# Optional groups, named on the command line.
FUZZ_PACKAGES=(clang libclang-rt-dev libomp-dev)  # clang, its sanitizer and fuzzer runtimes, its OpenMP
BENCH_PACKAGES=(lammps valgrind)
# The shared libraries paraview 5.11 links to (its Depends, less the web server's Python modules), a software
# OpenGL driver and a virtual display for headless rendering.
PARAVIEW_PACKAGES=(
  libavcodec59 libavformat59 libavutil57 libswscale6 libdouble-conversion3 libexpat1 libfreetype6 libgdal32
  libgl2ps1.4 libglew2.2 libglx0 libopengl0 libgl1-mesa-dri libhdf5-openmpi-103-1 libjpeg62-turbo liblz4-1 liblzma5
  libnetcdf19 libogg0 libtheora0 libopenmpi3 libpng16-16 libpython3.11 libqt5core5a libqt5gui5 libqt5help5
  libqt5network5 libqt5opengl5 libqt5widgets5 libtiff6 libx11-6 libxcursor1 libxml2 zlib1g
  xvfb
)
PARAVIEW_DEBS=(paraview python3-paraview)

want_paraview=0
for group in "$@"; do
  case "$group" in
    fuzz) PACKAGES+=("${FUZZ_PACKAGES[@]}") ;;
    bench) PACKAGES+=("${BENCH_PACKAGES[@]}") ;;
    paraview) PACKAGES+=("${PARAVIEW_PACKAGES[@]}"); want_paraview=1 ;;
    *) echo "setup: unknown group '$group' (known: fuzz, bench, paraview)" >&2; exit 2 ;;
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

# ParaView: the two packages unpacked (dpkg-deb -x) into a folder of their own, never installed. Idempotent: a
# stamp naming the unpacked version; a new candidate version is unpacked afresh.
if [ "$want_paraview" = 1 ]; then
  repo=$(cd "$(dirname "$0")/.." && pwd)
  pv_dir=${POLYFLOE_PARAVIEW_DIR:-$repo/.paraview}
  version=$(apt-cache policy paraview | awk '/Candidate:/ {print $2}')
  if [ -z "$version" ] || [ "$version" = "(none)" ]; then
    SUDO=""
    if [ "$(id -u)" -ne 0 ]; then SUDO="sudo"; fi
    $SUDO apt-get update -qq
    version=$(apt-cache policy paraview | awk '/Candidate:/ {print $2}')
  fi
  if [ -x "$pv_dir/root/usr/bin/pvbatch" ] && [ "$(cat "$pv_dir/version" 2>/dev/null)" = "$version" ]; then
    echo "setup: ParaView $version present in $pv_dir"
  else
    echo "setup: unpacking ParaView $version into $pv_dir"
    mkdir -p "$pv_dir"
    work=$(mktemp -d "$pv_dir/.unpack.XXXXXX")
    trap 'rm -rf "$work"' EXIT
    # apt-get download as root drops to the _apt user, which may not write here: download as ourselves.
    (cd "$work" && apt-get download -qq -o APT::Sandbox::User="$(id -un)" "${PARAVIEW_DEBS[@]}")
    for deb in "$work"/*.deb; do dpkg-deb -x "$deb" "$work/root"; done
    rm -f "$work"/*.deb
    "$work/root/usr/bin/pvbatch" --version >/dev/null  # the libraries are all there
    rm -rf "$pv_dir/root"
    mv "$work/root" "$pv_dir/root"
    echo "$version" >"$pv_dir/version"
    echo "setup: ParaView $version in $pv_dir (pvbatch: bash scripts/pvbatch.sh SCRIPT.py)"
  fi
fi

# Matplotlib builds its font cache on its first import. The tests run plot scripts side by side, and two first
# imports at once on a fresh machine race for the cache's lock (the loser gives up after 5 s): build it here, once.
/usr/bin/python3 -c "import matplotlib; matplotlib.use('Agg'); import matplotlib.pyplot" || true
