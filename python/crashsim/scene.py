"""Scenes: vehicles with initial states, contact parameters per pair, and runs.

World frame: right-handed, z up, SI. A vehicle's position is its CG's; heading is the yaw of
its body x axis from world x (rad, counter-clockwise seen from above).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from itertools import combinations
from typing import Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

from crashsim import _core
from crashsim.errors import ParameterError, SceneError
from crashsim.result import Result
from crashsim.vehicle import Vehicle, _finite_vector


def _quaternion_from_matrix(r: NDArray[np.float64]) -> NDArray[np.float64]:
    """(w, x, y, z) of a proper rotation matrix."""
    if r.shape != (3, 3) or not np.allclose(r @ r.T, np.eye(3), atol=1e-9):
        raise ParameterError("orientation matrix must be a 3x3 rotation (orthonormal)")
    if np.linalg.det(r) <= 0.0:
        raise ParameterError("orientation matrix must be a proper rotation (det = +1)")
    t = np.trace(r)
    if t > 0:
        s = math.sqrt(t + 1.0) * 2.0
        q = [0.25 * s, (r[2, 1] - r[1, 2]) / s, (r[0, 2] - r[2, 0]) / s, (r[1, 0] - r[0, 1]) / s]
    else:
        i = int(np.argmax(np.diag(r)))
        j, k = (i + 1) % 3, (i + 2) % 3
        s = math.sqrt(1.0 + r[i, i] - r[j, j] - r[k, k]) * 2.0
        q = [0.0, 0.0, 0.0, 0.0]
        q[0] = (r[k, j] - r[j, k]) / s
        q[1 + i] = 0.25 * s
        q[1 + j] = (r[j, i] + r[i, j]) / s
        q[1 + k] = (r[k, i] + r[i, k]) / s
    return np.asarray(q, dtype=float)


def _orientation(heading: float, orientation: ArrayLike | None) -> NDArray[np.float64]:
    if orientation is None:
        if not math.isfinite(heading):
            raise ParameterError(f"heading = {heading} must be a finite angle in rad")
        return np.array([math.cos(heading / 2.0), 0.0, 0.0, math.sin(heading / 2.0)])
    o = np.asarray(orientation, dtype=float)
    if o.shape == (3, 3):
        return _quaternion_from_matrix(o)
    return _finite_vector(o, "orientation (w, x, y, z)", size=4)


@dataclass
class _Placed:
    vehicle: Vehicle
    position: NDArray[np.float64]
    orientation: NDArray[np.float64]
    velocity: NDArray[np.float64]
    angular_velocity: NDArray[np.float64]


@dataclass
class Scene:
    """Vehicles and contact parameters. Defaults apply to every pair unless `contact` overrides.

    depth_of_penetration (s, [0, 0.060], default 0.030): time from first overlap to the
    exchange. restitution ([0, 1], 0.1) and friction (>= 0, 0.6). restitution_mode: "total"
    (Kudlich-Slibar) or "normal" (Newton/Brach). normal: None (horizontal part of the volume
    normal, tilted by pitch rad), "volume", or a world vector. centroid: None (automatic).
    """

    depth_of_penetration: float = 0.030
    restitution: float = 0.1
    friction: float = 0.6
    restitution_mode: str = "total"
    normal: Any = None
    pitch: float = 0.0
    _placed: list[_Placed] = field(default_factory=list, init=False, repr=False)
    _contacts: dict[tuple[str, str], dict[str, Any]] = field(
        default_factory=dict, init=False, repr=False
    )

    @property
    def vehicles(self) -> list[Vehicle]:
        """The vehicles, in the order added."""
        return [p.vehicle for p in self._placed]

    def _index(self, vehicle: Vehicle | str) -> int:
        name = vehicle if isinstance(vehicle, str) else vehicle.name
        for i, p in enumerate(self._placed):
            if p.vehicle.name == name and (isinstance(vehicle, str) or p.vehicle is vehicle):
                return i
        raise SceneError(f"vehicle {name!r} is not in the scene: add it first")

    def add(
        self,
        vehicle: Vehicle,
        position: ArrayLike,
        heading: float = 0.0,
        velocity: ArrayLike = (0.0, 0.0, 0.0),
        angular_velocity: ArrayLike = (0.0, 0.0, 0.0),
        orientation: ArrayLike | None = None,
    ) -> Scene:
        """Place a vehicle: CG position (m), heading (rad) or a full orientation (quaternion
        (w, x, y, z) or rotation matrix), velocity (m/s) and angular velocity (rad/s), world."""
        if any(p.vehicle.name == vehicle.name for p in self._placed):
            raise SceneError(f"a vehicle named {vehicle.name!r} is already in the scene")
        self._placed.append(
            _Placed(
                vehicle=vehicle,
                position=_finite_vector(position, "position"),
                orientation=_orientation(heading, orientation),
                velocity=_finite_vector(velocity, "velocity"),
                angular_velocity=_finite_vector(angular_velocity, "angular_velocity"),
            )
        )
        return self

    def contact(self, vehicle1: Vehicle | str, vehicle2: Vehicle | str, **params: Any) -> Scene:
        """Parameters of one pair; the normal points from vehicle1 into vehicle2.

        Keys: depth_of_penetration, restitution, friction, restitution_mode, normal, pitch,
        centroid (None; a world point (x, y, z); or (vehicle, (x, y, z)) a point fixed in that
        vehicle's body frame, m from its CG)."""
        allowed = {
            "depth_of_penetration",
            "restitution",
            "friction",
            "restitution_mode",
            "normal",
            "pitch",
            "centroid",
        }
        unknown = set(params) - allowed
        if unknown:
            raise SceneError(
                f"unknown contact parameter(s) {sorted(unknown)}; use {sorted(allowed)}"
            )
        i, j = self._index(vehicle1), self._index(vehicle2)
        if i == j:
            raise SceneError("a contact needs two different vehicles")
        names = (self._placed[i].vehicle.name, self._placed[j].vehicle.name)
        self._contacts.pop((names[1], names[0]), None)
        self._contacts[names] = params
        return self

    def _contact_kwargs(self, params: dict[str, Any], i: int, j: int) -> dict[str, Any]:
        kw: dict[str, Any] = {
            "depth_of_penetration": params.get("depth_of_penetration", self.depth_of_penetration),
            "restitution": params.get("restitution", self.restitution),
            "friction": params.get("friction", self.friction),
            "restitution_mode": params.get("restitution_mode", self.restitution_mode),
            "pitch": params.get("pitch", self.pitch),
        }
        normal = params.get("normal", self.normal)
        if normal is None:
            kw["normal"] = "horizontal"
        elif isinstance(normal, str):
            if normal not in ("horizontal", "volume"):
                raise ParameterError(f"normal = {normal!r}: use None, 'volume' or a vector")
            kw["normal"] = normal
        else:
            kw["normal"] = "vector"
            kw["normal_vector"] = _finite_vector(normal, "normal")
        centroid = params.get("centroid")
        if centroid is None:
            kw["centroid"] = "auto"
        elif (
            isinstance(centroid, tuple)
            and len(centroid) == 2
            and isinstance(centroid[0], Vehicle | str)
        ):
            body = self._index(centroid[0])
            if body not in (i, j):
                raise SceneError("the centroid must be fixed in one of the pair's vehicles")
            kw.update(centroid="body", centroid_body=body)
            kw["centroid_point"] = _finite_vector(centroid[1], "centroid point")
        else:
            kw.update(centroid="world", centroid_point=_finite_vector(centroid, "centroid"))
        for key in ("depth_of_penetration", "restitution", "friction", "pitch"):
            try:
                kw[key] = float(kw[key])
            except (TypeError, ValueError) as e:
                raise ParameterError(f"{key} must be a number, got {kw[key]!r}") from e
        return kw

    def build_world(self) -> _core.World:
        """A fresh engine world holding this scene."""
        if len(self._placed) < 1:
            raise SceneError("the scene has no vehicles: add some with scene.add(...)")
        world = _core.World()
        for p in self._placed:
            world.add_body(
                p.vehicle.shape,
                p.vehicle.mass,
                p.vehicle.inertia,
                p.position,
                p.orientation,
                p.velocity,
                p.angular_velocity,
            )
        names = [p.vehicle.name for p in self._placed]
        for i, j in combinations(range(len(names)), 2):
            if (names[j], names[i]) in self._contacts:
                i, j = j, i
            params = self._contacts.get((names[i], names[j]), {})
            world.set_contact(i, j, **self._contact_kwargs(params, i, j))
        return world

    def run(self, duration: float = 1.0, dt: float = 1e-3) -> Result:
        """Run the scene for `duration` s with steps of at most `dt` s (default 1 ms)."""
        world = self.build_world()
        raw = world.run(float(duration), float(dt))
        return Result(raw, [p.vehicle.name for p in self._placed])
