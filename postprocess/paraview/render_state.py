"""Renders a ParaView state file (.pvsm) of these scripts against a results folder: what loading it in the GUI
shows (File > Load State, "Search files under specified directory").

    bash scripts/pvbatch.sh postprocess/paraview/render_state.py STATE.pvsm DATA_DIR -o PICTURE.png [-t T]

DATA_DIR holds the files the state reads (floes.pvd, ...; for ice_over_field also FIELD.pvd, anywhere below it).
"""
import argparse
import os
import sys

import paraview.simple as pv

SCRIPT = "render_state.py"


def main():
    ap = argparse.ArgumentParser(prog=SCRIPT, description=__doc__.split("\n")[0])
    ap.add_argument("state", help="a .pvsm written by one of these scripts")
    ap.add_argument("data", help="the folder whose files replace the state's (searched below it)")
    ap.add_argument("-o", "--output", required=True, help="the picture to write (.png)")
    ap.add_argument("-t", "--time", type=float,
                    help="the time [s] (default: the state's, or the data's last time when the data end before it)")
    ap.add_argument("--size", type=int, nargs=2, default=[1600, 900], metavar=("W", "H"))
    a = ap.parse_args()
    for path, what in ((a.state, "state file"), (a.data, "data folder")):
        if not os.path.exists(path):
            sys.stderr.write(f"{SCRIPT}: {path}: no such {what}\n")
            sys.exit(2)
    pv.LoadState(a.state, data_directory=os.path.abspath(a.data), restrict_to_data_directory=True)
    scene = pv.GetAnimationScene()
    t = a.time if a.time is not None else scene.AnimationTime
    scene.UpdateAnimationUsingDataTimeSteps()
    times = list(pv.GetTimeKeeper().TimestepValues or [])
    if times:
        t = min(max(t, times[0]), times[-1])
    scene.AnimationTime = t
    layout = pv.GetLayouts().values()
    target = list(layout)[0] if layout else pv.GetActiveView()
    pv.SaveScreenshot(a.output, target, ImageResolution=list(a.size), TransparentBackground=0)
    print(f"{SCRIPT}: wrote {a.output}")


if __name__ == "__main__":
    main()
