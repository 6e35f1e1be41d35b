"""Operating-system helpers of the process pools (files are written by
:mod:`tribodyn._safe_write`).

* :func:`exit_with_parent` makes a pool worker end when the process that started it
  dies (even by SIGKILL, which runs no clean-up code): on Linux the kernel sends it
  SIGKILL (``prctl(PR_SET_PDEATHSIG)``), and everywhere a daemon thread checks once per
  ``WATCH_INTERVAL`` seconds whether its parent has changed (the orphan was re-parented)
  or the starting process no longer exists.
"""

from __future__ import annotations

import os
import signal
import sys
import threading
import time

__all__ = ["exit_with_parent", "pid_alive", "WATCH_INTERVAL"]

#: Period of the parent check of a pool worker [s].
WATCH_INTERVAL = 0.5
_PR_SET_PDEATHSIG = 1  # <linux/prctl.h>


def pid_alive(pid: int) -> bool:
    """Whether a process ``pid`` exists (signal 0; one owned by another user counts)."""
    try:
        os.kill(pid, 0)
    except ProcessLookupError:
        return False
    except PermissionError:  # exists, owned by someone else
        return True
    return True


def exit_with_parent(starter: int) -> None:
    """Pool-worker initializer: end this process when its parent or the process with PID
    ``starter`` (the one that made the pool) dies. Call it first in the worker."""
    parent = os.getppid()
    if sys.platform.startswith("linux"):
        try:
            import ctypes

            libc = ctypes.CDLL(None, use_errno=True)
            libc.prctl(_PR_SET_PDEATHSIG, int(signal.SIGKILL), 0, 0, 0)
        except (OSError, AttributeError):  # no prctl: the thread below still watches
            pass

    def gone() -> bool:
        return os.getppid() != parent or not pid_alive(starter)

    if gone():  # the parent died before the signal was armed
        os._exit(1)

    def watch() -> None:
        while True:
            time.sleep(WATCH_INTERVAL)
            if gone():
                os._exit(1)

    threading.Thread(target=watch, name="tribodyn-parent-watch", daemon=True).start()
