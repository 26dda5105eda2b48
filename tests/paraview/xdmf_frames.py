"""pvbatch: what one of ParaView's XDMF readers reads from a run's results.xmf, frame by frame, as JSON
(tests/paraview/test_paraview.py). Arguments: the .xmf, the reader (`open` for OpenDataFile, the GUI's choice, or
Xdmf3ReaderS, Xdmf3ReaderT, XDMFReader) and a body id. Prints the reader's name, its cell arrays, and per time
step: the time, the cell count, and that body's first vertex and velocity."""
import json
import sys

from paraview import servermanager
import paraview.simple as pv

xmf, reader, body = sys.argv[1], sys.argv[2], int(sys.argv[3])
if reader == "open":
    r = pv.OpenDataFile(xmf)
elif reader == "XDMFReader":
    r = pv.XDMFReader(FileNames=[xmf])
else:
    r = getattr(pv, reader)(FileName=xmf)
r.UpdatePipelineInformation()
frames = []
for t in list(r.TimestepValues):
    r.UpdatePipeline(t)
    d = servermanager.Fetch(r)
    if d.IsA("vtkMultiBlockDataSet"):  # a reader that keeps the collection's blocks: the one grid of this time
        it = d.NewIterator()
        it.InitTraversal()
        d = it.GetCurrentDataObject()
    ids = d.GetCellData().GetArray("id")
    k = next((i for i in range(d.GetNumberOfCells()) if ids is not None and int(ids.GetTuple1(i)) == body), None)
    v = d.GetCellData().GetArray("velocity")
    frames.append({"time": t, "cells": d.GetNumberOfCells(),
                   "point": list(d.GetCell(k).GetPoints().GetPoint(0)) if k is not None else None,
                   "velocity": list(v.GetTuple3(k)) if k is not None and v is not None else None})
print(json.dumps({"reader": r.GetXMLName(), "arrays": list(r.CellData.keys()), "frames": frames}))
