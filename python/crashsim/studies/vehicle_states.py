"""What a study's vehicle paths change in the variants' initial states
(crashsim.studies.paths.overrides): the base states of the scene's vehicles and, for each
vehicle, its mass, position, heading, direction of travel, speed, velocity and yaw rate.

World frame, z up; quaternions (w, x, y, z) from body to world; SI units (m, rad, m/s,
rad/s, kg). Arrays are indexed [variant, vehicle, ...] as run_batch's overrides are.
"""

from __future__ import annotations

import math
from collections.abc import Iterable, Mapping
from typing import Any

import numpy as np
from numpy.typing import NDArray

Array = NDArray[np.float64]

STATE_KEYS = ("position", "orientation", "velocity", "angular_velocity", "mass")
"""The override arrays of the vehicles' initial states, in the order they are made."""


def _yaw(q: Array) -> float:
    """Yaw of the body x axis from world x (rad) of a quaternion (w, x, y, z)."""
    w, x, y, z = (float(c) for c in q)
    return math.atan2(2.0 * (w * z + x * y), 1.0 - 2.0 * (y * y + z * z))


def _rz(angle: float) -> Array:
    c, s = math.cos(angle), math.sin(angle)
    return np.array([[c, -s, 0.0], [s, c, 0.0], [0.0, 0.0, 1.0]])


def _qmul(a: Array, b: Array) -> Array:
    aw, ax, ay, az = a
    bw, bx, by, bz = b
    return np.array(
        [
            aw * bw - ax * bx - ay * by - az * bz,
            aw * bx + ax * bw + ay * bz - az * by,
            aw * by - ax * bz + ay * bw + az * bx,
            aw * bz + ax * by - ay * bx + az * bw,
        ]
    )


def _body_x(q: Array) -> Array:
    w, x, y, z = (float(c) for c in q)
    return np.array([1 - 2 * (y * y + z * z), 2 * (x * y + w * z), 2 * (x * z - w * y)])


def _state_keys(parameters: Iterable[str]) -> set[str]:
    """The state arrays that the vehicle parameters named change (a heading turns the
    orientation, the velocity and the angular velocity)."""
    state_keys = set()
    for parameter in parameters:
        if parameter == "mass":
            state_keys.add("mass")
        elif parameter in ("position_x", "position_y"):
            state_keys.add("position")
        elif parameter == "heading":
            state_keys.update(("orientation", "velocity", "angular_velocity"))
        elif parameter == "yaw_rate":
            state_keys.add("angular_velocity")
        else:
            state_keys.add("velocity")
    return state_keys


def _base_states(placements: Iterable[Any]) -> dict[str, Array]:
    """The scene's vehicles' initial states, stacked: [vehicle, ...]."""
    placements = list(placements)
    return {
        "position": np.stack([p.position for p in placements]),
        "orientation": np.stack([p.orientation for p in placements]),
        "velocity": np.stack([p.velocity for p in placements]),
        "angular_velocity": np.stack([p.angular_velocity for p in placements]),
        "mass": np.array([p.vehicle.mass for p in placements], dtype=np.float64),
    }


def _set_vehicle_state(
    out: dict[str, Array],
    j: int,
    ps: Mapping[str, Array],
    base: Mapping[str, Array],
    count: int,
    ground: Any,
) -> None:
    """Vehicle ``j``'s states in ``out`` from its paths' values ``ps`` {parameter: (count,)},
    in this order: mass, position, heading, direction, speed, velocity components, yaw
    rate (each later one acting on what the earlier ones set)."""
    p0 = base["position"][j]
    q0 = base["orientation"][j]
    if "mass" in ps:
        out["mass"][:, j] = ps["mass"]
    if "position_x" in ps or "position_y" in ps:
        _set_position(out, j, ps, p0, count, ground)
    if "heading" in ps:
        _set_heading(out, j, ps["heading"], base, q0)
    if "direction" in ps:
        for i, d in enumerate(ps["direction"]):
            vel = out["velocity"][i, j]
            s = math.hypot(vel[0], vel[1])
            out["velocity"][i, j, :2] = (s * math.cos(d), s * math.sin(d))
    if "speed" in ps:
        for i, s in enumerate(ps["speed"]):
            vel = out["velocity"][i, j]
            size = float(np.linalg.norm(vel))
            if size > 0.0:
                out["velocity"][i, j] = vel * (float(s) / size)
            else:
                q = out["orientation"][i, j] if "orientation" in out else q0
                out["velocity"][i, j] = float(s) * _body_x(q)
    if "velocity_x" in ps:
        out["velocity"][:, j, 0] = ps["velocity_x"]
    if "velocity_y" in ps:
        out["velocity"][:, j, 1] = ps["velocity_y"]
    if "yaw_rate" in ps:
        out["angular_velocity"][:, j, 2] = ps["yaw_rate"]


def _set_position(
    out: dict[str, Array], j: int, ps: Mapping[str, Array], p0: Array, count: int, ground: Any
) -> None:
    """Vehicle ``j``'s CG x and y (m, world; the base's where not given); on a terrain its
    height moves with the ground under the CG (NaN off the terrain: that variant fails)."""
    xs = ps.get("position_x", np.full(count, p0[0]))
    ys = ps.get("position_y", np.full(count, p0[1]))
    out["position"][:, j, 0] = xs
    out["position"][:, j, 1] = ys
    if ground is not None and ground.terrain is not None:
        h0 = ground.height_at(p0[0], p0[1])
        for i in range(count):
            h = ground.height_at(xs[i], ys[i])
            if h is None or h0 is None:
                h = math.nan  # off the terrain: that variant fails (non-finite z)
            out["position"][i, j, 2] = p0[2] + (h - (h0 or 0.0))


def _set_heading(
    out: dict[str, Array], j: int, headings: Array, base: Mapping[str, Array], q0: Array
) -> None:
    """Vehicle ``j`` turned about the vertical through its CG to each heading (rad from
    world x), its velocity and angular velocity turned with it."""
    h0 = _yaw(q0)
    level = q0[1] == 0.0 and q0[2] == 0.0
    for i, h in enumerate(headings):
        turn = float(h) - h0
        rz = _rz(turn)
        if level:  # exactly what Scene.add(heading=h) gives
            out["orientation"][i, j] = [math.cos(h / 2.0), 0.0, 0.0, math.sin(h / 2.0)]
        else:
            dq = np.array([math.cos(turn / 2.0), 0.0, 0.0, math.sin(turn / 2.0)])
            out["orientation"][i, j] = _qmul(dq, q0)
        if turn != 0.0:
            out["velocity"][i, j] = rz @ base["velocity"][j]
            out["angular_velocity"][i, j] = rz @ base["angular_velocity"][j]
