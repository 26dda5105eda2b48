#!/usr/bin/python3
"""ParaView as the client, end to end: small runs of the channel scene (twice, into two folders: once in one
process, once on 2 MPI ranks with its VTK frames in per-rank pieces) and of the frozen sheet's uniaxial
compression, each picture script of postprocess/paraview/ rendered by ParaView's own pvbatch (scripts/pvbatch.sh, on
a virtual display), each picture checked by its pixels (not blank: coloured floes, arrows, cracks), each state file
loaded by pvbatch against the other folder (the pieces) and checked to draw the same picture, the first frame's
arrays as ParaView reads them, frame times on the interval's multiples, and an animation.

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

        # results.xmf: ParaView's XDMF Reader reads the HDF5 time series, frame for frame.
        out = run(["bash", PVBATCH, os.path.join(ROOT, "tests", "paraview", "xdmf_frames.py"), f"{work}/a/results.xmf"],
                  "xdmf_frames.py")
        xdmf = json.loads([line for line in out.splitlines() if line.startswith("{")][-1])
        check(xdmf["times"] == [float(t) for t in times], f"results.xmf frame times {xdmf['times']}")
        h5 = run(["/usr/bin/python3", "-c", "import h5py, json, sys; f = h5py.File(sys.argv[1], 'r'); "
                  "k = int(sys.argv[2]); first = int(f['floes/polygon_offsets'][k]); "
                  "print(json.dumps({'n': len(f['floes/id']), 'xy': f['state/vertices_xy'][-1, first].tolist(), "
                  "'v': f['state/velocity'][-1, k].tolist()}))", f"{work}/a/results.h5", str(xdmf["body"])],
                 "reading results.h5")
        h5 = json.loads(h5)
        check(xdmf["cells"] == h5["n"], f"results.xmf: {xdmf['cells']} polygons, results.h5 {h5['n']} bodies")
        check({"velocity", "angular_velocity", "id", "thickness", "motion"} <= set(xdmf["arrays"]),
              f"results.xmf cell arrays {xdmf['arrays']}")
        check(max(abs(a - b) for a, b in zip(xdmf["point"][:2], h5["xy"])) < 1e-9 and h5["v"] != [0.0, 0.0, 0.0] and
              max(abs(a - b) for a, b in zip(xdmf["velocity"], h5["v"])) < 1e-12,
              f"results.xmf's last frame is results.h5's (body {xdmf['body']}): first vertex {xdmf['point'][:2]} vs {h5['xy']}, "
              f"velocity {xdmf['velocity']} vs {h5['v']}")

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


if __name__ == "__main__":
    sys.exit(main())
