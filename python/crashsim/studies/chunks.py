"""A study's variants in chunks, for the local and the Dask backends alike: the chunk
bounds (fixed, or shrinking towards the end for workers that run chunks side by side), a
chunk taken into the study whole (its columns, finished flags and errors, even under
Ctrl-C), and the empty columns of a study stopped before any chunk returned (a chunk's errors
move to the study's variants by ``VariantError.shifted``)."""

from __future__ import annotations

import contextlib
import math
import signal
import threading
from collections.abc import Iterator, Mapping
from typing import TYPE_CHECKING, Any

import numpy as np

if TYPE_CHECKING:
    from crashsim.batch import BatchResult
    from crashsim.scene import Scene


def chunk_bounds(n: int, size: int) -> list[tuple[int, int]]:
    return [(s, min(s + size, n)) for s in range(0, n, size)]


def shrinking_bounds(n: int, size: int, workers: int) -> list[tuple[int, int]]:
    """Chunks for ``workers`` running side by side, taken in order as each worker frees up:
    ``size`` variants, and once fewer than ``2 workers size`` are left, a quarter of what is
    left per worker (at least ``size / 32``, at least 1), so the workers finish together: with
    equal chunks the last one ran on one worker while the others waited (up to a chunk's time,
    11 s of 54 s for 1,000 variants of the 20k two-sedan scene on 2 workers)."""
    smallest = max(1, math.ceil(size / 32))
    bounds = []
    start = 0
    while start < n:
        s = max(smallest, min(size, math.ceil((n - start) / (2 * workers))))
        bounds.append((start, min(n, start + s)))
        start += s
    return bounds


def place_chunk(columns: dict[str, np.ndarray], chunk: Mapping[str, np.ndarray], start: int,
           n: int) -> None:
    for k, v in chunk.items():
        if k not in columns:
            fill = -1 if v.dtype.kind in "iu" else np.nan
            columns[k] = np.full(n, fill, dtype=v.dtype)
        columns[k][start:start + v.size] = v


@contextlib.contextmanager
def interrupt_deferred() -> Iterator[None]:
    """Ctrl-C (SIGINT) during the block is raised when the block ends, as the handler in place
    before it would have raised it then, so the block's bookkeeping is never left half done
    (a study's columns written for a chunk whose finished flags were not). On the main thread
    only (Python delivers signals there); elsewhere the block runs as it is."""
    if threading.current_thread() is not threading.main_thread():
        yield
        return
    caught: list[int] = []
    previous = signal.signal(signal.SIGINT, lambda signum, _frame: caught.append(signum))
    try:
        yield
    finally:
        signal.signal(signal.SIGINT, previous)
        if caught:
            signal.raise_signal(signal.SIGINT)  # to the handler before: KeyboardInterrupt


def take_chunk(columns: dict[str, np.ndarray], finished: np.ndarray, errors: list[Any],
               chunk: BatchResult, start: int, n: int) -> None:
    """Takes a chunk of variants ``start..`` (of ``n``) into the study's columns, finished
    flags and errors (shifted to the study's variant numbers), all three or, under Ctrl-C,
    all three and then KeyboardInterrupt (:func:`interrupt_deferred`): a study interrupted
    here keeps the chunk it was taking (before, the interrupt could leave the study's loop
    between them and the whole study was lost)."""
    with interrupt_deferred():
        place_chunk(columns, chunk.columns, start, n)
        finished[start:start + len(chunk.finished)] = chunk.finished
        errors.extend(e.shifted(start) for e in chunk.errors)


def empty_columns(scene: Scene, n: int, max_impacts: int) -> dict[str, np.ndarray]:
    from crashsim.batch import run_batch

    b = run_batch(scene, None, n=0, duration=1.0, dt=1e-3, max_impacts=max_impacts)
    return {k: np.full(n, -1 if v.dtype.kind in "iu" else np.nan, dtype=v.dtype)
            for k, v in b.columns.items()}
