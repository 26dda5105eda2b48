#!/usr/bin/python3
"""Writes the field files of the bad-input corpus (cases 87-94 and the field_file_* cases): one valid two-snapshot field and one file
spoiled per way a field file can be wrong. Rerun after changing the field-file layout (dem/formats/field_file.h):
    /usr/bin/python3 tests/bad_input/fields/make_fields.py
"""
import pathlib

import h5py
import numpy as np

HERE = pathlib.Path(__file__).resolve().parent


def write(name, *, fmt="polyfloe-ocean-field", version=1, t=(0.0, 600.0), u_shape=None, nan=False, land=False,
          huge=False):
    x, y, z = np.linspace(-100, 2000, 4), np.linspace(0, 1000, 3), np.array([-1.0])
    t = np.asarray(t, dtype=float)
    shape = (len(t), len(z), len(y), len(x), 3)
    u = np.zeros(u_shape or shape)
    u[..., 0] = 1.0
    if nan:
        u[-1, 0, 1, 2, 1] = np.nan
    if huge:
        u[0, 0, 0, 1, 0] = 1e300
    mask = np.zeros((len(z), len(y), len(x)), dtype=np.uint8) if land else np.ones((len(z), len(y), len(x)), np.uint8)
    with h5py.File(HERE / name, "w") as f:
        f.attrs["format"] = fmt
        f.attrs["format_version"] = np.int64(version)
        f.attrs["source"] = "tests/bad_input/fields/make_fields.py"
        f.attrs["created_by"] = "make_fields.py"
        for axis, values in (("x", x), ("y", y), ("z", z), ("t", t)):
            f[axis] = values
        f["U"] = u
        f["mask"] = mask


write("two_snapshots.h5")
write("wrong_format.h5", fmt="netcdf-ish")
write("future_version.h5", version=2)
write("bad_shape.h5", u_shape=(2, 1, 4, 3, 3))
write("nan.h5", nan=True)
write("all_land.h5", land=True)
write("time_backwards.h5", t=(600.0, 0.0))
write("huge_velocity.h5", huge=True)


def declared(name, *, nx, ny, nt):
    """Axes and datasets of a huge declared shape, chunked and never written: a small file that claims gigabytes."""
    with h5py.File(HERE / name, "w") as f:
        f.attrs["format"] = "polyfloe-ocean-field"
        f.attrs["format_version"] = np.int64(1)
        for axis, n in (("x", nx), ("y", ny), ("t", nt)):
            f.create_dataset(axis, shape=(n,), dtype="f8", chunks=(min(n, 4096),))
        f["z"] = np.array([-1.0])
        f.create_dataset("U", shape=(nt, 1, ny, nx, 3), dtype="f8", chunks=(1, 1, min(ny, 64), min(nx, 64), 3))
        f.create_dataset("mask", shape=(1, ny, nx), dtype="u1", chunks=(1, min(ny, 64), min(nx, 64)))


declared("declared_huge.h5", nx=30000, ny=30000, nt=1)  # 9e8 nodes: 21.6 GB of velocities
declared("axis_huge.h5", nx=200_000_000, ny=3, nt=1)
(HERE / "not_hdf5.h5").write_text("this is a text file with an .h5 name\n")
