"""The multibody pedestrian: one rigid body per segment of :func:`body_segments`, joined by
the engine's joints (docs/human.md, "The multibody pedestrian").

Each segment is a :class:`crashsim.Vehicle` named ``"<name>/<segment>"`` (e.g.
"pedestrian/head"): its contact shape a capsule whose ends are the segment's endpoints (the
radius of body_segments' capsule), its mass and principal inertias those of the segment data,
its model frame the segment's frame (origin at its first endpoint, axes parallel to the body
frame in the standing posture). The joints follow the anatomy: hinges ("revolute") at the
knees, elbows and ankles, balls ("spherical") with a swing cone and twist limits at the hips,
shoulders, wrists, lumbar, thoracic and neck joints. Ranges of motion come from
data/segments.toml (Castori 2012) and data/pedestrian.toml (the motions segments.toml lacks);
the relaxed leg's joints (hips, knees, ankles) carry Riener and Edrich's (1999) passive elastic
moments, coupled through the two-joint muscles (data/pedestrian.toml, [passive]); every joint
an assumed small damping (no published damping was read).

Body frame as body_segments': x forward, y left, z up, origin on the ground midway between
the feet. ``Scene.add(pedestrian, (x, y), heading=, velocity=)`` puts that origin at (x, y)
on the ground (the body's lowest point 1 mm above it), its x axis at ``heading``, every
segment moving at ``velocity``, and joins the segments.
"""

from __future__ import annotations

import math
import tomllib
from collections.abc import Mapping
from dataclasses import dataclass, field, replace
from functools import cache
from importlib import resources
from types import MappingProxyType
from typing import Any

import numpy as np
import trimesh
from numpy.typing import ArrayLike, NDArray

from crashsim import _core
from crashsim.errors import ParameterError
from crashsim.human.anthropometry import Segment, body_segments
from crashsim.human.cycling_pose import cycling_angles
from crashsim.joints import CoupledAngle, PassiveMoment
from crashsim.names import check_name
from crashsim.small_linalg import dot, matmul, norm, rotation_about, transform_points
from crashsim.vehicles.vehicle import Vehicle

__all__ = ["POSES", "Pedestrian", "PedestrianJoint"]

Array = NDArray[np.float64]
POSES = ("standing", "walking", "cycling", "running")  # (a study's `p.pose` is the index)
CLEARANCE = 1e-3  # m, the lowest point of the body above the ground at the start
# The published passive moments may be scaled by at most this (a sensitivity's bound: a
# relaxed subject's moments times ten; the engine's sub-steps follow the laws' slopes).
PASSIVE_MOMENTS_MAX = 10.0
# A clothed person's friction sliding on the road (each segment's with the ground, in place of
# the ground's body friction, a car body's 0.45): the 0.66 that the 1997 throw factors were
# derived with (docs/human.md, "The corridors and their sources"), inside the 0.6-0.7 that
# JSPS KAKEN project 23H05208 measured towing a clothed dummy over a dry and a wet road
# (cotton and nylon; 2023 report) and the 0.6-0.7 of its dummies dropped from a car at about
# 50 km/h (0.6-0.9 at 20-25 km/h).
ROAD_FRICTION = 0.66
_CAPSULE_COUNT = (8, 8)  # trimesh capsule resolution: 128 triangles a segment

_X, _Y, _Z = np.eye(3)


@cache
def _table() -> dict[str, Any]:
    path = resources.files("crashsim.human").joinpath("data", "pedestrian.toml")
    return tomllib.loads(path.read_text(encoding="utf-8"))


def _rot(axis: Array, angle_deg: float) -> Array:
    """The rotation by ``angle_deg`` about the unit ``axis`` (Rodrigues)."""
    a = math.radians(angle_deg)
    return rotation_about(axis, math.sin(a), math.cos(a))


@dataclass(frozen=True)
class PedestrianJoint:
    """A joint of the pedestrian, as made in its pose: ``parent`` and ``child`` segment names,
    ``kind`` ("spherical" or "revolute"), ``at`` the joint centre and ``axes`` (3, 3) the joint
    frame (columns x, y, z) in the body frame (m); a hinge turns about the frame's z, a ball's
    swing is measured from it (its cone's axis) to ``child_axes``'s z (the limb; None: the
    same frame, the cone centred on the pose). ``limits`` {angle: (lower, upper)} rad from
    the pose; ``rom`` the published ranges used (motion -> rad from the standing posture);
    resistance; ``passive`` {angle: law} the published passive moments (the leg's), their
    coupled angles naming the person's joints as here (:meth:`passive_in` names them as a
    scene does)."""

    name: str
    parent: str
    child: str
    kind: str
    at: Array
    axes: Array
    limits: Mapping[str, tuple[float, float]]
    rom: Mapping[str, float]
    stiffness: float  # N m/rad
    damping: float  # N m s/rad
    friction: float  # N m
    child_axes: Array | None = None
    passive: Mapping[str, PassiveMoment] = field(default_factory=lambda: MappingProxyType({}))

    def passive_in(self, prefix: str) -> dict[str, PassiveMoment]:
        """The passive moments with each coupled joint named as the scene names it
        (``prefix`` + this person's joint name, e.g. "pedestrian/hip_left")."""
        return {
            angle: replace(law, terms=tuple(
                (*term[:3], tuple(replace(c, joint=prefix + c.joint) for c in term[3]))
                if len(term) > 3 else term
                for term in law.terms
            ))
            for angle, law in self.passive.items()
        }  # fmt: skip


_Body = tuple[Vehicle, Array, Array, Array]  # body, CG m, rotation, velocity m/s (world)
# joint, anchor m, axes (world), the child's axes (world; None: the same)
_JointAt = tuple[PedestrianJoint, Array, Array, Array | None]


@dataclass(frozen=True)
class _Posed:
    segment: Segment
    rotation: Array  # segment frame -> body frame
    joint_at: Array  # where its joint to the parent (or its origin, the pelvis) is, body frame


class Pedestrian:
    """A multibody pedestrian (module docstring). ``height`` m, ``mass`` kg, ``sex``
    ("male" or "female"), or ``percentile`` (0-100, ANSUR II stature; then ``height`` is
    not used); ``pose`` "standing", "walking", "running" or "cycling"; ``name`` prefixes its
    segments' names; ``passive_moments`` scales the leg's published passive joint moments
    (1: Riener and Edrich's relaxed subjects, the default; 0: none, the joints' damping
    alone; at most PASSIVE_MOMENTS_MAX; docs/human.md, "Resistance"); ``road_friction``
    is each segment's friction sliding on the road, in (0, 2] (default ROAD_FRICTION, a
    clothed person's 0.66; the ground's body friction is a car body's).

    Attributes: ``segments`` (the :class:`crashsim.Vehicle` of each segment, pelvis first),
    ``joints`` (:class:`PedestrianJoint`), ``data`` (body_segments' :class:`Segment`\\ s),
    ``height``, ``mass``, ``sex``, ``pose``, ``pose_angles``, ``name``. The "cycling" pose
    is seated on a bicycle (crashsim.Cyclist puts one under it; docs/human.md, "The
    cyclist")."""

    def __init__(
        self,
        height: float = 1.75,
        mass: float = 75.0,
        sex: str = "male",
        percentile: float | None = None,
        pose: str = "standing",
        name: str = "pedestrian",
        passive_moments: float = 1.0,
        road_friction: float = ROAD_FRICTION,
    ) -> None:
        check_name(name, "a pedestrian")
        if not (isinstance(road_friction, int | float) and not isinstance(road_friction, bool)):
            raise ParameterError(
                f"road_friction = {road_friction!r}: give a number in (0, 2] (a clothed "
                f"person on asphalt about {ROAD_FRICTION:g})"
            )
        _core.check_ground_friction(float(road_friction), "road_friction")
        if not (isinstance(passive_moments, int | float) and not isinstance(passive_moments, bool)
                and 0.0 <= passive_moments <= PASSIVE_MOMENTS_MAX):  # fmt: skip
            raise ParameterError(
                f"passive_moments = {passive_moments!r}: give a factor from 0 (no passive joint "
                f"moments) to {PASSIVE_MOMENTS_MAX:g} (1: the published relaxed subjects')"
            )
        if pose not in POSES:
            raise ParameterError(
                f"pose {pose!r} is not known: give one of {', '.join(map(repr, POSES))}"
            )
        data = body_segments(None if percentile is not None else height, mass, sex, percentile)
        self._name, self._pose, self._sex = name, pose, sex
        self._arguments = {"height": height, "mass": mass, "sex": sex,
                           "percentile": percentile, "pose": pose, "name": name,
                           "passive_moments": float(passive_moments),
                           "road_friction": float(road_friction)}  # fmt: skip
        self._data = tuple(data)
        angles = dict(_table()["poses"][pose])
        if pose == "cycling":
            angles.update(cycling_angles(data, angles))
        self._angles = MappingProxyType(
            {k: float(v) for k, v in angles.items() if isinstance(v, (int, float))}
        )
        self._posed = _pose(data, angles, sex)
        self._segments = tuple(_segment_vehicle(p, name) for p in self._posed.values())
        self._passive_moments = float(passive_moments)
        self._road_friction = float(road_friction)
        self._joints = tuple(_joints(self._posed, sex, self._passive_moments))
        self._height = max(s.origin[2] for s in data)
        self._mass = sum(s.mass for s in data)

    # -- what it is ----------------------------------------------------------------------

    @property
    def name(self) -> str:
        return self._name

    @property
    def pose(self) -> str:
        return self._pose

    @property
    def sex(self) -> str:
        return self._sex

    @property
    def height(self) -> float:
        """Stature (m): the vertex's height in the standing posture."""
        return self._height

    @property
    def mass(self) -> float:
        """Body mass (kg): the segments' masses summed."""
        return self._mass

    @property
    def passive_moments(self) -> float:
        """The factor on the leg's published passive joint moments (0: none)."""
        return self._passive_moments

    @property
    def road_friction(self) -> float:
        """Each segment's friction sliding on the road (in place of the ground's body
        friction)."""
        return self._road_friction

    @property
    def pose_angles(self) -> Mapping[str, float]:
        """The pose's angles and targets as made (degrees; lengths in m): pedestrian.toml's
        ``[poses.<pose>]``, and for "cycling" the joint angles solved from its targets
        (crashsim.human.cycling_pose.CYCLING_KEYS)."""
        return self._angles

    @property
    def arguments(self) -> dict[str, Any]:
        """The arguments it was made with (``height``, ``mass``, ``sex``, ``percentile``,
        ``pose``, ``name``, ``passive_moments``, ``road_friction``):
        ``Pedestrian(**p.arguments)`` makes the same body, bit for bit (a study's variant of
        another height is ``Pedestrian(**{**p.arguments, "height": h})``; the ``height``
        property is the stature computed from the segments)."""
        return dict(self._arguments)

    @property
    def data(self) -> tuple[Segment, ...]:
        return self._data

    @property
    def segments(self) -> tuple[Vehicle, ...]:
        return self._segments

    @property
    def joints(self) -> tuple[PedestrianJoint, ...]:
        return self._joints

    def segment(self, name: str) -> Vehicle:
        """A segment's body by its short name ("head", "thigh_left", ...)."""
        for s in self._segments:
            if s.name == f"{self._name}/{name}":
                return s
        known = [p.segment.name for p in self._posed.values()]
        raise ParameterError(f"the pedestrian has no segment {name!r}: it has {known}")

    def posed(self, name: str) -> tuple[Array, Array]:
        """A segment's pose in the body frame: (its CG, m; its rotation (3, 3), segment
        frame -> body frame), before the body is lifted onto the ground."""
        p = self._posed[name]
        return _to_posed(p, np.asarray(p.segment.cg_body)), p.rotation.copy()

    def vertices(self) -> Array:
        """Every contact capsule's vertices in the body frame, posed (m)."""
        out = []
        for p, v in zip(self._posed.values(), self._segments, strict=True):
            out.append(_to_posed(p, np.asarray(v.mesh.vertices) + p.segment.origin))
        return np.vstack(out)

    def cg(self) -> Array:
        """The whole body's centre of mass in the body frame, posed (m)."""
        total = np.zeros(3)
        for p in self._posed.values():
            total += p.segment.mass * _to_posed(p, np.asarray(p.segment.cg_body))
        return total / self._mass

    # -- in a scene ----------------------------------------------------------------------

    def placement(
        self, position: ArrayLike, heading: float, velocity: ArrayLike, ground: float
    ) -> tuple[list[_Body], list[_JointAt]]:
        """Where each segment starts in the world: [(body, CG m, rotation (3, 3) body ->
        world, velocity m/s)], and each joint's [(joint, anchor m, axes (3, 3)) world]. The
        body frame's origin at ``position``: (x, y) puts the body's lowest point CLEARANCE
        above the ground's height ``ground`` (m) there, (x, y, z) puts the origin at that
        world point (a fall, a person lifted); its x axis at ``heading`` rad about world z;
        every segment moving at ``velocity``."""
        p = np.asarray(position, dtype=np.float64).reshape(-1)
        v = np.asarray(velocity, dtype=np.float64).reshape(-1)
        if p.size not in (2, 3) or v.size != 3:
            raise ParameterError(
                f"a pedestrian's position is (x, y) m and its velocity (vx, vy, vz) m/s, got "
                f"{position!r} and {velocity!r}"
            )
        yaw = _rot(_Z, math.degrees(heading))
        if p.size == 3:
            origin = p.copy()
        else:
            origin = np.array([p[0], p[1], ground + CLEARANCE - float(self.vertices()[:, 2].min())])
        bodies = []
        for posed, vehicle in zip(self._posed.values(), self._segments, strict=True):
            cg = _to_posed(posed, np.asarray(posed.segment.cg_body))
            rotation = matmul(yaw, posed.rotation)
            bodies.append((vehicle, origin + matmul(yaw, cg), rotation, v.copy()))
        joints = [
            (j, origin + matmul(yaw, j.at), matmul(yaw, j.axes),
             None if j.child_axes is None else matmul(yaw, j.child_axes))
            for j in self._joints
        ]  # fmt: skip
        return bodies, joints

    def __reduce__(self) -> tuple[Any, tuple[dict[str, Any]]]:
        """Pickled as the arguments it was made with (:attr:`arguments`): rebuilt bit for bit
        (a scene with a pedestrian pickles, for studies on other processes)."""
        return (_rebuilt, (dict(self._arguments),))

    def __repr__(self) -> str:
        return (
            f"Pedestrian(height={self._height:.3f}, mass={self._mass:.1f}, sex={self._sex!r}, "
            f"pose={self._pose!r}, name={self._name!r}, passive_moments={self._passive_moments:g}, "
            f"road_friction={self._road_friction:g})"
        )


def _rebuilt(arguments: dict[str, Any]) -> Pedestrian:
    """A pickled pedestrian, made again from its arguments."""
    return Pedestrian(**arguments)


def _to_posed(p: _Posed, x: Array) -> Array:
    """Body-frame points of the standing posture moved with their segment into the pose."""
    standing_at = np.asarray(p.segment.joint.position if p.segment.joint else p.segment.origin)
    return matmul(np.asarray(x) - standing_at, p.rotation.T) + p.joint_at


def _pose(data: list[Segment], angles: dict[str, Any], sex: str) -> dict[str, _Posed]:
    """Each segment's rotation and joint position in the pose, parents first."""
    rel = _relative_rotations(angles)
    posed: dict[str, _Posed] = {}
    for s in data:
        if s.parent is None:
            posed[s.name] = _Posed(s, np.eye(3), np.asarray(s.origin, dtype=np.float64))
            continue
        parent = posed[s.parent]
        assert s.joint is not None
        at = _to_posed(parent, np.asarray(s.joint.position))
        rotation = matmul(parent.rotation, rel.get(s.name, np.eye(3)))
        posed[s.name] = _Posed(s, rotation, at)
    return posed


def _relative_rotations(a: dict[str, Any]) -> dict[str, Array]:
    """Each segment's rotation relative to its parent (body axes), from a pose's angles
    (degrees). Signs: abduction of a left limb is about +x, flexion of a hip or shoulder
    about -y, of a knee about +y, of an elbow about -y, plantarflexion about +y; the trunk's
    (lumbar) flexion about +y, the neck's extension about -y."""
    if "lumbar_flexion" in a:
        return _cycling_rotations(a)
    out: dict[str, Array] = {}
    for side, s in (("left", 1.0), ("right", -1.0)):
        out[f"upper_arm_{side}"] = _rot(_X, s * a.get("shoulder_abduction", 0.0))
        out[f"thigh_{side}"] = _rot(_X, s * a.get("hip_abduction", 0.0))
    if "lead_hip_flexion" in a:
        out["thigh_left"] = matmul(_rot(_Y, -a["lead_hip_flexion"]), out["thigh_left"])
        out["shank_left"] = _rot(_Y, a["lead_knee_flexion"])
        out["thigh_right"] = matmul(_rot(_Y, a["trail_hip_extension"]), out["thigh_right"])
        out["shank_right"] = _rot(_Y, a["trail_knee_flexion"])
        out["foot_right"] = _rot(_Y, a["trail_ankle_plantarflexion"])
        # the arms swing against the legs: the right arm forward
        out["upper_arm_right"] = matmul(_rot(_Y, -a["arm_swing"]), out["upper_arm_right"])
        out["upper_arm_left"] = matmul(_rot(_Y, a["arm_swing"]), out["upper_arm_left"])
        for side in ("left", "right"):
            out[f"forearm_{side}"] = _rot(_Y, -a["elbow_flexion"])
    return out


def _cycling_rotations(a: dict[str, Any]) -> dict[str, Array]:
    """The cycling pose's rotations (cycling_pose.CYCLING_KEYS, degrees): every one in the
    sagittal plane; both arms alike."""
    out = {
        "lower_torso": _rot(_Y, a["lumbar_flexion"]),
        "head": _rot(_Y, -a["neck_extension"]),
    }
    for side in ("left", "right"):
        out[f"upper_arm_{side}"] = _rot(_Y, -a["shoulder_flexion"])
        out[f"forearm_{side}"] = _rot(_Y, -a["elbow_flexion"])
        out[f"thigh_{side}"] = _rot(_Y, -a[f"hip_flexion_{side}"])
        out[f"shank_{side}"] = _rot(_Y, a[f"knee_flexion_{side}"])
        out[f"foot_{side}"] = _rot(_Y, a[f"ankle_plantarflexion_{side}"])
    return out


def _capsule(segment: Segment) -> trimesh.Trimesh:
    """The segment's contact capsule in its frame: body_segments' radius, its ends at the
    segment's endpoints (a sphere at the middle when the segment is shorter than its
    diameter: the trunk's segments)."""
    r = segment.contact.radius
    a, b = np.zeros(3), np.asarray(segment.end) - np.asarray(segment.origin)
    length = float(norm(b))
    axis = b / length
    core = length - 2.0 * r  # between the caps' centres
    if core <= 0.0:
        mesh = trimesh.creation.uv_sphere(radius=r, count=list(_CAPSULE_COUNT))
    else:
        mesh = trimesh.creation.capsule(height=core, radius=r, count=list(_CAPSULE_COUNT))
    # trimesh's capsule lies along z, centred at the origin: turn z onto the axis (every
    # segment's axis is along z, -z or x in the segment frame)
    transform = np.eye(4)
    if axis[2] < -0.5:
        transform[:3, :3] = _rot(_X, 180.0)
    elif axis[2] < 0.5:
        transform[:3, :3] = _rot(np.cross(_Z, axis) / norm(np.cross(_Z, axis)), 90.0)
    transform[:3, 3] = (a + b) / 2.0
    return trimesh.Trimesh(transform_points(mesh.vertices, transform), mesh.faces, process=False)


def _segment_vehicle(p: _Posed, name: str) -> Vehicle:
    s = p.segment
    return Vehicle(
        _capsule(s),
        s.mass,
        np.asarray(s.cg),
        np.diag(s.inertia),
        name=f"{name}/{s.name}",
        sources={"cg": "de Leva (1996)", "inertia": "de Leva (1996)"},
    )


# The anatomical joint of each segment: its kind and how its published ranges become limits.
_HINGES = {"knee", "elbow", "ankle"}
# The joints pedestrian.toml's [passive] gives laws for (Riener and Edrich's), one per side.
_PASSIVE_JOINTS = ("hip", "knee", "ankle")


def _rom(segment: Segment, sex: str) -> dict[str, float]:
    """Every range of the segment's joint (rad): segments.toml's and pedestrian.toml's."""
    assert segment.joint is not None
    joint = segment.joint.name
    rom = dict(segment.joint.rom)
    for motion, deg in _table()["rom"].get(joint, {}).items():
        rom.setdefault(motion, math.radians(float(deg)))
    if joint in ("lumbar", "thoracic"):
        t = _table()["rom_thoracolumbar"]
        rom["lateral_flexion"] = math.radians(float(t["lateral_flexion"]) * float(t["share"]))
    return rom


def _joints(posed: dict[str, _Posed], sex: str, passive_moments: float) -> list[PedestrianJoint]:
    res = _table()["resistance"]
    made = []
    # Per hinge and hip (by its name, e.g. "knee_left"): the engine's angle a passive law
    # reads and phi, the law's anatomical angle (rad), where the joint is made less that
    # angle then (the law's offset)
    starts: dict[str, tuple[str, float]] = {}
    for p in posed.values():
        s = p.segment
        if s.parent is None:
            continue
        assert s.joint is not None
        parent = posed[s.parent]
        rom = _rom(s, sex)
        side = 1.0 if s.side != "right" else -1.0
        joint = s.joint.name
        full = joint if s.side is None else f"{joint}_{s.side}"
        if joint in _HINGES:
            axes, limits, start = _hinge(joint, parent.rotation, rom, p, parent)
            kind = "revolute"
            starts[full] = ("angle", start)
        else:
            axes, limits = _ball(joint, parent.rotation, rom, p, side)
            kind = "spherical"
        child_axes = None
        if joint == "hip":
            # A cone between flexion (forward) and extension: its axis the standing thigh's
            # turned forward (about the pelvis's lateral axis) by half their difference, its
            # half-angle half their sum; the pose's thigh starts inside it.
            flexion, extension = rom["flexion"], rom["extension"]
            # the pose's hip turn undone
            standing = matmul(matmul(parent.rotation, p.rotation.T), axes)
            turn = _axis_angle(matmul(parent.rotation, _Y), -(flexion - extension) / 2.0)
            child_axes, axes = axes, matmul(turn, standing)
            limits["swing"] = (0.0, (flexion + extension) / 2.0)
            # The ball's rotation-vector "y" (about the frame's y, the pelvis's right: the
            # thigh forward is positive) is the flexion less the cone's forward turn.
            starts[full] = ("y", (flexion - extension) / 2.0)
        made.append((s, full, kind, p, axes, limits, rom, child_axes))
    return [
        PedestrianJoint(
            name=full,
            parent=s.parent,
            child=s.name,
            kind=kind,
            at=p.joint_at.copy(),
            axes=axes,
            limits=MappingProxyType(limits),
            rom=MappingProxyType(rom),
            stiffness=float(res["stiffness"]),
            damping=float(res["damping"]),
            friction=float(res["friction"]),
            child_axes=child_axes,
            passive=MappingProxyType(_passive(s, starts, passive_moments)),
        )
        for s, full, kind, p, axes, limits, rom, child_axes in made
    ]


def _passive(
    segment: Segment, starts: Mapping[str, tuple[str, float]], factor: float
) -> dict[str, PassiveMoment]:
    """Riener and Edrich's passive moment of a hip, knee or ankle (pedestrian.toml's
    [passive], angles in degrees) times ``factor`` as the engine's law about the joint's
    angle: each term sign exp(exponent + sum of coefficient x angle), the joint's own angle's
    coefficient its rate, the same side's other joints' its coupled angles; {} for the other
    joints, and for every joint when ``factor`` is 0."""
    assert segment.joint is not None
    laws = _table()["passive"]
    joint = segment.joint.name
    if joint not in _PASSIVE_JOINTS or segment.side is None or factor == 0.0:
        return {}
    law = laws[joint]
    per_rad = 180.0 / math.pi  # the law's coefficients are per degree
    own, offset = starts[f"{joint}_{segment.side}"]
    terms = []
    for term in law["terms"]:
        coupled = []  # the same side's other joints this term reads
        for other in _PASSIVE_JOINTS:
            if other != joint and other in term:
                name = f"{other}_{segment.side}"
                angle, start = starts[name]
                coupled.append(CoupledAngle(name, angle, float(term[other]) * per_rad, start))
        row = (
            factor * float(term["sign"]) * math.exp(float(term["exponent"])),
            float(term.get(joint, 0.0)) * per_rad,
            0.0,
        )
        terms.append((*row, tuple(coupled)) if coupled else row)
    constant = factor * float(law["constant"])
    return {own: PassiveMoment(terms=tuple(terms), constant=constant, offset=offset)}


def _axis_angle(axis: Array, angle: float) -> Array:
    """The rotation matrix of ``angle`` rad about the unit ``axis`` (Rodrigues)."""
    k = np.asarray(axis, dtype=np.float64) / norm(axis)
    return rotation_about(k, math.sin(angle), math.cos(angle))


def _frame(z: Array, x_hint: Array) -> Array:
    """A right-handed frame (columns x, y, z) with the given z and x as near x_hint."""
    z = z / norm(z)
    x = x_hint - dot(x_hint, z) * z
    if norm(x) < 1e-9:
        x = np.cross(_Y, z)
    x /= norm(x)
    return np.column_stack([x, np.cross(z, x), z])


def _relative_angle(parent: _Posed, child: _Posed, axis: Array) -> float:
    """The pose's starting angle of a hinge (rad): the child's rotation relative to its
    parent, a rotation about ``axis`` (parent frame)."""
    rel = matmul(parent.rotation.T, child.rotation)
    vee = np.array([rel[2, 1] - rel[1, 2], rel[0, 2] - rel[2, 0], rel[1, 0] - rel[0, 1]])
    return math.atan2(float(dot(axis, vee)) / 2.0, (float(np.trace(rel)) - 1.0) / 2.0)


def _hinge(
    joint: str, parent_rot: Array, rom: dict[str, float], child: _Posed, parent: _Posed
) -> tuple[Array, dict[str, tuple[float, float]], float]:
    """A hinge about the parent's lateral axis, its angle positive in flexion (knee, elbow)
    or plantarflexion (ankle); limits from the standing posture's ranges minus the pose's
    starting angle; that starting angle (rad from the standing posture)."""
    if joint == "ankle":
        axis, lo, hi = _Y, -rom["dorsiflexion"], rom["plantarflexion"]
    elif joint == "knee":
        axis, lo, hi = _Y, -rom["hyperextension"], rom["flexion"]
    else:  # elbow: flexion brings the forearm forward, about -y
        axis, lo, hi = -_Y, -rom["hyperextension"], rom["flexion"]
    start = _relative_angle(parent, child, axis)
    axes = matmul(parent_rot, _frame(axis, _X))
    return axes, {"angle": (lo - start, hi - start)}, start


def _ball(
    joint: str, parent_rot: Array, rom: dict[str, float], child: _Posed, side: float
) -> tuple[Array, dict[str, tuple[float, float]]]:
    """A ball whose frame's z runs along the child segment from the joint (its swing is the
    limb's deviation from the pose); the swing cone is the largest published range (a cone
    stands for every direction), the twist (about the limb) from the rotation ranges."""
    s = child.segment
    far = s.origin if norm(np.subtract(s.origin, s.joint.position)) > norm(
        np.subtract(s.end, s.joint.position)) else s.end
    z = _to_posed(child, np.asarray(far)) - child.joint_at
    axes = _frame(z, matmul(parent_rot, _X))
    limits: dict[str, tuple[float, float]] = {}
    swing = max((v for k, v in rom.items() if "rotation" not in k and k not in
                 ("pronation", "supination")), default=None)
    if swing is not None and swing < math.pi:
        limits["swing"] = (0.0, swing)
    if joint in ("hip", "shoulder"):
        # z runs down the limb: external rotation of a left limb is negative about it
        ext, inn = rom["external_rotation"], rom["internal_rotation"]
        limits["twist"] = (-ext, inn) if side > 0 else (-inn, ext)
    elif joint == "wrist":
        # the forearm's pronation and supination, put at the wrist (the elbow is a hinge)
        sup, pro = rom["supination"], rom["pronation"]
        limits["twist"] = (-sup, pro) if side > 0 else (-pro, sup)
    return axes, limits
