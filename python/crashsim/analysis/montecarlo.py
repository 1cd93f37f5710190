"""Monte Carlo of the depth of penetration dt_p = sqrt(m'/k') over vehicle-class pairs.

The seed note's study, made precise:

* Configurations: "front-front" (vehicle 1's front into vehicle 2's front), "front-rear"
  (1's front into 2's rear), "front-side" (1's front into 2's side) and "rear-side" (1's rear
  into 2's side).
* Pairs: in every configuration, vehicle 1 and vehicle 2 are each one of the N classes, as
  ORDERED pairs (class i as vehicle 1, class j as vehicle 2), a class meeting itself
  included: N^2 pairs, all weighted equally. In the symmetric front-front case this is the
  same as drawing both vehicles independently: an unordered pair of two different classes
  counts twice (i, j and j, i), a class against itself once. A class without B data for a
  face is left out only of the role that needs that face (e.g. without rear data it still
  strikes with its front in front-rear, but is never struck there); ``DtpMonteCarlo.excluded``
  lists what was left out.
* Weights: the samples are split equally between the configurations (the first ones get one
  more when the count does not divide) and, within a configuration, cyclically between its
  pairs (sample k takes pair k mod P): stratified, so every pair's count is within one of
  every other's and no pair is favoured by chance.
* Each sample: mass m_i, width w_i and the struck face's B_i of each vehicle drawn
  independently and uniformly in [mean - sd, mean + sd] (no variation when sd is None);
  full-width, in-line engagement over the smaller width W = min(w1, w2); k_i = B_i W;
  dt_p = sqrt(m'/k') with m' = m1 m2 / (m1 + m2) and k' = k1 k2 / (k1 + k2) (seed eqs.
  19-21, 28). Central impacts, so no effective-mass factor.
* Random numbers: ``numpy.random.default_rng(seed)``, one draw of a (6, samples) block of
  uniforms; the same seed and inputs give the same bits.

The vehicle classes come from ``crashsim.vehicles.vehicle_data.vehicle_classes()`` unless given: a
mapping name -> class (or a sequence of classes, named by their ``name`` attribute) where a
class has ``mass``, ``width`` and faces ``front``, ``rear``, ``side``, each face with ``B``;
mass, width and B are figures with ``value`` and ``sd`` (SI: kg, m, N/m^2; sd may be None).
Times are in s in the API; the command line and the picture show ms.
"""

from __future__ import annotations

import math
import numbers
from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import TYPE_CHECKING, Any

import numpy as np
from numpy.typing import NDArray

from crashsim.errors import ParameterError

if TYPE_CHECKING:
    from matplotlib.figure import Figure

__all__ = [
    "BAND",
    "CONFIGURATIONS",
    "PERCENTILES",
    "DtpMonteCarlo",
    "dtp_montecarlo",
    "plot_dtp_histogram",
    "summarize",
]

Array = NDArray[np.float64]

# configuration -> (vehicle 1's face, vehicle 2's face)
_FACES: dict[str, tuple[str, str]] = {
    "front-front": ("front", "front"),
    "front-rear": ("front", "rear"),
    "front-side": ("front", "side"),
    "rear-side": ("rear", "side"),
}
CONFIGURATIONS: tuple[str, ...] = tuple(_FACES)
PERCENTILES: tuple[float, ...] = (2.5, 5.0, 25.0, 50.0, 75.0, 95.0, 97.5)
BAND: tuple[float, float] = (0.010, 0.060)  # s: the seed's typical range of dt_p


def _pkey(p: float) -> str:
    """'2.5', '5', '50', ... (percentile keys of the summary)."""
    return f"{p:g}"


def summarize(dtp: Any, band: tuple[float, float] = BAND) -> dict[str, Any]:
    """Summary of depth-of-penetration samples (s): ``n``; ``mean`` (s); ``percentiles``
    {"2.5": s, "5": s, "25": s, "50": s, "75": s, "95": s, "97.5": s} (numpy's default
    linear interpolation between order statistics); ``fraction_in_band``: the share of
    samples with band[0] <= dt_p <= band[1] (default 10-60 ms)."""
    x = np.asarray(dtp, dtype=np.float64).ravel()
    if x.size == 0:
        raise ParameterError("no samples to summarise")
    lo, hi = band
    q = np.percentile(x, PERCENTILES)
    return {
        "n": int(x.size),
        "mean": float(np.mean(x)),
        "percentiles": {_pkey(p): float(v) for p, v in zip(PERCENTILES, q, strict=True)},
        "fraction_in_band": float(np.count_nonzero((x >= lo) & (x <= hi)) / x.size),
    }


@dataclass(frozen=True, eq=False)
class DtpMonteCarlo:
    """The samples of ``dtp_montecarlo`` (one entry per sample, grouped by configuration).

    dtp: depth of penetration, s. configuration: index into ``configurations``. class1,
    class2: indices into ``class_names`` of vehicle 1 (striking face) and vehicle 2.
    mass1, mass2: kg; width: the engagement width min(w1, w2), m; B1, B2: the faces' B,
    N/m^2. pairs: per configuration, the (class 1, class 2) names used. excluded: per
    configuration, what was left out for missing face data, as "name (vehicle k: no <face> B)".
    seed: the generator's seed."""

    dtp: Array
    configuration: NDArray[np.int8]
    class1: NDArray[np.int16]
    class2: NDArray[np.int16]
    mass1: Array
    mass2: Array
    width: Array
    B1: Array
    B2: Array
    class_names: tuple[str, ...]
    configurations: tuple[str, ...]
    pairs: dict[str, tuple[tuple[str, str], ...]] = field(default_factory=dict)
    excluded: dict[str, tuple[str, ...]] = field(default_factory=dict)
    seed: int | None = None

    def __len__(self) -> int:
        return int(self.dtp.size)

    def samples_of(self, configuration: str) -> Array:
        """The dt_p samples (s) of one configuration."""
        if configuration not in self.configurations:
            raise ParameterError(
                f"unknown configuration {configuration!r}: use one of "
                f"{', '.join(self.configurations)}"
            )
        return self.dtp[self.configuration == self.configurations.index(configuration)]

    def summary(self, band: tuple[float, float] = BAND) -> dict[str, Any]:
        """{"samples", "seed", "band": [lo, hi] s, "overall": summarize(all),
        "by_configuration": {name: summarize(its samples)}}; times in s."""
        return {
            "samples": len(self),
            "seed": self.seed,
            "band": [float(band[0]), float(band[1])],
            "overall": summarize(self.dtp, band),
            "by_configuration": {
                c: summarize(self.samples_of(c), band) for c in self.configurations
            },
        }


# --- reading the class data -----------------------------------------------------------------


def _spread(fig: Any, what: str, unit: str) -> tuple[float, float]:
    """(mean, half-range) of a figure with ``value`` and ``sd`` (sd None -> 0)."""
    value = getattr(fig, "value", fig)
    sd = getattr(fig, "sd", None)
    try:
        v = float(value)
        s = 0.0 if sd is None else float(sd)
    except (TypeError, ValueError) as e:
        raise ParameterError(f"{what}: value and sd must be numbers ({unit}), got {fig!r}") from e
    if not (math.isfinite(v) and math.isfinite(s)) or s < 0.0:
        raise ParameterError(f"{what}: value = {v}, sd = {s} must be finite with sd >= 0 ({unit})")
    if v - s <= 0.0:
        raise ParameterError(
            f"{what}: value - sd = {v} - {s} <= 0 {unit}, so uniform sampling within one "
            "standard deviation would give non-positive values; fix the class data"
        )
    return v, s


def _face_b(cls: Any, face: str) -> Any:
    """The B figure of a class's face, or None without data."""
    f = getattr(cls, face, None)
    return None if f is None else getattr(f, "B", None)


def _class_list(classes: Any) -> list[tuple[str, Any]]:
    if classes is None:
        try:
            from crashsim.vehicles.vehicle_data import vehicle_classes
        except ImportError as e:
            raise ParameterError(
                "no vehicle classes given and crashsim.vehicles.vehicle_data is not available; "
                "pass classes={name: class, ...}"
            ) from e
        classes = vehicle_classes()
    if isinstance(classes, Mapping):
        items = [(str(k), v) for k, v in classes.items()]
    elif isinstance(classes, Sequence) and not isinstance(classes, str):
        items = [(str(getattr(c, "name", None) or f"class {i}"), c) for i, c in enumerate(classes)]
    else:
        raise ParameterError(
            f"classes must be a mapping name -> class or a sequence of classes, got "
            f"{type(classes).__name__}"
        )
    if not items:
        raise ParameterError("no vehicle classes to pair")
    names = [n for n, _ in items]
    if len(set(names)) != len(names):
        raise ParameterError(f"class names must be unique, got {names}")
    return items


# --- the Monte Carlo ------------------------------------------------------------------------


def dtp_montecarlo(
    samples: int = 1_000_000,
    seed: int | None = 0,
    classes: Mapping[str, Any] | Sequence[Any] | None = None,
    configurations: Sequence[str] = CONFIGURATIONS,
) -> DtpMonteCarlo:
    """Sample dt_p = sqrt(m'/k') over all ordered class pairs in each configuration (see the
    module docstring for the exact pairing, weighting and sampling).

    samples: total number of samples (int); it must give every pair of every configuration
    at least one. seed: an int for reproducible bits (None: fresh entropy). classes: as the
    module docstring says (default ``crashsim.vehicles.vehicle_data.vehicle_classes()``).
    configurations: a subset of CONFIGURATIONS, in the order wanted."""
    configs = _check_run(samples, seed, configurations)
    items = _class_list(classes)
    names = tuple(n for n, _ in items)
    if len(names) > np.iinfo(np.int16).max:
        raise ParameterError(f"too many classes ({len(names)})")

    mass = np.array([_spread(c.mass, f"{n}: mass", "kg") for n, c in items])
    width = np.array([_spread(c.width, f"{n}: width", "m") for n, c in items])
    face_b = _face_spreads(items)
    pairs, excluded, pair_index = _class_pairs(configs, names, face_b)

    total_pairs = sum(len(p) for p in pair_index)
    if samples < total_pairs:
        raise ParameterError(
            f"samples = {samples} is too few: give at least {total_pairs} so every one of the "
            f"{total_pairs} class pairs of the {len(configs)} configuration(s) is sampled"
        )
    cfg, i1, i2, b1_spread, b2_spread = _stratified(samples, configs, pair_index, face_b)

    rng = np.random.default_rng(seed)
    u = 2.0 * rng.random((6, samples)) - 1.0  # uniform in [-1, 1)
    m1 = mass[i1, 0] + mass[i1, 1] * u[0]
    m2 = mass[i2, 0] + mass[i2, 1] * u[1]
    w = np.minimum(width[i1, 0] + width[i1, 1] * u[2], width[i2, 0] + width[i2, 1] * u[3])
    bb1 = b1_spread[:, 0] + b1_spread[:, 1] * u[4]
    bb2 = b2_spread[:, 0] + b2_spread[:, 1] * u[5]
    m_red = m1 * m2 / (m1 + m2)
    k_ser = bb1 * bb2 / (bb1 + bb2) * w  # (B1 W)(B2 W)/(B1 W + B2 W)
    dtp = np.sqrt(m_red / k_ser)

    arrays = [dtp, cfg, i1, i2, m1, m2, w, bb1, bb2]
    for a in arrays:
        a.setflags(write=False)
    return DtpMonteCarlo(
        *arrays,
        class_names=names,
        configurations=configs,
        pairs=pairs,
        excluded=excluded,
        seed=None if seed is None else int(seed),
    )


def _check_run(samples: Any, seed: Any, configurations: Sequence[str]) -> tuple[str, ...]:
    """ParameterError for a bad sample count, seed or configuration list; the configurations."""
    if isinstance(samples, bool) or not isinstance(samples, numbers.Integral):
        raise ParameterError(f"samples must be a whole number, got {samples!r}")
    if seed is not None and (isinstance(seed, bool) or not isinstance(seed, numbers.Integral)):
        raise ParameterError(f"seed must be a whole number or None, got {seed!r}")
    if seed is not None and seed < 0:
        raise ParameterError(f"seed must be >= 0, got {seed}")
    configs = tuple(configurations)
    if not configs:
        raise ParameterError("give at least one configuration")
    for c in configs:
        if c not in _FACES:
            raise ParameterError(f"unknown configuration {c!r}: use {', '.join(CONFIGURATIONS)}")
    if len(set(configs)) != len(configs):
        raise ParameterError(f"configurations repeat: {configs}")
    return configs


def _face_spreads(items: list[tuple[str, Any]]) -> dict[str, Array]:
    """Each face's B (N/m^2) per class as (mean, half-width) rows; NaN where a class has no
    B for that face."""
    face_b: dict[str, Array] = {}
    for face in ("front", "rear", "side"):
        rows = []
        for n, c in items:
            b = _face_b(c, face)
            rows.append((np.nan, np.nan) if b is None else _spread(b, f"{n}: {face} B", "N/m^2"))
        face_b[face] = np.array(rows)
    return face_b


def _class_pairs(
    configs: tuple[str, ...], names: tuple[str, ...], face_b: dict[str, Array]
) -> tuple[
    dict[str, tuple[tuple[str, str], ...]], dict[str, tuple[str, ...]], list[NDArray[np.int64]]
]:
    """Per configuration: the ordered class pairs (by name), the classes left out of a role
    for want of its face's B, and the pairs as (P, 2) class indices."""
    pairs: dict[str, tuple[tuple[str, str], ...]] = {}
    excluded: dict[str, tuple[str, ...]] = {}
    pair_index: list[NDArray[np.int64]] = []
    for c in configs:
        f1, f2 = _FACES[c]
        ok1 = np.flatnonzero(~np.isnan(face_b[f1][:, 0]))
        ok2 = np.flatnonzero(~np.isnan(face_b[f2][:, 0]))
        excluded[c] = tuple(
            f"{names[i]} (vehicle {role}: no {face} B)"
            for role, face, ok in ((1, f1, ok1), (2, f2, ok2))
            for i in range(len(names))
            if i not in set(ok.tolist())
        )
        if ok1.size == 0 or ok2.size == 0:
            raise ParameterError(f"no class has the {f1} and {f2} B data that {c} needs")
        p = np.array([(i, j) for i in ok1 for j in ok2], dtype=np.int64)
        pair_index.append(p)
        pairs[c] = tuple((names[i], names[j]) for i, j in p)
    return pairs, excluded, pair_index


def _stratified(
    samples: int,
    configs: tuple[str, ...],
    pair_index: list[NDArray[np.int64]],
    face_b: dict[str, Array],
) -> tuple[Array, Array, Array, Array, Array]:
    """Each sample's configuration, vehicle 1's and 2's class and their struck faces' B
    spreads: the samples split equally between the configurations (the first ones one
    more), cyclically between each one's pairs."""
    base, extra = divmod(int(samples), len(configs))
    counts = [base + (1 if k < extra else 0) for k in range(len(configs))]
    cfg = np.repeat(np.arange(len(configs), dtype=np.int8), counts)
    i1 = np.empty(samples, dtype=np.int16)
    i2 = np.empty(samples, dtype=np.int16)
    b1_spread = np.empty((samples, 2))
    b2_spread = np.empty((samples, 2))
    start = 0
    for k, (c, p) in enumerate(zip(configs, pair_index, strict=True)):
        stop = start + counts[k]
        which = p[np.arange(counts[k]) % len(p)]
        i1[start:stop] = which[:, 0]
        i2[start:stop] = which[:, 1]
        f1, f2 = _FACES[c]
        b1_spread[start:stop] = face_b[f1][which[:, 0]]
        b2_spread[start:stop] = face_b[f2][which[:, 1]]
        start = stop
    return cfg, i1, i2, b1_spread, b2_spread


# --- the picture ----------------------------------------------------------------------------

_COLOURS = ("#1f77b4", "#ff7f0e", "#2ca02c", "#d62728", "#9467bd", "#8c564b")
_BAND_COLOUR = "#d9f0d3"
_MS = 1e3  # ms per s


def plot_dtp_histogram(
    result: DtpMonteCarlo,
    path: str | Path | None = None,
    *,
    band: tuple[float, float] = BAND,
    bin_ms: float = 1.0,
    source: str | None = None,
) -> Figure:
    """Histogram of the Monte Carlo's dt_p (ms), stacked by configuration, with the band
    (default 10-60 ms) shaded and the overall percentiles marked; below it, each
    configuration's median, 25-75 % and 2.5-97.5 % ranges and share inside the band.
    Writes a PNG (or any format matplotlib knows by the suffix) to ``path`` when given;
    returns the matplotlib Figure (Agg canvas, no pyplot state). ``source`` is a short note
    on where the class data came from, printed under the title."""
    try:
        from matplotlib.backends.backend_agg import FigureCanvasAgg
        from matplotlib.figure import Figure
    except ImportError as e:  # matplotlib is needed for pictures only
        raise ImportError("the histogram needs matplotlib: pip install matplotlib") from e

    if not bin_ms > 0.0:
        raise ParameterError(f"bin_ms must be > 0 ms, got {bin_ms}")
    summ = result.summary(band)
    ms = _MS
    x_all = result.dtp * ms
    top = float(np.percentile(x_all, 99.5))
    x_max = max(band[1] * ms + 10.0, math.ceil(top / 10.0) * 10.0)
    edges = np.arange(0.0, x_max + bin_ms, bin_ms)
    hidden = int(np.count_nonzero(x_all > edges[-1]))

    fig = Figure(figsize=(11.5, 8.0), layout="constrained")
    FigureCanvasAgg(fig)
    grid = fig.add_gridspec(2, 2, width_ratios=[4.0, 1.0], height_ratios=[3.0, 1.6])
    ax = fig.add_subplot(grid[0, 0])
    ax2 = fig.add_subplot(grid[1, 0], sharex=ax)
    side = fig.add_subplot(grid[:, 1])
    side.axis("off")

    colours = [_COLOURS[k % len(_COLOURS)] for k in range(len(result.configurations))]
    _draw_stacked_histogram(ax, result, summ, colours, edges, band)
    _draw_side_panel(side, ax, summ, band)
    ax.set_ylabel(f"share of all samples per {bin_ms:g} ms bin (%)")
    ax.grid(axis="y", color="0.9")
    ax.set_axisbelow(True)
    title = (
        f"Depth of penetration $\\Delta t_p = \\sqrt{{m'/k'}}$ for vehicle-class pairs: "
        f"{len(result):,} Monte Carlo samples (seed {result.seed})"
    )
    sub = (
        f"{len(result.class_names)} classes, ordered pairs per configuration; full-width "
        "in-line impacts over the narrower width; mass, width and B uniform within $\\pm$1 SD"
    )
    if source:
        sub += f"\nclass data: {source}"
    fig.suptitle(title + "\n" + sub, fontsize=10.5)
    _draw_configuration_rows(ax2, result, summ, colours, band)
    xlabel = "depth of penetration $\\Delta t_p$ (ms)"
    if hidden:
        xlabel += f"   ({hidden} samples above {edges[-1]:g} ms not drawn)"
    ax2.set_xlabel(xlabel)
    ax2.set_xlim(0.0, edges[-1])
    ax2.grid(axis="x", color="0.9")
    ax2.set_axisbelow(True)
    if path is not None:
        fig.savefig(Path(path), dpi=120)
    return fig


def _draw_stacked_histogram(
    ax: Any,
    result: DtpMonteCarlo,
    summ: dict[str, Any],
    colours: list[str],
    edges: Array,
    band: tuple[float, float],
) -> None:
    """The upper panel: the band shaded, the dt_p histogram (ms; % of all samples) stacked
    by configuration, and the overall 2.5, 50 and 97.5 % percentiles marked."""
    ms = _MS
    x_all = result.dtp * ms
    per = [result.samples_of(c) * ms for c in result.configurations]
    weights = [np.full(s.size, 100.0 / x_all.size) for s in per]
    ax.axvspan(band[0] * ms, band[1] * ms, color=_BAND_COLOUR, zorder=0)
    ax.hist(
        per,
        bins=edges,
        weights=weights,
        stacked=True,
        color=colours,
        label=list(result.configurations),
        histtype="stepfilled",
        alpha=0.85,
        edgecolor="white",
        linewidth=0.3,
        zorder=2,
    )
    pc = summ["overall"]["percentiles"]
    marks = [("2.5", ":"), ("50", "-"), ("97.5", ":")]
    for key, style in marks:
        ax.axvline(pc[key] * ms, color="black", linestyle=style, linewidth=1.2, zorder=3)
    ymax = ax.get_ylim()[1]
    for key, _ in marks:
        ax.text(
            pc[key] * ms,
            ymax * 0.985,
            f" {key} %: {pc[key] * ms:.1f} ms",
            rotation=90,
            va="top",
            ha="right",
            fontsize=8.5,
            bbox={"boxstyle": "square,pad=0.15", "facecolor": "white", "edgecolor": "none"},
            zorder=4,
        )


def _draw_side_panel(side: Any, ax: Any, summ: dict[str, Any], band: tuple[float, float]) -> None:
    """The side panel: the upper panel's legend and the table of all samples' figures."""
    from matplotlib.lines import Line2D
    from matplotlib.patches import Patch

    ms = _MS
    pc = summ["overall"]["percentiles"]
    handles, labels = ax.get_legend_handles_labels()
    handles = [
        *handles,
        Patch(color=_BAND_COLOUR),
        Line2D([], [], color="black", linestyle="-"),
        Line2D([], [], color="black", linestyle=":"),
    ]
    labels = [
        *labels,
        f"band {band[0] * ms:g}-{band[1] * ms:g} ms",
        "median (all samples)",
        "2.5 % and 97.5 % (all)",
    ]
    side.legend(handles, labels, title="configuration (stacked)", loc="upper left", fontsize=9)
    o = summ["overall"]
    table = "\n".join(
        [
            "all samples",
            f"n       {o['n']:,}",
            f"mean    {o['mean'] * ms:6.1f} ms",
            *(f"P{p:<6g} {pc[_pkey(p)] * ms:6.1f} ms" for p in PERCENTILES),
            f"in band {100.0 * o['fraction_in_band']:6.1f} %  "
            f"({band[0] * ms:g}-{band[1] * ms:g} ms)",
        ]
    )
    side.text(
        0.0,
        0.66,
        table,
        transform=side.transAxes,
        ha="left",
        va="top",
        multialignment="left",
        family="monospace",
        fontsize=8.5,
        bbox={"boxstyle": "round", "facecolor": "white", "edgecolor": "0.6", "alpha": 0.95},
        zorder=5,
    )


def _draw_configuration_rows(
    ax2: Any,
    result: DtpMonteCarlo,
    summ: dict[str, Any],
    colours: list[str],
    band: tuple[float, float],
) -> None:
    """The lower panel: one row per configuration, its median, 25-75 % and 2.5-97.5 % ranges
    (ms) and its share in the band."""
    ms = _MS
    ax2.axvspan(band[0] * ms, band[1] * ms, color=_BAND_COLOUR, zorder=0)
    for k, c in enumerate(result.configurations):
        s = summ["by_configuration"][c]
        q = {key: v * ms for key, v in s["percentiles"].items()}
        y = len(result.configurations) - 1 - k
        ax2.plot([q["2.5"], q["97.5"]], [y, y], color=colours[k], linewidth=1.5)
        ax2.plot([q["25"], q["75"]], [y, y], color=colours[k], linewidth=7, solid_capstyle="butt")
        ax2.plot([q["50"]], [y], marker="|", color="black", markersize=14, markeredgewidth=2)
        ax2.text(
            q["2.5"],
            y + 0.22,
            f"median {q['50']:.1f} ms, {100.0 * s['fraction_in_band']:.1f} % in band",
            va="bottom",
            ha="left",
            fontsize=8.5,
        )
    ax2.set_yticks(range(len(result.configurations)))
    ax2.set_yticklabels(list(reversed(result.configurations)))
    ax2.set_ylim(-0.5, len(result.configurations) - 0.2)
    ax2.set_title(
        "per configuration: median (|), 25-75 % (thick), 2.5-97.5 % (thin)", fontsize=9, loc="left"
    )
