"""A run killed as a lost node would be: every process of it (mpirun's ranks, or the one process) sent SIGKILL once
its folder holds a given number of new checkpoints. Shared by tests/mpi/test_cli_ranks.py and
tests/paraview/test_paraview.py."""
import os
import signal
import subprocess
import time


def killed_after(args, env, folder, checkpoints, cwd=None):
    """Starts `args`, and kills every process of it (mpirun's ranks, or the one process) once `folder` holds
    `checkpoints` numbered checkpoints more than it did (run in `cwd`, where given). Returns whether it was killed
    before it ended."""
    def count():  # the newest checkpoint's number (older ones are pruned)
        d = os.path.join(folder, "checkpoints")
        names = [n for n in os.listdir(d) if n.startswith("checkpoint_")] if os.path.isdir(d) else []
        return max([int(n[len("checkpoint_"):-len(".h5")]) for n in names], default=0)

    before = count()
    p = subprocess.Popen(args, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL, env=env,
                         start_new_session=True, cwd=cwd)
    while p.poll() is None and count() < before + checkpoints:
        time.sleep(0.02)
    if p.poll() is not None:
        return False
    # mpirun and its ranks, each rank in a process group of its own but all in the session started here: a lost node
    for _ in range(200):
        alive = session_members(p.pid)
        if not alive:
            break
        for pid in alive:
            try:
                os.kill(pid, signal.SIGKILL)
            except ProcessLookupError:
                pass
        time.sleep(0.01)
        p.poll()
    p.wait()
    if session_members(p.pid):
        raise RuntimeError(f"processes of the killed run are still alive: {session_members(p.pid)}")
    return True


def session_members(sid):
    """The live processes of session `sid` (zombies left out)."""
    out = []
    for name in os.listdir("/proc"):
        if not name.isdigit():
            continue
        try:
            with open(f"/proc/{name}/stat") as f:
                fields = f.read().rsplit(")", 1)[1].split()
        except OSError:
            continue
        if int(fields[3]) == sid and fields[0] != "Z":
            out.append(int(name))
    return out
