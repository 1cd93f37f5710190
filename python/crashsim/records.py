"""The records a run returns, one per thing recorded (plain data: numpy and the engine's
records only): a body's ``Trajectory``, the contact log's ``ContactEvent``, an impulse
exchange's ``Impact`` (``Impact.from_core`` reads the engine's impact records, dicts keyed by
the core record's field names, the one place that does), on the ground a vehicle's
``WheelRecord`` and ``RestState``, and its ``SeparationState`` at a pair's separation;
``rotation_matrix`` of quaternions. crashsim.result's Result builds them and re-exports them
(import either way).

Everything is SI and world frame unless a name says otherwise: positions m, velocities m/s,
angular velocities rad/s, impulses N s, energies J, forces N, times s, quaternions (w, x, y,
z) rotating body-frame vectors into the world. Arrays are read-only.
"""

from __future__ import annotations

import functools
import math
import types
import typing
from collections.abc import Collection
from dataclasses import dataclass, field, fields
from typing import Any, NamedTuple

import numpy as np
from numpy.typing import ArrayLike, NDArray

from crashsim.errors import SceneError
from crashsim.small_linalg import dot, norm

__all__ = [
    "ContactEvent",
    "Impact",
    "RestState",
    "SeparationState",
    "Trajectory",
    "WheelRecord",
    "rotation_matrix",
]

Array = NDArray[np.float64]


def _frozen(a: Any) -> Array:
    out = np.array(a, dtype=np.float64)
    out.setflags(write=False)
    return out


def _name_of(vehicle: Any) -> str:
    """A vehicle's name from a name or a Vehicle."""
    return vehicle if isinstance(vehicle, str) else str(getattr(vehicle, "name", vehicle))


def _finite_or_none(x: Any) -> Any:
    """None for an infinite float (JSON has no Infinity), else x."""
    return None if isinstance(x, float) and not math.isfinite(x) else x


# How Impact.from_core reads a field (dataclass field metadata): keyed by vehicle name from the
# engine's per-body pair, computed from other fields, or reshaped.
_HOW = "engine"
_SHAPE = "shape"


def _per_vehicle(*, obstacle_too: bool = False, **kw: Any) -> Any:
    """An Impact field the engine records per body ([body 1, body 2]), kept as a dict keyed
    by vehicle name: the moving vehicles' entries (a fixed obstacle has no velocity or
    delta-V), or both with ``obstacle_too``."""
    return field(metadata={_HOW: "both" if obstacle_too else "moving"}, **kw)


def _derived(**kw: Any) -> Any:
    """An Impact field that from_core computes from others (the engine has none of its name)."""
    return field(metadata={_HOW: "derived"}, **kw)


def _points(**kw: Any) -> Any:
    """An Impact field of points, (p, 3) m, also when there are none."""
    return field(metadata={_SHAPE: (-1, 3)}, **kw)


@functools.cache
def _engine_fields(cls: type) -> tuple[tuple[Any, Any], ...]:
    """(field, resolved annotation) of each field of ``cls`` read from the engine's record."""
    hints = typing.get_type_hints(cls)
    return tuple((f, hints[f.name]) for f in fields(cls) if f.metadata.get(_HOW) != "derived")


def _engine_value(f: Any, tp: Any, raw: Any, pair: tuple[str, str], moving: list[str]) -> Any:
    """The engine's value ``raw`` of field ``f`` as its annotation ``tp`` says: a per-body
    pair as a dict keyed by name (see ``_per_vehicle``), else ``_as_type``."""
    how = f.metadata.get(_HOW)
    if how is None:
        out = _as_type(tp, raw)
        shape = f.metadata.get(_SHAPE)
        return out if shape is None else _frozen(np.reshape(out, shape))
    if raw is None:
        return None
    _, value_type = typing.get_args(_not_none(tp))
    keep = pair if how == "both" else moving
    values = dict(zip(pair, raw, strict=True))
    return {name: _as_type(value_type, values[name]) for name in keep}


def _as_type(tp: Any, raw: Any) -> Any:
    """One engine value (float, int, bool, str, None or nested lists) as the type ``tp``:
    arrays as read-only float64, tuples, numbers and strings; None where ``tp`` allows it."""
    if raw is None:
        return None
    tp = _not_none(tp)
    if tp in (float, int, bool, str):
        return tp(raw)
    if tp == Array:
        return _frozen(raw)
    if typing.get_origin(tp) is tuple:
        return tuple(raw)
    raise TypeError(f"records.py cannot read an engine value as {tp}")


def _not_none(tp: Any) -> Any:
    """``X`` of ``X | None``; any other type as it is."""
    if isinstance(tp, types.UnionType):
        (inner,) = [a for a in typing.get_args(tp) if a is not type(None)]
        return inner
    return tp


def rotation_matrix(q: ArrayLike) -> Array:
    """The 3x3 rotation (body -> world) of a unit quaternion (w, x, y, z); for quaternions
    (..., 4), the rotations (..., 3, 3), each quaternion normalised."""
    q = np.asarray(q, dtype=np.float64)
    if q.ndim == 1:
        w, x, y, z = q / norm(q)
    else:
        w, x, y, z = np.moveaxis(q / np.linalg.norm(q, axis=-1, keepdims=True), -1, 0)
    r = np.array(
        [
            [1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)],
            [2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)],
            [2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)],
        ]
    )
    return r if q.ndim == 1 else np.moveaxis(r, (0, 1), (-2, -1))


class Trajectory(NamedTuple):
    """One vehicle's samples (world frame): t (k,) s; position (k, 3) of the CG, m;
    orientation (k, 4) (w, x, y, z); velocity (k, 3) m/s; angular_velocity (k, 3) rad/s.

    Samples are every step end, every first overlap and every exchange (the state just after
    it); times never decrease."""

    t: Array
    position: Array
    orientation: Array
    velocity: Array
    angular_velocity: Array


@dataclass(frozen=True)
class ContactEvent:
    """An entry of the contact log: ``kind`` is "first_overlap", "closing_again" (an engaged
    pair closes again: a secondary timer starts), "separation" or "no_exchange" (with a
    ``reason``)."""

    vehicles: tuple[str, str]
    time: float
    kind: str
    reason: str | None = None

    @classmethod
    def from_core(cls, raw: dict[str, Any], names: list[str]) -> ContactEvent:
        """An entry from the engine's record of it (a dict keyed by the core ContactEvent's
        field names, world/events.rs; "reason" only for a skipped exchange) and the bodies'
        names: the one place that reads the engine's contact log."""
        reason = raw.get("reason")
        return cls(
            vehicles=(names[int(raw["body1"])], names[int(raw["body2"])]),
            time=float(raw["time"]),
            kind=str(raw["kind"]),
            reason=None if reason is None else str(reason),
        )

    def to_dict(self) -> dict[str, Any]:
        return {
            "vehicles": list(self.vehicles),
            "time": self.time,
            "kind": self.kind,
            "reason": self.reason,
        }


@dataclass(frozen=True, eq=False)
class Impact:
    """One impulse exchange between ``vehicles[0]`` (vehicle 1) and ``vehicles[1]`` (2).

    The normal (unit) points from 1 into 2; ``impulse`` acts on 2 and its negative on 1
    (N s). ``first_contact_time`` is when the timer started (the first overlap, or the
    closing again of an engaged pair for a ``secondary`` exchange); ``time`` is the exchange
    instant, ``first_contact_time + depth_of_penetration``. Per-vehicle quantities are dicts
    keyed by vehicle name; relative velocities are vehicle 1's point minus vehicle 2's at
    the centroid. ``contact_frame`` rows are n, t, b; ``region_min`` / ``region_max`` bound
    the overlap region ``region_points`` in that frame (m).

    ``depth_of_penetration_mode`` is "fixed" (the pair's parameter) or "auto"
    (sqrt(m'/k') from ``effective_mass`` and ``spring_rates``). ``struck_faces`` names each
    vehicle's face ("front", "rear", "left", "right") facing the other along the normal;
    ``overlap_width`` is the region's extent along the contact tangent t (m);
    ``spring_rates`` are k = B W of the struck faces (N/m; None without stiffness data; a
    fixed obstacle without any is rigid: inf);
    ``effective_mass`` is each vehicle's mass as felt along n at the centroid (kg);
    ``notes`` are the engine's remarks (e.g. an automatic dt_p outside 10-60 ms);
    ``normal_time`` is when the overlap's volume normal behind ``normal`` was taken (s): for a
    first exchange, once the overlap is at most 2 cm deep (a deep, narrow overlap at the
    exchange would turn it toward the side walls that sank into each other), else ``time``.
    ``delta_v_body`` is each moving vehicle's delta-V in its body frame at the exchange (m/s;
    x forward, y left, z up: an event data recorder's longitudinal is x, its lateral, +right,
    is -y) and ``pdof_deg`` its SAE principal direction of force (deg in [0, 360), None
    without a horizontal delta-V), both computed by the engine (the report and a batch's
    columns read these)."""

    vehicles: tuple[str, str] = _derived()
    bodies: tuple[int, int] = _derived()  # the engine's body indices (order of Scene.add)
    first_contact_time: float
    time: float
    depth_of_penetration: float
    secondary: bool
    sliding: bool
    centroid: Array
    normal: Array
    impulse: Array
    delta_v: dict[str, Array] = _derived()
    delta_omega: dict[str, Array] = _derived()
    velocity_before: dict[str, Array] = _per_vehicle()
    velocity_after: dict[str, Array] = _per_vehicle()
    angular_velocity_before: dict[str, Array] = _per_vehicle()
    angular_velocity_after: dict[str, Array] = _per_vehicle()
    relative_velocity_before: Array
    relative_velocity_after: Array
    energy_dissipated: float
    region_points: Array = _points()
    contact_frame: Array
    region_min: Array
    region_max: Array
    depth_of_penetration_mode: str = "fixed"
    struck_faces: dict[str, str] = _per_vehicle(obstacle_too=True, default_factory=dict)
    overlap_width: float = 0.0
    spring_rates: dict[str, float] | None = _per_vehicle(obstacle_too=True, default=None)
    effective_mass: dict[str, float] = _per_vehicle(obstacle_too=True, default_factory=dict)
    notes: tuple[str, ...] = ()
    normal_time: float = float("nan")
    obstacle: str | None = _derived(default=None)
    delta_v_body: dict[str, Array] = _per_vehicle(default_factory=dict)
    pdof_deg: dict[str, float | None] = _per_vehicle(default_factory=dict)

    @classmethod
    def from_core(
        cls, raw: dict[str, Any], names: list[str], obstacles: Collection[str] = ()
    ) -> Impact:
        """An Impact from the engine's record of one exchange (a dict keyed by the core
        record's field names, world/events.rs) and the bodies' names (vehicles then
        obstacles); ``obstacles`` names the fixed ones: their per-body entries (delta-V,
        velocities) are left out and their effective mass is infinite. The one place that
        reads the engine's impact records: every field but the derived ones is the engine's
        value of the same name, read as its annotation says (see ``_engine_value``)."""
        bodies = (int(raw["body1"]), int(raw["body2"]))
        pair = (names[bodies[0]], names[bodies[1]])
        fixed = [n for n in pair if n in obstacles]
        moving = [n for n in pair if n not in obstacles]
        values: dict[str, Any] = {}
        for f, tp in _engine_fields(cls):
            values[f.name] = _engine_value(f, tp, raw[f.name], pair, moving)
        v0, v1 = values["velocity_before"], values["velocity_after"]
        w0, w1 = values["angular_velocity_before"], values["angular_velocity_after"]
        return cls(
            vehicles=pair,
            bodies=bodies,
            delta_v={k: _frozen(v1[k] - v0[k]) for k in moving},
            delta_omega={k: _frozen(w1[k] - w0[k]) for k in moving},
            obstacle=fixed[0] if fixed else None,
            **values,
        )

    @property
    def closing_speed(self) -> float:
        """Normal relative velocity at the centroid before the exchange (m/s, > 0 closing)."""
        return float(dot(self.relative_velocity_before, self.normal))

    def impulse_on(self, vehicle: Any) -> Array:
        """The impulse acting on a vehicle (name or Vehicle), N s, world."""
        name = self._check(vehicle)
        return self.impulse if name == self.vehicles[1] else _frozen(-self.impulse)

    def speed_change(self, vehicle: Any) -> float:
        """|delta-V| of a vehicle's CG (m/s). SceneError for an obstacle (it has none)."""
        name = self._check(vehicle)
        if name == self.obstacle:
            raise SceneError(f"{name!r} is a fixed obstacle: it has no delta-V")
        return _magnitude(self.delta_v[name])

    @property
    def moving(self) -> tuple[str, ...]:
        """The pair's moving bodies (both, or the vehicle of a vehicle-obstacle pair)."""
        return tuple(n for n in self.vehicles if n != self.obstacle)

    def _check(self, vehicle: Any) -> str:
        name = _name_of(vehicle)
        if name not in self.vehicles:
            raise SceneError(f"vehicle {name!r} is not in this impact {self.vehicles}")
        return name

    def to_dict(self) -> dict[str, Any]:
        """A JSON-friendly copy (lists, floats, bools, str; an obstacle's infinite effective
        mass is None, so the JSON stays valid)."""
        out: dict[str, Any] = {}
        for f in fields(self):
            value = getattr(self, f.name)
            if f.name == "obstacle" and value is None:
                continue
            if f.name in ("delta_v_body", "pdof_deg"):
                continue  # the report's per-vehicle part gives them (analysis/report.py)
            if isinstance(value, np.ndarray):
                out[f.name] = value.tolist()
            elif isinstance(value, dict):
                out[f.name] = {
                    k: v.tolist() if isinstance(v, np.ndarray) else _finite_or_none(v)
                    for k, v in value.items()
                }
            elif isinstance(value, tuple):
                out[f.name] = list(value)
            else:
                out[f.name] = value
        return out


class WheelRecord(NamedTuple):
    """One vehicle's wheels over a run on the ground (world frame, SI): ``names`` (n,) in the
    engine's order; at the sample times ``t`` (k,): ``contact`` (n, k, 3) where each tyre
    meets the ground (m; the point below the wheel centre when the wheel is in the air),
    ``load`` (n, k) its normal load (N, 0 in the air), ``force`` (n, k, 3) the ground's force
    on the tyre (N: normal plus tyre forces), ``sliding`` (n, k) True where the contact patch
    slides at the friction limit (it leaves a tyre mark), ``steer`` (n, k) its road-wheel
    angle (rad, + left, about the body z axis; through the steering linkage)."""

    names: tuple[str, ...]
    t: Array
    contact: Array
    load: Array
    force: Array
    sliding: NDArray[np.bool_]
    steer: Array


class RestState(NamedTuple):
    """Where and when a vehicle came to rest (world frame, SI).

    ``time``: when it became slow for good (speed and yaw rate below the engine's rest
    thresholds from then to the end; s). ``position`` (3,) of the CG and ``heading`` (rad,
    yaw of the body x axis from world x, counter-clockwise) at the end of the run.
    ``distance``: path length of the CG from the start to the end (m); ``displacement``:
    straight-line distance of the CG from its start (m). ``last_exchange``: the time of the
    vehicle's last impulse exchange (None without one), with ``distance_from_exchange`` and
    ``displacement_from_exchange`` (m) measured from there."""

    time: float
    position: Array
    heading: float
    distance: float
    displacement: float
    last_exchange: float | None
    distance_from_exchange: float | None
    displacement_from_exchange: float | None


class SeparationState(NamedTuple):
    """A vehicle's state when a pair it belongs to stops overlapping (world frame, SI):
    ``time`` (s), ``other`` (the other vehicle or obstacle), ``velocity`` (3,) of the CG
    (m/s), ``speed`` (m/s), ``angular_velocity`` (3,) (rad/s), ``heading`` (rad)."""

    time: float
    other: str
    velocity: Array
    speed: float
    angular_velocity: Array
    heading: float


def _magnitude(v: Any) -> float:
    """|v| as sqrt(x x + y y + z z) in plain float arithmetic (m/s for a velocity): the
    core's `magnitude` (events.rs) bit for bit, so a batch's speed and delta-V columns equal
    what a Result gives."""
    x, y, z = (float(c) for c in v)
    return math.sqrt(x * x + y * y + z * z)
