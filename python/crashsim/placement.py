"""Where a scene's bodies start: initial states of vehicles and obstacles (crashsim.Scene).

World frame: right-handed, z up, SI (m, s, rad). A vehicle's position is its CG's; heading is
the yaw of its body x axis from world x (rad, counter-clockwise seen from above); orientations
are quaternions (w, x, y, z) rotating body-frame vectors into the world. A body given by (x, y)
only stands on the ground there: at its static height, and on a terrain a vehicle on wheels is
tilted to the plane fitted through the ground under its wheels.
"""

from __future__ import annotations

import dataclasses
import math
from dataclasses import dataclass
from typing import Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

from crashsim import _core
from crashsim.environment.ground import Ground
from crashsim.environment.obstacles import Obstacle
from crashsim.errors import ParameterError, SceneError
from crashsim.records import rotation_matrix
from crashsim.small_linalg import matmul, norm, rotation_about
from crashsim.vehicles.checks import _as_float, _read_only
from crashsim.vehicles.inputs import DriverInputs
from crashsim.vehicles.vehicle import Vehicle
from crashsim.vehicles.wheels import Wheels

Array = NDArray[np.float64]



def _quaternion_from_matrix(r: Array) -> Array:
    """(w, x, y, z) of a proper rotation matrix (columns: body axes in world)."""
    if not np.all(np.isfinite(r)) or not np.allclose(r @ r.T, np.eye(3), rtol=0.0, atol=1e-9):
        raise ParameterError(
            "the orientation matrix is not orthonormal: give a 3x3 rotation matrix "
            "(columns are the body x, y, z axes in world coordinates)"
        )
    if np.linalg.det(r) <= 0.0:
        raise ParameterError("the orientation matrix is a reflection (det = -1): give a rotation")
    t = float(np.trace(r))
    if t > 0.0:
        s = 2.0 * math.sqrt(t + 1.0)
        q = [0.25 * s, (r[2, 1] - r[1, 2]) / s, (r[0, 2] - r[2, 0]) / s, (r[1, 0] - r[0, 1]) / s]
    else:  # largest diagonal element first, for accuracy
        i = int(np.argmax(np.diag(r)))
        j, k = (i + 1) % 3, (i + 2) % 3
        s = 2.0 * math.sqrt(1.0 + r[i, i] - r[j, j] - r[k, k])
        q = [0.0, 0.0, 0.0, 0.0]
        q[0] = (r[k, j] - r[j, k]) / s
        q[1 + i] = 0.25 * s
        q[1 + j] = (r[j, i] + r[i, j]) / s
        q[1 + k] = (r[k, i] + r[i, k]) / s
    return np.asarray(q, dtype=np.float64)


def _in_body(frame: tuple[Array, Array], placement: Placement) -> tuple[Array, Array]:
    """A world frame (anchor, m; axes, quaternion w, x, y, z) in the body frame of a placed
    vehicle: what a joint keeps of it."""
    anchor, axes = frame
    rot = rotation_matrix(placement.orientation)
    local = _quaternion_from_matrix(matmul(rot.T, rotation_matrix(axes)))
    return matmul(rot.T, anchor - placement.position), local


def _orientation(heading: float | None, orientation: ArrayLike | None) -> Any:
    """The quaternion (w, x, y, z) for a heading (rad about world z) or a full orientation
    (quaternion or 3x3 rotation matrix). Quaternion checks are the engine's."""
    if orientation is None:
        h = 0.0 if heading is None else _as_float(heading, "heading", "rad")
        if not math.isfinite(h):
            raise ParameterError(f"heading = {h} is invalid: give a finite angle in rad")
        return np.array([math.cos(h / 2.0), 0.0, 0.0, math.sin(h / 2.0)])
    if heading is not None:
        raise ParameterError("give heading or orientation, not both")
    try:
        o = np.asarray(orientation, dtype=np.float64)
    except (TypeError, ValueError):
        return orientation  # the engine says what it expected
    return _quaternion_from_matrix(o) if o.shape == (3, 3) else o


def _position(position: ArrayLike, orientation: ArrayLike | None) -> tuple[Any, bool]:
    """(position, True) with z = 0 for now when only (x, y) is given (the caller puts it on
    the ground); the position as given otherwise (the engine checks it)."""
    try:
        p = np.asarray(position, dtype=np.float64).reshape(-1)
    except (TypeError, ValueError):
        return position, False
    if p.size == 2:
        if orientation is not None:
            raise ParameterError(
                "with an orientation give the position's x, y and z (m): only a heading "
                "leaves z to the ground"
            )
        return np.array([p[0], p[1], 0.0]), True
    return position, False


@dataclass(frozen=True)
class Placement:
    """A vehicle and its initial state (world frame, SI), as Scene.add placed it
    (Scene.placements); a frozen record, read-only arrays."""

    vehicle: Vehicle
    position: Array  # CG, m
    orientation: Array  # (w, x, y, z), body -> world
    velocity: Array  # CG, m/s
    angular_velocity: Array  # rad/s
    inputs: DriverInputs | None = None
    # Given as (x, y): z is the CG's static height above the ground there (re-read when the
    # scene's ground changes; without a ground the model frame's ground on z = 0).
    z_from_ground: bool = False
    # The heading-only orientation and the (x, y) given (a vehicle on wheels on a terrain is
    # tilted to it, which moves its CG a little off (x, y)).
    level: Array | None = None
    anchor: tuple[float, float] | None = None


# The class's name until 2026-11-27: pickles made before name it.
_Placement = Placement


@dataclass(frozen=True)
class _ObstaclePlacement:
    """An obstacle and its pose (world frame, SI)."""

    obstacle: Obstacle
    position: Array  # the obstacle frame's origin, m
    orientation: Array  # (w, x, y, z)
    z_from_ground: bool = False


def _static_height(vehicle: Vehicle) -> float:
    """The CG's height above level ground at static ride height (m): its wheels', else the
    model frame's (ground at z = 0)."""
    w = vehicle.wheels
    if w is None:
        return float(vehicle.cg[2])
    if w.cg_height is not None:
        return float(w.cg_height)
    return float(np.mean(w.radii - w.centers[:, 2]))


def _check_state(position: Any, orientation: Any, velocity: Any, angular_velocity: Any) -> None:
    """The engine's checks of an initial state (ParameterError naming the bad input)."""
    _core.check_state(position, orientation, velocity, angular_velocity)


def _ground_height(ground: Ground | None, x: float, y: float, what: str) -> float:
    """The ground's height at (x, y) (0 without a ground); SceneError off the terrain."""
    if ground is None:
        return 0.0
    h = ground.height_at(x, y)
    if h is None:
        raise SceneError(
            f"{what} at ({x:.2f}, {y:.2f}) m has no ground under it: the terrain does not "
            "reach there (extend it, or place it on the terrain)"
        )
    return h


def _resting(ground: Ground | None, p: Placement) -> Placement:
    """p with its CG at its static height above the ground at its (x, y); a vehicle on
    wheels on a terrain is also tilted so its wheels stand on the plane fitted through
    the terrain's heights under them."""
    x, y = (float(p.position[0]), float(p.position[1])) if p.anchor is None else p.anchor
    what = f"vehicle {p.vehicle.name!r}"
    level = p.orientation if p.level is None else p.level
    wheels = p.vehicle.wheels
    h = _static_height(p.vehicle)
    if ground is None or ground.terrain is None or wheels is None:
        z = _ground_height(ground, x, y, what)
        return dataclasses.replace(
            p,
            position=_read_only([x, y, z + h]),
            orientation=level,
            level=level,
            anchor=(x, y),
        )
    yaw = rotation_matrix(level)
    feet = np.array([x, y]) + matmul(wheels.contact_points()[:, :2], yaw[:2, :2].T)
    heights = []
    for k, (fx, fy) in enumerate(feet):
        height = ground.height_at(fx, fy)
        if height is None:
            raise SceneError(
                f"{what} wheel {wheels.names[k]!r} at ({fx:.2f}, {fy:.2f}) m has no ground "
                "under it: the terrain does not reach there (extend it, or place the "
                "vehicle on it)"
            )
        heights.append(height)
    b, c, a = _plane_through(feet, heights)
    n = np.array([-b, -c, 1.0]) / math.sqrt(b * b + c * c + 1.0)
    axis = np.cross([0.0, 0.0, 1.0], n)
    sin, cos = float(norm(axis)), float(n[2])
    tilt = np.eye(3)
    if sin > 0.0:
        tilt = rotation_about(axis / sin, sin, cos)
    q = _quaternion_from_matrix(matmul(tilt, yaw))
    cg = np.array([x, y, a + b * x + c * y]) + h * n
    return dataclasses.replace(
        p, position=_read_only(cg), orientation=_read_only(q), level=level, anchor=(x, y)
    )


def _plane_through(points: Array, heights: list[float]) -> tuple[float, float, float]:
    """(b, c, a) of the plane z = a + b x + c y through the heights at the points (x, y) by
    least squares; the smallest slope that fits when the points lie on a line (a single-track
    vehicle's wheels). Exactly rounded sums (``math.fsum``) and Cramer's rule, not LAPACK,
    so that the placement is the same bits on every machine (crashsim.small_linalg)."""
    n = len(heights)
    xs, ys = [float(v) for v in points[:, 0]], [float(v) for v in points[:, 1]]
    mx, my, mz = math.fsum(xs) / n, math.fsum(ys) / n, math.fsum(heights) / n
    dx, dy, dz = [v - mx for v in xs], [v - my for v in ys], [v - mz for v in heights]
    sxx = math.fsum(u * u for u in dx)
    syy = math.fsum(v * v for v in dy)
    sxy = math.fsum(u * v for u, v in zip(dx, dy, strict=True))
    sxz = math.fsum(u * w for u, w in zip(dx, dz, strict=True))
    syz = math.fsum(v * w for v, w in zip(dy, dz, strict=True))
    det = sxx * syy - sxy * sxy
    if det > 1e-12 * (sxx + syy) ** 2:
        b, c = (sxz * syy - syz * sxy) / det, (syz * sxx - sxz * sxy) / det
    elif sxx + syy > 0.0:  # on a line: the slope along it only
        # the line's direction: dx, dy = t (ux, uy), so sxx : syy : sxy = ux^2 : uy^2 : ux uy
        ux, uy = math.sqrt(sxx), math.copysign(math.sqrt(syy), sxy)
        length = math.hypot(ux, uy)
        ux, uy = ux / length, uy / length
        tz = math.fsum((ux * u + uy * v) * w for u, v, w in zip(dx, dy, dz, strict=True))
        tt = math.fsum((ux * u + uy * v) ** 2 for u, v in zip(dx, dy, strict=True))
        g = tz / tt
        b, c = g * ux, g * uy
    else:
        b = c = 0.0
    return b, c, mz - b * mx - c * my


def _grounded(ground: Ground | None, p: _ObstaclePlacement) -> _ObstaclePlacement:
    """p with its frame's origin on the ground at its (x, y) (z = 0 without a ground)."""
    x, y = float(p.position[0]), float(p.position[1])
    z = _ground_height(ground, x, y, f"obstacle {p.obstacle.name!r}")
    return dataclasses.replace(p, position=_read_only([x, y, z]))


def _check_terrain_under(ground: Ground | None, p: Placement, wheels: Wheels) -> None:
    """SceneError when a wheel starts over a hole in the terrain."""
    if ground is None or ground.terrain is None:
        return
    r = rotation_matrix(p.orientation)
    points = p.position + matmul(wheels.contact_points(), r.T)
    for k in ground.holes(points):
        x, y = points[k][:2]
        raise SceneError(
            f"vehicle {p.vehicle.name!r} wheel {wheels.names[k]!r} starts at "
            f"({x:.2f}, {y:.2f}) m where the terrain has no surface: extend the terrain "
            "under the vehicle, or move the vehicle onto it"
        )
