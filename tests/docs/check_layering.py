#!/usr/bin/python3
"""Checks that every include between PolyFloe's modules points the way the build's dependencies do.

    /usr/bin/python3 tests/docs/check_layering.py [--list]

The modules and their dependencies are read from the build itself: each `polyfloe_module(NAME ... DEPS ...
PRIVATE_DEPS ...)` of dem/CMakeLists.txt, and polyfloe_coupling's target_link_libraries in coupling/CMakeLists.txt.
A file of module M may include its own module's headers and those of the modules M depends on: for a header, the
public dependencies (DEPS) and, through them, theirs; for a source file, also its private dependencies (and their
public ones). `dem/app/main.cpp` is the `polyfloe` program (links run, and mpi where built); `coupling/app/` is `polyfloe-field` (links
coupling). Every module exports dem/ as its include directory, so the compiler would accept an include that points
the wrong way; this check, run by CTest (`layering`), does not. Exit 1 naming each file, line and include.
"""
import argparse
import os
import re
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
INCLUDE = re.compile(r'^\s*#\s*include\s+"([^"]+)"')


def modules_from_cmake():
    """{module: (public deps, private deps)} of the polyfloe modules, names without the polyfloe_ prefix."""
    text = open(os.path.join(ROOT, "dem", "CMakeLists.txt"), encoding="utf-8").read()
    text = re.sub(r"#[^\n]*", "", text)
    mods = {}
    for m in re.finditer(r"polyfloe_module\(\s*(\w+)(.*?)\)", text, re.S):
        name, body = m.group(1), m.group(2)
        sections = re.split(r"\b(SOURCES|DEPS|PRIVATE_DEPS)\b", body)
        deps = {"DEPS": [], "PRIVATE_DEPS": []}
        for key, value in zip(sections[1::2], sections[2::2]):
            if key in deps:
                deps[key] = [d[len("polyfloe_"):] for d in value.split() if d.startswith("polyfloe_")]
        mods[name] = (set(deps["DEPS"]), set(deps["PRIVATE_DEPS"]))
    coupling = open(os.path.join(ROOT, "coupling", "CMakeLists.txt"), encoding="utf-8").read()
    m = re.search(r"target_link_libraries\(polyfloe_coupling\s+PUBLIC(.*?)(PRIVATE|\))", coupling, re.S)
    if not m:
        sys.exit("check_layering: cannot read polyfloe_coupling's dependencies from coupling/CMakeLists.txt")
    mods["coupling"] = ({d[len("polyfloe_"):] for d in m.group(1).split() if d.startswith("polyfloe_")}, set())
    if len(mods) < 9:
        sys.exit(f"check_layering: found only {sorted(mods)} in the CMake files (has the module function changed?)")
    return mods


def public_closure(mods, start):
    """The modules reachable from `start` through public dependencies, `start` included."""
    seen, todo = set(), list(start)
    while todo:
        m = todo.pop()
        if m in seen:
            continue
        seen.add(m)
        todo += list(mods.get(m, (set(), set()))[0])
    return seen


def allowed(mods, module, header):
    public, private = mods[module]
    deps = set(public) | (set() if header else set(private))
    return {module} | public_closure(mods, deps)


def files():
    """(module, path) of every C++ file of dem/ and coupling/."""
    for base in ("dem", "coupling"):
        for folder, _, names in os.walk(os.path.join(ROOT, base)):
            rel = os.path.relpath(folder, ROOT).split(os.sep)
            for n in sorted(names):
                if not n.endswith((".h", ".cpp")):
                    continue
                if base == "coupling":
                    module = "coupling-app" if rel[-1] == "app" else "coupling"
                else:
                    module = "dem-app" if rel[1] == "app" else rel[1]
                yield module, os.path.join(folder, n)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--list", action="store_true", help="print each module's allowed includes and stop")
    a = ap.parse_args()
    mods = modules_from_cmake()
    mods["dem-app"] = ({"run", "mpi"} if "mpi" in mods else {"run"}, set())
    mods["coupling-app"] = ({"coupling"}, set())
    coupling_headers = {n for n in os.listdir(os.path.join(ROOT, "coupling")) if n.endswith(".h")}
    if a.list:
        for m in sorted(mods):
            print(f"{m}: headers {sorted(allowed(mods, m, True))}, sources {sorted(allowed(mods, m, False))}")
        return 0
    problems, checked = [], 0
    for module, path in files():
        if module not in mods:
            problems.append(f"{os.path.relpath(path, ROOT)}: folder '{module}' is not a module of dem/CMakeLists.txt")
            continue
        ok = allowed(mods, module, path.endswith(".h"))
        for number, line in enumerate(open(path, encoding="utf-8"), 1):
            m = INCLUDE.match(line)
            if not m:
                continue
            target = m.group(1)
            if "/" in target:
                to = target.split("/")[0]
                if to not in mods:
                    continue  # a third-party path
            elif target in coupling_headers:
                to = "coupling"
            else:
                continue  # the file's own folder
            checked += 1
            if to not in ok:
                problems.append(f"{os.path.relpath(path, ROOT)}:{number}: #include \"{target}\": module '{module}' "
                                f"may include only {sorted(ok)} (dem/CMakeLists.txt)")
    for p in problems:
        print(f"check_layering: {p}", file=sys.stderr)
    print(f"check_layering: {checked} includes between modules checked, {len(problems)} pointing the wrong way")
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
