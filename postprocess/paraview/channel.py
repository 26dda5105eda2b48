"""A channel run in ParaView: the floes coloured by speed on one range for the whole run (0 to the run's fastest
floe), the walls, and beside it the ice velocity grid where the ice fraction is at least --ice-fraction.

    bash scripts/pvbatch.sh postprocess/paraview/channel.py results/channel [-o OUT] [-t T] [--animation]

Writes OUT/channel.png (and .pvsm, and with --animation the frames and a movie); see polyfloe_pv.py.
"""
import os

import paraview.simple as pv  # noqa: E402
import polyfloe_pv as P  # noqa: E402

SCRIPT = "channel.py"


def main():
    a = P.arguments(SCRIPT, __doc__.split("\n")[0], extra=lambda ap: ap.add_argument(
        "--ice-fraction", type=float, default=0.05,
        help="draw the velocity grid's cells with at least this ice fraction [-] (default 0.05)"))
    floes = P.open_series(SCRIPT, a.results, "floes", "the floes' VTK series (output.vtk: true)")
    t = P.pick_time(SCRIPT, floes, a.time)
    grid_file = os.path.join(a.results, "velocity.pvd")
    two = os.path.isfile(grid_file)
    box = P.bounds_over_run(floes)
    # Two maps side by side, or one above the other for a long channel.
    stacked = two and (box[1] - box[0]) > 1.2 * (box[3] - box[2]) * a.size[0] / a.size[1]
    first = list(a.size) if not two else [a.size[0], a.size[1] // 2] if stacked else [a.size[0] // 2, a.size[1]]
    second = [a.size[0] - first[0], a.size[1]] if not stacked else [a.size[0], a.size[1] - first[1]]
    layout = pv.CreateLayout("channel")
    left = P.view(first)
    pv.AssignViewToLayout(view=left, layout=layout, hint=0)

    ice = P.by_motion(floes, "ice", [0, 0])
    walls = P.by_motion(floes, "walls", [1, 2])
    speed = P.array_range(ice, "CELLS", "speed") or (0.0, 1.0)
    rng = (0.0, max(speed[1], 1e-6))
    d = pv.Show(ice, left)
    P.flat(d)
    P.colour(d, left, "CELLS", "speed", rng, "Turbo", "floe speed [m/s]")
    P.solid(pv.Show(walls, left), P.WALL)
    P.flat(pv.GetDisplayProperties(walls, left))
    P.time_label(left)
    cameras = [(left, box)]

    if two:
        grid = P.open_series(SCRIPT, a.results, "velocity", "the ice velocity grid")
        right = P.view(second)
        if stacked:
            layout.SplitVertical(0, 0.5)
        else:
            layout.SplitHorizontal(0, 0.5)
        pv.AssignViewToLayout(view=right, layout=layout, hint=2)
        iced = pv.Threshold(registrationName="ice-covered cells", Input=grid, Scalars=["CELLS", "ice_fraction"],
                            LowerThreshold=a.ice_fraction, UpperThreshold=1.0, ThresholdMethod="Between")
        g = pv.Show(iced, right)
        P.flat(g)
        P.colour(g, right, "CELLS", "speed", rng, "Turbo", "ice velocity grid: speed [m/s]")
        P.solid(pv.Show(walls, right), P.WALL)
        P.flat(pv.GetDisplayProperties(walls, right))
        cameras.append((right, box))
    P.save(SCRIPT, layout, a, a.name or "channel", t, P.times(floes), cameras)


if __name__ == "__main__":
    main()
