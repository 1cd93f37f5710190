"""The picture of a fit (FitResult.plot): the fitted run over the evidence, seen from above,
and the objective along each unknown around the optimum (the scan, the samples, the 95 %
ranges as the fit's verdict quotes them: green the Jacobian's, orange dashed the sampling's;
the verdict leads the title), each unknown in the unit it was written in when given (a scene
file's: ``crashsim fit``), else SI with angles in degrees."""

from __future__ import annotations

import math
from collections.abc import Mapping, Sequence
from os import PathLike
from typing import TYPE_CHECKING, Any, Protocol

import numpy as np

from crashsim.studies.evidence import ImpactPoint, RestHeading, RestPosition, TyreMark

if TYPE_CHECKING:
    from crashsim.result import Result
    from crashsim.studies.evidence import Evidence
    from crashsim.studies.verdict import Verdict


class FitPicture(Protocol):
    """What the picture reads of a fit (crashsim.studies.fit.result.FitResult has it)."""

    @property
    def names(self) -> Sequence[str]: ...
    @property
    def units(self) -> Mapping[str, str]: ...
    @property
    def values(self) -> Mapping[str, float]: ...
    @property
    def objective(self) -> float: ...
    @property
    def sigma(self) -> Mapping[str, float]: ...
    @property
    def ranges(self) -> Mapping[str, tuple[float, float] | None]: ...
    @property
    def evidence(self) -> Sequence[Evidence]: ...
    @property
    def result(self) -> Result | None: ...
    @property
    def scan(self) -> Mapping[str, tuple[Any, Any]] | None: ...
    @property
    def sample_ranges(self) -> Mapping[str, tuple[float, float] | None] | None: ...
    @property
    def samples(self) -> Any: ...
    @property
    def verdict(self) -> Verdict | None: ...

EVIDENCE = "#d62728"  # colour of the evidence (red); the fitted run in the vehicles' colours


def plot_fit(
    fit: FitPicture,
    path: str | PathLike[str] | None = None,
    units: Mapping[str, tuple[str, float]] | None = None,
) -> Any:
    """``units``: {unknown: (unit name, SI per unit)} for the unknowns to show in another
    unit than SI (e.g. {"red.speed": ("km/h", 1 / 3.6)})."""
    from matplotlib.patches import Circle

    from crashsim.plots import _new_figure, silhouette, vehicle_colour
    from crashsim.records import rotation_matrix

    k = len(fit.names)
    fig = _new_figure((12.0, max(5.0, 2.2 * k)))
    grid = fig.add_gridspec(k, 2, width_ratios=(2.2, 1.0))
    ax = fig.add_subplot(grid[:, 0])
    ax.set_aspect("equal")
    ax.set_xlabel("x (m)")
    ax.set_ylabel("y (m)")
    said = "" if fit.verdict is None else f"{fit.verdict.status.upper()}: "
    ax.set_title(f"{said}fitted run (chi^2 = {fit.objective:.3g}) over the evidence (red)")
    result = fit.result
    if result is not None:
        for i, name in enumerate(result.vehicles):
            c = vehicle_colour(i)
            tr = result.trajectory(name)
            ax.plot(tr.position[:, 0], tr.position[:, 1], color=c, lw=1.2, label=f"{name} CG")
            for j, at in ((0, "start"), (-1, "rest")):
                shape = silhouette(result.vehicle(name), tr.position[j],
                                   rotation_matrix(tr.orientation[j]))  # fmt: skip
                geoms = getattr(shape, "geoms", [shape])
                for g in geoms:
                    xy = np.asarray(g.exterior.coords)
                    ax.fill(xy[:, 0], xy[:, 1], color=c, alpha=0.12 if at == "start" else 0.3,
                            lw=1.0, ec=c)  # fmt: skip
        for imp in result.impacts:
            ax.plot(imp.centroid[0], imp.centroid[1], "k*", ms=9)
    for e in fit.evidence:
        if isinstance(e, RestPosition):
            ax.add_patch(Circle((e.x, e.y), e.tolerance, fill=False, ec=EVIDENCE, lw=1.2))
            ax.plot(e.x, e.y, "+", color=EVIDENCE, ms=10, mew=1.5)
        elif isinstance(e, ImpactPoint):
            ax.add_patch(Circle((e.x, e.y), e.tolerance, fill=False, ec=EVIDENCE, lw=1.0,
                                ls="--"))  # fmt: skip
            ax.plot(e.x, e.y, "x", color=EVIDENCE, ms=8)
        elif isinstance(e, TyreMark):
            p = np.asarray(e.polyline, dtype=float)
            ax.plot(p[:, 0], p[:, 1], color=EVIDENCE, lw=3.0, alpha=0.5)
            if result is not None:
                w = result.wheel_path(e.vehicle, e.wheel)
                ax.plot(w[:, 0], w[:, 1], color="0.3", lw=0.8, ls=":")
    for e in fit.evidence:  # headings drawn from the evidence's rest position
        if isinstance(e, RestHeading):
            at = next((p for p in fit.evidence if isinstance(p, RestPosition)
                       and p.vehicle == e.vehicle), None)  # fmt: skip
            if at is None:
                continue
            for h, ls in ((e.heading, "-"), (e.heading - e.tolerance, ":"),
                          (e.heading + e.tolerance, ":")):  # fmt: skip
                ax.plot([at.x, at.x + 2.0 * math.cos(h)], [at.y, at.y + 2.0 * math.sin(h)],
                        color=EVIDENCE, lw=1.2, ls=ls)  # fmt: skip
    ax.legend(loc="best", fontsize=8)
    ax.autoscale_view()
    for j, n in enumerate(fit.names):
        a = fig.add_subplot(grid[j, 1])
        best = fit.values[n]
        if units is not None and n in units:
            shown, factor = units[n]
            scale = 1.0 / factor
        elif fit.units[n] == "rad":
            scale, shown = 180.0 / math.pi, "deg"
        else:
            scale, shown = 1.0, fit.units[n]
        if fit.samples is not None:  # its lower edge: the profile (the others free)
            keep = fit.samples.chi2 - fit.objective <= 4.0 * 3.84
            a.plot(fit.samples.x[keep, j] * scale, fit.samples.chi2[keep] - fit.objective, ".",
                   ms=2, color="0.6", label="samples")  # fmt: skip
        if fit.scan is not None and n in fit.scan:
            xs, chi = fit.scan[n]
            a.plot(xs * scale, chi - fit.objective, "o-", ms=3, color="C0", label="scan")
        s = fit.sigma[n]
        if math.isfinite(s) and s > 0:
            xs = np.linspace(best - 3 * s, best + 3 * s, 61)
            a.plot(xs * scale, ((xs - best) / s) ** 2, color="0.5", lw=1, ls="--",
                   label="Jacobian")  # fmt: skip
        a.axhline(3.84, color=EVIDENCE, lw=0.8, ls=":")
        span = fit.ranges[n]  # None where the verdict withholds it
        if span is not None and math.isfinite(span[0]) and math.isfinite(span[1]):
            a.axvspan(span[0] * scale, span[1] * scale, color="C2", alpha=0.15)
        sampled = fit.sample_ranges.get(n) if fit.sample_ranges is not None else None
        for v in sampled or ():
            a.axvline(v * scale, color="C1", lw=1.0, ls="--")
        a.axvline(best * scale, color="k", lw=0.8)
        a.set_xlabel(f"{n} ({shown})")
        a.set_ylabel("chi^2 - best")
        if j == 0:
            a.legend(fontsize=7)
    if path is not None:
        fig.savefig(path, dpi=110)
    return fig
