"""Reports a reconstructionist can use: per impulse exchange the impact report (delta-V, PDOF,
clock direction, yaw-rate change, energy and its split, EES) and the deformation report
(bounding-box and mesh deformation, overlap depth, spring-model maximum and residual crush),
as a text table and as versioned JSON (schema ``crashsim-report`` version 1,
``crashsim/analysis/schema/report-1.schema.json``; every field, unit, frame and sign:
docs/report.md).

    report = crashsim.report(result)    # = crashsim.analysis.report.build_report(result)
    print(report)                       # the text table
    report.write_json("case.json")      # the JSON report

Frames and signs. World: right-handed, z up, SI. Vehicle body frame: ISO 8855 (origin at the
CG, x forward, y left, z up), posed at the exchange instant. The normal n (unit, world) points
from vehicle 1 into vehicle 2; the impulse J (N s, world) acts on vehicle 2 and -J on vehicle 1.
Event-data-recorder components: longitudinal +forward (body x), lateral +RIGHT (-body y).
PDOF (SAE J224): the direction FROM which the force acts on the vehicle, in its horizontal
(body x-y) plane, degrees clockwise seen from above from straight ahead: 0 = from ahead,
90 = from the right, 180 = from behind, 270 = from the left, in [0, 360). Clock direction:
the PDOF to the nearest hour, 12 = 0 deg, 3 = 90 deg (half hours round up). Yaw-rate change:
the world z component of the change of angular velocity, deg/s, + counter-clockwise seen from
above.
"""

from __future__ import annotations

import hashlib
import json
import math
from dataclasses import dataclass, fields
from importlib import resources
from os import PathLike
from typing import TYPE_CHECKING, Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

from crashsim import _core
from crashsim.analysis import penetration
from crashsim.analysis.engagements import WHY_SECONDARY, Engagement, engagements
from crashsim.analysis.joints import (
    ArticulationEvent,
    JointReport,
    articulation_events,
    articulation_lines,
    joint_lines,
    joint_reports,
)
from crashsim.analysis.pedestrian import PedestrianReport, pedestrian_lines, pedestrian_reports
from crashsim.analysis.runout import RunOutReport, run_out, run_out_lines
from crashsim.errors import ParameterError, SceneError
from crashsim.units import to_kmh, to_mph

if TYPE_CHECKING:
    from crashsim.result import Impact, Result
    from crashsim.scene import Scene
    from crashsim.vehicles.vehicle import Vehicle

__all__ = [
    "SCHEMA_NAME",
    "SCHEMA_VERSION",
    "DeformationReport",
    "ImpactReport",
    "JointReport",
    "ObstacleImpactReport",
    "Report",
    "RunOutReport",
    "VehicleImpactReport",
    "build_report",
    "clock_direction",
    "pdof",
    "report_schema",
]

Array = NDArray[np.float64]

SCHEMA_NAME = "crashsim-report"
SCHEMA_VERSION = 1
_SCHEMA_FILE = ("schema", "report-1.schema.json")

# Words used in the report (and in the schema's enums).
FULL, SLIDING = "full", "sliding"
BY_STIFFNESS = "stiffness"
UNKNOWN = "unknown"
# An obstacle's struck face as the side of its own frame it is on: the engine names faces
# with a vehicle's words (front +x, rear -x, left +y, right -y), which mean nothing on a pole.
FACE_SIDES = {"front": "+x", "rear": "-x", "left": "+y", "right": "-y", UNKNOWN: UNKNOWN}
EQUAL_SHARES = "equal (stiffness unknown)"
RIGID_OBSTACLE = "rigid obstacle"

UNITS = {
    "length": "m",
    "time": "s",
    "mass": "kg",
    "velocity": "m/s",
    "angular_velocity": "rad/s",
    "yaw_rate_change": "deg/s",
    "angle": "deg",
    "impulse": "N s",
    "energy": "J",
    "inertia": "kg m^2",
    "spring_rate": "N/m",
    "stiffness_A": "N/m",
    "stiffness_B": "N/m^2",
    "orientation": "unit quaternion (w, x, y, z), body -> world",
}

CONVENTIONS = {
    "world_frame": "right-handed, z up, ground at z = 0",
    "body_frame": (
        "ISO 8855: origin at the vehicle's CG, x forward, y left, z up; posed at the exchange"
    ),
    "model_frame": "the vehicle's mesh frame (x forward, y left, z up); body = model - cg",
    "normal": "unit, world, from vehicle 1 into vehicle 2",
    "impulse": "world, N s; acts on vehicle 2, its negative on vehicle 1",
    "delta_v_edr": "longitudinal +forward (body x), lateral +right (-body y), vertical +up",
    "pdof": (
        "SAE: direction FROM which the force acts on the vehicle, in its body x-y plane, "
        "degrees clockwise seen from above from straight ahead (0 ahead, 90 right, 180 "
        "behind, 270 left), in [0, 360)"
    ),
    "clock": "PDOF to the nearest hour: 12 = 0 deg, 3 = 90, 6 = 180, 9 = 270 (x.5 rounds up)",
    "yaw_rate_change": "world z component of the angular velocity change, + counter-clockwise "
    "seen from above",
    "deformation": (
        "vehicle 1 measured along +n, vehicle 2 along -n, from the impulse centroid to the "
        "undeformed (body-frame) bounding box or mesh surface"
    ),
    "engagements": (
        "a pair's contact from its first overlap to its separation: its exchanges grouped "
        "(the primary, then the secondary ones) with their delta-V summed (world); " + WHY_SECONDARY
    ),
}


# -- small conversions ----------------------------------------------------------------------


def _vec(a: ArrayLike) -> list[float]:
    return [float(x) for x in np.asarray(a, dtype=np.float64).reshape(-1)]


def _mat(a: ArrayLike) -> list[list[float]]:
    return [[float(x) for x in row] for row in np.asarray(a, dtype=np.float64)]


def _opt(x: float | None) -> float | None:
    return None if x is None else float(x)


def _plain(value: Any) -> Any:
    """A JSON-ready copy: numpy scalars and arrays become floats / ints / lists, tuples lists,
    a Vehicle its name; anything else unrepresentable raises ParameterError."""
    if value is None or isinstance(value, bool | str):
        return value
    if isinstance(value, int | np.integer):
        return int(value)
    if isinstance(value, float | np.floating):
        return float(value)
    if isinstance(value, np.ndarray):
        return _plain(value.tolist())
    if isinstance(value, dict):
        return {str(k): _plain(v) for k, v in value.items()}
    if isinstance(value, list | tuple):
        return [_plain(v) for v in value]
    name = getattr(value, "name", None)
    if isinstance(name, str):  # a Vehicle (e.g. the body of a fixed centroid)
        return name
    raise ParameterError(f"cannot put a {type(value).__name__} into a JSON report: {value!r}")


# -- PDOF and clock -------------------------------------------------------------------------


def pdof(delta_v_body: ArrayLike) -> float | None:
    """The SAE principal direction of force (deg, in [0, 360)) from a delta-V in the ISO body
    frame (x forward, y left, z up; m/s): the direction FROM which the force acts, in the
    vehicle's x-y plane, clockwise seen from above from straight ahead (0 ahead, 90 right,
    180 behind, 270 left). The force is along delta-V, so it comes from -delta-V:
    PDOF = atan2(dv_y, -dv_x). None when delta-V has no horizontal part (exactly, or below
    1e-12 of |delta-V|)."""
    dv = np.asarray(delta_v_body, dtype=np.float64).reshape(-1)
    if dv.size != 3 or not np.all(np.isfinite(dv)):
        raise ParameterError(f"delta_v_body must be 3 finite numbers (m/s), got {dv.tolist()}")
    horizontal = math.hypot(dv[0], dv[1])
    if horizontal == 0.0 or horizontal <= 1e-12 * float(np.linalg.norm(dv)):
        return None
    angle = math.degrees(math.atan2(dv[1], -dv[0])) % 360.0
    return 0.0 if angle >= 360.0 else angle  # -1e-17 % 360 is 360.0 in floating point


def clock_direction(pdof_deg: float | None) -> int | None:
    """The clock direction (1-12) of a PDOF in degrees: the nearest hour, 30 deg each,
    12 = 0 deg, 3 = 90, 6 = 180, 9 = 270; a PDOF half-way between two hours rounds up
    (15 deg -> 1). None for None."""
    if pdof_deg is None:
        return None
    if not math.isfinite(pdof_deg):
        raise ParameterError(f"PDOF = {pdof_deg} deg is invalid: give a finite angle")
    hour = math.floor((pdof_deg % 360.0) / 30.0 + 0.5) % 12
    return 12 if hour == 0 else hour


# -- the report's parts ---------------------------------------------------------------------


def _freeze_arrays(obj: Any) -> None:
    """Make a report dataclass's arrays read-only copies (float64), as Result's are."""
    for f in fields(obj):
        value = getattr(obj, f.name)
        if isinstance(value, np.ndarray):
            frozen = np.array(value, dtype=np.float64)
            frozen.setflags(write=False)
            object.__setattr__(obj, f.name, frozen)


@dataclass(frozen=True)
class DeformationReport:
    """One vehicle's deformation at one exchange (all m, along ``direction``).

    ``direction``: the world unit vector the vehicle's deformation is measured along (+n for
    vehicle 1, -n for vehicle 2). ``bounding_box``: from the impulse centroid P to the far
    side of the vehicle's undeformed body-frame bounding box posed at the exchange
    (max over the box's corners of direction.c minus direction.P; the seed's "deformation").
    ``mesh``: from P to the farthest crossing of the ray from P along ``direction`` with the
    vehicle's mesh (the outer surface; the seed's implied maximum crush); None when the ray
    crosses nothing (P outside the mesh on that side, or a hole in an open mesh), with a note.
    ``mesh_crossings``: how many times that ray crosses the mesh. ``overlap_depth``: the
    overlap region's extent along n (region_max - region_min along n; the same for both
    vehicles). Spring model (seed eqs. 34-35): ``crush_share`` of the total crush
    v_n dt_p (k_other / (k1 + k2), or 1/2 when ``crush_share_basis`` says the stiffness is
    unknown); ``max_crush`` = share x v_n x dt_p with v_n the closing speed along n at the
    centroid; ``residual_crush`` from it by SAE 880223 (C_max = 3.5 in + 1.14 C_residual; 0
    below 3.5 in, flagged by ``residual_below_threshold``)."""

    vehicle: str
    direction: Array
    bounding_box: float
    mesh: float | None
    mesh_crossings: int
    overlap_depth: float
    crush_share: float
    crush_share_basis: str
    max_crush: float
    residual_crush: float
    residual_below_threshold: bool
    notes: tuple[str, ...] = ()

    def __post_init__(self) -> None:
        _freeze_arrays(self)

    def to_dict(self) -> dict[str, Any]:
        return {
            "direction": _vec(self.direction),
            "bounding_box": float(self.bounding_box),
            "mesh": _opt(self.mesh),
            "mesh_ray_crossings": int(self.mesh_crossings),
            "overlap_depth": float(self.overlap_depth),
            "spring_model": {
                "share": float(self.crush_share),
                "share_basis": self.crush_share_basis,
                "max_crush": float(self.max_crush),
                "residual_crush": float(self.residual_crush),
                "residual_below_threshold": bool(self.residual_below_threshold),
            },
            "notes": list(self.notes),
        }


@dataclass(frozen=True)
class VehicleImpactReport:
    """One vehicle's side of one exchange (SI, world frame unless named otherwise).

    ``role`` 1 or 2 (vehicle 1 or 2 of the pair). ``centroid_body``: the impulse centroid in
    this vehicle's ISO body frame at the exchange (m from the CG). ``impulse``: the impulse
    on this vehicle (N s). ``delta_v``: world (m/s); ``delta_v_body``: ISO body frame at the
    exchange pose; ``longitudinal`` (+forward), ``lateral`` (+RIGHT, = -body y) and
    ``vertical`` (+up) are the event-data-recorder components. ``pdof_deg`` (SAE, [0, 360))
    and ``clock`` (1-12), None without a horizontal delta-V. ``yaw_rate_change``: deg/s,
    world z, + counter-clockwise seen from above; ``delta_omega``: the whole change, world,
    rad/s. ``speed_before`` / ``speed_after``: |velocity| of the CG (m/s).
    ``translational_energy_change`` / ``rotational_energy_change``: this vehicle's kinetic
    energy after minus before (J; the rotational part with the world inertia at the
    exchange). ``energy``: its share of the dissipated energy by stiffness (J) and ``ees``
    = sqrt(2 energy / mass) (m/s), both None when the stiffness is unknown."""

    name: str
    role: int
    mass: float
    struck_face: str
    effective_mass: float
    spring_rate: float | None
    centroid_body: Array
    impulse: Array
    delta_v: Array
    delta_v_body: Array
    longitudinal: float
    lateral: float
    vertical: float
    delta_v_magnitude: float
    pdof_deg: float | None
    clock: int | None
    yaw_rate_change: float
    delta_omega: Array
    velocity_before: Array
    velocity_after: Array
    speed_before: float
    speed_after: float
    translational_energy_change: float
    rotational_energy_change: float
    energy: float | None
    ees: float | None
    deformation: DeformationReport

    def __post_init__(self) -> None:
        _freeze_arrays(self)

    def to_dict(self) -> dict[str, Any]:
        return {
            "name": self.name,
            "role": int(self.role),
            "mass": float(self.mass),
            "struck_face": self.struck_face,
            "effective_mass": float(self.effective_mass),
            "spring_rate": _opt(self.spring_rate),
            "centroid_body": _vec(self.centroid_body),
            "impulse": _vec(self.impulse),
            "delta_v": {
                "world": _vec(self.delta_v),
                "body": _vec(self.delta_v_body),
                "longitudinal": float(self.longitudinal),
                "lateral": float(self.lateral),
                "vertical": float(self.vertical),
                "magnitude": float(self.delta_v_magnitude),
            },
            "pdof_deg": _opt(self.pdof_deg),
            "clock": None if self.clock is None else int(self.clock),
            "yaw_rate_change_deg_s": float(self.yaw_rate_change),
            "delta_omega_world": _vec(self.delta_omega),
            "velocity_before": _vec(self.velocity_before),
            "velocity_after": _vec(self.velocity_after),
            "speed_before": float(self.speed_before),
            "speed_after": float(self.speed_after),
            "kinetic_energy_change": {
                "translational": float(self.translational_energy_change),
                "rotational": float(self.rotational_energy_change),
            },
            "energy": {"share": _opt(self.energy), "ees": _opt(self.ees)},
            "deformation": self.deformation.to_dict(),
        }


@dataclass(frozen=True)
class ObstacleImpactReport:
    """The fixed obstacle's side of an exchange with a vehicle: ``name``, ``role`` (1 or 2
    in the pair), ``struck_face`` (the engine's name of the face of its own frame whose
    stiffness is taken: front +x, rear -x, left +y, right -y) and ``struck_side`` (the same
    as the side of its frame: "+x", "-x", "+y", "-y"; the words a reader is given, since a
    pole has no front or rear), ``spring_rate`` (k = B W, N/m; None without stiffness:
    then it is rigid), ``centroid_body`` (the centroid in the obstacle's frame, m). It has
    an infinite mass (``effective_mass`` is None in the JSON), never moves and has no
    delta-V."""

    name: str
    role: int
    struck_face: str
    spring_rate: float | None
    centroid_body: Array

    def __post_init__(self) -> None:
        _freeze_arrays(self)

    @property
    def struck_side(self) -> str:
        return FACE_SIDES[self.struck_face]

    def to_dict(self) -> dict[str, Any]:
        return {
            "name": self.name,
            "role": int(self.role),
            "struck_face": self.struck_face,
            "struck_side": self.struck_side,
            "effective_mass": None,
            "spring_rate": _opt(self.spring_rate),
            "centroid_body": _vec(self.centroid_body),
        }


@dataclass(frozen=True)
class ImpactReport:
    """One impulse exchange (SI, world frame).

    ``number``: 1, 2, ... in time order. ``vehicles``: (vehicle 1, vehicle 2).
    ``first_contact_time`` (the timer's start: first overlap, or closing again for a
    ``secondary`` exchange) and ``exchange_time`` (s). ``depth_of_penetration`` (s) and its
    ``depth_of_penetration_mode`` ("fixed": the pair's parameter; "auto": sqrt(m'/k') at the
    exchange); ``reduced_mass`` m' (kg) of the effective masses along n; ``series_stiffness``
    k' = k1 k2 / (k1 + k2) (N/m, None without stiffness; the vehicle's k against a rigid
    obstacle) and ``implied_depth_of_penetration``
    sqrt(m'/k') (s, None without stiffness). ``centroid`` and ``normal`` (unit, 1 -> 2);
    ``contact_frame`` rows n, t, b. ``impulse`` on vehicle 2 (N s) and its magnitude.
    ``impact_type`` "full" or "sliding". ``closing_speed``: the normal relative velocity at
    the centroid before the exchange (m/s, > 0 closing). ``energy_dissipated`` (J) and
    ``energy_split_basis`` ("stiffness", "unknown", or "rigid obstacle": a fixed obstacle
    without stiffness data for both parties takes none of the crush and energy).
    ``overlap_depth`` (along n) and ``overlap_width`` (along t), m. ``parties``: the
    VehicleImpactReports of the moving vehicles, vehicle 1 first (one when the other party
    is a fixed obstacle, described by ``obstacle``: its mass is infinite, so m' is the
    vehicle's effective mass). ``notes``: the engine's remarks and the report's."""

    number: int
    vehicles: tuple[str, str]
    secondary: bool
    first_contact_time: float
    exchange_time: float
    depth_of_penetration: float
    depth_of_penetration_mode: str
    reduced_mass: float
    series_stiffness: float | None
    implied_depth_of_penetration: float | None
    centroid: Array
    normal: Array
    contact_frame: Array
    impulse: Array
    impulse_magnitude: float
    impact_type: str
    closing_speed: float
    energy_dissipated: float
    energy_split_basis: str
    overlap_depth: float
    overlap_width: float
    region_min: Array
    region_max: Array
    parties: tuple[VehicleImpactReport, ...]
    notes: tuple[str, ...] = ()
    obstacle: ObstacleImpactReport | None = None

    def __post_init__(self) -> None:
        _freeze_arrays(self)

    def vehicle(self, name: str) -> VehicleImpactReport:
        """The per-vehicle part of a named vehicle."""
        for p in self.parties:
            if p.name == name:
                return p
        raise SceneError(f"vehicle {name!r} is not in impact {self.number} {self.vehicles}")

    @property
    def how_depth_of_penetration(self) -> str:
        """A sentence saying where dt_p came from."""
        if self.depth_of_penetration_mode == "auto":
            return (
                "auto: sqrt(m'/k') at the exchange, m' the reduced effective mass along n, "
                "k' the series stiffness of the struck faces (k = B W), at most 60 ms"
            )
        return "fixed: the pair's depth_of_penetration parameter"

    def to_dict(self) -> dict[str, Any]:
        return {
            "number": int(self.number),
            "vehicles": list(self.vehicles),
            "secondary": bool(self.secondary),
            "first_contact_time": float(self.first_contact_time),
            "exchange_time": float(self.exchange_time),
            "depth_of_penetration": {
                "value": float(self.depth_of_penetration),
                "mode": self.depth_of_penetration_mode,
                "how": self.how_depth_of_penetration,
                "reduced_effective_mass": float(self.reduced_mass),
                "series_stiffness": _opt(self.series_stiffness),
                "implied_by_spring_model": _opt(self.implied_depth_of_penetration),
            },
            "centroid": {
                "world": _vec(self.centroid),
                "body": {
                    n: _vec(
                        self.obstacle.centroid_body
                        if self.obstacle is not None and n == self.obstacle.name
                        else self.vehicle(n).centroid_body
                    )
                    for n in self.vehicles
                },
            },
            "normal": _vec(self.normal),
            "contact_frame": _mat(self.contact_frame),
            "impulse": {"on_vehicle_2": _vec(self.impulse), "magnitude": self.impulse_magnitude},
            "impact_type": self.impact_type,
            "closing_speed": float(self.closing_speed),
            "struck_faces": {
                n: (
                    self.obstacle.struck_face
                    if self.obstacle is not None and n == self.obstacle.name
                    else self.vehicle(n).struck_face
                )
                for n in self.vehicles
            },
            "overlap": {
                "depth_along_normal": float(self.overlap_depth),
                "width": float(self.overlap_width),
                "region_min": _vec(self.region_min),
                "region_max": _vec(self.region_max),
            },
            "energy": {
                "dissipated": float(self.energy_dissipated),
                "split_basis": self.energy_split_basis,
            },
            "parties": [p.to_dict() for p in self.parties],
            "notes": list(self.notes),
            **({} if self.obstacle is None else {"obstacle": self.obstacle.to_dict()}),
        }


# -- building -------------------------------------------------------------------------------


def _deformation(
    vehicle: Vehicle,
    position: Array,
    rotation: Array,
    centroid: Array,
    direction: Array,
    overlap_depth: float,
    share: float,
    share_basis: str,
    total_crush: float,
) -> DeformationReport:
    """The deformation figures of one vehicle (see DeformationReport)."""
    notes: list[str] = []
    lo, hi = (np.asarray(a, dtype=np.float64) for a in vehicle.shape.aabb())
    corners = np.array(
        [[x, y, z] for x in (lo[0], hi[0]) for y in (lo[1], hi[1]) for z in (lo[2], hi[2])]
    )
    world_corners = position + corners @ rotation.T
    bounding_box = float(np.max(world_corners @ direction) - centroid @ direction)
    origin_body = rotation.T @ (centroid - position)
    hits = np.asarray(vehicle.shape.ray_hits(origin_body, rotation.T @ direction), dtype=np.float64)
    mesh = float(hits[-1]) if hits.size else None
    if mesh is None:
        notes.append(
            "no mesh deformation: the ray from the centroid along the measuring direction "
            "crosses no triangle of the mesh (the centroid is outside the vehicle on that "
            "side, or the mesh is open there)"
        )
    max_crush = share * total_crush
    residual = float(penetration.residual_crush_from_max(max_crush))
    below = max_crush < penetration.SAE_880223_INTERCEPT
    if below:
        notes.append(
            f"maximum crush {max_crush:.4f} m is below 3.5 in (0.0889 m): SAE 880223 "
            "predicts no residual crush (0 reported)"
        )
    if share_basis == EQUAL_SHARES:
        notes.append("stiffness unknown: the spring-model crush is split equally")
    return DeformationReport(
        vehicle=vehicle.name,
        direction=direction,
        bounding_box=bounding_box,
        mesh=mesh,
        mesh_crossings=int(hits.size),
        overlap_depth=overlap_depth,
        crush_share=share,
        crush_share_basis=share_basis,
        max_crush=max_crush,
        residual_crush=residual,
        residual_below_threshold=below,
        notes=tuple(notes),
    )


def _impact_report(result: Result, impact: Impact, number: int) -> ImpactReport:
    names = impact.vehicles
    n = np.asarray(impact.normal, dtype=np.float64)
    p = np.asarray(impact.centroid, dtype=np.float64)
    e = float(impact.energy_dissipated)
    rates = impact.spring_rates
    k = None if rates is None else (float(rates[names[0]]), float(rates[names[1]]))
    m_eff = (float(impact.effective_mass[names[0]]), float(impact.effective_mass[names[1]]))
    if impact.obstacle is not None:  # infinite mass: m' = m1 m2 / (m1 + m2) -> the vehicle's
        reduced = m_eff[1] if names[0] == impact.obstacle else m_eff[0]
    else:
        reduced = float(penetration.reduced_mass(*m_eff))
    notes = list(impact.notes)
    series: float | None = None
    implied: float | None = None
    # each party's k = B W as reported (None without data, or for a rigid obstacle)
    party_rates: tuple[float | None, float | None] = (None, None) if k is None else k
    if impact.obstacle is not None and (k is None or math.isinf(max(k))):
        # A fixed obstacle without stiffness data is rigid (the engine's infinite rate): the
        # vehicle takes the whole crush and energy (its EES is then the equivalent barrier
        # speed); with the vehicle's B W, k' is that and sqrt(m'/k') its spring's time.
        vehicle_first = names[0] != impact.obstacle
        shares = (1.0, 0.0) if vehicle_first else (0.0, 1.0)
        basis, crush_basis = RIGID_OBSTACLE, RIGID_OBSTACLE
        if k is not None:
            series = k[0] if vehicle_first else k[1]
            implied = math.sqrt(reduced / series)
            party_rates = (series, None) if vehicle_first else (None, series)
        notes.append(
            f"{impact.obstacle} taken as rigid (no stiffness data): the vehicle takes all the "
            "crush and dissipated energy"
        )
    elif k is not None and k[0] > 0.0 and k[1] > 0.0:
        series = float(penetration.series_stiffness(*k))
        implied = math.sqrt(reduced / series)
        # E1 = E k2 / (k1 + k2): the softer vehicle absorbs more (equal spring forces)
        shares = (k[1] / (k[0] + k[1]), k[0] / (k[0] + k[1]))
        basis, crush_basis = BY_STIFFNESS, BY_STIFFNESS
    else:
        party_rates = (None, None)
        shares, basis, crush_basis = (0.5, 0.5), UNKNOWN, EQUAL_SHARES
        notes.append("stiffness unknown: the dissipated energy is not split, no EES")
    overlap_depth = float(impact.region_max[0] - impact.region_min[0])  # row 0 of the frame: n
    v_n = float(impact.closing_speed)
    total_crush = v_n * float(impact.depth_of_penetration)
    if total_crush < 0.0:
        notes.append(
            f"closing speed {v_n:.6g} m/s is not closing: spring-model crush reported as 0"
        )
        total_crush = 0.0
    parties = []
    obstacle = None
    for role, name in enumerate(names, start=1):
        position, rotation = (
            np.asarray(a, dtype=np.float64) for a in result.pose(name, impact.time)
        )
        if name == impact.obstacle:
            obstacle = ObstacleImpactReport(
                name=name,
                role=role,
                struck_face=str(impact.struck_faces.get(name, UNKNOWN)),
                spring_rate=party_rates[role - 1],
                centroid_body=rotation.T @ (p - position),
            )
            continue
        vehicle = result.vehicle(name)
        direction = n if role == 1 else -n
        deformation = _deformation(
            vehicle,
            position,
            rotation,
            p,
            direction,
            overlap_depth,
            shares[role - 1],
            crush_basis,
            total_crush,
        )
        dv = np.asarray(impact.delta_v[name], dtype=np.float64)
        # the engine's EDR frame and PDOF (events.rs): a batch's columns are the same bits
        dv_body = np.asarray(impact.delta_v_body[name], dtype=np.float64)
        pdof_deg = impact.pdof_deg[name]
        v0 = np.asarray(impact.velocity_before[name], dtype=np.float64)
        v1 = np.asarray(impact.velocity_after[name], dtype=np.float64)
        w0 = np.asarray(impact.angular_velocity_before[name], dtype=np.float64)
        w1 = np.asarray(impact.angular_velocity_after[name], dtype=np.float64)
        inertia_world = rotation @ np.asarray(vehicle.inertia, dtype=np.float64) @ rotation.T
        mass = float(vehicle.mass)
        share_energy = None if basis == UNKNOWN else e * shares[role - 1]
        ees = None if share_energy is None else math.sqrt(2.0 * max(share_energy, 0.0) / mass)
        parties.append(
            VehicleImpactReport(
                name=name,
                role=role,
                mass=mass,
                struck_face=str(impact.struck_faces.get(name, UNKNOWN)),
                effective_mass=m_eff[role - 1],
                spring_rate=party_rates[role - 1],
                centroid_body=rotation.T @ (p - position),
                impulse=np.asarray(impact.impulse_on(name), dtype=np.float64),
                delta_v=dv,
                delta_v_body=dv_body,
                longitudinal=float(dv_body[0]),
                lateral=float(-dv_body[1]),
                vertical=float(dv_body[2]),
                delta_v_magnitude=impact.speed_change(name),
                pdof_deg=pdof_deg,
                clock=clock_direction(pdof_deg),
                yaw_rate_change=math.degrees(float(w1[2] - w0[2])),
                delta_omega=w1 - w0,
                velocity_before=v0,
                velocity_after=v1,
                speed_before=float(np.linalg.norm(v0)),
                speed_after=float(np.linalg.norm(v1)),
                translational_energy_change=0.5 * mass * float(v1 @ v1 - v0 @ v0),
                rotational_energy_change=0.5
                * float(w1 @ inertia_world @ w1 - w0 @ inertia_world @ w0),
                energy=share_energy,
                ees=ees,
                deformation=deformation,
            )
        )
    return ImpactReport(
        number=number,
        vehicles=names,
        secondary=bool(impact.secondary),
        first_contact_time=float(impact.first_contact_time),
        exchange_time=float(impact.time),
        depth_of_penetration=float(impact.depth_of_penetration),
        depth_of_penetration_mode=str(impact.depth_of_penetration_mode),
        reduced_mass=reduced,
        series_stiffness=series,
        implied_depth_of_penetration=implied,
        centroid=p,
        normal=n,
        contact_frame=np.asarray(impact.contact_frame, dtype=np.float64),
        impulse=np.asarray(impact.impulse, dtype=np.float64),
        impulse_magnitude=float(np.linalg.norm(impact.impulse)),
        impact_type=SLIDING if impact.sliding else FULL,
        closing_speed=v_n,
        energy_dissipated=e,
        energy_split_basis=basis,
        overlap_depth=overlap_depth,
        overlap_width=float(impact.overlap_width),
        region_min=np.asarray(impact.region_min, dtype=np.float64),
        region_max=np.asarray(impact.region_max, dtype=np.float64),
        parties=tuple(parties),
        notes=tuple(notes),
        obstacle=obstacle,
    )


def _mesh_record(vehicle: Vehicle, include_mesh: bool) -> dict[str, Any]:
    """What the report knows of a vehicle's mesh: size, model-frame bounds, a SHA-256 of its
    vertices (float64, model frame, m) and faces (int64), the scalar entries of trimesh's
    metadata (a file name, a box's extents, ...) and, when asked, the mesh itself."""
    mesh = vehicle.mesh
    vertices = np.ascontiguousarray(mesh.vertices, dtype=np.float64)
    faces = np.ascontiguousarray(mesh.faces, dtype=np.int64)
    digest = hashlib.sha256(vertices.tobytes() + faces.tobytes()).hexdigest()
    metadata: dict[str, Any] = {}
    for key, value in mesh.metadata.items():
        if str(key).startswith("_"):
            continue
        if isinstance(value, str | bool | int | float):
            metadata[str(key)] = value
        elif isinstance(value, np.ndarray) and value.size <= 16 and value.dtype.kind in "fiu":
            metadata[str(key)] = value.tolist()
    out: dict[str, Any] = {
        "triangles": len(faces),
        "vertices": len(vertices),
        "bounds_model": _mat(mesh.bounds),
        "sha256": digest,
        "metadata": metadata,
    }
    if include_mesh:
        out["vertex_positions"] = _mat(vertices)
        out["face_indices"] = [[int(i) for i in f] for f in faces]
    return out


def _contact_pairs(scene: Scene) -> list[dict[str, Any]]:
    """Every pair's parameters as the engine gets them, vehicle 1 first (the normal and a
    fixed centroid are given as seen from vehicle 1)."""
    return [{"vehicles": [a, b], "parameters": _plain(params)} for a, b, params in scene.pairs()]


def _scene_record(result: Result, include_meshes: bool) -> dict[str, Any]:
    scene = result.scene
    assert scene is not None
    vehicles = []
    for name in result.vehicles:
        v = result.vehicle(name)
        tr = result.trajectory(name)
        vehicles.append(
            {
                "name": name,
                "mass": float(v.mass),
                "mass_source": str(v.mass_source),
                "cg_model": _vec(v.cg),
                "inertia": _mat(v.inertia),
                "sources": {str(a): str(b) for a, b in v.sources.items()},
                "stiffness": _plain(v.stiffness.to_dict()),
                "summary": v.summary(),
                "mesh": _mesh_record(v, include_meshes),
                "generator": None
                if v.generator_params is None
                else _plain(v.generator_params.as_dict()),
                "initial_state": {
                    "time": float(tr.t[0]),
                    "position": _vec(tr.position[0]),
                    "orientation": _vec(tr.orientation[0]),
                    "velocity": _vec(tr.velocity[0]),
                    "angular_velocity": _vec(tr.angular_velocity[0]),
                },
                # optional: a vehicle on its wheels in a run on the ground
                **(
                    {"wheels": _plain(v.wheels.describe(v.mass))}
                    if v.wheels is not None and getattr(result, "on_ground", False)
                    else {}
                ),
            }
        )
    out: dict[str, Any] = {
        "vehicles": vehicles,
        "contact": {
            "defaults": _plain(scene.defaults),
            "pairs": _contact_pairs(scene),
        },
    }
    if result.obstacles:
        out["obstacles"] = []
        for name in result.obstacles:
            o = result.obstacle(name)
            tr = result.trajectory(name)
            out["obstacles"].append(
                {
                    "name": name,
                    "kind": o.kind,
                    "stiffness": _plain(o.stiffness.to_dict()),
                    "position": _vec(tr.position[0]),
                    "orientation": _vec(tr.orientation[0]),
                    "extents": _vec(o.extents),
                }
            )
    return out


def build_report(result: Result) -> Report:
    """The report of a run (a Result that keeps its scene, as Scene.run returns it)."""
    if result.scene is None:
        raise SceneError(
            "this result has no scene, so the report lacks the vehicles' meshes and masses: "
            "build the report from the Result that Scene.run returned"
        )
    impacts = [_impact_report(result, imp, i) for i, imp in enumerate(result.impacts, start=1)]
    # a pedestrian's segments are reported as one person (its own section), not as vehicles
    segments = {s.name for p in result.scene.pedestrians.values() for s in p.segments}
    runout = (
        [run_out(result, n) for n in result.vehicles if n not in segments]
        if result.on_ground
        else []
    )
    return Report(
        result=result,
        impacts=impacts,
        engagements=engagements(result),
        run_out=runout,
        joints=joint_reports(result),
        articulation=articulation_events(result),
        pedestrians=pedestrian_reports(result),
    )


# -- the text table -------------------------------------------------------------------------


def _fmt(x: float | None, digits: int) -> str:
    """A fixed-point number ("unknown" for None); a negative zero after rounding loses its
    sign (round-off must not read as a direction)."""
    if x is None:
        return "unknown"
    text = f"{x:.{digits}f}"
    return text[1:] if text.startswith("-") and float(text) == 0.0 else text


def _fmt_angle(deg: float | None) -> str:
    """A PDOF to 0.01 deg in [0, 360) ("n/a" for None: no horizontal delta-V)."""
    if deg is None:
        return "n/a"
    text = _fmt(deg, 2)
    return "0.00" if text == "360.00" else text


def _fmt3(v: ArrayLike, digits: int) -> str:
    """(x, y, z) with _fmt's numbers."""
    return "(" + ", ".join(_fmt(float(x), digits) for x in np.asarray(v).reshape(-1)) + ")"


def _table(headers: list[str], rows: list[list[str]]) -> list[str]:
    """Lines of a plain table: first column left-aligned, the others right-aligned."""
    widths = [max(len(h), *(len(r[i]) for r in rows)) for i, h in enumerate(headers)]

    def line(cells: list[str]) -> str:
        out = [cells[0].ljust(widths[0])]
        out += [c.rjust(w) for c, w in zip(cells[1:], widths[1:], strict=True)]
        return "  " + " | ".join(out)

    rule = "  " + "-+-".join("-" * w for w in widths)
    return [line(headers), rule, *(line(r) for r in rows)]


def _pair(names: tuple[str, str] | list[str]) -> str:
    return f"{names[0]}-{names[1]}"


def _numbers(indices: tuple[int, ...]) -> str:
    """Impact numbers (1-based) of impact indices: "3", "3 and 5", "3, 5 and 7"."""
    n = [str(i + 1) for i in indices]
    return n[0] if len(n) == 1 else ", ".join(n[:-1]) + " and " + n[-1]


def _engagement_lines(e: Engagement, impacts: list[ImpactReport]) -> list[str]:
    """A pair's contact in words: its exchanges grouped, their summed delta-V, the causes of
    its secondary exchanges, and any timer that ended without an impulse (labelled)."""
    apart = [t for t, reason in e.no_exchange if "no longer overlap" in reason]
    if e.separation_time is not None:
        end = f"separated at {_fmt(e.separation_time, 6)} s"
    elif apart:
        end = f"found apart when its timer expired at {_fmt(apart[-1], 6)} s"
    else:
        end = "still overlapping when the run ended"
    head = f"  {_pair(e.vehicles)}: first overlap at {_fmt(e.first_overlap_time, 6)} s, {end}"
    if not e.exchanged:
        lines = [head]
        for t, reason in e.no_exchange or ((e.first_overlap_time, "no timer expired"),):
            lines.append(
                f"    NO EXCHANGE: the overlap that began at {_fmt(e.first_overlap_time, 6)} s "
                f"ended without an impulse (timer end {_fmt(t, 6)} s: {reason})"
            )
        return lines
    primary, secondary = e.exchanges[0], e.exchanges[1:]
    which = f"impact {primary + 1}"
    which += f" (primary) and secondary {_numbers(secondary)}" if secondary else " only"
    lines = [head + f"; {which}"]
    summed = []
    for name in e.vehicles:
        if name not in e.delta_v:  # a fixed obstacle
            continue
        dv = float(np.linalg.norm(e.delta_v[name]))
        summed.append(
            f"{name} {_fmt(dv, 3)} m/s ({_fmt(to_kmh(dv), 2)} km/h, {_fmt(to_mph(dv), 2)} mph)"
        )
    lines.append(
        f"    summed delta-V (vector sum over its {len(e.exchanges)} exchange(s)): "
        + ", ".join(summed)
        + f"; energy dissipated {_fmt(e.energy_dissipated, 1)} J"
    )
    for i in e.exchanges:
        if i in e.causes:
            closing = impacts[i].closing_speed
            lines.append(
                f"    impact {i + 1} (secondary, closing speed {_fmt(closing, 3)} m/s): "
                f"{e.causes[i]}"
            )
    for t, reason in e.no_exchange:
        lines.append(
            f"    NO EXCHANGE: a timer ended at {_fmt(t, 6)} s without an impulse: {reason}"
        )
    return lines


def _speed_cells(v: float | None) -> list[str]:
    if v is None:
        return ["unknown"] * 3
    return [_fmt(v, 3), _fmt(to_kmh(v), 2), _fmt(to_mph(v), 2)]


def _impact_lines(imp: ImpactReport, primary: int | None = None) -> list[str]:
    """The text of one impact; ``primary``: the number of the impact a secondary one
    follows in its pair's engagement."""
    v1, v2 = imp.vehicles
    c = imp.centroid
    n = imp.normal
    dtp = f"{_fmt(imp.depth_of_penetration * 1e3, 3)} ms ({imp.depth_of_penetration_mode}"
    if imp.series_stiffness is not None:
        dtp += f"; m' = {_fmt(imp.reduced_mass, 1)} kg, k' = {imp.series_stiffness:.6g} N/m"
    else:
        dtp += f"; m' = {_fmt(imp.reduced_mass, 1)} kg, k' unknown"
    dtp += ")"
    lines = [
        f"Impact {imp.number}: {v1} (1) -> {v2} (2)"
        + (
            " [secondary" + (f" to impact {primary}" if primary else "") + "]"
            if imp.secondary
            else ""
        )
        + f", {imp.impact_type} impact",
        f"  first overlap t0 = {_fmt(imp.first_contact_time, 6)} s, exchange "
        f"t = {_fmt(imp.exchange_time, 6)} s, depth of penetration {dtp}",
        f"  centroid (world) {_fmt3(c, 4)} m; normal 1->2 {_fmt3(n, 4)}",
        f"  impulse on {v2} {_fmt3(imp.impulse, 1)} N s, "
        f"|J| = {_fmt(imp.impulse_magnitude, 1)} N s; closing speed "
        f"{_fmt(imp.closing_speed, 3)} m/s",
        f"  energy dissipated {_fmt(imp.energy_dissipated, 1)} J, split by stiffness: "
        + {BY_STIFFNESS: "yes", RIGID_OBSTACLE: "all to the vehicle (rigid obstacle)"}.get(
            imp.energy_split_basis, "unknown"
        )
        + f"; overlap depth along n {_fmt(imp.overlap_depth, 4)} m, "
        + f"width {_fmt(imp.overlap_width, 4)} m",
    ]
    for p in imp.parties:
        cb = p.centroid_body
        lines.append(
            f"  centroid in {p.name}'s body frame {_fmt3(cb, 4)} m"
            f" (x fwd, y left, z up from the CG); struck face: {p.struck_face}"
        )
    if imp.obstacle is not None:
        o = imp.obstacle
        lines.append(
            f"  {o.name} is a fixed obstacle (infinite mass, no delta-V); centroid in its "
            f"frame {_fmt3(o.centroid_body, 4)} m; struck on its {o.struck_side} side (its "
            f"frame; the {o.struck_face} face for its stiffness)"
        )
    lines.append("")
    lines += _table(
        [
            "Vehicle",
            "dV (m/s)",
            "dV (km/h)",
            "dV (mph)",
            "dV long (m/s)",
            "dV lat (m/s)",
            "PDOF (deg)",
            "Clock",
            "dYaw rate (deg/s)",
        ],
        [
            [
                p.name,
                *_speed_cells(p.delta_v_magnitude),
                _fmt(p.longitudinal, 3),
                _fmt(p.lateral, 3),
                _fmt_angle(p.pdof_deg),
                "unknown" if p.clock is None else f"{p.clock}",
                _fmt(p.yaw_rate_change, 2),
            ]
            for p in imp.parties
        ],
    )
    lines.append("")
    lines += _table(
        [
            "Vehicle",
            "v before (m/s)",
            "v before (km/h)",
            "v before (mph)",
            "v after (m/s)",
            "v after (km/h)",
            "v after (mph)",
        ],
        [
            [p.name, *_speed_cells(p.speed_before), *_speed_cells(p.speed_after)]
            for p in imp.parties
        ],
    )
    lines.append("")
    lines += _table(
        [
            "Vehicle",
            "Energy (J)",
            "EES (m/s)",
            "EES (km/h)",
            "EES (mph)",
            "Box def. (m)",
            "Mesh def. (m)",
            "Overlap (m)",
            "C max (m)",
            "C residual (m)",
        ],
        [
            [
                p.name,
                _fmt(p.energy, 1),
                *_speed_cells(p.ees),
                _fmt(p.deformation.bounding_box, 4),
                "n/a" if p.deformation.mesh is None else _fmt(p.deformation.mesh, 4),
                _fmt(p.deformation.overlap_depth, 4),
                _fmt(p.deformation.max_crush, 4),
                _fmt(p.deformation.residual_crush, 4),
            ]
            for p in imp.parties
        ],
    )
    notes = list(imp.notes)
    for p in imp.parties:
        notes += [f"{p.name}: {x}" for x in p.deformation.notes]
    if notes:
        lines.append("  notes:")
        lines += [f"  - {x}" for x in notes]
    return lines


# -- the report -----------------------------------------------------------------------------


class Report:
    """The report of a run: ``impacts`` (ImpactReport list, in time order), ``result`` (the
    Result it was built from), ``run_out`` (a run on a ground: each vehicle's
    RunOutReport, from its separation to rest; crashsim.analysis.runout), ``joints`` (a
    scene with joints: each JointReport, crashsim.analysis.joints).
    ``summary_table()`` / ``str(report)``: the text table; ``to_dict()`` / ``to_json()`` /
    ``write_json(path)``: the versioned JSON report."""

    def __init__(
        self,
        result: Result,
        impacts: list[ImpactReport],
        engagements: list[Engagement] | None = None,
        run_out: list[RunOutReport] | None = None,
        joints: list[JointReport] | None = None,
        articulation: list[ArticulationEvent] | None = None,
        pedestrians: list[PedestrianReport] | None = None,
    ) -> None:
        self.result = result
        self.impacts = list(impacts)
        #: the pairs' contacts, exchanges grouped (crashsim.analysis.engagements)
        self.engagements = list(engagements) if engagements is not None else []
        #: each vehicle's run-out to rest (runs on a ground; empty otherwise)
        self.run_out = list(run_out) if run_out is not None else []
        #: each joint over the run (a scene with joints; empty otherwise)
        self.joints = list(joints) if joints is not None else []
        #: the combinations' jackknifes and trailer swings (crashsim.analysis.joints' rules)
        self.articulation = list(articulation) if articulation is not None else []
        #: each pedestrian: its first contacts, head impact, end (crashsim.analysis.pedestrian)
        self.pedestrians = list(pedestrians) if pedestrians is not None else []

    def vehicle_run_out(self, name: str) -> RunOutReport:
        """The run-out of a named vehicle (SceneError when the run had no ground)."""
        for r in self.run_out:
            if r.vehicle == name:
                return r
        if not self.run_out:
            raise SceneError("the run had no ground: its report has no run-out")
        raise SceneError(f"no vehicle named {name!r} in this report: {self.vehicles}")

    @property
    def vehicles(self) -> list[str]:
        return list(self.result.vehicles)

    def summary_table(self) -> str:
        """The text report: per impact a header, then per vehicle delta-V (m/s, km/h, mph),
        EDR components, PDOF, clock and yaw-rate change; speeds before and after; energy,
        EES and the deformations."""
        lines = [
            f"crashsim {_core.__version__} report: {len(self.impacts)} impact(s); vehicles "
            + ", ".join(
                f"{n} ({self.result.vehicle(n).mass:.1f} kg)" for n in self.result.vehicles
            ),
            "Signs: dV long +forward, dV lat +right (event data recorder axes, at the exchange "
            "pose); PDOF SAE: direction the force comes FROM, deg clockwise from ahead seen from "
            "above (90 = from the right); dYaw rate + counter-clockwise seen from above. "
            "Deformation: vehicle 1 along +n, vehicle 2 along -n, centroid to bounding box or "
            "mesh; C max = share x closing speed x dt_p; C residual by SAE 880223.",
        ]
        if not self.impacts:
            lines.append("No impulse exchange in this run.")
        # Contacts by pair, when a pair had more than one exchange or one had none (a
        # first overlap without an exchange is never left out).
        if any(len(e.exchanges) != 1 or e.no_exchange for e in self.engagements):
            lines += [
                "",
                "Contacts by pair (each from its first overlap to its separation; the "
                "delta-V of a pair's exchanges summed):",
            ]
            for e in self.engagements:
                lines += _engagement_lines(e, self.impacts)
            if any(e.secondary for e in self.engagements):
                lines.append(f"  Why secondary exchanges: {WHY_SECONDARY}.")
        primaries = {
            i: e.primary + 1 for e in self.engagements if e.primary is not None for i in e.secondary
        }
        for k, imp in enumerate(self.impacts):
            lines.append("")
            lines += _impact_lines(imp, primaries.get(k))
        if self.run_out:
            lines.append("")
            lines += run_out_lines(self.run_out, _table, obstacles=bool(self.result.obstacles))
            lines += _vehicle_data_lines(self.result)
        if self.joints:
            lines.append("")
            lines += joint_lines(self.joints)
            if self.articulation:
                lines.append("Jackknifes and trailer swings (crashsim's rules, docs/joints.md):")
                lines += articulation_lines(self.articulation)
        if self.pedestrians:
            lines.append("")
            lines += pedestrian_lines(self.pedestrians)
        return "\n".join(lines)

    def __str__(self) -> str:
        return self.summary_table()

    def __repr__(self) -> str:
        return f"Report(vehicles={self.vehicles}, impacts={len(self.impacts)})"

    def to_dict(self, include_meshes: bool = False) -> dict[str, Any]:
        """The JSON report as plain Python (dicts, lists, str, bool, int, float, None);
        ``include_meshes`` adds every vehicle's vertices and faces (model frame)."""
        r = self.result
        scene = _scene_record(r, include_meshes)
        if self.joints:  # optional: a scene with joints (schema version stays 1)
            scene["joints"] = [j.definition() for j in self.joints]
        return {
            "schema": SCHEMA_NAME,
            "schema_version": SCHEMA_VERSION,
            "crashsim_version": str(_core.__version__),
            "units": dict(UNITS),
            "conventions": dict(CONVENTIONS),
            "scene": scene,
            "run": {
                "start_time": float(r.t[0]),
                "duration": None if r.duration is None else float(r.duration),
                "dt": None if r.dt is None else float(r.dt),
                "end_time": float(r.t[-1]),
                "samples": int(r.t.size),
                # optional: a run on the ground (its states between samples are interpolated)
                **({"on_ground": True} if getattr(r, "on_ground", False) else {}),
            },
            "impacts": [imp.to_dict() for imp in self.impacts],
            "contacts": [_plain(c.to_dict()) for c in r.contacts],
            "engagements": [_engagement_record(e) for e in self.engagements],
            # optional: a run on a ground (schema version stays 1)
            **({"run_out": [r.to_dict() for r in self.run_out]} if self.run_out else {}),
            # optional: a scene with joints (schema version stays 1)
            **(
                {
                    "joints": [j.to_dict() for j in self.joints],
                    "joint_events": [e.to_dict() for e in r.joint_events],
                    "articulation_events": [e.to_dict() for e in self.articulation],
                }
                if self.joints
                else {}
            ),
            # optional: a scene with pedestrians (schema version stays 1)
            **(
                {"pedestrians": [p.to_dict() for p in self.pedestrians]}
                if self.pedestrians
                else {}
            ),
        }

    def to_json(self, include_meshes: bool = False, indent: int | None = 2) -> str:
        """The JSON report as text (NaN and infinity refused: JSON has no such numbers)."""
        return json.dumps(self.to_dict(include_meshes), indent=indent, allow_nan=False)

    def write_json(self, path: str | PathLike[str], include_meshes: bool = False) -> None:
        """Write the JSON report (UTF-8) to ``path``."""
        with open(path, "w", encoding="utf-8") as f:
            f.write(self.to_json(include_meshes))
            f.write("\n")


def _vehicle_data_lines(result: Result) -> list[str]:
    """The vehicles on the ground as the engine ran them: tyre, steering, springs and bars."""
    lines: list[str] = []
    for name in result.vehicles:
        v = result.vehicle(name)
        if v.wheels is None:
            continue
        d = v.wheels.describe(v.mass)
        if not lines:
            lines += ["", "Vehicles on their wheels (as run):"]
        t = d["tyre"]
        law = {
            "linear": f"linear, cornering {math.radians(t.get('cornering', 0.0)):.4f} per deg "
            f"(1 per {1.0 / math.radians(t.get('cornering', 1.0)):.1f} deg)",
            "linear_friction_scaled": "linear scaled by the friction, mu Fz at "
            f"{math.degrees(t.get('saturation_angle', 0.0)):.1f} deg",
            "magic_formula": f"Magic Formula B {t.get('b')}, C {t.get('c')}, E {t.get('e')}",
        }[t["model"]]
        lines.append(
            f"  {name}: tyre {law}; relaxation length {t['relaxation_length']:.3f} m; rolling "
            f"resistance {t['rolling_resistance']:g}; combined slip {t['combined']}; load "
            f"sensitivity {t['load_sensitivity']:g}"
        )
        st = d["steering"]
        ratio = "none" if st["ratio"] is None else f"{st['ratio']:g}"
        lines.append(
            f"  {name}: steering ratio {ratio}, Ackermann {st['ackermann']:g} (input: the "
            f"{st['reference']} wheel's angle); ABS {'on' if d['abs'] else 'off'}"
        )
        freq = ", ".join(f"{f:.2f}" for f in d["natural_frequencies"])
        zeta = ", ".join(f"{z:.2f}" for z in d["damping_ratios"])
        springs = f"  {name}: springs {freq} Hz, damping ratios {zeta}"
        if "roll_stiffness" in d:
            rs = d["roll_stiffness"]
            bars = ", ".join(
                f"bar {b['left']}-{b['right']} {math.radians(b['roll_stiffness']):.0f}"
                for b in d["anti_roll"]
            )
            springs += (
                f"; roll stiffness front {math.radians(rs['front']):.0f}, rear "
                f"{math.radians(rs['rear']):.0f} N m/deg ({bars or 'springs only, no bars'})"
            )
            if d.get("roll_gradient") is not None:
                springs += f"; roll gradient {math.degrees(d['roll_gradient']):.1f} deg/g"
        lines.append(springs)
    return lines


def _engagement_record(e: Engagement) -> dict[str, Any]:
    """An engagement as JSON (impact numbers 1-based, as in ``impacts[].number``)."""
    return {
        "vehicles": list(e.vehicles),
        "first_overlap_time": float(e.first_overlap_time),
        "separation_time": _opt(e.separation_time),
        "exchanged": e.exchanged,
        "primary": None if e.primary is None else e.primary + 1,
        "secondary": [i + 1 for i in e.secondary],
        "secondary_causes": [
            {"impact": i + 1, "cause": cause} for i, cause in sorted(e.causes.items())
        ],
        "no_exchange": [{"time": float(t), "reason": reason} for t, reason in e.no_exchange],
        "delta_v": {
            "summed": {n: _vec(v) for n, v in e.delta_v.items()},
            "magnitude": {n: float(np.linalg.norm(v)) for n, v in e.delta_v.items()},
        },
        "energy_dissipated": float(e.energy_dissipated),
    }


def report_schema() -> dict[str, Any]:
    """The JSON Schema (draft 2020-12) of the report, version SCHEMA_VERSION."""
    text = resources.files("crashsim.analysis").joinpath(*_SCHEMA_FILE).read_text(encoding="utf-8")
    return dict(json.loads(text))
