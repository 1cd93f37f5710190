"""What a fit returns: FitResult (the best values, ranges, residuals, verdict; its text,
picture and plain data) and ItemResidual (one evidence item at the optimum)."""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass, field
from os import PathLike
from typing import TYPE_CHECKING, Any

import numpy as np

from crashsim.studies.evidence import Evidence
from crashsim.studies.fit.problem import Array
from crashsim.studies.verdict import Verdict

if TYPE_CHECKING:
    from crashsim.result import Result
    from crashsim.scene import Scene

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
