"""Parametric vehicle bodies: a closed, watertight, single-shell mesh from a vehicle's dimensions.

Users often have no mesh, only a vehicle's length, width, height and wheelbase. This module
builds a plausible body for the classes in :data:`PRESETS` from those dimensions and a few shape
parameters (every one in metres, with a per-class default; the defaults of the wheel radius and
four other parameters adapt to the dimensions, so any dimensions a vehicle of the class can have
give a valid body: see :func:`body_params`). ``crashsim.Vehicle.generate`` makes a whole
vehicle (mass, CG, inertia, stiffness from the class table) on such a body::

    from crashsim.vehicles.generator import body_params, generate_body
    p = body_params("sedan", length=4.8, width=1.82, height=1.45, wheelbase=2.75)
    mesh = generate_body(p)          # trimesh.Trimesh, model frame

Model frame (m): x forward, y left, z up; the ground is z = 0. The body's bounding box is centred
in x and y and spans x in [-length/2, length/2], y in [-width/2, width/2] and
z in [ground_clearance, height]: ``height`` is the roof height above the ground (as in a
vehicle's specification), and the body floats at ``ground_clearance`` because it has no separate
wheels (it is one shell). Distances along the body (``windshield_base``, ``roof_start``, ...)
are measured rearwards from the front face, d = length/2 - x.

Construction: a loft of cross-sections along x. Each section is a simple polygon in the y-z
plane with the same number of points and the same structure (underside, wheel-arch notch, sill
rounding, side wall, greenhouse leaning in by the tumblehome, rounded roof or hood, mirrored in
y), its heights taken from a side-view profile (hood, windshield, roof, rear window, deck) and
its widths scaled by the plan-view rounding of the corners. The two end sections are closed by
fans. Wheel arches are notches in the lower outer part of the sections at both axles, sized from
the wheel radius. Only +, -, *, / and sqrt are used on the coordinates (sin and cos come from a
fixed polynomial), so the same parameters give the same bits on any IEEE-754 machine.
"""

from __future__ import annotations

import dataclasses
import math
from collections.abc import Mapping
from dataclasses import dataclass
from typing import Any, NoReturn

import numpy as np
import trimesh
from numpy.typing import NDArray

from crashsim.errors import MeshError, ParameterError

__all__ = [
    "PRESETS",
    "default_dims",
    "SHAPE_PARAMETERS",
    "BodyParams",
    "body_params",
    "body_sections",
    "generate_body",
    "loft",
    "ply_bytes",
]

Array = NDArray[np.float64]

PRESETS = ("sedan", "suv", "pickup", "van", "bus")


def default_dims(preset: str) -> dict[str, float]:
    """length, width, height (roof above the ground) and wheelbase (m) of the preset's vehicle
    class in the built-in table (crashsim.vehicles.vehicle_data; sources in
    docs/vehicle-data.md)."""
    from crashsim.vehicles.vehicle_data import vehicle_class  # a data module: no import cycle

    if preset not in PRESETS:
        _fail(f"preset = {preset!r} is unknown: use one of {', '.join(PRESETS)}")
    vc = vehicle_class(preset)
    return {
        "length": vc.length.value,
        "width": vc.width.value,
        "height": vc.height.value,
        "wheelbase": vc.wheelbase.value,
    }


# The shape parameters: name -> (meaning, unit). All lengths in metres; heights are above the
# ground; positions "from the front" are distances rearwards from the front face.
SHAPE_PARAMETERS: dict[str, str] = {
    "front_overhang": "m, front face to the front axle (the rear axle is wheelbase behind it)",
    "ground_clearance": "m, height of the underside between the axles (the body's lowest point)",
    "wheel_radius": "m, tyre radius; the wheel centres are at this height above the ground",
    "arch_gap": "m, radial gap between tyre and wheel arch (arch radius = wheel_radius + gap)",
    "arch_depth": "m, how far each wheel-arch cut reaches in from the body side (tyre width)",
    "bumper_bottom": "m, lower edge of the front and rear ends (the underside rises to it "
    "from ground_clearance at the axles)",
    "nose_height": "m, top of the front face (leading edge of the hood)",
    "hood_height": "m, top of the hood at the windshield base",
    "windshield_base": "m from the front, where the windshield meets the hood (cabin start)",
    "roof_start": "m from the front, top of the windshield (its slope: rise over run from "
    "windshield_base)",
    "roof_end": "m from the front, end of the roof (top of the rear window or back of the cab)",
    "rear_window_end": "m from the front, bottom of the rear window or of the cab back (start "
    "of the trunk lid, bed or tailgate)",
    "deck_height": "m, height at rear_window_end (trunk lid, pickup bed deck, tailgate top)",
    "tail_height": "m, top of the rear face",
    "beltline": "m, lower edge of the side windows; above it the sides lean in",
    "tumblehome": "m, inward offset of the roof edge from the body side, per side (>= 0)",
    "bumper_radius": "m, plan-view radius of the four corners (rounded bumpers)",
    "edge_radius": "m, side-view radius of the top and bottom edges of the front and rear faces",
    "shoulder_radius": "m, cross-section radius where the sides meet the roof, hood and deck",
}

# Nominal shape per preset: name -> (rule, factor). Rules: "m" absolute metres; "L", "W", "H"
# a fraction of length, width or height; "overhang" a share of (length - wheelbase). Five of
# them are then adapted to the dimensions (see _ADAPTIVE below): wheel_radius,
# ground_clearance, bumper_bottom, edge_radius and bumper_radius. The van is the class's
# 1990s minivan (one-box, short sloping hood), the sedan a low 1990s mid-size car.
_DEFAULTS: dict[str, dict[str, tuple[str, float]]] = {
    "sedan": {
        "front_overhang": ("overhang", 0.46),
        "ground_clearance": ("m", 0.14),
        "wheel_radius": ("m", 0.31),
        "arch_gap": ("m", 0.04),
        "arch_depth": ("m", 0.25),
        "bumper_bottom": ("H", 0.21),
        "nose_height": ("H", 0.56),
        "hood_height": ("H", 0.71),
        "windshield_base": ("L", 0.35),
        "roof_start": ("L", 0.51),
        "roof_end": ("L", 0.70),
        "rear_window_end": ("L", 0.835),
        "deck_height": ("H", 0.75),
        "tail_height": ("H", 0.72),
        "beltline": ("H", 0.70),
        "tumblehome": ("W", 0.07),
        "bumper_radius": ("W", 0.24),
        "edge_radius": ("m", 0.10),
        "shoulder_radius": ("m", 0.12),
    },
    "suv": {
        "front_overhang": ("overhang", 0.45),
        "ground_clearance": ("m", 0.20),
        "wheel_radius": ("m", 0.37),
        "arch_gap": ("m", 0.05),
        "arch_depth": ("m", 0.28),
        "bumper_bottom": ("H", 0.23),
        "nose_height": ("H", 0.51),
        "hood_height": ("H", 0.63),
        "windshield_base": ("L", 0.305),
        "roof_start": ("L", 0.45),
        "roof_end": ("L", 0.925),
        "rear_window_end": ("L", 0.975),
        "deck_height": ("H", 0.64),
        "tail_height": ("H", 0.61),
        "beltline": ("H", 0.64),
        "tumblehome": ("W", 0.055),
        "bumper_radius": ("W", 0.21),
        "edge_radius": ("m", 0.10),
        "shoulder_radius": ("m", 0.12),
    },
    "pickup": {
        "front_overhang": ("overhang", 0.43),
        "ground_clearance": ("m", 0.23),
        "wheel_radius": ("m", 0.40),
        "arch_gap": ("m", 0.06),
        "arch_depth": ("m", 0.30),
        "bumper_bottom": ("H", 0.26),
        "nose_height": ("H", 0.57),
        "hood_height": ("H", 0.68),
        "windshield_base": ("L", 0.27),
        "roof_start": ("L", 0.37),
        "roof_end": ("L", 0.60),
        "rear_window_end": ("L", 0.615),
        "deck_height": ("H", 0.68),
        "tail_height": ("H", 0.665),
        "beltline": ("H", 0.69),
        "tumblehome": ("W", 0.05),
        "bumper_radius": ("W", 0.17),
        "edge_radius": ("m", 0.10),
        "shoulder_radius": ("m", 0.10),
    },
    "van": {
        "front_overhang": ("overhang", 0.50),
        "ground_clearance": ("m", 0.16),
        "wheel_radius": ("m", 0.32),
        "arch_gap": ("m", 0.045),
        "arch_depth": ("m", 0.26),
        "bumper_bottom": ("H", 0.17),
        "nose_height": ("H", 0.45),
        "hood_height": ("H", 0.62),
        "windshield_base": ("L", 0.20),
        "roof_start": ("L", 0.43),
        "roof_end": ("L", 0.93),
        "rear_window_end": ("L", 0.975),
        "deck_height": ("H", 0.60),
        "tail_height": ("H", 0.57),
        "beltline": ("H", 0.60),
        "tumblehome": ("W", 0.05),
        "bumper_radius": ("W", 0.17),
        "edge_radius": ("m", 0.12),
        "shoulder_radius": ("m", 0.15),
    },
    "bus": {
        "front_overhang": ("overhang", 0.45),
        "ground_clearance": ("m", 0.25),
        "wheel_radius": ("m", 0.50),
        "arch_gap": ("m", 0.06),
        "arch_depth": ("m", 0.32),
        "bumper_bottom": ("H", 0.125),
        "nose_height": ("H", 0.96),
        "hood_height": ("H", 0.98),
        "windshield_base": ("L", 0.01),
        "roof_start": ("L", 0.0375),
        "roof_end": ("L", 0.97),
        "rear_window_end": ("L", 0.99),
        "deck_height": ("H", 0.98),
        "tail_height": ("H", 0.96),
        "beltline": ("m", 1.25),
        "tumblehome": ("W", 0.02),
        "bumper_radius": ("W", 0.14),
        "edge_radius": ("m", 0.15),
        "shoulder_radius": ("m", 0.18),
    },
}

# Fixed details of the cross-section (m).
_SILL_RADIUS = 0.04  # rounding of the lower outer edge of each section (sill, arch lip)
_STEP = 0.008  # inward bevel of a wheel arch's inner wall between underside and arch
_SHOULDER_MIN = 0.05  # least height of the rounded top above the side wall (hood, deck sides)
_CROWN = 0.012  # roof crown as a fraction of the width (limited by the local top height)
_MARGIN = 0.01  # least clearance between stacked features of a section (m)
_ARCH_RAMP_DEG = 10.0  # the arch's near-vertical lower edges span this much of its circle
_FILLET = 0.25  # side-view fillets use up to this share of each adjacent profile segment
_FILLET_MAX = 0.35  # ... and at most this path length (m)
_PROFILE_SAMPLES = 16  # points per side-view fillet in the profile polylines


@dataclass(frozen=True)
class BodyParams:
    """The validated parameters of a generated body (make one with :func:`body_params`).

    All lengths in metres. Heights are above the ground (z = 0); positions "from the front"
    are distances rearwards from the front face.
    """

    preset: str  # one of PRESETS
    length: float  # overall length (x extent)
    width: float  # overall width (y extent)
    height: float  # roof height above the ground (top of the body)
    wheelbase: float  # front axle to rear axle
    front_overhang: float  # front face to the front axle
    ground_clearance: float  # underside between the axles (lowest point of the body)
    wheel_radius: float  # tyre radius = wheel-centre height
    arch_gap: float  # tyre to arch; arch radius = wheel_radius + arch_gap
    arch_depth: float  # how far the arch cut reaches in from the body side
    bumper_bottom: float  # lower edge of the front and rear ends
    nose_height: float  # top of the front face
    hood_height: float  # hood at the windshield base
    windshield_base: float  # from the front: windshield meets the hood
    roof_start: float  # from the front: top of the windshield
    roof_end: float  # from the front: top of the rear window / back of the cab
    rear_window_end: float  # from the front: bottom of the rear window / cab back
    deck_height: float  # height at rear_window_end (trunk, bed, tailgate)
    tail_height: float  # top of the rear face
    beltline: float  # lower edge of the side windows
    tumblehome: float  # roof-edge inset per side (>= 0)
    bumper_radius: float  # plan-view corner radius
    edge_radius: float  # side-view radius of the end faces' top and bottom edges
    shoulder_radius: float  # section radius where sides meet roof, hood, deck

    def __post_init__(self) -> None:
        """Every number finite and > 0 (tumblehome >= 0) and the combination buildable, else
        ParameterError; so a BodyParams made directly or by dataclasses.replace is checked
        like one from body_params."""
        if not isinstance(self.preset, str) or self.preset not in PRESETS:
            raise ParameterError(f"unknown preset {self.preset!r}: use one of {', '.join(PRESETS)}")
        for name in _NUMBERS:
            object.__setattr__(self, name, _number(getattr(self, name), name))
        _check(self)

    @property
    def rear_overhang(self) -> float:
        """Rear axle to the rear face (m)."""
        return self.length - self.front_overhang - self.wheelbase

    @property
    def arch_radius(self) -> float:
        """Radius of the wheel arches (m): wheel_radius + arch_gap."""
        return self.wheel_radius + self.arch_gap

    def as_dict(self) -> dict[str, Any]:
        """The parameters as a dict, in field order."""
        return dataclasses.asdict(self)


_DIMS = ("length", "width", "height", "wheelbase")
_NUMBERS = tuple(f.name for f in dataclasses.fields(BodyParams) if f.name != "preset")
_MAY_BE_ZERO = frozenset({"tumblehome"})


def _number(value: Any, name: str) -> float:
    """A finite float (m) or a ParameterError naming the parameter."""
    if isinstance(value, bool) or not isinstance(value, int | float | np.integer | np.floating):
        raise ParameterError(f"{name} must be a number of metres, got {value!r}")
    x = float(value)
    if not math.isfinite(x):
        raise ParameterError(f"{name} = {x} is invalid: give a finite number of metres")
    if x < 0.0 or (x == 0.0 and name not in _MAY_BE_ZERO):
        rule = ">= 0" if name in _MAY_BE_ZERO else "> 0"
        raise ParameterError(f"{name} = {x} m is invalid: it must be {rule} m")
    return x


def body_params(
    preset: str,
    *,
    length: float,
    width: float,
    height: float,
    wheelbase: float,
    **shape: float,
) -> BodyParams:
    """Validated parameters of a body of class ``preset`` (one of :data:`PRESETS`).

    length, width, height (roof above the ground) and wheelbase are in metres. Any shape
    parameter of :data:`SHAPE_PARAMETERS` may be given (m); the others take the preset's
    default, scaled to the dimensions, and five defaults adapt so that any dimensions of a
    vehicle of the class give a valid body (each only where the nominal value would not fit,
    and only after the given numbers are in place):

    - wheel_radius: the preset's tyre radius, or the largest radius (to the mm below) with
      which each arch leaves 0.08 m of body before the end of the body, the arches leave
      0.1 m between them, and over each arch's whole length the top of the body side (the
      beltline, or the hood, roof or deck line less 0.05 m) stays 0.07 m above the arch's
      top (wheel_radius + arch radius). Never below half the preset's radius: dimensions that
      need less are refused.
    - ground_clearance: at most 0.75 wheel_radius. bumper_bottom: at least ground_clearance.
    - edge_radius: at most the body between an arch and the end of the body, and at most 0.45
      of what the lower end face leaves beside its fixed details.
    - bumper_radius: at most 0.8 of the shorter overhang.

    Raises ParameterError, naming the parameter and how to fix it, for a non-finite or
    non-positive number, an unknown preset or parameter, or a combination that gives no valid
    body (axles beyond the body, arches that do not fit, a beltline above the roof, ...).
    """
    if not isinstance(preset, str) or preset not in PRESETS:
        raise ParameterError(f"unknown preset {preset!r}: use one of {', '.join(PRESETS)}")
    unknown = sorted(set(shape) - set(SHAPE_PARAMETERS))
    if unknown:
        raise ParameterError(
            f"unknown shape parameter(s) {', '.join(unknown)}: the shape parameters are "
            f"{', '.join(SHAPE_PARAMETERS)}"
        )
    dims = {"length": length, "width": width, "height": height, "wheelbase": wheelbase}
    values: dict[str, float] = {k: _number(v, k) for k, v in dims.items()}
    L, W, H, wb = (values[k] for k in _DIMS)
    if wb >= L:
        raise ParameterError(
            f"wheelbase = {wb} m is not shorter than length = {L} m: give a shorter wheelbase"
        )
    given = {name: _number(value, name) for name, value in shape.items()}
    nominal: dict[str, float] = {}
    for name, (rule, factor) in _DEFAULTS[preset].items():
        scale = {"m": 1.0, "L": L, "W": W, "H": H, "overhang": L - wb}[rule]
        nominal[name] = factor * scale
    values.update(nominal)
    values.update(given)
    # The adaptive defaults, in this order (each sees the values fixed before it).
    for name, adapt in _ADAPTIVE:
        if name not in given:
            values[name] = adapt(values, nominal[name])
    return BodyParams(preset=preset, **values)


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


class _Values:
    """Attribute access to a dict of parameters (for the profile functions)."""

    def __init__(self, values: Mapping[str, float]) -> None:
        self.__dict__.update(values)


def _fail(message: str) -> NoReturn:
    raise ParameterError(message)


def _check(p: BodyParams) -> None:
    """ParameterError for combinations that give no valid body (all sizes are > 0 here)."""
    L, W, H = p.length, p.width, p.height
    if p.wheelbase >= L:
        _fail(
            f"wheelbase = {p.wheelbase} m is not shorter than length = {L} m: give a shorter "
            "wheelbase"
        )
    half = W / 2.0
    ra = p.arch_radius
    fo, ro = p.front_overhang, p.rear_overhang
    # The axles and wheel arches along the body.
    if ro <= 0.0:
        _fail(
            f"wheelbase + front_overhang = {p.wheelbase + fo:.4g} m is not shorter than "
            f"length = {L} m: shorten the wheelbase or the front_overhang"
        )
    if fo < ra + 0.05:
        _fail(
            f"front_overhang = {fo:.4g} m leaves no bumper ahead of the front wheel arch "
            f"(arch radius wheel_radius + arch_gap = {ra:.4g} m, and 0.05 m in front of it): "
            "raise front_overhang or lower wheel_radius"
        )
    if ro < ra + 0.05:
        _fail(
            f"the rear overhang (length - front_overhang - wheelbase = {ro:.4g} m) leaves no "
            f"bumper behind the rear wheel arch (arch radius {ra:.4g} m, and 0.05 m behind it): "
            "shorten the wheelbase or front_overhang, or lower wheel_radius"
        )
    if p.wheelbase < 2.0 * ra + 0.1:
        _fail(
            f"wheelbase = {p.wheelbase} m is too short for two wheel arches of radius "
            f"{ra:.4g} m (needs at least {2 * ra + 0.1:.4g} m): lower wheel_radius or arch_gap"
        )
    # Heights.
    if p.ground_clearance >= p.wheel_radius:
        _fail(
            f"ground_clearance = {p.ground_clearance} m is not below the wheel centres "
            f"(wheel_radius = {p.wheel_radius} m): lower ground_clearance or raise wheel_radius"
        )
    if p.bumper_bottom < p.ground_clearance:
        _fail(
            f"bumper_bottom = {p.bumper_bottom} m is below ground_clearance = "
            f"{p.ground_clearance} m (the body's lowest point): raise bumper_bottom"
        )
    if p.beltline >= H:
        _fail(
            f"beltline = {p.beltline} m is not below the roof (height = {H} m): lower the beltline"
        )
    if p.beltline <= p.ground_clearance:
        _fail(f"beltline = {p.beltline} m is not above ground_clearance: raise the beltline")
    for name in ("nose_height", "hood_height", "deck_height", "tail_height"):
        value = getattr(p, name)
        if value > H:
            _fail(f"{name} = {value} m is above the roof (height = {H} m): lower {name}")
    # Positions along the body (from the front).
    order = ("windshield_base", "roof_start", "roof_end", "rear_window_end")
    previous_name, previous = "the front face", 0.0
    for name in order:
        value = getattr(p, name)
        if value < previous + 0.01:
            _fail(
                f"{name} = {value:.4g} m (from the front) must be at least 0.01 m behind "
                f"{previous_name} ({previous:.4g} m): the profile runs front face, "
                f"{', '.join(order)}, rear face"
            )
        previous_name, previous = name, value
    if p.rear_window_end > L:
        _fail(
            f"rear_window_end = {p.rear_window_end:.4g} m (from the front) is behind the rear "
            f"face (length = {L} m): give at most the length"
        )
    # Widths and roundings.
    if p.bumper_radius >= half:
        _fail(
            f"bumper_radius = {p.bumper_radius} m is not less than half the width "
            f"({half} m): lower bumper_radius"
        )
    if p.bumper_radius > min(fo, ro):
        which = "front_overhang" if fo <= ro else "rear overhang"
        _fail(
            f"bumper_radius = {p.bumper_radius} m is larger than the {which} "
            f"({min(fo, ro):.4g} m): the corner rounding would reach past the axle; "
            "lower bumper_radius"
        )
    least = _STEP + _SILL_RADIUS + 0.02
    if p.arch_depth < least:
        _fail(f"arch_depth = {p.arch_depth} m is too small: give at least {least:.3g} m")
    if p.arch_depth > 0.8 * half:
        _fail(
            f"arch_depth = {p.arch_depth} m reaches too far in (more than 0.8 of the half width "
            f"{half} m): lower arch_depth"
        )
    if p.tumblehome > 0.5 * half:
        _fail(
            f"tumblehome = {p.tumblehome} m narrows the roof by more than half the half width "
            f"({half} m): lower tumblehome"
        )
    if p.edge_radius > min(fo, ro) - ra:
        _fail(
            f"edge_radius = {p.edge_radius} m reaches into a wheel arch (it must be at most the "
            f"overhang minus the arch radius, {min(fo, ro) - ra:.4g} m): lower edge_radius"
        )
    for end, top in (("front", p.nose_height), ("rear", p.tail_height)):
        face = top - p.bumper_bottom
        fixed = _SILL_RADIUS + _SHOULDER_MIN + 2.0 * _MARGIN
        need = 2.0 * p.edge_radius + fixed
        if face < need:
            name = "nose_height" if end == "front" else "tail_height"
            _fail(
                f"the {end} face is too low: {name} - bumper_bottom = {face:.4g} m must be at "
                f"least {need:.4g} m (2 edge_radius + {fixed:.2f} m): raise {name}, lower "
                "bumper_bottom or edge_radius"
            )
    # Every section: the wheel arches and sill must fit under the hood, beltline and deck.
    d = _check_stations(p)
    prof = _profiles(p, d)
    room = prof["z_shoulder"] - (prof["z_notch"] + _SILL_RADIUS + _MARGIN)
    bad = np.flatnonzero(room < 0.0)
    if bad.size:
        i = int(bad[np.argmin(room[bad])])
        where = float(d[i])
        axle = _near_axle(p, where)
        if axle:
            _fail(
                f"the {axle} wheel arch does not fit: at {where:.3f} m from the front its top "
                f"({float(prof['z_notch'][i]):.3f} m) is too close to the top of the body side "
                f"({float(prof['z_shoulder'][i]):.3f} m, needs {_SILL_RADIUS + _MARGIN:.2f} m "
                "between): lower wheel_radius or arch_gap, or raise hood_height, nose_height, "
                "deck_height or beltline"
            )
        if prof["z_shoulder"][i] == p.beltline:
            _fail(
                f"beltline = {p.beltline} m is too low: at {where:.3f} m from the front the "
                f"underside is at {float(prof['z_notch'][i]):.3f} m and needs "
                f"{_SILL_RADIUS + _MARGIN:.2f} m below the beltline: raise the beltline or "
                "lower bumper_bottom or ground_clearance"
            )
        _fail(
            f"the body is too low at {where:.3f} m from the front: the underside "
            f"({float(prof['z_notch'][i]):.3f} m) is too close to the top "
            f"({float(prof['z_top'][i]):.3f} m): raise nose_height, hood_height, deck_height or "
            "tail_height, or lower bumper_bottom or ground_clearance"
        )


def _near_axle(p: BodyParams, d: float) -> str:
    """'front' or 'rear' when d (m from the front) is within an arch, else ''."""
    for name, da in (("front", p.front_overhang), ("rear", p.front_overhang + p.wheelbase)):
        if abs(d - da) <= p.arch_radius:
            return name
    return ""


# -- deterministic elementary functions -------------------------------------------------------


def _cos_sin(theta: Array) -> tuple[Array, Array]:
    """cos and sin of angles in [0, pi] (rad) by fixed Taylor polynomials (error < 1e-16).

    Only + - * / in a fixed order, so the bits do not depend on the platform's libm or on
    numpy's SIMD paths."""
    theta = np.asarray(theta, dtype=np.float64)
    flip = theta > math.pi / 2.0
    x = np.where(flip, math.pi - theta, theta)  # in [0, pi/2]
    x2 = x * x
    s = np.ones_like(x)
    c = np.ones_like(x)
    for k in range(13, 0, -1):
        s = 1.0 - x2 * s / float((2 * k) * (2 * k + 1))
        c = 1.0 - x2 * c / float((2 * k - 1) * (2 * k))
    return np.where(flip, -c, c), x * s


def _interp(xq: Array, xp: Array, fp: Array) -> Array:
    """Piecewise-linear interpolation of (xp, fp) at xq (xp strictly increasing, xq inside).
    Written out (not np.interp) so the arithmetic is fixed; flat pieces give exact values."""
    i = np.clip(np.searchsorted(xp, xq, side="right") - 1, 0, len(xp) - 2)
    x0, x1, f0, f1 = xp[i], xp[i + 1], fp[i], fp[i + 1]
    return f0 + (xq - x0) / (x1 - x0) * (f1 - f0)


def _filleted(points: list[tuple[float, float]], per_corner: int) -> tuple[Array, Array]:
    """A polyline (d, z) with strictly increasing d whose interior corners are replaced by
    quadratic Bezier fillets sampled at per_corner points (the ends are kept)."""
    pts = np.array(points, dtype=np.float64)
    out = [pts[0]]
    for k in range(1, len(pts) - 1):
        a, b, c = pts[k - 1], pts[k], pts[k + 1]
        # lengths written out: a BLAS dot product may fuse multiply-adds on some machines
        ux, uz, vx, vz = (float(t) for t in (b[0] - a[0], b[1] - a[1], c[0] - b[0], c[1] - b[1]))
        la = math.sqrt(ux * ux + uz * uz)
        lc = math.sqrt(vx * vx + vz * vz)
        f = min(_FILLET * la, _FILLET * lc, _FILLET_MAX)
        p0 = b + (a - b) * (f / la)
        p2 = b + (c - b) * (f / lc)
        t = np.arange(per_corner + 1, dtype=np.float64) / per_corner
        u = 1.0 - t
        curve = (u * u)[:, None] * p0 + (2.0 * u * t)[:, None] * b + (t * t)[:, None] * p2
        out.extend(curve)
    out.append(pts[-1])
    poly = np.array(out)
    return poly[:, 0], poly[:, 1]


# -- the side view, the plan view and the stations along x ------------------------------------


def _top_points(p: BodyParams | _Values) -> list[tuple[float, float]]:
    return [
        (0.0, p.nose_height),
        (p.windshield_base, p.hood_height),
        (p.roof_start, p.height),
        (p.roof_end, p.height),
        (p.rear_window_end, p.deck_height),
        (p.length, p.tail_height),
    ]


def _bottom_points(p: BodyParams) -> list[tuple[float, float]]:
    fo = p.front_overhang
    return [
        (0.0, p.bumper_bottom),
        (fo, p.ground_clearance),
        (fo + p.wheelbase, p.ground_clearance),
        (p.length, p.bumper_bottom),
    ]


def _profiles(p: BodyParams, d: Array) -> dict[str, Array]:
    """Side-view and plan-view quantities at stations d (m from the front).

    z_top: top of the section at y = 0; z_bottom: underside at y = 0; z_notch: underside of the
    outer part (raised inside the wheel arches); z_shoulder: top of the vertical side wall;
    scale: plan-view half width / (width / 2) (1 between the rounded corners)."""
    L, half = p.length, p.width / 2.0
    td, tz = _filleted(_top_points(p), _PROFILE_SAMPLES)
    bd, bz = _filleted(_bottom_points(p), _PROFILE_SAMPLES)
    z_top = _interp(d, td, tz)
    z_bottom = _interp(d, bd, bz)
    # Side-view rounding of the end faces' top and bottom edges (radius edge_radius).
    rho = p.edge_radius
    e = np.minimum(d, L - d)
    inside = e < rho
    q = np.where(inside, rho - e, 0.0)
    bump = np.where(inside, rho - np.sqrt(rho * rho - q * q), 0.0)
    z_top = z_top - bump
    z_bottom = z_bottom + bump
    # Plan-view rounding of the corners (radius bumper_radius).
    r = p.bumper_radius
    inside = e < r
    q = np.where(inside, r - e, 0.0)
    w = np.where(inside, half - r + np.sqrt(r * r - q * q), half)
    scale = w / half
    # Wheel arches: a circle about the wheel centre, with near-vertical lower edges.
    ra, wr = p.arch_radius, p.wheel_radius
    cos0, sin0 = (float(v[0]) for v in _cos_sin(np.array([math.radians(_ARCH_RAMP_DEG)])))
    z_notch = z_bottom.copy()
    for da in (p.front_overhang, p.front_overhang + p.wheelbase):
        dx = np.abs(d - da)
        circle = wr + np.sqrt(np.maximum(ra * ra - dx * dx, 0.0))
        h_ramp = wr + ra * sin0
        ramp = z_bottom + (h_ramp - z_bottom) * (ra - dx) / (ra - ra * cos0)
        h = np.where(dx <= ra * cos0, circle, np.where(dx < ra, ramp, -np.inf))
        z_notch = np.maximum(z_notch, h)
    z_shoulder = np.minimum(p.beltline, z_top - _SHOULDER_MIN)
    return {
        "z_top": z_top,
        "z_bottom": z_bottom,
        "z_notch": z_notch,
        "z_shoulder": z_shoulder,
        "scale": scale,
    }


def _arc_stations(radius: float, n: int) -> Array:
    """Distances from an end face, radius (1 - cos phi) for n + 1 equal steps of phi in
    [0, pi/2]: where the side-view or plan-view end rounding changes fastest."""
    phi = np.arange(n + 1, dtype=np.float64) * (math.pi / 2.0 / n)
    c, _ = _cos_sin(phi)
    return radius - radius * c


def _stations(p: BodyParams, resolution: float) -> Array:
    """Section positions d (m from the front), strictly increasing from 0 to length: the corner
    and edge roundings, the arches and the profile's corners, filled in evenly elsewhere."""
    L = p.length
    n_fill = max(8, round(16 * resolution))
    n_end = max(3, round(5 * resolution))
    n_arch = max(5, round(8 * resolution))
    per_corner = max(2, round(3 * resolution))
    keys = [np.array([0.0, L])]
    for radius in (p.bumper_radius, p.edge_radius):
        a = _arc_stations(radius, n_end)
        keys += [a, L - a]
    theta0 = math.radians(_ARCH_RAMP_DEG)
    theta = theta0 + np.arange(n_arch, dtype=np.float64) * ((math.pi - 2 * theta0) / (n_arch - 1))
    c_arch, _ = _cos_sin(theta)
    ra = p.arch_radius
    for da in (p.front_overhang, p.front_overhang + p.wheelbase):
        keys.append(np.array([da - ra, da + ra]))
        keys.append(da - ra * c_arch)
    for pts in (_top_points(p), _bottom_points(p)):
        keys.append(_filleted(pts, per_corner)[0])
    key = np.unique(np.concatenate(keys))
    key = key[(key >= 0.0) & (key <= L)]
    # Merge keys closer than tol (keeping 0 and L), then drop even fillers near a key.
    tol = 2e-4 * L
    kept = [0.0]
    for v in key[1:]:
        if v - kept[-1] > tol:
            kept.append(float(v))
    if kept[-1] != L:
        if L - kept[-1] <= tol:
            kept[-1] = L
        else:
            kept.append(L)
    key = np.array(kept)
    fill = np.arange(1, n_fill, dtype=np.float64) * (L / n_fill)
    gap = 0.3 * L / n_fill
    j = np.clip(np.searchsorted(key, fill), 1, len(key) - 1)
    near = np.minimum(fill - key[j - 1], key[j] - fill)
    return np.sort(np.concatenate([key, fill[near > gap]]))


def _check_stations(p: BodyParams) -> Array:
    """Dense stations for validating a parameter set (independent of the resolution)."""
    even = np.arange(2001, dtype=np.float64) * (p.length / 2000)
    return np.unique(np.concatenate([even, _stations(p, 4.0)]))


# -- cross-sections ---------------------------------------------------------------------------


def _counts(resolution: float) -> dict[str, int]:
    """Points per part of a half cross-section."""

    def n(base: float, least: int) -> int:
        return max(least, round(base * resolution))

    return {
        "bottom": n(2, 1),
        "notch": n(1, 1),
        "corner": n(3, 2),
        "wall": n(3, 2),
        "side": n(2, 1),
        "fillet": n(3, 2),
        "roof": n(3, 2),
    }


def body_sections(p: BodyParams, resolution: float = 1.0) -> tuple[Array, Array]:
    """The loft of the body: x (k,) strictly increasing (m, model frame) and the sections
    (k, n, 2) as (y, z) points (m), each a simple polygon, counter-clockwise seen from +x."""
    res = _resolution(resolution)
    d = _stations(p, res)
    prof = _profiles(p, d)
    half = p.width / 2.0
    s = prof["scale"][:, None]
    zb = prof["z_bottom"][:, None]
    zn = prof["z_notch"][:, None]
    zs = prof["z_shoulder"][:, None]
    zt = prof["z_top"][:, None]
    cnt = _counts(res)
    parts_y: list[Array] = []
    parts_z: list[Array] = []

    def add(y: Array, z: Array) -> None:
        y, z = np.broadcast_arrays(y, z)
        parts_y.append(y)
        parts_z.append(z)

    def frac(n: int, first: int = 1) -> Array:
        """j / n for j = first..n as a (1, n - first + 1) row."""
        return (np.arange(first, n + 1, dtype=np.float64) / n)[None, :]

    y_inner = (half - p.arch_depth) * s  # inner wall of the arch notch at the underside
    # 1. underside from the centre line (excluded) to the arch's inner wall
    add(y_inner * frac(cnt["bottom"]), zb)
    # 2. the arch's inner wall, bevelled by _STEP
    y_step = y_inner + _STEP * s
    add(y_step, zn)
    # 3. underside of the notch (points strictly between the wall and the sill rounding)
    y_corner = (half - _SILL_RADIUS) * s
    t = frac(cnt["notch"] + 1)[:, :-1]
    add(y_step + (y_corner - y_step) * t, zn)
    # 4. sill rounding: a quarter ellipse (half axes _SILL_RADIUS * scale, _SILL_RADIUS)
    phi = np.arange(cnt["corner"] + 1, dtype=np.float64) * (math.pi / 2.0 / cnt["corner"])
    c, sn = _cos_sin(phi)  # phi = 0: bottom of the rounding, pi/2: foot of the wall
    add(y_corner + (_SILL_RADIUS * s) * sn[None, :], zn + _SILL_RADIUS * (1.0 - c[None, :]))
    # 5. vertical side wall up to the shoulder
    w = half * s
    z_foot = zn + _SILL_RADIUS
    add(w, z_foot + (zs - z_foot) * frac(cnt["wall"]))
    # 6. greenhouse side (leaning in by the tumblehome) up to the start of the roof fillet
    green = np.minimum((zt - zs) / (p.height - p.beltline), 1.0)
    w_top = (half - p.tumblehome * green) * s
    crown = np.minimum(_CROWN * p.width, 0.3 * (zt - zs))
    kz = zt - crown  # roof edge corner K = (w_top, kz)
    ay, az = w, zs
    side = np.sqrt((ay - w_top) ** 2 + (az - kz) ** 2)
    f_side = np.minimum(p.shoulder_radius, 0.45 * side)
    psy = w_top + (ay - w_top) * (f_side / side)
    psz = kz + (az - kz) * (f_side / side)
    add(ay + (psy - ay) * frac(cnt["side"]), az + (psz - az) * frac(cnt["side"]))
    # 7. shoulder fillet: quadratic Bezier from Ps over K to Pe on the roof
    f_roof = np.minimum(p.shoulder_radius, 0.45 * w_top)
    pey = w_top - f_roof
    pez = zt - crown * (pey / w_top) ** 2
    tb = frac(cnt["fillet"])
    ub = 1.0 - tb
    add(
        ub * ub * psy + 2.0 * ub * tb * w_top + tb * tb * pey,
        ub * ub * psz + 2.0 * ub * tb * kz + tb * tb * pez,
    )
    # 8. crowned roof (or hood, deck) towards the centre line (excluded)
    t = frac(cnt["roof"] + 1)[:, :-1]
    ry = pey - pey * t
    add(ry, zt - crown * (ry / w_top) ** 2)
    hy = np.concatenate(parts_y, axis=1)
    hz = np.concatenate(parts_z, axis=1)
    k = len(d)
    zeros = np.zeros((k, 1))
    y = np.concatenate([zeros, hy, zeros, -hy[:, ::-1]], axis=1)
    z = np.concatenate([zb, hz, zt, hz[:, ::-1]], axis=1)
    x = p.length / 2.0 - d[::-1]  # x increases; d = 0 is the front face at x = length / 2
    sections = np.stack([y[::-1], z[::-1]], axis=2)
    _check_sections(sections, p)
    return x, sections


def _check_sections(sections: Array, p: BodyParams) -> None:
    """Internal guard of what makes each section a simple polygon: its y > 0 half climbs from
    the underside to the roof (z never decreases, and where it stays level y grows) with every
    point but the two on the centre line at y > 0; the other half is its mirror image."""
    n = sections.shape[1]
    half = sections[:, : n // 2 + 1, :]  # bottom centre ... top centre, y >= 0
    dy = np.diff(half[..., 0], axis=1)
    dz = np.diff(half[..., 1], axis=1)
    climbs = (dz > 1e-9) | ((dz >= 0.0) & (dy > 1e-9))
    if not np.all(climbs) or np.any(half[:, 1:-1, 0] <= 0.0):
        raise ParameterError(
            f"the {p.preset} parameters give a degenerate cross-section: {p.as_dict()} "
            "(please report this with the parameters)"
        )


def _resolution(resolution: float) -> float:
    if isinstance(resolution, bool) or not isinstance(resolution, int | float):
        raise ParameterError(f"resolution must be a number, got {resolution!r}")
    res = float(resolution)
    if not math.isfinite(res) or not 0.25 <= res <= 8.0:
        raise ParameterError(
            f"resolution = {resolution} is invalid: give a number in [0.25, 8] (1 = default, "
            "a few thousand triangles; the count grows about as resolution squared)"
        )
    return res


# -- the loft ---------------------------------------------------------------------------------


def loft(x: Array, sections: Array) -> trimesh.Trimesh:
    """A closed, outward-wound mesh through cross-sections along x (model frame, m).

    x: (k,) strictly increasing, k >= 2. sections: (k, n, 2) points (y, z), n >= 3, each a
    simple polygon counter-clockwise seen from +x, point j of one section joined to point j of
    the next. Each end is closed by a fan from the centre of its section's bounding box, so
    the end sections must be star-shaped from there (a convex section is). Vertices: the
    sections in order, then the two fan centres (rear end, front end). Quads are split so
    that mirror-symmetric sections (about y = 0) give a mirror-symmetric mesh.
    """
    x = np.asarray(x, dtype=np.float64)
    sections = np.asarray(sections, dtype=np.float64)
    if x.ndim != 1 or len(x) < 2 or sections.shape[:1] != x.shape:
        raise MeshError("loft needs k >= 2 stations x and k sections (k, n, 2)")
    if sections.ndim != 3 or sections.shape[2] != 2 or sections.shape[1] < 3:
        raise MeshError(f"loft sections must be (k, n >= 3, 2), got {sections.shape}")
    if not (np.all(np.isfinite(x)) and np.all(np.isfinite(sections))):
        raise MeshError("loft stations and sections must be finite")
    if np.any(np.diff(x) <= 0.0):
        raise MeshError("loft stations x must be strictly increasing")
    k, n, _ = sections.shape
    ends = []
    for i in (0, k - 1):
        sec = sections[i]
        centre = (sec.min(axis=0) + sec.max(axis=0)) / 2.0
        a = sec - centre
        b = np.roll(sec, -1, axis=0) - centre
        if np.any(a[:, 0] * b[:, 1] - a[:, 1] * b[:, 0] <= 0.0):
            raise MeshError(
                f"loft end section {i} is not counter-clockwise and star-shaped about the "
                "centre of its bounding box: its end cap would fold"
            )
        ends.append(centre)
    xs = np.repeat(x, n)
    vertices = np.concatenate(
        [
            np.column_stack([xs, sections.reshape(-1, 2)]),
            [[x[0], ends[0][0], ends[0][1]], [x[-1], ends[1][0], ends[1][1]]],
        ]
    )
    i = np.arange(k - 1)[:, None] * n
    j = np.arange(n)[None, :]
    a = (i + j).ravel()
    b = (i + (j + 1) % n).ravel()
    c = a + n
    dd = b + n
    # Split each quad along the diagonal b-c where its mean y >= 0 and along a-dd where it is
    # below: mirrored quads get mirrored diagonals, so a left-right symmetric set of sections
    # gives a mirror-symmetric mesh (no spurious products of inertia or normal tilt).
    flat = sections.reshape(-1, 2)
    left = flat[a, 0] + flat[b, 0] + flat[c, 0] + flat[dd, 0] >= 0.0
    sides = np.concatenate(
        [
            np.column_stack([a, b, c])[left],
            np.column_stack([b, dd, c])[left],
            np.column_stack([a, b, dd])[~left],
            np.column_stack([a, dd, c])[~left],
        ]
    )
    rear_c, front_c = k * n, k * n + 1
    jj = np.arange(n)
    rear = np.column_stack([np.full(n, rear_c), (jj + 1) % n, jj])
    front = np.column_stack([np.full(n, front_c), (k - 1) * n + jj, (k - 1) * n + (jj + 1) % n])
    faces = np.concatenate([sides, rear, front]).astype(np.int64)
    return trimesh.Trimesh(vertices=vertices, faces=faces, process=False)


def generate_body(p: BodyParams, resolution: float = 1.0) -> trimesh.Trimesh:
    """The closed, watertight, single-shell body of ``p`` (from :func:`body_params`) as a
    trimesh.Trimesh in the model frame (m; x forward, y left, z up, ground z = 0; bounding box
    x in [-length/2, length/2], y in [-width/2, width/2], z in [ground_clearance, height]).

    resolution scales the number of sections and of points per section (1: a few thousand
    triangles; the count grows about as resolution squared). Deterministic: the same
    parameters give the same vertex and face arrays, bit for bit."""
    if not isinstance(p, BodyParams):
        raise ParameterError(
            f"generate_body needs a BodyParams from body_params(...), got {type(p).__name__}"
        )
    x, sections = body_sections(p, resolution)
    return loft(x, sections)


# -- binary PLY -------------------------------------------------------------------------------


def ply_bytes(mesh: trimesh.Trimesh, comments: Mapping[str, Any] | None = None) -> bytes:
    """The mesh as a binary little-endian PLY (float64 vertices, int32 indices), byte-exact
    for the same arrays; ``comments`` become "comment key=value" header lines."""
    vertices = np.ascontiguousarray(mesh.vertices, dtype="<f8")
    faces = np.asarray(mesh.faces)
    lines = ["ply", "format binary_little_endian 1.0"]
    for key, value in (comments or {}).items():
        text = f"{key}={value!r}" if isinstance(value, float) else f"{key}={value}"
        if "\n" in text:
            raise ValueError("a PLY comment must be one line")
        lines.append(f"comment {text}")
    lines += [
        f"element vertex {len(vertices)}",
        "property double x",
        "property double y",
        "property double z",
        f"element face {len(faces)}",
        "property list uchar int vertex_indices",
        "end_header",
    ]
    header = ("\n".join(lines) + "\n").encode("ascii")
    record = np.dtype([("n", "u1"), ("v", "<i4", (3,))])
    face_data = np.empty(len(faces), dtype=record)
    face_data["n"] = 3
    face_data["v"] = faces
    return header + vertices.tobytes() + face_data.tobytes()
