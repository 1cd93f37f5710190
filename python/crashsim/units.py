"""Unit helpers for the edges of the program (input parsing, reports). SI inside.

Exact definitions: 1 ft = 0.3048 m, 1 mph = 0.44704 m/s, 1 lb = 0.45359237 kg (pound-mass),
1 km/h = 1/3.6 m/s. Every helper accepts a float or a numpy array and returns the same kind.
"""

from __future__ import annotations

import math
from typing import TypeVar

import numpy as np
from numpy.typing import NDArray

__all__ = [
    "FOOT",
    "MILE_PER_HOUR",
    "POUND",
    "deg",
    "ft",
    "ft_s",
    "kmh",
    "lb",
    "mph",
    "to_deg",
    "to_ft",
    "to_ft_s",
    "to_kmh",
    "to_lb",
    "to_mph",
]

FOOT = 0.3048  # m, exact
MILE_PER_HOUR = 0.44704  # m/s, exact (5280 ft per 3600 s)
POUND = 0.45359237  # kg, exact (pound-mass)
_KMH_PER_M_S = 3.6  # km/h in one m/s, exact
_RAD_PER_DEG = math.pi / 180.0

X = TypeVar("X", float, NDArray[np.float64])


def mph(x: X) -> X:
    """Miles per hour -> m/s."""
    return x * MILE_PER_HOUR


def kmh(x: X) -> X:
    """Kilometres per hour -> m/s."""
    return x / _KMH_PER_M_S


def ft(x: X) -> X:
    """Feet -> m."""
    return x * FOOT


def ft_s(x: X) -> X:
    """Feet per second (fps) -> m/s."""
    return x * FOOT


def lb(x: X) -> X:
    """Pounds (mass) -> kg."""
    return x * POUND


def deg(x: X) -> X:
    """Degrees -> radians."""
    return x * _RAD_PER_DEG


def to_mph(v: X) -> X:
    """m/s -> miles per hour."""
    return v / MILE_PER_HOUR


def to_kmh(v: X) -> X:
    """m/s -> kilometres per hour."""
    return v * _KMH_PER_M_S


def to_ft(x: X) -> X:
    """m -> feet."""
    return x / FOOT


def to_ft_s(v: X) -> X:
    """m/s -> feet per second."""
    return v / FOOT


def to_lb(m: X) -> X:
    """kg -> pounds (mass)."""
    return m / POUND


def to_deg(a: X) -> X:
    """Radians -> degrees."""
    return a / _RAD_PER_DEG
