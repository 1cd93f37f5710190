"""The Dask backend of a study (``backend="dask"``): the same batch, run on a dask.distributed
cluster.

- ``client=None``: a LocalCluster of worker processes on this machine (one per core, or
  ``threads`` of them; one thread each; loopback only, no dashboard), closed afterwards.
  ``client="tcp://host:8786"``: a Client of that scheduler (closed afterwards, the cluster
  left running). ``client=<Client>``: used as it is and left open.
- The base scene, meshes included, is scattered to every worker once
  (``client.scatter(scene, broadcast=True)``); each task is one chunk of variants: the
  chunk's slice of the override arrays (a few hundred bytes per variant), run by
  ``crashsim.batch.run_batch`` with one thread on the worker. The chunks shrink towards the
  end (``chunks.shrinking_bounds``; ``chunk_size`` fixes them), so the workers finish
  together: the scheduler hands out the chunks in order, and an idle worker steals the small
  last ones.
- Results are assembled by chunk index in variant order. A worker that dies mid-study
  loses its chunks; the scheduler runs them again on another worker, and each chunk's result
  is taken once (the first to arrive), so nothing is lost and nothing is counted twice. Every
  variant's figures are those of the local backend, bit for bit (the batch's results do
  not depend on the thread or the process that runs them; floats travel pickled, exactly).
"""

from __future__ import annotations

import math
import os
from collections.abc import Callable, Mapping
from typing import TYPE_CHECKING, Any

import numpy as np
from numpy.typing import NDArray

from crashsim.errors import StudyError

if TYPE_CHECKING:
    from crashsim.batch import BatchResult
    from crashsim.scene import Scene

__all__ = ["local_cluster", "require_distributed", "run_dask"]

Array = NDArray[np.float64]

MAX_CHUNK = 256  # variants per task at most
TASKS_PER_WORKER = 4  # full-size chunks per worker (when n allows), then shrinking ones
CONNECT_TIMEOUT = "10s"  # how long to try reaching a scheduler given by its address


def require_distributed() -> None:
    """StudyError, before any work, when dask.distributed cannot be imported (the study extra
    installs it)."""
    try:
        import distributed  # noqa: F401
    except ImportError as e:
        raise StudyError(
            f"the Dask backend needs dask.distributed, which cannot be imported ({e}): "
            "pip install 'dask[distributed]' (or 'crashsim[study]'), or run the study on this "
            'machine (backend "local")'
        ) from None


def local_cluster(n_workers: int | None = None) -> Any:
    """A LocalCluster on this machine: ``n_workers`` worker processes (default: the cores),
    one thread each, listening on the loopback only (the HTTP server on a free port). Each
    worker imports crashsim as it starts (``preload``), so the cluster is ready when it
    returns: the import (trimesh, scipy) took 2.3 s in one process and 5.2 s in two workers
    at once on the shared 2-core machine (load 4.5-5), in the first study's first chunks
    otherwise."""
    from distributed import LocalCluster

    return LocalCluster(
        n_workers=n_workers or os.cpu_count() or 1,
        threads_per_worker=1,
        processes=True,
        host="127.0.0.1",
        dashboard_address="127.0.0.1:0",  # its HTTP server (health, metrics) on a free port
        preload=["crashsim.batch"],
    )


def _run_chunk(
    scene: Scene, overrides: Mapping[str, Array], n: int, options: Mapping[str, Any]
) -> BatchResult:
    """One task: a chunk of variants on a worker (one thread: the worker's)."""
    from crashsim.batch import run_batch

    return run_batch(scene, overrides, n=n, threads=1, **options)


def _connect(client: Any, threads: int | None) -> tuple[Any, list[Any]]:
    """(client, what to close afterwards)."""
    from distributed import Client

    if client is None:
        cluster = local_cluster(threads)
        c = Client(cluster)
        return c, [c, cluster]
    if isinstance(client, str):
        try:
            c = Client(client, timeout=CONNECT_TIMEOUT)
        except OSError as e:
            raise StudyError(
                f"cannot reach the Dask scheduler at {client!r}: {e}; start one (dask scheduler) "
                "or give backend='local'"
            ) from None
        return c, [c]
    if not isinstance(client, Client):
        raise StudyError(
            f"client must be a dask.distributed Client, a scheduler address or None, got "
            f"{type(client).__name__}"
        )
    return client, []


def run_dask(
    scene: Scene,
    overrides: Mapping[str, Array],
    n: int,
    options: Mapping[str, Any],
    *,
    client: Any = None,
    chunk_size: int | None = None,
    progress: Callable[[int], None] | None = None,
    threads: int | None = None,
) -> tuple[dict[str, np.ndarray], list[Any], NDArray[np.bool_], bool]:
    """Run the variants on a Dask cluster: (columns, errors, finished, interrupted) in variant
    order, as the local backend returns them."""
    from distributed import as_completed

    from crashsim.studies.chunks import (
        chunk_bounds,
        empty_columns,
        shrinking_bounds,
        take_chunk,
    )

    c, owned = _connect(client, threads)
    columns: dict[str, np.ndarray] = {}
    errors: list[Any] = []
    finished = np.zeros(n, dtype=bool)
    interrupted = False
    futures: dict[Any, int] = {}
    try:
        workers = max(1, len(c.scheduler_info().get("workers", {})))
        if chunk_size:
            chunks = chunk_bounds(n, chunk_size)
        else:
            size = max(1, min(MAX_CHUNK, math.ceil(n / (TASKS_PER_WORKER * workers))))
            chunks = shrinking_bounds(n, size, workers)
        shared = c.scatter(scene, broadcast=True, hash=False)  # the meshes: once per worker
        for k, (start, stop) in enumerate(chunks):
            part = {key: np.ascontiguousarray(v[start:stop]) for key, v in overrides.items()}
            f = c.submit(_run_chunk, shared, part, stop - start, dict(options), pure=False)
            futures[f] = k
        taken: set[int] = set()
        done = 0
        try:
            for f in as_completed(list(futures)):
                k = futures[f]
                if k in taken:  # a chunk is counted once, whichever run of it arrives
                    continue
                b = f.result()
                start, stop = chunks[k]
                take_chunk(columns, finished, errors, b, start, n)
                taken.add(k)
                done += stop - start
                if progress is not None:
                    progress(done)
        except KeyboardInterrupt:
            interrupted = True
            c.cancel([f for f, k in futures.items() if k not in taken])
        c.cancel([shared])
    finally:
        for thing in owned:
            thing.close()
    if not columns:
        columns = empty_columns(scene, n, int(options["max_impacts"]))
    return columns, errors, finished, interrupted
