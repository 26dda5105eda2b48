#!/usr/bin/python3
"""Compares the VTK frames of two PolyFloe output folders by content, whichever way each wrote them: one .vtp per
frame, or a .pvtp listing pieces (output.vtk_pieces). Each series (floes, contacts, bonds) must list the same
number of frames at the same times, and each frame must hold the same bodies, contacts and bond faces with the same
values, bit for bit, in any order and cut into any pieces. ParaView's own readers read the files
(vtkXMLPolyDataReader, vtkXMLPPolyDataReader), so a .pvtp they cannot read fails too. Prints each difference; exit 0
when there is none, 1 otherwise, 2 on bad arguments.

    /usr/bin/python3 scripts/compare_vtk_content.py RUN_A RUN_B
"""
import os
import re
import sys

import numpy as np
from vtkmodules.util.numpy_support import vtk_to_numpy
from vtkmodules.vtkIOXML import vtkXMLPolyDataReader, vtkXMLPPolyDataReader

SERIES = ("floes", "contacts", "bonds")


def frames(folder, series):
    """(time, file) of each frame a series' .pvd lists; None where there is no such series."""
    pvd = os.path.join(folder, series + ".pvd")
    if not os.path.exists(pvd):
        return None
    with open(pvd) as f:
        return [(t, os.path.join(folder, name))
                for t, name in re.findall(r'timestep="([^"]*)"[^>]*file="([^"]*)"', f.read())]


def read(path):
    reader = vtkXMLPPolyDataReader() if path.endswith(".pvtp") else vtkXMLPolyDataReader()
    reader.SetFileName(path)
    reader.Update()
    if reader.GetErrorCode() != 0:
        raise RuntimeError(f"{path}: VTK could not read it")
    return reader.GetOutput()


def arrays(attributes):
    out = {}
    for k in range(attributes.GetNumberOfArrays()):
        a = attributes.GetArray(k)
        if a is not None:
            v = vtk_to_numpy(a)
            out[a.GetName()] = (str(v.dtype), v.reshape(a.GetNumberOfTuples(), a.GetNumberOfComponents()))
    return out


def records(data):
    """Each cell as bytes: its points' coordinates and point values, then its cell values; sorted. Also the
    arrays' names and types."""
    points = vtk_to_numpy(data.GetPoints().GetData()) if data.GetPoints() else np.zeros((0, 3))
    point_arrays, cell_arrays = arrays(data.GetPointData()), arrays(data.GetCellData())
    out = []
    for c in range(data.GetNumberOfCells()):
        ids = data.GetCell(c).GetPointIds()
        pts = [ids.GetId(j) for j in range(ids.GetNumberOfIds())]
        parts = [points[pts].tobytes()]
        parts += [v[pts].tobytes() for _, (_, v) in sorted(point_arrays.items())]
        parts += [v[c].tobytes() for _, (_, v) in sorted(cell_arrays.items())]
        out.append(b"|".join(parts))
    names = ({k: t for k, (t, _) in point_arrays.items()}, {k: t for k, (t, _) in cell_arrays.items()})
    return sorted(out), names


def compare(a, b):
    differences = []
    for series in SERIES:
        fa, fb = frames(a, series), frames(b, series)
        if (fa is None) != (fb is None):
            differences.append(f"{series}: a series in only one of the folders")
            continue
        if fa is None:
            continue
        if [t for t, _ in fa] != [t for t, _ in fb]:
            differences.append(f"{series}: the frames' times differ ({len(fa)} and {len(fb)} frames)")
            continue
        for (t, pa), (_, pb) in zip(fa, fb):
            ra, na = records(read(pa))
            rb, nb = records(read(pb))
            if na != nb:
                differences.append(f"{series} at t = {t}: arrays differ: {na} and {nb}")
            elif ra != rb:
                differences.append(f"{series} at t = {t}: {len(ra)} and {len(rb)} cells, contents differ "
                                   f"({os.path.relpath(pa, a)}, {os.path.relpath(pb, b)})")
    return differences


def main():
    if len(sys.argv) != 3 or not all(os.path.isdir(d) for d in sys.argv[1:]):
        print(__doc__, file=sys.stderr)
        return 2
    differences = compare(sys.argv[1], sys.argv[2])
    for d in differences:
        print(d)
    return 1 if differences else 0


if __name__ == "__main__":
    sys.exit(main())
