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
    from crashsim.joints import Joint, JointEvent, JointRecord, PassiveMoment
    from crashsim.result import Result

__all__ = [
    "EVENT_SPEED",
    "JACKKNIFE_ANGLE",
    "SWING_SLIP",
    "ArticulationEvent",
    "JointReport",
    "articulation_events",
    "articulation_lines",
    "joint_lines",
    "joint_reports",
]

# crashsim's rules for a combination's articulation events (not from a standard; the
# thresholds say what they are). Below this speed of the towing vehicle (m/s, 18 km/h) a
# large articulation is a manoeuvre (a yard, a tight corner), not an event.
EVENT_SPEED = 5.0
# A jackknife: the units folded past this articulation (rad, 45 deg; a steady road curve's is
# a few degrees, the wheelbase over the radius).
JACKKNIFE_ANGLE = math.radians(45.0)
# A trailer swing: the trailer sliding sideways, its heading this far (rad, 10 deg) from its
# course (its CG's velocity): its tyres past their grip, the tower's still holding.
SWING_SLIP = math.radians(10.0)


@dataclass(frozen=True)
class JointReport:
    """One joint over a run. ``joint``: the scene's (name, vehicles, kind, anchor, axes,
    limits, resistance). ``angle_min`` and ``angle_max`` (3,) rad: the record's angle columns'
    extremes (the kind's angles in the order of ``angle_names``, the rest 0).
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
        """The joint as the scene made it (JSON ``scene.joints[]``): Joint.to_dict (with its
        passive moments when it has some) with its stiffness (N m/rad), damping (N m s/rad),
        friction (N m) and ``collide``."""
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


@dataclass(frozen=True)
class ArticulationEvent:
    """A combination's articulation event (crashsim's rules: EVENT_SPEED, JACKKNIFE_ANGLE,
    SWING_SLIP): ``kind`` "jackknife" (the units folded past JACKKNIFE_ANGLE) or
    "trailer_swing" (the trailer's heading SWING_SLIP from its course), the ``joint`` and its
    ``trailer``, the first ``time`` (s) it held with the tower faster than EVENT_SPEED, the
    articulation then (rad, the trailer's yaw relative to the tower's, + left) and the
    tower's ``speed`` (m/s)."""

    kind: str
    joint: str
    trailer: str
    time: float
    angle: float
    speed: float

    def to_dict(self) -> dict[str, Any]:
        return {
            "kind": self.kind,
            "joint": self.joint,
            "trailer": self.trailer,
            "time": self.time,
            "angle": self.angle,
            "speed": self.speed,
        }


def _heading(q: np.ndarray) -> np.ndarray:
    """The yaw (rad) of the body x axis of quaternions (k, 4) (w, x, y, z)."""
    w, x, y, z = q.T
    return np.arctan2(2.0 * (w * z + x * y), 1.0 - 2.0 * (y * y + z * z))


def articulation_events(result: Result) -> list[ArticulationEvent]:
    """Every jackknife and trailer swing of the result's combinations (joints between two
    vehicles on wheels: not a pedestrian's), in time order: the first instant each rule holds
    per joint."""
    scene = result.scene
    if scene is None:
        return []
    on_wheels = {v.name for v in scene.vehicles if v.wheels is not None}
    out = []
    for joint in scene.joints:
        tower, trailer = joint.vehicles
        if trailer is None or joint.kind == "fixed" or not {tower, trailer} <= on_wheels:
            continue
        a, b = result.trajectory(tower), result.trajectory(trailer)
        speed = np.linalg.norm(a.velocity[:, :2], axis=1)
        articulation = np.angle(np.exp(1j * (_heading(b.orientation) - _heading(a.orientation))))
        course = np.arctan2(b.velocity[:, 1], b.velocity[:, 0])
        slip = np.abs(np.angle(np.exp(1j * (_heading(b.orientation) - course))))
        moving = (speed > EVENT_SPEED) & (np.linalg.norm(b.velocity[:, :2], axis=1) > 1.0)
        for kind, hit in (
            ("jackknife", moving & (np.abs(articulation) > JACKKNIFE_ANGLE)),
            ("trailer_swing", moving & (slip > SWING_SLIP)),
        ):
            if hit.any():
                k = int(np.argmax(hit))
                out.append(
                    ArticulationEvent(
                        kind=kind,
                        joint=joint.name,
                        trailer=trailer,
                        time=float(result.t[k]),
                        angle=float(articulation[k]),
                        speed=float(speed[k]),
                    )
                )
    return sorted(out, key=lambda e: e.time)


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
            lines.append(f"    {ranges}")
        for angle, law in r.joint.passive.items():
            lines.append(f"    passive moment about {angle}: {_law_text(law)}")
        for e in r.events:
            lines.append(
                f"    limit of {e.angle} hit at {e.time:.3f} s ({_deg(e.rate)} deg/s taken out)"
            )
    return lines


def _law_text(law: PassiveMoment) -> str:
    """A passive moment as the text report writes it: 'M = 5 exp(-3 (phi - 0.2)) - 1 N m, phi =
    0.2 rad + the angle'."""
    parts = []
    for term in law.terms:
        scale, rate, centre = term[:3]
        reads = "".join(
            f" + {c.rate:.4g} ({c.joint} {c.angle} + {c.offset:.4g})"
            for c in (term[3] if len(term) > 3 else ())
        )
        parts.append(f"{scale:.4g} exp({rate:.4g} (phi - {centre:.4g}){reads})")
    if law.constant or not parts:
        parts.append(f"{law.constant:.4g}")
    text = " + ".join(parts).replace("+ -", "- ").replace("- -", "+ ")
    return f"M = {text} N m, phi = {law.offset:.4g} rad + the angle"


def articulation_lines(events: list[ArticulationEvent]) -> list[str]:
    """The articulation events' lines of the text report."""
    words = {"jackknife": "jackknife", "trailer_swing": "trailer swing"}
    return [
        f"  {words[e.kind]} of {e.trailer!r} ({e.joint}) at {e.time:.3f} s: articulation "
        f"{_deg(e.angle)} deg at {e.speed:.1f} m/s"
        for e in events
    ]
