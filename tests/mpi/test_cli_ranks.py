#!/usr/bin/python3
"""`polyfloe run` under mpirun, through the command line only: every output bitwise that of one process.

    /usr/bin/python3 tests/mpi/test_cli_ranks.py --build BUILD [--work DIR] [--quick]

1. The channel (walls, a strait, the velocity grid and checkpoints), a floe field drifting in a vortex current, a
   pack driven against a wall, two floes colliding (ranks with no floe) and a frozen sheet crushed until most of
   its bonds break, each run in one process (no mpirun, 1 thread) and then under mpirun at 1, 2, 3
   and 4 ranks x 1 and 2 threads: every file of the output folder (results.h5 dataset by dataset and bit for bit,
   every VTK frame and series, the checkpoints, results.xmf, the resolved scene) the same, and the first line
   naming the ranks and threads.
2. The channel and the breaking sheet on 2 ranks killed (SIGKILL to every rank, as a lost node) after their second
   checkpoint, restarted on 3 ranks, killed again, and finished in one process without mpirun: bitwise the
   uninterrupted run (the folder's manifest aside, which lists the restart's own temporary file).
3. A floe field driven by an ocean field file (written here in the documented layout; every rank reads it) at 2-4
   ranks, bitwise one process's; the same field cut short so that the ice leaves it: exit 1 and one message from
   the rank that met it (which ends the job).
4. A run that becomes unstable (two floes at a step far too long) on 2 ranks: exit 3, the message once, its
   folder (checkpoints/unstable.h5 included) bitwise one process's. The guard's kinetic-energy limit is the whole
   ice's: a fast pair of floes that is one rank's share (tests/mpi/split_energy.yaml) runs on at 2 and 3 ranks as in
   one process; over the ice's limit, the same stop and message.
5. What does not run across ranks is refused with exit code 2, one message and no output folder: a spatial scene;
   and bad input is reported once: a bad output folder, a bad --set.
--quick (the sanitizer build's run): the channel and the breaking sheet at 3 ranks x 1 thread (and at 2 and 3 in
the restarts), the channel in pieces at 3 ranks (the restart in pieces is left to the full run), the field file at
2 ranks. Exit 0 when every check holds; each failure is printed. About 2 minutes on 2 cores.
"""
import argparse
import os
import re
import shutil
import subprocess
import sys
import tempfile
import time

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
sys.path.insert(0, os.path.join(ROOT, "scripts"))
import compare_outputs  # noqa: E402
import compare_vtk_content  # noqa: E402
sys.path.insert(0, os.path.join(ROOT, "tests", "support"))
from kill_run import killed_after  # noqa: E402

MPIRUN = ["mpirun", "--allow-run-as-root", "--oversubscribe", "-x", "OMP_WAIT_POLICY=passive"]
SCENES = {  # name: (scene, the --set options that keep it to a few seconds)
    "channel": ("channel", ["run.duration=3", "output.interval=1", "output.checkpoint.every=1"]),
    "drift_vortex": ("drift_vortex", ["run.duration=6", "output.interval=2"]),
    "pack_ice_sheet": ("pack_ice_sheet", ["run.duration=3", "output.interval=1"]),
    "two_floes": ("two_floes", ["run.duration=1.5"]),  # two floes: at 3 and 4 ranks, ranks with no floe
    # a 60 m frozen sheet (about 180 bonded elements, 253 faces) crushed by plates closing at 4 m/s: 230 faces break
    "breaking_sheet": ("uniaxial_compression", [
        "run.duration=0.4", "output.interval=0.02", "ice_sheet.region=[0,0,60,60]", "floes.0.rectangle.height=80",
        "floes.1.rectangle.height=80", "floes.0.position=[-10,30]", "floes.1.position=[70,30]",
        "floes.0.velocity=[2,0]", "floes.1.velocity=[-2,0]", "ice_sheet.bonds.tensile_strength=0.2e6",
        "ice_sheet.bonds.shear_strength=0.2e6"]),
}
failures = []


def fail(what):
    failures.append(what)
    print("FAIL:", what, flush=True)


def command(polyfloe, scene, out, sets, ranks=0, threads=1, extra=()):
    path = scene if scene.endswith(".yaml") else os.path.join(ROOT, "dem", "scenes", scene + ".yaml")
    args = [polyfloe, "run", path, "-o", out, "--threads",
            str(threads)]
    for s in sets:
        args += ["--set", s]
    args += list(extra)
    return (MPIRUN + ["-np", str(ranks)] if ranks else []) + args


def run(args, env):
    return subprocess.run(args, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, env=env)


def differences(a, b, ignore=()):
    return [d for d in compare_outputs.compare(a, b) if not any(d.startswith(i + ":") for i in ignore)]


def matrix(polyfloe, work, env, quick):
    layouts = [(3, 1)] if quick else [(r, t) for r in (1, 2, 3, 4) for t in (1, 2)]
    for name, (scene, sets) in SCENES.items():
        if quick and name not in ("channel", "breaking_sheet"):
            continue
        ref = os.path.join(work, name + "_one")
        r = run(command(polyfloe, scene, ref, sets), env)
        if r.returncode != 0:
            fail(f"{name}: one process: exit {r.returncode}: {r.stderr[-2000:]}")
            continue
        if name == "breaking_sheet":  # the case is about bonds breaking across the cuts: most of them must
            import h5py
            with h5py.File(os.path.join(ref, "results.h5"), "r") as f:
                intact = f["bonds/intact_faces"][()]
            if not intact[-1] < 0.25 * intact[0]:
                fail(f"breaking_sheet: the sheet did not break ({intact[0]} -> {intact[-1]} intact faces)")
        for ranks, threads in layouts:
            out = os.path.join(work, f"{name}_{ranks}x{threads}")
            t0 = time.monotonic()
            r = run(command(polyfloe, scene, out, sets, ranks, threads), env)
            where = f"{name}: {ranks} ranks x {threads} threads"
            if r.returncode != 0:
                fail(f"{where}: exit {r.returncode}: {r.stderr[-2000:]}")
                continue
            rank_word = "rank" if ranks == 1 else "ranks"
            named = f"{ranks} MPI {rank_word} x {threads} thread{'s' if threads > 1 else ''} each"
            if named not in r.stderr.splitlines()[0]:
                fail(f"{where}: the first line does not name '{named}': {r.stderr.splitlines()[0]}")
            d = differences(ref, out)
            if d:
                fail(f"{where}: differs from one process: " + "; ".join(d[:5]))
            print(f"{where}: {'same' if not d else 'DIFFERENT'} ({time.monotonic() - t0:.1f} s)", flush=True)
            shutil.rmtree(out)


VTK_SERIES = ("floes", "contacts", "bonds")


def vtk_file(difference):
    """Whether a difference compare_outputs reports is about a VTK series (its .pvd or its frames)."""
    path = difference.split(":", 1)[0]
    return any(path == s + ".pvd" or path.startswith(s + "/") for s in VTK_SERIES)


def pieces_check(folder, ranks=None):
    """Problems with a folder written in pieces: a frame whose .pvtp does not list `ranks` pieces (where given), or
    a piece file on disk that no .pvtp lists (left over)."""
    problems = []
    for series in VTK_SERIES:
        d = os.path.join(folder, series)
        if not os.path.isdir(d):
            continue
        listed = set()
        for name in sorted(os.listdir(d)):
            if name.endswith(".pvtp"):
                with open(os.path.join(d, name)) as f:
                    sources = re.findall(r'<Piece Source="([^"]*)"', f.read())
                frame = int(name[len(series) + 1:-len(".pvtp")])
                if ranks is not None and len(sources) != ranks:
                    problems.append(f"{series}/{name} (frame {frame}) lists {len(sources)} pieces, not {ranks}")
                listed.update(sources)
        stray = [n for n in os.listdir(d) if n.endswith(".vtp") and n not in listed]
        if stray:
            problems.append(f"{series}/: pieces no .pvtp lists: {sorted(stray)[:3]}")
    return problems


def pieces(polyfloe, work, env, quick):
    """output.vtk_pieces: one piece per rank, by content the frames of the gathered one-process run."""
    layouts = [(3, 1)] if quick else [(0, 1), (1, 1), (2, 1), (3, 2), (4, 1)]
    for name in ("channel",) if quick else ("channel", "breaking_sheet"):
        scene, sets = SCENES[name]
        ref = os.path.join(work, name + "_one")  # (the matrix's)
        for ranks, threads in layouts:
            out = os.path.join(work, f"{name}_pieces_{ranks}x{threads}")
            where = f"{name} in pieces: " + (f"{ranks} ranks x {threads} threads" if ranks else "one process")
            r = run(command(polyfloe, scene, out, sets + ["output.vtk_pieces=true"], ranks, threads), env)
            if r.returncode != 0:
                fail(f"{where}: exit {r.returncode}: {r.stderr[-2000:]}")
                continue
            d = compare_vtk_content.compare(ref, out) + pieces_check(out, max(ranks, 1))
            # (every other file bitwise, results.h5 and the checkpoints dataset by dataset: only the scene's text,
            # which holds the --set, and the manifest, which lists the pieces, may differ)
            d += [x for x in differences(ref, out, ignore=("scene.resolved.yaml", ".polyfloe-manifest"))
                  if not vtk_file(x) and not x.endswith(("attribute //overrides: differs",
                                                         "attribute //scene_resolved: differs"))]
            if d:
                fail(f"{where}: " + "; ".join(d[:5]))
            print(f"{where}: {'same content' if not d else 'DIFFERENT'}", flush=True)
            shutil.rmtree(out)


def restart_across_rank_counts(polyfloe, work, env, name, extra_sets):
    scene, sets = SCENES[name][0], SCENES[name][1] + extra_sets
    in_pieces = "output.vtk_pieces=true" in extra_sets
    name_dir = name + ("_pieces" if in_pieces else "")
    ref = os.path.join(work, name_dir + "_restart_ref")
    r = run(command(polyfloe, scene, ref, sets), env)
    if r.returncode != 0:
        return fail(f"restart of {name_dir}: the uninterrupted run: exit {r.returncode}: {r.stderr[-2000:]}")
    out = os.path.join(work, name_dir + "_restart")
    if not killed_after(command(polyfloe, scene, out, sets, 2), env, out, 2):
        return fail(f"restart of {name_dir}: the 2-rank run ended before it could be killed")
    if not killed_after(command(polyfloe, scene, out, sets, 3, extra=["--restart", out]), env, out, 1):
        return fail(f"restart of {name_dir}: the 3-rank restart ended before it could be killed")
    r = run(command(polyfloe, scene, out, sets, extra=["--restart", out]), env)
    if r.returncode != 0 or "restarting from" not in r.stderr:
        return fail(f"restart of {name_dir}: one process from the 3-rank checkpoint: exit {r.returncode}: {r.stderr[-2000:]}")
    d = differences(ref, out, ignore=(".polyfloe-manifest",))
    if in_pieces:  # frames cut into 1, 2 or 3 pieces: their content compared
        d = [x for x in d if not vtk_file(x)] + compare_vtk_content.compare(ref, out)
        d += pieces_check(out)
    if d:
        fail(f"restart of {name_dir}: 2 ranks, killed, 3 ranks, killed, one process: differs from the uninterrupted "
             "run: " + "; ".join(d[:5]))
    else:
        print(f"restart of {name_dir}: 2 ranks -> SIGKILL -> 3 ranks -> SIGKILL -> one process: same as uninterrupted",
              flush=True)


FIELD_SCENE = """name: field_drift
run: {duration: DURATION}
output: {interval: 1}
forcing:
  ocean:
    field: {type: file, path: ocean.h5}
  air:
    drag: {enabled: false}
floe_field:
  region: [0, 0, 300, 300]
  concentration: 0.4
  size: {min: 5, max: 40, exponent: 2.0}
  seed: 3
"""


def write_field(path, x1):
    """An ocean field file (the layout of docs/scene-reference.md) over [-50, x1] x [-50, 350] m: a current of
    1.5 m/s along +x sheared across y and meandering in x, steady, one level."""
    import h5py
    import numpy as np
    x, y = np.linspace(-50.0, x1, 41), np.linspace(-50.0, 350.0, 41)
    X, Y = np.meshgrid(x, y)
    U = np.zeros((1, 1, len(y), len(x), 3))
    U[0, 0, :, :, 0] = 1.5 + 0.002 * (Y - 150.0)
    U[0, 0, :, :, 1] = 0.3 * np.sin(X / 60.0)
    with h5py.File(path, "w") as f:
        f.attrs["format"] = "polyfloe-ocean-field"
        f.attrs["format_version"] = 1
        f.attrs["source"] = "tests/mpi/test_cli_ranks.py"
        f.attrs["created_by"] = "tests/mpi/test_cli_ranks.py"
        f["x"], f["y"], f["z"], f["t"] = x, y, np.array([0.0]), np.array([0.0])
        f["U"] = U
        f["mask"] = np.ones((1, len(y), len(x)), dtype=np.uint8)


def field_file_runs(polyfloe, work, env, quick):
    """A floe field driven by an ocean field file (every rank reads it): bitwise one process's; and a field too
    small for the run, which the ice leaves: exit 1 from the rank that met it, its message once."""
    folder = os.path.join(work, "field_scene")
    os.makedirs(folder, exist_ok=True)
    write_field(os.path.join(folder, "ocean.h5"), 650.0)
    scene = os.path.join(folder, "field_drift.yaml")
    with open(scene, "w") as f:
        f.write(FIELD_SCENE.replace("DURATION", "4"))
    ref, args = os.path.join(work, "field_one"), [polyfloe, "run", scene, "--threads", "1", "-o"]
    r = run(args + [ref], env)
    if r.returncode != 0:
        return fail(f"field file: one process: exit {r.returncode}: {r.stderr[-2000:]}")
    for ranks in (2,) if quick else (2, 3, 4):
        out = os.path.join(work, f"field_{ranks}")
        r = run(MPIRUN + ["-np", str(ranks)] + args + [out], env)
        if r.returncode != 0:
            fail(f"field file on {ranks} ranks: exit {r.returncode}: {r.stderr[-2000:]}")
            continue
        d = differences(ref, out)
        if d:
            fail(f"field file on {ranks} ranks: differs from one process: " + "; ".join(d[:5]))
        print(f"field file: {ranks} ranks: {'same' if not d else 'DIFFERENT'}", flush=True)
    # The ice leaves a field that ends at x = 301 m: the rank that owns the first floe to leave reports it.
    write_field(os.path.join(folder, "ocean.h5"), 301.0)
    with open(scene, "w") as f:
        f.write(FIELD_SCENE.replace("DURATION", "20"))
    r = run(MPIRUN + ["-np", "3"] + args + [os.path.join(work, "field_left")], env)
    if r.returncode != 1 or r.stderr.count("a forcing field does not cover the run") != 1:
        fail(f"a field the ice leaves, on 3 ranks: exit {r.returncode} (not 1) or not one message: "
             f"{r.stderr[-2000:]}")
    else:
        print("field file: the ice leaving it on 3 ranks: exit 1, one message", flush=True)
    # A wind field file that ends at x = 150 m: the floes beyond it meet its end at t = 0, in the forces every rank
    # evaluates before its first step; the ranks that own them report it and end the job (none waits for the rest).
    write_field(os.path.join(folder, "wind.h5"), 150.0)
    with open(scene, "w") as f:
        f.write(FIELD_SCENE.replace("DURATION", "4").replace(
            "    drag: {enabled: false}", "    field: {type: file, path: wind.h5}"))
    one = run(args + [os.path.join(work, "wind_short_one")], env)
    try:
        r = subprocess.run(MPIRUN + ["-np", "2"] + args + [os.path.join(work, "wind_short")], stdout=subprocess.PIPE,
                           stderr=subprocess.PIPE, text=True, env=env, timeout=120)
    except subprocess.TimeoutExpired:
        return fail("a wind field short of the ice at t = 0, on 2 ranks: still running after 120 s (a rank waits)")
    # The message names the wind file, and not the ocean (which covers the ice).
    said = [p.stderr for p in (one, r)]
    if one.returncode != 1 or r.returncode != 1 or any(
            "a forcing field does not cover the run" not in s or "wind.h5: no water" not in s or "ocean.h5" in s
            for s in said):
        fail(f"a wind field short of the ice at t = 0: exit {r.returncode} on 2 ranks, {one.returncode} in one "
             f"process (both should be 1, naming the wind file, not the ocean): {said[0][-800:]} / {said[1][-800:]}")
    else:
        print("field file: a wind field short of the ice at t = 0 on 2 ranks: exit 1, as one process", flush=True)


def unstable(polyfloe, work, env):
    """Two floes at a step far too long: the ranks agree that the run became unstable; exit 3, the message once,
    and the folder (frames, checkpoints, the state in checkpoints/unstable.h5) bitwise one process's."""
    sets = ["run.dt=0.02"]
    ref, out = os.path.join(work, "unstable_one"), os.path.join(work, "unstable_2")
    one = run(command(polyfloe, "two_floes", ref, sets), env)
    r = run(command(polyfloe, "two_floes", out, sets, 2), env)
    if one.returncode != 3 or r.returncode != 3 or r.stderr.count("the run became unstable") != 1:
        return fail(f"an unstable run on 2 ranks: exit {r.returncode} (one process: {one.returncode}), not 3 with "
                    f"one message: {r.stderr[-1500:]}")
    d = differences(ref, out)
    if d or not os.path.exists(os.path.join(out, "checkpoints", "unstable.h5")):
        return fail("an unstable run on 2 ranks: its folder differs from one process's: " + "; ".join(d[:5]))
    print("unstable on 2 ranks: exit 3, one message, the folder (unstable.h5 included) as one process's", flush=True)


def guard_weighs_the_ice(polyfloe, work, env):
    """The run guard's kinetic-energy limit is the whole ice's on any number of ranks: a fast pair of floes that
    is a rank's whole share, over its share's limit but not the ice's, runs on as in one process (bitwise); over
    the ice's limit it stops the run as one process does, with the same message."""
    scene = os.path.join(ROOT, "tests", "mpi", "split_energy.yaml")
    ref = os.path.join(work, "split_energy_one")
    one = run(command(polyfloe, scene, ref, []), env)
    if one.returncode != 0:
        return fail(f"split energy in one process: exit {one.returncode}: {one.stderr[-1500:]}")
    for ranks in (2, 3):
        out = os.path.join(work, f"split_energy_{ranks}")
        r = run(command(polyfloe, scene, out, [], ranks), env)
        d = differences(ref, out) if r.returncode == 0 else []
        if r.returncode != 0 or d:
            fail(f"split energy on {ranks} ranks (72 % of the ice's limit): exit {r.returncode}, not one process's "
                 f"0: {'; '.join(d[:5]) or r.stderr[-1500:]}")
        shutil.rmtree(out)
    fast = ["floes.2.velocity=[16,0]", "floes.3.velocity=[16,0]"]  # 128 % of the ice's limit
    one = run(command(polyfloe, scene, ref + "_fast", fast), env)
    r = run(command(polyfloe, scene, os.path.join(work, "split_energy_fast_2"), fast, 2), env)
    said = [re.findall(r"the kinetic energy of the ice.*runaway energy", x.stderr) for x in (one, r)]
    if one.returncode != 3 or r.returncode != 3 or not said[0] or said[0] != said[1]:
        return fail(f"split energy over the ice's limit: exit {r.returncode} on 2 ranks, {one.returncode} in one "
                    f"process (both should be 3, with one message): {said}")
    print("the guard weighs the ice: a fast rank's share runs on as in one process; over the ice's limit, the same "
          "stop and message", flush=True)


def refusals(polyfloe, work, env):
    cases = [
        ("cube_plate", [], [], "spatial scene"),
        ("channel", ["run.duration=-1"], [], "run.duration"),
    ]
    for scene, sets, extra, words in cases:
        out = os.path.join(work, "refused_" + scene)
        r = run(command(polyfloe, scene, out, sets, 2, extra=extra), env)
        where = f"refusal of {scene} {' '.join(sets)} on 2 ranks"
        if r.returncode != 2:
            fail(f"{where}: exit {r.returncode}, not 2: {r.stderr[-1000:]}")
        if r.stderr.count("polyfloe: error:") != 1 or words not in r.stderr:
            fail(f"{where}: not one message naming '{words}': {r.stderr[-1000:]}")
        if os.path.exists(out):
            fail(f"{where}: the output folder {out} was created")
    r = run(command(polyfloe, "channel", "/proc/polyfloe", SCENES["channel"][1], 3), env)
    if r.returncode != 2 or r.stderr.count("polyfloe: error:") != 1:
        fail(f"an output folder in /proc on 3 ranks: exit {r.returncode}, not 2 with one message: {r.stderr[-1000:]}")
    print("refusals: exit 2, one message, no output", flush=True)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--build", required=True, help="the build folder (holds polyfloe)")
    ap.add_argument("--work", help="where the runs go (default: a temporary folder, removed)")
    ap.add_argument("--quick", action="store_true", help="the channel on two layouts only")
    a = ap.parse_args()
    polyfloe = os.path.join(os.path.abspath(a.build), "polyfloe")
    env = dict(os.environ, OMP_WAIT_POLICY="passive")
    env.pop("OMP_NUM_THREADS", None)
    work = a.work or tempfile.mkdtemp(prefix="polyfloe-mpi-cli-")
    os.makedirs(work, exist_ok=True)
    try:
        matrix(polyfloe, work, env, a.quick)
        restart_across_rank_counts(polyfloe, work, env, "channel", ["run.duration=5"])
        restart_across_rank_counts(polyfloe, work, env, "breaking_sheet", ["output.checkpoint.every=2"])
        pieces(polyfloe, work, env, a.quick)
        if not a.quick:
            restart_across_rank_counts(polyfloe, work, env, "breaking_sheet",
                                       ["output.checkpoint.every=2", "output.vtk_pieces=true"])
        field_file_runs(polyfloe, work, env, a.quick)
        unstable(polyfloe, work, env)
        guard_weighs_the_ice(polyfloe, work, env)
        refusals(polyfloe, work, env)
    finally:
        if not a.work:
            shutil.rmtree(work, ignore_errors=True)
    print(f"{len(failures)} failures" if failures else "all checks hold")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
