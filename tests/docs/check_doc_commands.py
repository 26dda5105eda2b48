#!/usr/bin/python3
"""Runs every command the documentation shows, as a new user would, in a fresh copy of the repository.

Commands are taken from the documents themselves, so an example is checked the day it is written:
  - README.md, docs/user-guide.md, docs/scene-reference.md: fenced blocks (```sh: every line; other blocks: lines
    that start with a command); continuation lines (trailing backslash) and for-loops are joined;
  - the scene files' comments (dem/scenes/*.yaml, of_cases/*/*.yaml): lines `#   polyfloe ...` or `#   bash ...`.
Each runs with bash in a copy of the tracked files (`git ls-files`; the build folder linked in, `polyfloe` on the
PATH), in document order, so a command may use what an earlier one wrote. Long runs are shortened: every
`polyfloe run` gets `--set run.duration=0.05` (after the document's own options, so it wins), scripts that run
scenes get the same after their `--`. The few commands that cannot run here, or need a stand-in, are in RULES
below with the reason; a command no rule knows runs as written.

It fails when a command exits non-zero, or writes into the repository: a tracked file changed, or a new file
outside the folders git ignores (build*/, results/, out/).

    /usr/bin/python3 tests/docs/check_doc_commands.py [--build build] [--list] [--only TEXT] [--keep]
"""
import argparse
import hashlib
import os
import re
import shutil
import subprocess
import sys
import tempfile
import time

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
DOCS = ["README.md", "docs/user-guide.md", "docs/scene-reference.md"]
SHORT = "--set run.duration=0.05"
COMMAND_START = re.compile(r"^(\./build/polyfloe|polyfloe|mpirun |bash |/usr/bin/python3 |of_cases/|cmake |for )")

# (pattern on the command, action, reason). Actions: "skip"; "shorten-script" (append SHORT after `--`, adding one);
# or a function of the command returning the command to run.
RULES = [
    (r"scripts/setup_and_(run|test)\.sh", "skip",
     "the two README commands are what CI runs (.ci/run calls the test command; its parts are checked here)"),
    (r"^bash scripts/build\.sh", "skip", "the build this check runs on"),
    (r"of_cases/\w+/All(run|clean)|of_cases/\w+/ice\.yaml", "skip",
     "OpenFOAM end to end: ctest -R 'test_strait_openfoam|test_openfoam_tutorials' (needs the case's field file)"),
    (r"\bCASE\b|field info field\.h5", "skip", "a template: CASE stands for your OpenFOAM case"),
    (r"scripts/pvbatch\.sh|scripts/setup\.sh paraview|make_figures\.sh paraview", "skip",
     "ParaView: ctest -R 'paraview_pictures|test_strait_openfoam' renders every script and loads every state file"),
    (r"scripts/(sweep|uniaxial_study)\.sh", "shorten-script", "scene runs shortened to 0.05 s"),
    (r"plot_frames\.py .* -t 0 150 300", lambda c: c.replace("-t 0 150 300", "-t 0 0.05"),
     "the runs above are shortened to 0.05 s: their frames are at 0 and 0.05 s"),
    (r"^mpirun ", lambda c: c.replace("mpirun ", "mpirun --allow-run-as-root --oversubscribe ", 1),
     "the check runs as root on 2 cores: the options the documents name for that"),
]


def logical_commands(where, numbered_lines):
    """(where:line, command) from (line number, text or None) pairs, None where no command can start: a command
    starts at a line marked as a possible start and goes on over continuation lines (a trailing backslash) and to the
    `done` of a for-loop."""
    out, pending, start = [], "", 0
    for n, text, can_start in numbered_lines:
        if not pending:
            if not can_start:
                continue
            start = n
        pending += (" " if pending else "") + strip_comment(text).rstrip()
        if pending.endswith("\\"):
            pending = pending[:-1].rstrip()
            continue
        if re.match(r"^for ", pending) and not re.search(r"\bdone$", pending):
            pending += ";" if not pending.endswith(("do", ";")) else ""
            continue
        out.append((f"{where}:{start}", pending.strip()))
        pending = ""
    return out


def commands_in_markdown(path):
    """Commands in fenced blocks: in ```sh blocks every line that starts at the margin, elsewhere lines that start
    with a command."""
    lines, in_block, lang = [], False, ""
    for n, line in enumerate(open(os.path.join(ROOT, path), encoding="utf-8").read().split("\n"), 1):
        fence = re.match(r"^\s*```(\w*)", line)
        if fence:
            in_block, lang = (not in_block), fence.group(1)
        elif in_block:
            starts = bool(COMMAND_START.match(line) or (lang == "sh" and line.strip() and not line.startswith(" ")))
            lines.append((n, line, starts))
    return logical_commands(path, lines)


def commands_in_scene_comments():
    """Commands in the scene files' comments: lines `#   polyfloe ...` or `#   bash ...`."""
    out = []
    for folder in ("dem/scenes", "of_cases"):
        for base, _, files in sorted(os.walk(os.path.join(ROOT, folder))):
            for f in sorted(x for x in files if x.endswith(".yaml")):
                lines = []
                for n, line in enumerate(open(os.path.join(base, f), encoding="utf-8"), 1):
                    m = re.match(r"^#\s+(.*)$", line.rstrip("\n"))
                    text = m.group(1) if m else ""
                    lines.append((n, text, bool(re.match(r"^(polyfloe |bash )", text))))
                out += logical_commands(os.path.relpath(os.path.join(base, f), ROOT), lines)
    return out


def strip_comment(line):
    """The line without a trailing shell comment (a # after a blank, outside quotes)."""
    quote = None
    for i, ch in enumerate(line):
        if quote:
            if ch == quote:
                quote = None
        elif ch in "'\"":
            quote = ch
        elif ch == "#" and (i == 0 or line[i - 1] in " \t"):
            return line[:i]
    return line


def shorten_runs(command):
    """Appends SHORT to every `polyfloe run` segment (segments split on ; && | and `do`)."""
    parts = re.split(r"(;|&&|\|\||\bdo\b)", command)
    for i, part in enumerate(parts):
        if re.search(r"(^|\s|/)polyfloe run\s", part):
            parts[i] = part.rstrip() + " " + SHORT + " "
    return "".join(parts).strip()


def with_restart_source(command):
    """A `--restart DIR` needs an interrupted run in DIR: where the documents assume one from before (a run killed at
    t = 212 s), a short run of the same scene into DIR stands for it."""
    m = re.search(r"(\S*polyfloe) run (\S+).*--restart (\S+)", command)
    if not m:
        return command, ""
    binary, scene, folder = m.groups()
    prelude = f"[ -d {folder}/checkpoints ] || {binary} run {scene} -o {folder} {SHORT} > /dev/null; "
    return prelude + command, f"a short run into {folder} stands for the interrupted one"


def plan(where, command):
    """(command to run or None, note)."""
    run, note = plan_rules(command)
    if run is None:
        return run, note
    run, restart_note = with_restart_source(run)
    return run, "; ".join(n for n in (note, restart_note) if n)


def plan_rules(command):
    for pattern, action, reason in RULES:
        if re.search(pattern, command):
            if action == "skip":
                return None, "skipped: " + reason
            if action == "shorten-script":
                return (command + (" " if " -- " in command else " -- ") + SHORT), reason
            return shorten_runs(action(command)), reason
    return shorten_runs(command), ""


def snapshot(tree):
    """path -> content digest of every file outside the folders git ignores."""
    files = {}
    for base, dirs, names in os.walk(tree):
        rel_base = os.path.relpath(base, tree)
        if rel_base == ".":
            dirs[:] = [d for d in dirs if not (d.startswith("build") or d in ("results", "out"))]
        dirs[:] = [d for d in dirs if d not in ("__pycache__",)]
        for name in names:
            if name.endswith(".pyc"):
                continue
            p = os.path.join(base, name)
            if os.path.islink(p):
                files[os.path.relpath(p, tree)] = "link:" + os.readlink(p)
                continue
            with open(p, "rb") as fh:
                files[os.path.relpath(p, tree)] = hashlib.sha1(fh.read()).hexdigest()
    return files


def fresh_copy(build):
    tree = tempfile.mkdtemp(prefix="polyfloe_docs_")
    tracked = subprocess.run(["git", "ls-files", "-z"], cwd=ROOT, check=True, capture_output=True).stdout
    for rel in tracked.decode().split("\0"):
        if not rel:
            continue
        dst = os.path.join(tree, rel)
        os.makedirs(os.path.dirname(dst), exist_ok=True)
        shutil.copy2(os.path.join(ROOT, rel), dst, follow_symlinks=False)
    os.symlink(os.path.abspath(build), os.path.join(tree, "build"))
    return tree


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--build", default=os.path.join(ROOT, "build"), help="the build folder (default: build/)")
    ap.add_argument("--list", action="store_true", help="list the commands and what will be run, then stop")
    ap.add_argument("--only", help="run only the commands containing this text")
    ap.add_argument("--keep", action="store_true", help="keep the copy of the repository (printed)")
    ap.add_argument("--timeout", type=float, default=600.0, help="seconds per command (default 600)")
    a = ap.parse_args()
    found = [c for d in DOCS for c in commands_in_markdown(d)] + commands_in_scene_comments()
    if a.only:
        found = [c for c in found if a.only in c[1]]
    if not found:
        sys.exit("check_doc_commands: no documented command found (is the repository there?)")
    if a.list:
        for where, command in found:
            run, note = plan(where, command)
            print(f"{where}: {command}\n    -> {run if run else '(not run)'}{'   # ' + note if note else ''}")
        return 0
    if not os.path.isfile(os.path.join(a.build, "polyfloe")):
        sys.exit(f"check_doc_commands: {a.build}/polyfloe is not built (bash scripts/build.sh)")
    tree = fresh_copy(a.build)
    env = dict(os.environ, PATH=os.path.join(tree, "build") + os.pathsep + os.environ.get("PATH", ""),
               OMP_NUM_THREADS=os.environ.get("OMP_NUM_THREADS", "2"))
    before = snapshot(tree)
    failures, ran, skipped = [], 0, 0
    for where, command in found:
        run, note = plan(where, command)
        if run is None:
            skipped += 1
            print(f"-- {where}: {command}\n   {note}")
            continue
        t0 = time.time()
        try:
            p = subprocess.run(["bash", "-c", "set -o pipefail; " + run], cwd=tree, env=env, capture_output=True,
                               text=True, timeout=a.timeout)
            code, output = p.returncode, (p.stdout + p.stderr)
        except subprocess.TimeoutExpired:
            code, output = "timeout", f"no answer in {a.timeout:.0f} s"
        ran += 1
        after = snapshot(tree)
        written = sorted(k for k in after if before.get(k) != after[k])
        gone = sorted(k for k in before if k not in after)
        before = after
        status = "ok" if code == 0 and not written and not gone else "FAILED"
        print(f"{status} {where} ({time.time() - t0:.1f} s): {run}" + (f"   # {note}" if note else ""))
        if code != 0:
            failures.append(f"{where}: `{command}` exited {code}:\n" + "\n".join(output.strip().split("\n")[-15:]))
        if written or gone:
            failures.append(f"{where}: `{command}` wrote into the repository: " + ", ".join(written + gone))
    if a.keep:
        print(f"the copy: {tree}")
    else:
        shutil.rmtree(tree, ignore_errors=True)
    print(f"check_doc_commands: {ran} commands run, {skipped} not run (reasons above), {len(failures)} failures")
    for f in failures:
        print("\n" + f, file=sys.stderr)
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
