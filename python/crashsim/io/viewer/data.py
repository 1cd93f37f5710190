"""What a case page holds, collected from a Result: one JSON-ready dict (``page_data``).

Data flows one way: Result (and the report built from it) -> this dict -> the page. Nothing
here computes a figure the page shows as a number: the tables are the report's ``to_dict()``
as it is, and the poses are the run's samples, which the page interpolates exactly as
``Result.state`` does (``interpolation``):

- "torque-free" (a run without a ground): the last sample at or before t carried forward by
  torque-free motion, with the engine's own integrator (RK4 on the quaternion in sub-steps
  of at most 0.01 rad, from the world angular momentum and the body inertia);
- "hermite" (a run on the ground, where forces act between samples): cubic Hermite on the
  position with the sampled velocities as slopes, slerp on the orientation.

Parts a run may or may not have (fixed obstacles, a ground with friction zones or a terrain,
tyre marks, rest positions) are read with ``getattr`` and drawn when present.

The format ("crashsim-view", version 1): see docs/viewer.md.
"""

from __future__ import annotations

import math
from typing import TYPE_CHECKING, Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

from crashsim._core import __version__
from crashsim.analysis.report import build_report
from crashsim.errors import CrashsimError, ParameterError, SceneError
from crashsim.io.viewer.meshes import DEFAULT_MAX_TRIANGLES, pack_array, pack_mesh
from crashsim.plots import VEHICLE_COLOURS
from crashsim.plots.common import SHADE

if TYPE_CHECKING:
    from crashsim.result import Result

__all__ = [
    "DEFAULT_MAX_SAMPLES",
    "FORMAT",
    "FORMAT_VERSION",
    "MAX_REGION_POINTS",
    "SAMPLE_KEYS",
    "arrow_scales",
    "body_entry",
    "colour_of",
    "dynamics",
    "people_of",
    "person_fields",
    "vehicle_colours",
    "keep_samples",
    "page_data",
]

Array = NDArray[np.float64]

FORMAT = "crashsim-view"
FORMAT_VERSION = 1
# Samples kept per body; a longer run keeps every k-th plus every event sample (see
# keep_samples). 13 float64 per body and sample: 5000 samples are 520 kB per body raw.
DEFAULT_MAX_SAMPLES = 5000
MAX_REGION_POINTS = 3000  # overlap-region points drawn per impact (evenly thinned)
MAX_MARK_POINTS = 2000  # points per tyre-mark polyline (evenly thinned)
OBSTACLE_COLOUR = "#7f7f7f"
SAMPLE_KEYS = ("position", "orientation", "velocity", "angular_velocity")


def _vec(a: ArrayLike) -> list[float]:
    return [float(x) for x in np.asarray(a, dtype=np.float64).reshape(-1)]


def _nice(x: float) -> float:
    """The number of the form 1, 2, 2.5 or 5 times a power of ten nearest to x (x > 0) by
    ratio (the plots' arrow scales are picked the same way)."""
    e = 10.0 ** math.floor(math.log10(x))
    return min((m * e for m in (1.0, 2.0, 2.5, 5.0, 10.0)), key=lambda c: abs(math.log(c / x)))


def _thin(points: Array, limit: int) -> Array:
    """At most ``limit`` rows, evenly spaced, first and last kept."""
    if len(points) <= limit:
        return points
    return points[np.unique(np.linspace(0, len(points) - 1, limit).round().astype(int))]


def keep_samples(t: Array, events: ArrayLike, max_samples: int) -> NDArray[np.int64]:
    """Indices of the samples a page keeps: all of them when there are at most
    ``max_samples``; else every k-th (k the smallest stride that fits), the last one, and
    every sample at an event time (first overlaps and exchanges: velocities jump there, and
    Result.state reads the last sample at a time). Without a ground this loses nothing (the
    state between events is torque-free from any earlier sample); on the ground the page
    interpolates between the kept samples only (docs/viewer.md)."""
    n = len(t)
    if n <= max_samples:
        return np.arange(n, dtype=np.int64)
    ev = np.asarray(events, dtype=np.float64).reshape(-1)
    at_event = np.isin(t, ev)
    budget = max(2, max_samples - int(at_event.sum()) - 1)
    stride = int(math.ceil(n / budget))
    keep = np.zeros(n, dtype=bool)
    keep[::stride] = True
    keep[-1] = True
    keep |= at_event
    return np.flatnonzero(keep).astype(np.int64)


def arrow_scales(
    delta_vs: list[Array], impulses: list[Array], lengths: list[float]
) -> dict[str, float]:
    """The exchange arrows' scales: ``velocity`` (m/s per m of arrow; delta-V) and
    ``impulse`` (N s per m), round numbers picked so that the largest delta-V is about half
    and the largest impulse about 0.4 of the longest body (m)."""
    size = max(lengths, default=1.0) or 1.0
    dv = [float(np.linalg.norm(v)) for v in delta_vs]
    jj = [float(np.linalg.norm(j)) for j in impulses]
    dv_max = max([x for x in dv if x > 0.0], default=1.0)
    j_max = max([x for x in jj if x > 0.0], default=1000.0)
    return {"velocity": _nice(dv_max / (0.5 * size)), "impulse": _nice(j_max / (0.4 * size))}


def body_entry(
    name: str,
    kind: str,
    colour: str,
    mesh: tuple[ArrayLike, ArrayLike],
    samples: dict[str, ArrayLike],
    max_triangles: int,
) -> dict[str, Any]:
    """One body of the page: its mesh (in the frame its samples pose) packed for display and
    its kept samples (position (k, 3), orientation (k, 4), velocity, angular_velocity)."""
    return {
        "name": name,
        "kind": kind,
        "colour": colour,
        "mesh": pack_mesh(mesh[0], mesh[1], max_triangles),
        "samples": {
            key: pack_array(samples[key], "f8")
            for key in ("position", "orientation", "velocity", "angular_velocity")
        },
    }


def dynamics(mass: float, inertia: ArrayLike) -> dict[str, Any]:
    """What the page's torque-free motion needs: mass (kg), body inertia and its inverse
    (kg m^2, kg^-1 m^-2) and the smallest principal moment (the engine's sub-step bound)."""
    i = np.asarray(inertia, dtype=np.float64).reshape(3, 3)
    return {
        "mass": float(mass),
        "inertia": _vec(i),
        "inverse_inertia": _vec(np.linalg.inv(i)),
        "min_principal": float(np.linalg.eigvalsh(i)[0]),
    }


def colour_of(index: int, obstacle: bool) -> str:
    """A body's colour: the plots' colour of the vehicle's index, grey for an obstacle."""
    return OBSTACLE_COLOUR if obstacle else VEHICLE_COLOURS[index % len(VEHICLE_COLOURS)]


def people_of(report: dict[str, Any]) -> dict[str, tuple[str, str]]:
    """Each body of a person in a report's ``pedestrians`` (its ``bodies``, a cyclist's
    ``bicycle.bodies``): its name -> (the person's name, "segment" or "bicycle"). A report
    written before those keys has none: its bodies are drawn as vehicles."""
    out: dict[str, tuple[str, str]] = {}
    people = report.get("pedestrians")
    for person in people if isinstance(people, list) else []:
        if not isinstance(person, dict):
            continue  # not a report's record: its bodies stay vehicles
        name = str(person.get("name"))
        bicycle = person.get("bicycle")
        for role, bodies in (
            ("segment", person.get("bodies")),
            ("bicycle", bicycle.get("bodies") if isinstance(bicycle, dict) else None),
        ):
            if isinstance(bodies, list):
                out.update({str(b): (name, role) for b in bodies})
    return out


def _darker(colour: str) -> str:
    """A hex colour SHADE of the way to black (a cyclist's bicycle: the plots' shade)."""
    rgb = [int(colour[i : i + 2], 16) for i in (1, 3, 5)]
    return "#" + "".join(f"{round((1.0 - SHADE) * c):02x}" for c in rgb)


def vehicle_colours(names: list[str], people: dict[str, tuple[str, str]]) -> list[str]:
    """Each vehicle's colour on the page: the plots' colours in order, one per vehicle and one
    per person (all its segments; a cyclist's bicycle in that colour's darker shade)."""
    index: dict[str, int] = {}
    out = []
    for name in names:
        unit, role = people.get(name, (name, "vehicle"))
        k = index.setdefault(unit, len(index))
        colour = colour_of(k, False)
        out.append(_darker(colour) if role == "bicycle" else colour)
    return out


def person_fields(name: str, people: dict[str, tuple[str, str]]) -> dict[str, Any]:
    """A body's ``person`` (the person's name, or None for a vehicle) and ``role``
    ("segment", "bicycle", or None)."""
    person, role = people.get(name, (None, None))
    return {"person": person, "role": role}


def _body_mesh(result: Result, name: str, obstacle: bool) -> tuple[Array, NDArray[np.int64]]:
    """A body's mesh in the frame its trajectory poses (a vehicle's body frame, origin at the
    CG; an obstacle's own frame)."""
    if obstacle:
        mesh = result.obstacle(name).mesh  # type: ignore[attr-defined]
        return np.asarray(mesh.vertices, dtype=np.float64), np.asarray(mesh.faces, np.int64)
    v = result.vehicle(name)
    return np.asarray(v.body_vertices, dtype=np.float64), np.asarray(v.mesh.faces, np.int64)


def _impact(imp: Any, number: int) -> dict[str, Any]:
    """One exchange as the page draws it (world frame, SI)."""
    return {
        "number": number,
        "vehicles": list(imp.vehicles),
        "obstacle": getattr(imp, "obstacle", None),
        "secondary": bool(imp.secondary),
        "first_contact_time": float(imp.first_contact_time),
        "time": float(imp.time),
        "centroid": _vec(imp.centroid),
        "normal": _vec(imp.normal),
        "impulse": _vec(imp.impulse),  # on vehicle 2
        "delta_v": {k: _vec(v) for k, v in imp.delta_v.items()},
        "contact_frame": _vec(imp.contact_frame),  # rows n, t, b
        "region_min": _vec(imp.region_min),
        "region_max": _vec(imp.region_max),
        "region_points_total": int(len(imp.region_points)),
        "region_points": pack_array(_thin(np.asarray(imp.region_points), MAX_REGION_POINTS), "f4"),
    }


def _ground(result: Result, max_triangles: int) -> dict[str, Any]:
    """The ground: its height (m), friction and zones, a terrain mesh when there is one.
    A run without a ground model still stands on z = 0 (the world's convention)."""
    ground = getattr(result.scene, "ground", None)
    out: dict[str, Any] = {"modelled": ground is not None, "height": 0.0, "zones": []}
    if ground is None:
        return out
    out["height"] = float(getattr(ground, "height", 0.0) or 0.0)
    friction = getattr(ground, "friction", None)
    out["friction"] = None if friction is None else float(friction)
    out["surface"] = getattr(ground, "surface", None)
    for k, zone in enumerate(getattr(ground, "zones", ()) or ()):
        label = zone.label(k) if hasattr(zone, "label") else f"zone {k}"
        out["zones"].append(
            {
                "label": str(label),
                "friction": float(zone.friction),
                "polygon": [_vec(p) for p in np.asarray(zone.polygon, dtype=np.float64)],
            }
        )
    terrain = getattr(ground, "terrain", None)
    if terrain is not None:
        out["terrain"] = pack_mesh(terrain.vertices, terrain.faces, max_triangles)
    return out


def _tyre_marks(result: Result, name: str) -> list[list[list[float]]]:
    """A vehicle's tyre marks (polylines, m, world), [] when the run has none."""
    marks = getattr(result, "tyre_marks", None)
    if marks is None:
        return []
    try:
        per_wheel = marks(name)
    except CrashsimError:  # no wheels, or no ground
        return []
    return [
        [_vec(p) for p in _thin(np.asarray(line, dtype=np.float64), MAX_MARK_POINTS)]
        for lines in per_wheel.values()
        for line in lines
    ]


def _rest(result: Result, name: str) -> dict[str, Any] | None:
    """Where a vehicle came to rest (None when the run has no rest states or it kept
    moving): time (s), CG position (m) and orientation (the last sample), heading (rad)."""
    rest = getattr(result, "rest", None)
    if rest is None:
        return None
    state = rest(name)
    if state is None:
        return None
    tr = result.trajectory(name)
    return {
        "time": float(state.time),
        "position": _vec(state.position),
        "orientation": _vec(tr.orientation[-1]),
        "heading": float(state.heading),
    }


def page_data(
    result: Result,
    *,
    title: str | None = None,
    max_triangles: int = DEFAULT_MAX_TRIANGLES,
    max_samples: int = DEFAULT_MAX_SAMPLES,
) -> dict[str, Any]:
    """The page's data of a run (a Result that keeps its scene, as Scene.run returns it)."""
    if getattr(result, "scene", None) is None:
        raise SceneError(
            "this result has no scene, so no vehicle meshes or masses to show: view the "
            "Result that Scene.run returned"
        )
    for key, value, least in (("max_triangles", max_triangles, 1), ("max_samples", max_samples, 2)):
        if isinstance(value, bool) or not isinstance(value, int | np.integer) or value < least:
            raise ParameterError(f"{key} must be an integer >= {least}, got {value!r}")
    report = build_report(result).to_dict()
    t = np.asarray(result.t, dtype=np.float64)
    events = [x for imp in result.impacts for x in (imp.first_contact_time, imp.time)]
    events += [c.time for c in result.contacts]
    keep = keep_samples(t, events, int(max_samples))
    obstacles = list(getattr(result, "obstacles", []) or [])
    people = people_of(report)
    colours = vehicle_colours(list(result.vehicles), people)
    bodies = []
    lengths = []
    for k, name in enumerate([*result.vehicles, *obstacles]):
        is_obstacle = name in obstacles
        tr = result.trajectory(name)
        mesh = _body_mesh(result, name, is_obstacle)
        lengths.append(float(np.max(np.ptp(mesh[0], axis=0))) if len(mesh[0]) else 0.0)
        body = body_entry(
            name,
            "obstacle" if is_obstacle else "vehicle",
            colour_of(k, True) if is_obstacle else colours[k],
            mesh,
            {key: np.asarray(getattr(tr, key))[keep] for key in SAMPLE_KEYS},
            int(max_triangles),
        )
        if not is_obstacle:
            vehicle = result.vehicle(name)
            body.update(dynamics(vehicle.mass, vehicle.inertia))
            body["tyre_marks"] = _tyre_marks(result, name)
            body["rest"] = _rest(result, name)
            body.update(person_fields(name, people))
        bodies.append(body)
    scales = arrow_scales(
        [v for imp in result.impacts for v in imp.delta_v.values()],
        [imp.impulse for imp in result.impacts],
        lengths,
    )
    return {
        "format": FORMAT,
        "version": FORMAT_VERSION,
        "crashsim_version": str(__version__),
        "title": title or "crashsim case: " + ", ".join(dict.fromkeys(
            people.get(n, (n, ""))[0] for n in result.vehicles)),  # fmt: skip
        "source": "run",
        "interpolation": "hermite" if getattr(result, "on_ground", False) else "torque-free",
        "samples": {"total": int(t.size), "kept": int(keep.size), "t": pack_array(t[keep], "f8")},
        "run": {
            "duration": None if result.duration is None else float(result.duration),
            "dt": None if result.dt is None else float(result.dt),
            "record_interval": None
            if getattr(result, "record_interval", None) is None
            else float(result.record_interval),  # type: ignore[arg-type]
        },
        "bodies": bodies,
        "impacts": [_impact(imp, i) for i, imp in enumerate(result.impacts, start=1)],
        "contacts": [c.to_dict() for c in result.contacts],
        "ground": _ground(result, int(max_triangles)),
        "scales": scales,
        "report": report,
    }
