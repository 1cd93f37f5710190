"""Fitting the unknowns of a scene to the evidence (the inverse problem; docs/fitting.md).

    import crashsim as cs
    from crashsim.studies.evidence import RestPosition, RestHeading
    fit = cs.fit(scene, {"red.speed": (10, 25), "blue.heading": (1.2, 1.9)},
                 [RestPosition("red", 12.1, 3.4, 0.3), RestHeading("red", 0.61, 0.05)])
    fit.values, fit.ranges, fit.summary(), fit.plot("fit.png")

Unknowns are parameter paths (crashsim.studies.paths, SI) with bounds (lo, hi); the evidence
items (crashsim.studies.evidence) each give a residual divided by their tolerance, so the
objective, the sum of their squares (chi^2), is dimensionless. The solver works in scaled
unknowns u = (x - lo) / (hi - lo) in [0, 1]:

- ``method="least_squares"``: scipy.optimize.least_squares (trust region reflective, bounds)
  from ``start``, with a central-difference Jacobian whose 2k candidates run as one batch;
  its step (``step``, 1e-2 of each range) is wider than the small jumps the residuals of a
  run to rest have (docs/fitting.md), so they do not pass for slopes;
- ``method="global"``: scipy.optimize.differential_evolution over the bounds, each
  generation's population evaluated as one batch (``vectorized``), the first a seeded Latin
  hypercube with the start as one member; it stops when ``patience`` generations gained
  less than 1 in chi^2 at a chi^2 the noise can give (99 % of chi^2 with m - k degrees of
  freedom), then the least-squares solve polishes its best.

Candidates run through the batch engine (crashsim.batch.run_batch) when every item reads
the batch's columns (rest positions and headings, EDR delta-V); an impact point, a tyre mark
or a post-impact speed needs each run's Result, and the candidates then run as Scenes
(paths.apply_overrides, the same variants) on a thread pool. Ctrl-C stops the fit and returns
the best candidate so far (``interrupted``).

The uncertainty, the tolerances taken as one standard deviation (so chi^2 is not rescaled):

- the covariance (J^T J)^-1 of the Jacobian J (residuals in tolerances per SI unit of the
  unknowns) at the optimum, J taken twice: at ``step``, then as the secant over +-1.96
  sigma of each unknown; the 95 % range is +-1.96 sigma (``ranges``, within the bounds);
- importance sampling of the posterior (flat within the bounds, likelihood exp(-chi^2/2)):
  ``samples`` candidates in two batches, from a Student-t on the Jacobian's covariance and
  then on the first batch's weighted covariance; the 95 % range is the weighted 2.5 and
  97.5 % quantiles (``sample_ranges``), which sees nonlinearity and jumps the Jacobian
  does not;
- a scan of the objective along each unknown (the others held at the optimum): where chi^2
  rises by at most 3.84 (``scan_ranges``), narrower than the others when unknowns are
  correlated; for the picture.

The verdict (crashsim.studies.verdict, ``verdict``): chi^2 over the items the fitted run
gives against its degrees of freedom (a p-value), the unknowns at a bound, the items the
fitted run cannot give; fits, poor fit (the ranges widened by the Birge ratio; withheld for
an unknown at a bound) or does not fit (the ranges withheld). Every range above is returned
as the verdict quotes it.
"""

from __future__ import annotations

import concurrent.futures
import math
import os
import sys
import threading
import time
import warnings
from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass, field
from os import PathLike
from typing import TYPE_CHECKING, Any

import numpy as np
from numpy.typing import NDArray

from crashsim.errors import CrashsimError, StudyError
from crashsim.studies import paths
from crashsim.studies.evidence import MISSING, Evidence, FitError, check_evidence
from crashsim.studies.verdict import Verdict, judge

if TYPE_CHECKING:
    from crashsim.result import Result
    from crashsim.scene import Scene

__all__ = ["FitError", "FitResult", "ItemResidual", "fit"]

Array = NDArray[np.float64]
METHODS = ("least_squares", "global")
STEP = 1e-2  # the Jacobian's difference step by default, a fraction of each unknown's range
CHI2_95 = 3.841458820694124  # 95 % quantile of chi^2 with one degree of freedom
XTOL, FTOL, GTOL = 1e-5, 1e-10, 1e-10  # the local solve's tolerances (scaled unknowns)
Z_95 = 1.959963984540054  # two-sided 95 % of the normal distribution


class _Interrupted(Exception):
    """Ctrl-C during an evaluation: the fit stops with the best so far."""


@dataclass(frozen=True)
class ItemResidual:
    """One evidence item at the fit's optimum: ``label``, ``unit``, its ``components``
    (e.g. ("x", "y")), the run's ``measured`` figure and the ``evidence``'s, the
    ``residual`` (measured - evidence, in ``unit``) and ``normalised`` (in tolerances)."""

    label: str
    unit: str
    components: tuple[str, ...]
    measured: Array
    evidence: Array
    residual: Array
    normalised: Array


@dataclass
class FitResult:
    """The answer of :func:`fit` (SI units and radians).

    ``values`` {path: best value}; ``start``, ``bounds``; ``objective`` chi^2 (sum of the
    squared residuals in tolerances); ``residuals`` one ItemResidual per evidence item;
    ``verdict`` (crashsim.studies.verdict.Verdict): fits, poor fit or does not fit, with
    chi^2, its degrees of freedom and p-value, the unknowns at a bound, the evidence the
    fitted run cannot give, and the reasons; every range below is as the verdict lets it be
    quoted: widened by its ``scale`` (a poor fit's Birge ratio), or None where withheld
    (every unknown of a fit that does not fit; an unknown at a bound or not fixed);
    ``covariance`` (k, k) from the Jacobian at the optimum (None when it could not be
    formed), ``sigma`` {path: standard deviation} (inf where the evidence does not fix the
    unknown; both with the tolerances as given, not widened),
    ``ranges`` {path: (lo, hi)} the 95 % range +-1.96 sigma (within the bounds);
    ``joint_ranges`` the same for all unknowns at once: +-sqrt(chi^2_k(0.95)) sigma, the box
    around the joint 95 % ellipsoid (3.08 sigma for four unknowns);
    ``sample_ranges`` {path: (lo, hi)} the 95 % range by importance sampling of the posterior
    (the 2.5 and 97.5 % quantiles; None when not sampled) and ``samples`` its candidates
    (``x``, ``chi2``, ``weight``, ``ess``); ``scan`` {path: (values, chi^2)} the objective
    along each unknown through the optimum, the others held, and ``scan_ranges`` {path: (lo,
    hi)} where it stays within 3.84 of its least (None when not scanned; narrower than the
    others when unknowns are correlated);
    ``result`` the fitted run, ``scene`` the fitted scene; ``n_runs`` runs made;
    ``interrupted`` (Ctrl-C: the best so far), ``message`` the solver's."""

    names: list[str]
    units: dict[str, str]
    values: dict[str, float]
    start: dict[str, float]
    bounds: dict[str, tuple[float, float]]
    objective: float
    residuals: list[ItemResidual]
    covariance: Array | None
    sigma: dict[str, float]
    ranges: dict[str, tuple[float, float] | None]
    joint_ranges: dict[str, tuple[float, float] | None]
    evidence: list[Evidence]
    scene: Scene
    result: Result | None
    method: str
    n_runs: int
    interrupted: bool = False
    message: str = ""
    scan: dict[str, tuple[Array, Array]] | None = None
    scan_ranges: dict[str, tuple[float, float] | None] | None = None
    sample_ranges: dict[str, tuple[float, float] | None] | None = None
    samples: Any = None
    verdict: Verdict | None = None
    elapsed: float = 0.0
    extra: dict[str, Any] = field(default_factory=dict)

    @property
    def x(self) -> Array:
        """The best values as an array in the order of ``names``."""
        return np.array([self.values[n] for n in self.names])

    def summary(self) -> str:
        """The best values with their 95 % ranges, and every item's residual, as text."""
        lines = [
            f"fit ({self.method}): objective chi^2 = {self.objective:.4g} over "
            f"{sum(len(r.normalised) for r in self.residuals)} residuals, {self.n_runs} runs, "
            f"{self.elapsed:.1f} s" + (" -- INTERRUPTED: the best so far" if self.interrupted
                                       else ""),
            "",
            f"{'unknown':<20} {'best':>11} {'95 % (Jacobian)':>21} {'all at once':>21} "
            f"{'95 % (sampling)':>21} {'along it alone':>21}  unit",
        ]

        def span(r: dict[str, tuple[float, float] | None] | None, n: str) -> str:
            v = r.get(n) if r else None
            if v is None:
                return (self.verdict.range_note(n) if r and self.verdict else "") or "-"
            return f"{v[0]:.5g} .. {v[1]:.5g}"

        for n in self.names:
            lines.append(
                f"{n:<20} {self.values[n]:>11.6g} {span(self.ranges, n):>21} "
                f"{span(self.joint_ranges, n):>21} {span(self.sample_ranges, n):>21} "
                f"{span(self.scan_ranges, n):>21}  {self.units[n]}"
            )
        if self.samples is not None:
            lines.append(f"(sampling: {len(self.samples.x)} candidates, effective sample size "
                         f"{self.samples.ess:.0f})")  # fmt: skip
        lines += ["", f"{'evidence':<36} {'component':<13} {'evidence':>10} {'fitted':>10} "
                  f"{'residual':>10} {'/tol':>7}  unit"]  # fmt: skip
        for r in self.residuals:
            for k, c in enumerate(r.components):
                lines.append(
                    f"{r.label:<36} {c or '-':<13} {r.evidence[k]:>10.4g} {r.measured[k]:>10.4g} "
                    f"{r.residual[k]:>10.3g} {r.normalised[k]:>7.2f}  {r.unit}"
                )
        if self.verdict is not None:
            lines += ["", *self.verdict.lines()]
        if self.message:
            lines += ["", f"solver: {self.message}"]
        return "\n".join(lines)

    def __repr__(self) -> str:
        v = ", ".join(f"{n}={self.values[n]:.5g}" for n in self.names)
        said = "" if self.verdict is None else f", {self.verdict.status}"
        return f"FitResult({v}; chi2={self.objective:.4g}{said}, runs={self.n_runs})"

    def plot(
        self,
        path: str | PathLike[str] | None = None,
        units: Mapping[str, tuple[str, float]] | None = None,
    ) -> Any:
        """The fitted run over the evidence (top-down: paths, rest outlines and headings with
        tolerance circles, marks, impact points) and the objective along each unknown around
        the optimum; written to ``path`` (PNG, SVG, PDF) when given. Returns the Figure.
        ``units``: {unknown: (unit name, SI per unit)} to show unknowns in (default SI, angles
        in degrees; ``FitSpec.display_units()`` gives a scene file's)."""
        from crashsim.studies.fitplot import plot_fit

        return plot_fit(self, path, units)

    def to_dict(self) -> dict[str, Any]:
        """The fit as plain data for JSON (SI units and radians, as the attributes): the
        verdict, the best values, bounds, start, sigma, 95 % ranges (Jacobian, all at once,
        sampling, scan: None where the verdict withholds one), the objective, every item's
        residual, the scans, the covariance, the run count and the interrupted flag. A
        number that is not finite (sigma where the evidence does not fix an unknown) is
        None."""

        def num(v: Any) -> float | None:
            v = float(v)
            return v if math.isfinite(v) else None

        def nums(a: Any) -> list[Any]:
            return [num(v) if np.ndim(v) == 0 else nums(v) for v in np.asarray(a, float)]

        def spans(r: dict[str, tuple[float, float] | None] | None) -> Any:
            return None if r is None else {n: None if v is None else nums(v)
                                           for n, v in r.items()}  # fmt: skip

        scan = self.scan
        return {
            "verdict": None if self.verdict is None else self.verdict.to_dict(),
            "method": self.method,
            "unknowns": list(self.names),
            "units": dict(self.units),
            "values": {n: num(v) for n, v in self.values.items()},
            "start": {n: num(v) for n, v in self.start.items()},
            "bounds": {n: nums(b) for n, b in self.bounds.items()},
            "sigma": {n: num(v) for n, v in self.sigma.items()},
            "ranges": spans(self.ranges),
            "joint_ranges": spans(self.joint_ranges),
            "sample_ranges": spans(self.sample_ranges),
            "scan_ranges": spans(self.scan_ranges),
            "objective": num(self.objective),
            "residuals": [
                {
                    "label": r.label,
                    "unit": r.unit,
                    "components": list(r.components),
                    "evidence": nums(r.evidence),
                    "fitted": nums(r.measured),
                    "residual": nums(r.residual),
                    "normalised": nums(r.normalised),
                }
                for r in self.residuals
            ],
            "scan": (
                None
                if scan is None
                else {n: {"values": nums(g), "objective": nums(c)} for n, (g, c) in scan.items()}
            ),
            "covariance": None if self.covariance is None else nums(self.covariance),
            "n_runs": self.n_runs,
            "elapsed": self.elapsed,
            "interrupted": self.interrupted,
            "message": self.message,
        }


# -- the problem ------------------------------------------------------------------------------


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
            if kw["until"] == "rest":
                return scene.run(dt=kw["dt"], until="rest", max_duration=kw["max_duration"],
                                 progress=check)  # fmt: skip
            if scene.pedestrians:  # its figures need samples, not every step's
                from crashsim.studies.pedestrians import RECORD_INTERVAL

                return scene.run(duration=kw["duration"], dt=kw["dt"], progress=check,
                                 record_interval=max(kw["dt"], RECORD_INTERVAL))  # fmt: skip
            return scene.run(duration=kw["duration"], dt=kw["dt"], progress=check)

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


# -- the solvers ------------------------------------------------------------------------------


JUMP = 1.0  # tolerances: a second difference larger than this is a jump, not curvature


def _jacobian(prob: _Problem, u: Array, lo: Array, hi: Array, step: float) -> Array:
    """(m, k) d residual / d u at ``step`` (a fraction of each range); see _differences."""
    return _differences(prob, u, lo, hi, np.full(len(u), step))


def _differences(prob: _Problem, u: Array, lo: Array, hi: Array, steps: Array) -> Array:
    """(m, k) d residual / d u by differences over ``steps`` (scaled) either side of u, the
    point and its 2k neighbours one batch (u itself is usually run already).

    Central differences, except where an unknown's two sides disagree by more than JUMP
    tolerances (the norm of the residuals' second difference): then a jump lies on one side
    (candidates whose run-out differs, e.g. a second contact: chi^2 180 against 7 on either
    side, docs/fitting.md), and the side whose residuals change less is taken. One-sided at
    a bound."""
    k = len(u)
    pts = [u]
    for j in range(k):
        a, b = u.copy(), u.copy()
        a[j] = min(1.0, u[j] + steps[j])
        b[j] = max(0.0, u[j] - steps[j])
        pts += [a, b]
    pts_a = np.array(pts)
    r = prob.residuals(lo + pts_a * (hi - lo))
    r0 = r[0]
    cols = []
    for j in range(k):
        ra, rb = r[1 + 2 * j], r[2 + 2 * j]
        ha, hb = pts_a[1 + 2 * j, j] - u[j], u[j] - pts_a[2 + 2 * j, j]
        if ha <= 0.0 or hb <= 0.0:  # at a bound: the side inside
            cols.append((ra - rb) / (ha + hb))
            continue
        fwd, bwd = (ra - r0) / ha, (r0 - rb) / hb
        if np.linalg.norm(fwd - bwd) * min(ha, hb) > JUMP:
            cols.append(fwd if np.linalg.norm(ra - r0) <= np.linalg.norm(r0 - rb) else bwd)
        else:
            cols.append((ra - rb) / (ha + hb))
    return np.column_stack(cols)


def _least_squares(
    prob: _Problem, u0: Array, lo: Array, hi: Array, step: float, max_nfev: int
) -> tuple[Array, str]:
    from scipy.optimize import least_squares

    def fun(u: Array) -> Array:
        return prob.residuals(lo + u * (hi - lo))[0]

    def jac(u: Array) -> Array:
        return _jacobian(prob, u, lo, hi, step)

    # Tolerances in scaled unknowns (the range = 1): XTOL stops at steps of 1e-5 of a range,
    # far below any figure the evidence fixes; tighter only spends runs on the jumps.
    sol = least_squares(fun, np.clip(u0, 0.0, 1.0), jac=jac, bounds=(0.0, 1.0), method="trf",
                        x_scale=1.0, xtol=XTOL, ftol=FTOL, gtol=GTOL,
                        max_nfev=max_nfev)  # fmt: skip
    return sol.x, str(sol.message)


class _Stall:
    """Differential evolution's callback: stop when the best chi^2 has gained less than
    ``gain`` over the last ``patience`` generations and is at most ``limit`` (a chi^2 the
    evidence's noise can give, so that a search stuck on a plateau of a wrong valley goes
    on); the local solve takes it from there."""

    def __init__(self, patience: int, limit: float, gain: float = 1.0) -> None:
        self.patience, self.limit, self.gain = patience, limit, gain
        self.history: list[float] = []

    def __call__(self, intermediate_result: Any) -> bool:
        self.history.append(float(intermediate_result.fun))
        h, p = self.history, self.patience
        return p > 0 and len(h) > p and h[-p - 1] - h[-1] < self.gain and h[-1] <= self.limit


def _global(
    prob: _Problem,
    u0: Array,
    lo: Array,
    hi: Array,
    seed: int | None,
    popsize: int,
    maxiter: int,
    patience: int,
) -> tuple[Array, str, list[float]]:
    """Differential evolution over the scaled bounds, each generation one batch; the first
    population a Latin hypercube (seeded) with ``u0`` (the start) as one member."""
    from scipy.optimize import differential_evolution
    from scipy.stats import chi2, qmc

    k = len(u0)

    def objective(us: Array) -> Array:  # (k, S) -> (S,)
        r = prob.residuals((lo[:, None] + us * (hi - lo)[:, None]).T)
        return np.einsum("ij,ij->i", r, r)

    rng = np.random.default_rng(seed)
    init = qmc.LatinHypercube(d=k, seed=rng).random(max(5, popsize * k))
    init[0] = np.clip(u0, 0.0, 1.0)
    # 99 % of the chi^2 the noise gives at the optimum (m residuals, k unknowns)
    stall = _Stall(patience, float(chi2.ppf(0.99, max(1, prob.m - k))))
    sol = differential_evolution(objective, [(0.0, 1.0)] * k, vectorized=True,
                                 updating="deferred", maxiter=maxiter, seed=rng,
                                 polish=False, init=init, tol=0.0, atol=0.0,
                                 callback=stall)  # fmt: skip
    return sol.x, f"{sol.message} ({sol.nit} generations)", stall.history


def _covariance(jx: Array) -> tuple[Array | None, Array]:
    """(J^T J)^-1 and the standard deviations of a Jacobian J (residuals in tolerances per SI
    unit); None and inf where the evidence does not fix the unknowns."""
    jtj = jx.T @ jx
    if not np.all(np.isfinite(jtj)):
        return None, np.full(jx.shape[1], math.inf)
    s = np.linalg.svd(jtj, compute_uv=False)
    if s[-1] <= s[0] * 1e-12:
        return None, np.full(jx.shape[1], math.inf)
    cov = np.linalg.inv(jtj)
    return cov, np.sqrt(np.maximum(np.diag(cov), 0.0))


def _uncertainty(
    prob: _Problem, best: Array, lo: Array, hi: Array, step: float
) -> tuple[Array | None, Array]:
    """Covariance (k, k) in SI of the unknowns and sigma (k,) from the Jacobian at ``best``.

    Two batches: central differences at ``step`` (a fraction of each range) give a first
    sigma; the Jacobian is then taken again over +-1.96 sigma of each unknown (at least
    ``step``, at most a quarter of its range): the secant over the width the 95 % range
    itself spans, so that the residuals' small jumps (docs/fitting.md) do not pass for
    slopes (a jump of 0.2 tolerances against the residuals' change of about 2 over the
    secant's half-width)."""
    u = (best - lo) / (hi - lo)
    cov, sigma = _covariance(_jacobian(prob, u, lo, hi, step) / (hi - lo))
    if cov is None:
        return cov, sigma
    steps = np.clip(Z_95 * sigma / (hi - lo), step, 0.25)
    return _covariance(_differences(prob, u, lo, hi, steps) / (hi - lo))


@dataclass(frozen=True)
class _Samples:
    """Importance samples of the posterior around the optimum (see :func:`_sample`)."""

    x: Array  # (n, k) SI, the candidates inside the bounds
    chi2: Array  # (n,)
    weight: Array  # (n,) normalised
    ranges: Array  # (k, 2) the 95 % range of each unknown (2.5 and 97.5 % quantiles)
    ess: float  # effective sample size 1 / sum(w^2)


NU = 4.0  # degrees of freedom of the sampling's Student-t proposals (heavy tails)
SPREAD = 1.5  # the first proposal's scale over the Jacobian's covariance


class _T:
    """A multivariate Student-t (NU degrees of freedom; scipy.stats.multivariate_t) with
    ``mean`` and scale matrix ``scale``; LinAlgError when the scale is not positive
    definite."""

    def __init__(self, mean: Array, scale: Array) -> None:
        from scipy.stats import multivariate_t

        np.linalg.cholesky(scale)  # LinAlgError for a scale that is not positive definite
        self.dist = multivariate_t(loc=mean, shape=scale, df=NU)

    def draw(self, rng: np.random.Generator, n: int) -> Array:
        return np.atleast_2d(self.dist.rvs(size=n, random_state=rng)).reshape(n, -1)

    def log_pdf(self, x: Array) -> Array:
        return np.atleast_1d(self.dist.logpdf(x))


def _sample(
    prob: _Problem, best: Array, cov: Array | None, lo: Array, hi: Array, n: int, seed: int | None
) -> _Samples | None:
    """The posterior of the unknowns given the evidence (flat within the bounds, likelihood
    exp(-chi^2 / 2)) by adaptive importance sampling in two batches of n / 2: candidates from
    a Student-t around ``best`` with SPREAD^2 times the Jacobian's covariance (uniform over
    the bounds when there is none), then from a Student-t with the first batch's weighted
    mean and covariance; every candidate weighted by exp(-chi^2 / 2) over the two proposals'
    mixture density (so a first proposal that missed the posterior's shape, e.g. where the
    Jacobian is off, costs efficiency but no bias). Candidates outside the bounds have
    weight 0 and are not run."""
    k = len(best)
    rng = np.random.default_rng(seed)
    width = (hi - lo) ** 2 / 12.0  # a uniform's variance over the bounds
    first: _T | None = None
    if cov is not None:
        try:
            first = _T(best, cov * SPREAD**2)
        except np.linalg.LinAlgError:
            first = None
    halves = (n // 2, n - n // 2)
    xs: list[Array] = []
    chis: list[Array] = []
    props: list[_T | None] = []
    for r, m in enumerate(halves):
        prop = first if r == 0 else _refit(xs, chis, props, lo, hi, width)
        x = prop.draw(rng, m) if prop is not None else lo + rng.random((m, k)) * (hi - lo)
        x = x[np.all((x >= lo) & (x <= hi), axis=1)]
        res = prob.residuals(x) if len(x) else np.empty((0, prob.m))
        xs.append(x)
        chis.append(np.einsum("ij,ij->i", res, res))
        props.append(prop)
    x, chi = np.concatenate(xs), np.concatenate(chis)
    if len(x) < 2:
        return None
    w = _weights(x, chi, props, halves, lo, hi)
    ranges = np.array([_weighted_quantiles(x[:, j], w, (0.025, 0.975)) for j in range(k)])
    return _Samples(x, chi, w, ranges, float(1.0 / np.sum(w**2)))


def _log_mixture(x: Array, props: list[_T | None], counts: tuple[int, ...], lo: Array,
                 hi: Array) -> Array:  # fmt: skip
    """log of the proposals' mixture density (weights by their draws) at x."""
    parts = []
    for prop, c in zip(props, counts, strict=True):
        if prop is None:  # uniform over the bounds
            d = np.full(len(x), -float(np.sum(np.log(hi - lo))))
        else:
            d = prop.log_pdf(x)
        parts.append(np.log(c / sum(counts)) + d)
    return np.logaddexp.reduce(np.array(parts), axis=0)


def _weights(x: Array, chi: Array, props: list[_T | None], counts: tuple[int, ...], lo: Array,
             hi: Array) -> Array:  # fmt: skip
    log_w = -0.5 * (chi - chi.min()) - _log_mixture(x, props, counts, lo, hi)
    w = np.exp(log_w - log_w.max())
    return w / w.sum()


def _refit(xs: list[Array], chis: list[Array], props: list[_T | None], lo: Array, hi: Array,
           width: Array) -> _T | None:  # fmt: skip
    """The second proposal: a Student-t with the first batch's weighted mean and covariance
    (the first proposal again when the batch is too small to give one)."""
    x, chi = xs[0], chis[0]
    k = x.shape[1]
    if len(x) < 2 * k + 2:
        return props[0]
    w = _weights(x, chi, props[:1], (len(x),), lo, hi)
    mean = w @ x
    d = x - mean
    cov = (w[:, None] * d).T @ d
    cov += np.diag(width * 1e-6)  # keep it positive definite
    try:
        return _T(mean, cov * SPREAD**2)
    except np.linalg.LinAlgError:
        return props[0]


def _weighted_quantiles(v: Array, w: Array, qs: tuple[float, ...]) -> Array:
    """Quantiles of the values v with weights w (normalised), between sorted values."""
    order = np.argsort(v)
    v, w = v[order], w[order]
    cdf = np.cumsum(w) - 0.5 * w
    return np.interp(qs, cdf, v)


def _scan(
    prob: _Problem, names: list[str], best: Array, sigma: Array, lo: Array, hi: Array, points: int
) -> tuple[dict[str, tuple[Array, Array]], dict[str, tuple[float, float]]]:
    """chi^2 along each unknown through ``best`` over +-3 sigma (within the bounds), one batch;
    the range where it stays within 3.84 of its least (the end of the scan where it does not
    rise that far)."""
    k = len(best)
    grids = []
    for j in range(k):
        half = 3.0 * sigma[j] if math.isfinite(sigma[j]) else 0.5 * (hi[j] - lo[j])
        half = min(half, hi[j] - lo[j])
        g = np.linspace(max(lo[j], best[j] - half), min(hi[j], best[j] + half), points)
        grids.append(np.unique(np.r_[g, best[j]]))
    xs = []
    for j in range(k):
        for v in grids[j]:
            x = best.copy()
            x[j] = v
            xs.append(x)
    r = prob.residuals(np.array(xs))
    chi = np.einsum("ij,ij->i", r, r)
    scans: dict[str, tuple[Array, Array]] = {}
    ranges: dict[str, tuple[float, float]] = {}
    at = 0
    for j, n in enumerate(names):
        g = grids[j]
        c = chi[at : at + len(g)]
        at += len(g)
        scans[n] = (g, c)
        i0 = int(np.argmin(c))
        level = c[i0] + CHI2_95

        ranges[n] = (
            _crossing(g, c, i0, level, range(i0 - 1, -1, -1)),
            _crossing(g, c, i0, level, range(i0 + 1, len(g))),
        )
    return scans, ranges


def _crossing(g: Array, c: Array, i0: int, level: float, idx: range) -> float:
    """Where the scan c over the grid g first rises above ``level`` walking from i0 along
    idx (interpolated between the last point inside and the first outside), else the last
    grid value."""
    prev = i0
    for i in idx:
        if c[i] > level:
            f = (level - c[prev]) / (c[i] - c[prev])
            return float(g[prev] + f * (g[i] - g[prev]))
        prev = i
    return float(g[prev])


# -- the verdict ------------------------------------------------------------------------------


def _verdict(
    prob: _Problem,
    items: list[Evidence],
    residuals: list[ItemResidual],
    names: list[str],
    units: dict[str, str],
    best: Array,
    lo: Array,
    hi: Array,
    sigma: Array,
    result: Result | None,
    ran: bool,
    until_rest: bool,
    interrupted: bool,
    lower_sample: float | None,
) -> Verdict:
    """The verdict (crashsim.studies.verdict) on the fit at ``best``: chi^2 over the items
    its run gave; the items it did not give, each with the fitted run's reason and how many
    of the runs tried gave it; a rest item's caveat (a run until rest that ended first)."""
    unavailable: dict[str, str] = {}
    caveats: dict[str, str] = {}
    tested: list[tuple[str, float]] = []
    gave = prob.gave_items(best) if ran else np.zeros(len(items), dtype=bool)
    for i, (e, r) in enumerate(zip(items, residuals, strict=True)):
        if not ran:
            continue
        if not gave[i]:
            why = (e.absent(result) if result is not None else None) or \
                "the fitted run gave no figure for it"  # fmt: skip
            tried = int(prob.given[i])
            unavailable[r.label] = (f"{why} ({tried or 'none'} of the {prob.n_runs} runs tried "
                                    f"gave it)")  # fmt: skip
            continue
        if (until_rest or e.caveat_always) and result is not None:
            caveat = e.caveat(result)
            if caveat is not None:
                caveats[r.label] = caveat
        tested += [(f"{r.label} {c}".rstrip(), float(v))
                   for c, v in zip(r.components, r.normalised, strict=True)]  # fmt: skip
    return judge(tested, names, best, lo, hi, sigma, unavailable=unavailable,
                 caveats=caveats, interrupted=interrupted, lower_sample=lower_sample,
                 units=units)  # fmt: skip


# -- the entry point --------------------------------------------------------------------------


def fit(
    scene: Scene,
    unknowns: Mapping[str, tuple[float, float]],
    evidence: Sequence[Evidence],
    *,
    method: str = "least_squares",
    start: Mapping[str, float] | None = None,
    duration: float | None = None,
    dt: float = 1e-3,
    until: str | None = "rest",
    max_duration: float = 30.0,
    progress: bool | Callable[[int, float], None] = True,
    seed: int | None = 0,
    threads: int | None = None,
    step: float = STEP,
    max_nfev: int = 60,
    popsize: int = 8,
    maxiter: int = 30,
    patience: int = 5,
    samples: int | None = None,
    scan: bool = True,
    scan_points: int = 9,
) -> FitResult:
    """Fit ``unknowns`` {path: (lo, hi)} (SI, crashsim.studies.paths) of ``scene`` to the
    ``evidence`` items (crashsim.studies.evidence); see the module's text.

    ``method``: "least_squares" (from ``start`` {path: value}, default the scene's own value
    when inside the bounds, else the middle) or "global" (differential evolution, seeded by
    ``seed``, ``popsize`` x k candidates a generation, the start one of the first, for at
    most ``maxiter`` generations, stopping early when ``patience`` generations gained less
    than 1 in chi^2 at a chi^2 the evidence's noise can give (0: never early); then least
    squares from its best). Runs:
    ``until="rest"`` (needs a ground) up to ``max_duration`` s, or ``until=None`` for
    ``duration`` s; steps of ``dt`` s; ``threads`` (None: all cores). ``step``: the
    Jacobian's difference step as a fraction of each unknown's range (1e-2: wider than the
    residuals' jumps, docs/fitting.md); ``max_nfev``: the least-squares solve's evaluations
    at most. ``samples``: candidates of the importance sampling of the 95 % ranges (two
    batches; None: 50 k, 0: none). ``scan``: scan the objective along each unknown
    (``scan_points`` per unknown) for the check and the picture. ``progress``: True a line
    on stderr, a callable (runs, best chi^2), or False. FitError (a StudyError) naming the
    unknown or evidence item for bad input."""
    if method not in METHODS:
        raise FitError(f"method {method!r} is unknown: use {' or '.join(METHODS)}")
    if until not in (None, "rest"):
        raise FitError(f'until = {until!r} is unknown: use until="rest" or None')
    if until is None and duration is None:
        raise FitError('give duration (s) for runs of a fixed length, or until="rest"')
    if until == "rest" and scene.ground is None:
        raise FitError('until="rest" needs a ground: give duration and until=None instead')
    if until == "rest" and scene.pedestrians:
        raise FitError(
            'until="rest" never ends for a pedestrian (its segments do not pass the engine\'s '
            "rest test, docs/human.md): give duration= (s, long enough for the person to stop: "
            "a PedestrianRest item says when it did not) and until=None"
        )
    for what, v in (("dt", dt), ("max_duration", max_duration), ("step", step)):
        if not (isinstance(v, int | float) and math.isfinite(v) and v > 0):
            raise FitError(f"{what} = {v!r} must be a number > 0")
    if step > 0.25:
        raise FitError(f"step = {step!r} is a fraction of each unknown's range: give <= 0.25")
    for what, v, least in (("max_nfev", max_nfev, 1), ("popsize", popsize, 1),
                           ("maxiter", maxiter, 1), ("patience", patience, 0),
                           ("scan_points", scan_points, 2),
                           ("samples", 0 if samples is None else samples, 0)):  # fmt: skip
        if isinstance(v, bool) or not isinstance(v, int | np.integer) or v < least:
            raise FitError(f"{what} = {v!r} must be a whole number >= {least}")
    if seed is not None and (isinstance(seed, bool) or not isinstance(seed, int | np.integer)):
        raise FitError(f"seed = {seed!r} must be a whole number or None")
    names, lo, hi, units = _check_unknowns(scene, unknowns)
    items = [evidence] if isinstance(evidence, Evidence) else list(evidence)
    labels = check_evidence(scene, items)
    x0 = _start(scene, names, lo, hi, start)
    bar = _Progress() if progress is True else None
    callback = bar if bar is not None else (progress if callable(progress) else None)
    run = {"duration": duration, "dt": dt, "until": until, "max_duration": max_duration}
    prob = _Problem(scene, names, items, labels, run, threads, callback)
    began = time.monotonic()
    interrupted = False
    message = ""
    best = x0.copy()
    cov: Array | None = None
    sigma = np.full(len(names), math.inf)
    scans = scan_ranges = None
    sampled: _Samples | None = None
    history: list[float] = []
    lower_sample: float | None = None
    n_samples = 50 * len(names) if samples is None else int(samples)
    try:
        u0 = (x0 - lo) / (hi - lo)
        if method == "global":
            u0, m, history = _global(prob, u0, lo, hi, seed, popsize, maxiter, patience)
            message = f"differential evolution: {m}; "
        u, m = _least_squares(prob, u0, lo, hi, step, max_nfev)
        message += f"least squares: {m}"
        best = lo + u * (hi - lo)
        if prob.best_x is not None and prob.best < prob.chi2(prob.residuals(best[None])[0]):
            best = prob.best_x.copy()
        cov, sigma = _uncertainty(prob, best, lo, hi, step)
        if n_samples > 0:
            sampled = _sample(prob, best, cov, lo, hi, n_samples, seed)
            if sampled is not None:
                c_best = prob.chi2(prob.residuals(best[None])[0])
                if sampled.chi2.min() < c_best - 1.0:
                    lower_sample = float(sampled.chi2.min())
                    message += (f"; a sample has chi^2 {lower_sample:.4g} < the "
                                f"optimum's {c_best:.4g}: the solve stopped short")  # fmt: skip
        if scan:
            scans, scan_ranges = _scan(prob, names, best, sigma, lo, hi, scan_points)
    except (_Interrupted, KeyboardInterrupt):
        interrupted = True
        message += "interrupted (Ctrl-C): the best candidate so far"
        if prob.best_x is not None:
            best = prob.best_x.copy()
    finally:
        if bar is not None:
            bar.close()
    values = {n: float(v) for n, v in zip(names, best, strict=True)}
    fitted = paths.with_(scene, values)
    result = None
    residuals: list[ItemResidual] = []
    if not interrupted:
        try:
            result = prob.run_one(fitted)
        except CrashsimError:
            result = None
    ran = not interrupted or prob.best_x is not None  # best is a candidate that ran
    r_best = prob.residuals(best[None])[0] if ran else np.full(prob.m, MISSING)
    at = 0
    for e, label in zip(items, labels, strict=True):
        nr = r_best[at : at + e.size]
        at += e.size
        if result is not None:
            measured = e.from_result(result)
            diff = e.difference(measured)
        else:
            diff = nr * float(e.tolerance)  # type: ignore[attr-defined]
            measured = e.target() + diff
        residuals.append(ItemResidual(label, e.unit, e.components, np.asarray(measured, float),
                                      e.target(), np.asarray(diff, float), nr))  # fmt: skip
    verdict = _verdict(prob, items, residuals, names, units, best, lo, hi, sigma, result,
                       ran, until == "rest", interrupted, lower_sample)  # fmt: skip
    ranges = {  # within the bounds: the unknowns' prior
        n: (float(max(lo[j], best[j] - Z_95 * sigma[j])),
            float(min(hi[j], best[j] + Z_95 * sigma[j])))
        for j, n in enumerate(names)
    }  # fmt: skip
    # The box around the joint 95 % ellipsoid of all k unknowns (chi^2 within its 95 %
    # quantile with k degrees of freedom): every true value inside its range at once.
    from scipy.stats import chi2

    z_joint = math.sqrt(float(chi2.ppf(0.95, len(names))))
    joint_ranges = {
        n: (float(max(lo[j], best[j] - z_joint * sigma[j])),
            float(min(hi[j], best[j] + z_joint * sigma[j])))
        for j, n in enumerate(names)
    }  # fmt: skip
    sample_ranges = None if sampled is None else {
        n: (float(sampled.ranges[j, 0]), float(sampled.ranges[j, 1]))
        for j, n in enumerate(names)
    }  # fmt: skip

    def quoted(r: dict[str, tuple[float, float]] | None) -> Any:
        return verdict.apply(names, best, lo, hi, r)  # widened or withheld by the verdict

    return FitResult(
        names=names,
        units=units,
        values=values,
        start={n: float(v) for n, v in zip(names, x0, strict=True)},
        bounds={n: (float(a), float(b)) for n, a, b in zip(names, lo, hi, strict=True)},
        objective=prob.chi2(r_best),
        residuals=residuals,
        covariance=cov,
        sigma={n: float(s) for n, s in zip(names, sigma, strict=True)},
        ranges=quoted(ranges),
        joint_ranges=quoted(joint_ranges),
        evidence=items,
        scene=fitted,
        result=result,
        method=method,
        n_runs=prob.n_runs,
        interrupted=interrupted,
        message=message,
        scan=scans,
        scan_ranges=quoted(scan_ranges),
        sample_ranges=quoted(sample_ranges),
        samples=sampled,
        verdict=verdict,
        elapsed=time.monotonic() - began,
        extra={"global_history": history} if method == "global" else {},
    )
