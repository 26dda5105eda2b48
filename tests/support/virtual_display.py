"""One virtual display (Xvfb) shared by a test's pvbatch calls: scripts/pvbatch.sh starts a display of its own for
each call where $DISPLAY is unset (about 1 s of each call), and uses $DISPLAY where it is set. Started as
scripts/pvbatch.sh starts its own (-displayfd: Xvfb picks a free display number; -noreset: no reset between
clients, during which a connection would fail). Used by tests/paraview/test_paraview.py."""
import contextlib
import os
import subprocess
import tempfile
import time


@contextlib.contextmanager
def shared_display():
    """Within the block $DISPLAY names a virtual display, stopped at the end; where $DISPLAY is set already, or Xvfb
    does not start, nothing changes (each pvbatch call then has a display of its own, as scripts/pvbatch.sh does)."""
    if os.environ.get("DISPLAY"):
        yield
        return
    with tempfile.TemporaryFile(mode="w+") as number:
        try:
            xvfb = subprocess.Popen(["Xvfb", "-displayfd", str(number.fileno()), "-screen", "0", "1920x1080x24",
                                     "-nolisten", "tcp", "-noreset"], pass_fds=(number.fileno(),),
                                    stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
        except OSError:
            yield
            return
        display = ""
        for _ in range(300):
            number.seek(0)
            display = number.read().strip()
            if display or xvfb.poll() is not None:
                break
            time.sleep(0.1)
        if not display:
            xvfb.kill()
            xvfb.wait()
            yield
            return
        os.environ["DISPLAY"] = f":{display}"
        try:
            yield
        finally:
            del os.environ["DISPLAY"]
            xvfb.terminate()
            try:
                xvfb.wait(timeout=10)
            except subprocess.TimeoutExpired:
                xvfb.kill()
                xvfb.wait()
