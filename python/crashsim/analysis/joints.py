"""What the report says of a run's joints (crashsim.joints; docs/report.md): each joint as the
scene made it, the range of its angles and the largest force and torque through it over the
run, and its limits' hits (Result.joint_events). World frame, SI: m, rad, N, N m, s.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

import numpy as np

if TYPE_CHECKING:
    from crashsim.joints import Joint, JointEvent, JointRecord
    from crashsim.result import Result

__all__ = ["JointReport", "joint_lines", "joint_reports"]


@dataclass(frozen=True)
class JointReport:
    """One joint over a run. ``joint``: the scene's (name, vehicles, kind, anchor, axes,
    limits, resistance). ``angle_min`` and ``angle_max`` (3,) rad: the record's angle columns'
    extremes (the kind's angles in the order of ``angle_names``, the rest 0; a spherical
    joint's columns are the rotation vector of the second body's frame in the first's).
    ``max_force`` (N) and ``max_torque`` (N m): the largest magnitudes of the force and the
    torque of the first vehicle on the second through the joint at the samples, at
    ``max_force_time`` and ``max_torque_time`` (s). ``events``: its limit hits."""

    joint: Joint
    angle_names: tuple[str, ...]
    angle_min: tuple[float, float, float]
    angle_max: tuple[float, float, float]
    max_force: float
    max_force_time: float
    max_torque: float
    max_torque_time: float
    events: tuple[JointEvent, ...]

    @property
    def name(self) -> str:
        return self.joint.name

    def definition(self) -> dict[str, Any]:
        """The joint as the scene made it (JSON ``scene.joints[]``): Joint.to_dict with its
        stiffness (N m/rad), damping (N m s/rad), friction (N m) and ``collide``."""
        stiffness, damping, friction = self.joint.core.resistance
        return {
            **self.joint.to_dict(),
            "stiffness": float(stiffness),
            "damping": float(damping),
            "friction": float(friction),
            "collide": bool(self.joint.core.collide),
        }

    def to_dict(self) -> dict[str, Any]:
        """The joint over the run (JSON ``joints[]``)."""
        return {
            "name": self.name,
            "angle_names": list(self.angle_names),
            "angle_min": list(self.angle_min),
            "angle_max": list(self.angle_max),
            "max_force": self.max_force,
            "max_force_time": self.max_force_time,
            "max_torque": self.max_torque,
            "max_torque_time": self.max_torque_time,
        }


def _report(joint: Joint, record: JointRecord, events: list[JointEvent]) -> JointReport:
    force = np.linalg.norm(record.force, axis=1)
    torque = np.linalg.norm(record.torque, axis=1)
    i, j = int(np.argmax(force)), int(np.argmax(torque))
    lo, hi = record.angles.min(axis=0), record.angles.max(axis=0)
    return JointReport(
        joint=joint,
        angle_names=tuple(record.angle_names),
        angle_min=(float(lo[0]), float(lo[1]), float(lo[2])),
        angle_max=(float(hi[0]), float(hi[1]), float(hi[2])),
        max_force=float(force[i]),
        max_force_time=float(record.t[i]),
        max_torque=float(torque[j]),
        max_torque_time=float(record.t[j]),
        events=tuple(e for e in events if e.joint == joint.name),
    )


def joint_reports(result: Result) -> list[JointReport]:
    """Every joint of the result's scene over the run, in the order made (empty without)."""
    scene = result.scene
    if scene is None:
        return []
    return [_report(j, result.joints[j.name], result.joint_events) for j in scene.joints]


def _deg(x: float) -> str:
    return f"{round(math.degrees(x), 1) + 0.0:.1f}"  # no "-0.0"


def joint_lines(reports: list[JointReport]) -> list[str]:
    """The joints' section of the text report."""
    lines = ["Joints (force and torque of the first vehicle on the second through the joint):"]
    for r in reports:
        first, second = r.joint.vehicles
        lines.append(
            f"  {r.name}: {r.joint.kind}, {first} - {second or 'the world'}; largest force "
            f"{r.max_force:.0f} N at {r.max_force_time:.3f} s, torque {r.max_torque:.0f} N m "
            f"at {r.max_torque_time:.3f} s"
        )
        if r.angle_names:
            ranges = ", ".join(
                f"{n} {_deg(r.angle_min[k])} to {_deg(r.angle_max[k])} deg"
                for k, n in enumerate(r.angle_names)
            )
        else:
            ranges = (
                "rotation vector (x, y, z) from ("
                + ", ".join(_deg(x) for x in r.angle_min)
                + ") to ("
                + ", ".join(_deg(x) for x in r.angle_max)
                + ") deg"
            )
        lines.append(f"    {ranges}")
        for e in r.events:
            lines.append(
                f"    limit of {e.angle} hit at {e.time:.3f} s ({_deg(e.rate)} deg/s taken out)"
            )
    return lines
