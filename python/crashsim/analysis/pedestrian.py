"""A struck pedestrian's figures from a run (issue 22; docs/human.md, "Head impact"): each
segment's first contact with a vehicle (when, the segment's speed relative to the vehicle at
the contact point, where on the vehicle, the wrap-around distance there), its largest relative
speed while in contact, and where the person's centre of mass comes to rest.

Frames: world (x, y, z up, m); a vehicle's model frame (x forward from the body's middle, y
left, z up from the road: the mesh's own coordinates). Speeds in m/s, times in s.
"""

from __future__ import annotations

from collections.abc import Iterable
from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np
import trimesh
from numpy.typing import ArrayLike

from crashsim.errors import ParameterError
from crashsim.result import Result, rotation_matrix

if TYPE_CHECKING:
    from crashsim.human.pedestrian import Pedestrian
    from crashsim.vehicles.vehicle import Vehicle

Array = np.ndarray

__all__ = [
    "PedestrianReport",
    "SegmentContact",
    "pedestrian_lines",
    "pedestrian_reports",
    "rest_of",
    "segment_contacts",
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
            s = float(np.clip(np.dot(p[[0, 2]] - a, ab) / max(float(ab @ ab), 1e-300), 0, 1))
            d = float(np.linalg.norm(a + s * ab - p[[0, 2]]))
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
        local = r_c.T @ (x_s - car_tr.position[k]) + vehicle.cg  # the car's model frame
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
    return x[-1], float(np.linalg.norm(v[-1]))


@dataclass(frozen=True)
class PedestrianReport:
    """One pedestrian over the run: ``name``; ``contacts`` {vehicle: {segment:
    SegmentContact}} for every vehicle it touched; ``rest`` (3,) its centre of mass at the
    last sample (world, m) and ``rest_speed`` (m/s) its speed there; ``end_time`` (s)."""

    name: str
    contacts: dict[str, dict[str, SegmentContact]]
    rest: Array
    rest_speed: float
    end_time: float

    def to_dict(self) -> dict[str, object]:
        """The JSON report's record (SI)."""
        return {
            "name": self.name,
            "struck_by": [
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
                }
                for vehicle, segs in self.contacts.items()
            ],
            "rest": [float(x) for x in self.rest],
            "rest_speed": self.rest_speed,
            "end_time": self.end_time,
        }


def pedestrian_reports(result: Result) -> list[PedestrianReport]:
    """Every pedestrian of the result's scene (none without one)."""
    scene = result.scene
    if scene is None or not scene.pedestrians:
        return []
    out = []
    segments = {s.name for p in scene.pedestrians.values() for s in p.segments}
    others = [v for v in scene.vehicles if v.name not in segments]
    for name, person in scene.pedestrians.items():
        contacts = {}
        for v in others:
            touched = segment_contacts(result, person, v)
            if touched:
                contacts[v.name] = touched
        rest, speed = rest_of(result, person)
        out.append(PedestrianReport(name, contacts, rest, speed, float(result.t[-1])))
    return out


def pedestrian_lines(reports: list[PedestrianReport]) -> list[str]:
    """The text report's lines: each pedestrian's first contacts (head first) and its end."""
    lines = []
    for r in reports:
        lines.append(f"Pedestrian {r.name!r}:")
        for vehicle, segs in r.contacts.items():
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
        x = r.rest
        lines.append(
            f"  centre of mass at ({x[0]:.2f}, {x[1]:.2f}, {x[2]:.2f}) m at {r.end_time:.2f} s, "
            f"{r.rest_speed:.2f} m/s"
            + (" (at rest)" if r.rest_speed < 0.1 else " (still moving)")
        )
    return lines
