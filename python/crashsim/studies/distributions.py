"""Input distributions of a Monte Carlo study (SI values, the unit of the path they feed).

- :class:`Uniform` ``(lo, hi)``: every value in [lo, hi) equally likely.
- :class:`Normal` ``(mean, sd, lo=None, hi=None)``: Gaussian, optionally truncated to
  [lo, hi] (the density renormalised inside; no value outside).
- :class:`Triangular` ``(lo, mode, hi)``: density rising linearly from lo to mode and falling
  to hi.
- :class:`Choice` ``(values, weights=None)``: one of a few values (e.g. a pedestrian's pose
  number), each with its weight (equal by default; normalised).
- :class:`ClassTable` ``(vehicle_class, figure="mass", k=3.0)``: a figure of the built-in
  vehicle-class table (crashsim.vehicles.vehicle_data, docs/vehicle-data.md): a normal with
  the class's value and published standard deviation, truncated to value +- k sd (3 by
  default, which keeps every class's mass positive). Figures without a published sd cannot be
  sampled (the error names them).

Parameters are checked when a study uses the distribution (:meth:`Distribution.check` with
the parameter path), so the StudyError names the path: sd <= 0, lo >= hi, a mode outside
[lo, hi], non-finite numbers, an unknown class or figure.

Sampling is reproducible: each distribution draws from the study's
``numpy.random.Generator`` (``numpy.random.default_rng(seed)``), in the order the study lists
its paths; :meth:`Distribution.ppf` (the inverse CDF) maps numbers in (0, 1) to values, for
designs that bring their own points (the Sobol design of crashsim.studies.sensitivity).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

from crashsim.errors import CrashsimError, StudyError

__all__ = [
    "Choice",
    "ClassTable",
    "Distribution",
    "Normal",
    "Triangular",
    "Uniform",
    "choice",
    "class_table",
    "normal",
    "triangular",
    "uniform",
]

Array = NDArray[np.float64]

_TINY = 1e-12  # u is kept in [_TINY, 1 - _TINY] for unbounded inverse CDFs


def _finite(key: str | None, what: str, value: Any, dist: str) -> float:
    try:
        x = float(value)
    except (TypeError, ValueError):
        raise StudyError(f"{_at(key)}{dist}: {what} = {value!r} is not a number", key) from None
    if not math.isfinite(x):
        raise StudyError(f"{_at(key)}{dist}: {what} = {x} must be a finite number", key)
    return x


def _at(key: str | None) -> str:
    return f'"{key}": ' if key else ""


class Distribution:
    """An input distribution (see the module docstring)."""

    def check(self, key: str | None = None) -> None:
        """StudyError naming ``key`` (the parameter path) for an invalid parameter."""
        raise NotImplementedError

    def ppf(self, u: ArrayLike) -> Array:
        """The inverse CDF: values at probabilities u (in [0, 1])."""
        raise NotImplementedError

    def sample(self, rng: np.random.Generator, n: int) -> Array:
        """n values drawn with ``rng``."""
        return self.ppf(rng.random(n))

    def percentile(self, p: float) -> float:
        """The value below which p percent of the distribution lies."""
        return float(self.ppf(np.array([p / 100.0]))[0])

    @property
    def median(self) -> float:
        return self.percentile(50.0)


@dataclass(frozen=True)
class Uniform(Distribution):
    lo: float
    hi: float

    def check(self, key: str | None = None) -> None:
        lo = _finite(key, "lo", self.lo, "uniform")
        hi = _finite(key, "hi", self.hi, "uniform")
        if not lo < hi:
            raise StudyError(
                f"{_at(key)}uniform({lo:g}, {hi:g}): lo must be below hi (give uniform(lo, hi) "
                "with lo < hi; a fixed value needs no distribution)",
                key,
            )

    def ppf(self, u: ArrayLike) -> Array:
        u = np.asarray(u, dtype=np.float64)
        return self.lo + (self.hi - self.lo) * u

    def __str__(self) -> str:
        return f"uniform({self.lo:g}, {self.hi:g})"


@dataclass(frozen=True)
class Normal(Distribution):
    mean: float
    sd: float
    lo: float | None = None
    hi: float | None = None

    def check(self, key: str | None = None) -> None:
        _finite(key, "mean", self.mean, "normal")
        sd = _finite(key, "sd", self.sd, "normal")
        if not sd > 0.0:
            raise StudyError(
                f"{_at(key)}normal({self.mean:g}, {sd:g}): the standard deviation must be > 0 "
                "(a fixed value needs no distribution)",
                key,
            )
        lo = -math.inf if self.lo is None else _finite(key, "lo", self.lo, "normal")
        hi = math.inf if self.hi is None else _finite(key, "hi", self.hi, "normal")
        if not lo < hi:
            raise StudyError(
                f"{_at(key)}normal truncated to [{lo:g}, {hi:g}]: lo must be below hi", key
            )
        if (self.lo is not None or self.hi is not None) and self._mass() < 1e-12:
            raise StudyError(
                f"{_at(key)}normal({self.mean:g}, {sd:g}) truncated to [{lo:g}, {hi:g}]: the "
                "interval lies too far in the tail (no probability inside): widen it or move it "
                "towards the mean",
                key,
            )

    def _bounds(self) -> tuple[float, float]:
        from scipy.stats import norm

        a = 0.0 if self.lo is None else float(norm.cdf((self.lo - self.mean) / self.sd))
        b = 1.0 if self.hi is None else float(norm.cdf((self.hi - self.mean) / self.sd))
        return a, b

    def _mass(self) -> float:
        a, b = self._bounds()
        return b - a

    def ppf(self, u: ArrayLike) -> Array:
        from scipy.stats import norm

        u = np.clip(np.asarray(u, dtype=np.float64), _TINY, 1.0 - _TINY)
        if self.lo is None and self.hi is None:
            return self.mean + self.sd * norm.ppf(u)
        from scipy.stats import truncnorm

        a = -np.inf if self.lo is None else (self.lo - self.mean) / self.sd
        b = np.inf if self.hi is None else (self.hi - self.mean) / self.sd
        x = self.mean + self.sd * truncnorm.ppf(u, a, b)
        lo = -np.inf if self.lo is None else self.lo
        hi = np.inf if self.hi is None else self.hi
        return np.asarray(np.clip(x, lo, hi), dtype=np.float64)

    def sample(self, rng: np.random.Generator, n: int) -> Array:
        if self.lo is None and self.hi is None:
            return self.mean + self.sd * rng.standard_normal(n)
        return self.ppf(rng.random(n))

    def __str__(self) -> str:
        trunc = ""
        if self.lo is not None or self.hi is not None:
            lo = "-inf" if self.lo is None else f"{self.lo:g}"
            hi = "inf" if self.hi is None else f"{self.hi:g}"
            trunc = f" in [{lo}, {hi}]"
        return f"normal({self.mean:g}, {self.sd:g}){trunc}"


@dataclass(frozen=True)
class Triangular(Distribution):
    lo: float
    mode: float
    hi: float

    def check(self, key: str | None = None) -> None:
        lo = _finite(key, "lo", self.lo, "triangular")
        mode = _finite(key, "mode", self.mode, "triangular")
        hi = _finite(key, "hi", self.hi, "triangular")
        if not lo < hi:
            raise StudyError(
                f"{_at(key)}triangular({lo:g}, {mode:g}, {hi:g}): lo must be below hi", key
            )
        if not lo <= mode <= hi:
            raise StudyError(
                f"{_at(key)}triangular({lo:g}, {mode:g}, {hi:g}): the mode {mode:g} lies outside "
                f"[{lo:g}, {hi:g}]; give triangular(lo, mode, hi) with lo <= mode <= hi",
                key,
            )

    def ppf(self, u: ArrayLike) -> Array:
        u = np.asarray(u, dtype=np.float64)
        lo, c, hi = self.lo, self.mode, self.hi
        f = (c - lo) / (hi - lo)
        left = lo + np.sqrt(u * (hi - lo) * (c - lo))
        right = hi - np.sqrt((1.0 - u) * (hi - lo) * (hi - c))
        return np.where(u < f, left, right)

    def __str__(self) -> str:
        return f"triangular({self.lo:g}, {self.mode:g}, {self.hi:g})"


@dataclass(frozen=True)
class Choice(Distribution):
    values: tuple[float, ...]
    weights: tuple[float, ...] | None = None

    def check(self, key: str | None = None) -> None:
        values = [_finite(key, "a value", v, "choice") for v in self.values]
        if not values:
            raise StudyError(f"{_at(key)}choice(): give at least one value", key)
        if self.weights is not None:
            weights = [_finite(key, "a weight", w, "choice") for w in self.weights]
            if len(weights) != len(values) or min(weights) < 0.0 or sum(weights) <= 0.0:
                raise StudyError(
                    f"{_at(key)}choice({list(self.values)}, weights={list(self.weights)}): give "
                    "one weight >= 0 per value, not all zero",
                    key,
                )

    def _cdf(self) -> Array:
        w = np.ones(len(self.values)) if self.weights is None else np.asarray(self.weights, float)
        return np.cumsum(w) / np.sum(w)

    def ppf(self, u: ArrayLike) -> Array:
        """The value whose cumulative weight first reaches u (values in the order given)."""
        u = np.asarray(u, dtype=np.float64)
        k = np.searchsorted(self._cdf(), u, side="left")
        return np.asarray(self.values, dtype=np.float64)[np.clip(k, 0, len(self.values) - 1)]

    def __str__(self) -> str:
        w = "" if self.weights is None else f", weights={list(self.weights)}"
        return f"choice({list(self.values)}{w})"


# the class table's figures and the quantity each measures (for the command line's units)
_FIGURE_DIMENSIONS = {
    "mass": "mass",
    "length": "length",
    "width": "length",
    "height": "length",
    "wheelbase": "length",
    "cg_to_front_axle": "length",
    "cg_height": "length",
    "yaw_inertia": "moment of inertia",
    "track_front": "length",
    "track_rear": "length",
    "tyre_radius": "length",
}


@dataclass(frozen=True)
class ClassTable(Distribution):
    vehicle_class: str
    figure: str = "mass"
    k: float = 3.0

    def _normal(self, key: str | None = None) -> Normal:
        from crashsim.vehicles.vehicle_data import vehicle_class

        try:
            vc = vehicle_class(self.vehicle_class)
        except CrashsimError as e:
            raise StudyError(f"{_at(key)}class table: {e}", key) from None
        figures = vc.figures()
        if self.figure not in figures:
            raise StudyError(
                f"{_at(key)}class table: the vehicle classes have no figure {self.figure!r}: "
                f"use one of {', '.join(figures)}",
                key,
            )
        fig = figures[self.figure]
        if fig.sd is None or not fig.sd > 0.0:
            with_sd = [n for n, f in figures.items() if f.sd is not None and f.sd > 0.0]
            raise StudyError(
                f"{_at(key)}class table: {vc.name}'s {self.figure} has no published standard "
                f"deviation, so it cannot be sampled (figures of {vc.name} with one: "
                f"{', '.join(with_sd)}); give a normal or uniform distribution instead",
                key,
            )
        k = float(self.k)
        return Normal(fig.value, fig.sd, fig.value - k * fig.sd, fig.value + k * fig.sd)

    @property
    def dimension(self) -> str | None:
        """The quantity the figure measures ("mass", "length", ...), None if unknown."""
        return _FIGURE_DIMENSIONS.get(self.figure)

    def check(self, key: str | None = None) -> None:
        k = _finite(key, "k", self.k, "class table")
        if not k > 0.0:
            raise StudyError(f"{_at(key)}class table: k = {k:g} standard deviations must be > 0",
                             key)
        self._normal(key).check(key)

    def ppf(self, u: ArrayLike) -> Array:
        return self._normal().ppf(u)

    def sample(self, rng: np.random.Generator, n: int) -> Array:
        return self._normal().sample(rng, n)

    def __str__(self) -> str:
        n = self._normal()
        return f"class table {self.vehicle_class} {self.figure}: {n}"


def uniform(lo: float, hi: float) -> Uniform:
    """Every value in [lo, hi) equally likely."""
    return Uniform(lo, hi)


def normal(mean: float, sd: float, lo: float | None = None, hi: float | None = None) -> Normal:
    """A normal distribution, optionally truncated to [lo, hi]."""
    return Normal(mean, sd, lo, hi)


def triangular(lo: float, mode: float, hi: float) -> Triangular:
    """A triangular distribution on [lo, hi] peaking at mode."""
    return Triangular(lo, mode, hi)


def choice(values: ArrayLike, weights: ArrayLike | None = None) -> Choice:
    """One of ``values`` (numbers), each drawn with its weight (equal by default)."""
    def listed(x: ArrayLike) -> tuple[Any, ...]:
        return tuple(np.atleast_1d(np.asarray(x, dtype=object)).tolist())

    return Choice(listed(values), None if weights is None else listed(weights))


def class_table(vehicle_class: str, figure: str = "mass", k: float = 3.0) -> ClassTable:
    """A figure of the built-in vehicle-class table: normal(value, sd) truncated to +- k sd."""
    return ClassTable(vehicle_class, figure, k)
