"""pvbatch: the arrays ParaView offers at the first time step of each .pvd in a results folder, one line per series:
`NAME t0 POINTS:a,b CELLS:c,d` (tests/paraview/test_paraview.py asserts them)."""
import glob
import os
import sys

import paraview.simple as pv

for pvd in sorted(glob.glob(os.path.join(sys.argv[1], "*.pvd"))):
    r = pv.PVDReader(FileName=pvd)
    r.UpdatePipelineInformation()
    ts = r.TimestepValues
    t0 = (ts[0] if hasattr(ts, "__len__") and len(ts) else ts) or 0.0
    r.UpdatePipeline(t0)
    print(os.path.basename(pvd)[:-4], repr(t0), "POINTS:" + ",".join(r.PointData.keys()),
          "CELLS:" + ",".join(r.CellData.keys()))
