"""The small helpers every part of the scene-file reader (crashsim.io.scenefile and its
scene_vehicles, scene_towing and scene_bodies) shares: an engine's refusal as an error at a
key, refused keys, optional arrays of tables, and an input file named by a key. It imports
none of them.
"""

from __future__ import annotations

from collections.abc import Callable
from pathlib import Path
from typing import Any

from crashsim.errors import CrashsimError
from crashsim.filekind import special_file
from crashsim.io.tomlvalues import SceneFileError, _Table


def _wrap(t: _Table, k: str | None, action: Callable[[], Any]) -> Any:
    """Run action; a crashsim input error becomes a SceneFileError at key k of table t."""
    try:
        return action()
    except SceneFileError:
        raise
    except CrashsimError as e:
        if not isinstance(e, ValueError):  # a SimulationError is not the file's fault
            raise
        raise t.error(k, str(e)) from e


def _reject(t: _Table, keys: tuple[str, ...], why: str) -> None:
    for k in keys:
        if t.has(k):
            t.fail(k, why)


def _input_file(where: _Table, key: str, name: str, base: Path, what: str) -> Path:
    """The file ``name`` (relative to the scene file's folder ``base``) that a ``what`` key
    names, checked to be a file there (a folder, a named pipe or a device is not read)."""
    path = Path(name).expanduser()
    path = path if path.is_absolute() else base / path
    kind = special_file(path)
    if kind is not None:
        where.fail(key, f'{what} file "{name}" is {kind}, not a file (at {path.resolve()})')
    if not path.is_file():
        where.fail(
            key,
            f'{what} file "{name}" does not exist (looked for {path.resolve()}); paths are '
            "relative to the scene file",
        )
    return path


def _rows(t: _Table, k: str, keys: tuple[str, ...]) -> list[_Table]:
    return t.tables(k, keys) if t.has(k) else []
