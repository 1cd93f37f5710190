"""Pedestrians in studies and fits (docs/studies.md, "Pedestrians"): each variant's scene with
its pedestrians rebuilt, and the figures a study records per variant.

A pedestrian's own paths (crashsim.studies.paths: ``<p>.height``, ``.mass``,
``.percentile``, ``.pose``, ``.passive_moments``, ``.road_friction``, ``.position_x``,
``.position_y``, ``.heading``, ``.speed``) change its segments' shapes, masses, joints,
friction and places, which the batch engine's override arrays cannot carry: a variant
**rebuilds the Pedestrian** (``Pedestrian(**arguments)`` with the variant's values) and
places it as
``Scene.add(pedestrian, position, heading=, velocity=)`` did in the base scene, in a scene
of the same ground; its segments and joints take the places of the base's under the same
names, so every pair's contact parameters, the no-contact pairs and the soft contacts carry
over. ``<v>/<p>.stiffness`` and ``.damping_ratio`` set the soft contact of vehicle v with
every segment of p.

A scene with pedestrians runs each variant as a Scene (crashsim.studies.scene_runs: threads
of this machine), not through the batch: the figures of the person (throw distance, the head's first
contact, its place on the vehicle) need each run's trajectories and contact log, which the
batch does not keep. Per variant the study records the batch's columns of the vehicles that
are not a pedestrian's segments, read from the Result as crashsim.batch defines them, and per
pedestrian p and striking vehicle v (units m, m/s, s):

- ``p.final_x``, ``p.final_y``, ``p.final_speed``: the whole-body centre of mass at the last
  sample (world) and its speed; ``p.rest_x``, ``p.rest_y``: the same when that speed is below
  REST_SPEED, else NaN (with ``until="rest"`` the run ends when every body, the person's
  segments included, passes the engine's rest test: docs/human.md, item 7a);
- ``p.v.first_contact_time``, ``p.v.throw_distance`` (crashsim.analysis.throw);
- ``p.v.head_time``, ``p.v.head_x``, ``p.v.head_y``, ``p.v.head_z`` (the head's first overlap
  with v, and v's surface point nearest the head's CG then, in v's model frame),
  ``p.v.head_wrap_around``, ``p.v.head_relative_speed``
  (crashsim.analysis.pedestrian.segment_contacts); NaN when the head never touched v.
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from typing import TYPE_CHECKING, Any

import numpy as np
from numpy.typing import NDArray

from crashsim import _core
from crashsim.errors import ParameterError, StudyError

if TYPE_CHECKING:
    from crashsim.human.pedestrian import Pedestrian
    from crashsim.result import Result
    from crashsim.studies.view import SceneLike, SceneView

__all__ = [
    "KEY",
    "REST_SPEED",
    "column_names",
    "columns_of",
    "empty_columns",
    "pose_name",
    "rebuild",
]

Array = NDArray[np.float64]

KEY = "pedestrian:"  # prefix of a study's arrays that rebuild a pedestrian (never the batch's)
REST_SPEED = 0.1  # m/s: the whole-body CG slower than this at the end is at rest (assumed)
HEAD = "head"
_HEAD_FIGURES = ("head_time", "head_x", "head_y", "head_z", "head_wrap_around",
                 "head_relative_speed")  # fmt: skip


def pose_name(value: float) -> str:
    """The pose of a ``<p>.pose`` value: its index in crashsim.human.pedestrian.POSES (0
    standing, 1 walking, 3 running; 2, cycling, is a cyclist's); ParameterError for any other
    number."""
    from crashsim.human.pedestrian import POSES

    x = float(value)
    if not (math.isfinite(x) and x.is_integer() and 0 <= x < len(POSES)):
        listed = ", ".join(f"{k} = {p}" for k, p in enumerate(POSES))
        raise ParameterError(f"pose = {value!r} is not a pose's number: give {listed}")
    return POSES[int(x)]


def segment_names(scene: SceneView) -> set[str]:
    """The names of every pedestrian's segments in the scene."""
    return {s.name for p in scene.pedestrians.values() for s in p.segments}


# -- one variant's scene ----------------------------------------------------------------------


_Values = dict[str, dict[str, float]]
_SoftValues = dict[tuple[str, str], dict[str, float]]


def _split(arrays: Mapping[str, Array], i: int) -> tuple[_Values, _SoftValues]:
    """Variant i's pedestrian values {pedestrian: {parameter: value}} and soft-contact values
    {(vehicle, pedestrian): {parameter: value}} from the study's KEY arrays."""
    people: _Values = {}
    soft: _SoftValues = {}
    for key, arr in arrays.items():
        if not key.startswith(KEY):
            continue
        target, _, parameter = key[len(KEY):].rpartition(".")
        value = float(np.asarray(arr)[i])
        if parameter in ("stiffness", "damping_ratio"):
            other, _, person = target.rpartition("/")
            soft.setdefault((other, person), {})[parameter] = value
        else:
            people.setdefault(target, {})[parameter] = value
    return people, soft


def _turn(v: Array, angle: float) -> Array:
    c, s = math.cos(angle), math.sin(angle)
    return np.array([c * v[0] - s * v[1], s * v[0] + c * v[1], v[2]])


def _new_person(old: Pedestrian, place: tuple[Array, float, Array], values: Mapping[str, float]
                ) -> tuple[Pedestrian, Array, float, Array]:  # fmt: skip
    """The rebuilt pedestrian and where it goes: (person, position, heading rad, velocity)."""
    from crashsim.human.pedestrian import Pedestrian

    args = old.arguments
    if "height" in values:
        args["height"], args["percentile"] = values["height"], None
    if "percentile" in values:
        args["percentile"] = values["percentile"]
    if "pose" in values:
        args["pose"] = pose_name(values["pose"])
    for key in ("mass", "passive_moments", "road_friction"):  # Pedestrian's own arguments
        if key in values:
            args[key] = values[key]
    position = np.array(place[0], dtype=np.float64)
    heading, velocity = place[1], np.array(place[2], dtype=np.float64)
    if "position_x" in values:
        position[0] = values["position_x"]
    if "position_y" in values:
        position[1] = values["position_y"]
    if "heading" in values:  # the velocity turns with the body, as a vehicle's does
        velocity = _turn(velocity, values["heading"] - heading)
        heading = values["heading"]
    if "speed" in values:
        size = float(np.linalg.norm(velocity))
        if size > 0.0:
            velocity = velocity * (values["speed"] / size)
        else:  # at rest: along its facing
            velocity = values["speed"] * np.array([math.cos(heading), math.sin(heading), 0.0])
    return Pedestrian(**args), position, heading, velocity


def rebuild(scene: SceneLike, arrays: Mapping[str, Array], i: int) -> tuple[SceneLike, set[str]]:
    """A copy of ``scene`` with variant ``i``'s pedestrians rebuilt and soft contacts set (the
    study's KEY arrays), and the names of the segments whose placements it made (the caller
    leaves their states alone). ParameterError (that variant fails) for a value the
    Pedestrian or the soft contact refuses."""
    people, soft = _split(arrays, i)
    placed = {name: _new_person(scene.pedestrians[name], scene.pedestrian_place(name), values)
              for name, values in people.items()}  # fmt: skip
    pairs: dict[frozenset[str], tuple[float, float]] = {}
    for (other, name), values in soft.items():
        # (a rebuilt person's segments keep their names)
        for seg in scene.pedestrians[name].segments:
            base = scene.soft_contact_of(other, seg.name)
            if base is None:  # the paths offer these parameters only where every segment has one
                raise StudyError(f"{other!r} and {seg.name!r} have no soft contact to vary")
            k, zeta = values.get("stiffness", base[0]), values.get("damping_ratio", base[1])
            _core.check_soft_contact(k, zeta)
            pairs[frozenset((other, seg.name))] = (k, zeta)
    return scene._with_people(placed, pairs)


# -- the figures of a run ---------------------------------------------------------------------


def _struck(scene: SceneView) -> list[str]:
    """The vehicles that are not a pedestrian's segments, in the order added."""
    segments = segment_names(scene)
    return [v.name for v in scene.vehicles if v.name not in segments]


def column_names(scene: SceneView, max_impacts: int) -> dict[str, type]:
    """The columns of a pedestrian scene's study, in order, and their dtypes."""
    cars = _struck(scene)
    out: dict[str, type] = {"n_impacts": np.int64}
    for k in range(1, max_impacts + 1):
        out[f"impact{k}.time"] = out[f"impact{k}.energy"] = np.float64
        for n in cars:
            for c in ("delta_v", "delta_v_x", "delta_v_y", "delta_v_long", "delta_v_lat",
                      "pdof_deg"):  # fmt: skip
                out[f"impact{k}.{n}.{c}"] = np.float64
    for n in cars:
        for c in ("total_delta_v", "final_x", "final_y", "final_heading_deg", "final_speed",
                  "rest_time", "rest_x", "rest_y", "rest_heading_deg"):  # fmt: skip
            out[f"{n}.{c}"] = np.float64
    for p in scene.pedestrians:
        for c in ("final_x", "final_y", "final_speed", "rest_x", "rest_y"):
            out[f"{p}.{c}"] = np.float64
        for n in cars:
            for c in ("first_contact_time", "throw_distance", *_HEAD_FIGURES):
                out[f"{p}.{n}.{c}"] = np.float64
    return out


def empty_columns(scene: SceneView, n: int, max_impacts: int) -> dict[str, np.ndarray]:
    return {k: np.full(n, -1 if t is np.int64 else np.nan, dtype=t)
            for k, t in column_names(scene, max_impacts).items()}  # fmt: skip


def _vehicle_figures(result: Result, cars: list[str], max_impacts: int) -> dict[str, float]:
    """The batch's columns of ``cars`` read from a Result (crashsim.batch's definitions)."""
    from crashsim.analysis.impact_report import pdof

    nan = math.nan
    out: dict[str, float] = {"n_impacts": len(result.impacts)}
    for k in range(1, max_impacts + 1):
        imp = result.impacts[k - 1] if k <= len(result.impacts) else None
        out[f"impact{k}.time"] = nan if imp is None else imp.time
        out[f"impact{k}.energy"] = nan if imp is None else imp.energy_dissipated
        for n in cars:
            pre = f"impact{k}.{n}."
            if imp is None or n not in imp.moving:
                for c in ("delta_v", "delta_v_x", "delta_v_y", "delta_v_long", "delta_v_lat",
                          "pdof_deg"):  # fmt: skip
                    out[pre + c] = nan
                continue
            body = result.delta_v_body(imp, n)
            angle = pdof(body)
            out.update({pre + "delta_v": imp.speed_change(n),
                        pre + "delta_v_x": imp.delta_v[n][0], pre + "delta_v_y": imp.delta_v[n][1],
                        pre + "delta_v_long": body[0], pre + "delta_v_lat": -body[1],
                        pre + "pdof_deg": nan if angle is None else angle})  # fmt: skip
    for n in cars:
        tr = result.trajectory(n)
        rest = result.rest(n)
        out[f"{n}.total_delta_v"] = sum(
            (imp.speed_change(n) for imp in result.impacts if n in imp.moving), 0.0)
        out[f"{n}.final_x"], out[f"{n}.final_y"] = tr.position[-1][0], tr.position[-1][1]
        out[f"{n}.final_heading_deg"] = math.degrees(result.heading(n, tr.t[-1]))
        out[f"{n}.final_speed"] = float(np.linalg.norm(tr.velocity[-1]))
        out[f"{n}.rest_time"] = nan if rest is None else rest.time
        out[f"{n}.rest_x"] = nan if rest is None else rest.position[0]
        out[f"{n}.rest_y"] = nan if rest is None else rest.position[1]
        out[f"{n}.rest_heading_deg"] = nan if rest is None else math.degrees(rest.heading)
    return out


def pedestrian_figures(result: Result, person: Pedestrian, vehicle: Any) -> dict[str, float]:
    """A pedestrian's figures against one vehicle (the module's list, without the prefix
    ``p.v.``): first_contact_time, throw_distance and the head's; NaN where there is none."""
    from crashsim.analysis.pedestrian import segment_contacts
    from crashsim.analysis.throw import first_contact_time, throw_distance

    out = dict.fromkeys(("first_contact_time", "throw_distance", *_HEAD_FIGURES), math.nan)
    try:
        out["first_contact_time"] = first_contact_time(result, vehicle.name, person)
    except ParameterError:  # never touched
        return out
    out["throw_distance"] = throw_distance(result, vehicle.name, person)
    head = segment_contacts(result, person, vehicle, segments=[HEAD]).get(HEAD)
    if head is not None:
        out.update(head_time=head.time, head_x=float(head.point[0]),
                   head_y=float(head.point[1]), head_z=float(head.point[2]),
                   head_relative_speed=head.relative_speed,
                   head_wrap_around=math.nan if head.wrap_around is None else head.wrap_around)
    return out


def columns_of(result: Result, scene: SceneView, max_impacts: int) -> dict[str, float]:
    """One run's row: the vehicles' batch columns and every pedestrian's figures (the
    module's list)."""
    from crashsim.analysis.pedestrian import whole_body

    cars = _struck(scene)
    out = _vehicle_figures(result, cars, max_impacts)
    by_name = {v.name: v for v in scene.vehicles}
    for name, person in scene.pedestrians.items():
        _, x, v = whole_body(result, person)
        speed = float(np.linalg.norm(v[-1]))
        still = speed < REST_SPEED
        out.update({f"{name}.final_x": x[-1, 0], f"{name}.final_y": x[-1, 1],
                    f"{name}.final_speed": speed,
                    f"{name}.rest_x": x[-1, 0] if still else math.nan,
                    f"{name}.rest_y": x[-1, 1] if still else math.nan})  # fmt: skip
        for car in cars:
            figures = pedestrian_figures(result, person, by_name[car])
            out.update({f"{name}.{car}.{k}": v for k, v in figures.items()})
    return out
