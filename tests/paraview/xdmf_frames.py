"""pvbatch: what ParaView's XDMF Reader reads from a run's results.xmf, as JSON (tests/paraview/test_paraview.py):
the frame times, and at the last time the cell count, the cell arrays, and the first dynamic body's index, first
vertex and velocity."""
import json
import sys

from paraview import servermanager
import paraview.simple as pv

r = pv.XDMFReader(FileNames=[sys.argv[1]])
r.UpdatePipelineInformation()
ts = list(r.TimestepValues)
r.UpdatePipeline(ts[-1])
d = servermanager.Fetch(r)
motion = d.GetCellData().GetArray("motion")
k = next(i for i in range(d.GetNumberOfCells()) if motion.GetTuple1(i) == 0)
print(json.dumps({"times": ts, "cells": d.GetNumberOfCells(), "arrays": list(r.CellData.keys()), "body": k,
                  "point": list(d.GetCell(k).GetPoints().GetPoint(0)),
                  "velocity": list(d.GetCellData().GetArray("velocity").GetTuple3(k))}))
