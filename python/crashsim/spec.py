"""A scene as the engine's value and back: the ``_core.SceneSpec`` built from a scene's parts
(crashsim.Scene.to_spec, the one path to the engine), a run's checked settings, and the
engine's errors with the names of the bodies it numbers (vehicles in the order added, then
the obstacles).
"""

from __future__ import annotations

from collections.abc import Callable
from itertools import combinations
from typing import Any

import numpy as np

from crashsim import _core
from crashsim.contacts import VehicleRef, _check_stiffness, _core_params
from crashsim.environment.ground import Ground
from crashsim.environment.obstacles import Obstacle
from crashsim.errors import (
    InitialOverlapError,
    Naming,
    ParameterError,
    Place,
    SceneError,
    at,
    renamed,
)
from crashsim.joints import Joint
from crashsim.placement import Placement, _check_terrain_under, _ObstaclePlacement
from crashsim.vehicles.checks import _as_float
from crashsim.vehicles.stiffness import FACES
from crashsim.vehicles.vehicle import Vehicle

DEFAULT_MAX_DURATION = 60.0
"""Longest run (s) of ``Scene.run(until="rest")`` when no max_duration is given."""


def _build_spec(
    *,
    placements: list[Placement],
    obstacles: list[_ObstaclePlacement],
    bodies: list[Vehicle | Obstacle],
    pairs: list[tuple[str, str, dict[str, Any]]],
    no_contact: set[frozenset[str]],
    soft: dict[frozenset[str], tuple[float, float]],
    ground: Ground | None,
    joints: list[Joint],
    index: Callable[[VehicleRef], int],
    settings: tuple[float, float, bool, float | None, int | None],
    ground_friction: dict[str, float] | None = None,
) -> _core.SceneSpec:
    """The engine's value of a scene's parts (:meth:`crashsim.Scene.to_spec`): the bodies
    (vehicles in the order placed, then the obstacles) and their face stiffness, every pair's
    parameters (``pairs`` as :meth:`crashsim.Scene.pairs` gives them; ``index`` gives a body's
    index in ``bodies``), the pairs that never collide, the soft contacts, with a ground the
    ground and each wheeled vehicle's wheels and inputs, the joints, and the run's checked
    ``settings`` (:func:`_run_settings`). ``ground_friction``: the bodies with their own
    friction with the ground (a person's segments), by vehicle name."""
    spec = _core.SceneSpec()
    for p in placements:
        v = p.vehicle
        spec.add_body(
            v.shape,
            v.mass,
            v.inertia,
            p.position,
            p.orientation,
            p.velocity,
            p.angular_velocity,
            name=v.name,
        )
    own = ground_friction or {}
    for i, p in enumerate(placements):
        if (mu := own.get(p.vehicle.name)) is not None:
            spec.set_ground_friction(i, mu)
    for o in obstacles:
        spec.add_obstacle(o.obstacle.shape, o.position, o.orientation, name=o.obstacle.name)
    for i, b in enumerate(bodies):
        faces = b.stiffness
        spec.set_stiffness(
            i,
            **{f: None if (s := faces.face(f)) is None else (s.A, s.B) for f in FACES},
        )
    for a, b, params in pairs:
        i, j = index(a), index(b)
        core = _core_params(params, (i, j), index, lambda: bodies)
        _check_stiffness(core, (bodies[i], bodies[j]))
        spec.set_contact(i, j, core)
    for pair in sorted(tuple(sorted(index(n) for n in p)) for p in no_contact):
        spec.set_no_contact(*pair)
    for names, (k, zeta) in soft.items():
        a, b = sorted(index(n) for n in names)
        spec.set_soft_contact(a, b, k, zeta)
    if ground is not None:
        spec.set_ground(ground.core)
        for i, p in enumerate(placements):
            w = p.vehicle.wheels
            if w is None:
                continue
            _check_terrain_under(ground, p, w)
            what = f"vehicle {p.vehicle.name!r}"
            inputs = {} if p.inputs is None else p.inputs.to_core(w, f"{what} inputs")
            try:
                # the inputs' steering ratio (if given) replaces the wheels'
                spec.set_vehicle(i, **{**w.spec(p.vehicle.mass), **inputs})
            except ParameterError as e:  # pragma: no cover - checked when put together
                raise at(e, ("part", None, what)) from e
    for joint in joints:
        a, b = joint.vehicles
        spec.add_joint(
            joint.core,
            index(a),
            None if b is None else index(b),
            joint.frames[0],
            joint.frames[1],
            name=joint.name,
        )
    duration_s, dt_s, until_rest, interval, max_bytes = settings
    spec.set_run(
        duration_s,
        dt_s,
        record_interval=interval,
        max_history_bytes=max_bytes,
        until_rest=until_rest,
    )
    return spec


def _run_settings(
    ground: Ground | None,
    duration: float | None,
    dt: float,
    until: str | None,
    max_duration: float | None,
    record_interval: float | None,
    max_history_bytes: int | None,
) -> tuple[float, float, bool, float | None, int | None]:
    """(duration s, dt s, until rest, record_interval s, max_history_bytes) of a run,
    checked as :meth:`crashsim.Scene.run` documents."""
    if until is not None and until != "rest":
        raise ParameterError(f'until = {until!r} is unknown: use until="rest" or a duration')
    if until == "rest":
        if ground is None:
            raise SceneError(
                "a run until rest needs a ground (without one nothing slows the vehicles): "
                "set scene.ground = crashsim.Ground(...)"
            )
        if duration is not None and max_duration is not None:
            raise ParameterError('with until="rest" give max_duration (or duration), not both')
        limit = max_duration if max_duration is not None else duration
        duration = DEFAULT_MAX_DURATION if limit is None else limit
    elif max_duration is not None:
        raise ParameterError('max_duration is for until="rest": give duration instead')
    duration = _as_float(1.0 if duration is None else duration, "duration", "s")
    dt = _as_float(dt, "dt", "s")
    if record_interval is not None:
        record_interval = _as_float(record_interval, "record_interval", "s")
    if max_history_bytes is not None and (
        isinstance(max_history_bytes, bool)
        or not isinstance(max_history_bytes, int | np.integer)
        or max_history_bytes < 1
    ):
        raise ParameterError(
            f"max_history_bytes = {max_history_bytes!r} is invalid: give a positive whole "
            "number of bytes (e.g. 2**30)"
        )
    if max_history_bytes is not None:
        max_history_bytes = int(max_history_bytes)
    return duration, dt, until == "rest", record_interval, max_history_bytes


def _scene_naming(
    placements: list[Placement], obstacles: list[_ObstaclePlacement]
) -> Naming:
    """Names the engine's places in a scene's run: body i is the i-th vehicle placed, then
    the obstacles; a wheel is named by the vehicle around it."""
    names = [f"vehicle {p.vehicle.name!r}" for p in placements]
    names += [f"obstacle {o.obstacle.name!r}" for o in obstacles]

    def body(i: int) -> str | None:
        return names[i] if 0 <= i < len(names) else None

    def name(place: Place, outer: tuple[Place, ...]) -> str | None:
        kind, index, _ = place
        if kind == "body":
            return body(index)
        if kind == "bodies" and all(0 <= i < len(names) for i in index):
            return " and ".join(names[i] for i in index)
        if kind == "wheel" and outer and outer[-1][0] == "body":
            i = outer[-1][1]
            wheels = placements[i].vehicle.wheels if 0 <= i < len(placements) else None
            if wheels is not None and 0 <= index < len(wheels.names):
                return f"wheel {wheels.names[index]!r}"
        return None

    return name


def _named_overlap_error(
    error: InitialOverlapError,
    placements: list[Placement],
    obstacles: list[_ObstaclePlacement],
    scene_pairs: Callable[[], list[tuple[str, str, dict[str, Any]]]],
) -> InitialOverlapError:
    """The engine's error with the bodies' names; two bodies overlapping at the start list
    every pair of the scene that does."""
    if not any(p[0] == "bodies" for p in error.loc):
        return renamed(error, _scene_naming(placements, obstacles))
    pairs = []
    placed = [(p.vehicle, p.position, p.orientation) for p in placements]
    placed += [(o.obstacle, o.position, o.orientation) for o in obstacles]
    # Only the pairs the engine searches (joined and no-contact ones pass through).
    searched = {frozenset(p[:2]) for p in scene_pairs()}
    for a, b in combinations(placed, 2):
        if frozenset((a[0].name, b[0].name)) not in searched:
            continue
        if _core.shapes_overlap(a[0].shape, a[1], a[2], b[0].shape, b[1], b[2]):
            pairs.append(f"{a[0].name!r} and {b[0].name!r}")
    if not pairs:
        return renamed(error, _scene_naming(placements, obstacles))
    return InitialOverlapError(
        f"vehicles {', '.join(pairs)} already overlap at t = 0: place them apart (the "
        "engine starts every contact at a first overlap it observes)"
    )
