"""The parts the trailer, tractor and rigid-truck builders share (crashsim.vehicles.trailer,
crashsim.vehicles.trucks): a checked positive number, a box mesh between two corners, the mass
properties of boxes each a uniform solid, a yaw inertia given to a tensor, and axles (each a
left and a right wheel) with the load-sharing groups of close axles. Model frame as
:meth:`crashsim.Vehicle.box`: x forward, y left, z up from the road; m, kg, kg m^2.
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import Any

import numpy as np
import trimesh

from crashsim.errors import ParameterError
from crashsim.vehicles.mass_properties import _box_inertia, _parallel_axis


def _positive(value: Any, name: str) -> float:
    try:
        x = float(value)
    except (TypeError, ValueError) as e:
        raise ParameterError(f"{name} must be a number (m or kg), got {value!r}") from e
    if not np.isfinite(x) or x <= 0.0:
        raise ParameterError(f"{name} = {value!r} is invalid: it must be a finite number > 0")
    return x


def _with_yaw_inertia(inertia: np.ndarray, yaw: float) -> None:
    """Gives an inertia tensor (about the CG, body axes, kg m^2) the yaw inertia ``yaw`` by
    changing its mass's spread along x: Izz = sum m (x^2 + y^2) and Iyy = sum m (x^2 + z^2)
    both change by the same amount (a measured yaw inertia with a uniform body's roll and
    pitch otherwise breaks the triangle inequality for a long trailer)."""
    change = yaw - inertia[2, 2]
    inertia[2, 2] += change
    inertia[1, 1] += change


def _box(lo: Sequence[float], hi: Sequence[float]) -> trimesh.Trimesh:
    lo_a, hi_a = np.asarray(lo, dtype=float), np.asarray(hi, dtype=float)
    mesh = trimesh.creation.box(extents=hi_a - lo_a)
    mesh.apply_translation((lo_a + hi_a) / 2.0)
    return mesh


# Axles closer than this (m) form a group (a tandem or tridem, 1.3-1.4 m apart) whose wheels
# share their load through a load-equalising suspension, one set per side.
GROUP_SPACING = 2.0


def _load_groups(axles_x: Sequence[float], names: Sequence[str]) -> list[list[str]]:
    """Each side's wheels of every run of axles closer than GROUP_SPACING."""
    runs: list[list[int]] = []
    for k in range(len(axles_x)):
        if runs and abs(axles_x[runs[-1][-1]] - axles_x[k]) < GROUP_SPACING:
            runs[-1].append(k)
        else:
            runs.append([k])
    return [
        [f"{names[k]}_{side}" for k in run]
        for run in runs
        if len(run) > 1
        for side in ("left", "right")
    ]


def _axle_wheels(
    axles_x: Sequence[float],
    track: float,
    radius: float,
    cg: np.ndarray,
    steered: Sequence[bool],
    names: Sequence[str],
) -> tuple[np.ndarray, list[bool], list[str]]:
    """Each axle's left and right wheel centres (body frame) at static ride height."""
    centers, flags, wheel_names = [], [], []
    for x, steer, name in zip(axles_x, steered, names, strict=True):
        for side, y in (("left", track / 2.0), ("right", -track / 2.0)):
            centers.append((x - cg[0], y - cg[1], radius - cg[2]))
            flags.append(bool(steer))
            wheel_names.append(f"{name}_{side}")
    return np.array(centers), flags, wheel_names


def _solid_box_parts(
    parts: Sequence[tuple[trimesh.Trimesh, float]],
) -> tuple[np.ndarray, np.ndarray]:
    """CG and inertia about it (body axes, kg m^2) of boxes each a uniform solid of its mass."""
    total = sum(m for _, m in parts)
    cg = sum(m * part.bounds.mean(axis=0) for part, m in parts) / total
    inertia = np.zeros((3, 3))
    for part, m in parts:
        lo, hi = part.bounds
        inertia += _parallel_axis(_box_inertia(m, *(hi - lo)), m, cg - (lo + hi) / 2.0)
    return cg, inertia
