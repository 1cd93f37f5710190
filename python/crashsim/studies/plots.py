"""Pictures of a study (matplotlib's object API on the Agg canvas, no pyplot state):
histograms of the outputs, the tornado chart, the Sobol indices. Each function writes a PNG
(or any format matplotlib knows by the suffix) when given a path and returns the Figure."""

from __future__ import annotations

import math
import re
from collections.abc import Sequence
from pathlib import Path
from typing import TYPE_CHECKING, Any, Protocol

import numpy as np

from crashsim.errors import StudyError
from crashsim.studies.summary import output_unit

if TYPE_CHECKING:
    import pandas as pd
    from matplotlib.figure import Figure

    from crashsim.studies.run import Study


class TornadoTable(Protocol):
    """What the tornado chart reads (crashsim.studies.sensitivity.Tornado has it)."""

    @property
    def study(self) -> Study: ...
    def table(self, output: str) -> pd.DataFrame: ...


class SobolIndices(Protocol):
    """What the Sobol chart reads (crashsim.studies.sensitivity.Sobol has it)."""

    @property
    def study(self) -> Study: ...
    @property
    def n(self) -> int: ...
    def of(self, output: str) -> pd.DataFrame: ...

__all__ = ["histogram_file", "plot_histogram", "plot_histograms", "plot_sobol", "plot_tornado"]

_BLUE, _ORANGE, _GREY = "#3b6ea8", "#d9822b", "#555555"


def _figure(size: tuple[float, float]) -> Figure:
    from matplotlib.backends.backend_agg import FigureCanvasAgg
    from matplotlib.figure import Figure

    fig = Figure(figsize=size, layout="constrained")
    FigureCanvasAgg(fig)
    return fig


def _save(fig: Figure, path: Any) -> None:
    if path is not None:
        fig.savefig(Path(path), dpi=110)


def _label(study: Study, name: str) -> str:
    unit = study.units.get(name, "") if name in study.inputs else output_unit(name)
    return f"{name} [{unit}]" if unit else name


def histogram_file(column: str) -> str:
    """The file name of a column's histogram: hist-<column with unsafe characters as _>.png."""
    return "hist-" + re.sub(r"[^A-Za-z0-9._-]+", "_", column) + ".png"


def plot_histogram(study: Study, column: str, path: Any = None, bins: Any = "auto") -> Figure:
    """Histogram of one column over the variants that ran to the end, with the 5th, 50th and
    95th percentiles marked and the count of variants without a value."""
    x = np.asarray(study[column], dtype=np.float64)[study.ok]
    finite = x[np.isfinite(x)]
    if finite.size == 0:
        raise StudyError(f"{column!r} has no finite value in the study: nothing to draw")
    fig = _figure((6.4, 4.3))
    ax = fig.add_subplot()
    if np.ptp(finite) == 0.0:
        bins = 1
    ax.hist(finite, bins=bins, color=_BLUE, edgecolor="white", linewidth=0.5)
    p5, p50, p95 = np.percentile(finite, [5, 50, 95])
    for value, label, style in ((p5, "P5", ":"), (p50, "P50 (median)", "-"), (p95, "P95", "--")):
        ax.axvline(value, color=_ORANGE, linestyle=style, linewidth=1.5,
                   label=f"{label} = {value:.4g}")
    fig.legend(loc="outside lower center", ncols=3, fontsize=8, frameon=False)
    ax.set_xlabel(_label(study, column))
    ax.set_ylabel("variants")
    missing = int(x.size - finite.size)
    failed = int(study.n - study.ok.sum())
    note = f"{finite.size} of {study.n} variants"
    if missing:
        note += f"; {missing} without a value"
    if failed:
        note += f"; {failed} failed or not run"
    ax.set_title(f"{column}\n{study.kind}, {note}", fontsize=10)
    ax.grid(axis="y", alpha=0.3)
    _save(fig, path)
    return fig


def plot_histograms(
    study: Study, folder: str | Path, columns: Sequence[str] | None = None
) -> list[Path]:
    """A histogram PNG per column (default: every output with a finite value and every
    input) into ``folder`` (created if needed), named :func:`histogram_file`; returns the
    paths."""
    out = Path(folder)
    out.mkdir(parents=True, exist_ok=True)
    names = list(columns) if columns is not None else [*study.inputs, *study.outputs]
    written = []
    for name in names:
        x = np.asarray(study[name], dtype=np.float64)[study.ok]
        if name == "n_impacts" and columns is None:
            x = x[x >= 0]
        if not np.any(np.isfinite(x)):
            if columns is not None:
                raise StudyError(f"{name!r} has no finite value in the study: nothing to draw")
            continue
        path = out / histogram_file(name)
        plot_histogram(study, name, path)
        written.append(path)
    return written


def plot_tornado(tornado: TornadoTable, output: str, path: Any = None) -> Figure:
    """The tornado chart of one output: per path (largest swing on top) a bar from the
    output at the base to the output at the path's low (one colour) and high (the other)
    value, the base output as a vertical line, the input range written beside each bar."""
    table = tornado.table(output)
    k = len(table)
    fig = _figure((7.6, 1.4 + 0.55 * k))
    ax = fig.add_subplot()
    base = float(table["base_output"].iloc[0]) if k else math.nan
    for row, (_, r) in enumerate(table.iterrows()):
        y = k - 1 - row
        for value, colour in ((r["output_low"], _BLUE), (r["output_high"], _ORANGE)):
            if np.isfinite(value) and np.isfinite(base):
                ax.barh(y, value - base, left=base, height=0.6, color=colour)
        unit = f" {r['unit']}" if r["unit"] and r["unit"] != "1" else ""
        ax.annotate(f"{r['low']:.4g} .. {r['high']:.4g}{unit}", xy=(1.0, y),
                    xycoords=("axes fraction", "data"), xytext=(4, 0),
                    textcoords="offset points", va="center", fontsize=8, color=_GREY)
    ax.set_yticks(range(k), list(table.index)[::-1])
    if np.isfinite(base):
        ax.axvline(base, color="black", linewidth=1)
    ax.set_xlabel(_label(tornado.study, output))
    from matplotlib.patches import Patch

    fig.legend(handles=[Patch(color=_BLUE, label="input at its low value"),
                        Patch(color=_ORANGE, label="input at its high value")],
               loc="outside lower center", ncols=2, fontsize=8, frameon=False)
    ax.set_title(f"Tornado: {output} (base {base:.4g}), one input at a time", fontsize=10)
    ax.grid(axis="x", alpha=0.3)
    _save(fig, path)
    return fig


def plot_sobol(result: SobolIndices, output: str, path: Any = None) -> Figure:
    """First-order (S1) and total (ST) Sobol indices of one output per path, with their
    95 % confidence intervals."""
    table = result.of(output)
    k = len(table)
    fig = _figure((6.8, 1.6 + 0.6 * k))
    ax = fig.add_subplot()
    y = np.arange(k)[::-1]
    h = 0.38
    ax.barh(y + h / 2, table["S1"], height=h, xerr=table["S1_conf"], color=_BLUE,
            label="S1 (first order: the input alone)", capsize=3)
    ax.barh(y - h / 2, table["ST"], height=h, xerr=table["ST_conf"], color=_ORANGE,
            label="ST (total: with its interactions)", capsize=3)
    ax.set_yticks(y, list(table.index))
    ax.set_xlim(min(0.0, float(np.nanmin(table[["S1", "ST"]].to_numpy())) - 0.05),
                max(1.05, float(np.nanmax(table[["S1", "ST"]].to_numpy())) + 0.05))
    ax.axvline(0.0, color="black", linewidth=0.8)
    ax.set_xlabel("share of the output's variance")
    fig.legend(loc="outside lower center", ncols=2, fontsize=8, frameon=False)
    runs = result.study.n
    ax.set_title(f"Sobol indices of {output}\n(Saltelli design, n = {result.n}, {runs} runs)",
                 fontsize=10)
    ax.grid(axis="x", alpha=0.3)
    _save(fig, path)
    return fig
