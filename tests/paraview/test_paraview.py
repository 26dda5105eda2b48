#!/usr/bin/python3
"""ParaView as the client, end to end: small runs of the channel scene (twice, into two folders: once in one
process, once on 2 MPI ranks with its VTK frames in per-rank pieces) and of the frozen sheet's uniaxial
compression, each picture script of postprocess/paraview/ rendered by ParaView's own pvbatch (scripts/pvbatch.sh, on
a virtual display), each picture checked by its pixels (not blank: coloured floes, arrows, cracks), each state file
loaded by pvbatch against the other folder (the pieces) and checked to draw the same picture, the first frame's
arrays as ParaView reads them, frame times on the interval's multiples, and an animation. results.xmf of the
channel, of the compression and of a channel run on 2 ranks killed after its second checkpoint and restarted on 3:
opened by OpenDataFile (the GUI's choice) and by each XDMF reader by name (Xdmf3ReaderS, Xdmf3ReaderT,
XDMFReader), each in a pvbatch of its own, every frame's time, cell count and one floe's first vertex and velocity
equal to results.h5's.

    /usr/bin/python3 tests/paraview/test_paraview.py --build build [--keep]

Needs ParaView (bash scripts/setup.sh paraview). The ice-over-field picture is checked with the OpenFOAM strait
(of_cases/strait/Allrun; tests/validation/test_strait_openfoam.cpp).
"""
import argparse
import json
import os
import re
import shutil
import subprocess
import sys
import tempfile

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
PVBATCH = os.path.join(ROOT, "scripts", "pvbatch.sh")
PICTURES = os.path.join(ROOT, "postprocess", "paraview")
CHECK = os.path.join(ROOT, "tests", "paraview", "check_image.py")
sys.path.insert(0, os.path.join(ROOT, "tests", "support"))
from kill_run import killed_after  # noqa: E402
from virtual_display import shared_display  # noqa: E402
failures = []


def run(cmd, what):
    p = subprocess.run(cmd, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True, cwd=ROOT)
    if p.returncode != 0:
        print(p.stdout)
        sys.exit(f"test_paraview: {what} failed (exit {p.returncode}): {' '.join(cmd)}")
    return p.stdout


def check(condition, message):
    print(("ok      " if condition else "FAILED  ") + message)
    if not condition:
        failures.append(message)


def image(png, *args):
    p = subprocess.run(["/usr/bin/python3", CHECK, png, *args], stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                       text=True)
    print(p.stdout.rstrip())
    check(p.returncode == 0, f"{os.path.basename(png)} {' '.join(args)}")


def check_xdmf(folder):
    """Opens FOLDER/results.xmf with OpenDataFile and with each XDMF reader by name, in a pvbatch of its own each:
    every frame's time and cell count, and one dynamic floe's first vertex and velocity, equal to results.h5's."""
    import h5py
    import numpy as np
    with h5py.File(f"{folder}/results.h5", "r") as f:
        times = f["time"][()].tolist()
        ids = f["floes/id"][()]
        dynamic = np.flatnonzero(f["floes/motion"][()] == 0)
        k = int(dynamic[len(dynamic) // 2])  # a floe in the middle of the dynamic ones, in id order
        first = int(f["floes/polygon_offsets"][k])
        xy = f["state/vertices_xy"][:, first, :].astype(np.float64)
        velocity = f["state/velocity"][:, k, :]
    body = int(ids[k])
    name = os.path.basename(folder)
    for reader in ("open", "Xdmf3ReaderS", "Xdmf3ReaderT", "XDMFReader"):
        p = subprocess.run(["bash", PVBATCH, os.path.join(ROOT, "tests", "paraview", "xdmf_frames.py"),
                            f"{folder}/results.xmf", reader, str(body)], stdout=subprocess.PIPE,
                           stderr=subprocess.STDOUT, text=True, cwd=ROOT)
        lines = [line for line in p.stdout.splitlines() if line.startswith("{")]
        what = f"{name}/results.xmf with {reader}"
        if p.returncode != 0 or not lines:
            print(p.stdout[-3000:])
            check(False, f"{what}: pvbatch exit {p.returncode}")
            continue
        got = json.loads(lines[-1])
        frames = got["frames"]
        check([fr["time"] for fr in frames] == times, f"{what} ({got['reader']}): frame times {len(frames)} = "
              f"results.h5's {len(times)}")
        check(all(fr["cells"] == len(ids) for fr in frames), f"{what}: {len(ids)} polygons at every frame")
        check({"velocity", "angular_velocity", "id", "thickness", "motion"} <= set(got["arrays"]),
              f"{what}: cell arrays {got['arrays']}")
        same = len(frames) == len(times) and all(
            fr["point"] is not None and fr["velocity"] is not None and fr["point"][:2] == xy[t].tolist() and
            fr["velocity"] == velocity[t].tolist() for t, fr in enumerate(frames))
        check(same and np.any(velocity[-1] != 0.0), f"{what}: floe {body}'s first vertex and velocity equal "
              f"results.h5's at every frame (last: {frames[-1]['point'][:2] if frames and frames[-1]['point'] else None}"
              f" vs {xy[-1].tolist()}, {frames[-1]['velocity'] if frames else None} vs {velocity[-1].tolist()})")


def pvbatch(script, *args):
    return run(["bash", PVBATCH, os.path.join(PICTURES, script), *args], script)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--build", default=os.path.join(ROOT, "build"))
    ap.add_argument("--keep", action="store_true", help="keep the runs and pictures (printed)")
    a = ap.parse_args()
    polyfloe = os.path.join(a.build, "polyfloe")
    work = tempfile.mkdtemp(prefix="polyfloe_paraview_")
    try:
        channel = ["run", "dem/scenes/channel.yaml", "--set", "run.duration=20", "--set", "output.interval=2.5",
                   "--threads", "1"]
        run([polyfloe, *channel, "-o", f"{work}/a"], "the channel run")
        # Again on 2 MPI ranks, its VTK frames in pieces (a .pvtp per frame listing each rank's piece): ParaView
        # reads them as the single files of the first run.
        run(["mpirun", "--allow-run-as-root", "--oversubscribe", "-x", "OMP_WAIT_POLICY=passive", "-np", "2",
             polyfloe, *channel, "--set", "output.vtk_pieces=true", "-o", f"{work}/b"],
            "the channel run again, on 2 ranks in pieces")
        check(os.path.isfile(f"{work}/b/floes/floes_000001_1.vtp") and 'floes/floes_000001.pvtp"' in
              open(f"{work}/b/floes.pvd").read(), "the 2-rank run's floes.pvd lists .pvtp frames of 2 pieces")
        run([polyfloe, "run", "dem/scenes/uniaxial_compression.yaml", "--set", "run.duration=1.1", "--set",
             "output.interval=0.1", "-o", f"{work}/sheet"], "the uniaxial compression run")
        # On 2 ranks, killed (SIGKILL to every rank) after its second checkpoint, restarted on 3 ranks.
        mpi = ["mpirun", "--allow-run-as-root", "--oversubscribe", "-x", "OMP_WAIT_POLICY=passive", "-np"]
        restarted = [polyfloe, *channel, "--set", "run.duration=10", "--set", "output.checkpoint.every=1", "-o",
                     f"{work}/restarted"]
        check(killed_after(mpi + ["2"] + restarted, None, f"{work}/restarted", 2, cwd=ROOT),
              "the 2-rank channel run was killed after its second checkpoint")
        run(mpi + ["3"] + restarted + ["--restart", f"{work}/restarted"], "the restart on 3 ranks")

        # Frame times: the interval's multiples, exactly.
        pvd = open(f"{work}/a/floes.pvd").read()
        times = re.findall(r'timestep="([^"]+)"', pvd)
        check(times == ["0", "2.5", "5", "7.5", "10", "12.5", "15", "17.5", "20"], f"floes.pvd frame times {times}")

        # What ParaView offers at the first time step (the empty contacts frame included).
        seen = {}
        for line in run(["bash", PVBATCH, os.path.join(ROOT, "tests", "paraview", "first_frame.py"), f"{work}/a"],
                        "first_frame.py").splitlines():
            parts = line.split()
            if len(parts) == 4 and parts[2].startswith("POINTS:"):
                seen[parts[0]] = (float(parts[1]), set(parts[2][7:].split(",")) | set(parts[3][6:].split(",")))
        print("first frames:", seen)
        # (A frame without contacts offers no arrays: ParaView's data information skips empty datasets, whatever
        # arrays the file holds. The state files and scripts configure the glyphs and colours explicitly.)
        check("contacts" in seen, "contacts.pvd opens")
        check({"speed", "velocity", "id", "motion"} <= seen.get("floes", (0, set()))[1],
              "floes.pvd's first frame offers speed, velocity, id, motion")
        check({"speed", "ice_fraction", "velocity"} <= seen.get("velocity", (0, set()))[1],
              "velocity.pvd's first frame offers speed, ice_fraction, velocity")

        # results.xmf: every XDMF reader of ParaView, each in a process of its own, reads results.h5's frames.
        for folder in (f"{work}/a", f"{work}/sheet", f"{work}/restarted"):
            check_xdmf(folder)

        pics = f"{work}/pictures"
        out = pvbatch("channel.py", f"{work}/a", "-o", pics, "--animation")
        image(f"{pics}/channel.png", "--coloured", "0.05")
        frames = sorted(f for f in os.listdir(f"{pics}/channel_frames") if f.endswith(".png"))
        check(len(frames) == 9, f"channel animation: {len(frames)} PNG frames (9 expected)")
        image(f"{pics}/channel_frames/{frames[-1]}", "--coloured", "0.05", "--same-as", f"{pics}/channel.png")
        check(os.path.isfile(f"{pics}/channel.avi") or "no movie" in out, "channel animation: a movie, or why not")
        # At t = 0 the floes are at rest: the low end of the run's range (blue), not saturated by the frame's own.
        pvbatch("channel.py", f"{work}/a", "-o", pics, "-t", "0", "--name", "channel_t0")
        image(f"{pics}/channel_t0.png", "--coloured", "0.05", "--blue")
        pvbatch("contacts.py", f"{work}/a", "-o", pics)
        image(f"{pics}/contacts.png", "--coloured", "0.003")
        pvbatch("cracks.py", f"{work}/sheet", "-o", pics)
        image(f"{pics}/cracks.png", "--coloured", "0.003")

        # Each state file on a fresh results folder (the same scene run again elsewhere: the channel on 2 ranks, in
        # pieces) draws the same picture.
        for name, data in (("channel", f"{work}/b"), ("contacts", f"{work}/b"), ("cracks", f"{work}/sheet")):
            pvbatch("render_state.py", f"{pics}/{name}.pvsm", data, "-o", f"{pics}/{name}_state.png")
            image(f"{pics}/{name}_state.png", "--same-as", f"{pics}/{name}.png")

        # The committed state files (postprocess/paraview/states/, made from the default scenes' full runs) load on
        # these short runs and draw something (their times and colour ranges are the full runs').
        for name, data in (("channel", f"{work}/b"), ("contacts", f"{work}/b"), ("cracks", f"{work}/sheet")):
            state = os.path.join(PICTURES, "states", f"{name}.pvsm")
            pvbatch("render_state.py", state, data, "-o", f"{pics}/{name}_committed_state.png")
            image(f"{pics}/{name}_committed_state.png", "--coloured", "0.001")

        # Bad input: a folder without the series gets a message naming the file, exit 2.
        p = subprocess.run(["bash", PVBATCH, os.path.join(PICTURES, "cracks.py"), f"{work}/a", "-o", pics],
                           stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
        check(p.returncode == 2 and "bonds.pvd not found" in p.stdout,
              f"cracks.py on a run without bonds: exit {p.returncode}, names bonds.pvd")
        p = subprocess.run(["bash", PVBATCH, os.path.join(PICTURES, "channel.py"), f"{work}/a", "-t", "3"],
                           stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
        check(p.returncode == 2 and "no frame at that time" in p.stdout,
              f"channel.py -t 3 (no frame there): exit {p.returncode}, says so")
    finally:
        if a.keep:
            print(f"test_paraview: kept {work}")
        else:
            shutil.rmtree(work, ignore_errors=True)
    print(f"test_paraview: {len(failures)} failures")
    return 1 if failures else 0


def main_on_one_display():
    # Every pvbatch call on one virtual display (about 1 s less per call than a display of its own each).
    with shared_display():
        return main()


if __name__ == "__main__":
    sys.exit(main_on_one_display())
