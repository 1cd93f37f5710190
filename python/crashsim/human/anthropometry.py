"""The multibody human's segment data: de Leva's (1996) segment table scaled to a body.

:func:`body_segments` gives 16 rigid segments (head with neck, upper torso, lower torso, pelvis,
and on each side upper arm, forearm, hand, thigh, shank, foot) with masses, lengths, centres of
mass, principal inertias, the joint to the parent with its ranges of motion, and a capsule for
contact, in a standing reference posture. Every number comes from ``data/segments.toml``, which
names its source; ``docs/human.md`` ("Body segment data") lists the sources, the derivations and
what was not found.

Body frame: x forward, y left, z up, origin on the ground midway between the feet. Standing
posture: trunk, head and legs upright, arms hanging at the sides, feet flat pointing forward.

Scaling (de Leva's own): masses are fractions of the body mass; lengths are fractions of the
reference subject's stature times the body's stature; a radius of gyration is a fraction of the
segment's length, so an inertia scales as mass x length^2. The segment lengths of the upright
chain (ankle to vertex) are scaled by one factor per sex, ``chain_factor``, so that the chain
on the ankle height stands exactly the stature tall: de Leva's male lengths on the ankle height
make the chain 2.0 % taller than his subject's stature, the female ones 0.1 % shorter.
"""

from __future__ import annotations

import math
import tomllib
from collections.abc import Mapping
from dataclasses import dataclass
from functools import cache
from importlib import resources
from statistics import NormalDist
from types import MappingProxyType
from typing import Any

from crashsim.errors import ParameterError

__all__ = [
    "SEXES",
    "ContactShape",
    "Joint",
    "Segment",
    "body_segments",
    "chain_factor",
    "stature_at_percentile",
    "whole_body_cg",
]

SEXES = ("male", "female")
HEIGHT_RANGE_M = (0.5, 2.5)  # accepted statures
MASS_RANGE_KG = (10.0, 300.0)  # accepted body masses
_TRUNK_DENSITY = 1000.0  # kg/m^3, assumed for head and trunk contact shapes: none was found

# The upright chain, from the ankle up: segment names in order.
_CHAIN = ("shank", "thigh", "pelvis", "lower_torso", "upper_torso", "head")


@dataclass(frozen=True)
class Joint:
    """The joint of a segment to its parent: where it is in the standing posture (body frame,
    m) and its published ranges of motion (motion name -> largest angle from the standing
    posture, rad). ``rom_not_found`` names the usual motions of the joint with no source."""

    name: str
    position: tuple[float, float, float]
    rom: Mapping[str, float]
    rom_not_found: tuple[str, ...]


@dataclass(frozen=True)
class ContactShape:
    """A capsule: the segment through points ``a`` and ``b`` (segment frame, m) and
    ``radius`` (m)."""

    kind: str
    radius: float
    a: tuple[float, float, float]
    b: tuple[float, float, float]


@dataclass(frozen=True)
class Segment:
    """One rigid segment in the standing posture.

    The segment frame has its origin at the segment's first endpoint in de Leva's table
    (``endpoints[0]``) and its axes parallel to the body frame in the standing posture.
    ``inertia`` holds the principal moments about the centre of mass along those axes
    (kg m^2); ``radii`` the radii of gyration as fractions of the length about the sagittal,
    transverse and longitudinal axes as published; the longitudinal axis runs along the
    segment (z, the foot's x), the sagittal axis is taken as x (the foot's z), the transverse
    one as y.
    """

    name: str
    side: str | None  # "left", "right" or None
    parent: str | None
    endpoints: tuple[str, str]
    mass: float  # kg
    length: float  # m, endpoint to endpoint
    origin: tuple[float, float, float]  # body frame, m
    end: tuple[float, float, float]  # body frame, m
    cg: tuple[float, float, float]  # segment frame, m
    cg_fraction: float  # from the first endpoint, fraction of the length
    radii: tuple[float, float, float]  # sagittal, transverse, longitudinal / length
    inertia: tuple[float, float, float]  # kg m^2 about x, y, z through the centre of mass
    joint: Joint | None  # to the parent; None for the pelvis (the root)
    contact: ContactShape

    @property
    def cg_body(self) -> tuple[float, float, float]:
        """The centre of mass in the body frame (m), standing posture."""
        return _add(self.origin, self.cg)


Point = tuple[float, float, float]


def _add(p: Point, q: Point) -> Point:
    return (p[0] + q[0], p[1] + q[1], p[2] + q[2])


@cache
def _table() -> dict[str, Any]:
    path = resources.files("crashsim.human").joinpath("data", "segments.toml")
    return tomllib.loads(path.read_text(encoding="utf-8"))


def _row(name: str, sex: str) -> tuple[float, ...]:
    return tuple(float(v) for v in _table()["segments"][name][sex])


def _mass_sum(sex: str) -> float:
    """The published mass percentages of the whole body (both sides), summed: 100.00 for men,
    99.99 for women (rounding); the fractions are divided by it so the masses add up."""
    table = _table()["segments"]
    sided = {"upper_arm", "forearm", "hand", "thigh", "shank", "foot"}
    return sum(_row(n, sex)[1] * (2 if n in sided else 1) for n in table)


def chain_factor(sex: str) -> float:
    """The factor on de Leva's segment lengths (as fractions of his subject's stature) that
    makes the upright chain (ankle height, shank, thigh, pelvis, lower and upper torso, head)
    exactly the stature: (1 - ankle height fraction) / (sum of the chain's fractions)."""
    _check_sex(sex)
    t = _table()
    stature = float(t["reference"][sex]["stature"]["value"])
    chain = sum(_row(n, sex)[0] for n in _CHAIN) / stature
    return (1.0 - float(t["ankle_height"]["value"])) / chain


def _check_sex(sex: object) -> str:
    if sex not in SEXES:
        raise ParameterError(f"sex {sex!r} is not known: give 'male' or 'female'")
    return str(sex)


def _check_number(name: str, value: object, lo: float, hi: float, unit: str) -> float:
    if isinstance(value, bool) or not isinstance(value, (int, float)):
        raise ParameterError(f"{name} must be a number in {unit}, not {value!r}")
    v = float(value)
    if not math.isfinite(v) or not lo <= v <= hi:
        raise ParameterError(
            f"{name} = {value!r} {unit} is outside {lo:g}-{hi:g} {unit}: give a finite value "
            f"in that range (in {unit}, not another unit)"
        )
    return v


def stature_at_percentile(sex: str, percentile: float) -> float:
    """The stature (m) of a sex's ``percentile`` (0-100, exclusive) in the ANSUR II survey,
    taken as normally distributed with the survey's mean and standard deviation."""
    _check_sex(sex)
    if isinstance(percentile, bool) or not isinstance(percentile, (int, float)):
        raise ParameterError(f"percentile must be a number between 0 and 100, not {percentile!r}")
    p = float(percentile)
    if not math.isfinite(p) or not 0.0 < p < 100.0:
        raise ParameterError(
            f"percentile = {percentile!r} is outside (0, 100): give e.g. 5, 50 or 95"
        )
    s = _table()["stature_survey"][sex]
    return NormalDist(float(s["mean"]), float(s["sd"])).inv_cdf(p / 100.0) / 1000.0


def _rom(joint: str, sex: str) -> dict[str, float]:
    out = {}
    for motion, value in _table()["rom"].get(joint, {}).items():
        deg = float(value[sex]) if isinstance(value, dict) else float(value)
        out[motion] = math.radians(deg)
    return out


# The usual motions of each joint, to name those with no published range.
_MOTIONS = {
    "neck": ("flexion", "extension", "lateral_flexion", "rotation"),
    "thoracic": ("flexion", "extension", "lateral_flexion", "rotation"),
    "lumbar": ("flexion", "extension", "lateral_flexion", "rotation"),
    "shoulder": ("flexion", "extension", "abduction", "adduction", "internal_rotation",
                 "external_rotation"),
    "elbow": ("flexion", "hyperextension", "pronation", "supination"),
    "wrist": ("flexion", "extension", "ulnar_deviation", "radial_deviation"),
    "hip": ("flexion", "extension", "abduction", "adduction", "internal_rotation",
            "external_rotation"),
    "knee": ("flexion", "hyperextension"),
    "ankle": ("dorsiflexion", "plantarflexion", "inversion", "eversion"),
}


def _joint(name: str, sex: str, position: tuple[float, float, float]) -> Joint:
    rom = _rom(name, sex)
    missing = tuple(m for m in _MOTIONS[name] if m not in rom)
    return Joint(name, position, MappingProxyType(rom), missing)


def body_segments(
    height_m: float | None = None,
    mass_kg: float | None = None,
    sex: str = "male",
    percentile: float | None = None,
) -> list[Segment]:
    """The 16 segments of a body of stature ``height_m`` (m) and mass ``mass_kg`` (kg), in
    the standing posture (module docstring: frame, posture, scaling).

    ``percentile`` (0-100) instead of ``height_m`` takes the stature of that percentile of
    the sex in the ANSUR II survey; the body mass must still be given: no sourced body-mass
    distribution was found. Bad input raises ParameterError saying what to give instead.
    """
    sex = _check_sex(sex)
    h, m = _checked_size(sex, height_m, mass_kg, percentile)
    L, R = _scaled_segments(sex, h, m)
    z = _standing_heights(h, L)
    y_hip = R["thigh"]  # the thighs' capsules side by side, touching at the mid-plane
    y_shoulder = R["upper_torso"] + R["upper_arm"]  # the arm's capsule against the torso's

    segments: list[Segment] = []

    def add(name: str, side: str | None, parent: str | None, origin: tuple[float, float, float],
            direction: tuple[float, float, float], joint: Joint | None) -> None:
        segments.append(_segment(name, side, parent, origin, direction, joint, L[name], R[name]))

    down, fwd = (0.0, 0.0, -1.0), (1.0, 0.0, 0.0)
    add("pelvis", None, None, (0.0, 0.0, z["OMPH"]), down, None)
    add("lower_torso", None, "pelvis", (0.0, 0.0, z["XYPH"]), down,
        _joint("lumbar", sex, (0.0, 0.0, z["OMPH"])))
    add("upper_torso", None, "lower_torso", (0.0, 0.0, z["CERV"]), down,
        _joint("thoracic", sex, (0.0, 0.0, z["XYPH"])))
    add("head", None, "upper_torso", (0.0, 0.0, z["VERT"]), down,
        _joint("neck", sex, (0.0, 0.0, z["CERV"])))
    for side, s in (("left", 1.0), ("right", -1.0)):
        sjc = (0.0, s * y_shoulder, z["CERV"])
        add("upper_arm", side, "upper_torso", sjc, down, _joint("shoulder", sex, sjc))
        ejc = segments[-1].end
        add("forearm", side, f"upper_arm_{side}", ejc, down, _joint("elbow", sex, ejc))
        wjc = segments[-1].end
        add("hand", side, f"forearm_{side}", wjc, down, _joint("wrist", sex, wjc))
        hjc = (0.0, s * y_hip, z["HJC"])
        add("thigh", side, "pelvis", hjc, down, _joint("hip", sex, hjc))
        kjc = segments[-1].end
        add("shank", side, f"thigh_{side}", kjc, down, _joint("knee", sex, kjc))
        ajc = segments[-1].end
        # the heel below the ankle, the foot's axis one capsule radius above the ground
        heel = (0.0, s * y_hip, R["foot"])
        add("foot", side, f"shank_{side}", heel, fwd, _joint("ankle", sex, ajc))
    return segments


def _checked_size(
    sex: str, height_m: float | None, mass_kg: float | None, percentile: float | None
) -> tuple[float, float]:
    """body_segments' stature (m; from the percentile when given) and mass (kg), checked."""
    if percentile is not None:
        if height_m is not None:
            raise ParameterError(
                "give either height_m or percentile, not both: the percentile sets the stature"
            )
        height_m = stature_at_percentile(sex, percentile)
    if height_m is None:
        raise ParameterError("give height_m (stature in m) or a percentile")
    if mass_kg is None:
        raise ParameterError(
            "give mass_kg (body mass in kg): no sourced body-mass distribution by percentile"
        )
    h = _check_number("height_m", height_m, *HEIGHT_RANGE_M, "m")
    m = _check_number("mass_kg", mass_kg, *MASS_RANGE_KG, "kg")
    return h, m


_SegmentData = tuple[float, float, float, tuple[float, float, float]]
"""A segment scaled to the body: length (m), mass (kg), CG fraction of the length from its
origin, and radii of gyration (sagittal, transverse, longitudinal) as fractions of the
length."""


def _scaled_segments(
    sex: str, h: float, m: float
) -> tuple[dict[str, _SegmentData], dict[str, float]]:
    """Each segment of the table scaled to stature ``h`` (m) and mass ``m`` (kg), and its
    capsule's radius (m): the cylinder of its length, mass and density."""
    t = _table()
    ref_stature = float(t["reference"][sex]["stature"]["value"])  # mm
    k = chain_factor(sex)
    mass_sum = _mass_sum(sex)
    density = {key: 1000.0 * float(v) for key, v in t["density"].items() if key != "source"}

    def data(name: str) -> _SegmentData:
        length_mm, mass_pct, cg_pct, r_sag, r_trans, r_long = _row(name, sex)
        length = k * length_mm / ref_stature * h
        return (length, m * mass_pct / mass_sum, cg_pct / 100.0,
                (r_sag / 100.0, r_trans / 100.0, r_long / 100.0))

    def radius(name: str, mass: float, length: float) -> float:
        # the cylinder of the segment's length, mass and density: m = rho pi r^2 L
        key = t["segments"][name].get("density")
        rho = density[key] if key else _TRUNK_DENSITY
        return math.sqrt(mass / (rho * math.pi * length))

    L = {n: data(n) for n in t["segments"]}
    R = {n: radius(n, L[n][1], L[n][0]) for n in L}
    return L, R


def _standing_heights(h: float, L: dict[str, _SegmentData]) -> dict[str, float]:
    """Heights (m above the ground) of the joint centres and landmarks in the standing
    posture of a body of stature ``h`` (m): the ankle's, then the segments stacked on it."""
    z_ajc = float(_table()["ankle_height"]["value"]) * h
    z = {"AJC": z_ajc}
    z["KJC"] = z["AJC"] + L["shank"][0]
    z["HJC"] = z["MIDH"] = z["KJC"] + L["thigh"][0]
    z["OMPH"] = z["MIDH"] + L["pelvis"][0]
    z["XYPH"] = z["OMPH"] + L["lower_torso"][0]
    z["CERV"] = z["XYPH"] + L["upper_torso"][0]
    z["VERT"] = z["CERV"] + L["head"][0]
    return z


def _segment(
    name: str,
    side: str | None,
    parent: str | None,
    origin: tuple[float, float, float],
    direction: tuple[float, float, float],
    joint: Joint | None,
    data: _SegmentData,
    radius: float,
) -> Segment:
    """One segment from ``origin`` (body frame, m) along the unit ``direction``, scaled by
    ``data``, its contact a capsule of ``radius`` (m)."""
    length, mass, cg_frac, radii = data
    end = _add(origin, tuple(length * d for d in direction))  # type: ignore[arg-type]
    cg = tuple(cg_frac * length * d for d in direction)
    if direction[0] != 0.0:  # the foot: longitudinal along x, sagittal about z
        r = (radii[2], radii[1], radii[0])
    else:
        r = radii
    inertia = tuple(mass * (ri * length) ** 2 for ri in r)
    seg_name = name if side is None else f"{name}_{side}"
    b = tuple(length * d for d in direction)
    return Segment(
        name=seg_name, side=side,
        parent=parent,
        endpoints=tuple(_table()["segments"][name]["endpoints"]),  # type: ignore[arg-type]
        mass=mass, length=length, origin=origin, end=end,
        cg=cg,  # type: ignore[arg-type]
        cg_fraction=cg_frac, radii=radii,
        inertia=inertia,  # type: ignore[arg-type]
        joint=joint,
        contact=ContactShape("capsule", radius, (0.0, 0.0, 0.0), b),  # type: ignore[arg-type]
    )


def whole_body_cg(segments: list[Segment]) -> tuple[float, float, float]:
    """The body's centre of mass (body frame, m) in the posture of ``segments``."""
    total = sum(s.mass for s in segments)
    return tuple(  # type: ignore[return-value]
        sum(s.mass * s.cg_body[i] for s in segments) / total for i in range(3)
    )
