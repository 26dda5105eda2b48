#!/usr/bin/python3
"""Writes the field files of the bad-input corpus (cases 87-94): one valid two-snapshot field and one file
spoiled per way a field file can be wrong. Rerun after changing the field-file layout (dem/io/field_file.h):
    /usr/bin/python3 tests/bad_input/fields/make_fields.py
"""
import pathlib

import h5py
import numpy as np

HERE = pathlib.Path(__file__).resolve().parent


def write(name, *, fmt="polyfloe-ocean-field", version=1, t=(0.0, 600.0), u_shape=None, nan=False, land=False):
    x, y, z = np.linspace(-100, 2000, 4), np.linspace(0, 1000, 3), np.array([-1.0])
    t = np.asarray(t, dtype=float)
    shape = (len(t), len(z), len(y), len(x), 3)
    u = np.zeros(u_shape or shape)
    u[..., 0] = 1.0
    if nan:
        u[-1, 0, 1, 2, 1] = np.nan
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
(HERE / "not_hdf5.h5").write_text("this is a text file with an .h5 name\n")
