"""Which input matters: the tornado (one at a time) and Sobol indices (variance-based).

**Tornado** (:func:`tornado`): the base variant (every path at the base scene's value, read
as the path's rule reads it: crashsim.studies.paths.base_value), then each path at its low
and at its high value with the others at their base: 1 + 2 k runs for k paths. A path's range
is ``(low, high)`` (SI) or a distribution, whose 5th and 95th percentiles are taken. The
swing of an output is |output(high) - output(low)|; the chart sorts the paths by it.

**Sobol indices** (:func:`sobol`, SALib): Saltelli's design (SALib.sample.sobol, scrambled
Sobol' points, no second-order terms) of n (a power of 2) base points in the unit hypercube,
mapped through each distribution's inverse CDF, n (k + 2) runs; SALib.analyze.sobol gives
each path's first-order index S1 (the share of the output's variance due to that input
alone) and total index ST (with its interactions), with 95 % bootstrap confidence intervals.
An output with a non-finite value in any variant (a failed variant, no second impact) or no
variance is left out (``Sobol.skipped`` says why).
"""

from __future__ import annotations

import math
from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any

import numpy as np

from crashsim.errors import StudyError
from crashsim.studies import design, paths
from crashsim.studies.distributions import Distribution
from crashsim.studies.run import Study, check_size, run_study

if TYPE_CHECKING:
    import pandas as pd

    from crashsim.scene import Scene

__all__ = ["Sobol", "Tornado", "sobol", "tornado"]

TORNADO_PERCENTILES = (5.0, 95.0)  # a distribution's range in a tornado


def _default_outputs(scene: Scene) -> list[str]:
    return [f"impact1.{v.name}.delta_v" for v in scene.vehicles]


@dataclass(eq=False)
class Tornado:
    """A one-at-a-time study: ``study`` (variant 0 the base, then low and high of each path
    in order), ``base`` ({path: value}), ``ranges`` ({path: (low, high)}), SI."""

    study: Study
    base: dict[str, float]
    ranges: dict[str, tuple[float, float]]
    outputs: list[str] = field(default_factory=list)

    def table(self, output: str) -> pd.DataFrame:
        """One row per path, largest swing first: low, high (the input's, SI), the output at
        the base, at low and at high, and the swing |at high - at low|."""
        import pandas as pd

        y = np.asarray(self.study[output], dtype=np.float64)
        rows = []
        for c, k in enumerate(self.ranges):
            lo, hi = self.ranges[k]
            y_lo, y_hi = float(y[1 + 2 * c]), float(y[2 + 2 * c])
            rows.append({"path": k, "unit": self.study.units.get(k, ""), "low": lo, "high": hi,
                         "base_output": float(y[0]), "output_low": y_lo, "output_high": y_hi,
                         "swing": abs(y_hi - y_lo)})
        out = pd.DataFrame(rows).sort_values("swing", ascending=False, na_position="last")
        return out.set_index("path")

    def plot(self, path: Any = None, output: str | None = None) -> Any:
        """The tornado chart of one output (default: the first); PNG when ``path`` is
        given. Returns the matplotlib Figure."""
        from crashsim.studies.plots import plot_tornado

        return plot_tornado(self, output or self.outputs[0], path)


def tornado(
    scene: Scene,
    ranges: Mapping[str, tuple[float, float] | Distribution],
    *,
    outputs: Sequence[str] | None = None,
    **run: Any,
) -> Tornado:
    """Run the one-at-a-time design of ``ranges`` ({path: (low, high) SI, or a distribution:
    its 5th and 95th percentiles}) around the base scene. ``outputs``: the columns the chart
    shows first (default the first impact's delta-V of each vehicle). Other keywords as for
    crashsim.sweep (duration, dt, until, backend, ...)."""
    if not ranges:
        raise StudyError("a tornado needs at least one parameter path and its range")
    lohi: dict[str, tuple[float, float]] = {}
    for k, r in ranges.items():
        if isinstance(r, Distribution):
            r.check(k)
            lohi[k] = (r.percentile(TORNADO_PERCENTILES[0]), r.percentile(TORNADO_PERCENTILES[1]))
            continue
        try:
            lo, hi = (float(x) for x in r)
        except (TypeError, ValueError):
            raise StudyError(
                f'"{k}": a range is (low, high) in SI or a distribution, got {r!r}', k
            ) from None
        if not (math.isfinite(lo) and math.isfinite(hi)) or lo == hi:
            raise StudyError(f'"{k}": the range ({lo:g}, {hi:g}) needs two different finite ends',
                             k)
        lohi[k] = (lo, hi)
    base = {k: paths.base_value(scene, k) for k in lohi}
    values = design.one_at_a_time(base, lohi)
    study = run_study(scene, values, kind="one-at-a-time", **run)
    return Tornado(study, base, lohi, list(outputs or _default_outputs(scene)))


@dataclass(eq=False)
class Sobol:
    """Sobol indices: ``study`` (the Saltelli design's runs), ``indices`` (a DataFrame, index
    (output, path): S1, S1_conf, ST, ST_conf), ``skipped`` ({output: why}), ``n`` (base
    points), ``seed``."""

    study: Study
    indices: pd.DataFrame
    skipped: dict[str, str]
    n: int
    seed: int | None
    outputs: list[str] = field(default_factory=list)

    def of(self, output: str) -> pd.DataFrame:
        """The indices of one output, one row per path."""
        if output in self.skipped:
            raise StudyError(f"no Sobol indices for {output!r}: {self.skipped[output]}")
        analysed = list(dict.fromkeys(self.indices.index.get_level_values("output")))
        if output not in analysed:
            self.study[output]  # UnknownColumnError for a column the study does not have
            raise StudyError(f"no Sobol indices for {output!r}: the outputs analysed are "
                             f"{', '.join(analysed)}")  # fmt: skip
        return self.indices.xs(output, level="output")

    def plot(self, path: Any = None, output: str | None = None) -> Any:
        """Bar chart of S1 and ST (with confidence intervals) of one output."""
        from crashsim.studies.plots import plot_sobol

        return plot_sobol(self, output or self.outputs[0], path)


def sobol(
    scene: Scene,
    distributions: Mapping[str, Distribution],
    n: int,
    seed: int | None = None,
    *,
    outputs: Sequence[str] | None = None,
    **run: Any,
) -> Sobol:
    """Sobol indices of the outputs (default: every output column with finite values in all
    variants and some variance) with respect to the paths of ``distributions``, from
    Saltelli's design of ``n`` base points (a power of 2; n (k + 2) runs). Other keywords as
    for crashsim.sweep."""
    try:
        from SALib.analyze import sobol as analyze
        from SALib.sample import sobol as sample
    except ImportError as e:  # pragma: no cover - SALib is in the study extra
        raise ImportError("Sobol indices need SALib: pip install 'crashsim[study]'") from e
    design._check_distributions(distributions)
    n = design._count(n)
    if n & (n - 1):
        raise StudyError(
            f"n = {n}: the Sobol' design needs a power of 2 base points (e.g. "
            f"{1 << max(0, n.bit_length() - 1)} or {1 << n.bit_length()})"
        )
    keys = list(distributions)
    check_size(scene, keys, n * (len(keys) + 2), run.get("max_impacts", 2),
               run.get("max_study_bytes"))  # fmt: skip
    problem = {"num_vars": len(keys), "names": keys, "bounds": [[0.0, 1.0]] * len(keys)}
    u = sample.sample(problem, n, calc_second_order=False, seed=seed)
    values = {k: np.asarray(distributions[k].ppf(u[:, c]), dtype=np.float64)
              for c, k in enumerate(keys)}
    study = run_study(scene, values, kind="sobol", seed=seed, distributions=distributions, **run)
    import pandas as pd

    rows = []
    skipped: dict[str, str] = {}
    wanted = list(outputs) if outputs is not None else [
        k for k, v in study.outputs.items() if v.dtype.kind == "f"
    ]
    for out in wanted:
        y = np.asarray(study[out], dtype=np.float64)
        if not np.all(np.isfinite(y)):
            skipped[out] = f"{int(np.count_nonzero(~np.isfinite(y)))} variants have no value"
            continue
        if np.ptp(y) == 0.0:
            skipped[out] = "the output does not vary"
            continue
        s = analyze.analyze(problem, y, calc_second_order=False, seed=seed,
                            print_to_console=False)
        for c, k in enumerate(keys):
            rows.append({"output": out, "path": k, "S1": float(s["S1"][c]),
                         "S1_conf": float(s["S1_conf"][c]), "ST": float(s["ST"][c]),
                         "ST_conf": float(s["ST_conf"][c])})
    frame = pd.DataFrame(rows, columns=["output", "path", "S1", "S1_conf", "ST", "ST_conf"])
    frame = frame.set_index(["output", "path"])
    shown = [o for o in (outputs or _default_outputs(scene)) if o not in skipped]
    return Sobol(study, frame, skipped, n, seed, shown or list(dict.fromkeys(
        frame.index.get_level_values("output"))))
