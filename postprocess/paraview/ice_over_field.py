"""Ice over an ocean field in ParaView: the current's speed at the surface level of a field file's VTK series
(`polyfloe field import CASE -o FIELD.h5` writes FIELD.pvd beside it), land grey, and the floes of an ice run
driven by it over it, white with dark edges; the walls dark.

    bash scripts/pvbatch.sh postprocess/paraview/ice_over_field.py results/strait --field of_cases/strait/field.pvd \\
        [-o OUT] [-t T] [--animation]

A transient field plays with the run (the field's snapshot at each frame's time, as ParaView's reader picks it:
the last snapshot at or before the time); a scene's `time_offset` or `offset` is not applied here. Writes
OUT/ice_over_field.png (and .pvsm; --animation: frames and a movie).
"""
import os

import paraview.simple as pv  # noqa: E402
import polyfloe_pv as P  # noqa: E402

SCRIPT = "ice_over_field.py"


def main():
    a = P.arguments(SCRIPT, __doc__.split("\n")[0], extra=lambda ap: ap.add_argument(
        "--field", required=True, help="the field's VTK series, FIELD.pvd (beside FIELD.h5)"))
    floes = P.open_series(SCRIPT, a.results, "floes", "the floes' VTK series (output.vtk: true)")
    ts = P.times(floes)
    t = P.pick_time(SCRIPT, floes, a.time)
    if not a.field.endswith(".pvd") or not os.path.isfile(a.field):
        P.fail(SCRIPT, f"--field {a.field}: not a .pvd file (polyfloe field import writes FIELD.pvd beside "
                       f"FIELD.h5 unless --no-vtk)")
    field = pv.PVDReader(registrationName="ocean field", FileName=os.path.abspath(a.field))
    field.UpdatePipelineInformation()
    P.go_to(t)
    field.UpdatePipeline(t)
    info = field.GetDataInformation().DataInformation
    if "U" not in field.PointData.keys():
        P.fail(SCRIPT, f"--field {a.field}: no point array U (a field file's VTK series has U, speed, mask)")
    extent = info.GetExtent()
    surface = field
    if extent[5] > extent[4]:  # several levels: the shallowest, the sea surface's
        surface = pv.ExtractSubset(registrationName="surface level", Input=field,
                                   VOI=[extent[0], extent[1], extent[2], extent[3], extent[5], extent[5]])
    b = info.GetBounds()
    land = pv.Plane(registrationName="land", Origin=[b[0], b[2], -1.0], Point1=[b[1], b[2], -1.0],
                    Point2=[b[0], b[3], -1.0])
    speed = P.array_range(surface, "POINTS", "speed") or (0.0, 1.0)

    ice = P.by_motion(floes, "ice", [0, 0])
    walls = P.by_motion(floes, "walls", [1, 2])
    v = P.view(a.size)
    g = pv.Show(land, v)
    P.flat(g)
    P.solid(g, [0.72, 0.70, 0.66])
    s = pv.Show(surface, v)
    P.flat(s)
    P.colour(s, v, "POINTS", "speed", (0.0, max(speed[1], 1e-6)), "Blues", "ocean current speed [m/s]",
             invert=True)
    d = pv.Show(ice, v)
    P.flat(d)
    P.solid(d, [1.0, 1.0, 1.0], edges=True)
    w = pv.Show(walls, v)
    P.flat(w)
    P.solid(w, P.WALL)
    P.time_label(v)
    ice_box = P.bounds_over_run(floes)
    box = [min(b[0], ice_box[0]), max(b[1], ice_box[1]), min(b[2], ice_box[2]), max(b[3], ice_box[3])]
    P.save(SCRIPT, v, a, a.name or "ice_over_field", t, ts, [(v, box)])


if __name__ == "__main__":
    main()
