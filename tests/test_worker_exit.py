"""Pool workers end when the process that started them is killed (SIGKILL runs no clean-up
code): the figure processes and the cycle study's pool must not stay blocked on their task
pipe, holding the caller's stdout open."""

import os
import signal
import subprocess
import sys
import textwrap
import threading
import time
from pathlib import Path

import pytest

SCRIPT = textwrap.dedent(
    """
    import os, sys, time
    from pathlib import Path

    PIDS = Path(sys.argv[2])

    def busy(*args):  # a task that never ends by itself
        with open(PIDS, "a") as f:
            f.write(f"{os.getpid()}\\n")
        time.sleep(600)
        return {}

    if __name__ == "__main__":
        if sys.argv[1] == "cycle":
            from tribodyn.workflow import cycle

            pool = cycle._local_pool(2)
            parts = [pool.submit(busy) for _ in range(2)]
            parts[0].result()
        else:
            import xarray as xr
            from tribodyn import _system
            from tribodyn.output import figures as F

            if sys.argv[1] == "watch":  # no kernel signal: the watch thread alone
                _system._PR_SET_PDEATHSIG = 0  # prctl(0, …) fails and is ignored

            F.has = lambda *a: True  # every figure wanted; each one "drawn" by busy
            F._draw_held = busy
            F.make_figures(xr.Dataset(), PIDS.parent / "figs", workers=2)
    """
)


def _running(pid: int) -> bool:
    """True while ``pid`` exists and is not a zombie (a dead child nobody reaped yet)."""
    try:
        state = Path(f"/proc/{pid}/stat").read_text().rsplit(")", 1)[1].split()[0]
    except (FileNotFoundError, ProcessLookupError):
        return False
    except OSError:  # no /proc: ask the kernel
        try:
            os.kill(pid, 0)
        except ProcessLookupError:
            return False
        return True
    return state not in ("Z", "X")


@pytest.mark.skipif(sys.platform == "win32", reason="SIGKILL is POSIX")
@pytest.mark.parametrize("pool", ["cycle", "figures", "watch"])
def test_workers_end_when_their_parent_is_killed(tmp_path, pool):
    script = tmp_path / "starter.py"
    script.write_text(SCRIPT)
    pids_file = tmp_path / "pids.txt"
    proc = subprocess.Popen(
        [sys.executable, str(script), pool, str(pids_file)],
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
    )
    pids: list[int] = []
    try:
        deadline = time.time() + 60
        while time.time() < deadline and len(pids) < 2:
            assert proc.poll() is None, proc.stderr.read().decode()
            time.sleep(0.1)
            if pids_file.exists():
                pids = [int(x) for x in pids_file.read_text().split()]
        assert len(pids) == 2, "the workers did not start"
        proc.send_signal(signal.SIGKILL)
        proc.wait(timeout=10)
        # the caller's pipes reach EOF once no worker holds them
        eof = threading.Event()
        reader = threading.Thread(target=lambda: (proc.stdout.read(), eof.set()), daemon=True)
        reader.start()
        assert eof.wait(10), "a process still holds the killed run's stdout"
        deadline = time.time() + 5
        while time.time() < deadline and any(_running(p) for p in pids):
            time.sleep(0.1)
        assert not [p for p in pids if _running(p)], "workers outlived their parent"
    finally:
        for p in pids:
            try:
                os.kill(p, signal.SIGKILL)
            except ProcessLookupError:
                pass
        if proc.poll() is None:
            proc.kill()
