"""A struck pedestrian's figures from a run (issue 22; docs/human.md, "Head impact"): each
segment's first contact with a vehicle (when, the segment's speed relative to the vehicle at
the contact point, where on the vehicle, the wrap-around distance there), its largest relative
speed while in contact, and where the person's centre of mass comes to rest.

Frames: world (x, y, z up, m); a vehicle's model frame (x forward from the body's middle, y
left, z up from the road: the mesh's own coordinates). Speeds in m/s, times in s.
"""

from __future__ import annotations

from collections.abc import Iterable, Mapping
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any, Protocol

import numpy as np
import trimesh
from numpy.typing import ArrayLike

from crashsim.errors import ParameterError
from crashsim.records import rotation_matrix
from crashsim.result import Result
from crashsim.small_linalg import dot, matmul, norm

if TYPE_CHECKING:
    from crashsim.human.bicycle import Bicycle
    from crashsim.human.pedestrian import Pedestrian
    from crashsim.vehicles.vehicle import Vehicle

Array = np.ndarray


class PeopleOf(Protocol):
    """What the analysis reads of a scene (a crashsim.Scene is one): its people by name. A
    protocol, so that the analysis (downstream of the scene) does not import it."""

    @property
    def pedestrians(self) -> Mapping[str, Any]: ...

    @property
    def cyclists(self) -> Mapping[str, Any]: ...

__all__ = [
    "BicycleReport",
    "PedestrianReport",
    "SegmentContact",
    "pedestrian_lines",
    "pedestrian_reports",
    "person_bodies",
    "rest_of",
    "segment_contacts",
    "Throw",
    "travel",
    "whole_body",
    "wrap_around_distance",
]

# How far (m) the outline may fall below its highest point so far while a wrap-around tape
# still follows it (a bonnet's or roof's curvature); past that it goes down the rear.
DESCENT = 0.2


@dataclass(frozen=True)
class SegmentContact:
    """A segment's first contact with the vehicle. ``segment`` its name (e.g. "head");
    ``time`` (s) the first overlap; ``point`` (3,) the vehicle's surface point nearest the
    segment's centre of mass then, in the vehicle's model frame (m); ``wrap_around`` (m) that
    point's wrap-around distance (:func:`wrap_around_distance`; None off the vehicle's front
    and top); ``relative_speed`` (m/s) the segment's velocity less the vehicle's at that point
    then; ``peak_relative_speed`` (m/s) the largest of it at the samples while the two
    overlap (from each first overlap to its separation)."""

    segment: str
    time: float
    point: Array
    wrap_around: float | None
    relative_speed: float
    peak_relative_speed: float


def _relative_speeds(
    result: Result, segment: str, vehicle: Vehicle, samples: Array, point: Array
) -> Array:
    """At each of the ``samples`` (indices), |the segment's velocity less the vehicle's| (m/s)
    at the vehicle's material point ``point`` (its model frame), both as rigid bodies."""
    car, seg = result.trajectory(vehicle.name), result.trajectory(segment)
    r = rotation_matrix(car.orientation[samples])  # (n, 3, 3)
    at = np.einsum("nij,j->ni", r, point - vehicle.cg) + car.position[samples]
    v_car = car.velocity[samples] + np.cross(car.angular_velocity[samples],
                                             at - car.position[samples])  # fmt: skip
    v_seg = seg.velocity[samples] + np.cross(seg.angular_velocity[samples],
                                             at - seg.position[samples])  # fmt: skip
    return np.linalg.norm(v_seg - v_car, axis=1)


def wrap_around_distance(vehicle: Vehicle, point: ArrayLike) -> float | None:
    """The wrap-around distance (m) of a point on the vehicle's surface (model frame): the
    length of a tape laid from the road up the vehicle's front and over its top to the point,
    in the vertical longitudinal plane through it (the mesh's section there): the height of
    the front's lowest point (the tape from the road straight up to it) plus the length along
    the section's outline from there, up the front, to the point. None when the point is not
    on the front or the top (under the vehicle, or on its rear: the outline fell more than
    DESCENT below its highest before the point)."""
    p = np.asarray(point, dtype=np.float64).reshape(3)
    section = vehicle.mesh.section(plane_origin=[0.0, p[1], 0.0], plane_normal=[0.0, 1.0, 0.0])
    if section is None:
        raise ParameterError(
            f"the point {p.tolist()} m is beside vehicle {vehicle.name!r} (no section of its "
            "mesh at that y): give a point on its surface (model frame)"
        )
    loops = [np.asarray(d)[:, [0, 2]] for d in section.discrete]
    # The loop through the point, and the point's place on it.
    best = None
    for loop in loops:
        for i in range(len(loop) - 1):
            a, b = loop[i], loop[i + 1]
            ab = b - a
            s = float(np.clip(dot(p[[0, 2]] - a, ab) / max(float(dot(ab, ab)), 1e-300), 0, 1))
            d = float(norm(a + s * ab - p[[0, 2]]))
            if best is None or d < best[0]:
                best = (d, loop, i, s)
    assert best is not None
    _, loop, seg, frac = best
    if loop.shape[0] > 1 and np.allclose(loop[0], loop[-1]):
        loop = loop[:-1]
    n = len(loop)
    lengths = np.linalg.norm(np.roll(loop, -1, axis=0) - loop, axis=1)  # edge i: i -> i + 1
    # The front's lowest point: the outline's frontmost among its points within 5 cm of its
    # lowest.
    low = loop[:, 1] <= loop[:, 1].min() + 0.05
    start = int(np.flatnonzero(low)[np.argmax(loop[low, 0])])
    # Walk from there up the front: the way whose next point is higher.
    up = 1 if loop[(start + 1) % n, 1] >= loop[(start - 1) % n, 1] else -1
    travelled, i, highest = 0.0, start, loop[start, 1]
    for _ in range(n):
        j = (i + up) % n
        edge = lengths[i] if up == 1 else lengths[j]
        on_edge = (i == seg and j == (seg + 1) % n) or (j == seg and i == (seg + 1) % n)
        if on_edge:
            at = frac if i == seg else 1.0 - frac
            return float(loop[start, 1] + travelled + at * edge)
        travelled += edge
        i = j
        highest = max(highest, loop[i, 1])
        if loop[i, 1] < highest - DESCENT:
            break  # over the top and down the rear: the point is not on the front or top
    return None


def segment_contacts(
    result: Result, pedestrian: Pedestrian, vehicle: Vehicle,
    segments: Iterable[str] | None = None,
) -> dict[str, SegmentContact]:
    """Each of the pedestrian's segments that touched ``vehicle`` in the run: its
    :class:`SegmentContact`, by segment name (e.g. "head"), in the order they first touched.
    The contact log gives the instants (first overlaps and separations, the soft contacts'
    and the exchanges' alike); the point is the vehicle's surface point nearest the segment's
    CG at the first overlap's sample. ``segments``: only these (short names, e.g.
    ``["head"]``; None: every segment)."""
    names = {s.name: s.name.split("/", 1)[1] for s in pedestrian.segments}
    if segments is not None:
        wanted = set(segments)
        unknown = wanted - set(names.values())
        if unknown:
            raise ParameterError(
                f"the pedestrian has no segment {sorted(unknown)}: it has {list(names.values())}"
            )
        names = {k: v for k, v in names.items() if v in wanted}
    car = vehicle.name
    spans: dict[str, list[list[float]]] = {}
    for c in result.contacts:
        if car not in c.vehicles:
            continue
        other = c.vehicles[0] if c.vehicles[1] == car else c.vehicles[1]
        if other not in names:
            continue
        if c.kind == "first_overlap":
            spans.setdefault(other, []).append([c.time, np.inf])
        elif c.kind == "separation" and spans.get(other):
            spans[other][-1][1] = c.time
    t = result.t
    out: dict[str, SegmentContact] = {}
    for name, intervals in sorted(spans.items(), key=lambda kv: kv[1][0][0]):
        t0 = intervals[0][0]
        k = int(np.searchsorted(t, t0 - 1e-12))
        car_tr = result.trajectory(car)
        r_c = rotation_matrix(car_tr.orientation[k])
        x_s = result.trajectory(name).position[k]
        local = matmul(r_c.T, x_s - car_tr.position[k]) + vehicle.cg  # the car's model frame
        nearest, _, _ = trimesh.proximity.closest_point(vehicle.mesh, local[None, :])
        point = nearest[0]
        touching = np.zeros(t.size, dtype=bool)
        for a, b in intervals:
            touching |= (t >= a) & (t <= b)
        speeds = _relative_speeds(result, name, vehicle, np.flatnonzero(touching), point)
        out[names[name]] = SegmentContact(
            segment=names[name],
            time=float(t0),
            point=point,
            wrap_around=wrap_around_distance(vehicle, point),
            relative_speed=float(_relative_speeds(result, name, vehicle, np.array([k]), point)[0]),
            peak_relative_speed=float(speeds.max(initial=0.0)),
        )
    return out


def whole_body(result: Result, pedestrian: Pedestrian) -> tuple[Array, Array, Array]:
    """The pedestrian's whole-body centre of mass over the run: t (k,) s, its position (k, 3)
    m and velocity (k, 3) m/s (world), its segments' weighted by their masses (every body of
    a run is sampled at the same times)."""
    total = sum(s.mass for s in pedestrian.segments)
    x = sum(s.mass * result.trajectory(s.name).position for s in pedestrian.segments)
    v = sum(s.mass * result.trajectory(s.name).velocity for s in pedestrian.segments)
    return np.asarray(result.t, dtype=np.float64), x / total, v / total


def rest_of(result: Result, pedestrian: Pedestrian) -> tuple[Array, float]:
    """The pedestrian's centre of mass at the run's last sample (world, m) and its speed
    there (m/s): the rest position when that speed is small."""
    _, x, v = whole_body(result, pedestrian)
    return x[-1], float(norm(v[-1]))


def travel(t: Array, x: Array, t0: float) -> float:
    """The horizontal distance (m) from ``x`` (k, 3) at the first sample at or after ``t0``
    (s; the last sample if none) to ``x`` at the last sample: a throw distance."""
    k0 = min(int(np.searchsorted(t, t0)), len(t) - 1)
    return float(norm(x[-1, :2] - x[k0, :2]))


# The post-impact trajectory types path_type reads (Ravani et al.'s names, SAE 811024, 1981;
# "carried": still over the vehicle's plan at the run's end).
TRAJECTORY_TYPES = ("forward projection", "wrap", "roof vault", "fender vault", "carried")


def path_type(result: Result, vehicle: Vehicle, x: Array, t0: float) -> str:
    """The trajectory type (TRAJECTORY_TYPES) of the centre-of-mass path ``x`` (k, 3; world,
    m, at the run's samples) from ``t0`` (s) on, over the plan of ``vehicle`` (its mesh's
    extent in x and y, its model frame): :func:`plan_path_type` of the path in that frame
    (crashsim.analysis.throw.trajectory_type says what each type means)."""
    t = np.asarray(result.t, dtype=np.float64)
    car = result.trajectory(vehicle.name)
    turn = rotation_matrix(car.orientation)  # (k, 3, 3) body -> world
    local = np.einsum("kji,kj->ki", turn, x - car.position) + vehicle.cg  # model frame, m
    lo, hi = np.asarray(vehicle.mesh.bounds, dtype=np.float64)
    k0 = min(int(np.searchsorted(t, t0)), len(t) - 1)
    return plan_path_type(local[k0:, :2], (lo[0], hi[0]), (lo[1], hi[1]))


def plan_path_type(
    xy: Array, x_range: tuple[float, float], y_range: tuple[float, float]
) -> str:
    """The trajectory type (TRAJECTORY_TYPES) of a path ``xy`` (k, 2) m in the vehicle's
    model frame against its plan, ``x_range`` (rear, front) and ``y_range`` (right, left) m:
    never inside the plan, "forward projection"; inside it at the end, "carried"; else by
    where it left the plan for the last time: over the front "wrap", behind the rear "roof
    vault", over a side "fender vault" (a body that leaves the plan in the air and lands on
    the vehicle again is still carried by it: its last way off names the type)."""
    (rear, front), (right, left) = x_range, y_range
    x, y = xy[:, 0], xy[:, 1]
    over = (x > rear) & (x < front) & (y > right) & (y < left)
    if not over.any():
        return "forward projection"
    if over[-1]:
        return "carried"
    k = int(np.flatnonzero(over)[-1]) + 1  # the first sample off the plan for good
    if x[k] >= front:
        return "wrap"
    if x[k] <= rear:
        return "roof vault"
    return "fender vault"


@dataclass(frozen=True)
class Throw:
    """How far a vehicle threw a person (or a bicycle): ``first_contact_time`` (s) the
    vehicle's first overlap with any of its bodies, ``distance`` (m) the horizontal travel of
    its centre of mass from that instant to the run's end (:func:`travel`); a person's
    ``trajectory`` (:func:`path_type`; None for a bicycle)."""

    first_contact_time: float
    distance: float
    trajectory: str | None = None


def _throws(
    result: Result,
    contacts: dict[str, dict[str, SegmentContact]],
    x: Array,
    vehicles: Mapping[str, Vehicle] | None = None,
) -> dict[str, Throw]:
    """Per vehicle in ``contacts`` ({vehicle: {segment: SegmentContact}}), the throw of the
    centre of mass whose path (k, 3) is ``x``; with ``vehicles`` (by name), its trajectory
    type too (a person's)."""
    t = np.asarray(result.t, dtype=np.float64)
    out = {}
    for vehicle, segs in contacts.items():
        t0 = min(c.time for c in segs.values())
        kind = None if vehicles is None else path_type(result, vehicles[vehicle], x, t0)
        out[vehicle] = Throw(float(t0), travel(t, x, t0), kind)
    return out


def _contacts_record(
    contacts: dict[str, dict[str, SegmentContact]], throws: dict[str, Throw]
) -> list[dict[str, Any]]:
    """``struck_by`` of the JSON report: per vehicle, its throw and each body's first
    contact."""
    return [
        {
            "vehicle": vehicle,
            "segments": [
                {
                    "segment": c.segment,
                    "time": c.time,
                    "point": [float(x) for x in c.point],
                    "wrap_around": c.wrap_around,
                    "relative_speed": c.relative_speed,
                    "peak_relative_speed": c.peak_relative_speed,
                }
                for c in segs.values()
            ],
            "first_contact_time": throws[vehicle].first_contact_time,
            "throw_distance": throws[vehicle].distance,
            **({} if throws[vehicle].trajectory is None
               else {"trajectory": throws[vehicle].trajectory}),
        }
        for vehicle, segs in contacts.items()
    ]


@dataclass(frozen=True)
class BicycleReport:
    """A cyclist's bicycle over the run: ``name`` (the bicycle's), ``bodies`` its bodies'
    vehicle names (frame, rear wheel, front wheel), ``mass`` (kg); ``contacts`` {vehicle:
    {body: SegmentContact}} (bodies "frame", "rear_wheel", "front_wheel"); ``throws``
    {vehicle: Throw} of the frame's CG from that vehicle's first contact with any of the
    bicycle's bodies; ``rest`` (3,) the frame's CG at the last sample (world, m) and
    ``rest_speed`` its speed there (m/s)."""

    name: str
    bodies: tuple[str, ...]
    mass: float
    contacts: dict[str, dict[str, SegmentContact]]
    throws: dict[str, Throw]
    rest: Array
    rest_speed: float

    def to_dict(self) -> dict[str, object]:
        """The JSON report's record (SI)."""
        return {
            "name": self.name,
            "bodies": list(self.bodies),
            "mass": self.mass,
            "struck_by": _contacts_record(self.contacts, self.throws),
            "rest": [float(x) for x in self.rest],
            "rest_speed": self.rest_speed,
        }


@dataclass(frozen=True)
class PedestrianReport:
    """One pedestrian, or a cyclist's rider, over the run: ``name`` (the cyclist's for a
    rider); ``contacts`` {vehicle: {segment: SegmentContact}} for every vehicle it touched;
    ``rest`` (3,) its centre of mass at the last sample (world, m) and ``rest_speed`` (m/s)
    its speed there; ``end_time`` (s); ``kind`` "pedestrian" or "cyclist"; ``bodies`` its
    segments' vehicle names; ``height`` (m) and ``mass`` (kg); ``road_friction`` (its
    segments' friction sliding on the road); ``throws`` {vehicle: Throw}
    of its whole-body centre of mass from that vehicle's first contact with a segment; a
    cyclist's ``bicycle`` (:class:`BicycleReport`)."""

    name: str
    contacts: dict[str, dict[str, SegmentContact]]
    rest: Array
    rest_speed: float
    end_time: float
    kind: str = "pedestrian"
    bodies: tuple[str, ...] = ()
    height: float | None = None
    mass: float | None = None
    throws: dict[str, Throw] = field(default_factory=dict)
    bicycle: BicycleReport | None = None
    road_friction: float | None = None

    def to_dict(self) -> dict[str, object]:
        """The JSON report's record (SI)."""
        out: dict[str, object] = {
            "name": self.name,
            "kind": self.kind,
            "bodies": list(self.bodies),
            "height": self.height,
            "mass": self.mass,
            "road_friction": self.road_friction,
            "struck_by": _contacts_record(self.contacts, self.throws),
            "rest": [float(x) for x in self.rest],
            "rest_speed": self.rest_speed,
            "end_time": self.end_time,
        }
        if self.bicycle is not None:
            out["bicycle"] = self.bicycle.to_dict()
        return out


def person_bodies(scene: PeopleOf | None) -> dict[str, str]:
    """Every body of the scene's pedestrians and cyclists (a cyclist's rider segments and its
    bicycle's bodies): its vehicle name -> the person's name ({} without a scene). A bicycle
    added on its own is not a person."""
    if scene is None:
        return {}
    out = {s.name: name for name, p in scene.pedestrians.items() for s in p.segments}
    for name, c in scene.cyclists.items():
        out.update({b.name: name for b in (*c.rider.segments, *c.bicycle.segments)})
    return out


def _struck(
    result: Result, person: Pedestrian | Bicycle, others: list[Vehicle]
) -> dict[str, dict[str, SegmentContact]]:
    """Each vehicle of ``others`` that touched the person's (or bicycle's) bodies: their
    first contacts."""
    contacts = {}
    for v in others:
        touched = segment_contacts(result, person, v)
        if touched:
            contacts[v.name] = touched
    return contacts


def _bicycle_report(result: Result, bicycle: Bicycle, others: list[Vehicle]) -> BicycleReport:
    contacts = _struck(result, bicycle, others)
    frame = result.trajectory(bicycle.frame.name)
    return BicycleReport(
        name=bicycle.name,
        bodies=tuple(b.name for b in bicycle.segments),
        mass=float(bicycle.mass),
        contacts=contacts,
        throws=_throws(result, contacts, frame.position),
        rest=np.array(frame.position[-1], dtype=np.float64),
        rest_speed=float(norm(frame.velocity[-1])),
    )


def pedestrian_reports(result: Result) -> list[PedestrianReport]:
    """Every pedestrian of the result's scene, then every cyclist (its rider's section with
    its bicycle's); none without a scene."""
    scene = result.scene
    if scene is None:
        return []
    people: list[tuple[str, Pedestrian, Bicycle | None]] = [
        ("pedestrian", p, None) for p in scene.pedestrians.values()
    ]
    people += [("cyclist", c.rider, c.bicycle) for c in scene.cyclists.values()]
    if not people:
        return []
    human = set(person_bodies(scene))
    human |= {b.name for bike in scene.bicycles.values() for b in bike.segments}
    others = [v for v in scene.vehicles if v.name not in human]
    out = []
    for kind, person, bicycle in people:
        contacts = _struck(result, person, others)
        _, x, v = whole_body(result, person)
        out.append(
            PedestrianReport(
                name=person.name,
                contacts=contacts,
                rest=x[-1],
                rest_speed=float(norm(v[-1])),
                end_time=float(result.t[-1]),
                kind=kind,
                bodies=tuple(s.name for s in person.segments),
                height=float(person.height),
                mass=float(person.mass),
                throws=_throws(result, contacts, x, {v.name: v for v in others}),
                bicycle=None if bicycle is None else _bicycle_report(result, bicycle, others),
                road_friction=float(person.road_friction),
            )
        )
    return out


def _first_contact_lines(
    contacts: dict[str, dict[str, SegmentContact]], throws: dict[str, Throw], what: str
) -> list[str]:
    """Per vehicle: the head's first contact (a person's), the first contacts, the throw."""
    lines = []
    for vehicle, segs in contacts.items():
        head = segs.get("head")
        if head is not None:
            wad = "off the front and top" if head.wrap_around is None else (
                f"wrap-around distance {head.wrap_around:.2f} m")
            lines.append(
                f"  head first touches {vehicle!r} at {head.time:.4f} s, {wad}, "
                f"{head.relative_speed:.2f} m/s relative to it (peak "
                f"{head.peak_relative_speed:.2f} m/s)"
            )  # fmt: skip
        first = ", ".join(f"{c.segment} {c.time:.4f} s ({c.relative_speed:.1f} m/s)"
                          for c in list(segs.values())[:6])  # fmt: skip
        lines.append(f"  first contacts with {vehicle!r}: {first}"
                     + (", ..." if len(segs) > 6 else ""))  # fmt: skip
        throw = throws[vehicle]
        kind = "" if throw.trajectory is None else f"; trajectory: {throw.trajectory}"
        lines.append(
            f"  throw distance from {vehicle!r}: {throw.distance:.2f} m ({what}, from the first "
            f"contact at {throw.first_contact_time:.4f} s to the end of the run{kind})"
        )
    return lines


def _end_words(x: Array, end_time: float, speed: float) -> str:
    return (
        f"({x[0]:.2f}, {x[1]:.2f}, {x[2]:.2f}) m at {end_time:.2f} s, {speed:.2f} m/s"
        + (" (at rest)" if speed < 0.1 else " (still moving)")
    )


def pedestrian_lines(reports: list[PedestrianReport]) -> list[str]:
    """The text report's lines: each person's first contacts (head first), throw and end; a
    cyclist's bicycle's too."""
    lines = []
    for r in reports:
        title = "Pedestrian" if r.kind == "pedestrian" else "Cyclist"
        rider = " (the rider)" if r.bicycle is not None else ""
        sliding = ("" if r.road_friction is None
                   else f", sliding on the road at friction {r.road_friction:g}")
        lines.append(f"{title} {r.name!r}{rider}{sliding}:")
        lines += _first_contact_lines(r.contacts, r.throws, "centre of mass")
        lines.append("  centre of mass at " + _end_words(r.rest, r.end_time, r.rest_speed))
        b = r.bicycle
        if b is None:
            continue
        lines.append(f"  the bicycle {b.name!r} ({b.mass:.2f} kg):")
        lines += ["  " + line for line in _first_contact_lines(b.contacts, b.throws, "frame")]
        lines.append("    frame's CG at " + _end_words(b.rest, r.end_time, b.rest_speed))
    return lines
