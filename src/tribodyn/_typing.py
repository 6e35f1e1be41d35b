"""Type aliases of the public API (annotations only; no behaviour)."""

from __future__ import annotations

import os
from typing import TypeAlias

from numpy.typing import ArrayLike

__all__ = ["ArrayLike", "PathLike"]

#: A file or folder name.
PathLike: TypeAlias = "str | os.PathLike[str]"
