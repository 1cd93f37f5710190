"""BodyParams, the validated numbers of a generated body, and the checks that refuse a
combination that gives no valid body (_check, with messages naming the parameter and the fix).

The checks read the body's side view, plan view and stations along it, so they live here too:
the side-view profile (hood, windshield, roof, rear window, deck; the underside with the wheel
arches), the plan-view rounding of the corners, and the stations d (m from the front face) at
which the sections are taken. Model frame (m): x forward, y left, z up, ground z = 0.
"""

from __future__ import annotations

import dataclasses
import math
from collections.abc import Mapping
from dataclasses import dataclass
from typing import Any

import numpy as np
from numpy.typing import NDArray

from crashsim.errors import ParameterError
from crashsim.vehicles.generator.elementary import _cos_sin, _filleted, _interp
from crashsim.vehicles.generator.presets import PRESETS, _fail

Array = NDArray[np.float64]

# Fixed details of the cross-section (m).
_SILL_RADIUS = 0.04  # rounding of the lower outer edge of each section (sill, arch lip)
_STEP = 0.008  # inward bevel of a wheel arch's inner wall between underside and arch
_SHOULDER_MIN = 0.05  # least height of the rounded top above the side wall (hood, deck sides)
_MARGIN = 0.01  # least clearance between stacked features of a section (m)
_ARCH_RAMP_DEG = 10.0  # the arch's near-vertical lower edges span this much of its circle
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


def _check(p: BodyParams) -> None:
    """ParameterError for combinations that give no valid body (all sizes are > 0 here)."""
    _check_axles(p)
    _check_heights(p)
    _check_positions(p)
    _check_widths(p)
    _check_section_room(p)


def _check_axles(p: BodyParams) -> None:
    """The wheelbase, the overhangs and the wheel arches along the body (m)."""
    L = p.length
    if p.wheelbase >= L:
        _fail(
            f"wheelbase = {p.wheelbase} m is not shorter than length = {L} m: give a shorter "
            "wheelbase"
        )
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


def _check_heights(p: BodyParams) -> None:
    """The heights (m above the ground): clearance, bumper, beltline, nose, hood, deck, tail."""
    H = p.height
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


def _check_positions(p: BodyParams) -> None:
    """The profile's positions along the body (m from the front), in order and inside it."""
    L = p.length
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


def _check_widths(p: BodyParams) -> None:
    """The widths and roundings (m): bumper and edge radii, arch depth, tumblehome, and the
    end faces' height for the edge radius."""
    half = p.width / 2.0
    ra = p.arch_radius
    fo, ro = p.front_overhang, p.rear_overhang
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


def _check_section_room(p: BodyParams) -> None:
    """Every section: the wheel arches and sill must fit under the hood, beltline and deck."""
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


# -- the side view, the plan view and the stations along x ------------------------------------


class _Values:
    """Attribute access to a dict of parameters (for the profile functions)."""

    def __init__(self, values: Mapping[str, float]) -> None:
        self.__dict__.update(values)


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
