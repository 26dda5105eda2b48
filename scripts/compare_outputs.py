#!/usr/bin/python3
"""Compares two PolyFloe output folders bitwise: the same files, every HDF5 file with the same groups, datasets
(type, shape and every value's bits) and attributes, every other file byte for byte. Attributes that name the
program rather than the result (code_version) are left out. Prints each difference; exit 0 when there is none,
1 otherwise, 2 on bad arguments.

    /usr/bin/python3 scripts/compare_outputs.py OLD_RUN NEW_RUN
"""
import os
import sys

import h5py
import numpy as np

IGNORED_ATTRIBUTES = {"code_version"}
IGNORED_FILES = {".polyfloe-lock"}


def files_of(root):
    out = set()
    for folder, _, names in os.walk(root):
        for name in names:
            if name not in IGNORED_FILES:
                out.add(os.path.relpath(os.path.join(folder, name), root))
    return out


def same_value(a, b):
    a, b = np.asarray(a), np.asarray(b)
    if a.dtype != b.dtype or a.shape != b.shape:
        return False
    if a.dtype.kind in "fc":  # bits, so that NaN equals NaN and -0 differs from 0
        return a.tobytes() == b.tobytes()
    return np.array_equal(a, b)


def hdf5_content(path):
    items = {}

    def attributes(name, obj):
        for key, value in obj.attrs.items():
            if key not in IGNORED_ATTRIBUTES:
                items[("attribute", name, key)] = value

    def visit(name, obj):
        attributes(name, obj)
        if isinstance(obj, h5py.Dataset):
            items[("dataset", name)] = obj[()]
        else:
            items[("group", name)] = None

    try:
        f = h5py.File(path, "r")
    except OSError:  # a copy taken while the run wrote it (the checkpoints' copy of results.h5): SWMR-readable
        f = h5py.File(path, "r", swmr=True)
    with f:
        attributes("/", f)
        f.visititems(visit)
    return items


def compare_hdf5(rel, old, new, report):
    a, b = hdf5_content(old), hdf5_content(new)
    for key in sorted(set(a) | set(b), key=str):
        where = f"{rel}: {key[0]} {'/'.join(key[1:])}"
        if key not in a or key not in b:
            report(f"{where}: only in {'the new' if key in b else 'the old'} run")
        elif key[0] != "group" and not same_value(a[key], b[key]):
            report(f"{where}: differs")


def compare(old_root, new_root):
    differences = []
    report = differences.append
    old_files, new_files = files_of(old_root), files_of(new_root)
    for rel in sorted(old_files ^ new_files):
        report(f"{rel}: only in {'the new' if rel in new_files else 'the old'} run")
    for rel in sorted(old_files & new_files):
        old, new = os.path.join(old_root, rel), os.path.join(new_root, rel)
        if rel.endswith(".h5"):
            compare_hdf5(rel, old, new, report)
        else:
            with open(old, "rb") as f, open(new, "rb") as g:
                if f.read() != g.read():
                    report(f"{rel}: differs")
    return differences


def main(argv):
    if len(argv) != 3 or not all(os.path.isdir(p) for p in argv[1:]):
        print(__doc__.strip(), file=sys.stderr)
        return 2
    differences = compare(argv[1], argv[2])
    for line in differences[:50]:
        print(line)
    if len(differences) > 50:
        print(f"... and {len(differences) - 50} more")
    return 1 if differences else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
