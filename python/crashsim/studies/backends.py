"""Where a study's variants run: a backend, by name. ``"local"`` runs them on this machine
(the batch engine's threads, chunk by chunk; a scene with pedestrians as Scenes),
``"dask"`` on a dask.distributed cluster (crashsim.studies.dask_backend). Both return the
same columns, bit for bit.

A third backend implements :class:`Backend` and is registered with :func:`register_backend`;
``crashsim.sweep``, ``crashsim.monte_carlo``, the sensitivity designs and the CLI's
``--backend`` then take its name, with no change to crashsim.studies.run or the CLI.
"""

from __future__ import annotations

from collections.abc import Callable, Mapping
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any, Protocol

import numpy as np
from numpy.typing import NDArray

from crashsim.errors import StudyError
from crashsim.studies.chunks import chunk_bounds, empty_columns, take_chunk

if TYPE_CHECKING:
    from crashsim.scene import Scene

Array = NDArray[np.float64]

#: What a backend's run returns: the output columns ({name: (n, ...)}, in variant order),
#: the failed variants' errors (crashsim.batch's VariantError, indices into the study), which
#: variants finished, and whether the run was interrupted (Ctrl-C).
BackendResult = tuple[dict[str, np.ndarray], list[Any], NDArray[np.bool_], bool]

#: Variants per batch call on this machine (Ctrl-C keeps the finished chunks).
DEFAULT_CHUNK = 256


@dataclass(frozen=True)
class Variants:
    """What a backend runs: the ``n`` variants of ``scene`` given by the engine's
    ``overrides`` ({path: (n, ...) arrays, SI}), each run with ``options`` (the batch's
    duration, dt, until and max_impacts); where and how: ``client`` (a scheduler, for a
    backend that takes one), ``threads`` (None: every core), ``chunk_size`` (None: the
    backend's own), and ``progress(done)`` to call as variants finish."""

    scene: Scene
    overrides: Mapping[str, Array]
    n: int
    options: Mapping[str, Any]
    client: Any
    threads: int | None
    chunk_size: int | None
    progress: Callable[[int], None]


class Backend(Protocol):
    """A place to run a study's variants."""

    #: The name studies and the CLI's ``--backend`` give.
    name: str
    #: Whether it runs scenes with pedestrians (their variants run as Scenes, whose
    #: trajectories give the person's figures, not through the batch engine).
    runs_people: bool
    #: Whether it takes a scheduler (the ``client`` argument; the CLI's ``--scheduler``).
    takes_scheduler: bool

    def check(self) -> None:
        """Raises StudyError saying what is missing when it cannot run here."""

    def run(self, v: Variants) -> BackendResult:
        """Runs the variants ``v``, in any order, returning them in variant order."""
        ...


class LocalBackend:
    """This machine: run_batch over chunks of ``chunk_size`` variants (256 by default), in
    variant order; a scene with pedestrians as Scenes (crashsim.studies.scene_runs)."""

    name = "local"
    runs_people = True
    takes_scheduler = False

    def check(self) -> None:
        return None

    def run(self, v: Variants) -> BackendResult:
        if v.scene.pedestrians:
            from crashsim.studies.scene_runs import run_scenes

            return run_scenes(v.scene, v.overrides, v.n, v.options, v.threads, v.progress)
        from crashsim.batch import run_batch

        scene, overrides, n, options, progress = v.scene, v.overrides, v.n, v.options, v.progress

        columns: dict[str, np.ndarray] = {}
        errors: list[Any] = []
        finished = np.zeros(n, dtype=bool)
        interrupted = False
        try:  # Ctrl-C anywhere in the loop ends it with the chunks taken so far
            for start, stop in chunk_bounds(n, v.chunk_size or DEFAULT_CHUNK):
                part = {k: a[start:stop] for k, a in overrides.items()}
                b = run_batch(
                    scene, part, n=stop - start, threads=v.threads,
                    progress=lambda done, _m, s=start: progress(s + done), **options,
                )
                take_chunk(columns, finished, errors, b, start, n)
                if b.interrupted:
                    interrupted = True
                    break
        except KeyboardInterrupt:
            interrupted = True
        if not columns:  # interrupted before the first chunk returned: empty columns
            columns = empty_columns(scene, n, int(options["max_impacts"]))
        return columns, errors, finished, interrupted


class DaskBackend:
    """A dask.distributed cluster (crashsim.studies.dask_backend, imported only when used:
    dask is an optional dependency)."""

    name = "dask"
    runs_people = False
    takes_scheduler = True

    def check(self) -> None:
        from crashsim.studies.dask_backend import require_distributed

        require_distributed()

    def run(self, v: Variants) -> BackendResult:
        from crashsim.studies.dask_backend import run_dask

        return run_dask(
            v.scene, v.overrides, v.n, v.options, client=v.client, chunk_size=v.chunk_size,
            progress=v.progress, threads=v.threads,
        )


_BACKENDS: dict[str, Backend] = {b.name: b for b in (LocalBackend(), DaskBackend())}


def register_backend(backend: Backend) -> None:
    """Makes ``backend`` available to studies and the CLI by its name (a new name, or the
    same object again)."""
    name = getattr(backend, "name", None)
    if not isinstance(name, str) or not name:
        raise StudyError("a backend needs a name (a non-empty str attribute `name`)")
    missing = [a for a in ("runs_people", "takes_scheduler", "check", "run")
               if not hasattr(backend, a)]
    if missing:
        raise StudyError(f"backend {name!r} lacks {', '.join(missing)} (see Backend)")
    if _BACKENDS.get(name, backend) is not backend:
        raise StudyError(f"a backend named {name!r} is already registered")
    _BACKENDS[name] = backend


def backend_names() -> list[str]:
    """The registered backends' names, "local" first."""
    return list(_BACKENDS)


def get_backend(name: Any) -> Backend:
    """The backend named ``name``; StudyError for another name."""
    backend = _BACKENDS.get(name) if isinstance(name, str) else None
    if backend is None:
        names = [f'"{k}"' for k in _BACKENDS]
        known = " or ".join([", ".join(names[:-1]), names[-1]] if len(names) > 1 else names)
        raise StudyError(f"backend = {name!r} is unknown: use {known}")
    return backend
