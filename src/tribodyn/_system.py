"""Operating-system helpers shared by the writers and the process pools.

* :func:`new_dir` and :func:`new_file` create a folder or file under a fresh unique name
  with the permissions the user's umask gives (``0o777``/``0o666`` masked), unlike
  :func:`tempfile.mkdtemp`/``mkstemp``, which always use 0700/0600 and would leave
  results readable by their owner alone once renamed into place.
* :func:`exit_with_parent` makes a pool worker end when the process that started it
  dies (even by SIGKILL, which runs no clean-up code): on Linux the kernel sends it
  SIGKILL (``prctl(PR_SET_PDEATHSIG)``), and everywhere a daemon thread checks once per
  ``WATCH_INTERVAL`` seconds whether its parent has changed (the orphan was re-parented)
  or the starting process no longer exists.
"""

from __future__ import annotations

import os
import secrets
import signal
import sys
import threading
import time
from pathlib import Path

__all__ = ["new_dir", "new_file", "exit_with_parent", "WATCH_INTERVAL"]

#: Period of the parent check of a pool worker [s].
WATCH_INTERVAL = 0.5
_PR_SET_PDEATHSIG = 1  # <linux/prctl.h>


def new_dir(parent: Path, prefix: str) -> Path:
    """Create ``parent/PREFIX<random>`` (mode 0o777 minus the umask) and return it."""
    for _ in range(100):
        p = Path(parent) / f"{prefix}{secrets.token_hex(4)}"
        try:
            os.mkdir(p, 0o777)
        except FileExistsError:
            continue
        return p
    raise FileExistsError(f"no free name {prefix}… in {parent}")


def new_file(parent: Path, prefix: str, suffix: str = "") -> tuple[int, Path]:
    """Create ``parent/PREFIX<random>SUFFIX`` exclusively (mode 0o666 minus the umask);
    return its open descriptor (write-only) and path."""
    flags = os.O_WRONLY | os.O_CREAT | os.O_EXCL | getattr(os, "O_CLOEXEC", 0)
    for _ in range(100):
        p = Path(parent) / f"{prefix}{secrets.token_hex(4)}{suffix}"
        try:
            return os.open(p, flags, 0o666), p
        except FileExistsError:
            continue
    raise FileExistsError(f"no free name {prefix}…{suffix} in {parent}")


def _alive(pid: int) -> bool:
    try:
        os.kill(pid, 0)
    except ProcessLookupError:
        return False
    except PermissionError:
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
        return os.getppid() != parent or not _alive(starter)

    if gone():  # the parent died before the signal was armed
        os._exit(1)

    def watch() -> None:
        while True:
            time.sleep(WATCH_INTERVAL)
            if gone():
                os._exit(1)

    threading.Thread(target=watch, name="tribodyn-parent-watch", daemon=True).start()
