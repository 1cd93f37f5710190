"""Parameter paths: the names a study gives to what varies, and what they change.

A path names one input of a scene (SI units in the API; the command line and scene files
take units, crashsim.io.studyfile):

=========================  ========  =====================================================
path                       unit      what it sets
=========================  ========  =====================================================
``red.speed``              m/s       the CG speed along the current direction of travel
                                     (the base velocity's direction; for a vehicle at rest,
                                     its body x axis: the heading)
``red.direction``          rad       the direction of travel, counter-clockwise from world
                                     x, speed and vertical velocity kept
``red.velocity_x/_y``      m/s       a world component of the CG velocity
``red.heading``            rad       yaw of the body x axis from world x: the vehicle is
                                     turned about the vertical through its CG, and its
                                     velocity and angular velocity are turned with it
``red.position_x/_y``      m         the CG's world x or y; the CG keeps its height above
                                     the ground (on a terrain it moves with the ground
                                     under the CG, the tilt kept)
``red.yaw_rate``           rad/s     the world z component of the angular velocity
``red.mass``               kg        the mass; inertia scaled with it (radii of gyration
                                     kept), wheels keep their natural frequencies
``restitution``            1         every pair's restitution; likewise ``friction``,
                                     ``depth_of_penetration`` (s; NaN = "auto") and
                                     ``pitch`` (rad)
``red/blue.restitution``   1         one pair's (either order; obstacles too:
                                     ``red/wall.friction``)
``ground.friction``        1         the tyre-road friction outside friction zones
``ground.body_friction``   1         body-ground friction (a car body on the road)
``ped.height``             m         a pedestrian's stature (``ped.percentile`` instead:
                                     ANSUR II's, 0-100); ``ped.mass`` kg; ``ped.pose`` the
                                     index in POSES (0 standing, 1 walking, 3 running);
                                     ``ped.passive_moments`` 1 the factor on its leg's
                                     passive joint moments (0-10);
                                     ``ped.road_friction`` 1 its segments' friction
                                     sliding on the road
``ped.position_x/_y``      m         its body frame's origin, as Scene.add took it
``ped.heading``            rad       its facing; its velocity turned with it
``ped.speed``              m/s       along its velocity (its facing when at rest)
``car/ped.friction``       1         that pair parameter of every pair of the vehicle and
                                     one of the pedestrian's segments (any of the four)
``car/ped.stiffness``      N/m       the soft contact of the vehicle with every segment;
                                     ``car/ped.damping_ratio`` 1
=========================  ========  =====================================================

A pedestrian's own paths rebuild it for each variant (crashsim.studies.pedestrians): they are
never the batch's override arrays, and a scene with pedestrians runs its variants as Scenes.

Several paths of one vehicle combine in this order: mass, position, heading (turning the base
velocity), direction, speed, then velocity_x/_y; ``speed`` or ``direction`` together with
``velocity_x``/``velocity_y`` of the same vehicle is refused (they set the same numbers).

:func:`overrides` maps a base scene and arrays of values (one per variant) to the core-level
override arrays of crashsim.batch.run_batch (the batch contract); :func:`with_` gives the
Scene of one variant (``Scene.with_`` calls it), which runs bit for bit as that variant of
the batch does.
"""

from __future__ import annotations

import dataclasses
import difflib
import math
from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

from crashsim.errors import StudyError
from crashsim.records import rotation_matrix
from crashsim.studies.vehicle_states import (
    STATE_KEYS,
    _base_states,
    _qmul,
    _set_vehicle_state,
    _state_keys,
    _yaw,
)
from crashsim.vehicles.checks import _read_only

if TYPE_CHECKING:
    from crashsim.studies.view import SceneLike, SceneView

__all__ = [
    "GROUND_PARAMETERS",
    "PAIR_PARAMETERS",
    "VEHICLE_PARAMETERS",
    "ParameterPath",
    "apply_overrides",
    "overrides",
    "parse_path",
    "valid_paths",
    "with_",
]

Array = NDArray[np.float64]

# parameter -> (dimension for unit parsing, None = a plain number; SI unit)
VEHICLE_PARAMETERS: dict[str, tuple[str | None, str]] = {
    "speed": ("speed", "m/s"),
    "direction": ("angle", "rad"),
    "velocity_x": ("speed", "m/s"),
    "velocity_y": ("speed", "m/s"),
    "heading": ("angle", "rad"),
    "position_x": ("length", "m"),
    "position_y": ("length", "m"),
    "yaw_rate": ("angular velocity", "rad/s"),
    "mass": ("mass", "kg"),
}
PAIR_PARAMETERS: dict[str, tuple[str | None, str]] = {
    "restitution": (None, "1"),
    "friction": (None, "1"),
    "depth_of_penetration": ("time", "s"),
    "pitch": ("angle", "rad"),
}
GROUND_PARAMETERS: dict[str, tuple[str | None, str]] = {
    "friction": (None, "1"),
    "body_friction": (None, "1"),
}
_GROUND_KEYS = {"friction": "ground.tyre_friction", "body_friction": "ground.body_friction"}
# The override arrays apply_overrides reads besides "contact.*" and "pedestrian:*".
_OVERRIDE_KEYS = frozenset(
    ("position", "orientation", "velocity", "angular_velocity", "mass", *_GROUND_KEYS.values())
)
# a pedestrian's own paths (crashsim.studies.pedestrians rebuilds it for each variant)
PEDESTRIAN_PARAMETERS: dict[str, tuple[str | None, str]] = {
    "height": ("length", "m"),
    "mass": ("mass", "kg"),
    "percentile": (None, "1"),
    "pose": (None, "1"),
    "passive_moments": (None, "1"),
    "road_friction": (None, "1"),
    "position_x": ("length", "m"),
    "position_y": ("length", "m"),
    "heading": ("angle", "rad"),
    "speed": ("speed", "m/s"),
}
# the soft contact of a vehicle with a pedestrian (Scene.soft_contact)
SOFT_PARAMETERS: dict[str, tuple[str | None, str]] = {
    "stiffness": (None, "N/m"),
    "damping_ratio": (None, "1"),
}
PEDESTRIAN_KINDS = ("pedestrian", "pedestrian pair")


@dataclass(frozen=True)
class ParameterPath:
    """A parsed path: ``name`` (as the study names it), ``kind`` ("vehicle", "pairs" (every
    pair), "pair", "ground", "pedestrian" or "pedestrian pair"), ``target`` (the vehicle's
    or pedestrian's name, the pair (vehicle 1, vehicle 2) as ``Scene.pairs()`` orders it,
    (vehicle, pedestrian), or None), ``parameter``, its ``dimension`` (for unit parsing;
    None: a plain number) and SI ``unit``."""

    name: str
    kind: str
    target: str | tuple[str, str] | None
    parameter: str
    dimension: str | None
    unit: str


def _names(scene: SceneView) -> tuple[list[str], list[str]]:
    return [v.name for v in scene.vehicles], [o.name for o in scene.obstacles]


def _struck(scene: SceneView) -> list[tuple[str, str, list[tuple[str, str]]]]:
    """Every (body, pedestrian) with pairs between the body (a vehicle or obstacle that is
    not one of the pedestrian's segments) and the pedestrian's segments: (body, pedestrian,
    those pairs in ``Scene.pairs()`` order)."""
    out = []
    pairs = [(a, b) for a, b, _ in scene.pairs()]
    for person, ped in scene.pedestrians.items():
        own = {s.name for s in ped.segments}
        found: dict[str, list[tuple[str, str]]] = {}
        for a, b in pairs:
            if (a in own) != (b in own):
                found.setdefault(b if a in own else a, []).append((a, b))
        out += [(body, person, ps) for body, ps in found.items()]
    return out


def _soft_with(scene: SceneView, body: str, person: str) -> bool:
    """Whether every segment of the pedestrian has a soft contact with the body."""
    return all(scene.soft_contact_of(body, s.name) is not None
               for s in scene.pedestrians[person].segments)  # fmt: skip


def _pedestrian_pair_parameters(scene: SceneView, body: str, person: str) -> list[str]:
    soft = list(SOFT_PARAMETERS) if _soft_with(scene, body, person) else []
    return [*PAIR_PARAMETERS, *soft]


def valid_paths(scene: SceneView) -> list[str]:
    """Every path the scene has, in a stable order (vehicles, every-pair, pairs, ground,
    pedestrians, the pairs of a body and a pedestrian)."""
    vehicles, _ = _names(scene)
    out = [f"{v}.{p}" for v in vehicles for p in VEHICLE_PARAMETERS]
    out += list(PAIR_PARAMETERS)
    out += [f"{a}/{b}.{p}" for a, b, _ in scene.pairs() for p in PAIR_PARAMETERS]
    if scene.ground is not None:
        out += [f"ground.{p}" for p in GROUND_PARAMETERS]
    out += [f"{p}.{k}" for p in scene.pedestrians for k in PEDESTRIAN_PARAMETERS]
    out += [f"{b}/{p}.{k}" for b, p, _ in _struck(scene)
            for k in _pedestrian_pair_parameters(scene, b, p)]  # fmt: skip
    return out


def _listing(scene: SceneView) -> str:
    """The valid paths, compactly: red.{speed, ...}, restitution, ..."""
    vehicles, _ = _names(scene)
    segments = {s.name for p in scene.pedestrians.values() for s in p.segments}
    params = ", ".join(VEHICLE_PARAMETERS)
    parts = [f"{v}.{{{params}}}" for v in vehicles if v not in segments]
    if segments:
        parts.append(f"each pedestrian's segment (e.g. {min(segments)}).{{{params}}}")
    parts += list(PAIR_PARAMETERS)
    pair_params = ", ".join(PAIR_PARAMETERS)
    parts += [f"{a}/{b}.{{{pair_params}}}" for a, b, _ in scene.pairs()
              if a not in segments and b not in segments]  # fmt: skip
    if scene.ground is not None:
        parts.append(f"ground.{{{', '.join(GROUND_PARAMETERS)}}}")
    parts += [f"{p}.{{{', '.join(PEDESTRIAN_PARAMETERS)}}}" for p in scene.pedestrians]
    parts += [f"{b}/{p}.{{{', '.join(_pedestrian_pair_parameters(scene, b, p))}}}"
              for b, p, _ in _struck(scene)]  # fmt: skip
    return "; ".join(parts)


def _unknown(scene: SceneView, name: str, why: str) -> StudyError:
    close = difflib.get_close_matches(name, valid_paths(scene), n=1, cutoff=0.6)
    hint = f'did you mean "{close[0]}"? ' if close else ""
    return StudyError(
        f'unknown parameter path "{name}": {why}; {hint}the paths of this scene are '
        f"{_listing(scene)}",
        key=name,
    )


def parse_path(scene: SceneView, name: str) -> ParameterPath:
    """The :class:`ParameterPath` of a name in a scene; StudyError naming it and listing the
    valid ones when the scene has no such input."""
    if not isinstance(name, str):
        raise StudyError(f"a parameter path must be a string such as 'red.speed', got {name!r}")
    text = name.strip()
    if text in PAIR_PARAMETERS:
        dim, unit = PAIR_PARAMETERS[text]
        return ParameterPath(text, "pairs", None, text, dim, unit)
    head, dot, parameter = text.rpartition(".")
    if not dot or not head:
        raise _unknown(scene, text, "a path is <vehicle>.<parameter>, <a>/<b>.<parameter>, "
                       "ground.<parameter> or an every-pair parameter")
    vehicles, obstacles = _names(scene)
    people = scene.pedestrians
    if head == "ground" and "ground" not in vehicles and "ground" not in people:
        if parameter not in GROUND_PARAMETERS:
            raise _unknown(scene, text, f"the ground has {', '.join(GROUND_PARAMETERS)}")
        if scene.ground is None:
            raise StudyError(
                f'"{text}" needs a ground, and the scene has none: set scene.ground = '
                "crashsim.Ground(...) (or a [ground] table in the scene file)",
                key=text,
            )
        dim, unit = GROUND_PARAMETERS[parameter]
        return ParameterPath(text, "ground", None, parameter, dim, unit)
    if head in vehicles:  # before pairs: a pedestrian's segment has "/" in its name
        if parameter not in VEHICLE_PARAMETERS:
            raise _unknown(scene, text, f"a vehicle has {', '.join(VEHICLE_PARAMETERS)}")
        dim, unit = VEHICLE_PARAMETERS[parameter]
        return ParameterPath(text, "vehicle", head, parameter, dim, unit)
    if head in people:
        if parameter not in PEDESTRIAN_PARAMETERS:
            raise _unknown(scene, text, f"a pedestrian has {', '.join(PEDESTRIAN_PARAMETERS)}")
        dim, unit = PEDESTRIAN_PARAMETERS[parameter]
        return ParameterPath(text, "pedestrian", head, parameter, dim, unit)
    if "/" in head:
        return _pair_path(scene, text, head, parameter)
    if head in obstacles:
        raise _unknown(scene, text, f"{head!r} is a fixed obstacle: it has no state to vary")
    raise _unknown(scene, text, f"the scene has no vehicle named {head!r}")


def _pair_path(scene: SceneView, text: str, head: str, parameter: str) -> ParameterPath:
    """A pair's path ``<a>/<b>.<parameter>``: two bodies, or a body and a pedestrian (every
    pair of the body with one of its segments). Names may hold "/" (a pedestrian's
    segments): the split that names two things of the scene is taken."""
    vehicles, obstacles = _names(scene)
    known = set(vehicles) | set(obstacles) | set(scene.pedestrians)
    cuts = [i for i, c in enumerate(head) if c == "/"]
    split = next(((head[:i].strip(), head[i + 1:].strip()) for i in cuts
                  if head[:i].strip() in known and head[i + 1:].strip() in known), None)
    if split is None:
        a, _, b = head.partition("/")
        raise _unknown(scene, text, f"the scene has no pair of {a.strip()!r} and {b.strip()!r}")
    a, b = split
    people = scene.pedestrians
    if a in people or b in people:
        if a in people and b in people:
            raise _unknown(scene, text, "a path names a pedestrian and a vehicle (or obstacle), "
                           "not two pedestrians")
        body, person = (b, a) if a in people else (a, b)
        found = next((ps for x, p, ps in _struck(scene) if x == body and p == person), None)
        if not found:
            raise _unknown(scene, text, f"{body!r} has no pair with {person!r}'s segments")
        allowed = _pedestrian_pair_parameters(scene, body, person)
        if parameter not in allowed:
            hint = "" if parameter not in SOFT_PARAMETERS else (
                f" (a soft contact's: give the pair one first, scene.soft_contact({body!r}, "
                f"{person!r}, stiffness=...))")
            raise _unknown(scene, text, f"a vehicle and a pedestrian have {', '.join(allowed)}"
                           + hint)
        dim, unit = {**PAIR_PARAMETERS, **SOFT_PARAMETERS}[parameter]
        return ParameterPath(text, "pedestrian pair", (body, person), parameter, dim, unit)
    if parameter not in PAIR_PARAMETERS:
        raise _unknown(scene, text, f"a pair has {', '.join(PAIR_PARAMETERS)}")
    for v1, v2, _ in scene.pairs():
        if {v1, v2} == {a, b} and a != b:
            dim, unit = PAIR_PARAMETERS[parameter]
            return ParameterPath(text, "pair", (v1, v2), parameter, dim, unit)
    raise _unknown(scene, text, f"the scene has no pair of {a!r} and {b!r}")


# -- values -> the contract's override arrays -------------------------------------------------


def _values(name: str, values: ArrayLike, n: int | None) -> Array:
    try:
        a = np.asarray(values, dtype=np.float64)
    except (TypeError, ValueError) as e:
        raise StudyError(f'"{name}": the values must be numbers (SI): {e}', key=name) from e
    if a.ndim == 0:
        a = a.reshape(1)
    if a.ndim != 1:
        raise StudyError(
            f'"{name}": give one value per variant (a 1-D array), got shape {a.shape}', key=name
        )
    if n is not None and a.size != n:
        raise StudyError(
            f'"{name}": {a.size} values for {n} variants: give one value per variant', key=name
        )
    return a


def overrides(
    scene: SceneView, values: Mapping[str, ArrayLike], n: int | None = None
) -> dict[str, Array]:
    """The core-level override arrays (crashsim.batch.run_batch's ``overrides``) for the
    variants whose inputs are ``values``: {path: (n,) values, SI}. Only the keys the paths
    touch are returned, filled with the base scene's values where a path does not set them.
    StudyError naming the path for an unknown path, a wrong number of values or
    conflicting paths; values out of range are left to the engine (that variant fails)."""
    paths = [parse_path(scene, k) for k in values]
    arrays = {p.name: _values(p.name, values[k], n) for p, k in zip(paths, values, strict=True)}
    sizes = {a.size for a in arrays.values()}
    if len(sizes) > 1:
        raise StudyError(
            "every path needs the same number of values (one per variant), got "
            + ", ".join(f"{k}: {a.size}" for k, a in arrays.items())
        )
    count = n if n is not None else (sizes.pop() if sizes else 0)
    vehicles = _check_conflicts(scene, paths)
    out: dict[str, Array] = {}
    by_vehicle = {v: [p for p in paths if p.kind == "vehicle" and p.target == v] for v in vehicles}
    state_keys = _state_keys(p.parameter for ps in by_vehicle.values() for p in ps)
    base = _base_states(scene.placements)
    for key in STATE_KEYS:
        if key in state_keys:
            out[key] = np.repeat(base[key][None], count, axis=0).astype(np.float64)
    ground = scene.ground
    for j, v in enumerate(vehicles):
        ps = {p.parameter: arrays[p.name] for p in by_vehicle[v]}
        if not ps:
            continue
        _set_vehicle_state(out, j, ps, base, count, ground)
    _move_combinations(scene, by_vehicle, base, out, count)
    _set_contacts(scene, paths, arrays, out, count)
    for p in paths:
        if p.kind == "ground":
            assert ground is not None
            key = _GROUND_KEYS[p.parameter]
            out[key] = arrays[p.name].copy()
        elif p.kind == "pedestrian" or p.kind == "pedestrian pair" and (
                p.parameter in SOFT_PARAMETERS):  # fmt: skip
            out[_pedestrian_key(p)] = arrays[p.name].copy()
    return out


def _check_conflicts(scene: SceneView, paths: list[ParameterPath]) -> list[str]:
    """StudyError when two paths set the same input, for a pedestrian's paths that do not
    go together, or when a vehicle's speed/direction and velocity components are both
    varied; the scene's vehicles."""
    seen: dict[tuple[Any, ...], str] = {}
    for p in paths:
        for key in _slots(scene, p):
            if key in seen:
                raise StudyError(
                    f'"{p.name}" and "{seen[key]}" set the same input: give one of them',
                    key=p.name,
                )
            seen[key] = p.name
    _check_pedestrian_paths(scene, paths)
    vehicles, _ = _names(scene)
    for v in vehicles:
        given = {p.parameter for p in paths if p.kind == "vehicle" and p.target == v}
        if given & {"speed", "direction"} and given & {"velocity_x", "velocity_y"}:
            raise StudyError(
                f"vehicle {v!r}: speed/direction and velocity_x/velocity_y set the same "
                "velocity: vary one or the other",
                key=f"{v}.velocity_x" if "velocity_x" in given else f"{v}.velocity_y",
            )
    return vehicles


def _set_contacts(
    scene: SceneView,
    paths: list[ParameterPath],
    arrays: Mapping[str, Array],
    out: dict[str, Array],
    count: int,
) -> None:
    """The pair parameters' arrays ``contact.<parameter>`` [variant, pair]: the paths' values
    for the pairs they name, the scene's own for the others ("auto" as NaN)."""
    pairs = scene.pairs()
    for p in paths:
        if p.kind not in ("pairs", "pair", "pedestrian pair") or p.parameter in SOFT_PARAMETERS:
            continue
        key = f"contact.{p.parameter}"
        if key not in out:
            out[key] = np.array(
                [[_pair_value(params[p.parameter]) for _, _, params in pairs]] * count,
                dtype=np.float64,
            ).reshape(count, len(pairs))
        chosen = set(_pairs_of(scene, p))
        for k, (a, b, _) in enumerate(pairs):
            if (a, b) in chosen:
                out[key][:, k] = arrays[p.name]


def _pedestrian_key(p: ParameterPath) -> str:
    """The study's array of a path that rebuilds a pedestrian or sets its soft contact
    (crashsim.studies.pedestrians.KEY + "<p>.<parameter>" or "<body>/<p>.<parameter>")."""
    from crashsim.studies.pedestrians import KEY

    target = p.target if isinstance(p.target, str) else "/".join(p.target or ())
    return f"{KEY}{target}.{p.parameter}"


def _pairs_of(scene: SceneView, p: ParameterPath) -> list[tuple[str, str]]:
    """The pairs (as Scene.pairs() orders them) a pair parameter's path sets."""
    if p.kind == "pairs":
        return [(a, b) for a, b, _ in scene.pairs()]
    if p.kind == "pair":
        assert isinstance(p.target, tuple)
        return [p.target]
    body, person = p.target  # type: ignore[misc]
    return next(ps for x, q, ps in _struck(scene) if x == body and q == person)


def _check_pedestrian_paths(scene: SceneView, paths: Sequence[ParameterPath]) -> None:
    """A pedestrian's own paths move or rebuild all its segments: StudyError when a path of
    one of its segments (as a vehicle) is given with them."""
    for p in paths:
        if p.kind != "pedestrian":
            continue
        own = {s.name for s in scene.pedestrians[str(p.target)].segments}
        clash = next((q for q in paths if q.kind == "vehicle" and q.target in own), None)
        if clash is not None:
            raise StudyError(
                f'"{p.name}" rebuilds pedestrian {p.target!r}, whose segment "{clash.name}" '
                "also varies: vary the pedestrian's paths (height, pose, position_x, heading, "
                "speed, ...) or its segments', not both",
                key=clash.name,
            )


def _combinations(scene: SceneView) -> list[list[int]]:
    """The vehicles joined to each other (Scene.join with two vehicles: a tractor and its
    trailers), as lists of placement indices, each in the order added."""
    names = [p.vehicle.name for p in scene.placements]
    group = list(range(len(names)))

    def root(i: int) -> int:
        while group[i] != i:
            i = group[i]
        return i

    for joint in scene.joints:
        a, b = joint.vehicles
        if b is not None:
            ra, rb = root(names.index(a)), root(names.index(b))
            group[max(ra, rb)] = min(ra, rb)
    out: dict[int, list[int]] = {}
    for i in range(len(names)):
        out.setdefault(root(i), []).append(i)
    return [members for members in out.values() if len(members) > 1]


def _move_combinations(
    scene: SceneView,
    by_vehicle: Mapping[str, list[ParameterPath]],
    base: Mapping[str, Array],
    out: dict[str, Array],
    count: int,
) -> None:
    """A combination moves as one: the state a path gives one of its units (position,
    heading, speed, direction, velocity, yaw rate) is given to the others as the same rigid
    motion (their places and headings turned and moved with it, their velocities those of
    its points), so the joints' frames still meet and their bodies move together. A
    StudyError when paths set the state of two units of one combination."""
    names = [p.vehicle.name for p in scene.placements]
    state = {"position_x", "position_y", "heading", "speed", "direction"}
    state |= {"velocity_x", "velocity_y", "yaw_rate"}
    for members in _combinations(scene):
        leads = [j for j in members if {p.parameter for p in by_vehicle[names[j]]} & state]
        if not leads:
            continue
        if len(leads) > 1:
            raise StudyError(
                f"vehicles {[names[j] for j in leads]} are joined (one combination): vary the "
                "state of one of them, the others follow",
                key=by_vehicle[names[leads[1]]][0].name,
            )
        j = leads[0]
        if "orientation" in out and "position" not in out:  # a turned lead moves the others
            out["position"] = np.repeat(base["position"][None], count, axis=0).astype(np.float64)
        p0, q0 = base["position"][j], base["orientation"][j]
        for k in members:
            if k == j:
                continue
            for i in range(count):
                pj = out["position"][i, j] if "position" in out else p0
                qj = out["orientation"][i, j] if "orientation" in out else q0
                turn = _qmul(qj, np.array([q0[0], -q0[1], -q0[2], -q0[3]]))  # qj q0^-1
                rot = rotation_matrix(turn)
                pk = pj + rot @ (base["position"][k] - p0)
                if "position" in out:
                    out["position"][i, k] = pk
                if "orientation" in out:
                    out["orientation"][i, k] = _qmul(turn, base["orientation"][k])
                if "velocity" in out or "angular_velocity" in out:
                    vj = out["velocity"][i, j] if "velocity" in out else base["velocity"][j]
                    wj = (
                        out["angular_velocity"][i, j]
                        if "angular_velocity" in out
                        else base["angular_velocity"][j]
                    )
                    if "velocity" in out:
                        out["velocity"][i, k] = vj + np.cross(wj, pk - pj)
                    if "angular_velocity" in out:
                        out["angular_velocity"][i, k] = wj


def _pair_value(value: Any) -> float:
    """A pair parameter as a number: "auto" (depth of penetration) is NaN."""
    if isinstance(value, str):
        return math.nan
    return float(value)


def _slots(scene: SceneView, p: ParameterPath) -> list[tuple[Any, ...]]:
    """The inputs a path sets (two paths setting one of them conflict)."""
    if p.kind == "vehicle":
        return [("vehicle", p.target, p.parameter)]
    if p.kind == "ground":
        return [("ground", p.parameter)]
    if p.kind == "pedestrian":  # a height and a percentile set the same stature
        what = "stature" if p.parameter in ("height", "percentile") else p.parameter
        return [("pedestrian", p.target, what)]
    if p.kind == "pedestrian pair" and p.parameter in SOFT_PARAMETERS:
        return [("soft", p.target, p.parameter)]
    return [("pair", pair, p.parameter) for pair in _pairs_of(scene, p)]


# -- one variant as a Scene -------------------------------------------------------------------


def apply_overrides(scene: SceneLike, arrays: Mapping[str, Array], i: int) -> SceneLike:
    """The Scene of variant ``i`` of core-level override arrays (the batch contract's keys):
    a copy of ``scene`` sharing its vehicles' meshes and engine shapes, with the variant's
    states, masses, pair parameters and ground frictions. Values are not checked here: the
    engine checks them when the scene runs (as in the batch). A pedestrian's own paths
    rebuild it (crashsim.studies.pedestrians.rebuild; ParameterError for a value it refuses)
    and its segments keep the rebuilt states. StudyError for a key no study makes (a path
    given as a key, "pedestrian.height", was ignored before: its variant ran the base scene)."""
    for key in arrays:
        if not (key in _OVERRIDE_KEYS or key.startswith(("contact.", "pedestrian:"))):
            raise StudyError(
                f"override array {key!r} is none of a study's (the keys crashsim.studies.paths."
                "overrides makes: states, mass, contact.*, ground frictions, pedestrian:*): "
                "give parameter paths to Scene.with_ instead"
            )
    new = scene  # the variant is a copy: Scene._varied below
    rebuilt: set[str] = set()
    if any(k.startswith("pedestrian:") for k in arrays):
        from crashsim.studies.pedestrians import rebuild

        new, rebuilt = rebuild(scene, arrays, i)
    placements = list(new.placements)
    for j, p in enumerate(placements):
        if p.vehicle.name in rebuilt:
            continue
        changes: dict[str, Any] = {}
        for key in ("position", "orientation", "velocity", "angular_velocity"):
            if key in arrays:
                changes[key] = _read_only(arrays[key][i, j])
        if "mass" in arrays and float(arrays["mass"][i, j]) != p.vehicle.mass:
            changes["vehicle"] = p.vehicle.with_mass(float(arrays["mass"][i, j]))
        if changes:
            placements[j] = dataclasses.replace(p, **changes)
    pair_changes: dict[tuple[str, str], dict[str, Any]] = {}
    for key, arr in arrays.items():
        if key.startswith("contact."):
            parameter = key.removeprefix("contact.")
            for k, (a, b, params) in enumerate(scene.pairs()):
                value: Any = float(arr[i, k])
                if parameter == "depth_of_penetration" and math.isnan(value):
                    value = "auto"
                if value != params[parameter] or isinstance(value, str):
                    pair_changes.setdefault((a, b), {})[parameter] = value
    ground = None
    if any(k in arrays for k in ("ground.tyre_friction", "ground.body_friction")):
        def value(key: str) -> float | None:
            return float(arrays[key][i]) if key in arrays else None

        ground = scene.ground.with_friction(
            value("ground.tyre_friction"), value("ground.body_friction")
        )
    return new._varied(placements, pair_changes, ground)


def with_(scene: SceneLike, changes: Mapping[str, Any]) -> SceneLike:
    """A new Scene with one variant's values ({path: value}, SI; see the module's table):
    ``scene.with_({"red.speed": 20.0, "restitution": 0.2})``. Running it gives what the
    batch gives for the same values, bit for bit. StudyError for an unknown path."""
    if not isinstance(changes, Mapping):
        raise StudyError(
            f"with_() takes a mapping of parameter paths to values, got {type(changes).__name__}"
        )
    arrays = overrides(scene, {k: [v] for k, v in changes.items()}, n=1)
    return apply_overrides(scene, arrays, 0)


def path_units(scene: SceneView, names: Sequence[str]) -> dict[str, str]:
    """{path: SI unit} of paths (for column headers and summaries)."""
    return {n: parse_path(scene, n).unit for n in names}


def base_value(scene: SceneView, name: str) -> float:
    """The base scene's value of a path (SI), as the path's rule reads it: speed |v|,
    direction atan2(vy, vx), heading the body x axis's yaw, ...; an every-pair parameter
    needs the same value on every pair (StudyError otherwise: name one pair); a depth of
    penetration "auto" is NaN."""
    p = parse_path(scene, name)
    if p.kind == "vehicle":
        j = [v.name for v in scene.vehicles].index(str(p.target))
        pl = scene.placements[j]
        v, w, q, pos = pl.velocity, pl.angular_velocity, pl.orientation, pl.position
        return float(
            {
                "speed": lambda: np.linalg.norm(v),
                "direction": lambda: math.atan2(v[1], v[0]),
                "velocity_x": lambda: v[0],
                "velocity_y": lambda: v[1],
                "heading": lambda: _yaw(q),
                "position_x": lambda: pos[0],
                "position_y": lambda: pos[1],
                "yaw_rate": lambda: w[2],
                "mass": lambda: pl.vehicle.mass,
            }[p.parameter]()
        )
    if p.kind == "ground":
        assert scene.ground is not None
        core = scene.ground.core
        return core.tyre_friction if p.parameter == "friction" else core.body_friction
    if p.kind == "pedestrian":
        return _pedestrian_value(scene, str(p.target), p.parameter)
    if p.kind == "pedestrian pair" and p.parameter in SOFT_PARAMETERS:
        body, person = p.target  # type: ignore[misc]
        # the same on every segment (the path is offered only then: _soft_with)
        k, zeta = {scene.soft_contact_of(body, s.name)
                   for s in scene.pedestrians[person].segments}.pop() or (math.nan, math.nan)
        return k if p.parameter == "stiffness" else zeta
    chosen = set(_pairs_of(scene, p))
    values = [_pair_value(params[p.parameter]) for a, b, params in scene.pairs()
              if (a, b) in chosen]  # fmt: skip
    distinct = {("nan" if math.isnan(x) else x) for x in values}
    if len(distinct) > 1:
        raise StudyError(
            f'"{name}" differs between the pairs ({sorted(map(str, distinct))}): name one pair, '
            f'e.g. "{scene.pairs()[0][0]}/{scene.pairs()[0][1]}.{p.parameter}"',
            key=name,
        )
    return values[0] if values else math.nan


def _pedestrian_value(scene: SceneView, person: str, parameter: str) -> float:
    """The base scene's value of a pedestrian's own path (SI; NaN: a percentile not given)."""
    from crashsim.human.pedestrian import POSES

    ped = scene.pedestrians[person]
    args = ped.arguments
    position, heading, velocity = scene.pedestrian_place(person)
    values = {
        "height": lambda: ped.height if args["percentile"] is not None else args["height"],
        "mass": lambda: args["mass"],
        "percentile": lambda: math.nan if args["percentile"] is None else args["percentile"],
        "pose": lambda: POSES.index(args["pose"]),
        "passive_moments": lambda: args["passive_moments"],
        "road_friction": lambda: args["road_friction"],
        "position_x": lambda: position[0],
        "position_y": lambda: position[1],
        "heading": lambda: heading,
        "speed": lambda: np.linalg.norm(velocity),
    }
    return float(values[parameter]())
