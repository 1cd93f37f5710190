"""Trailers as vehicles with couplings (docs/joints.md, "Articulated vehicles").

:class:`Trailer` builds a trailer's body (a box, with its drawbar for a centre-axle trailer),
its axles (each a left and a right wheel, unsteered; a tandem or tridem is two or three
axles, each on its own springs) and its coupling: a semitrailer's kingpin or a drawbar's
coupler, which carries its share of the weight at rest (:meth:`Wheels.custom`'s
``coupling``). Tractors and rigid trucks, which tow them: :mod:`crashsim.vehicles.trucks`; the
parts both draw: :mod:`crashsim.vehicles.parts`. Model frame as :meth:`crashsim.Vehicle.box`:
x forward from the body's middle, y left, z up from the road; lengths in m, masses in kg.
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import Any

import numpy as np
import trimesh
from numpy.typing import ArrayLike

from crashsim.errors import ParameterError
from crashsim.vehicles.coupling import Hitch
from crashsim.vehicles.mass_properties import _box_inertia, _parallel_axis
from crashsim.vehicles.parts import (
    _axle_wheels,
    _box,
    _load_groups,
    _positive,
    _solid_box_parts,
    _with_yaw_inertia,
)
from crashsim.vehicles.vehicle import Vehicle
from crashsim.vehicles.wheels import Tyre, Wheels

__all__ = ["TRAILER_KINDS", "TRAILER_PRESETS", "Trailer"]

TRAILER_KINDS = ("semitrailer", "centre_axle", "drawbar_body")
"""A semitrailer rests on a kingpin over a fifth wheel; a centre-axle trailer (a caravan, a
cargo trailer, a dolly) on a drawbar's coupler over a tow ball; a drawbar trailer's body on a
ring over its dolly's turntable (:meth:`Trailer.drawbar`)."""

TRAILER_PRESETS = ("box_van", "flatbed", "tanker", "caravan")
"""The combination classes :meth:`Trailer.generate` builds (the others lack a body's
dimensions)."""

# The drawbar of a centre-axle trailer drawn into its mesh: a bar this wide and high (m).
DRAWBAR_SECTION = 0.12


# Not sourced (combination_classes.toml has none): a caravan's drawbar from the body's front
# to the coupler (m), its tyre radius (m, a 185/70 R13's) and track (m, its width less 0.35):
# assumptions of the caravan preset.
CARAVAN_DRAWBAR = 1.2
CARAVAN_TYRE_RADIUS = 0.29
CARAVAN_TRACK_INSET = 0.35
# A caravan's body stands this far above the road (m; not sourced): its floor over the axle.
CARAVAN_CLEARANCE = 0.35
# A semitrailer's kingpin lock (and a box van's floor) at the tractor_6x4 class's fifth-wheel
# height (m, the midpoint of axleload_eu's 100-120 cm).
KINGPIN_HEIGHT = 1.1
# Not sourced (combination_classes.toml has none): the height of a laden flatbed's load, a
# box the deck's length and width centred on the deck (m), an assumption of the flatbed preset.
FLATBED_LOAD_HEIGHT = 1.0
# The tanker class has no axle group: its preset takes the tandem spread of tractor_6x4 (the
# register's 1.37 m) and puts the tandem's centre as far ahead of its rear end as the flatbed
# class's spread axles (2.743 m); its barrel (a solid cylinder the class's width across, the
# class's length long) rests at KINGPIN_HEIGHT. Assumptions of the tanker preset.


# The keywords the flatbed and tanker presets take besides their class's numbers.
_SEMI_OVERRIDES = (
    "mass", "length", "track", "radius", "tyre", "natural_frequency", "damping_ratio", "abs",
    "load_sharing", "load_height",
)


class Trailer:
    """Trailers (a namespace of builders; each returns a :class:`crashsim.Vehicle` with
    wheels and a ``coupler``)."""

    @staticmethod
    def generate(
        preset: str,
        *,
        laden: bool = True,
        coupler_height: float | None = None,
        name: str | None = None,
        **overrides: Any,
    ) -> Vehicle:
        """A trailer from a combination class (docs/vehicle-data.md), as :meth:`box` builds
        it; keywords of :meth:`box` replace the class's numbers.

        - "box_van": a tridem semitrailer, laden (``laden=True``: the class's laden mass,
          CG height and yaw inertia) or empty (its empty mass; the CG at the box's middle,
          its height and the inertia the uniform box's: not sourced); the kingpin at its
          setback, the tridem's centre the kingpin-to-axle-group distance behind it, the
          axles the group's spread apart; the box from ``coupler_height`` (default 1.1 m,
          the class's fifth-wheel height: the kingpin at the floor) to the class's height.
        - "flatbed": a 53 ft spread-axle flatbed, a deck from ``coupler_height`` (default
          KINGPIN_HEIGHT) to the class's deck height, the kingpin at its setting, the two
          axles the class's spread apart about the group's centre; ``laden`` adds the class's
          payload as a box the deck's length and width, ``load_height`` (FLATBED_LOAD_HEIGHT,
          not sourced) tall, centred on the deck; deck and load uniform solids.
        - "tanker": a petroleum tank semitrailer, a barrel (a solid cylinder the class's width
          across, its length long) from ``coupler_height`` up on a subframe over a tandem
          (spread and place not sourced: see the module's constants), laden to the class's
          mass (the CG at the barrel's axis); the empty mass was not found: ``laden=False``
          needs ``mass``.
        - "caravan": a single-axle caravan, ``laden`` its maximum mass else its mass in
          running order, the CG at the body's middle; the axle placed so the coupler carries
          the class's nose-load share (6 %); the drawbar (1.2 m), tyres and track are
          assumptions (CARAVAN_*), the coupler at the class's coupling height.
        """
        from crashsim.vehicles.combination_data import combination_class

        cls = combination_class(preset)
        value = {q: cls[q].value for q in cls.quantities}
        if preset in ("flatbed", "tanker"):
            unknown = sorted(set(overrides) - set(_SEMI_OVERRIDES))
            if unknown:
                raise ParameterError(
                    f"Trailer.generate({preset!r}) takes {', '.join(_SEMI_OVERRIDES)}; "
                    f"got {', '.join(unknown)}"
                )
            hz = coupler_height if coupler_height is not None else KINGPIN_HEIGHT
            build = Trailer._flatbed if preset == "flatbed" else Trailer._tanker
            return build(value, laden, _positive(hz, "coupler_height"), name or preset, overrides)
        if preset == "box_van":
            hz = coupler_height if coupler_height is not None else KINGPIN_HEIGHT
            group = value["kingpin_setback"] + value["kingpin_to_axle_group"]
            spread = value["axle_group_spread"] / 2.0
            args: dict[str, Any] = dict(
                length=value["length"],
                width=value["width"],
                height=value["height"] - hz,
                mass=value["mass_laden"] if laden else value["mass"],
                ground_clearance=hz,
                coupler=value["kingpin_setback"],
                coupler_height=hz,
                axles=[group - spread, group, group + spread],
                track=value["track"],
                radius=value["tyre_radius"],
            )
            if laden:
                args["cg_height"] = value["cg_height_laden"]
                args["yaw_inertia"] = value["yaw_inertia_laden"]
            kind = "semitrailer"
        elif preset == "caravan":
            length = value["length"]
            share = value["nose_load_share"]
            # The axle behind the CG (the body's middle) so that the coupler, DRAWBAR ahead of
            # the body, carries `share` of the weight: x_axle = -share x_coupler / (1 - share).
            coupler_x = length / 2.0 + CARAVAN_DRAWBAR
            axle_x = -share * coupler_x / (1.0 - share)
            args = dict(
                length=length,
                width=value["width"],
                height=value["height"] - CARAVAN_CLEARANCE,
                mass=value["mass_max"] if laden else value["mass"],
                ground_clearance=CARAVAN_CLEARANCE,
                coupler=CARAVAN_DRAWBAR,
                coupler_height=coupler_height or value["coupling_height"],
                axles=[length / 2.0 - axle_x],
                track=value["width"] - CARAVAN_TRACK_INSET,
                radius=CARAVAN_TYRE_RADIUS,
            )
            kind = "centre_axle"
        else:
            raise ParameterError(
                f"trailer preset {preset!r} has no builder: the presets are "
                f"{', '.join(repr(p) for p in TRAILER_PRESETS)} (the other combination "
                "classes lack the dimensions a body needs; build them with Trailer.box)"
            )
        args.update(overrides)
        return Trailer.box(kind, name=name or preset, **args)

    @staticmethod
    def _semitrailer(
        name: str, parts: list[tuple[trimesh.Trimesh, float]], extra: list[trimesh.Trimesh],
        kingpin: np.ndarray, axles: list[float], track: float, radius: float,
        options: dict[str, Any],
    ) -> Vehicle:
        """A semitrailer of uniform solid parts (mesh, mass) and massless drawn ``extra``."""
        cg, inertia = _solid_box_parts(parts)
        mesh = trimesh.util.concatenate([p for p, _ in parts] + extra)
        mass = sum(m for _, m in parts)
        body = Vehicle(mesh, mass, cg, inertia, name=name,
                       sources={"cg": "uniform solids", "inertia": "uniform solids"})
        return Trailer.from_vehicle(body, "semitrailer", coupler_at=kingpin, axles=axles,
                                    track=track, radius=radius, **options)

    @staticmethod
    def _flatbed(
        value: dict[str, float], laden: bool, hz: float, name: str, given: dict[str, Any]
    ) -> Vehicle:
        """The flatbed preset (see :meth:`generate`); model frame x = 0 mid-deck."""
        length = _positive(given.get("length", value["length"]), "length")
        width, deck = value["width"], value["deck_height"]
        if not hz < deck:
            raise ParameterError(
                f"coupler_height = {hz} m must lie under the flatbed's deck ({deck:.3f} m)"
            )
        front = length / 2.0
        group = front - value["kingpin_setback"] - value["kingpin_to_axle_group"]
        half = value["axle_group_spread"] / 2.0
        empty = value["mass"]
        platform = _box((-front, -width / 2, hz), (front, width / 2, deck))
        parts = [(platform, empty)]
        if laden:
            top = deck + _positive(given.get("load_height", FLATBED_LOAD_HEIGHT), "load_height")
            load = _box((-front, -width / 2, deck), (front, width / 2, top))
            parts.append((load, value["mass_laden"] - empty))
        if "mass" in given:  # the mass given, its parts in the class's proportion
            scale = _positive(given["mass"], "mass") / sum(m for _, m in parts)
            parts = [(p, m * scale) for p, m in parts]
        return Trailer._semitrailer(
            name, parts, [], np.array([front - value["kingpin_setback"], 0.0, hz]),
            [group + half, group - half], given.get("track", value["track"]),
            given.get("radius", value["tyre_radius"]), _wheel_options(given),
        )

    @staticmethod
    def _tanker(
        value: dict[str, float], laden: bool, hz: float, name: str, given: dict[str, Any]
    ) -> Vehicle:
        """The tanker preset (see :meth:`generate`); model frame x = 0 mid-barrel."""
        from crashsim.vehicles.combination_data import combination_class

        if not laden and "mass" not in given:
            raise ParameterError(
                "the tanker class has no empty mass (not found, docs/vehicle-data.md): "
                "give Trailer.generate('tanker', laden=False, mass=...) in kg"
            )
        mass = _positive(given.get("mass", value["mass_laden"]), "mass")
        length = _positive(given.get("length", value["length"]), "length")
        r = value["width"] / 2.0
        barrel = trimesh.creation.cylinder(radius=r, height=length, sections=48)
        barrel.apply_transform(trimesh.transformations.rotation_matrix(np.pi / 2, [0, 1, 0]))
        barrel.apply_translation([0.0, 0.0, hz + r])
        flatbed = combination_class("flatbed")
        to_rear = (
            flatbed["length"].value
            - flatbed["kingpin_setback"].value
            - flatbed["kingpin_to_axle_group"].value
        )
        group = -length / 2.0 + to_rear
        half = combination_class("tractor_6x4")["tandem_spread"].value / 2.0
        # the subframe over the tandem and the kingpin's plate (drawn, massless)
        frame = _box((group - 2 * half - 0.5, -0.55, hz - 0.25), (group + 2 * half + 0.5, 0.55, hz))
        plate = _box((length / 2 - 2.0, -0.55, hz - 0.05), (length / 2 - 0.2, 0.55, hz))
        # a solid cylinder about its axis (x): m r^2 / 2; across: m (3 r^2 + L^2) / 12
        across = mass * (3 * r**2 + length**2) / 12.0
        inertia = np.diag([mass * r**2 / 2.0, across, across])
        mesh = trimesh.util.concatenate([barrel, frame, plate])
        body = Vehicle(mesh, mass, [0.0, 0.0, hz + r], inertia, name=name,
                       sources={"cg": "the barrel's axis", "inertia": "solid cylinder"})
        return Trailer.from_vehicle(
            body, "semitrailer",
            coupler_at=[length / 2.0 - value["kingpin_setback"], 0.0, hz],
            axles=[group + half, group - half],
            track=given.get("track", value["track"]),
            radius=given.get("radius", value["tyre_radius"]),
            **_wheel_options(given),
        )

    @staticmethod
    def from_vehicle(
        vehicle: Vehicle,
        kind: str,
        *,
        coupler_at: ArrayLike,
        axles: Sequence[float],
        track: float,
        radius: float,
        tyre: Tyre | dict[str, Any] | None = None,
        natural_frequency: float | None = None,
        damping_ratio: float | None = None,
        abs: bool = True,
        load_sharing: bool = True,
    ) -> Vehicle:
        """Any vehicle made a trailer (a new Vehicle): its own mesh, mass, CG and inertia
        (:meth:`crashsim.Vehicle.from_mesh`, standing on the model frame's ground z = 0),
        ``kind`` as :meth:`box`'s, its coupling ``coupler_at`` (a model-frame point, m: the
        kingpin's lock, the drawbar's eye or the turntable's ring; within 1 m of the body),
        its ``axles`` (each axle's model-frame x, m), ``track`` and tyre ``radius`` (m), the
        wheels unsteered on the model frame's centre line, their springs, tyre and ABS, and
        tandems and tridems sharing their load (``load_sharing``). The coupling carries its
        share of the weight at rest (:meth:`Wheels.custom`'s ``coupling``)."""
        if kind not in TRAILER_KINDS:
            raise ParameterError(f"trailer kind {kind!r} is unknown: give one of {TRAILER_KINDS}")
        xs = [float(x) for x in axles]
        if not xs or not all(np.isfinite(xs)):
            raise ParameterError(
                f"a trailer needs at least one axle: axles must be model-frame x positions "
                f"(m), got {axles!r}"
            )
        try:
            point = np.asarray(coupler_at, dtype=np.float64).reshape(3)
        except (TypeError, ValueError) as e:
            raise ParameterError(
                f"coupler_at must be a model-frame point (m), got {coupler_at!r}"
            ) from e
        cg = np.asarray(vehicle.cg, dtype=np.float64)
        r = _positive(radius, "radius")
        axle_names = [f"axle{k + 1}" for k in range(len(xs))]
        centers, flags, names = _axle_wheels(
            xs, _positive(track, "track"), r, cg, [False] * len(xs), axle_names
        )
        wheels = Wheels.custom(
            centers,
            r,
            flags,
            names=names,
            natural_frequency=natural_frequency,
            damping_ratio=damping_ratio,
            tyre=tyre,
            abs=abs,
            coupling=point - cg,
            load_groups=_load_groups(xs, axle_names) if load_sharing else (),
        )
        coupler = Hitch.at(
            {"semitrailer": "kingpin", "centre_axle": "coupler", "drawbar_body": "ring"}[kind],
            point - cg,
            towing=False,
        )
        vehicle._check_reach(coupler, "coupler")
        trailer = vehicle.with_wheels(wheels)
        trailer._coupler = coupler
        return trailer

    @staticmethod
    def drawbar(
        *,
        length: float,
        width: float,
        height: float,
        mass: float,
        ground_clearance: float,
        turntable: float,
        rear_axles: Sequence[float],
        drawbar: float,
        eye_height: float,
        track: float,
        radius: float,
        dolly_mass: float,
        cg_height: float | None = None,
        cg_from_front: float | None = None,
        tyre: Tyre | dict[str, Any] | None = None,
        name: str = "trailer",
    ) -> tuple[Vehicle, Vehicle]:
        """A drawbar (full) trailer as two units (m, kg): its dolly (a 0.6 m frame on one
        axle, of ``dolly_mass``, its drawbar's eye ``drawbar`` m ahead of the axle at
        ``eye_height``, a turntable over the axle at the body's floor) and its body (a box as
        :meth:`box`, the turntable's ring ``turntable`` m behind its front, its
        ``rear_axles`` behind the front). ``Scene.add(truck, trailers=[dolly, body])`` puts
        the eye on the truck's ball (a spherical joint) and the body on the turntable (a
        revolute joint about the vertical: the dolly steers the body's front). Returns
        (dolly, body), named ``name + "_dolly"`` and ``name``."""
        body = Trailer.box(
            "drawbar_body",
            length=length,
            width=width,
            height=height,
            mass=mass,
            ground_clearance=ground_clearance,
            coupler=turntable,
            coupler_height=ground_clearance,
            axles=rear_axles,
            track=track,
            radius=radius,
            cg_height=cg_height,
            cg_from_front=cg_from_front,
            tyre=tyre,
            name=name,
        )
        frame = 0.6
        top = _positive(ground_clearance, "ground_clearance")
        dolly = Trailer.box(
            "centre_axle",
            length=frame,
            width=_positive(width, "width") * 0.8,
            height=0.2,
            mass=dolly_mass,
            ground_clearance=top - 0.25,
            coupler=_positive(drawbar, "drawbar") - frame / 2.0,
            coupler_height=eye_height,
            axles=[frame / 2.0],
            track=track,
            radius=radius,
            cg_height=top - 0.15,
            tyre=tyre,
            name=f"{name}_dolly",
        )
        # the turntable over the axle, at the body's floor (model frame: the frame's middle)
        dolly = dolly.with_hitch(dolly.cg + [0.0, 0.0, top - float(dolly.cg[2])], "turntable")
        return dolly, body

    @staticmethod
    def box(
        kind: str,
        *,
        length: float,
        width: float,
        height: float,
        mass: float,
        ground_clearance: float,
        coupler: float,
        coupler_height: float,
        axles: Sequence[float],
        track: float,
        radius: float,
        cg_height: float | None = None,
        cg_from_front: float | None = None,
        tyre: Tyre | dict[str, Any] | None = None,
        natural_frequency: float | None = None,
        damping_ratio: float | None = None,
        abs: bool = True,
        yaw_inertia: float | None = None,
        load_sharing: bool = True,
        name: str = "trailer",
    ) -> Vehicle:
        """A box trailer (m, kg): a body ``length`` x ``width`` x ``height`` from
        ``ground_clearance`` up, of ``mass`` with its CG at ``cg_from_front`` behind the
        body's front (default the middle) and ``cg_height`` above the road (default the box's
        middle), a uniform box's inertia about it.

        ``kind`` "semitrailer": the kingpin ``coupler`` m behind the body's front (its
        setback), at ``coupler_height`` (the fifth wheel's height: the kingpin's lock);
        "drawbar_body": the ring of the dolly's turntable ``coupler`` m behind the front, at
        ``coupler_height``;
        "centre_axle": the drawbar's coupler ``coupler`` m ahead of the body's front (the
        drawbar, drawn into the mesh), at ``coupler_height`` (the tow ball's).
        ``axles``: each axle's distance behind the body's front (m; two or three close
        together make a tandem or tridem); ``track`` and tyre ``radius`` (m); springs
        (``natural_frequency`` Hz, ``damping_ratio``; the engine's defaults otherwise), the
        ``tyre`` and ABS as for :class:`crashsim.Wheels`. ``load_sharing``: axles closer
        than GROUP_SPACING (a tandem, a tridem) share their load through a load-equalising
        suspension (default; False: each axle on its own springs).
        """
        if kind not in TRAILER_KINDS:
            raise ParameterError(f"trailer kind {kind!r} is unknown: give one of {TRAILER_KINDS}")
        dims = [
            _positive(v, k) for k, v in (("length", length), ("width", width), ("height", height))
        ]
        m = _positive(mass, "mass")
        lo_z = float(ground_clearance)
        if not np.isfinite(lo_z) or lo_z <= 0.0:
            raise ParameterError(f"ground_clearance = {ground_clearance!r} must be > 0 m")
        ln, wd, ht = dims
        front = ln / 2.0
        body = _box((-front, -wd / 2, lo_z), (front, wd / 2, lo_z + ht))
        point, mesh = _box_coupler(kind, body, ln, coupler, coupler_height)
        axles_x = [front - _positive(a, f"axles[{k}]") for k, a in enumerate(axles)]
        if not axles_x:
            raise ParameterError(
                "a trailer needs at least one axle (axles=[...], m behind the front)"
            )
        cg = np.array(
            [
                0.0 if cg_from_front is None else front - float(cg_from_front),
                0.0,
                lo_z + ht / 2.0 if cg_height is None else float(cg_height),
            ]
        )
        inertia = _parallel_axis(
            _box_inertia(m, ln, wd, ht), m, cg - np.array([0, 0, lo_z + ht / 2])
        )
        if yaw_inertia is not None:
            _with_yaw_inertia(inertia, _positive(yaw_inertia, "yaw_inertia"))
        vehicle = Vehicle(
            mesh,
            m,
            cg,
            inertia,
            name=name,
            sources={"cg": "user", "inertia": "uniform box"},
        )
        vehicle = Trailer.from_vehicle(
            vehicle,
            kind,
            coupler_at=point,
            axles=axles_x,
            track=track,
            radius=radius,
            tyre=tyre,
            natural_frequency=natural_frequency,
            damping_ratio=damping_ratio,
            abs=abs,
            load_sharing=load_sharing,
        )
        return vehicle


def _box_coupler(
    kind: str, body: trimesh.Trimesh, ln: float, coupler: float, coupler_height: float
) -> tuple[np.ndarray, trimesh.Trimesh]:
    """Trailer.box's coupling point (model frame, m) and mesh: a kingpin or turntable ring
    ``coupler`` m behind the front of the ``ln`` m ``body``, or (centre-axle) a drawbar's
    coupler that far ahead of it, the drawbar drawn into the mesh."""
    front = ln / 2.0
    bar = _positive(coupler, "coupler") if kind == "centre_axle" else float(coupler)
    hz = _positive(coupler_height, "coupler_height")
    if kind in ("semitrailer", "drawbar_body"):
        if not 0.0 <= bar < ln:
            raise ParameterError(
                f"coupler = {coupler} m: a semitrailer's kingpin lies behind the body's "
                f"front and ahead of its rear (0 to {ln} m)"
            )
        return np.array([front - bar, 0.0, hz]), body
    point = np.array([front + bar, 0.0, hz])
    half = DRAWBAR_SECTION / 2.0
    drawbar = _box((front - 0.05, -half, hz - half), (front + bar, half, hz + half))
    return point, trimesh.util.concatenate([body, drawbar])


def _wheel_options(given: dict[str, Any]) -> dict[str, Any]:
    """The wheel keywords of :meth:`Trailer.from_vehicle` among a preset's overrides."""
    keys = ("tyre", "natural_frequency", "damping_ratio", "abs", "load_sharing")
    return {k: given[k] for k in keys if k in given}
