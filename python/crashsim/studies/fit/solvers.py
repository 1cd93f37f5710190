"""The fit's solvers in scaled unknowns u in [0, 1]: the Jacobian by differences that step
over jumps, scipy's least squares (trust region reflective) and differential evolution (a
generation one batch, stopped when it stalls)."""

from __future__ import annotations

from typing import Any

import numpy as np

from crashsim.studies.fit.problem import Array, _Problem

XTOL, FTOL, GTOL = 1e-5, 1e-10, 1e-10  # the local solve's tolerances (scaled unknowns)
# The local solve also stops once a Gauss-Newton step from its point would lower chi^2 by less
# than this (the linear model's decrement: the part of the residuals its Jacobian's columns
# span, squared): the unknowns are then within sqrt(SETTLED_CHI2) = 0.03 of a standard
# deviation of that model's optimum. Without it the solve went on in the residuals' scatter:
# a struck pedestrian's speed fit made 8 iterations where 3 reach the same answer, 32 runs in
# all against 16 (docs/fitting.md, "The methods").
SETTLED_CHI2 = 1e-3


JUMP = 1.0  # tolerances: a second difference larger than this is a jump, not curvature
# A side that changes the residuals this many times more than the other holds a jump.
CLIFF_RATIO = 3.0
# The local solve's Jacobian looks WIDEN times further, up to WIDEST of a range, where the
# sides disagree but change alike; it stops widening once the disagreement grows KINK times.
WIDEN, WIDEST, KINK = 3.0, 0.1, 2.0

_Sides = tuple[Array, Array, float, float]  # residuals above and below u, their distances


def _jacobian(
    prob: _Problem, u: Array, lo: Array, hi: Array, step: float, widen: bool = False
) -> Array:
    """(m, k) d residual / d u at ``step`` (a fraction of each range); see _differences."""
    return _differences(prob, u, lo, hi, np.full(len(u), step), widen)


def _sides(
    prob: _Problem, u: Array, lo: Array, hi: Array, steps: Array, which: list[int]
) -> tuple[Array, dict[int, _Sides]]:
    """The residuals at u and, for each unknown in ``which``, at ``steps`` (scaled) above and
    below it (clipped to the bounds), as one batch."""
    pts = [u]
    for j in which:
        a, b = u.copy(), u.copy()
        a[j] = min(1.0, u[j] + steps[j])
        b[j] = max(0.0, u[j] - steps[j])
        pts += [a, b]
    pts_a = np.array(pts)
    r = prob.residuals(lo + pts_a * (hi - lo))
    out = {
        j: (r[1 + 2 * n], r[2 + 2 * n], pts_a[1 + 2 * n, j] - u[j], u[j] - pts_a[2 + 2 * n, j])
        for n, j in enumerate(which)
    }  # fmt: skip
    return r[0], out


def _differences(
    prob: _Problem, u: Array, lo: Array, hi: Array, steps: Array, widen: bool = False
) -> Array:
    """(m, k) d residual / d u by differences over ``steps`` (scaled) either side of u, the
    point and its 2k neighbours one batch (u itself is usually run already).

    Central differences, except where an unknown's two sides disagree by more than JUMP
    tolerances (the norm of the residuals' second difference). Then a jump lies on one side
    (candidates whose run-out differs, e.g. a second contact: chi^2 180 against 7 on either
    side, docs/fitting.md) and the side whose residuals change less is taken; with ``widen``
    (the local solve's Jacobian) only where that side changes them CLIFF_RATIO times less.
    Where both change alike, the local solve looks WIDEN times further on both sides (one
    more batch): a side whose residuals grow in proportion to the step is smooth, one that
    does not holds the jump, and the smooth side is taken; both in proportion (a kink, such
    as a distance to a tyre mark at its zero): the side changing less, as above; neither
    (scatter: a struck pedestrian's rest moves by up to 2 tolerances between speeds 0.45
    km/h apart, docs/fitting.md, where either side alone can point the wrong way): wider
    still, to WIDEST or until the sides agree or their disagreement grows KINK times with a
    widening (a curve), and the central difference over the widest steps. One-sided at a
    bound."""
    k = len(u)
    steps = np.array(steps, dtype=np.float64)
    r0, near = _sides(prob, u, lo, hi, steps, list(range(k)))
    cols: list[Array] = []
    unclear: list[int] = []
    for j in range(k):
        ra, rb, ha, hb = near[j]
        col, second = _difference(r0, ra, rb, ha, hb, strict=not widen)
        cols.append(col)
        if second > 0.0:
            unclear.append(j)
    scatter: dict[int, float] = {}
    if unclear:
        steps[unclear] = np.minimum(WIDEST, steps[unclear] * WIDEN)
        _, far = _sides(prob, u, lo, hi, steps, unclear)
        for j in unclear:
            col, second = _judge(r0, near[j], far[j])
            cols[j] = col
            if second > 0.0:
                scatter[j] = second
    while scatter:  # widen the scattered unknowns while the sides disagree as scatter does
        grow = [j for j in scatter if steps[j] < WIDEST]
        if not grow:
            break
        steps[grow] = np.minimum(WIDEST, steps[grow] * WIDEN)
        _, wider = _sides(prob, u, lo, hi, steps, grow)
        still: dict[int, float] = {}
        for j in grow:
            ra, rb, ha, hb = wider[j]
            second = _second(r0, ra, rb, ha, hb)
            if second >= KINK * scatter[j]:
                continue  # a curve: the last central difference stands
            cols[j] = (ra - rb) / (ha + hb)
            if second > JUMP:
                still[j] = second
        scatter = still
    return np.column_stack(cols)


def _second(r0: Array, ra: Array, rb: Array, ha: float, hb: float) -> float:
    """The second difference's norm (tolerances) at the shorter of the two steps."""
    return float(np.linalg.norm((ra - r0) / ha - (r0 - rb) / hb) * min(ha, hb))


def _difference(
    r0: Array, ra: Array, rb: Array, ha: float, hb: float, strict: bool
) -> tuple[Array, float]:
    """d residual / d u from the residuals at u (r0), ha above (ra) and hb below (rb), as
    _differences says for the first steps; and the second difference's norm (tolerances)
    where the sides disagree but change alike, to be judged further (0 otherwise; never
    when ``strict``, which takes the side changing less on any disagreement)."""
    if ha <= 0.0 or hb <= 0.0:  # at a bound: the side inside
        return (ra - rb) / (ha + hb), 0.0
    fwd, bwd = (ra - r0) / ha, (r0 - rb) / hb
    second = _second(r0, ra, rb, ha, hb)
    if second <= JUMP:
        return (ra - rb) / (ha + hb), 0.0
    change_a, change_b = np.linalg.norm(ra - r0), np.linalg.norm(r0 - rb)
    less = fwd if change_a <= change_b else bwd
    if strict or max(change_a, change_b) > CLIFF_RATIO * min(change_a, change_b):
        return less, 0.0
    return less, second


def _judge(r0: Array, near: _Sides, far: _Sides) -> tuple[Array, float]:
    """An unknown whose sides at ``near`` disagree but change alike, seen again at ``far``
    (WIDEN times further): the smooth side's slope at near where only one side's change
    grew in proportion to its step (within JUMP); the side changing less where both did (a
    kink); the central difference at far, with its second difference's norm to widen on,
    where neither did (scatter)."""
    ra, rb, ha, hb = near
    fa, fb, ga, gb = far
    smooth_a = np.linalg.norm((fa - r0) - (ra - r0) * (ga / ha)) <= JUMP
    smooth_b = np.linalg.norm((r0 - fb) - (r0 - rb) * (gb / hb)) <= JUMP
    fwd, bwd = (ra - r0) / ha, (r0 - rb) / hb
    if smooth_a and not smooth_b:
        return fwd, 0.0
    if smooth_b and not smooth_a:
        return bwd, 0.0
    if smooth_a and smooth_b:
        return (fwd if np.linalg.norm(ra - r0) <= np.linalg.norm(r0 - rb) else bwd), 0.0
    second = _second(r0, fa, fb, ga, gb)
    return (fa - fb) / (ga + gb), (second if second > JUMP else 0.0)


def _least_squares(
    prob: _Problem, u0: Array, lo: Array, hi: Array, step: float, max_nfev: int
) -> tuple[Array, str]:
    from scipy.optimize import least_squares

    def fun(u: Array) -> Array:
        return prob.residuals(lo + u * (hi - lo))[0]

    last: list[tuple[Array, Array]] = []  # the Jacobian last made, and where
    final: list[Array] = []  # the Gauss-Newton step's end where the solve settled

    def jac(u: Array) -> Array:
        j = _jacobian(prob, u, lo, hi, step, widen=True)
        last[:] = [(u.copy(), j)]
        return j

    def settled(intermediate_result: Any) -> None:
        """Stops the solve (StopIteration) once its Gauss-Newton step would lower chi^2 by
        less than SETTLED_CHI2, keeping that step's end (within the bounds) to be run once;
        scipy makes the Jacobian at an accepted point before this."""
        u, r = intermediate_result.x, intermediate_result.fun
        if not last or not np.array_equal(last[0][0], u):
            return
        j = last[0][1]
        d = np.linalg.lstsq(j, -r, rcond=None)[0]
        if float(np.sum((j @ d) ** 2)) < SETTLED_CHI2:
            final[:] = [np.clip(u + d, 0.0, 1.0)]
            raise StopIteration

    # Tolerances in scaled unknowns (the range = 1): XTOL stops at steps of 1e-5 of a range,
    # far below any figure the evidence fixes; tighter only spends runs on the jumps.
    sol = least_squares(fun, np.clip(u0, 0.0, 1.0), jac=jac, bounds=(0.0, 1.0), method="trf",
                        x_scale=1.0, xtol=XTOL, ftol=FTOL, gtol=GTOL, max_nfev=max_nfev,
                        callback=settled)  # fmt: skip
    if sol.status != -2:
        return sol.x, str(sol.message)
    # The last step, taken where it lowers chi^2 (exact for a linear model; in scatter the
    # better of the two points).
    settled_at = f"a Gauss-Newton step would lower chi^2 by less than {SETTLED_CHI2:g}"
    r_final = fun(final[0])
    if float(np.sum(r_final**2)) < float(np.sum(sol.fun**2)):
        return final[0], settled_at + " (that step taken)"
    return sol.x, settled_at


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
