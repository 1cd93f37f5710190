"""Tractors and rigid trucks as vehicles with hitches (docs/joints.md, "Articulated vehicles").

:func:`tractor` builds a tractor (a cab and a chassis frame, a steered front axle, the driven
axles, a fifth wheel); :func:`rigid_truck` a two-axle rigid truck (a cab, a load body and a
frame, its axles, a rear hitch). Both take a combination class's numbers
(:mod:`crashsim.vehicles.combination_data`), and are :meth:`crashsim.Vehicle.generate`'s
"tractor" and "rigid_truck" presets: this module registers them in
crashsim.vehicles.builders.COMBINATION_PRESETS when imported (crashsim's __init__ imports it).
The trailers they tow: :mod:`crashsim.vehicles.trailer`. Model frame as
:meth:`crashsim.Vehicle.box`: x forward from the body's middle, y left, z up from the road;
lengths in m, masses in kg.
"""

from __future__ import annotations

from typing import Any

import numpy as np
import trimesh

from crashsim.errors import ParameterError
from crashsim.vehicles.builders import COMBINATION_PRESETS
from crashsim.vehicles.mass_properties import _box_inertia, _parallel_axis
from crashsim.vehicles.parts import (
    _axle_wheels,
    _box,
    _load_groups,
    _positive,
    _solid_box_parts,
    _with_yaw_inertia,
)
from crashsim.vehicles.trailer import KINGPIN_HEIGHT
from crashsim.vehicles.vehicle import Vehicle
from crashsim.vehicles.wheels import Tyre, Wheels

__all__ = ["RIGID_PRESETS", "TRACTOR_PRESETS", "rigid_truck", "tractor"]

RIGID_PRESETS = {"rigid_truck": "rigid_truck"}
""":meth:`crashsim.Vehicle.generate`'s rigid-truck presets and the combination class each is."""

TRACTOR_PRESETS = {"tractor": "tractor_6x4", "tractor_6x4": "tractor_6x4"}
""":meth:`crashsim.Vehicle.generate`'s tractor presets and the combination class each is."""


# Not sourced (combination_classes.toml has no overhang): a cab-over tractor's front axle this
# far behind its bumper (m), an assumption of the tractor builder.
FRONT_OVERHANG = 1.4


def _from_class(preset: str, fields: dict[str, str]) -> dict[str, Any]:
    """The builder's keywords a combination class gives (keyword -> the class's quantity)."""
    from crashsim.vehicles.combination_data import combination_class

    cls = combination_class(preset)
    return {k: cls[q].value for k, q in fields.items() if q in cls}


# The tractor builder's keywords a combination class gives: keyword -> the class's quantity.
TRACTOR_FIELDS = {
    "mass": "mass",
    "wheelbase": "wheelbase",
    "tandem_spread": "tandem_spread",
    "fifth_wheel_ahead": "fifth_wheel_offset",
    "fifth_wheel_height": "fifth_wheel_height",
    "cg_to_front_axle": "cg_to_front_axle",
    "cg_height": "cg_height",
    "length": "length",
    "width": "width",
    "cab_height": "height",
    "track": "track_front",
    "radius_front": "tyre_radius_front",
    "radius_rear": "tyre_radius_rear",
    "yaw_inertia": "yaw_inertia",
}


def tractor(
    preset: str | None = None,
    *,
    mass: float | None = None,
    wheelbase: float | None = None,
    tandem_spread: float | None = None,
    fifth_wheel_ahead: float | None = None,
    fifth_wheel_height: float | None = None,
    cg_to_front_axle: float | None = None,
    cg_height: float | None = None,
    track: float | None = None,
    radius: float | tuple[float, float] | None = None,
    length: float | None = None,
    width: float = 2.5,
    cab_height: float = 3.0,
    front_overhang: float = FRONT_OVERHANG,
    driven_axles: int = 2,
    tyre: Tyre | dict[str, Any] | None = None,
    natural_frequency: float | None = None,
    damping_ratio: float | None = None,
    steering_ratio: float | None = None,
    steering_reference: str | None = None,
    abs: bool = True,
    inertia: Any = None,
    load_sharing: bool = True,
    name: str | None = None,
) -> Vehicle:
    """A tractor (m, kg): a cab (``front_overhang`` + 1.0 m long from the front bumper,
    ``cab_height`` tall) and a chassis frame back to ``length``; a steered front axle
    ``front_overhang`` behind the bumper; ``driven_axles`` (1: 4x2, 2: 6x4 tandem) behind it,
    ``wheelbase`` from the front axle to the rear axles' centre, ``tandem_spread`` apart;
    the fifth wheel's kingpin lock ``fifth_wheel_ahead`` of the rear axles' centre at
    ``fifth_wheel_height``; the CG ``cg_to_front_axle`` behind the front axle at ``cg_height``;
    tyre ``radius`` (one, or front and rear); ``inertia`` (3, 3) kg m^2 about the CG (default
    the cab and frame as uniform boxes sharing the mass by volume, about the CG); a 6x4's
    tandem shares its load (``load_sharing``, as :meth:`Trailer.box`).

    ``preset="tractor_6x4"``: every number the combination class gives
    (docs/vehicle-data.md: mass, length, width, height as the cab's, wheelbase, tandem spread,
    fifth-wheel lead and height, CG, yaw inertia, tracks, tyre radii); keywords given replace
    them; the front overhang (not sourced) is FRONT_OVERHANG."""
    given: dict[str, Any] = {
        "mass": mass,
        "wheelbase": wheelbase,
        "tandem_spread": tandem_spread,
        "fifth_wheel_ahead": fifth_wheel_ahead,
        "fifth_wheel_height": fifth_wheel_height,
        "cg_to_front_axle": cg_to_front_axle,
        "cg_height": cg_height,
        "track": track,
        "radius": radius,
        "length": length,
    }
    given, width, cab_height, yaw_inertia = _tractor_numbers(
        preset, given, width, cab_height, inertia
    )
    m = _positive(given["mass"], "mass")
    wb = _positive(given["wheelbase"], "wheelbase")
    ln = _positive(given["length"], "length")
    overhang = _positive(front_overhang, "front_overhang")
    if driven_axles not in (1, 2):
        raise ParameterError(f"driven_axles = {driven_axles!r}: a tractor has 1 (4x2) or 2 (6x4)")
    front = ln / 2.0
    x_front_axle = front - overhang
    x_rear = x_front_axle - wb
    spread = _positive(given["tandem_spread"], "tandem_spread") if driven_axles == 2 else 0.0
    rear_axles = [x_rear + spread / 2.0, x_rear - spread / 2.0] if driven_axles == 2 else [x_rear]
    radius = given["radius"]
    r_front, r_rear = radius if isinstance(radius, tuple | list) else (radius, radius)
    r_front, r_rear = _positive(r_front, "radius"), _positive(r_rear, "radius")
    cab, frame = _tractor_parts(front, overhang, width, cab_height, given["fifth_wheel_height"])
    mesh = trimesh.util.concatenate([cab, frame])
    cg = np.array(
        [
            x_front_axle - _positive(given["cg_to_front_axle"], "cg_to_front_axle"),
            0.0,
            _positive(given["cg_height"], "cg_height"),
        ]
    )
    if inertia is None:
        inertia = _boxes_by_volume_inertia(m, [cab, frame], cg)
        if yaw_inertia is not None:
            _with_yaw_inertia(inertia, float(yaw_inertia))
    sources = {"cg": "user", "inertia": "uniform boxes"}
    vehicle = Vehicle(mesh, m, cg, inertia, name=name or preset or "tractor", sources=sources)
    running = {"natural_frequency": natural_frequency, "damping_ratio": damping_ratio,
               "tyre": tyre, "steering_ratio": steering_ratio,
               "steering_reference": steering_reference, "abs": abs}  # fmt: skip
    wheels = _tractor_wheels([x_front_axle, *rear_axles], given["track"], r_front, r_rear, cg,
                             driven_axles, load_sharing, running)  # fmt: skip
    vehicle = vehicle.with_wheels(wheels)
    kingpin = np.array(
        [x_rear + float(given["fifth_wheel_ahead"]), 0.0, float(given["fifth_wheel_height"])]
    )
    return vehicle.with_hitch(kingpin, "fifth_wheel")


def _check_given(builder: str, given: dict[str, Any]) -> None:
    """ParameterError naming the numbers neither given nor from the preset (None)."""
    missing = [k for k, v in given.items() if v is None]
    if missing:
        raise ParameterError(
            f"{builder}: give {', '.join(missing)} (m, kg), or a preset "
            "(crashsim.vehicles.combination_data)"
        )


def _tractor_wheels(
    axles_x: list[float],
    track: Any,
    r_front: float,
    r_rear: float,
    cg: np.ndarray,
    driven_axles: int,
    load_sharing: bool,
    running: dict[str, Any],
) -> Wheels:
    """The tractor's wheels: a steered front axle and the driven ones at ``axles_x`` (model
    frame x, m), each axle's centre at its own tyre's radius; a tandem shares its load when
    ``load_sharing``. ``running``: Wheels.custom's springs, tyre, steering and ABS."""
    names = ["steer", *(["drive"] if driven_axles == 1 else ["drive1", "drive2"])]
    centers, flags, wheel_names = _axle_wheels(
        axles_x, _positive(track, "track"), r_front, cg, [True] + [False] * driven_axles, names
    )
    radii = np.array([r_front] * 2 + [r_rear] * (2 * driven_axles))
    centers[2:, 2] += r_rear - r_front  # each axle's centre at its own tyre's radius
    return Wheels.custom(
        centers, radii, flags, names=wheel_names, **running,
        load_groups=_load_groups(axles_x[1:], names[1:]) if load_sharing else (),
    )  # fmt: skip


def _tractor_numbers(
    preset: str | None, given: dict[str, Any], width: float, cab_height: float, inertia: Any
) -> tuple[dict[str, Any], float, float, Any]:
    """The tractor's numbers: those ``given`` (None: not given), the rest from the preset's
    combination class; its width, cab height and yaw inertia (kg m^2, None unless the class
    gives it and no ``inertia`` is given). ParameterError naming what is still missing."""
    yaw_inertia = None
    if preset is not None:
        data = _from_class(preset, TRACTOR_FIELDS)
        if "radius_front" in data:
            data["radius"] = (data["radius_front"], data.get("radius_rear", data["radius_front"]))
        given = {k: data.get(k) if v is None else v for k, v in given.items()}
        width = data.get("width", width)
        cab_height = data.get("cab_height", cab_height)
        yaw_inertia = data.get("yaw_inertia") if inertia is None else None
    _check_given("tractor", given)
    return given, width, cab_height, yaw_inertia


def _tractor_parts(
    front: float, overhang: float, width: float, cab_height: float, fifth_wheel_height: float
) -> tuple[trimesh.Trimesh, trimesh.Trimesh]:
    """The tractor's cab (``overhang`` + 1.0 m long from the bumper at x = ``front``) and its
    chassis frame back to -``front``, its top 0.05 m under the fifth wheel (model frame, m)."""
    cab_len = overhang + 1.0
    cab = _box(
        (front - cab_len, -width / 2, 0.45), (front, width / 2, _positive(cab_height, "cab_height"))
    )
    frame_top = _positive(fifth_wheel_height, "fifth_wheel_height") - 0.05
    frame = _box((-front, -0.55, 0.45), (front - cab_len + 0.05, 0.55, frame_top))
    return cab, frame


def _boxes_by_volume_inertia(m: float, boxes: list[trimesh.Trimesh], cg: np.ndarray) -> Any:
    """The inertia (kg m^2) about ``cg`` of ``boxes`` as uniform solids sharing the mass ``m``
    (kg) by volume."""
    parts = [(box, box.volume) for box in boxes]
    total = sum(v for _, v in parts)
    inertia = np.zeros((3, 3))
    for part, v in parts:
        lo, hi = part.bounds
        mp = m * v / total
        inertia += _parallel_axis(_box_inertia(mp, *(hi - lo)), mp, cg - (lo + hi) / 2.0)
    return inertia


# The rigid-truck builder's keywords a combination class gives: keyword -> the class's quantity.
RIGID_FIELDS = {
    "mass": "mass_max",
    "wheelbase": "wheelbase",
    "cg_to_front_axle": "cg_to_front_axle_laden",
    "length": "length",
    "width": "width",
    "height": "height",
    "front_overhang": "front_overhang",
    "track": "track_front",
    "radius": "tyre_radius_front",
}
# Not sourced: a rigid truck's cab height (m, as the tractor builder's default) and its load
# body's floor (m, KINGPIN_HEIGHT, as the box van's); drawing rules of the rigid-truck builder.
RIGID_CAB_HEIGHT = 3.0


def rigid_truck(
    preset: str | None = None,
    *,
    mass: float | None = None,
    wheelbase: float | None = None,
    cg_to_front_axle: float | None = None,
    cg_height: float | None = None,
    track: float | None = None,
    radius: float | None = None,
    length: float | None = None,
    width: float | None = None,
    height: float | None = None,
    front_overhang: float | None = None,
    cab_height: float = RIGID_CAB_HEIGHT,
    floor_height: float = KINGPIN_HEIGHT,
    hitch_height: float | None = None,
    tyre: Tyre | dict[str, Any] | None = None,
    natural_frequency: float | None = None,
    damping_ratio: float | None = None,
    steering_ratio: float | None = None,
    steering_reference: str | None = None,
    abs: bool = True,
    name: str | None = None,
) -> Vehicle:
    """A two-axle rigid truck (m, kg): a cab (``front_overhang`` + 1.0 m long, ``cab_height``
    tall), a load body from 0.1 m behind it to the rear end (``length`` in all), its floor at
    ``floor_height`` and its top at ``height``, and a chassis frame under it from 0.45 m up;
    a steered front axle ``front_overhang`` behind the bumper, the driven rear axle
    ``wheelbase`` behind it (one wheel a side at the twin tyres' centres, ``track`` apart);
    the CG ``cg_to_front_axle`` behind the front axle at ``cg_height`` (default: the cab, body
    and frame as uniform solids sharing the mass by volume, as their inertia about the CG is);
    a rear hitch (a ball joint's, for a drawbar or centre-axle trailer) at the frame's rear end,
    ``hitch_height`` above the road (default the frame's mid-height).

    ``preset="rigid_truck"``: every number the combination class gives (docs/vehicle-data.md):
    the truck laden to its maximum mass (18 t) with the CG where an 18 t rigid's axle loads put
    it, the class's dimensions, tracks and the front tyre's radius (the rear's as the front's:
    not found); keywords given replace them. The kerb mass was not found: an empty truck needs
    ``mass`` (the CG then kept where the laden truck's is)."""
    given: dict[str, Any] = {
        "mass": mass,
        "wheelbase": wheelbase,
        "cg_to_front_axle": cg_to_front_axle,
        "track": track,
        "radius": radius,
        "length": length,
        "width": width,
        "height": height,
        "front_overhang": front_overhang,
    }
    if preset is not None:
        data = _from_class(preset, RIGID_FIELDS)
        given = {k: data.get(k) if v is None else v for k, v in given.items()}
    _check_given("rigid_truck", given)
    m = _positive(given["mass"], "mass")
    wb = _positive(given["wheelbase"], "wheelbase")
    ln = _positive(given["length"], "length")
    wd = _positive(given["width"], "width")
    top = _positive(given["height"], "height")
    overhang = _positive(given["front_overhang"], "front_overhang")
    floor = _positive(floor_height, "floor_height")
    r = _positive(given["radius"], "radius")
    front = ln / 2.0
    x_front_axle = front - overhang
    x_rear_axle = x_front_axle - wb
    _check_rigid_layout(front, x_front_axle, x_rear_axle, overhang, wb, ln, floor, top)
    parts = _rigid_parts(front, overhang, wd, floor, top, cab_height)
    volume = sum(p.volume for p in parts)
    uniform_cg, inertia = _solid_box_parts([(p, m * p.volume / volume) for p in parts])
    cg = np.array(
        [
            x_front_axle - _positive(given["cg_to_front_axle"], "cg_to_front_axle"),
            0.0,
            uniform_cg[2] if cg_height is None else _positive(cg_height, "cg_height"),
        ]
    )
    inertia = _parallel_axis(inertia, m, cg - uniform_cg)  # the same boxes, about the CG
    sources = {
        "cg": "user" if preset is None else f"class {preset}",
        "inertia": "uniform boxes",
    }
    vehicle = Vehicle(
        trimesh.util.concatenate(parts), m, cg, inertia, name=name or preset or "rigid_truck",
        sources=sources,
    )  # fmt: skip
    centers, flags, wheel_names = _axle_wheels(
        [x_front_axle, x_rear_axle], _positive(given["track"], "track"), r, cg,
        [True, False], ["steer", "drive"],
    )  # fmt: skip
    wheels = Wheels.custom(
        centers, r, flags, names=wheel_names, natural_frequency=natural_frequency,
        damping_ratio=damping_ratio, tyre=tyre, steering_ratio=steering_ratio,
        steering_reference=steering_reference, abs=abs,
    )  # fmt: skip
    vehicle = vehicle.with_wheels(wheels)
    hz = (0.45 + floor) / 2.0 if hitch_height is None else _positive(hitch_height, "hitch_height")
    return vehicle.with_hitch(np.array([-front + 0.05, 0.0, hz]), "ball")


def _check_rigid_layout(
    front: float,
    x_front_axle: float,
    x_rear_axle: float,
    overhang: float,
    wb: float,
    ln: float,
    floor: float,
    top: float,
) -> None:
    """ParameterError when the rigid truck's axles reach past its length or its load body's
    floor is not between the frame (0.45 m) and the body's top (m)."""
    if not -front < x_rear_axle < x_front_axle:
        raise ParameterError(
            f"rigid_truck: front_overhang {overhang} m + wheelbase {wb} m reach past its length "
            f"{ln} m"
        )
    if not 0.45 < floor < top:
        raise ParameterError(
            f"rigid_truck: floor_height = {floor} m must lie between the frame's 0.45 m and "
            f"the body's top {top} m"
        )


def _rigid_parts(
    front: float, overhang: float, wd: float, floor: float, top: float, cab_height: float
) -> list[trimesh.Trimesh]:
    """The rigid truck's cab, load body and chassis frame as boxes (model frame, m)."""
    cab_len = overhang + 1.0
    cab_top = _positive(cab_height, "cab_height")
    cab = _box((front - cab_len, -wd / 2, 0.45), (front, wd / 2, cab_top))
    body = _box((-front, -wd / 2, floor), (front - cab_len - 0.1, wd / 2, top))
    frame = _box((-front, -0.55, 0.45), (front - cab_len + 0.05, 0.55, floor))
    return [cab, body, frame]


def _generated(preset: str) -> Any:
    """Vehicle.generate(preset) for a tractor or rigid-truck preset: the class's vehicle,
    built by the function named as the builder (the error messages name it)."""
    if preset in RIGID_PRESETS:

        def rigid_truck_(*, mass: float | None, length: float | None, name: str | None) -> Vehicle:
            return rigid_truck(RIGID_PRESETS[preset], mass=mass, length=length, name=name)

        rigid_truck_.__name__ = "rigid_truck"
        return rigid_truck_

    def tractor_(*, mass: float | None, length: float | None, name: str | None) -> Vehicle:
        return tractor(TRACTOR_PRESETS[preset], mass=mass, length=length, name=name or "tractor")

    tractor_.__name__ = "tractor"
    return tractor_


COMBINATION_PRESETS.update(
    {preset: _generated(preset) for preset in (*TRACTOR_PRESETS, *RIGID_PRESETS)}
)
