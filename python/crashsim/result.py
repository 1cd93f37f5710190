"""Run results: impacts (one per impulse exchange), trajectories, the contact log and, for a
scene with a ground, the wheels' records, tyre marks and rest positions.

Everything is SI and world frame unless a name says otherwise: positions m, velocities m/s,
angular velocities rad/s, impulses N s, energies J, forces N, times s, quaternions (w, x, y,
z) rotating body-frame vectors into the world. Arrays are read-only.

Bodies are the vehicles (``Result.vehicles``, in the order added) and the fixed obstacles
(``Result.obstacles``, after them): both have trajectories (an obstacle's never changes);
an impact may pair a vehicle with an obstacle (``Impact.obstacle``), which has no delta-V
and an infinite effective mass.
"""

from __future__ import annotations

import math
from collections.abc import Mapping, Sequence
from typing import TYPE_CHECKING, Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

from crashsim import _core
from crashsim.errors import ParameterError, SceneError
from crashsim.joints import JointEvent, JointRecord
from crashsim.records import (
    ContactEvent,
    Impact,
    RestState,
    SeparationState,
    Trajectory,
    WheelRecord,
    _frozen,
    _name_of,
    rotation_matrix,
)
from crashsim.small_linalg import by_libm, norm

if TYPE_CHECKING:
    from crashsim.vehicles.vehicle import Vehicle

__all__ = [
    "ContactEvent",
    "Impact",
    "RestState",
    "Result",
    "SeparationState",
    "Trajectory",
    "WheelRecord",
]

Array = NDArray[np.float64]


def _heading(q: Array) -> float:
    """Yaw of the body x axis from world x (rad), counter-clockwise seen from above:
    atan2(R[1][0], R[0][0]) of the unit quaternion (w, x, y, z), in plain float arithmetic
    (the core's `heading`, events.rs, is the same bits: a batch's heading columns equal it)."""
    w, x, y, z = (float(c) for c in q)
    return math.atan2(2.0 * (x * y + w * z), 1.0 - 2.0 * (y * y + z * z))


def _path_length(points: Array) -> float:
    return float(np.sum(np.linalg.norm(np.diff(points, axis=0), axis=1))) if len(points) else 0.0


def _slerp(q0: Array, q1: Array, s: Array) -> Array:
    """Spherical linear interpolation of unit quaternions (shortest arc), row by row: q0, q1
    (m, 4), s (m,) in [0, 1]."""
    q0 = q0 / np.linalg.norm(q0, axis=1, keepdims=True)
    q1 = q1 / np.linalg.norm(q1, axis=1, keepdims=True)
    d = np.einsum("ij,ij->i", q0, q1)
    flip = d < 0.0
    q1 = np.where(flip[:, None], -q1, q1)
    d = np.where(flip, -d, d)
    near = d > 1.0 - 1e-12  # nearly the same rotation: linear, normalised
    linear = q0 + s[:, None] * (q1 - q0)
    linear /= np.linalg.norm(linear, axis=1, keepdims=True)
    theta = by_libm(math.acos, np.minimum(1.0, d))
    sin = np.where(near, 1.0, by_libm(math.sin, theta))  # unused where near
    arc = (
        by_libm(math.sin, (1.0 - s) * theta)[:, None] * q0
        + by_libm(math.sin, s * theta)[:, None] * q1
    ) / sin[:, None]
    return np.where(near[:, None], linear, arc)


class Result:
    """What a run returns: ``impacts`` (Impact list, in time order), ``contacts`` (the
    ContactEvent log), ``vehicles`` (names in the order added), ``obstacles`` (the fixed
    obstacles' names; ``bodies`` = vehicles then obstacles, the engine's order), ``t``
    (sample times, s), per-body trajectories, ``scene`` (the Scene that ran, None for a bare
    result), the run's ``duration``, largest step ``dt`` and ``record_interval`` (the spacing
    of the kept step samples) (s; None when not known), and ``on_ground`` (True when the
    scene had a ground: then :meth:`wheels`, :meth:`wheel_path`, :meth:`tyre_marks` and
    :meth:`rest` describe the run-out)."""

    def __init__(
        self,
        raw: dict[str, Any],
        names: list[str],
        scene: Any = None,  # the Scene that ran (not imported: a scene imports this module)
        duration: float | None = None,
        dt: float | None = None,
        record_interval: float | None = None,
        obstacles: Sequence[str] = (),
        wheel_names: Mapping[str, Sequence[str]] | None = None,
        on_ground: bool = False,
        joints: Sequence[Any] = (),  # crashsim.joints.Joint (not imported: plain data here)
    ) -> None:
        self.bodies: list[str] = list(names)
        self.obstacles: list[str] = list(obstacles)
        self.vehicles: list[str] = [n for n in names if n not in self.obstacles]
        self.scene = scene
        self.duration = duration
        self.dt = dt
        # Interval between kept step samples (s); events are always kept.
        self.record_interval = record_interval
        self.on_ground = bool(on_ground)
        self.t: Array = _frozen(raw["t"])
        self._position = _frozen(raw["position"])  # (n_bodies, k, 3)
        self._orientation = _frozen(raw["orientation"])  # (n_bodies, k, 4)
        self._velocity = _frozen(raw["velocity"])
        self._angular_velocity = _frozen(raw["angular_velocity"])
        self.impacts: list[Impact] = [
            Impact.from_core(r, self.bodies, self.obstacles) for r in raw["impacts"]
        ]
        self.contacts: list[ContactEvent] = [
            ContactEvent.from_core(c, self.bodies) for c in raw["contacts"]
        ]
        # Joints: the engine's rows are joint after joint, in the order made.
        self.joints: dict[str, JointRecord] = {}
        self.joint_events: list[JointEvent] = []
        for k, joint in enumerate(joints):
            self.joints[joint.name] = JointRecord(
                name=joint.name,
                kind=joint.kind,
                vehicles=tuple(joint.vehicles),
                angle_names=joint.angle_names,
                t=self.t,
                angles=_frozen(raw["joint_angles"][k]),
                force=_frozen(raw["joint_force"][k]),
                torque=_frozen(raw["joint_torque"][k]),
            )
        for e in raw.get("joint_events", []):
            joint = joints[int(e["joint"])]
            self.joint_events.append(
                JointEvent(
                    joint=joint.name,
                    angle=str(joint.core.limits[int(e["limit"])][0]),
                    time=float(e["time"]),
                    rate=float(e["rate"]),
                )
            )
        # Wheels: the engine's rows are body after body.
        self._wheels: dict[str, WheelRecord] = {}
        counts = [int(c) for c in raw.get("wheel_counts", [])]
        names_of = dict(wheel_names or {})
        row = 0
        for i, n in enumerate(counts):
            if n == 0:
                continue
            name = self.bodies[i]
            wheel = tuple(names_of.get(name, [f"wheel_{k}" for k in range(n)]))
            sel = slice(row, row + n)
            self._wheels[name] = WheelRecord(
                names=wheel,
                t=self.t,
                contact=_frozen(raw["wheel_contact"][sel]),
                load=_frozen(raw["wheel_load"][sel]),
                force=_frozen(raw["wheel_force"][sel]),
                sliding=_frozen_bool(raw["wheel_sliding"][sel]),
                steer=_frozen(raw["wheel_steer"][sel]),
            )
            row += n
        rest = list(raw.get("rest", [None] * len(self.bodies)))
        self._rest_time: dict[str, float | None] = {
            name: None if r is None else float(r)
            for name, r in zip(self.bodies, rest, strict=False)
        }

    def _index(self, vehicle: Any) -> int:
        name = _name_of(vehicle)
        if name not in self.bodies:
            raise SceneError(f"no vehicle named {name!r} in this result: {self.vehicles}")
        return self.bodies.index(name)

    def is_obstacle(self, name: Any) -> bool:
        """True when the named body is a fixed obstacle (SceneError for an unknown name)."""
        self._index(name)
        return _name_of(name) in self.obstacles

    def _vehicle_name(self, vehicle: Any) -> str:
        name = _name_of(vehicle)
        self._index(name)
        if name in self.obstacles:
            raise SceneError(f"{name!r} is a fixed obstacle, not a vehicle")
        return name

    def trajectory(self, vehicle: Any) -> Trajectory:
        """The samples of one vehicle or obstacle (name or object)."""
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
        """The Vehicle object (mesh, mass properties, stiffness, wheels) of a name."""
        name = self._vehicle_name(vehicle)
        if self.scene is None:
            raise SceneError("this result has no scene, so no vehicle objects")
        return self.scene.vehicles[self.vehicles.index(name)]

    def obstacle(self, name: Any) -> Any:
        """The Obstacle object (mesh, stiffness) of a name."""
        key = _name_of(name)
        if key not in self.obstacles:
            raise SceneError(f"no obstacle named {key!r} in this result: {self.obstacles}")
        if self.scene is None:
            raise SceneError("this result has no scene, so no obstacle objects")
        return self.scene.obstacles[self.obstacles.index(key)]

    def state(self, vehicle: Any, time: float) -> dict[str, Array]:
        """A vehicle's state at any ``time`` (s) in the run.

        Without a ground (``on_ground`` False): the last sample at or before it carried
        forward by torque-free motion (exact: nothing else acts between samples). With a
        ground, forces act between samples, so the state is interpolated between the two
        samples around ``time``: cubic Hermite on the position with the sampled velocities
        as its slopes (the velocity just before an exchange at the later sample), linear on
        the velocities, spherical linear (slerp) on the orientation
        and linear on the angular velocity (an approximation whose error shrinks with the
        sample spacing, ``record_interval``). At an exchange instant this is the state after
        the exchange; ask for ``impact.time`` minus a hair (or use ``state_before``) for the
        one before. :meth:`states` gives many times at once."""
        many = self.states(vehicle, [time])
        return {key: _frozen(value[0]) for key, value in many.items()}

    def states(self, vehicle: Any, times: ArrayLike) -> dict[str, Array]:
        """A vehicle's states at many ``times`` (s, each in the run), as :meth:`state` gives
        each: position (m, 3), orientation (m, 4), velocity (m, 3), angular_velocity (m, 3)
        for m times, in their order; its cost grows with the times asked, not the samples."""
        tr = self.trajectory(vehicle)
        ts = np.asarray(times, dtype=np.float64).reshape(-1)
        outside = ts[~((tr.t[0] <= ts) & (ts <= tr.t[-1]))]
        if outside.size:
            time = outside[0].item()
            raise SceneError(f"t = {time!r} s is outside the run [{tr.t[0]}, {tr.t[-1]}] s")
        k = np.searchsorted(tr.t, ts, side="right") - 1
        out = {
            "position": tr.position[k],
            "orientation": tr.orientation[k],
            "velocity": tr.velocity[k],
            "angular_velocity": tr.angular_velocity[k],
        }
        between = np.flatnonzero(tr.t[k] != ts)
        if between.size and not self.is_obstacle(vehicle):
            kb = k[between]
            if self.on_ground:
                part = self._interpolated(tr, kb, ts[between], _name_of(vehicle))
            else:
                part = self._carried(vehicle, tr, kb, ts[between])
            for key, value in part.items():
                out[key][between] = value
        return {key: _frozen(value) for key, value in out.items()}

    def _carried(
        self, vehicle: Any, tr: Trajectory, k: NDArray[np.intp], times: Array
    ) -> dict[str, Array]:
        """Samples k carried forward to ``times`` by torque-free motion."""
        v = self.vehicle(vehicle)
        rows = [
            _core.free_motion(
                v.mass,
                v.inertia,
                tr.position[j],
                tr.orientation[j],
                tr.velocity[j],
                tr.angular_velocity[j],
                float(t - tr.t[j]),
            )
            for j, t in zip(k, times, strict=True)
        ]
        keys = ("position", "orientation", "velocity", "angular_velocity")
        return {key: np.array([row[i] for row in rows]) for i, key in enumerate(keys)}

    def _interpolated(
        self, tr: Trajectory, k: NDArray[np.intp], times: Array, name: str
    ) -> dict[str, Array]:
        """Between samples k and k + 1 (each time its own k): Hermite position, slerp
        orientation, linear rates, the rates at k + 1 those just before an exchange there
        (its sample holds the rates after it)."""
        t0, t1 = tr.t[k], tr.t[k + 1]
        h = t1 - t0
        s = (times - t0) / h
        # s * s * s, not s**3: numpy's power is its SIMD or the C library's, by the CPU
        s2 = s * s
        s3 = s2 * s
        h00, h10 = 2 * s3 - 3 * s2 + 1, s3 - 2 * s2 + s
        h01, h11 = -2 * s3 + 3 * s2, s3 - s2
        p0, p1 = tr.position[k], tr.position[k + 1]
        v0, v1 = tr.velocity[k], tr.velocity[k + 1].copy()
        w0, w1 = tr.angular_velocity[k], tr.angular_velocity[k + 1].copy()
        # the rates just before an exchange at k + 1 (the first impact of the vehicle there)
        for imp in reversed(self.impacts):
            if name in imp.delta_v:
                hit = t1 == imp.time
                v1[hit] = imp.velocity_before[name]
                w1[hit] = imp.angular_velocity_before[name]
        col = (slice(None), None)
        return {
            "position": h00[col] * p0 + (h10 * h)[col] * v0 + h01[col] * p1 + (h11 * h)[col] * v1,
            "orientation": _slerp(tr.orientation[k], tr.orientation[k + 1], s),
            "velocity": (1 - s)[col] * v0 + s[col] * v1,
            "angular_velocity": (1 - s)[col] * w0 + s[col] * w1,
        }

    def state_before(self, vehicle: Any, impact: Impact) -> dict[str, Array]:
        """A vehicle's state just before an impact's exchange (same pose; the velocities
        before the impulse)."""
        name = impact._check(vehicle)
        after = self.state_at(name, impact.time)
        if name == impact.obstacle:
            return after
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

    def heading(self, vehicle: Any, time: float) -> float:
        """Yaw of the body x axis from world x at ``time`` (rad, counter-clockwise seen from
        above, in (-pi, pi])."""
        return _heading(self.state(vehicle, time)["orientation"])

    def delta_v_body(self, impact: Impact, vehicle: Any) -> Array:
        """An impact's delta-V of a vehicle in its body frame at the exchange (m/s; ISO 8855:
        x forward, y left, z up; event data recorders report lateral +right, i.e. -y)."""
        name = impact._check(vehicle)
        if name == impact.obstacle:
            raise SceneError(f"{name!r} is a fixed obstacle: it has no delta-V")
        return impact.delta_v_body[name]

    # -- the run-out (scenes with a ground) -----------------------------------------------

    def wheels(self, vehicle: Any) -> WheelRecord:
        """A vehicle's wheel records (see WheelRecord). SceneError for a vehicle without
        wheels or a run without ground."""
        name = self._vehicle_name(vehicle)
        if name not in self._wheels:
            why = "the scene had no ground" if not self.on_ground else "it has no wheels"
            raise SceneError(f"vehicle {name!r} has no wheel records: {why}")
        return self._wheels[name]

    def _wheel(self, record: WheelRecord, wheel: Any) -> int:
        from crashsim.vehicles.wheels import wheel_index

        try:
            return wheel_index(record.names, wheel)
        except ParameterError as e:
            raise SceneError(str(e)) from None

    def wheel_path(self, vehicle: Any, wheel: Any) -> Array:
        """(k, 3) where one wheel's tyre met the ground at each sample time ``t`` (m, world):
        the path of its contact patch. ``wheel``: a name ("front_left"), a short name ("FL")
        or an index."""
        record = self.wheels(vehicle)
        return record.contact[self._wheel(record, wheel)]

    def wheel_centres(self, vehicle: Any) -> Array:
        """(n, k, 3) where each wheel's centre is at the sample times ``t`` (m, world), in
        the wheels' order: the engine's wheel is massless and its tyre follows the ground,
        so while the spring can reach the ground the centre is the tyre radius above the
        contact point along the ground's normal (the suspension's travel shows as the
        centre moving against the body); a wheel in the air hangs at the spring's full
        extension (static load / rate below its static place, along the body's z). At static ride
        height it is the body-frame centre ``Wheels.centers`` posed with the body."""
        name = self._vehicle_name(vehicle)
        record = self.wheels(name)
        v = self.vehicle(name)
        if v.wheels is None:  # pragma: no cover - a wheel record comes from wheels
            raise SceneError(f"vehicle {name!r} has no wheels")
        spec = v.wheels.spec(v.mass)
        body = np.asarray(spec["centers"], dtype=np.float64)  # (n, 3) body frame, m
        radius = np.asarray(spec["radii"], dtype=np.float64)[:, None, None]  # (n, 1, 1) m
        droop = (  # m: the spring's extension from static ride height to no load
            np.asarray(spec["static_loads"], dtype=np.float64)
            / np.asarray(spec["spring_rates"], dtype=np.float64)
        )[:, None, None]
        tr = self.trajectory(name)
        rot = rotation_matrix(tr.orientation)  # (k, 3, 3)
        hub = tr.position[None, :, :] + np.einsum("kij,nj->nki", rot, body)  # (n, k, 3)
        d = hub - record.contact  # the ground's normal times the hub's height above it
        h = np.linalg.norm(d, axis=2)
        # the ground's normal points up (+z): d / |d|, turned up when the hub is below it
        normal = np.where((h > 1e-12)[..., None], d / np.where(h > 1e-12, h, 1.0)[..., None], 0.0)
        normal[h <= 1e-12] = (0.0, 0.0, 1.0)
        below = normal[..., 2] < 0.0
        normal[below] *= -1.0
        height = np.where(below, -h, h)[..., None]  # the hub's signed height above the ground
        touching = height <= radius + droop
        hanging = hub - rot[None, :, :, 2] * droop  # along the body's z, the spring's axis
        out = np.where(touching, record.contact + normal * radius, hanging)
        return _frozen(out)

    def wheel_steer(self, vehicle: Any) -> Array:
        """(n, k) each wheel's road-wheel steering angle at the sample times ``t`` (rad, + to
        the left, about the body z axis), as the engine ran it: the driver's input through
        the steering linkage (Ackermann geometry) or the wheel's own table; 0 on wheels that
        do not steer."""
        return self.wheels(vehicle).steer

    def tyre_marks(self, vehicle: Any, min_length: float = 0.0) -> dict[str, list[Array]]:
        """The stretches where each wheel's contact patch slid at the friction limit (skid
        and yaw marks): {wheel name: [polyline (m, 3) of contact points (m, world), ...]},
        each polyline the consecutive samples of one stretch (at least 2 points and at least
        ``min_length`` m long), in time order; wheels without marks map to []."""
        record = self.wheels(vehicle)
        out: dict[str, list[Array]] = {}
        for w, name in enumerate(record.names):
            marks: list[Array] = []
            sliding = np.asarray(record.sliding[w], dtype=bool)
            edges = np.flatnonzero(np.diff(np.r_[0, sliding.astype(np.int8), 0]))
            for a, b in zip(edges[::2], edges[1::2], strict=True):
                if b - a < 2:
                    continue
                line = record.contact[w, a:b]
                if _path_length(line) >= min_length:
                    marks.append(_frozen(line))
            out[name] = marks
        return out

    def rest(self, vehicle: Any) -> RestState | None:
        """Where and when a vehicle came to rest (RestState), or None when it was still
        moving at the end of the run (or the scene had no ground)."""
        name = self._vehicle_name(vehicle)
        time = self._rest_time.get(name)
        if time is None:
            return None
        tr = self.trajectory(name)
        last = None
        for imp in self.impacts:
            if name in imp.vehicles:
                last = imp.time
        start = tr.position[0]
        end = tr.position[-1]
        if last is None:
            from_exchange = displaced = None
        else:
            k = int(np.searchsorted(tr.t, last, side="left"))
            from_exchange = _path_length(tr.position[k:])
            displaced = float(norm(end - tr.position[k]))
        return RestState(
            time=time,
            position=end,
            heading=_heading(tr.orientation[-1]),
            distance=_path_length(tr.position),
            displacement=float(norm(end - start)),
            last_exchange=last,
            distance_from_exchange=from_exchange,
            displacement_from_exchange=displaced,
        )

    def separations(self, vehicle: Any) -> list[SeparationState]:
        """A vehicle's state at every separation (a pair it belongs to stops overlapping),
        in time order: the speeds at separation."""
        name = self._vehicle_name(vehicle)
        out = []
        for c in self.contacts:
            if c.kind != "separation" or name not in c.vehicles:
                continue
            s = self.state(name, c.time)
            other = c.vehicles[1] if c.vehicles[0] == name else c.vehicles[0]
            out.append(
                SeparationState(
                    time=c.time,
                    other=other,
                    velocity=s["velocity"],
                    speed=float(norm(s["velocity"])),
                    angular_velocity=s["angular_velocity"],
                    heading=_heading(s["orientation"]),
                )
            )
        return out

    def to_dict(self, trajectories: bool = False) -> dict[str, Any]:
        """A JSON-friendly copy: vehicles, impacts, contacts, obstacles (when there are any),
        rest states (runs on the ground) and, when asked, trajectories ({name: {"t": [...],
        "position": [...], ...}})."""
        out: dict[str, Any] = {
            "vehicles": list(self.vehicles),
            "impacts": [i.to_dict() for i in self.impacts],
            "contacts": [c.to_dict() for c in self.contacts],
        }
        if self.obstacles:
            out["obstacles"] = list(self.obstacles)
        if self.on_ground:
            rest: dict[str, Any] = {}
            for name in self.vehicles:
                r = self.rest(name)
                rest[name] = (
                    None
                    if r is None
                    else {
                        k: v.tolist() if isinstance(v, np.ndarray) else v
                        for k, v in r._asdict().items()
                    }
                )
            out["rest"] = rest
        if trajectories:
            out["trajectories"] = {
                name: {k: v.tolist() for k, v in self.trajectory(name)._asdict().items()}
                for name in self.vehicles
            }
        return out

    def __repr__(self) -> str:
        extra = f", obstacles={self.obstacles}" if self.obstacles else ""
        return (
            f"Result(vehicles={self.vehicles}{extra}, samples={self.t.size}, "
            f"impacts={len(self.impacts)}, contacts={len(self.contacts)})"
        )


def _frozen_bool(a: Any) -> NDArray[np.bool_]:
    out = np.array(a, dtype=bool)
    out.setflags(write=False)
    return out
