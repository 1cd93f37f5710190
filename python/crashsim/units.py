"""Unit helpers for the edges of the program (input parsing, reports). SI inside.

Exact definitions: 1 ft = 0.3048 m, 1 mph = 0.44704 m/s, 1 lb = 0.45359237 kg.
"""

import math

FOOT = 0.3048  # m
MILE_PER_HOUR = 0.44704  # m/s
KILOMETRE_PER_HOUR = 1000.0 / 3600.0  # m/s
POUND = 0.45359237  # kg


def mph(x: float) -> float:
    """Miles per hour -> m/s."""
    return x * MILE_PER_HOUR


def kmh(x: float) -> float:
    """Kilometres per hour -> m/s."""
    return x * KILOMETRE_PER_HOUR


def ft(x: float) -> float:
    """Feet -> m."""
    return x * FOOT


def ft_s(x: float) -> float:
    """Feet per second -> m/s."""
    return x * FOOT


def lb(x: float) -> float:
    """Pounds (mass) -> kg."""
    return x * POUND


def deg(x: float) -> float:
    """Degrees -> radians."""
    return math.radians(x)


def to_mph(v: float) -> float:
    """m/s -> miles per hour."""
    return v / MILE_PER_HOUR


def to_kmh(v: float) -> float:
    """m/s -> kilometres per hour."""
    return v / KILOMETRE_PER_HOUR


def to_ft(x: float) -> float:
    """m -> feet."""
    return x / FOOT


def to_ft_s(v: float) -> float:
    """m/s -> feet per second."""
    return v / FOOT


def to_lb(m: float) -> float:
    """kg -> pounds (mass)."""
    return m / POUND


def to_deg(a: float) -> float:
    """Radians -> degrees."""
    return math.degrees(a)
