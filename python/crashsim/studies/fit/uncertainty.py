"""The fit's uncertainty: the covariance of the Jacobian (taken twice), importance sampling
of the posterior (two Student-t proposals), the scan of the objective along each unknown."""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from crashsim.studies.fit.problem import Array, _Problem
from crashsim.studies.fit.solvers import _differences, _jacobian

CHI2_95 = 3.841458820694124  # 95 % quantile of chi^2 with one degree of freedom

Z_95 = 1.959963984540054  # two-sided 95 % of the normal distribution


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
