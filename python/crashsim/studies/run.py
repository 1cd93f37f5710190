"""Running a study: sweeps and Monte Carlo over one scene, in chunks through the batch engine
(crashsim.batch.run_batch) on this machine or on a Dask cluster, into a :class:`Study`.

    study = cs.sweep(scene, {"red.speed": cs.studies.linspace(10, 20, 5),
                             "restitution": [0.0, 0.1, 0.2]}, duration=0.5, dt=1e-3)
    study = cs.monte_carlo(scene, {"red.speed": cs.studies.normal(15, 1)}, n=1000, seed=1)
    study.frame                 # pandas DataFrame: one row per variant, inputs then outputs
    study["impact1.red.delta_v"]  # a numpy column
    study.to_parquet("study.parquet"); study.summary()

Inputs are the parameter paths (crashsim.studies.paths; SI: m, m/s, rad, kg, s); outputs are
the batch's columns (m, m/s, s, J; degrees where the name ends ``_deg``): docs/studies.md.
A variant that fails (vehicles overlapping at t = 0, a value the engine refuses) is listed in
``study.errors`` with its inputs; the others finish. Ctrl-C stops the study and returns what
finished (``study.interrupted``; the variants not run have status "not run").
"""

from __future__ import annotations

import math
import sys
from collections.abc import Callable, Mapping
from dataclasses import dataclass, field
from os import PathLike
from typing import TYPE_CHECKING, Any

import numpy as np
from numpy.typing import NDArray

from crashsim.errors import StudyError
from crashsim.studies import design, paths
from crashsim.studies.backends import Variants, get_backend
from crashsim.studies.chunks import empty_columns
from crashsim.studies.distributions import Distribution

if TYPE_CHECKING:
    import pandas as pd

    from crashsim.scene import Scene

__all__ = [
    "MAX_STUDY_BYTES",
    "FailedVariant",
    "Study",
    "UnknownColumnError",
    "check_size",
    "monte_carlo",
    "run_study",
    "sweep",
]

Array = NDArray[np.float64]

OK, FAILED, NOT_RUN = "ok", "failed", "not run"
# Bytes a study's arrays may take at most (inputs, the engine's override arrays, outputs,
# status), unless ``max_study_bytes`` says otherwise; as a run's history limit (1 GiB).
MAX_STUDY_BYTES = 1 << 30


class UnknownColumnError(StudyError, KeyError):
    """A study has no column of that name (a StudyError; a KeyError too, as a lookup by
    name is). The message lists the inputs and some outputs."""

    def __str__(self) -> str:  # the message, not KeyError's quoted repr of it
        return str(self.args[0])


@dataclass(frozen=True)
class FailedVariant:
    """A variant that failed: its ``index``, ``kind`` (the crashsim exception class name,
    e.g. "InitialOverlapError"), ``message`` (naming the variant and its inputs) and
    ``inputs`` ({path: value, SI})."""

    index: int
    kind: str
    message: str
    inputs: dict[str, float]

    def __str__(self) -> str:
        return f"{self.kind}: {self.message}"


def _fmt(x: float) -> str:
    return "auto" if isinstance(x, float) and math.isnan(x) else f"{x:.6g}"


@dataclass(eq=False)
class Study:
    """A study's variants: ``inputs`` ({path: (n,) values, SI}), ``outputs`` ({column: (n,)},
    the batch's columns), ``status`` (n,) ("ok", "failed", "not run"), ``errors`` (the failed
    variants), ``interrupted`` (stopped by Ctrl-C); ``kind`` ("sweep", "montecarlo",
    "one-at-a-time" or "sobol"), ``units`` of the inputs, ``seed`` and ``distributions`` of a
    Monte Carlo study, ``settings`` (duration, dt, until, backend)."""

    kind: str
    inputs: dict[str, Array]
    outputs: dict[str, np.ndarray]
    status: NDArray[np.str_]
    errors: list[FailedVariant] = field(default_factory=list)
    interrupted: bool = False
    units: dict[str, str] = field(default_factory=dict)
    seed: int | None = None
    distributions: dict[str, Distribution] = field(default_factory=dict)
    settings: dict[str, Any] = field(default_factory=dict)

    @property
    def n(self) -> int:
        return int(self.status.size)

    @property
    def ok(self) -> NDArray[np.bool_]:
        """(n,) True where the variant ran to the end."""
        return np.asarray(self.status == OK)

    @property
    def finished(self) -> NDArray[np.bool_]:
        """(n,) True where the variant ran (to the end or into an error)."""
        return np.asarray(self.status != NOT_RUN)

    def __len__(self) -> int:
        return self.n

    def __getitem__(self, name: str) -> np.ndarray:
        """A column (input path or output) as a numpy array."""
        if name in self.inputs:
            return self.inputs[name]
        if name in self.outputs:
            return self.outputs[name]
        raise UnknownColumnError(
            f"no column {name!r}: the inputs are {', '.join(self.inputs)}; outputs such as "
            f"{', '.join(list(self.outputs)[:4])}, ... (study.outputs)"
        )

    @property
    def columns(self) -> list[str]:
        return [*self.inputs, *self.outputs, "status"]

    @property
    def frame(self) -> pd.DataFrame:
        """One row per variant (index ``variant``): the inputs, the outputs, ``status``."""
        import pandas as pd

        data: dict[str, Any] = {**self.inputs, **self.outputs, "status": self.status}
        out = pd.DataFrame(data)
        out.index.name = "variant"
        return out

    def to_csv(self, path: str | PathLike[str]) -> None:
        """Write :attr:`frame` as CSV (a header row of column names, full precision)."""
        self.frame.to_csv(path, float_format="%.17g")

    def to_parquet(self, path: str | PathLike[str]) -> None:
        """Write :attr:`frame` as Parquet (pyarrow), exact floats."""
        self.frame.to_parquet(path, engine="pyarrow")

    def write(self, path: str | PathLike[str]) -> None:
        """CSV or Parquet by the file's suffix (.csv, .parquet, .pq)."""
        suffix = str(path).lower().rsplit(".", 1)[-1]
        if suffix == "csv":
            self.to_csv(path)
        elif suffix in ("parquet", "pq"):
            self.to_parquet(path)
        else:
            raise StudyError(f"{path}: write a .csv or a .parquet file")

    def summary(self, percentiles: tuple[float, ...] | None = None) -> pd.DataFrame:
        """Percentiles of every output (and input) over the variants that ran to the end:
        see crashsim.studies.summary.percentiles."""
        from crashsim.studies.summary import percentiles as table

        return table(self, percentiles)

    def __repr__(self) -> str:
        failed = len(self.errors)
        stop = ", interrupted" if self.interrupted else ""
        return (
            f"Study(kind={self.kind!r}, n={self.n}, inputs={list(self.inputs)}, "
            f"ok={int(self.ok.sum())}, failed={failed}{stop})"
        )


class _Progress:
    """The study's progress: a callable (done, n), a tqdm bar on stderr, or nothing."""

    def __init__(self, progress: bool | Callable[[int, int], None] | None, n: int) -> None:
        self.bar = None
        self.call: Callable[[int, int], None] | None = None
        self.n = n
        if callable(progress):
            self.call = progress
        elif progress:
            from tqdm import tqdm

            self.bar = tqdm(total=n, unit="variant", file=sys.stderr, smoothing=0.1)

    def __call__(self, done: int) -> None:
        if self.bar is not None:
            self.bar.update(done - self.bar.n)
        if self.call is not None:
            self.call(done, self.n)

    def close(self) -> None:
        if self.bar is not None:
            self.bar.close()


def _show_bytes(b: int) -> str:
    return f"{b / (1 << 30):,.2f} GiB" if b >= 1 << 30 else f"{b / (1 << 20):,.1f} MiB"


def check_size(
    scene: Scene, keys: list[str], n: int, max_impacts: int, max_bytes: int | None = None
) -> None:
    """StudyError before anything is allocated when the arrays of a study of ``n`` variants
    varying ``keys`` would take more than ``max_bytes`` (default MAX_STUDY_BYTES): per
    variant 8 bytes an input, the engine's override arrays (as paths.overrides makes them
    for one variant), each output column (as run_batch makes them for none) and the status."""
    if max_bytes is None:
        max_bytes = MAX_STUDY_BYTES
    if isinstance(max_bytes, bool) or not isinstance(max_bytes, int | np.integer) or max_bytes < 1:
        raise StudyError(
            f"max_study_bytes = {max_bytes!r} is invalid: give a positive whole number of "
            "bytes (e.g. 2**30)"
        )
    probe = paths.overrides(scene, {k: np.zeros(1) for k in keys})  # StudyError: a bad path
    if scene.pedestrians:  # its variants run as Scenes: crashsim.studies.pedestrians
        from crashsim.studies.pedestrians import empty_columns as pedestrian_columns

        outputs = pedestrian_columns(scene, 0, max_impacts)
    else:
        outputs = empty_columns(scene, 0, max_impacts)
    status = np.dtype(object).itemsize + np.dtype(f"U{len(NOT_RUN)}").itemsize
    per = (8 * len(keys) + sum(a.nbytes for a in probe.values())
           + sum(c.dtype.itemsize for c in outputs.values()) + status)  # fmt: skip
    need = n * per
    if need <= max_bytes:
        return
    raise StudyError(
        f"the study's {n:,} variants would take {_show_bytes(need)} ({per:,} bytes each: "
        f"{len(keys)} inputs, the engine's overrides, {len(outputs)} outputs, the status), "
        f"more than the study limit of {_show_bytes(int(max_bytes))}: run at most "
        f"{int(max_bytes) // per:,} variants at a time (a smaller n or fewer values to "
        "sweep; Monte Carlo studies with different seeds add up), or raise the limit "
        "(max_study_bytes)"
    )


def _check_options(
    backend: str, duration: float | None, dt: float, until: str | None
) -> tuple[float, float]:
    get_backend(backend).check()
    if until is not None and until != "rest":
        raise StudyError(f'until = {until!r} is unknown: use until="rest" or None')
    if duration is None:
        from crashsim.spec import DEFAULT_MAX_DURATION

        duration = DEFAULT_MAX_DURATION if until == "rest" else 1.0
    for name, x in (("duration", duration), ("dt", dt)):
        number = isinstance(x, int | float) and not isinstance(x, bool)
        if not number or not x > 0 or not math.isfinite(x):
            raise StudyError(f"{name} = {x!r} is invalid: give a time > 0 in s")
    return float(duration), float(dt)


def run_study(
    scene: Scene,
    values: Mapping[str, Array],
    *,
    kind: str,
    duration: float | None = None,
    dt: float = 1e-3,
    until: str | None = None,
    backend: str = "local",
    client: Any = None,
    threads: int | None = None,
    progress: bool | Callable[[int, int], None] | None = True,
    chunk_size: int | None = None,
    max_impacts: int = 2,
    seed: int | None = None,
    distributions: Mapping[str, Distribution] | None = None,
    max_study_bytes: int | None = None,
) -> Study:
    """Run the variants ``values`` ({path: (n,) values, SI}) of ``scene``: the common engine
    of :func:`sweep`, :func:`monte_carlo` and the sensitivity designs."""
    duration, dt = _check_options(backend, duration, dt, until)
    n = int(np.asarray(next(iter(values.values()))).size) if values else 0
    if n < 1:
        raise StudyError("the study has no variants")
    check_size(scene, list(values), n, max_impacts, max_study_bytes)
    overrides = paths.overrides(scene, values)  # StudyError for a path given twice, ...
    if chunk_size is not None and (
        isinstance(chunk_size, bool) or not isinstance(chunk_size, int) or chunk_size < 1
    ):
        raise StudyError(f"chunk_size = {chunk_size!r} is invalid: give an integer >= 1")
    options = {"duration": duration, "dt": dt, "until": until, "max_impacts": max_impacts}
    runner = get_backend(backend)
    if scene.pedestrians and not runner.runs_people:
        raise StudyError(
            f'a study of a scene with pedestrians runs on this machine (backend="local"), not '
            f'on backend "{backend}": its variants run as Scenes, whose trajectories give the '
            "person's figures, not through the batch engine other backends distribute"
        )
    bar = _Progress(progress, n)
    try:
        result = runner.run(Variants(scene, overrides, n, options, client=client,
                                     threads=threads, chunk_size=chunk_size, progress=bar))
    finally:
        bar.close()
    columns, errors, finished, interrupted = result
    status = np.full(n, NOT_RUN, dtype=object)
    status[finished] = OK
    failed = []
    for e in sorted(errors, key=lambda e: e.index):
        status[e.index] = FAILED
        inputs = {k: float(v[e.index]) for k, v in values.items()}
        units = paths.path_units(scene, list(values))
        given = ", ".join(
            f"{k} = {_fmt(x)}" + ("" if units[k] == "1" else f" {units[k]}")
            for k, x in inputs.items()
        )
        failed.append(FailedVariant(e.index, e.kind,
                                    f"variant {e.index} ({given}): {e.within()}", inputs))
    return Study(
        kind=kind,
        inputs={k: np.asarray(v, dtype=np.float64) for k, v in values.items()},
        outputs=columns,
        status=np.asarray(status.astype(str)),
        errors=failed,
        interrupted=interrupted,
        units=paths.path_units(scene, list(values)),
        seed=seed,
        distributions=dict(distributions or {}),
        settings={**options, "backend": backend},
    )


def sweep(
    scene: Scene,
    grid: Mapping[str, Any],
    *,
    duration: float | None = None,
    dt: float = 1e-3,
    until: str | None = None,
    backend: str = "local",
    client: Any = None,
    threads: int | None = None,
    progress: bool | Callable[[int, int], None] | None = True,
    chunk_size: int | None = None,
    max_impacts: int = 2,
    max_study_bytes: int | None = None,
) -> Study:
    """Run the full factorial of ``grid`` ({path: values (a list, or
    crashsim.studies.linspace(start, stop, count))}, SI), the first path varying slowest.

    ``duration`` (s; default 1 s, or 60 s as the longest with ``until="rest"``) and ``dt``
    (s) as for Scene.run. ``backend``: "local" (this machine, ``threads`` threads, None = all
    cores) or "dask" (``client``: a dask.distributed Client, a scheduler address, or None for
    a LocalCluster of this machine's cores, closed afterwards). ``progress``: True draws a bar
    on stderr, a callable gets (done, n), False nothing. ``max_impacts``: impacts reported as
    columns. ``max_study_bytes``: the study's arrays at most (default MAX_STUDY_BYTES, 1 GiB;
    a larger study is refused before its design is made: :func:`check_size`). Returns a
    :class:`Study`."""
    _check_options(backend, duration, dt, until)
    check_size(scene, list(grid), design.grid_size(grid), max_impacts, max_study_bytes)
    values = design.grid(grid)
    return run_study(
        scene, values, kind="sweep", duration=duration, dt=dt, until=until, backend=backend,
        client=client, threads=threads, progress=progress, chunk_size=chunk_size,
        max_impacts=max_impacts, max_study_bytes=max_study_bytes,
    )


def monte_carlo(
    scene: Scene,
    distributions: Mapping[str, Distribution],
    n: int,
    seed: int | None = None,
    *,
    duration: float | None = None,
    dt: float = 1e-3,
    until: str | None = None,
    backend: str = "local",
    client: Any = None,
    threads: int | None = None,
    progress: bool | Callable[[int, int], None] | None = True,
    chunk_size: int | None = None,
    max_impacts: int = 2,
    max_study_bytes: int | None = None,
) -> Study:
    """Run ``n`` variants whose inputs are drawn from ``distributions`` ({path:
    crashsim.studies.uniform / normal / triangular / class_table}, SI) with
    ``numpy.random.default_rng(seed)``: the same seed gives the same variants. Other
    arguments as for :func:`sweep`. StudyError naming the path for an invalid distribution."""
    _check_options(backend, duration, dt, until)
    check_size(scene, list(distributions), design._count(n), max_impacts, max_study_bytes)
    values = design.monte_carlo_sample(distributions, n, seed)
    return run_study(
        scene, values, kind="montecarlo", duration=duration, dt=dt, until=until,
        backend=backend, client=client, threads=threads, progress=progress,
        chunk_size=chunk_size, max_impacts=max_impacts, seed=seed,
        distributions=distributions, max_study_bytes=max_study_bytes,
    )
