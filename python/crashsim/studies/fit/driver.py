"""The fit's entry point, :func:`fit` (see the package's text): its checks, the solve, the
uncertainty, the fitted run and its verdict."""

from __future__ import annotations

import math
import time
from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any

import numpy as np

from crashsim.errors import CrashsimError
from crashsim.studies import paths
from crashsim.studies.evidence import MISSING, Evidence, FitError, check_evidence
from crashsim.studies.fit.problem import (
    Array,
    _check_unknowns,
    _Interrupted,
    _Problem,
    _Progress,
    _start,
)
from crashsim.studies.fit.result import FitResult, ItemResidual
from crashsim.studies.fit.solvers import _global, _least_squares
from crashsim.studies.fit.uncertainty import Z_95, _sample, _Samples, _scan, _uncertainty
from crashsim.studies.verdict import Verdict, judge

if TYPE_CHECKING:
    from crashsim.result import Result
    from crashsim.scene import Scene

METHODS = ("least_squares", "global")
STEP = 1e-2  # the Jacobian's difference step by default, a fraction of each unknown's range


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
    _check_settings(scene, method, until, duration, dt, max_duration, step, max_nfev, popsize,
                    maxiter, patience, scan_points, samples, seed)  # fmt: skip
    names, lo, hi, units = _check_unknowns(scene, unknowns)
    items = [evidence] if isinstance(evidence, Evidence) else list(evidence)
    labels = check_evidence(scene, items)
    x0 = _start(scene, names, lo, hi, start)
    bar = _Progress() if progress is True else None
    callback = bar if bar is not None else (progress if callable(progress) else None)
    run = {"duration": duration, "dt": dt, "until": until, "max_duration": max_duration}
    prob = _Problem(scene, names, items, labels, run, threads, callback)
    began = time.monotonic()
    n_samples = 50 * len(names) if samples is None else int(samples)
    how = _SolveSettings(method, seed, popsize, maxiter, patience, step, max_nfev, n_samples,
                         scan, scan_points)  # fmt: skip
    solved = _solve(prob, names, x0, lo, hi, how, bar)
    best, sigma = solved.best, solved.sigma
    interrupted, sampled = solved.interrupted, solved.sampled
    values = {n: float(v) for n, v in zip(names, best, strict=True)}
    fitted = paths.with_(scene, values)
    result = None if interrupted else _fitted_run(prob, fitted)
    ran = not interrupted or prob.best_x is not None  # best is a candidate that ran
    r_best = prob.residuals(best[None])[0] if ran else np.full(prob.m, MISSING)
    residuals = _item_residuals(items, labels, r_best, result)
    verdict = _verdict(prob, items, residuals, names, units, best, lo, hi, sigma, result,
                       ran, until == "rest", interrupted, solved.lower_sample)  # fmt: skip
    ranges, joint_ranges, sample_ranges = _ranges(names, best, sigma, lo, hi, sampled)

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
        covariance=solved.cov,
        sigma={n: float(s) for n, s in zip(names, sigma, strict=True)},
        ranges=quoted(ranges),
        joint_ranges=quoted(joint_ranges),
        evidence=items,
        scene=fitted,
        result=result,
        method=method,
        n_runs=prob.n_runs,
        interrupted=interrupted,
        message=solved.message,
        scan=solved.scans,
        scan_ranges=quoted(solved.scan_ranges),
        sample_ranges=quoted(sample_ranges),
        samples=sampled,
        verdict=verdict,
        elapsed=time.monotonic() - began,
        extra={"global_history": solved.history} if method == "global" else {},
    )


def _check_settings(
    scene: Scene,
    method: str,
    until: str | None,
    duration: float | None,
    dt: float,
    max_duration: float,
    step: float,
    max_nfev: int,
    popsize: int,
    maxiter: int,
    patience: int,
    scan_points: int,
    samples: int | None,
    seed: int | None,
) -> None:
    """FitError for a bad setting of :func:`fit` (all but the unknowns and the evidence)."""
    if method not in METHODS:
        raise FitError(f"method {method!r} is unknown: use {' or '.join(METHODS)}")
    if until not in (None, "rest"):
        raise FitError(f'until = {until!r} is unknown: use until="rest" or None')
    if until is None and duration is None:
        raise FitError('give duration (s) for runs of a fixed length, or until="rest"')
    if until == "rest" and scene.ground is None:
        raise FitError('until="rest" needs a ground: give duration and until=None instead')
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


@dataclass
class _Solve:
    """What the solve found so far (kept when it is interrupted part way)."""

    best: Array  # SI, one per unknown
    sigma: Array  # SI, one per unknown (inf: unknown)
    interrupted: bool = False
    message: str = ""
    cov: Array | None = None
    scans: Any = None
    scan_ranges: Any = None
    sampled: _Samples | None = None
    history: list[float] = field(default_factory=list)
    lower_sample: float | None = None


@dataclass(frozen=True)
class _SolveSettings:
    """How the solve runs (fit's arguments of the same names, checked by _check_settings)."""

    method: str
    seed: int | None
    popsize: int
    maxiter: int
    patience: int
    step: float
    max_nfev: int
    n_samples: int
    scan: bool
    scan_points: int


def _solve(
    prob: _Problem,
    names: list[str],
    x0: Array,
    lo: Array,
    hi: Array,
    how: _SolveSettings,
    bar: _Progress | None,
) -> _Solve:
    """The solve from ``x0`` (_solve_steps); interrupted (Ctrl-C, or the progress callback),
    what it found so far with the best candidate that ran. Closes the progress ``bar``."""
    s = _Solve(best=x0.copy(), sigma=np.full(len(names), math.inf))
    try:
        _solve_steps(s, prob, names, x0, lo, hi, how)
    except (_Interrupted, KeyboardInterrupt):
        s.interrupted = True
        s.message += "interrupted (Ctrl-C): the best candidate so far"
        if prob.best_x is not None:
            s.best = prob.best_x.copy()
    finally:
        if bar is not None:
            bar.close()
    return s


def _solve_steps(
    s: _Solve,
    prob: _Problem,
    names: list[str],
    x0: Array,
    lo: Array,
    hi: Array,
    how: _SolveSettings,
) -> None:
    """The global search (for method "global"), the least-squares solve, the uncertainty, the
    sampling and the scan, each writing into ``s`` as it ends."""
    u0 = (x0 - lo) / (hi - lo)
    if how.method == "global":
        u0, m, s.history = _global(prob, u0, lo, hi, how.seed, how.popsize, how.maxiter,
                                   how.patience)  # fmt: skip
        s.message = f"differential evolution: {m}; "
    u, m = _least_squares(prob, u0, lo, hi, how.step, how.max_nfev)
    s.message += f"least squares: {m}"
    s.best = lo + u * (hi - lo)
    if prob.best_x is not None and prob.best < prob.chi2(prob.residuals(s.best[None])[0]):
        s.best = prob.best_x.copy()
    s.cov, s.sigma = _uncertainty(prob, s.best, lo, hi, how.step)
    if how.n_samples > 0:
        s.sampled = _sample(prob, s.best, s.cov, lo, hi, how.n_samples, how.seed)
        if s.sampled is not None:
            c_best = prob.chi2(prob.residuals(s.best[None])[0])
            if s.sampled.chi2.min() < c_best - 1.0:
                s.lower_sample = float(s.sampled.chi2.min())
                s.message += (f"; a sample has chi^2 {s.lower_sample:.4g} < the "
                              f"optimum's {c_best:.4g}: the solve stopped short")  # fmt: skip
    if how.scan:
        s.scans, s.scan_ranges = _scan(prob, names, s.best, s.sigma, lo, hi, how.scan_points)


def _fitted_run(prob: _Problem, fitted: Scene) -> Result | None:
    """The run of the fitted scene (None when it fails)."""
    try:
        return prob.run_one(fitted)
    except CrashsimError:
        return None


def _item_residuals(
    items: list[Evidence], labels: list[str], r_best: Array, result: Result | None
) -> list[ItemResidual]:
    """Each evidence item's residual at the best: measured on the fitted run's ``result``, or
    (without it) rebuilt from the normalised residuals ``r_best`` of the best candidate."""
    residuals: list[ItemResidual] = []
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
    return residuals


def _ranges(
    names: list[str], best: Array, sigma: Array, lo: Array, hi: Array, sampled: _Samples | None
) -> tuple[dict[str, tuple[float, float]], dict[str, tuple[float, float]], Any]:
    """The unknowns' 95 % ranges (SI) before the verdict: each on its own, the joint box and
    the sampled ones (None without samples)."""
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
    return ranges, joint_ranges, sample_ranges
