"""Designs: which variants a study runs, as {parameter path: (n,) values, SI}.

- :func:`grid`: the full factorial of each path's values (a list of numbers, or
  :func:`linspace`), the first path varying slowest (``itertools.product`` order).
- :func:`monte_carlo_sample`: n draws of every path's distribution from
  ``numpy.random.default_rng(seed)``, the paths drawn in the order given (reproducible).
- :func:`one_at_a_time`: the tornado's design: the base values, then each path at its low
  and at its high value with the others at their base.

Values and parameters are checked here: StudyError naming the path.
"""

from __future__ import annotations

import math
from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np
from numpy.typing import NDArray

from crashsim.errors import StudyError
from crashsim.studies.distributions import Distribution

__all__ = ["Linspace", "grid", "grid_size", "linspace", "monte_carlo_sample", "one_at_a_time"]

Array = NDArray[np.float64]


@dataclass(frozen=True)
class Linspace:
    """``count`` evenly spaced values from ``start`` to ``stop`` (both included)."""

    start: float
    stop: float
    count: int

    def size(self, key: str | None = None) -> int:
        """The number of values, checked (StudyError naming ``key``) without making them."""
        at = f'"{key}": ' if key else ""
        if isinstance(self.count, bool) or not isinstance(self.count, int | np.integer):
            raise StudyError(f"{at}linspace count must be a whole number, got {self.count!r}", key)
        if self.count < 1:
            raise StudyError(f"{at}linspace count = {self.count} must be >= 1", key)
        if not (math.isfinite(self.start) and math.isfinite(self.stop)):
            raise StudyError(f"{at}linspace({self.start}, {self.stop}): give finite ends", key)
        if self.count == 1 and self.start != self.stop:
            raise StudyError(
                f"{at}linspace({self.start:g}, {self.stop:g}, 1): one value cannot span two "
                "ends; give a count >= 2, or a single value",
                key,
            )
        return int(self.count)

    def values(self, key: str | None = None) -> Array:
        return np.linspace(float(self.start), float(self.stop), self.size(key))

    def __str__(self) -> str:
        return f"{self.start:g}:{self.stop:g}:{self.count}"


def linspace(start: float, stop: float, count: int) -> Linspace:
    """``count`` evenly spaced values from start to stop, both included (numpy.linspace)."""
    return Linspace(start, stop, count)


def _axis(key: str, values: Any) -> Array:
    """One path's grid values as a float array (NaN kept for depth_of_penetration = auto)."""
    if isinstance(values, Linspace):
        return values.values(key)
    if isinstance(values, str) or not isinstance(values, Sequence | np.ndarray):
        values = [values]
    out = []
    for v in values:
        if isinstance(v, str) and v.strip().lower() == "auto" and key.endswith(
            "depth_of_penetration"
        ):
            out.append(math.nan)
            continue
        try:
            x = float(v)
        except (TypeError, ValueError):
            raise StudyError(f'"{key}": the value {v!r} is not a number (SI)', key) from None
        if not math.isfinite(x) and not (math.isnan(x) and key.endswith("depth_of_penetration")):
            raise StudyError(f'"{key}": the value {v!r} is not a finite number', key)
        out.append(x)
    if not out:
        raise StudyError(f'"{key}": no values to sweep: give at least one', key)
    return np.asarray(out, dtype=np.float64)


def grid_size(spec: Mapping[str, Any]) -> int:
    """The number of variants of the full factorial of ``spec``, found without making it."""
    if not spec:
        raise StudyError("a sweep needs at least one parameter path with values")
    sizes = []
    for k, v in spec.items():
        if isinstance(v, Linspace):
            sizes.append(v.size(k))
        elif isinstance(v, str) or not isinstance(v, Sequence | np.ndarray):
            sizes.append(1)
        else:
            sizes.append(len(v))
    return math.prod(sizes)


def grid(spec: Mapping[str, Any]) -> dict[str, Array]:
    """The full factorial of ``spec`` ({path: values or Linspace}): n = the product of the
    counts, the first path varying slowest (``itertools.product`` order), each column made
    at once (n values; no list of n rows)."""
    grid_size(spec)  # an empty spec or a bad count, before any values are made
    axes = [_axis(k, v) for k, v in spec.items()]
    sizes = [a.size for a in axes]
    out = {}
    for c, (k, a) in enumerate(zip(spec, axes, strict=True)):
        slower, faster = math.prod(sizes[:c]), math.prod(sizes[c + 1:])
        out[k] = np.tile(np.repeat(a, faster), slower)
    return out


def _check_distributions(distributions: Mapping[str, Any]) -> None:
    if not distributions:
        raise StudyError("a Monte Carlo study needs at least one parameter path and distribution")
    for key, d in distributions.items():
        if not isinstance(d, Distribution):
            raise StudyError(
                f'"{key}": {d!r} is not a distribution: use crashsim.studies.uniform, normal, '
                "triangular or class_table",
                key,
            )
        d.check(key)


def _count(n: Any, what: str = "n") -> int:
    if isinstance(n, bool) or not isinstance(n, int | np.integer) or n < 1:
        raise StudyError(f"{what} = {n!r} is invalid: give the number of variants, an integer >= 1")
    return int(n)


def monte_carlo_sample(
    distributions: Mapping[str, Distribution], n: int, seed: int | None
) -> dict[str, Array]:
    """n draws of every path's distribution (numpy.random.default_rng(seed); the same seed and
    paths in the same order give the same values)."""
    _check_distributions(distributions)
    n = _count(n)
    if seed is not None and (isinstance(seed, bool) or not isinstance(seed, int | np.integer)
                             or seed < 0):
        raise StudyError(f"seed = {seed!r} is invalid: give an integer >= 0 (or None)")
    rng = np.random.default_rng(seed)
    return {k: np.asarray(d.sample(rng, n), dtype=np.float64) for k, d in distributions.items()}


def one_at_a_time(
    base: Mapping[str, float], ranges: Mapping[str, tuple[float, float]]
) -> dict[str, Array]:
    """The tornado's design: variant 0 at the base values, then for each path (in order) one
    variant at its low and one at its high value, the others at their base: 1 + 2 k variants."""
    keys = list(ranges)
    n = 1 + 2 * len(keys)
    out = {k: np.full(n, float(base[k])) for k in keys}
    for c, k in enumerate(keys):
        lo, hi = ranges[k]
        out[k][1 + 2 * c] = float(lo)
        out[k][2 + 2 * c] = float(hi)
    return out
