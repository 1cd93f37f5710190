"""Property-based tests of a fit's verdict (crashsim.studies.verdict.judge and
Verdict.apply) with hypothesis: random residual vectors, unknowns, bounds and best values
(some exactly at a bound). The verdict follows its rules against scipy's chi^2 quantiles
(the inverse of the p-value it computes), p-values lie in [0, 1] and fall as chi^2 grows,
larger residuals never give a better verdict, and a quoted range is never narrower than
the computed one, never outside the bounds, and absent exactly where withheld.
Profiles: conftest.py ("ci" by default, "long")."""

from __future__ import annotations

import math

import numpy as np
from crashsim.studies.verdict import (
    AT_BOUND,
    DOES_NOT_FIT,
    FITS,
    P_POOR,
    P_REJECT,
    POOR,
    judge,
    p_value,
)
from hypothesis import assume, given
from hypothesis import strategies as st
from scipy.stats import chi2 as chi2_dist

SEVERITY = {FITS: 0, POOR: 1, DOES_NOT_FIT: 2}
Z_95 = 1.959963984540054



@st.composite
def residual_values(draw: st.DrawFn) -> list[float]:
    """Up to 12 residuals (in tolerances) of one magnitude, from well within the
    tolerances to 30 times them, so that chi^2 falls on every side of the thresholds."""
    size = draw(st.integers(0, 12))
    scale = draw(st.sampled_from([0.5, 1.5, 2.5, 4.0, 30.0]))
    return [scale * x for x in draw(st.lists(st.floats(-1.0, 1.0), min_size=size,
                                             max_size=size))]  # fmt: skip


@st.composite
def unknowns(draw: st.DrawFn) -> tuple[list[str], np.ndarray, np.ndarray, np.ndarray,
                                       np.ndarray]:  # fmt: skip
    """k unknowns: names, lo, hi, best (a quarter of them exactly at a bound) and sigma."""
    k = draw(st.integers(1, 4))
    lo = np.array(draw(st.lists(st.floats(-100.0, 100.0), min_size=k, max_size=k)))
    hi = lo + np.array(draw(st.lists(st.floats(0.1, 100.0), min_size=k, max_size=k)))
    where = [draw(st.floats(0.01, 0.99)) for _ in range(k)]
    for j in range(k):
        side = draw(st.integers(0, 7))  # 0: at the lower bound, 1: at the upper, else inside
        where[j] = float(side) if side < 2 else where[j]
    best = lo + np.array(where) * (hi - lo)
    sigma = np.array(draw(st.lists(st.floats(1e-4, 50.0), min_size=k, max_size=k)))
    return [f"u{j}" for j in range(k)], lo, hi, best, sigma


def _verdict(values: list[float], u: tuple, **kw):
    names, lo, hi, best, sigma = u
    residuals = [(f"item {i}", v) for i, v in enumerate(values)]
    return judge(residuals, names, best, lo, hi, sigma, **kw)


@given(st.floats(0.0, 1e4), st.floats(0.0, 1e4), st.integers(1, 60))
def test_p_values_lie_in_0_1_and_fall_as_chi2_grows(a: float, b: float, dof: int) -> None:
    pa, pb = p_value(a, dof), p_value(b, dof)
    assert 0.0 <= pa <= 1.0 and 0.0 <= pb <= 1.0
    if a <= b:
        assert pa >= pb
    assert p_value(0.0, dof) == 1.0


@given(residual_values(), unknowns())
def test_the_verdict_follows_its_rules(values: list[float], u: tuple) -> None:
    names, lo, hi, best, sigma = u
    v = _verdict(values, u)
    at = {n for j, n in enumerate(names) if best[j] - lo[j] <= AT_BOUND * (hi[j] - lo[j])
          or hi[j] - best[j] <= AT_BOUND * (hi[j] - lo[j])}  # fmt: skip
    assert set(v.at_bound) == at and v.free == len(names) - len(at)
    m = len(values)
    assert v.residuals == m and v.dof == m - v.free and v.dof_tested == max(v.dof, 1)
    chi2 = math.fsum(x * x for x in values)
    assert math.isclose(v.chi2, chi2, rel_tol=1e-12, abs_tol=1e-300)
    if m == 0:
        assert v.p_value is None and v.status == (POOR if at else FITS)
        return
    assert 0.0 <= v.p_value <= 1.0
    # against the chi^2 quantiles (scipy's inverse of the survival function judge uses),
    # away from the thresholds themselves (rounding)
    poor_at = chi2_dist.isf(P_POOR, v.dof_tested)
    reject_at = chi2_dist.isf(P_REJECT, v.dof_tested)
    assume(all(abs(chi2 - c) > 1e-6 * c for c in (poor_at, reject_at)))
    if chi2 > reject_at:
        assert v.status == DOES_NOT_FIT and v.withheld == tuple(names)
    elif chi2 > poor_at:
        assert v.status == POOR and v.scale > 1.0
        assert math.isclose(v.scale, math.sqrt(chi2 / v.dof_tested), rel_tol=1e-12)
    else:
        assert v.scale == 1.0 and v.status == (POOR if at else FITS)
    assert (v.status == FITS) == (not v.reasons)
    for n in at:
        assert n in v.withheld and any(r.startswith(f"{n} ended at its") for r in v.reasons)


@given(residual_values(), unknowns(), st.floats(1.0, 20.0))
def test_larger_residuals_never_give_a_better_verdict(values: list[float], u: tuple,
                                                      c: float) -> None:  # fmt: skip
    a, b = _verdict(values, u), _verdict([c * x for x in values], u)
    assert SEVERITY[b.status] >= SEVERITY[a.status]
    assert b.scale >= a.scale or b.status == DOES_NOT_FIT


@given(residual_values(), unknowns(), st.booleans())
def test_quoted_ranges_are_never_narrower_and_absent_exactly_where_withheld(
    values: list[float], u: tuple, unavailable: bool
) -> None:
    names, lo, hi, best, sigma = u
    v = _verdict(values, u, unavailable={"evidence[0] X": "no impact"} if unavailable else None)
    ranges = {n: (max(lo[j], best[j] - Z_95 * sigma[j]), min(hi[j], best[j] + Z_95 * sigma[j]))
              for j, n in enumerate(names)}  # fmt: skip
    quoted = v.apply(names, best, lo, hi, ranges)
    assert quoted is not None and list(quoted) == names
    if unavailable:
        assert v.status == DOES_NOT_FIT and "evidence[0] X: no impact" in v.reasons
    for j, n in enumerate(names):
        q = quoted[n]
        assert (q is None) == (n in v.withheld)
        if q is None:
            assert v.range_note(n)  # the table says why
            continue
        a, b = ranges[n]
        assert lo[j] <= q[0] <= a <= best[j] <= b <= q[1] <= hi[j]
        if v.scale == 1.0:
            assert q == (a, b)
    assert v.apply(names, best, lo, hi, None) is None


@given(residual_values(), unknowns())
def test_an_unknown_the_evidence_does_not_fix_gets_no_range(values: list[float], u: tuple) -> None:
    names, lo, hi, best, sigma = u
    sigma = sigma.copy()
    sigma[0] = math.inf
    v = _verdict(values, (names, lo, hi, best, sigma))
    assert names[0] in v.withheld and v.status != FITS
    if names[0] not in v.at_bound:
        assert names[0] in v.not_fixed
