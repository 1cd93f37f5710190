"""What an input path names when it is there but is not a regular file: the one check the
readers of input files (scene files, meshes, terrains, reports) make before opening one.
Opening a named pipe waits for a writer and a character device such as /dev/zero never ends,
so the kind is read with ``os.stat`` and nothing is opened."""

from __future__ import annotations

import os
import stat
from pathlib import Path

__all__ = ["special_file"]

_KINDS = (
    (stat.S_ISDIR, "a folder"),
    (stat.S_ISFIFO, "a named pipe (FIFO)"),
    (stat.S_ISCHR, "a character device"),
    (stat.S_ISBLK, "a block device"),
    (stat.S_ISSOCK, "a socket"),
)


def special_file(path: str | os.PathLike[str]) -> str | None:
    """What ``path`` is when it exists but is not a regular file ("a folder", "a named pipe
    (FIFO)", "a character device (a link to /dev/zero)", ...), for a message "... is {kind},
    not a file"; None for a regular file (or a link to one) and for a path where nothing is
    (the caller says that in its own words)."""
    p = Path(path)
    try:
        mode = p.stat().st_mode  # follows links
    except OSError:
        return None  # nothing there, or out of reach: opening it says why
    if stat.S_ISREG(mode):
        return None
    kind = next((name for test, name in _KINDS if test(mode)), "a special file")
    if p.is_symlink():
        kind += f" (a link to {os.path.realpath(p)})"
    return kind
