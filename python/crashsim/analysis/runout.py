"""The run-out of each vehicle: from its separation to rest (a run on a ground).

What a reconstructionist reads off the post-impact motion: the speeds at separation, where and
when each vehicle came to rest, how far it travelled, its tyre marks and what it hit.

Where the run-out starts (``RunOutReport.start``):

- "separation": the vehicle's last impulse exchange was followed by its pair's separation
  (the meshes stop overlapping): the run-out starts there (the pair's first separation after
  that exchange, so a later touch without an impulse does not move it);
- "exchange": the pair never separated (still in contact at the end, e.g. a car wrapped
  around a pole): the run-out starts at the last exchange, with the velocities after it;
- "start": the vehicle had no exchange: the whole run.

Frames, units and signs: world frame (z up), SI; angles in degrees, counter-clockwise seen
from above from world x, in (-180, 180]; the yaw rate is the world z component of the angular
velocity (deg/s, + counter-clockwise). ``distance`` is the length of the CG's path from the
start of the run-out to the end of the run (3-D, sampled at the run's samples);
``displacement`` the straight line between the two. A vehicle at rest ends at its rest
position (``Result.rest``: the position at the end of the run); one still moving at the end
has no rest time and says so. Tyre marks are ``Result.tyre_marks``: where a contact patch
slid at the friction limit (each mark's length is the length of its polyline of contact
points, m).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any

import numpy as np
from numpy.typing import NDArray

from crashsim.analysis.engagements import engagements
from crashsim.errors import SceneError
from crashsim.small_linalg import norm
from crashsim.units import to_kmh

if TYPE_CHECKING:
    from crashsim.result import Result

__all__ = [
    "ObstacleHit",
    "RunOutReport",
    "TyreMarks",
    "run_out",
    "run_out_lines",
]

Array = NDArray[np.float64]

SEPARATION, EXCHANGE, START = "separation", "exchange", "start"
UPRIGHT = 30.0  # deg: a vehicle tilted less than this is upright, more than 180 - this on its roof


def _deg(angle_rad: float) -> float:
    """Degrees in (-180, 180]."""
    d = math.degrees(math.atan2(math.sin(angle_rad), math.cos(angle_rad)))
    return 180.0 if d == -180.0 else d


def _yaw(q: Array) -> float:
    """Yaw of the body x axis from world x (rad), counter-clockwise seen from above."""
    from crashsim.records import rotation_matrix

    r = rotation_matrix(q)
    return math.atan2(float(r[1, 0]), float(r[0, 0]))


def _length(points: Array) -> float:
    """Length of a polyline (m)."""
    if len(points) < 2:
        return 0.0
    return float(np.sum(np.linalg.norm(np.diff(points, axis=0), axis=1)))


@dataclass(frozen=True)
class TyreMarks:
    """One wheel's tyre marks: ``count`` stretches where its patch slid, their total
    ``length`` and the ``longest`` (m)."""

    count: int
    length: float
    longest: float

    def to_dict(self) -> dict[str, Any]:
        return {"count": int(self.count), "length": self.length, "longest": self.longest}


@dataclass(frozen=True)
class ObstacleHit:
    """An exchange of the vehicle with a fixed obstacle: ``impact`` (its number in the report,
    1-based), ``obstacle``, ``time`` (s), ``closing_speed`` (m/s at the centroid along n),
    ``delta_v`` (|delta-V| of the CG, m/s), ``speed_before`` / ``speed_after`` (m/s)."""

    impact: int
    obstacle: str
    time: float
    closing_speed: float
    delta_v: float
    speed_before: float
    speed_after: float

    def to_dict(self) -> dict[str, Any]:
        return {
            "impact": int(self.impact),
            "obstacle": self.obstacle,
            "time": self.time,
            "closing_speed": self.closing_speed,
            "delta_v": self.delta_v,
            "speed_before": self.speed_before,
            "speed_after": self.speed_after,
        }


@dataclass(frozen=True)
class RunOutReport:
    """One vehicle's run-out (see the module docstring for frames, units and where it starts).

    At the start (``start`` "separation", "exchange" or "start"; ``start_time`` s; ``other``:
    the vehicle or obstacle it separated from or last exchanged with, None for "start"):
    ``start_position`` (3,) m, ``velocity`` (3,) m/s and ``speed`` (m/s) of the CG,
    ``yaw_rate`` (deg/s), ``direction`` of travel (deg; None below the rest speed, where it
    means nothing), ``heading`` (deg).

    At the end: ``at_rest`` (the engine's rest criterion held to the end of the run);
    ``rest_time`` (s, None when still moving) and ``time_to_rest`` = rest_time - start_time
    (s); ``end_time`` (s), ``end_speed`` (m/s), ``end_yaw_rate`` (deg/s); ``position`` (3,)
    m and ``end_heading`` (deg) at the end of the run (the rest position when at rest);
    ``tilt``: the angle between the body's z axis and the vertical then (deg, 0 upright,
    180 upside down) and ``attitude`` in words ("upright" below 30 deg, "on its roof" above
    150 deg, "on its side" between);
    ``heading_change``: the yaw turned through from the start to the end (deg, unwrapped:
    a full spin is 360). ``distance`` (m, along the CG path) and ``displacement`` (m,
    straight). ``tyre_marks`` {wheel: TyreMarks} (empty for a vehicle without wheels);
    ``obstacle_impacts``: its exchanges with fixed obstacles over the whole run."""

    vehicle: str
    start: str
    start_time: float
    other: str | None
    start_position: Array
    velocity: Array
    speed: float
    yaw_rate: float
    direction: float | None
    heading: float
    at_rest: bool
    rest_time: float | None
    time_to_rest: float | None
    end_time: float
    end_speed: float
    end_yaw_rate: float
    position: Array
    end_heading: float
    tilt: float
    attitude: str
    heading_change: float
    distance: float
    displacement: float
    tyre_marks: dict[str, TyreMarks] = field(default_factory=dict)
    obstacle_impacts: tuple[ObstacleHit, ...] = ()

    def __post_init__(self) -> None:
        for name in ("start_position", "velocity", "position"):
            a = np.array(getattr(self, name), dtype=np.float64)
            a.setflags(write=False)
            object.__setattr__(self, name, a)

    @property
    def start_words(self) -> str:
        """Where the run-out starts, in words."""
        if self.start == SEPARATION:
            return f"separation from {self.other}"
        if self.start == EXCHANGE:
            return f"last exchange (with {self.other}; never separated)"
        return "start of the run (no impact)"

    def to_dict(self) -> dict[str, Any]:
        return {
            "vehicle": self.vehicle,
            "start": {
                "kind": self.start,
                "time": self.start_time,
                "other": self.other,
                "position": [float(x) for x in self.start_position],
                "velocity": [float(x) for x in self.velocity],
                "speed": self.speed,
                "yaw_rate_deg_s": self.yaw_rate,
                "direction_of_travel_deg": self.direction,
                "heading_deg": self.heading,
            },
            "at_rest": self.at_rest,
            "rest_time": self.rest_time,
            "time_to_rest": self.time_to_rest,
            "end": {
                "time": self.end_time,
                "speed": self.end_speed,
                "yaw_rate_deg_s": self.end_yaw_rate,
                "position": [float(x) for x in self.position],
                "heading_deg": self.end_heading,
                "tilt_deg": self.tilt,
                "attitude": self.attitude,
            },
            "heading_change_deg": self.heading_change,
            "distance": self.distance,
            "displacement": self.displacement,
            "tyre_marks": {w: m.to_dict() for w, m in self.tyre_marks.items()},
            "obstacle_impacts": [h.to_dict() for h in self.obstacle_impacts],
        }


def _start(result: Result, name: str) -> tuple[str, float, str | None]:
    """(kind, time, other) of where a vehicle's run-out starts."""
    last = None
    for k, imp in enumerate(result.impacts):
        if name in imp.vehicles:
            last = k
    if last is None:
        return START, float(result.t[0]), None
    imp = result.impacts[last]
    other = imp.vehicles[1] if imp.vehicles[0] == name else imp.vehicles[0]
    for e in engagements(result):
        if last in e.exchanges and e.separation_time is not None:
            return SEPARATION, float(e.separation_time), other
    return EXCHANGE, float(imp.time), other


def _attitude(tilt: float) -> str:
    """How a vehicle lies, from its tilt (deg): upright, on its side or on its roof."""
    if tilt < UPRIGHT:
        return "upright"
    return "on its roof" if tilt > 180.0 - UPRIGHT else "on its side"


def _obstacle_hits(result: Result, name: str) -> tuple[ObstacleHit, ...]:
    out = []
    for k, imp in enumerate(result.impacts, start=1):
        if imp.obstacle is None or name not in imp.vehicles:
            continue
        out.append(
            ObstacleHit(
                impact=k,
                obstacle=imp.obstacle,
                time=float(imp.time),
                closing_speed=float(imp.closing_speed),
                delta_v=imp.speed_change(name),
                speed_before=float(norm(imp.velocity_before[name])),
                speed_after=float(norm(imp.velocity_after[name])),
            )
        )
    return tuple(out)


def _tyre_marks(result: Result, name: str) -> dict[str, TyreMarks]:
    try:
        marks = result.tyre_marks(name)
    except SceneError:  # a vehicle without wheels slides on its body: no tyre marks
        return {}
    out = {}
    for wheel, lines in marks.items():
        lengths = [_length(np.asarray(line)) for line in lines]
        out[wheel] = TyreMarks(len(lines), float(sum(lengths)), max(lengths, default=0.0))
    return out


def run_out(result: Result, vehicle: Any) -> RunOutReport:
    """The run-out of one vehicle (name or Vehicle) of a run on a ground (SceneError for a
    run without one: nothing slows the vehicles there)."""
    if not result.on_ground:
        raise SceneError("the run had no ground: there is no run-out to rest to report")
    name = result._vehicle_name(vehicle)
    kind, t0, other = _start(result, name)
    tr = result.trajectory(name)
    s = result.state(name, t0)
    after = int(np.searchsorted(tr.t, t0, side="right"))  # the samples after the start
    path = np.vstack([np.asarray(s["position"])[None, :], tr.position[after:]])
    yaws = np.unwrap([_yaw(s["orientation"]), *(_yaw(q) for q in tr.orientation[after:])])
    velocity = np.asarray(s["velocity"], dtype=np.float64)
    speed = float(norm(velocity))
    from crashsim.vehicles.wheels import dynamics_defaults

    moving = speed >= dynamics_defaults()["rest_speed"]
    rest = result.rest(name)
    end_v = tr.velocity[-1]
    from crashsim.records import rotation_matrix

    up = float(rotation_matrix(tr.orientation[-1])[2, 2])  # body z . world z
    tilt = math.degrees(math.acos(max(-1.0, min(1.0, up))))
    return RunOutReport(
        vehicle=name,
        start=kind,
        start_time=t0,
        other=other,
        start_position=np.asarray(s["position"]),
        velocity=velocity,
        speed=speed,
        yaw_rate=math.degrees(float(s["angular_velocity"][2])),
        direction=_deg(math.atan2(velocity[1], velocity[0])) if moving else None,
        heading=_deg(float(yaws[0])),
        at_rest=rest is not None,
        rest_time=None if rest is None else float(rest.time),
        time_to_rest=None if rest is None else max(0.0, float(rest.time) - t0),
        end_time=float(tr.t[-1]),
        end_speed=float(norm(end_v)),
        end_yaw_rate=math.degrees(float(tr.angular_velocity[-1][2])),
        position=tr.position[-1],
        end_heading=_deg(float(yaws[-1])),
        tilt=tilt,
        attitude=_attitude(tilt),
        heading_change=math.degrees(float(yaws[-1] - yaws[0])),
        distance=_length(path),
        displacement=float(norm(path[-1] - path[0])),
        tyre_marks=_tyre_marks(result, name),
        obstacle_impacts=_obstacle_hits(result, name),
    )


# -- the text ----------------------------------------------------------------------------


def _f(x: float | None, digits: int) -> str:
    if x is None:
        return "n/a"
    text = f"{x:.{digits}f}"
    return text[1:] if text.startswith("-") and float(text) == 0.0 else text


def run_out_lines(reports: list[RunOutReport], table: Any, obstacles: bool = False) -> list[str]:
    """The run-out section of the text report. ``table(headers, rows)`` makes a plain table;
    ``obstacles``: the scene has fixed obstacles (their impacts are listed, "none" too)."""
    lines = [
        "Run-out (each vehicle from its separation to the end of the run; world frame, z up; "
        "directions and headings counter-clockwise from world x; yaw rate + counter-clockwise):",
    ]
    lines += table(
        [
            "Vehicle",
            "from",
            "t (s)",
            "speed (m/s)",
            "speed (km/h)",
            "yaw rate (deg/s)",
            "travel dir. (deg)",
            "heading (deg)",
        ],
        [
            [
                r.vehicle,
                r.start_words,
                _f(r.start_time, 3),
                _f(r.speed, 3),
                _f(to_kmh(r.speed), 2),
                _f(r.yaw_rate, 2),
                _f(r.direction, 2),
                _f(r.heading, 2),
            ]
            for r in reports
        ],
    )
    lines.append("")
    lines += table(
        [
            "Vehicle",
            "at rest at t (s)",
            "time to rest (s)",
            "rest x (m)",
            "rest y (m)",
            "rest heading (deg)",
            "turned (deg)",
            "distance (m)",
            "displacement (m)",
        ],
        [
            [
                r.vehicle,
                _f(r.rest_time, 3) if r.at_rest else "NOT AT REST",
                _f(r.time_to_rest, 3),
                _f(float(r.position[0]), 3),
                _f(float(r.position[1]), 3),
                _f(r.end_heading, 2),
                _f(r.heading_change, 1),
                _f(r.distance, 3),
                _f(r.displacement, 3),
            ]
            for r in reports
        ],
    )
    lines += _end_state_lines(reports)
    lines += _marks_and_obstacle_lines(reports, obstacles)
    return lines


def _end_state_lines(reports: list[RunOutReport]) -> list[str]:
    """The run-out's notes: a vehicle that ends tipped or not at rest, and what distance and
    displacement mean."""
    lines: list[str] = []
    for r in reports:
        if r.attitude != "upright":
            lines.append(
                f"  {r.vehicle} ends {r.attitude}: its body z axis {_f(r.tilt, 1)} deg from "
                "the vertical"
            )
        if not r.at_rest:
            lines.append(
                f"  {r.vehicle} did NOT reach rest: still moving at t = {_f(r.end_time, 3)} s, "
                f"speed {_f(r.end_speed, 3)} m/s ({_f(to_kmh(r.end_speed), 2)} km/h), yaw rate "
                f"{_f(r.end_yaw_rate, 2)} deg/s; its position, heading and distance are at that "
                "time (run longer: max_duration)"
            )
    lines.append(
        "  distance: along the CG path (3-D) from the start of the run-out to the end of the "
        "run; displacement: the straight line between them"
    )
    return lines


def _marks_and_obstacle_lines(reports: list[RunOutReport], obstacles: bool) -> list[str]:
    """Each vehicle's tyre marks (m, count) and, when the scene has fixed obstacles, its
    impacts with them ("none" too)."""
    lines: list[str] = []
    lines.append(
        "  Tyre marks (where a tyre's contact patch slid at the friction limit; total length "
        "in m, number of marks):"
    )
    for r in reports:
        if not r.tyre_marks:
            lines.append(f"  {r.vehicle}: no wheels, no tyre marks")
            continue
        lines.append(
            f"  {r.vehicle}: "
            + ", ".join(f"{w} {_f(m.length, 2)} m ({m.count})" for w, m in r.tyre_marks.items())
        )
    if obstacles:
        lines.append("  Impacts with fixed obstacles:")
        for r in reports:
            if not r.obstacle_impacts:
                lines.append(f"  {r.vehicle}: none")
            for h in r.obstacle_impacts:
                lines.append(
                    f"  {r.vehicle}: impact {h.impact} with {h.obstacle} at t = {_f(h.time, 3)} "
                    f"s, closing speed {_f(h.closing_speed, 3)} m/s, delta-V "
                    f"{_f(h.delta_v, 3)} m/s ({_f(to_kmh(h.delta_v), 2)} km/h), speed "
                    f"{_f(h.speed_before, 3)} -> {_f(h.speed_after, 3)} m/s"
                )
    return lines
