"""Run results: impacts (one per impulse exchange), trajectories and the contact log.

Everything is SI and world frame: velocities m/s, angular velocities rad/s, impulses N s,
energies J, positions m, quaternions (w, x, y, z) body -> world.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any, NamedTuple

import numpy as np
from numpy.typing import NDArray

from crashsim.errors import SceneError

Array = NDArray[np.float64]


class Trajectory(NamedTuple):
    """One vehicle's samples: times (k,), position (k, 3), orientation (k, 4),
    velocity (k, 3), angular_velocity (k, 3)."""

    t: Array
    position: Array
    orientation: Array
    velocity: Array
    angular_velocity: Array


@dataclass(frozen=True)
class Impact:
    """One impulse exchange between `vehicles[0]` (1) and `vehicles[1]` (2).

    The normal points from 1 into 2; `impulse` acts on 2 and its negative on 1 (N s).
    `first_contact_time` is when the timer started (first overlap, or closing again for a
    secondary exchange); `time` is the exchange instant."""

    vehicles: tuple[str, str]
    first_contact_time: float
    time: float
    depth_of_penetration: float
    secondary: bool
    centroid: Array
    normal: Array
    impulse: Array
    sliding: bool
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

    @property
    def delta_v(self) -> dict[str, Array]:
        """Change of each vehicle's CG velocity (m/s, world)."""
        return {k: self.velocity_after[k] - self.velocity_before[k] for k in self.vehicles}

    @property
    def delta_omega(self) -> dict[str, Array]:
        """Change of each vehicle's angular velocity (rad/s, world)."""
        return {
            k: self.angular_velocity_after[k] - self.angular_velocity_before[k]
            for k in self.vehicles
        }

    @property
    def closing_speed(self) -> float:
        """Normal relative velocity at the centroid before the exchange (m/s, > 0 closing)."""
        return float(self.relative_velocity_before @ self.normal)

    def to_dict(self) -> dict[str, Any]:
        """JSON-friendly copy."""
        out: dict[str, Any] = {}
        for key, value in self.__dict__.items():
            if isinstance(value, np.ndarray):
                out[key] = value.tolist()
            elif isinstance(value, dict):
                out[key] = {k: v.tolist() for k, v in value.items()}
            else:
                out[key] = list(value) if isinstance(value, tuple) else value
        out["delta_v"] = {k: v.tolist() for k, v in self.delta_v.items()}
        out["delta_omega"] = {k: v.tolist() for k, v in self.delta_omega.items()}
        return out


def _impact(raw: dict[str, Any], names: list[str]) -> Impact:
    pair = (names[raw["body1"]], names[raw["body2"]])

    def per_vehicle(rows: Array) -> dict[str, Array]:
        return {pair[0]: rows[0].copy(), pair[1]: rows[1].copy()}

    return Impact(
        vehicles=pair,
        first_contact_time=float(raw["first_contact_time"]),
        time=float(raw["time"]),
        depth_of_penetration=float(raw["depth_of_penetration"]),
        secondary=bool(raw["secondary"]),
        centroid=raw["centroid"],
        normal=raw["normal"],
        impulse=raw["impulse"],
        sliding=bool(raw["sliding"]),
        velocity_before=per_vehicle(raw["velocity_before"]),
        velocity_after=per_vehicle(raw["velocity_after"]),
        angular_velocity_before=per_vehicle(raw["angular_velocity_before"]),
        angular_velocity_after=per_vehicle(raw["angular_velocity_after"]),
        relative_velocity_before=raw["relative_velocity_before"],
        relative_velocity_after=raw["relative_velocity_after"],
        energy_dissipated=float(raw["energy_dissipated"]),
        region_points=raw["region_points"],
        contact_frame=raw["contact_frame"],
        region_min=raw["region_min"],
        region_max=raw["region_max"],
    )


class Result:
    """What a run returns: `impacts`, `contacts` (the event log) and trajectories."""

    def __init__(self, raw: dict[str, Any], names: list[str]) -> None:
        self.vehicles: list[str] = list(names)
        self.t: Array = raw["t"]
        self._raw = raw
        self.impacts: list[Impact] = [_impact(r, names) for r in raw["impacts"]]
        self.contacts: list[dict[str, Any]] = [
            {
                "vehicles": (names[c["body1"]], names[c["body2"]]),
                "time": float(c["time"]),
                "kind": c["kind"],
                "reason": c["reason"],
            }
            for c in raw["contacts"]
        ]

    def trajectory(self, vehicle: Any) -> Trajectory:
        """Samples of one vehicle (name or Vehicle): every step end, first overlap and
        exchange (the state just after it)."""
        name = vehicle if isinstance(vehicle, str) else getattr(vehicle, "name", None)
        if name not in self.vehicles:
            raise SceneError(f"no vehicle named {name!r} in this result: {self.vehicles}")
        i = self.vehicles.index(name)
        r = self._raw
        return Trajectory(
            t=self.t,
            position=r["position"][i],
            orientation=r["orientation"][i],
            velocity=r["velocity"][i],
            angular_velocity=r["angular_velocity"][i],
        )

    def state_at(self, vehicle: Any, time: float) -> dict[str, Array]:
        """The recorded sample of a vehicle at exactly `time` (a step end or an event)."""
        tr = self.trajectory(vehicle)
        hits = np.flatnonzero(tr.t == time)
        if hits.size == 0:
            raise SceneError(f"no sample at t = {time} s; samples are step ends and events")
        k = int(hits[-1])
        return {
            "position": tr.position[k],
            "orientation": tr.orientation[k],
            "velocity": tr.velocity[k],
            "angular_velocity": tr.angular_velocity[k],
        }

    def to_dict(self) -> dict[str, Any]:
        """JSON-friendly summary (impacts and the contact log)."""
        return {
            "vehicles": self.vehicles,
            "impacts": [i.to_dict() for i in self.impacts],
            "contacts": [dict(c, vehicles=list(c["vehicles"])) for c in self.contacts],
        }
