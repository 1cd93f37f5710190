"""Uncertainty outputs of a study: percentiles of every column, and each output's unit.

``percentiles(study)`` gives, over the variants that ran to the end (status "ok"), for every
input path and every output column: its unit, the count of finite values, mean, standard
deviation, minimum, the percentiles (5, 25, 50, 75, 95 by default; numpy's linear
interpolation between order statistics) and maximum. A column with no finite value (e.g.
``impact2.*`` when no variant had a second impact, ``rest_*`` without a ground) has count 0
and NaN elsewhere.
"""

from __future__ import annotations

import math
from collections.abc import Mapping, Sequence
from typing import TYPE_CHECKING, Protocol

import numpy as np
from numpy.typing import NDArray

from crashsim.errors import StudyError

if TYPE_CHECKING:
    import pandas as pd

__all__ = ["PERCENTILES", "format_summary", "output_unit", "percentiles"]

PERCENTILES: tuple[float, ...] = (5.0, 25.0, 50.0, 75.0, 95.0)


def output_unit(name: str) -> str:
    """The unit of a batch column by its name (the batch contract's units)."""
    last = name.rsplit(".", 1)[-1]
    if name == "n_impacts":
        return "count"
    if last.endswith("_deg"):
        return "deg"
    if last in ("time", "rest_time", "first_contact_time", "head_time"):
        return "s"
    if last == "energy":
        return "J"
    if last.startswith("delta_v") or last == "total_delta_v" or last == "final_speed":
        return "m/s"
    if last in ("head_relative_speed",):
        return "m/s"
    if last in ("final_x", "final_y", "rest_x", "rest_y", "throw_distance", "head_x", "head_y",
                "head_z", "head_wrap_around"):  # fmt: skip
        return "m"
    return ""


def _check(ps: Sequence[float]) -> tuple[float, ...]:
    out = []
    for p in ps:
        try:
            x = float(p)
        except (TypeError, ValueError):
            raise StudyError(f"percentile {p!r} is not a number in [0, 100]") from None
        if not 0.0 <= x <= 100.0:
            raise StudyError(f"percentile {p!r} is outside [0, 100]")
        out.append(x)
    return tuple(out)


class StudyColumns(Protocol):
    """What the summary reads of a study (crashsim.studies.run.Study has it): the columns
    by name, which are inputs, their units, and which variants ran."""

    @property
    def ok(self) -> NDArray[np.bool_]: ...
    @property
    def inputs(self) -> Mapping[str, np.ndarray]: ...
    @property
    def outputs(self) -> Mapping[str, np.ndarray]: ...
    @property
    def units(self) -> Mapping[str, str]: ...
    def __getitem__(self, name: str) -> np.ndarray: ...


def percentiles(study: StudyColumns, ps: Sequence[float] | None = None) -> pd.DataFrame:
    """The summary table (see the module docstring): one row per column, index = the column
    name; columns unit, n, mean, sd, min, P<p> ..., max."""
    import pandas as pd

    qs = _check(PERCENTILES if ps is None else ps)
    ok = study.ok
    rows = []
    names = []
    for name in [*study.inputs, *study.outputs]:
        x = np.asarray(study[name], dtype=np.float64)[ok]
        if name == "n_impacts":
            x = x[x >= 0]
        x = x[np.isfinite(x)]
        unit = study.units.get(name, "") if name in study.inputs else output_unit(name)
        row: dict[str, object] = {"unit": unit, "n": int(x.size)}
        if x.size:
            row.update(mean=float(np.mean(x)), sd=float(np.std(x, ddof=1)) if x.size > 1
                       else math.nan, min=float(np.min(x)))
            row.update({f"P{q:g}": float(v) for q, v in zip(qs, np.percentile(x, qs),
                                                             strict=True)})
            row["max"] = float(np.max(x))
        else:
            row.update(mean=math.nan, sd=math.nan, min=math.nan)
            row.update({f"P{q:g}": math.nan for q in qs})
            row["max"] = math.nan
        rows.append(row)
        names.append(name)
    out = pd.DataFrame(rows, index=pd.Index(names, name="column"))
    return out


def format_summary(table: pd.DataFrame, *, skip_empty: bool = True) -> str:
    """The summary as a fixed-width text table (6 significant digits), for the terminal;
    rows without a finite value left out unless ``skip_empty`` is False."""
    shown = table[table["n"] > 0] if skip_empty else table
    cols = [c for c in shown.columns if c not in ("unit", "n")]
    width = max([len("column"), *(len(str(i)) for i in shown.index)])
    head = f"{'column':<{width}}  {'unit':<5} {'n':>6}" + "".join(f"{c:>12}" for c in cols)
    lines = [head]
    for name, row in shown.iterrows():
        cells = "".join(f"{float(row[c]):>12.6g}" for c in cols)
        lines.append(f"{name!s:<{width}}  {row['unit']!s:<5} {int(row['n']):>6}{cells}")
    return "\n".join(lines)
