"""Cracks in ParaView: the broken bonds of a frozen sheet as a crack network over the ice, each crack face coloured
by when it broke; the elements in ice colour, the plates and walls dark.

    bash scripts/pvbatch.sh postprocess/paraview/cracks.py results/uniaxial [-o OUT] [-t T] [--animation]

Needs a run with bonds (bonds.pvd: one line per bonded face, `intact` 0 once it broke, `broken_time`). Writes
OUT/cracks.png (and .pvsm; --animation: frames and a movie).
"""
import math

import paraview.simple as pv  # noqa: E402
import polyfloe_pv as P  # noqa: E402

SCRIPT = "cracks.py"


def main():
    a = P.arguments(SCRIPT, __doc__.split("\n")[0], extra=lambda ap: ap.add_argument(
        "--width", type=float, default=3.0, help="the cracks' line width in pixels (default 3)"))
    floes = P.open_series(SCRIPT, a.results, "floes", "the floes' VTK series (output.vtk: true)")
    bonds = P.open_series(SCRIPT, a.results, "bonds", "the bonds' VTK series: a scene with bonds (ice_sheet with "
                                                      "bonds, or frozen floes) and output.vtk: true")
    ts = P.times(bonds)
    t = P.pick_time(SCRIPT, bonds, a.time)
    P.go_to(t)
    broken = pv.Threshold(registrationName="cracks", Input=bonds, Scalars=["CELLS", "intact"], LowerThreshold=0.0,
                          UpperThreshold=0.5, ThresholdMethod="Between")
    when = P.array_range(bonds, "CELLS", "broken_time")
    if when is None:
        print(f"{SCRIPT}: no bond broke during the run (the picture shows the intact sheet)")
        when = (ts[0], ts[-1])
    when = (min(when[0], ts[0]), ts[-1]) if when[0] < when[1] else (when[0], when[0] + 1.0)

    ice = P.by_motion(floes, "ice", [0, 0])
    walls = P.by_motion(floes, "walls", [1, 2])
    v = P.view(a.size)
    d = pv.Show(ice, v)
    P.flat(d)
    P.solid(d, P.ICE)
    w = pv.Show(walls, v)
    P.flat(w)
    P.solid(w, P.WALL)
    c = pv.Show(broken, v)
    c.LineWidth = a.width
    c.RenderLinesAsTubes = 0
    P.flat(c)
    P.colour(c, v, "CELLS", "broken_time", when, "Viridis (matplotlib)", "crack: time of breaking [s]")
    P.time_label(v, "t = {time:.3g} s")
    n = len([x for x in P.values(broken, "CELLS", "broken_time", t) if not math.isnan(x)])
    print(f"{SCRIPT}: {n} broken bond faces at t = {t:g} s")
    P.save(SCRIPT, v, a, a.name or "cracks", t, ts, [(v, P.bounds_over_run(floes))])


if __name__ == "__main__":
    main()
