"""Run results: impacts (one per impulse exchange), trajectories and the contact log.

Everything is SI and world frame unless a name says otherwise: positions m, velocities m/s,
angular velocities rad/s, impulses N s, energies J, times s, quaternions (w, x, y, z)
rotating body-frame vectors into the world. Arrays are read-only.
"""

from __future__ import annotations

from dataclasses import dataclass, field, fields
from typing import TYPE_CHECKING, Any, NamedTuple

import numpy as np
from numpy.typing import NDArray

from crashsim import _core
from crashsim.errors import SceneError

if TYPE_CHECKING:
    from crashsim.vehicles.vehicle import Vehicle

__all__ = ["ContactEvent", "Impact", "Result", "Trajectory"]

Array = NDArray[np.float64]


def _frozen(a: Any) -> Array:
    out = np.array(a, dtype=np.float64)
    out.setflags(write=False)
    return out


def _name_of(vehicle: Any) -> str:
    """A vehicle's name from a name or a Vehicle."""
    return vehicle if isinstance(vehicle, str) else str(getattr(vehicle, "name", vehicle))


def rotation_matrix(q: Array) -> Array:
    """The 3x3 rotation (body -> world) of a unit quaternion (w, x, y, z)."""
    w, x, y, z = np.asarray(q, dtype=np.float64) / np.linalg.norm(q)
    return np.array(
        [
            [1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)],
            [2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)],
            [2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)],
        ]
    )


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
    ``spring_rates`` are k = B W of the struck faces (N/m; None without stiffness data);
    ``effective_mass`` is each vehicle's mass as felt along n at the centroid (kg);
    ``notes`` are the engine's remarks (e.g. an automatic dt_p outside 10-60 ms);
    ``normal_time`` is when the overlap's volume normal behind ``normal`` was taken (s): for a
    first exchange, once the overlap is at most 2 cm deep (a deep, narrow overlap at the
    exchange would turn it toward the side walls that sank into each other), else ``time``."""

    vehicles: tuple[str, str]
    bodies: tuple[int, int]  # the engine's body indices (order of Scene.add)
    first_contact_time: float
    time: float
    depth_of_penetration: float
    secondary: bool
    sliding: bool
    centroid: Array
    normal: Array
    impulse: Array
    delta_v: dict[str, Array]
    delta_omega: dict[str, Array]
    velocity_before: dict[str, Array]
    velocity_after: dict[str, Array]
    angular_velocity_before: dict[str, Array]
    angular_velocity_after: dict[str, Array]
    relative_velocity_before: Array
    relative_velocity_after: Array
    energy_dissipated: float
    region_points: Array
    contact_frame: Array
    region_min: Array
    region_max: Array
    depth_of_penetration_mode: str = "fixed"
    struck_faces: dict[str, str] = field(default_factory=dict)
    overlap_width: float = 0.0
    spring_rates: dict[str, float] | None = None
    effective_mass: dict[str, float] = field(default_factory=dict)
    notes: tuple[str, ...] = ()
    normal_time: float = float("nan")

    @classmethod
    def from_core(cls, raw: dict[str, Any], names: list[str]) -> Impact:
        """An Impact from one of the engine's impact dicts and the vehicles' names."""
        bodies = (int(raw["body1"]), int(raw["body2"]))
        pair = (names[bodies[0]], names[bodies[1]])

        def per_vehicle(rows: Any) -> dict[str, Array]:
            rows = np.asarray(rows, dtype=np.float64)
            return {pair[0]: _frozen(rows[0]), pair[1]: _frozen(rows[1])}

        v0, v1 = per_vehicle(raw["velocity_before"]), per_vehicle(raw["velocity_after"])
        w0 = per_vehicle(raw["angular_velocity_before"])
        w1 = per_vehicle(raw["angular_velocity_after"])
        return cls(
            vehicles=pair,
            bodies=bodies,
            first_contact_time=float(raw["first_contact_time"]),
            time=float(raw["time"]),
            depth_of_penetration=float(raw["depth_of_penetration"]),
            secondary=bool(raw["secondary"]),
            sliding=bool(raw["sliding"]),
            centroid=_frozen(raw["centroid"]),
            normal=_frozen(raw["normal"]),
            impulse=_frozen(raw["impulse"]),
            delta_v={k: _frozen(v1[k] - v0[k]) for k in pair},
            delta_omega={k: _frozen(w1[k] - w0[k]) for k in pair},
            velocity_before=v0,
            velocity_after=v1,
            angular_velocity_before=w0,
            angular_velocity_after=w1,
            relative_velocity_before=_frozen(raw["relative_velocity_before"]),
            relative_velocity_after=_frozen(raw["relative_velocity_after"]),
            energy_dissipated=float(raw["energy_dissipated"]),
            region_points=_frozen(np.reshape(raw["region_points"], (-1, 3))),
            contact_frame=_frozen(raw["contact_frame"]),
            region_min=_frozen(raw["region_min"]),
            region_max=_frozen(raw["region_max"]),
            depth_of_penetration_mode=str(raw["depth_of_penetration_mode"]),
            struck_faces=dict(zip(pair, raw["struck_faces"], strict=True)),
            overlap_width=float(raw["overlap_width"]),
            spring_rates=None
            if raw["spring_rates"] is None
            else dict(zip(pair, map(float, raw["spring_rates"]), strict=True)),
            effective_mass=dict(zip(pair, map(float, raw["effective_mass"]), strict=True)),
            notes=tuple(raw["notes"]),
            normal_time=float(raw["normal_time"]),
        )

    @property
    def closing_speed(self) -> float:
        """Normal relative velocity at the centroid before the exchange (m/s, > 0 closing)."""
        return float(self.relative_velocity_before @ self.normal)

    def impulse_on(self, vehicle: Any) -> Array:
        """The impulse acting on a vehicle (name or Vehicle), N s, world."""
        name = self._check(vehicle)
        return self.impulse if name == self.vehicles[1] else _frozen(-self.impulse)

    def speed_change(self, vehicle: Any) -> float:
        """|delta-V| of a vehicle's CG (m/s)."""
        return float(np.linalg.norm(self.delta_v[self._check(vehicle)]))

    def _check(self, vehicle: Any) -> str:
        name = _name_of(vehicle)
        if name not in self.vehicles:
            raise SceneError(f"vehicle {name!r} is not in this impact {self.vehicles}")
        return name

    def to_dict(self) -> dict[str, Any]:
        """A JSON-friendly copy (lists, floats, bools, str)."""
        out: dict[str, Any] = {}
        for f in fields(self):
            value = getattr(self, f.name)
            if isinstance(value, np.ndarray):
                out[f.name] = value.tolist()
            elif isinstance(value, dict):
                out[f.name] = {
                    k: v.tolist() if isinstance(v, np.ndarray) else v for k, v in value.items()
                }
            elif isinstance(value, tuple):
                out[f.name] = list(value)
            else:
                out[f.name] = value
        return out


class Result:
    """What a run returns: ``impacts`` (Impact list, in time order), ``contacts`` (the
    ContactEvent log), ``vehicles`` (names in the order added), ``t`` (sample times, s),
    per-vehicle trajectories, ``scene`` (the Scene that ran, None for a bare result), the
    run's ``duration``, largest step ``dt`` and ``record_interval`` (the spacing of the kept
    step samples) (s; None when not known)."""

    def __init__(
        self,
        raw: dict[str, Any],
        names: list[str],
        scene: Any = None,  # the Scene that ran (not imported: a scene imports this module)
        duration: float | None = None,
        dt: float | None = None,
        record_interval: float | None = None,
    ) -> None:
        self.vehicles: list[str] = list(names)
        self.scene = scene
        self.duration = duration
        self.dt = dt
        # Interval between kept step samples (s); events are always kept.
        self.record_interval = record_interval
        self.t: Array = _frozen(raw["t"])
        self._position = _frozen(raw["position"])  # (n_vehicles, k, 3)
        self._orientation = _frozen(raw["orientation"])  # (n_vehicles, k, 4)
        self._velocity = _frozen(raw["velocity"])
        self._angular_velocity = _frozen(raw["angular_velocity"])
        self.impacts: list[Impact] = [Impact.from_core(r, self.vehicles) for r in raw["impacts"]]
        self.contacts: list[ContactEvent] = [
            ContactEvent(
                vehicles=(self.vehicles[int(c["body1"])], self.vehicles[int(c["body2"])]),
                time=float(c["time"]),
                kind=str(c["kind"]),
                reason=None if c.get("reason") is None else str(c["reason"]),
            )
            for c in raw["contacts"]
        ]

    def _index(self, vehicle: Any) -> int:
        name = _name_of(vehicle)
        if name not in self.vehicles:
            raise SceneError(f"no vehicle named {name!r} in this result: {self.vehicles}")
        return self.vehicles.index(name)

    def trajectory(self, vehicle: Any) -> Trajectory:
        """The samples of one vehicle (name or Vehicle)."""
        i = self._index(vehicle)
        return Trajectory(
            t=self.t,
            position=self._position[i],
            orientation=self._orientation[i],
            velocity=self._velocity[i],
            angular_velocity=self._angular_velocity[i],
        )

    def state_at(self, vehicle: Any, time: float) -> dict[str, Array]:
        """A vehicle's recorded sample at exactly ``time`` (a step end, a first overlap or an
        exchange; at an exchange, the state after it): position, orientation, velocity,
        angular_velocity."""
        tr = self.trajectory(vehicle)
        hits = np.flatnonzero(tr.t == time)
        if hits.size == 0:
            raise SceneError(
                f"no sample at t = {time!r} s: samples are step ends, first overlaps and "
                "exchanges (see Result.t)"
            )
        k = int(hits[-1])
        return {
            "position": tr.position[k],
            "orientation": tr.orientation[k],
            "velocity": tr.velocity[k],
            "angular_velocity": tr.angular_velocity[k],
        }

    def vehicle(self, vehicle: Any) -> Vehicle:
        """The Vehicle object (mesh, mass properties, stiffness) of a name."""
        i = self._index(vehicle)
        if self.scene is None:
            raise SceneError("this result has no scene, so no vehicle objects")
        return self.scene.vehicles[i]

    def state(self, vehicle: Any, time: float) -> dict[str, Array]:
        """A vehicle's state at any ``time`` (s) in the run: the last sample at or before it
        carried forward by torque-free motion (exact: nothing else acts between samples).
        At an exchange instant this is the state after the exchange; ask for
        ``impact.time`` minus a hair (or use ``state_before``) for the one before."""
        tr = self.trajectory(vehicle)
        if not tr.t[0] <= time <= tr.t[-1]:
            raise SceneError(f"t = {time!r} s is outside the run [{tr.t[0]}, {tr.t[-1]}] s")
        k = int(np.searchsorted(tr.t, time, side="right")) - 1
        sample = {
            "position": tr.position[k],
            "orientation": tr.orientation[k],
            "velocity": tr.velocity[k],
            "angular_velocity": tr.angular_velocity[k],
        }
        if tr.t[k] == time:
            return sample
        v = self.vehicle(vehicle)
        p, q, vel, w = _core.free_motion(
            v.mass,
            v.inertia,
            sample["position"],
            sample["orientation"],
            sample["velocity"],
            sample["angular_velocity"],
            float(time - tr.t[k]),
        )
        return {
            "position": _frozen(p),
            "orientation": _frozen(q),
            "velocity": _frozen(vel),
            "angular_velocity": _frozen(w),
        }

    def state_before(self, vehicle: Any, impact: Impact) -> dict[str, Array]:
        """A vehicle's state just before an impact's exchange (same pose; the velocities
        before the impulse)."""
        name = impact._check(vehicle)
        after = self.state_at(name, impact.time)
        return {
            "position": after["position"],
            "orientation": after["orientation"],
            "velocity": impact.velocity_before[name],
            "angular_velocity": impact.angular_velocity_before[name],
        }

    def pose(self, vehicle: Any, time: float) -> tuple[Array, Array]:
        """(CG position (3,) m, rotation matrix (3, 3) body -> world) at ``time``."""
        s = self.state(vehicle, time)
        return s["position"], _frozen(rotation_matrix(s["orientation"]))

    def delta_v_body(self, impact: Impact, vehicle: Any) -> Array:
        """An impact's delta-V of a vehicle in its body frame at the exchange (m/s; ISO 8855:
        x forward, y left, z up; event data recorders report lateral +right, i.e. -y)."""
        name = impact._check(vehicle)
        q = self.state_at(name, impact.time)["orientation"]
        return _frozen(rotation_matrix(q).T @ impact.delta_v[name])

    def to_dict(self, trajectories: bool = False) -> dict[str, Any]:
        """A JSON-friendly copy: vehicles, impacts, contacts and, when asked, trajectories
        ({name: {"t": [...], "position": [...], ...}})."""
        out: dict[str, Any] = {
            "vehicles": list(self.vehicles),
            "impacts": [i.to_dict() for i in self.impacts],
            "contacts": [c.to_dict() for c in self.contacts],
        }
        if trajectories:
            out["trajectories"] = {
                name: {k: v.tolist() for k, v in self.trajectory(name)._asdict().items()}
                for name in self.vehicles
            }
        return out

    def __repr__(self) -> str:
        return (
            f"Result(vehicles={self.vehicles}, samples={self.t.size}, "
            f"impacts={len(self.impacts)}, contacts={len(self.contacts)})"
        )
