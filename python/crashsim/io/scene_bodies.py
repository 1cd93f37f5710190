"""The scene file's other bodies and links (docs/scene-format.md): [[obstacles]], [[joints]]
(whose limits and resistance a towed vehicle's coupling shares), [[pedestrians]] and
[[cyclists]].
"""

from __future__ import annotations

import math
from pathlib import Path
from typing import Any

import numpy as np

from crashsim import _core
from crashsim.environment.obstacles import Obstacle
from crashsim.human.pedestrian import ROAD_FRICTION
from crashsim.io.scene_common import _rows, _wrap
from crashsim.io.scene_vehicles import _mesh_options, _stiffness
from crashsim.io.tomlvalues import _show, _Table
from crashsim.names import check_name
from crashsim.scene import Scene

PEDESTRIAN_KEYS = (
    "name",
    "height",
    "mass",
    "sex",
    "percentile",
    "pose",
    "passive_moments",
    "road_friction",
    "position",
    "heading",
    "speed",
    "direction",
    "soft_contact",
)
CYCLIST_KEYS = (
    "name",
    "height",
    "mass",
    "sex",
    "percentile",
    "passive_moments",
    "road_friction",
    "bicycle",
    "position",
    "heading",
    "speed",
    "direction",
    "soft_contact",
)
SOFT_CONTACT_KEYS = ("with", "stiffness", "damping_ratio")
_OBSTACLE_SHAPES = ("wall", "pole", "barrier", "kerb", "tree", "mesh")
OBSTACLE_KEYS = ("name", *_OBSTACLE_SHAPES, "position", "heading", "stiffness")
OBSTACLE_SHAPE_KEYS = {
    "wall": ("length", "thickness", "height"),
    "pole": ("diameter", "height"),
    "barrier": ("length", "height", "base_width", "top_width"),
    "kerb": ("length", "height", "width"),
    "tree": ("diameter", "height"),
}
JOINT_KEYS = (
    "vehicles",
    "kind",
    "at",
    "axes",
    "limits",
    "stiffness",
    "damping",
    "friction",
    "collide",
    "name",
    "passive",
)
# a passive moment's keys ([joints.passive.<angle>]): crashsim.PassiveMoment's
PASSIVE_KEYS = ("terms", "constant", "offset")
# a joint's resistance to its free rotation: key, quantity
_JOINT_RESISTANCE = (
    ("stiffness", "rotational stiffness"),
    ("damping", "rotational damping"),
    ("friction", "torque"),
)


def _obstacle(t: _Table, scene: Scene, base: Path) -> None:
    name = t.string("name")
    _wrap(t, "name", lambda: check_name(name, "an obstacle"))
    given = [g for g in _OBSTACLE_SHAPES if t.has(g)]
    t.taken.update(_OBSTACLE_SHAPES)
    if len(given) != 1:
        what = "none" if not given else " and ".join(given)
        t.fail(None, f"give exactly one of {', '.join(_OBSTACLE_SHAPES)} (got {what})")
    kind = given[0]
    stiffness: Any = None
    if t.has("stiffness"):
        value = t.raw("stiffness")
        if isinstance(value, dict) and set(value) <= {"A", "B"}:
            f = t.table("stiffness", ("A", "B"))
            assert f is not None
            stiffness = (
                f.quantity("A", "force per width", 0.0, low=">= 0"),
                f.quantity("B", "force per width per crush", low="> 0"),
            )
            f.finish()
        else:
            stiffness = _stiffness(t)
    t.taken.add("stiffness")
    if kind == "mesh":
        options, file = _mesh_options(t, base)
        options.pop("solid", None)
        obstacle = _wrap(
            t, "mesh", lambda: Obstacle.from_mesh(file, name=name, stiffness=stiffness, **options)
        )
    else:
        shape = t.table(kind, OBSTACLE_SHAPE_KEYS[kind])
        if shape is None:
            t.fail(kind, "expected a table of its dimensions (lengths)")
        dims = {k: shape.quantity(k, "length", low="> 0") for k in shape.data}
        shape.finish()
        obstacle = _wrap(
            t,
            kind,
            lambda: getattr(Obstacle, kind)(name=name, stiffness=stiffness, **dims),
        )
    position = t.vector("position", "length", sizes=(2, 3))
    heading = t.quantity("heading", "angle", 0.0)
    t.finish()
    _wrap(t, None, lambda: scene.add_obstacle(obstacle, position, heading=heading))


def _joint(t: _Table, scene: Scene, obstacles: list[str]) -> None:
    """A [[joints]] table: Scene.join with its values in SI. The engine's checks of the kind,
    each limit and each resistance are asked one key at a time, so their messages name the
    key; the rest (the axes, a joint of the same name or pair) name the table."""
    names = [v.name for v in scene.vehicles]
    pair = t.raw("vehicles")
    if not (
        isinstance(pair, list) and len(pair) in (1, 2) and all(isinstance(p, str) for p in pair)
    ):
        t.fail(
            "vehicles",
            'expected one or two vehicle names, e.g. ["car", "trailer"] (one: joined to the '
            f"world), got {_show(pair)}",
        )
    for i, n in enumerate(pair):
        if n in obstacles:
            t.fail(
                f"vehicles[{i}]",
                f'"{n}" is a fixed obstacle, which cannot be joined: give the vehicle alone to '
                "join it to the world",
            )
        if n not in names:
            t.fail(f"vehicles[{i}]", f'no vehicle named "{n}" (the vehicles: {", ".join(names)})')
    if len(pair) == 2 and pair[0] == pair[1]:
        t.fail("vehicles", "a joint needs two different vehicles (or one: joined to the world)")
    if scene.ground is None:
        t.fail(None, "a joint needs a ground: add a [ground] table")
    kind = t.string("kind", "spherical")
    at = t.vector("at", "length")
    axes = None
    if t.has("axes"):  # as a vehicle's orientation: a quaternion or a rotation matrix
        value = t.raw("axes")
        if isinstance(value, list) and value and isinstance(value[0], list):
            axes = t.matrix("axes", None)
        else:
            axes = t.vector("axes", None, sizes=(4,))
    t.taken.add("axes")
    options = _joint_options(t)
    passive = _passive(t)
    if passive:
        options["passive"] = passive
    name = t.string("name", None)
    if name is not None:
        _wrap(t, "name", lambda: check_name(name, "a joint"))
    t.finish()
    _wrap(t, "kind", lambda: _core.Joint(kind))
    _check_joint_options(t, kind, options)
    for a, law in passive.items():  # the engine's checks, each naming its angle's table
        row = (a, law.offset, [tuple(x[:3]) for x in law.terms], law.constant)
        coupled = [
            (a, k, c.joint, c.angle, c.offset, c.rate)
            for k, x in enumerate(law.terms)
            for c in (x[3] if len(x) > 3 else ())
        ]
        _wrap(
            t,
            f"passive.{a}",
            lambda row=row, coupled=coupled: _core.Joint(kind, passive=[row], coupled=coupled),
        )
    _wrap(
        t,
        None,
        lambda: scene.join(
            pair[0],
            pair[1] if len(pair) == 2 else None,
            at=at,
            kind=kind,
            axes=axes,
            name=name,
            **options,
        ),
    )


def _joint_options(t: _Table) -> dict[str, Any]:
    """A joint's limits, resistance and collide in table t ([[joints]], a trailer's coupling)
    as Scene.join's keywords (SI)."""
    limits = t.table("limits", None)  # angle name = [lower, upper]
    bounds = {} if limits is None else {a: limits.vector(a, "angle", (2,)) for a in limits.data}
    return {
        "limits": {a: (float(lo), float(hi)) for a, (lo, hi) in bounds.items()},
        **{k: t.quantity(k, dim, 0.0) for k, dim in _JOINT_RESISTANCE},
        "collide": t.boolean("collide", False),
    }


def _passive(t: _Table) -> dict[str, Any]:
    """A [[joints]] entry's passive moments ([joints.passive.<angle>]: ``terms`` a list of
    [scale torque, rate per angle, centre angle], ``constant`` torque, ``offset`` angle) as
    {angle name: crashsim.PassiveMoment} (SI)."""
    from crashsim.joints import CoupledAngle, PassiveMoment

    table = t.table("passive", None)
    if table is None:
        return {}
    laws = {}
    for angle in table.data:
        law = table.table(angle, PASSIVE_KEYS)
        if law is None:
            continue
        rows = law.raw("terms", [])
        if not isinstance(rows, list):
            law.fail("terms", f"expected a list of [scale, rate, centre] terms, got {_show(rows)}")
        terms = []
        for i, row in enumerate(rows):
            key = f"terms[{i}]"
            if not isinstance(row, list) or len(row) not in (3, 4):
                law.fail(key, f"expected [scale, rate, centre] (torque, per angle, angle), and "
                              f"optionally the coupled angles, got {_show(row)}")  # fmt: skip
            one = _Table({"scale": row[0], "rate": row[1], "centre": row[2]}, law.key(key),
                         law.file)  # fmt: skip
            term: tuple[Any, ...] = (one.quantity("scale", "torque"),
                                     one.quantity("rate", "per angle"),
                                     one.quantity("centre", "angle"))  # fmt: skip
            if len(row) == 4:
                couplings = []
                if not isinstance(row[3], list):
                    law.fail(f"{key}[3]", f"expected a list of [joint, angle, rate, offset], got "
                                          f"{_show(row[3])}")  # fmt: skip
                for j, c in enumerate(row[3]):
                    ckey = f"{key}[3][{j}]"
                    if (not isinstance(c, list) or len(c) not in (3, 4)
                            or not all(isinstance(x, str) for x in c[:2])):  # fmt: skip
                        law.fail(ckey, "expected [joint name, angle name, rate (per angle), "
                                       f"offset (angle, default 0)], got {_show(c)}")  # fmt: skip
                    values = {"rate": c[2], "offset": c[3] if len(c) == 4 else 0.0}
                    two = _Table(values, law.key(ckey), law.file)
                    couplings.append(CoupledAngle(c[0], c[1], two.quantity("rate", "per angle"),
                                                  two.quantity("offset", "angle")))  # fmt: skip
                term = (*term, tuple(couplings))
            terms.append(term)
        laws[angle] = PassiveMoment(
            terms=tuple(terms),
            constant=law.quantity("constant", "torque", 0.0),
            offset=law.quantity("offset", "angle", 0.0),
        )
        law.finish()
    return laws


def _check_joint_options(t: _Table, kind: str, options: dict[str, Any]) -> None:
    """The engine's checks of each limit and resistance for a joint of ``kind``, one key at a
    time, so a refusal names its key."""
    for a, (lo, hi) in options["limits"].items():
        _wrap(t, f"limits.{a}", lambda a=a, lo=lo, hi=hi: _core.Joint(kind, limits=[(a, lo, hi)]))
    for k, _ in _JOINT_RESISTANCE:
        _wrap(t, k, lambda k=k: _core.Joint(kind, **{k: options[k]}))


def _pedestrian(t: _Table, scene: Scene, names: list[str]) -> None:
    """A [[pedestrians]] entry: crashsim.Pedestrian's keywords (SI), placed by Scene.add
    (its body frame's origin on the ground at position (x, y), or at the world point (x, y, z),
    facing heading, moving at speed along direction (default the heading)), and its soft
    contacts with the vehicles named."""
    kwargs = _person(t, scene, names, "pedestrian")
    from crashsim.human.pedestrian import POSES, Pedestrian

    # (a cyclist's seated pose is [[cyclists]]')
    kwargs["pose"] = t.string("pose", "standing", choices=tuple(p for p in POSES if p != "cycling"))

    person = _wrap(t, None, lambda: Pedestrian(**kwargs))
    position, heading, velocity = _motion(t)
    for segment in person.segments:
        if segment.name in names:
            t.fail("name", f'its segment "{segment.name}" has the name of a vehicle: rename one')
    _wrap(t, None, lambda: scene.add(person, position, heading=heading, velocity=velocity))
    _soft_contacts(t, scene, person, names)
    t.finish()


def _person(t: _Table, scene: Scene, names: list[str], what: str) -> dict[str, Any]:
    """The keywords of the person in table t ([[pedestrians]], [[cyclists]]): name, height
    or percentile, mass, sex, passive_moments, road_friction (SI)."""
    name = t.string("name")
    if name in names:
        t.fail("name", f'a vehicle or obstacle named "{name}" is already in the scene: names '
               "must be unique")  # fmt: skip
    if scene.ground is None:
        t.fail("name", f"a {what} needs a ground: add a [ground] table")
    kwargs: dict[str, Any] = {"name": name}
    if t.has("percentile"):
        kwargs["percentile"] = t.number("percentile")
    else:
        kwargs["height"] = t.quantity("height", "length", 1.75, low="> 0")
    kwargs["mass"] = t.quantity("mass", "mass", 75.0, low="> 0")
    kwargs["sex"] = t.string("sex", "male", choices=("male", "female"))
    kwargs["passive_moments"] = t.number("passive_moments", 1.0)
    kwargs["road_friction"] = t.number("road_friction", ROAD_FRICTION)
    return kwargs


def _motion(t: _Table) -> tuple[Any, float, Any]:
    """position, heading (rad) and velocity (m/s) from position, heading, speed and direction
    (default the heading)."""
    position = t.vector("position", "length", sizes=(2, 3))
    heading = t.quantity("heading", "angle", 0.0)
    speed = t.quantity("speed", "speed", 0.0, low=">= 0")
    direction = t.quantity("direction", "angle", heading)
    return position, heading, speed * np.array([math.cos(direction), math.sin(direction), 0.0])


def _cyclist(t: _Table, scene: Scene, names: list[str]) -> None:
    """A [[cyclists]] entry: crashsim.Cyclist's keywords (SI; ``bicycle`` its kind), placed by
    Scene.add (its bicycle frame's origin on the ground at position (x, y), riding towards
    heading at speed along direction (default the heading)), and its soft contacts with the
    vehicles named (every body of it)."""
    from crashsim.human.bicycle import KINDS, Bicycle
    from crashsim.human.cyclist import Cyclist

    kwargs = _person(t, scene, names, "cyclist")
    kind = t.string("bicycle", "city", choices=KINDS)
    cyclist = _wrap(t, None, lambda: Cyclist(bicycle=Bicycle(kind), **kwargs))
    position, heading, velocity = _motion(t)
    for body in cyclist.bodies:
        if body.name in names:
            t.fail("name", f'its body "{body.name}" has the name of a vehicle: rename one')
    _wrap(t, None, lambda: scene.add(cyclist, position, heading=heading, velocity=velocity))
    _soft_contacts(t, scene, cyclist, names)
    t.finish()


def _soft_contacts(t: _Table, scene: Scene, thing: Any, names: list[str]) -> None:
    """The [[<table>.soft_contact]] rows of a pedestrian or cyclist: Scene.soft_contact with
    each vehicle named."""
    for c in _rows(t, "soft_contact", SOFT_CONTACT_KEYS):
        others = c.raw("with")
        if isinstance(others, str):
            others = [others]
        if not (isinstance(others, list) and others and all(isinstance(o, str) for o in others)):
            c.fail("with", f'expected vehicle names, e.g. ["car"], got {_show(others)}')
        for i, other in enumerate(others):
            if other not in names:
                key = f"with[{i}]" if len(others) > 1 else "with"
                c.fail(key, f'no vehicle named "{other}" (the vehicles: {", ".join(names)})')
        law = {
            "stiffness": c.quantity("stiffness", "force per width", low="> 0"),
            "damping_ratio": c.number("damping_ratio", 0.5),
        }
        c.finish()
        for other in others:
            _wrap(c, "stiffness", lambda o=other, law=law: scene.soft_contact(o, thing, **law))
