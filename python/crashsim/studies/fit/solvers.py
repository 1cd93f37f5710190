"""The fit's solvers in scaled unknowns u in [0, 1]: the Jacobian by differences that step
over jumps, scipy's least squares (trust region reflective) and differential evolution (a
generation one batch, stopped when it stalls)."""

from __future__ import annotations

from typing import Any

import numpy as np

from crashsim.studies.fit.problem import Array, _Problem

XTOL, FTOL, GTOL = 1e-5, 1e-10, 1e-10  # the local solve's tolerances (scaled unknowns)


JUMP = 1.0  # tolerances: a second difference larger than this is a jump, not curvature
# A jump on one side changes the residuals at least this many times more than the other
# side's step does; comparable changes either side are the runs' scatter (below).
CLIFF_RATIO = 3.0
# Scatter widens an unknown's step by WIDEN at a time, to WIDEST (fractions of its range),
# while the second difference grows less than KINK times a widening.
WIDEN, WIDEST, KINK = 3.0, 0.1, 2.0


def _jacobian(
    prob: _Problem, u: Array, lo: Array, hi: Array, step: float, widen: bool = False
) -> Array:
    """(m, k) d residual / d u at ``step`` (a fraction of each range); see _differences."""
    return _differences(prob, u, lo, hi, np.full(len(u), step), widen)


def _differences(
    prob: _Problem, u: Array, lo: Array, hi: Array, steps: Array, widen: bool = False
) -> Array:
    """(m, k) d residual / d u by differences over ``steps`` (scaled) either side of u, the
    point and its 2k neighbours one batch (u itself is usually run already).

    Central differences, except where an unknown's two sides disagree by more than JUMP
    tolerances (the norm of the residuals' second difference):
    - one side changes the residuals CLIFF_RATIO times more than the other: a jump lies on
      that side (candidates whose run-out differs, e.g. a second contact: chi^2 180 against
      7 on either side, docs/fitting.md), and the other side is taken;
    - both change alike: scatter (a struck pedestrian's rest moves by +-2 tolerances between
      speeds 0.45 km/h apart, docs/fitting.md), where either side alone can point the wrong
      way: the central difference, the secant over both steps, is taken; with ``widen`` (the
      local solve's Jacobian) after widening the unknown's step WIDEN times (one more batch
      of its two neighbours) until its sides agree, it reaches WIDEST, or the disagreement
      grows with the step (KINK: a kink or a curve, not scatter).
    One-sided at a bound."""
    k = len(u)
    steps = np.array(steps, dtype=np.float64)
    cols: list[Array] = [np.empty(0)] * k
    bent: list[float] = [np.inf] * k  # each unknown's last second difference (tolerances)
    todo = list(range(k))
    while todo:
        pts = [u]
        for j in todo:
            a, b = u.copy(), u.copy()
            a[j] = min(1.0, u[j] + steps[j])
            b[j] = max(0.0, u[j] - steps[j])
            pts += [a, b]
        pts_a = np.array(pts)
        r = prob.residuals(lo + pts_a * (hi - lo))
        scattered = []
        for n, j in enumerate(todo):
            ra, rb = r[1 + 2 * n], r[2 + 2 * n]
            ha, hb = pts_a[1 + 2 * n, j] - u[j], u[j] - pts_a[2 + 2 * n, j]
            cols[j], second = _difference(r[0], ra, rb, ha, hb)
            # Scatter keeps its size as the step widens; a kink (a distance's |d| at its
            # zero) or a curve grows with it: WIDEN or WIDEN^2 times.
            if widen and 0.0 < second < KINK * bent[j] and steps[j] < WIDEST:
                scattered.append(j)
                bent[j] = second
                steps[j] = min(WIDEST, steps[j] * WIDEN)
        todo = scattered
    return np.column_stack(cols)


def _difference(r0: Array, ra: Array, rb: Array, ha: float, hb: float) -> tuple[Array, float]:
    """d residual / d u from the residuals at u (r0), ha above (ra) and hb below (rb), as
    _differences says; and the second difference's norm (tolerances) where the sides change
    alike yet disagree by more than JUMP, as scatter does (0 otherwise)."""
    if ha <= 0.0 or hb <= 0.0:  # at a bound: the side inside
        return (ra - rb) / (ha + hb), 0.0
    fwd, bwd = (ra - r0) / ha, (r0 - rb) / hb
    second = float(np.linalg.norm(fwd - bwd) * min(ha, hb))
    if second <= JUMP:
        return (ra - rb) / (ha + hb), 0.0
    change_a, change_b = np.linalg.norm(ra - r0), np.linalg.norm(r0 - rb)
    if max(change_a, change_b) > CLIFF_RATIO * min(change_a, change_b):
        return (fwd if change_a <= change_b else bwd), 0.0
    return (ra - rb) / (ha + hb), second


def _least_squares(
    prob: _Problem, u0: Array, lo: Array, hi: Array, step: float, max_nfev: int
) -> tuple[Array, str]:
    from scipy.optimize import least_squares

    def fun(u: Array) -> Array:
        return prob.residuals(lo + u * (hi - lo))[0]

    def jac(u: Array) -> Array:
        return _jacobian(prob, u, lo, hi, step, widen=True)

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
