"""A fit's verdict: does the answer fit the evidence, and which ranges may be quoted
(docs/fitting.md, "The verdict").

    v = judge(residuals, names, best, lo, hi, sigma, unavailable={...})
    v.status            # "fits", "poor fit" or "does not fit"; v.reasons, v.notes
    ranges = v.apply(names, best, lo, hi, fit_ranges)   # widened, withheld or as computed

The tolerances are one standard deviation, so at a right answer chi^2 (the squared residuals
in tolerances, over the items the fitted run gives) follows chi^2 with ``dof`` = residuals -
free unknowns degrees of freedom (an unknown at a bound is held by it, not by the evidence,
and is not free). The rules, each threshold with its reason:

- **does not fit** when an evidence item is one the fitted run cannot give (EDR delta-V of
  an impact the run does not have, ...: its residual is no residual), or when p, the chance
  of a chi^2 at least this large, is below P_REJECT: the one-sided 5-sigma level (2.9e-7)
  by which particle physics rejects a hypothesis, so that a correct fit is told it does not
  fit fewer than once in 3 million. Its ranges are withheld: they would be the spread of a
  model the evidence rejects.
- **poor fit** when P_REJECT <= p < P_POOR (0.01, the usual 1 % level: one correct fit in a
  hundred is flagged, and that costs it only wider ranges); when an unknown ended at a bound
  (within AT_BOUND of its range: the bounds, not the evidence, set it); when the evidence
  does not fix an unknown (the Jacobian's J^T J is singular); when a rest item's vehicle was
  still moving at the end of a run until rest; when a sample of the posterior had a chi^2
  more than 1 below the optimum's (the solve stopped short); or when the fit was
  interrupted. With p < P_POOR every range is widened about the best value by the Birge
  ratio sqrt(chi^2 / dof) (R. T. Birge, Phys. Rev. 40, 207 (1932); the Particle Data
  Group's scale factor S for its averages and fits: the tolerances taken as too small by one
  common factor). An unknown at a bound or not fixed by the evidence gets no range: one end
  would be the bound's, not the evidence's ("90 .. 90" is no range). An interrupted fit gets
  none (its uncertainty was not computed).
- **fits** otherwise; ranges as computed.

With no spare residual (dof <= 0) a model that can reach the evidence reaches it exactly
(chi^2 = 0 in the linear model), so chi^2 is tested against one degree of freedom, the
strictest of the tests a spare residual would give; a pass then says little (a note).
"""

from __future__ import annotations

import math
from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field
from typing import Any

import numpy as np
from numpy.typing import NDArray

__all__ = [
    "AT_BOUND",
    "DOES_NOT_FIT",
    "FITS",
    "P_POOR",
    "P_REJECT",
    "POOR",
    "Verdict",
    "judge",
]

Array = NDArray[np.float64]

FITS, POOR, DOES_NOT_FIT = "fits", "poor fit", "does not fit"
P_POOR = 0.01  # below: a poor fit, its ranges widened by the Birge ratio
P_REJECT = 2.866515718791939e-07  # one-sided 5 sigma (scipy.stats.norm.sf(5)): does not fit
# An unknown within this fraction of its range of a bound is at the bound: 100 times the
# local solve's step tolerance (XTOL, 1e-5 of a range: a solve the bound stopped ends that
# close), a tenth of the Jacobian's difference step (1e-2: its difference is one-sided there).
AT_BOUND = 1e-3
WORST = 3  # residual components named when chi^2 fails its test


@dataclass(frozen=True)
class Verdict:
    """Does the fit fit? ``status`` FITS, POOR or DOES_NOT_FIT; ``reasons`` why it is not
    FITS (empty when it is), ``notes`` what a reader should know that does not change it.

    ``chi2`` over the ``residuals`` residual components of the items the fitted run gives,
    ``free`` unknowns not at a bound, ``dof`` = residuals - free, ``p_value`` the chance of a
    chi^2 at least this large with ``dof_tested`` = max(dof, 1) degrees of freedom (None
    with no residual to test), ``reduced_chi2`` chi2 / dof_tested; ``scale`` the factor of
    every range about the best value (the Birge ratio sqrt(reduced chi^2) when p < P_POOR,
    else 1); ``at_bound`` {unknown: "lower" | "upper"}, ``not_fixed`` the unknowns the
    evidence does not fix, ``unavailable`` {evidence label: why the fitted run cannot give
    it}; ``withheld`` the unknowns whose ranges are withheld and ``range_rule`` what was
    done to the ranges, in words."""

    status: str
    chi2: float
    residuals: int
    free: int
    dof: int
    dof_tested: int
    p_value: float | None
    reduced_chi2: float | None
    scale: float
    at_bound: dict[str, str] = field(default_factory=dict)
    not_fixed: tuple[str, ...] = ()
    unavailable: dict[str, str] = field(default_factory=dict)
    withheld: tuple[str, ...] = ()
    range_rule: str = "as computed"
    reasons: tuple[str, ...] = ()
    notes: tuple[str, ...] = ()

    @property
    def fits(self) -> bool:
        return self.status == FITS

    def range_note(self, name: str) -> str:
        """Why ``name``'s range is withheld, in a few words for a table cell ("" if not)."""
        if name not in self.withheld:
            return ""
        side = self.at_bound.get(name)
        if side is not None:
            return f"at {side} bound"
        return "not fixed" if name in self.not_fixed else "withheld"

    def apply(self, names: Sequence[str], best: Array, lo: Array, hi: Array,
              ranges: Mapping[str, tuple[float, float]] | None
              ) -> dict[str, tuple[float, float] | None] | None:  # fmt: skip
        """``ranges`` {unknown: (lo, hi)} as the verdict lets them be quoted: None for a
        withheld one, the others' distances from the best value times ``scale``, within the
        bounds ``lo``, ``hi``."""
        if ranges is None:
            return None
        out: dict[str, tuple[float, float] | None] = {}
        for j, n in enumerate(names):
            if n in self.withheld or n not in ranges:
                out[n] = None
                continue
            a, b = ranges[n]
            if self.scale == 1.0:  # as computed (recomputing them could round them inwards)
                out[n] = (float(a), float(b))
                continue
            out[n] = (float(max(lo[j], best[j] - self.scale * (best[j] - a))),
                      float(min(hi[j], best[j] + self.scale * (b - best[j]))))  # fmt: skip
        return out

    def lines(self) -> list[str]:
        """The verdict as text: a head line, the reasons and notes, what the ranges are."""
        p = "-" if self.p_value is None else f"{self.p_value:.2g}"
        red = "-" if self.reduced_chi2 is None else f"{self.reduced_chi2:.3g}"
        tested = ("" if self.dof == self.dof_tested or self.p_value is None
                  else f" (tested as {self.dof_tested})")  # fmt: skip
        out = [
            f"verdict: {self.status.upper()} -- chi^2 {self.chi2:.4g} over "
            f"{_count(self.residuals, 'residual')} with {_count(self.free, 'free unknown')}: "
            f"{_count(self.dof, 'degree')} of freedom{tested}, p = {p}, chi^2/dof = {red}"
        ]
        out += [f"  - {r}" for r in self.reasons]
        out += [f"  note: {n}" for n in self.notes]
        out.append(f"  ranges: {self.range_rule}")
        return out

    def to_dict(self) -> dict[str, Any]:
        """Plain data for JSON (the thresholds too)."""
        return {
            "status": self.status,
            "chi2": self.chi2,
            "residuals": self.residuals,
            "free_unknowns": self.free,
            "dof": self.dof,
            "dof_tested": self.dof_tested,
            "p_value": self.p_value,
            "reduced_chi2": self.reduced_chi2,
            "range_scale": self.scale,
            "range_rule": self.range_rule,
            "withheld": list(self.withheld),
            "at_bound": dict(self.at_bound),
            "not_fixed": list(self.not_fixed),
            "unavailable": dict(self.unavailable),
            "reasons": list(self.reasons),
            "notes": list(self.notes),
            "thresholds": {"p_poor": P_POOR, "p_reject": P_REJECT, "at_bound": AT_BOUND},
        }


def _count(n: int, what: str) -> str:
    return f"{n} {what}" + ("" if n == 1 else "s")


def p_value(chi2: float, dof: int) -> float:
    """The chance that chi^2 with ``dof`` (>= 1) degrees of freedom is at least ``chi2``."""
    from scipy.stats import chi2 as dist

    return float(dist.sf(chi2, dof))


def judge(
    residuals: Sequence[tuple[str, float]],
    names: Sequence[str],
    best: Array,
    lo: Array,
    hi: Array,
    sigma: Array,
    *,
    unavailable: Mapping[str, str] | None = None,
    caveats: Mapping[str, str] | None = None,
    interrupted: bool = False,
    lower_sample: float | None = None,
    units: Mapping[str, str] | None = None,
) -> Verdict:
    """The verdict on a fit (the module's rules).

    ``residuals`` (name, value in tolerances) of every residual component of the items the
    fitted run gives; ``names``, ``best``, ``lo``, ``hi`` the unknowns, their best values and
    bounds (SI); ``sigma`` their Jacobian standard deviations (inf where the evidence does
    not fix one); ``unavailable`` {item: why the fitted run cannot give it} (does not fit);
    ``caveats`` {item: what makes its figure doubtful} (poor); ``interrupted`` (Ctrl-C: the
    best so far); ``lower_sample`` the least chi^2 of the posterior's samples when more than
    1 below the optimum's (the solve stopped short); ``units`` {unknown: SI unit} for the
    text."""
    unavailable = dict(unavailable or {})
    caveats = dict(caveats or {})
    values = np.array([v for _, v in residuals], dtype=np.float64)
    chi2 = float(values @ values)
    m = len(values)
    best, lo, hi, sigma = (np.asarray(a, dtype=np.float64) for a in (best, lo, hi, sigma))
    at_bound = _at_bounds(names, best, lo, hi)
    free = len(names) - len(at_bound)
    dof = m - free
    tested = max(dof, 1)
    p = p_value(chi2, tested) if m > 0 else None
    reduced = chi2 / tested if m > 0 else None
    # (a Jacobian taken on the placeholders of items the run did not give says nothing)
    not_fixed = () if interrupted or unavailable else tuple(
        n for j, n in enumerate(names) if not math.isfinite(sigma[j]) and n not in at_bound
    )  # fmt: skip

    fail: list[str] = []
    poor: list[str] = []
    notes: list[str] = []
    for label, why in unavailable.items():
        fail.append(f"{label}: {why}")
    if p is not None:
        _chi2_reasons(residuals, chi2, tested, p, dof, m, free, fail, poor, notes)
    for n, side in at_bound.items():
        j = list(names).index(n)
        bound = lo[j] if side == "lower" else hi[j]
        unit = f" {units[n]}" if units and n in units else ""
        poor.append(f"{n} ended at its {side} bound ({bound:.6g}{unit}): the bound, not the "
                    f"evidence, set it; widen the bounds if the evidence asks for more")
    for n in not_fixed:
        poor.append(f"the evidence does not fix {n} (the residuals do not determine it)")
    for label, why in caveats.items():
        poor.append(f"{label}: {why}")
    if lower_sample is not None:
        poor.append(f"a sample of the posterior has chi^2 {lower_sample:.4g}, more than 1 below "
                    f"the optimum's: the solve stopped short of the least chi^2")
    if interrupted:
        poor.append("interrupted (Ctrl-C): the best candidate so far, not an optimum")

    status = DOES_NOT_FIT if fail else POOR if poor else FITS
    scale = 1.0
    if status == DOES_NOT_FIT or interrupted:
        withheld = tuple(names)
        rule = ("withheld: the fit does not fit" if status == DOES_NOT_FIT
                else "withheld: the fit was interrupted")  # fmt: skip
    else:
        withheld = tuple(n for n in names if n in at_bound or n in not_fixed)
        scale, rule = _range_rule(p, chi2, tested, withheld)
        _note_ranges_at_bounds(names, withheld, scale, best, lo, hi, sigma, notes)
    return Verdict(
        status=status,
        chi2=chi2,
        residuals=m,
        free=free,
        dof=dof,
        dof_tested=tested,
        p_value=p,
        reduced_chi2=reduced,
        scale=scale,
        at_bound=at_bound,
        not_fixed=not_fixed,
        unavailable=unavailable,
        withheld=withheld,
        range_rule=rule,
        reasons=tuple(fail + poor),
        notes=tuple(notes),
    )


def _at_bounds(names: Sequence[str], best: Array, lo: Array, hi: Array) -> dict[str, str]:
    """The unknowns whose best value is within AT_BOUND of its range from a bound: "lower"
    or "upper"."""
    span = hi - lo
    at_bound: dict[str, str] = {}
    for j, n in enumerate(names):
        if best[j] - lo[j] <= AT_BOUND * span[j]:
            at_bound[n] = "lower"
        elif hi[j] - best[j] <= AT_BOUND * span[j]:
            at_bound[n] = "upper"
    return at_bound


def _chi2_reasons(
    residuals: Sequence[tuple[str, float]],
    chi2: float,
    tested: int,
    p: float,
    dof: int,
    m: int,
    free: int,
    fail: list[str],
    poor: list[str],
    notes: list[str],
) -> None:
    """The chi^2 test's reason (does not fit below P_REJECT, poor below P_POOR, with the
    largest residuals) and a note when there are no degrees of freedom to spare."""
    worst = ", ".join(f"{k} {v:+.3g}" for k, v in sorted(residuals, key=lambda r: -abs(r[1]))
                      [:WORST])  # fmt: skip
    test = f"chi^2 {chi2:.4g} with {_count(tested, 'degree')} of freedom: p = {p:.2g}"
    if p < P_REJECT:
        fail.append(f"{test} < {P_REJECT:.2g} (5 sigma): the model cannot give the evidence "
                    f"within its tolerances (largest residuals, in tolerances: {worst})")
    elif p < P_POOR:
        poor.append(f"{test} < {P_POOR:g}: the residuals are larger than the tolerances "
                    f"allow (largest, in tolerances: {worst})")  # fmt: skip
    if dof <= 0:
        notes.append(f"{_count(dof, 'degree')} of freedom ({_count(m, 'residual')}, "
                     f"{_count(free, 'free unknown')}): the evidence has no residual to "
                     "spare, so chi^2 tests little")  # fmt: skip


def _range_rule(
    p: float | None, chi2: float, tested: int, withheld: tuple[str, ...]
) -> tuple[float, str]:
    """The ranges' scale (the Birge ratio when the chi^2 test is poor, else 1) and the rule's
    words, for a fit that fits or fits poorly."""
    scale = 1.0
    parts = []
    if p is not None and p < P_POOR:
        scale = math.sqrt(chi2 / tested)
        parts.append(f"widened by the Birge ratio sqrt(chi^2/dof) = {scale:.3g}")
    if withheld:
        parts.append(f"withheld for {', '.join(withheld)} (at a bound or not fixed)")
    return scale, "; ".join(parts) if parts else "as computed"


def _note_ranges_at_bounds(
    names: Sequence[str],
    withheld: tuple[str, ...],
    scale: float,
    best: Array,
    lo: Array,
    hi: Array,
    sigma: Array,
    notes: list[str],
) -> None:
    """A note for each quoted 95 % range (the Jacobian's, scaled) that reaches a bound."""
    from scipy.stats import norm

    z = float(norm.ppf(0.975))  # 1.96: the Jacobian's two-sided 95 %
    for j, n in enumerate(names):
        if n in withheld:
            continue
        reach = scale * z * sigma[j]
        if best[j] - reach <= lo[j] or best[j] + reach >= hi[j]:
            notes.append(f"{n}'s 95 % range reaches a bound: that end is the bound's, "
                         "not the evidence's")  # fmt: skip
