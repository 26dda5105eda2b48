"""The floes of one frame of a PolyFloe results.h5 as world-frame polygons."""
import numpy as np


def frame_polygons(f, k):
    """World-frame outlines [m] of every body at frame k of the open results.h5 `f` (an (n, 2) array each)."""
    off = f["/floes/polygon_offsets"][:]
    xy = f["/floes/polygon_xy"][:]
    pos = f["/state/position"][k]
    q = f["/state/orientation"][k]
    yaw = 2.0 * np.arctan2(q[:, 3], q[:, 0])
    polys = []
    for i in range(len(off) - 1):
        c, s = np.cos(yaw[i]), np.sin(yaw[i])
        local = xy[off[i]:off[i + 1]]
        world = np.column_stack([c * local[:, 0] - s * local[:, 1], s * local[:, 0] + c * local[:, 1]])
        polys.append(world + pos[i, :2])
    return polys
