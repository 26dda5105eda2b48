"""Contacts in ParaView: an arrow at each contact point along the force on the first floe, its length growing with
the logarithm of the force (a contact at the run's median force is --arrow long, one 100 times stronger twice that,
clamped to 0.3 ... 3 times), coloured by the force on a log scale; the floes grey, the walls dark.

    bash scripts/pvbatch.sh postprocess/paraview/contacts.py results/channel [-o OUT] [-t T] [--animation]

Contact forces span orders of magnitude (10^3 ... 10^7 N in the channel scene): arrows in proportion to the force
would show the strongest few. Writes OUT/contacts.png (and .pvsm; --animation: frames and a movie).
"""

import paraview.simple as pv  # noqa: E402
import polyfloe_pv as P  # noqa: E402

SCRIPT = "contacts.py"


def median(xs):
    xs = sorted(xs)
    n = len(xs)
    return 0.0 if n == 0 else xs[n // 2] if n % 2 else 0.5 * (xs[n // 2 - 1] + xs[n // 2])


def main():
    a = P.arguments(SCRIPT, __doc__.split("\n")[0],
                    time_help="the picture's time [s] (default: the frame with the most contacts)",
                    extra=lambda ap: ap.add_argument(
                        "--arrow", type=float, help="the median contact's arrow length [m] (default: 1.5 %% of the "
                                                    "picture's width)"))
    floes = P.open_series(SCRIPT, a.results, "floes", "the floes' VTK series (output.vtk: true)")
    contacts = P.open_series(SCRIPT, a.results, "contacts", "the contacts' VTK series (output.contacts: true)")
    ts = P.times(contacts)
    # The run's forces: the median sets the arrows' length, the range the colours.
    forces, busiest, most = [], ts[-1], -1
    for t in ts:
        f = P.values(contacts, "POINTS", "normal_force", t)
        forces += [abs(x) for x in f if x == x]
        if len(f) > most:
            busiest, most = t, len(f)
    if not forces:
        P.fail(SCRIPT, f"{a.results}/contacts.pvd holds no contact in any frame: nothing to draw")
    t = P.pick_time(SCRIPT, contacts, a.time) if a.time is not None else busiest
    f_median = max(median(forces), 1e-30)
    f_range = (max(min(x for x in forces if x > 0) if any(x > 0 for x in forces) else 1.0, max(forces) * 1e-6),
               max(max(forces), 1e-30))

    P.go_to(t)
    ice = P.by_motion(floes, "ice", [0, 0])
    walls = P.by_motion(floes, "walls", [1, 2])
    box = P.bounds_over_run(floes)
    if a.arrow is None:  # visible in the whole picture
        a.arrow = 0.015 * max(box[1] - box[0], box[3] - box[2])
    length = pv.Calculator(registrationName="arrow length", Input=contacts, ResultArrayName="arrow_length",
                           Function=f"clamp(0.3, 1 + 0.5 * log10(abs(normal_force) / {f_median!r}), 3)")
    arrows = pv.Glyph(registrationName="contact arrows", Input=length, GlyphType="Arrow",
                      OrientationArray=["POINTS", "force"], ScaleArray=["POINTS", "arrow_length"],
                      ScaleFactor=a.arrow, GlyphMode="All Points")
    arrows.GlyphType.TipRadius = 0.2
    arrows.GlyphType.ShaftRadius = 0.08

    v = P.view(a.size)
    d = pv.Show(ice, v)
    P.flat(d)
    P.solid(d, [0.82, 0.84, 0.86], edges=True)
    d.EdgeColor = [0.6, 0.6, 0.6]
    P.solid(pv.Show(walls, v), P.WALL)
    P.flat(pv.GetDisplayProperties(walls, v))
    g = pv.Show(arrows, v)
    P.flat(g)
    P.colour(g, v, "POINTS", "normal_force", f_range, "Inferno (matplotlib)", "contact normal force [N]", log=True)
    P.time_label(v)
    print(f"{SCRIPT}: {len(forces)} contact-frames, median normal force {f_median:.3g} N "
          f"(range {f_range[0]:.3g} ... {f_range[1]:.3g} N), arrow {a.arrow:.3g} m at the median; "
          f"picture at t = {t:g} s ({most if a.time is None else 'chosen'} contacts)")
    P.save(SCRIPT, v, a, a.name or "contacts", t, ts, [(v, box)])


if __name__ == "__main__":
    main()
