# Shared by the of_cases Allrun scripts (source it): the OpenFOAM environment, running a tool with a log, the
# mesh option. Debian 12's OpenFOAM v1912 (package openfoam, installed by scripts/setup.sh) puts its binaries in
# /usr/bin and needs only these two variables; its bashrc is not sourced (it trips `set -u`).
export WM_PROJECT_DIR="${WM_PROJECT_DIR:-/usr/share/openfoam}"
export FOAM_ETC="${FOAM_ETC:-/usr/share/openfoam/etc}"
export FOAM_SIGFPE=1  # stop on a floating-point exception instead of writing NaN fields
# The PolyFloe checkout (postprocess/, scripts/, build/); a test that runs a copy of a case sets it.
POLYFLOE_ROOT="${POLYFLOE_ROOT:-$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)}"

of_require() {
  if ! command -v blockMesh >/dev/null 2>&1 || [ ! -d "$FOAM_ETC" ]; then
    echo "$(basename "$PWD"): OpenFOAM is not installed; run \`bash scripts/setup.sh\` (Debian package openfoam)" >&2
    exit 1
  fi
}

# of_run TOOL [ARGS...]: runs an OpenFOAM tool in the case folder, its output in log.TOOL. OpenFOAM tools can exit
# 0 after a fatal error, so the log is checked too.
of_run() {
  local tool="$1" log="log.$1"
  shift
  echo "  $tool $*"
  if ! "$tool" "$@" >"$log" 2>&1 || grep -q "FOAM FATAL" "$log"; then
    echo "$(basename "$PWD"): $tool failed; the end of $PWD/$log:" >&2
    tail -n 25 "$log" >&2
    exit 1
  fi
}

# of_mesh_option ARGS...: sets MESH to ci (default) or fine from --fine / --ci or the MESH variable.
of_mesh_option() {
  MESH="${MESH:-ci}"
  for arg in "$@"; do
    case "$arg" in
      --fine) MESH=fine ;;
      --ci) MESH=ci ;;
      *) echo "usage: $0 [--ci | --fine]   (or MESH=ci|fine)" >&2; exit 2 ;;
    esac
  done
  case "$MESH" in ci | fine) ;; *) echo "$0: MESH must be ci or fine, not '$MESH'" >&2; exit 2 ;; esac
}

# of_clean: removes what Allrun made (meshes, solutions other than 0/, logs, the field file and ice results).
of_clean() {
  rm -rf constant/polyMesh system/meshSize log.* processor* postProcessing VTK ./*.foam field.h5 field.pvd field ice
  local d
  for d in [0-9]*; do
    [ "$d" != "0" ] && [ -d "$d" ] && rm -rf "$d"
  done
  return 0
}

# polyfloe_binary: the polyfloe program of this checkout (POLYFLOE_BUILD_DIR, default build/), built if missing.
polyfloe_binary() {
  local root="$POLYFLOE_ROOT" build
  build="${POLYFLOE_BUILD_DIR:-$root/build}"
  case "$build" in /*) ;; *) build="$root/$build" ;; esac
  if [ ! -x "$build/polyfloe" ] || [ ! -x "$build/polyfloe-field" ]; then
    echo "  building polyfloe (scripts/build.sh)" >&2
    POLYFLOE_BUILD_DIR="$build" bash "$root/scripts/build.sh" >&2
  fi
  echo "$build/polyfloe"
}

# of_mesh: a clean case with the $MESH mesh (system/meshSize.$MESH -> system/meshSize; blockMesh, checkMesh).
of_mesh() {
  of_clean
  cp "system/meshSize.$MESH" system/meshSize
  of_run blockMesh
  of_run checkMesh
}
