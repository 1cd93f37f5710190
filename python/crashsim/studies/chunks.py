"""A study's variants in chunks, for the local and the Dask backends alike: the chunk
bounds, a chunk's columns placed into the study's, its error messages renumbered, and the
empty columns of a study stopped before any chunk returned."""

from __future__ import annotations

from collections.abc import Mapping
from typing import TYPE_CHECKING

import numpy as np

if TYPE_CHECKING:
    from crashsim.scene import Scene


def chunk_bounds(n: int, size: int) -> list[tuple[int, int]]:
    return [(s, min(s + size, n)) for s in range(0, n, size)]


def renumbered(message: str, index: int, start: int) -> str:
    """A chunk's "variant i: ..." renumbered to the study's variant."""
    prefix = f"variant {index}: "
    if start and message.startswith(prefix):
        return f"variant {index + start}: " + message[len(prefix):]
    return message


def place_chunk(columns: dict[str, np.ndarray], chunk: Mapping[str, np.ndarray], start: int,
           n: int) -> None:
    for k, v in chunk.items():
        if k not in columns:
            fill = -1 if v.dtype.kind in "iu" else np.nan
            columns[k] = np.full(n, fill, dtype=v.dtype)
        columns[k][start:start + v.size] = v


def empty_columns(scene: Scene, n: int, max_impacts: int) -> dict[str, np.ndarray]:
    from crashsim.batch import run_batch

    b = run_batch(scene, None, n=0, duration=1.0, dt=1e-3, max_impacts=max_impacts)
    return {k: np.full(n, -1 if v.dtype.kind in "iu" else np.nan, dtype=v.dtype)
            for k, v in b.columns.items()}
