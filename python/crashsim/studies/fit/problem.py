"""The fit's problem: candidates (rows of unknowns, SI) run, through the batch engine or as
Scenes on threads, to residual vectors in tolerances (cached, the best kept); the progress
line; the unknowns' and the start's checks."""

from __future__ import annotations

import concurrent.futures
import math
import os
import sys
import threading
import time
import warnings
from collections.abc import Callable, Mapping, Sequence
from typing import TYPE_CHECKING, Any

import numpy as np
from numpy.typing import NDArray

from crashsim.errors import CrashsimError, StudyError
from crashsim.studies import paths
from crashsim.studies.evidence import MISSING, Evidence, FitError

if TYPE_CHECKING:
    from crashsim.result import Result
    from crashsim.scene import Scene

Array = NDArray[np.float64]


class _Interrupted(Exception):
    """Ctrl-C during an evaluation: the fit stops with the best so far."""


class _Problem:
    """Evaluates candidates (rows of unknowns, SI) to residual vectors in tolerances."""

    def __init__(
        self,
        scene: Scene,
        names: list[str],
        evidence: list[Evidence],
        labels: list[str],
        run: dict[str, Any],
        threads: int | None,
        progress: Callable[[int, float], None] | None,
    ) -> None:
        self.scene, self.names, self.evidence, self.labels = scene, names, evidence, labels
        self.run_kw, self.threads, self.progress = run, threads, progress
        self.sizes = [e.size for e in evidence]
        self.m = sum(self.sizes)
        # a pedestrian's own paths rebuild it: never the batch's override arrays
        self.use_result = any(e.uses_result for e in evidence) or any(
            paths.parse_path(scene, n).kind in paths.PEDESTRIAN_KINDS for n in names)
        self.max_impacts = max([1] + [int(getattr(e, "impact", 1)) for e in evidence])
        self.cache: dict[bytes, Array] = {}
        self.gave: dict[bytes, NDArray[np.bool_]] = {}  # per candidate: the items its run gave
        self.given = np.zeros(len(evidence), dtype=np.int64)  # per item: the runs that gave it
        self.n_runs = 0
        self.best_x: Array | None = None
        self.best_r: Array | None = None
        self.best = math.inf

    def chi2(self, r: Array) -> float:
        return float(np.dot(r, r))

    def residuals(self, xs: Array) -> Array:
        """(c, m) residuals (in tolerances) of (c, k) candidates; repeated ones from a cache."""
        xs = np.atleast_2d(np.asarray(xs, dtype=np.float64))
        keys = [x.tobytes() for x in xs]
        todo = [i for i, k in enumerate(keys) if k not in self.cache]
        todo = list(dict.fromkeys(todo))
        unique: dict[bytes, int] = {}
        for i in todo:
            unique.setdefault(keys[i], i)
        rows = list(unique.values())
        if rows:
            out, gave = self._run(xs[rows])
            for i, r, g in zip(rows, out, gave, strict=True):
                self.cache[keys[i]] = r
                self.gave[keys[i]] = g
                self.given += g
                c = self.chi2(r)
                if c < self.best:
                    self.best, self.best_x, self.best_r = c, xs[i].copy(), r
            self.n_runs += len(rows)
            if self.progress is not None:
                self.progress(self.n_runs, self.best)
        return np.array([self.cache[k] for k in keys])

    def gave_items(self, x: Array) -> NDArray[np.bool_]:
        """Per evidence item: whether the run of candidate ``x`` (run already) gave it."""
        return self.gave[np.asarray(x, dtype=np.float64).tobytes()]

    def _row(self, diffs: Sequence[Array]) -> tuple[Array, NDArray[np.bool_]]:
        """A run's residuals (in tolerances; MISSING where it gave nothing) from each item's
        difference (in its unit), and per item whether the run gave it."""
        gave = np.array([bool(np.all(np.isfinite(d))) for d in diffs])
        row = np.concatenate([e.normalised(d) for e, d in zip(self.evidence, diffs, strict=True)])
        return row, gave

    def _run(self, xs: Array) -> tuple[Array, NDArray[np.bool_]]:
        """(c, m) residuals of (c, k) candidates and (c, items) whether each run gave each
        item."""
        values = {n: xs[:, j] for j, n in enumerate(self.names)}
        arrays = paths.overrides(self.scene, values, n=len(xs))
        if self.use_result:
            return self._run_results(arrays, len(xs))
        from crashsim.batch import run_batch

        kw = self.run_kw
        duration = kw["max_duration"] if kw["until"] == "rest" else kw["duration"]
        try:
            br = run_batch(self.scene, arrays, duration=duration, dt=kw["dt"], until=kw["until"],
                           threads=self.threads, max_impacts=self.max_impacts)  # fmt: skip
        except KeyboardInterrupt as e:  # pragma: no cover - run_batch keeps Ctrl-C itself
            raise _Interrupted from e
        if br.interrupted:
            raise _Interrupted
        failed = {e.index for e in br.errors}
        out = np.full((len(xs), self.m), MISSING)
        gave = np.zeros((len(xs), len(self.evidence)), dtype=bool)
        for i in range(len(xs)):
            if i in failed or not br.finished[i]:
                continue
            out[i], gave[i] = self._row([e.difference(e.measured(br.columns, i))
                                         for e in self.evidence])  # fmt: skip
        return out, gave

    def run_one(self, scene: Scene, stop: threading.Event | None = None) -> Result:
        kw = self.run_kw

        def check(_t: float) -> None:
            if stop is not None and stop.is_set():
                raise _Interrupted

        with warnings.catch_warnings():
            warnings.simplefilter("ignore")  # the residuals carry what the warnings say
            record: dict[str, float] = {}
            if scene.pedestrians:  # its figures need samples, not every step's
                from crashsim.studies.scene_runs import RECORD_INTERVAL

                record["record_interval"] = max(kw["dt"], RECORD_INTERVAL)
            if kw["until"] == "rest":
                return scene.run(dt=kw["dt"], until="rest", max_duration=kw["max_duration"],
                                 progress=check, **record)  # fmt: skip
            return scene.run(duration=kw["duration"], dt=kw["dt"], progress=check, **record)

    def from_result(self, result: Result) -> tuple[Array, NDArray[np.bool_]]:
        return self._row([e.difference(e.from_result(result)) for e in self.evidence])

    def _run_results(self, arrays: Mapping[str, Array], n: int
                     ) -> tuple[Array, NDArray[np.bool_]]:  # fmt: skip
        stop = threading.Event()

        def one(i: int) -> tuple[Array, NDArray[np.bool_]]:
            try:
                result = self.run_one(paths.apply_overrides(self.scene, arrays, i), stop)
            except CrashsimError:
                return np.full(self.m, MISSING), np.zeros(len(self.evidence), dtype=bool)
            return self.from_result(result)

        workers = (os.cpu_count() or 1) if self.threads is None else self.threads
        pool = concurrent.futures.ThreadPoolExecutor(max_workers=max(1, min(workers, n)))
        try:
            futures = [pool.submit(one, i) for i in range(n)]
            done = [f.result() for f in futures]
            return np.array([r for r, _ in done]), np.array([g for _, g in done])
        except KeyboardInterrupt as e:
            stop.set()
            raise _Interrupted from e
        finally:
            pool.shutdown(wait=True, cancel_futures=True)


class _Progress:
    """A line on stderr: runs made and the best objective so far."""

    def __init__(self) -> None:
        self.last = 0.0

    def __call__(self, runs: int, best: float) -> None:
        now = time.monotonic()
        if now - self.last >= 0.5:
            self.last = now
            sys.stderr.write(f"\rfit: {runs} runs, best chi^2 {best:.4g}   ")
            sys.stderr.flush()

    def close(self) -> None:
        sys.stderr.write("\n")
        sys.stderr.flush()


# -- checks -----------------------------------------------------------------------------------


def _check_unknowns(
    scene: Scene, unknowns: Mapping[str, Any]
) -> tuple[list[str], Array, Array, dict[str, str]]:
    if not isinstance(unknowns, Mapping) or not unknowns:
        raise FitError('give the unknowns as {path: (lo, hi)}, e.g. {"red.speed": (10, 25)}')
    names, lo, hi, units = [], [], [], {}
    for name, bounds in unknowns.items():
        try:
            p = paths.parse_path(scene, name)
        except StudyError as e:
            raise FitError(f"unknown {name!r}: {e}", key=str(name)) from e
        try:
            a, b = (float(v) for v in bounds)
        except (TypeError, ValueError) as e:
            raise FitError(
                f"unknown {name!r}: bounds must be two numbers (lo, hi) in {p.unit}, got "
                f"{bounds!r}",
                key=name,
            ) from e
        if not (math.isfinite(a) and math.isfinite(b)) or a >= b:
            raise FitError(
                f"unknown {name!r}: bounds ({a:g}, {b:g}) {p.unit} need finite lo < hi",
                key=name,
            )
        names.append(p.name)
        lo.append(a)
        hi.append(b)
        units[p.name] = p.unit
    if len(set(names)) != len(names):
        raise FitError("an unknown is given twice")
    paths.overrides(scene, {n: [0.5 * (a + b)] for n, a, b in zip(names, lo, hi, strict=True)},
                    n=1)  # fmt: skip  (conflicting paths: StudyError naming them)
    return names, np.array(lo), np.array(hi), units


def _start(
    scene: Scene, names: list[str], lo: Array, hi: Array, start: Mapping[str, float] | None
) -> Array:
    x0 = np.empty(len(names))
    given = dict(start or {})
    for k in given:
        if k not in names:
            raise FitError(f"start {k!r} is not one of the unknowns ({', '.join(names)})", key=k)
    for j, n in enumerate(names):
        if n in given:
            v = float(given[n])
            if not lo[j] <= v <= hi[j]:
                raise FitError(
                    f"start of {n!r} = {v:g} lies outside its bounds ({lo[j]:g}, {hi[j]:g})",
                    key=n,
                )
        else:
            try:
                v = paths.base_value(scene, n)
            except StudyError:
                v = math.nan
            if not (math.isfinite(v) and lo[j] <= v <= hi[j]):
                v = 0.5 * (lo[j] + hi[j])
        x0[j] = v
    return x0
