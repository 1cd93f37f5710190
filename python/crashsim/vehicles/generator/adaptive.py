"""The generator's adaptive defaults: five shape parameters (wheel_radius, ground_clearance,
bumper_bottom, edge_radius, bumper_radius) that body_params moves away from a conflict when
the caller does not give them, so that any dimensions of a vehicle of the class give a valid
body. Lengths in metres; distances along the body from the front face.
"""

from __future__ import annotations

import math
from collections.abc import Mapping

import numpy as np
from numpy.typing import NDArray

from crashsim.vehicles.generator.elementary import _filleted, _interp
from crashsim.vehicles.generator.params import (
    _MARGIN,
    _PROFILE_SAMPLES,
    _SHOULDER_MIN,
    _SILL_RADIUS,
    _top_points,
    _Values,
)

Array = NDArray[np.float64]

# -- adaptive defaults -------------------------------------------------------------------------
# A parameter the caller does not give starts from its nominal value (the _DEFAULTS rule); the
# five below are then adapted so that the defaults give a valid body for any dimensions a
# vehicle of the class can have. Each rule only ever moves its parameter away from a conflict,
# and leaves the nominal value (for _check to report clearly) when no value would do.

_ARCH_BUMPER = 0.08  # m of body kept ahead of the front arch and behind the rear arch
_ARCH_CLEARANCE = 0.07  # m from the top of an arch to the top of the body side above it
_WHEEL_LEAST_SHARE = 0.5  # an adapted wheel_radius is at least this share of the preset's
_CLEARANCE_SHARE = 0.75  # ground_clearance at most this share of wheel_radius
_CORNER_SHARE = 0.8  # bumper_radius at most this share of the shorter overhang


def _overhangs(v: Mapping[str, float]) -> tuple[float, float]:
    """(front, rear) overhang (m), computed as BodyParams does."""
    fo = v["front_overhang"]
    return fo, v["length"] - fo - v["wheelbase"]


def _side_top(v: Mapping[str, float]) -> tuple[Array, Array]:
    """The top of the body's side wall along the body: (d, z) of a polyline (m), the side
    view's top profile less _SHOULDER_MIN, capped at the beltline (as _profiles makes it,
    without the end faces' edge rounding)."""
    td, tz = _filleted(_top_points(_Values(v)), _PROFILE_SAMPLES)
    return td, tz - _SHOULDER_MIN


def _lowest_side(v: Mapping[str, float], td: Array, tz: Array, a: float, b: float) -> float:
    """The lowest top of the side wall for d in [a, b] (m): exact for the polyline (its
    vertices inside and its values at the ends), then capped at the beltline."""
    inside = tz[(td > a) & (td < b)]
    ends = _interp(np.array([a, b]), td, tz)
    low = float(min(ends.min(), inside.min())) if inside.size else float(ends.min())
    return min(v["beltline"], low)


def _wheel_fits(v: Mapping[str, float], td: Array, tz: Array, wr: float) -> bool:
    """Does a wheel of radius wr (m) keep the rule of the wheel_radius default?"""
    fo, ro = _overhangs(v)
    ra = wr + v["arch_gap"]
    if ra + _ARCH_BUMPER > min(fo, ro) or 2.0 * ra + 0.1 > v["wheelbase"]:
        return False
    need = wr + ra + _ARCH_CLEARANCE  # the arch's top plus the clearance
    axles = (fo, fo + v["wheelbase"])
    return all(_lowest_side(v, td, tz, da - ra, da + ra) >= need for da in axles)


def _adapt_wheel_radius(v: Mapping[str, float], nominal: float) -> float:
    """The preset's tyre radius, or the largest radius (rounded down to the mm) with which
    each arch leaves _ARCH_BUMPER of body before the end of the body, the two arches leave
    0.1 m between them, and over each arch's whole length the top of the body side (the
    beltline, or the hood, roof or deck line less _SHOULDER_MIN) is at least _ARCH_CLEARANCE
    above the arch's top (wheel_radius + arch radius). When that radius would be less than
    _WHEEL_LEAST_SHARE of the preset's, the dimensions are not a vehicle of the class: the
    preset's radius is kept and _check names the conflict."""
    td, tz = _side_top(v)
    if _wheel_fits(v, td, tz, nominal):
        return nominal
    lo, hi = 0.0, nominal
    for _ in range(60):  # bisection: the rule holds for every radius below the largest
        mid = 0.5 * (lo + hi)
        if _wheel_fits(v, td, tz, mid):
            lo = mid
        else:
            hi = mid
    fit = math.floor(lo * 1000.0) / 1000.0
    return fit if fit >= _WHEEL_LEAST_SHARE * nominal else nominal


def _adapt_ground_clearance(v: Mapping[str, float], nominal: float) -> float:
    """The preset's clearance, at most _CLEARANCE_SHARE of the wheel radius."""
    return min(nominal, _CLEARANCE_SHARE * v["wheel_radius"])


def _adapt_bumper_bottom(v: Mapping[str, float], nominal: float) -> float:
    """The preset's share of the height, at least the ground clearance."""
    return max(nominal, v["ground_clearance"])


def _adapt_edge_radius(v: Mapping[str, float], nominal: float) -> float:
    """The preset's radius, at most the body between an arch and the end of the body, and
    at most 0.45 of what the lower end face leaves beside its fixed details."""
    fo, ro = _overhangs(v)
    room = min(fo, ro) - (v["wheel_radius"] + v["arch_gap"])
    fixed = _SILL_RADIUS + _SHOULDER_MIN + 2.0 * _MARGIN
    face = min(v["nose_height"], v["tail_height"]) - v["bumper_bottom"] - fixed
    r = min(nominal, room, 0.45 * face)
    return r if r > 0.0 else nominal


def _adapt_bumper_radius(v: Mapping[str, float], nominal: float) -> float:
    """The preset's share of the width, at most _CORNER_SHARE of the shorter overhang."""
    r = min(nominal, _CORNER_SHARE * min(_overhangs(v)))
    return r if r > 0.0 else nominal


_ADAPTIVE = (
    ("wheel_radius", _adapt_wheel_radius),
    ("ground_clearance", _adapt_ground_clearance),
    ("bumper_bottom", _adapt_bumper_bottom),
    ("edge_radius", _adapt_edge_radius),
    ("bumper_radius", _adapt_bumper_radius),
)
