"""A study's variants run as Scenes on this machine's threads (``Scene.run``), not through the
batch: what a scene with pedestrians needs (docs/studies.md, "Pedestrians"), and what a fit
whose evidence needs each run's Result uses (crashsim.studies.fit.problem). Each variant's
row is crashsim.studies.pedestrians' columns."""

from __future__ import annotations

import concurrent.futures
import os
import threading
import warnings
from collections.abc import Callable, Mapping
from typing import TYPE_CHECKING, Any

import numpy as np
from numpy.typing import NDArray

from crashsim.batch import VariantError
from crashsim.errors import CrashsimError
from crashsim.studies.chunks import interrupt_deferred
from crashsim.studies.paths import apply_overrides
from crashsim.studies.pedestrians import columns_of, empty_columns

if TYPE_CHECKING:
    from crashsim.result import Result
    from crashsim.scene import Scene

__all__ = ["RECORD_INTERVAL", "run_one", "run_scenes"]

Array = NDArray[np.float64]

RECORD_INTERVAL = 2e-3  # s between kept samples of a study's runs (first overlaps are kept)


class _Stopped(Exception):
    """Ctrl-C: the run in a worker thread stops."""


def run_one(scene: Scene, options: Mapping[str, Any], stop: threading.Event | None = None
            ) -> Result:  # fmt: skip
    """Run a variant's scene for ``options["duration"]`` s at ``options["dt"]`` (with
    ``options["until"] == "rest"``: until every body rests, at most that long), samples kept
    every RECORD_INTERVAL (at least every step; first overlaps and exchanges always)."""

    def check(_t: float) -> None:
        if stop is not None and stop.is_set():
            raise _Stopped

    dt, duration = float(options["dt"]), float(options["duration"])
    record = max(dt, RECORD_INTERVAL)
    if options.get("until") == "rest":
        return scene.run(dt=dt, until="rest", max_duration=duration, record_interval=record,
                         progress=check)  # fmt: skip
    return scene.run(duration, dt=dt, record_interval=record, progress=check)


def run_scenes(
    scene: Scene,
    overrides: Mapping[str, Array],
    n: int,
    options: Mapping[str, Any],
    threads: int | None,
    bar: Callable[[int], None],
) -> tuple[dict[str, np.ndarray], list[Any], NDArray[np.bool_], bool]:
    """Every variant as a Scene (paths.apply_overrides) run on ``threads`` threads (None:
    one per core), its row from :func:`columns_of`: (columns, errors as
    crashsim.batch.VariantError, finished, interrupted), as the batch's chunks give them."""
    max_impacts = int(options["max_impacts"])
    columns = empty_columns(scene, n, max_impacts)
    finished = np.zeros(n, dtype=bool)
    errors: list[VariantError] = []
    stop = threading.Event()

    def one(i: int) -> dict[str, float] | VariantError | None:
        try:
            variant = apply_overrides(scene, overrides, i)
            return columns_of(run_one(variant, options, stop), variant, max_impacts)
        except _Stopped:
            return None
        except CrashsimError as e:
            return VariantError.of(i, e)

    workers = (os.cpu_count() or 1) if threads is None else threads
    pool = concurrent.futures.ThreadPoolExecutor(max_workers=max(1, min(workers, n)))
    interrupted = False
    done = 0
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # per-run warnings (dt_p, rest) would repeat n times
        futures = {pool.submit(one, i): i for i in range(n)}
        try:
            for f in concurrent.futures.as_completed(futures):
                i, out = futures[f], f.result()
                if isinstance(out, VariantError):
                    errors.append(out)
                elif out is not None:
                    with interrupt_deferred():  # the row and its flag together
                        for k, v in out.items():
                            columns[k][i] = v
                        finished[i] = True
                done += 1
                bar(done)
        except KeyboardInterrupt:
            stop.set()
            interrupted = True
        finally:
            pool.shutdown(wait=True, cancel_futures=True)
    return columns, errors, finished, interrupted
