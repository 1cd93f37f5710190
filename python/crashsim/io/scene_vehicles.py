"""A [[vehicles]] entry's own tables in a scene file (docs/scene-format.md): mass, crush
stiffness and inertia; a box, mesh or generated body; its wheels, tyre and driver inputs; and
its state at t = 0. Tractors, trailers and towing are crashsim.io.scene_towing; the table as a
whole is read by crashsim.io.scenefile.
"""

from __future__ import annotations

import math
from pathlib import Path
from typing import Any

import numpy as np

from crashsim.errors import ParameterError
from crashsim.io.scene_common import _input_file, _reject, _rows, _wrap
from crashsim.io.tomlvalues import (
    STANDARD_GRAVITY,
    _check_low,
    _Invalid,
    _quantity,
    _show,
    _Table,
)
from crashsim.scene import Scene
from crashsim.vehicles.generator.presets import SHAPE_PARAMETERS
from crashsim.vehicles.inputs import Brake, DriverInputs, named_brake
from crashsim.vehicles.mass_properties import SOLIDS
from crashsim.vehicles.meshio import axes_rotation, unit_scale
from crashsim.vehicles.tyre import COMBINED_SLIP_LAWS, TYRE_MODELS, TYRE_PARAMETERS, Tyre
from crashsim.vehicles.vehicle import Vehicle
from crashsim.vehicles.vehicle_data import vehicle_class

_GEOMETRY = ("box", "mesh", "generate", "trailer")
VEHICLE_KEYS = (
    "name",
    *_GEOMETRY,
    "mass",
    "weight",
    "cg",
    "cg_height",
    "inertia",
    "wheelbase",
    "stiffness",
    "position",
    "heading",
    "orientation",
    "velocity",
    "speed",
    "direction",
    "angular_velocity",
    "yaw_rate",
    "wheels",
    "tyre",
    "inputs",
    "hitch",
    "towed_by",
    "coupling",
)
# a vehicle's state at t = 0: a towed vehicle takes its tower's
_STATE_KEYS = (
    "position",
    "heading",
    "orientation",
    "velocity",
    "speed",
    "direction",
    "angular_velocity",
    "yaw_rate",
)
WHEEL_KEYS = (
    "wheelbase",
    "track",
    "radius",
    "cg_to_front_axle",
    "cg_height",
    "steer",
    "natural_frequency",
    "damping_ratio",
    "spring_rates",
    "damping",
    "anti_roll",
    "roll_gradient",
    "anti_roll_front_share",
    "steering_ratio",
    "ackermann",
    "steering_reference",
    "steering_interpolation",
    "abs",
)
TYRE_KEYS = TYRE_PARAMETERS
INPUT_KEYS = (
    "steer",
    "steering_wheel",
    "steering_ratio",
    "path",
    "preview",
    "min_distance",
    "brake",
    "drive",
    "wheel_states",
)
BRAKE_KEYS = ("time", "fraction", "deceleration", "wheels", "front_share")
DRIVE_KEYS = ("time", "force", "wheels")
STEER_KEYS = ("time", "angle", "wheels")
STATE_KEYS = ("wheel", "state", "time", "exchange", "fraction")
_BOX_KEYS = ("length", "width", "height", "ground_clearance")
MESH_KEYS = ("file", "units", "up", "forward", "ground", "center", "solid")
GENERATE_KEYS = ("preset", "length", "width", "height", "wheelbase", *SHAPE_PARAMETERS)
_MOMENTS = ("Ixx", "Iyy", "Izz")
_STIFFNESS_FACES = ("front", "rear", "left", "right", "side")


def _mass(t: _Table, required: bool = True) -> dict[str, float]:
    """Vehicle keywords for the mass: mass (kg) or weight_lb (lb, kept as written); none when
    it is not ``required`` and not given."""
    given = [k for k in ("mass", "weight") if t.has(k)]
    if len(given) == 2:
        t.fail("weight", "give mass or weight, not both")
    if not given:
        t.taken.update(("mass", "weight"))
        if not required:
            return {}
        t.fail(
            "mass",
            'this key is required and missing: give e.g. mass = "1450 kg" or weight = "3200 lb"',
        )
    k = given[0]
    value = t.raw(k)
    if k == "weight" and isinstance(value, str):
        try:  # a weight may be a force: mass = weight / standard gravity
            si, number, unit = _quantity(value, "force")
        except _Invalid:
            pass
        else:
            _check_low(t, k, value, si, "> 0")
            if unit == "lbf":
                return {"weight_lb": number}
            return {"mass": si / STANDARD_GRAVITY}
    si, number, unit = t.quantity_with_unit(k, "mass")
    if unit in ("lb", "lbm"):
        return {"weight_lb": number}
    return {"mass": si}


def _stiffness(t: _Table) -> Any:
    """None, or what Stiffness.coerce takes: a vehicle class's faces or {face: (A, B)}."""
    if not t.has("stiffness"):
        t.taken.add("stiffness")
        return None
    value = t.raw("stiffness")
    if isinstance(value, str):
        return _wrap(t, "stiffness", lambda: vehicle_class(value).stiffness)
    s = t.table("stiffness", _STIFFNESS_FACES)
    assert s is not None
    faces: dict[str, tuple[float, float]] = {}
    for face in _STIFFNESS_FACES:
        f = s.table(face, ("A", "B"))
        if f is None:
            continue
        a = f.quantity("A", "force per width", 0.0, low=">= 0")
        b = f.quantity("B", "force per width per crush", low="> 0")
        f.finish()
        faces[face] = (a, b)
    s.finish()
    if "side" in faces and ("left" in faces or "right" in faces):
        s.fail("side", "side sets both left and right: give side, or left and right")
    if not faces:
        s.fail(None, f"no face given: use {', '.join(_STIFFNESS_FACES)} (each with A and B)")
    return faces


def _inertia(t: _Table) -> Any:
    if not t.has("inertia"):
        t.taken.add("inertia")
        return None
    value = t.raw("inertia")
    if isinstance(value, str):
        return t.string("inertia", choices=("mesh", "empirical"))
    if isinstance(value, dict):
        i = t.table("inertia", _MOMENTS)
        assert i is not None
        moments = [i.quantity(k, "moment of inertia", low="> 0") for k in ("Ixx", "Iyy", "Izz")]
        i.finish()
        return np.diag(moments)
    return t.matrix("inertia", "moment of inertia")


def _body(
    t: _Table, base: Path, name: str, geometry: str, generate: tuple[_Table, str] | None
) -> Vehicle:
    """A box, mesh or generated body (its generate table and preset read)."""
    mass = _mass(t)
    stiffness = _stiffness(t)
    if geometry == "box":
        _reject(t, ("cg",), "a box has its CG at its centre: move it up or down with cg_height")
        b = t.table("box", _BOX_KEYS)
        if b is None:
            t.fail("box", "expected a table { length = ..., width = ..., height = ... }")
        dims = {k: b.quantity(k, "length", low="> 0") for k in _BOX_KEYS[:3]}
        dims["ground_clearance"] = b.quantity("ground_clearance", "length", 0.0, low=">= 0")
        b.finish()
        cg_height = t.quantity("cg_height", "length", None, low="> 0")
        inertia = _inertia(t)
        wheelbase = t.quantity("wheelbase", "length", None, low="> 0")
        return _wrap(
            t,
            None,
            lambda: Vehicle.box(
                **dims,
                name=name,
                cg_height=cg_height,
                inertia=inertia,
                wheelbase=wheelbase,
                stiffness=stiffness,
                **mass,
            ),
        )
    if geometry == "mesh":
        _reject(t, ("cg_height",), "cg_height is for box vehicles: give cg = [x, y, z] (m)")
        options, file = _mesh_options(t, base)
        cg: Any = None
        if t.has("cg"):
            cg = "mesh" if t.raw("cg") == "mesh" else t.vector("cg", "length")
        t.taken.add("cg")
        inertia = _inertia(t)
        wheelbase = t.quantity("wheelbase", "length", None, low="> 0")
        return _wrap(
            t,
            None,
            lambda: Vehicle.from_mesh(
                file,
                name=name,
                cg=cg,
                inertia=inertia,
                wheelbase=wheelbase,
                stiffness=stiffness,
                **options,
                **mass,
            ),
        )
    _reject(
        t,
        ("cg", "cg_height", "inertia", "wheelbase"),
        "a generated body takes its CG and inertia from the generator (the wheelbase goes "
        "in the generate table); for other values use a mesh",
    )
    assert generate is not None
    g, preset = generate
    dims = {}
    for k in GENERATE_KEYS[1:]:
        if g.has(k):
            dims[k] = g.quantity(k, "length", low=">= 0" if k == "tumblehome" else "> 0")
        else:
            g.taken.add(k)
    g.finish()
    return _wrap(
        t,
        "generate",
        lambda: Vehicle.generate(preset, name=name, stiffness=stiffness, **mass, **dims),
    )


def _preset_table(
    t: _Table, k: str, keys: tuple[str, ...], presets: tuple[str, ...]
) -> tuple[_Table, str]:
    """Key k as a preset's name ("tractor") or a table { preset = "tractor", ... } of keys:
    the table (empty for a name) and the preset."""
    value = t.raw(k)
    if isinstance(value, str):
        return _Table({}, t.key(k), t.file, keys), t.string(k, choices=presets)
    if not isinstance(value, dict):
        t.fail(
            k,
            f'expected a preset\'s name such as "{presets[0]}" or a table {{ preset = '
            f'"{presets[0]}", ... }}, got {_show(value)}',
        )
    g = t.table(k, keys)
    assert g is not None
    return g, g.string("preset", choices=presets)


def _mesh_options(t: _Table, base: Path) -> tuple[dict[str, Any], Path]:
    """from_mesh keywords and the mesh file (resolved against the scene file's folder)."""
    value = t.raw("mesh")
    options: dict[str, Any] = {}
    if isinstance(value, str):
        name, where = value, t
        key = "mesh"
    else:
        m = t.table("mesh", MESH_KEYS)
        assert m is not None
        name, where, key = m.string("file"), m, "file"
        if m.has("units"):
            units = m.raw("units")
            if isinstance(units, bool) or not isinstance(units, str | int | float):
                m.fail(
                    "units",
                    f'expected a unit name ("mm", "in", ...) or metres per file unit, '
                    f"got {_show(units)}",
                )
            options["units"] = units
        for k in ("up", "forward", "solid"):
            if m.has(k):
                options[k] = m.string(k)
        for k in ("ground", "center"):
            if m.has(k):
                options[k] = m.boolean(k, False)
        m.finish()
    if not name:
        where.fail(key, "the mesh file name is empty")
    path = _input_file(where, key, name, base, "mesh")
    if options:
        _wrap(where, None, lambda: _check_mesh_options(options))
    return options, path


def _check_mesh_options(options: dict[str, Any]) -> None:
    unit_scale(options.get("units", "m"))
    axes_rotation(options.get("up", "z"), options.get("forward", "x"))
    solid = options.get("solid", "auto")
    if solid not in SOLIDS:
        raise ParameterError(f"solid = {solid!r} is unknown: use one of {', '.join(SOLIDS)}")


def _state(t: _Table, scene: Scene, vehicle: Vehicle) -> dict[str, Any]:
    """Scene.add's keywords of the state at t = 0: position of the CG, heading or orientation,
    velocity, spin, and the driver's inputs."""
    heading = orientation = None
    if t.has("heading") and t.has("orientation"):
        t.fail("orientation", "give heading or orientation, not both")
    if t.has("orientation"):
        value = t.raw("orientation")
        if isinstance(value, list) and value and isinstance(value[0], list):
            orientation = t.matrix("orientation", None)
        else:
            orientation = t.vector("orientation", None, sizes=(4,))
    t.taken.add("orientation")
    if t.has("heading") or orientation is None:
        heading = t.quantity("heading", "angle", 0.0)
    position = t.vector("position", "length", sizes=(2, 3))
    if position.size == 2:
        if orientation is not None:
            t.fail("position", "with an orientation give all of x, y, z (m)")
        if scene.ground is None:
            # the model frame's ground (z = 0) on the world's ground: the CG at its own height
            position = np.array([*position, vehicle.cg[2]])
        # with a ground, the scene puts the CG at its static height above it
    if t.has("velocity") and (t.has("speed") or t.has("direction")):
        t.fail("velocity", "give velocity, or speed and direction, not both")
    if t.has("direction") and not t.has("speed"):
        t.fail("direction", "direction (of travel) needs a speed")
    if t.has("velocity"):
        velocity = t.vector("velocity", "speed", sizes=(2, 3))
        if velocity.size == 2:
            velocity = np.array([*velocity, 0.0])
        t.taken.update(("speed", "direction"))
    else:
        speed = t.quantity("speed", "speed", 0.0, low=">= 0")
        if t.has("direction"):
            direction = t.quantity("direction", "angle")
        elif heading is not None or not t.has("speed"):
            direction = 0.0 if heading is None else heading
            t.taken.add("direction")
        else:
            t.fail("speed", "with an orientation give the direction of travel (or a velocity)")
        velocity = speed * np.array([math.cos(direction), math.sin(direction), 0.0])
    if t.has("angular_velocity") and t.has("yaw_rate"):
        t.fail("yaw_rate", "give angular_velocity or yaw_rate, not both")
    if t.has("angular_velocity"):
        omega = t.vector("angular_velocity", "angular velocity")
        t.taken.add("yaw_rate")
    else:
        omega = np.array([0.0, 0.0, t.quantity("yaw_rate", "angular velocity", 0.0)])
    inputs = _inputs(t)
    return {
        "position": position,
        "heading": heading,
        "orientation": orientation,
        "velocity": velocity,
        "angular_velocity": omega,
        "inputs": inputs,
    }


def _axle_pair(t: _Table, k: str, dimension: str | None) -> Any:
    """One quantity, or a list [front, rear] (or one per wheel) of them."""
    value = t.raw(k)
    if isinstance(value, list):
        return t.vector(k, dimension, sizes=(2, 4))
    if dimension is None:
        return t.number(k)
    return t.quantity(k, dimension, low="> 0")


def _tyre(t: _Table) -> Tyre | None:
    """The [vehicles.tyre] table, or None."""
    ty = t.table("tyre", TYRE_KEYS)
    if ty is None:
        return None
    values: dict[str, Any] = {"model": ty.string("model", "linear", choices=TYRE_MODELS)}
    if ty.has("saturation_angle"):
        values["saturation_angle"] = ty.quantity("saturation_angle", "angle", low="> 0")
    if ty.has("cornering"):
        values["cornering"] = ty.quantity("cornering", "per angle", low="> 0")
    ty.taken.add("cornering")
    plain = ("b", "c", "e", "rolling_resistance", "load_sensitivity", "longitudinal_stiffness")
    for k in plain:
        if ty.has(k):
            values[k] = ty.number(k)
        ty.taken.add(k)
    if ty.has("combined"):
        values["combined"] = ty.string("combined", choices=COMBINED_SLIP_LAWS)
    if ty.has("relaxation_length"):
        values["relaxation_length"] = ty.quantity("relaxation_length", "length", low="> 0")
    ty.taken.add("relaxation_length")
    ty.finish()
    return _wrap(ty, None, lambda: Tyre(**values))


def _wheels(t: _Table, vehicle: Vehicle) -> Vehicle:
    """The vehicle with its [vehicles.wheels] and [vehicles.tyre] tables applied."""
    w = t.table("wheels", WHEEL_KEYS)
    tyre = _tyre(t)
    if w is None and tyre is None:
        return vehicle
    if w is None:
        if vehicle.wheels is None:
            t.fail("tyre", "a tyre needs wheels: add a [vehicles.wheels] table")
        return _wrap(t, "tyre", lambda: vehicle.with_wheels(vehicle.wheels, tyre=tyre))
    given: dict[str, Any] = {}
    for k in ("wheelbase", "cg_to_front_axle", "cg_height"):
        if w.has(k):
            given[k] = w.quantity(k, "length", low="> 0")
        w.taken.add(k)
    for k in ("track", "radius"):
        if w.has(k):
            given[k] = _axle_pair(w, k, "length")
        w.taken.add(k)
    if w.has("steer"):
        given["steer"] = w.string("steer", choices=("front", "rear", "both", "none"))
    if w.has("natural_frequency"):
        given["natural_frequency"] = _axle_pair(w, "natural_frequency", "frequency")
    if w.has("damping_ratio"):
        given["damping_ratio"] = _axle_pair(w, "damping_ratio", None)
    if w.has("spring_rates"):
        given["spring_rates"] = _axle_pair(w, "spring_rates", "force per width")
    if w.has("damping"):
        given["damping"] = _axle_pair(w, "damping", "damping")
    if w.has("anti_roll"):
        given["anti_roll"] = w.vector("anti_roll", "rotational stiffness", sizes=(2,))
    if w.has("roll_gradient"):
        given["roll_gradient"] = w.quantity("roll_gradient", "roll gradient", low="> 0")
    for k in ("anti_roll_front_share", "steering_ratio", "ackermann"):
        if w.has(k):
            given[k] = w.number(k)
    if w.has("steering_reference"):
        given["steering_reference"] = w.string("steering_reference", choices=("outer", "centre"))
    if w.has("steering_interpolation"):
        given["steering_interpolation"] = w.string(
            "steering_interpolation", choices=("input", "wheels")
        )
    if w.has("abs"):
        value = w.raw("abs")
        if not isinstance(value, bool):
            w.fail("abs", f"expected true or false, got {value!r}")
        given["abs"] = value
    w.taken.update(WHEEL_KEYS)
    w.finish()
    old = vehicle.wheels
    if old is not None and old.wheelbase is not None:  # a generated vehicle: change some
        assert old.track is not None
        base = {
            "wheelbase": old.wheelbase,
            "track": old.track,
            "radius": (float(old.radii[0]), float(old.radii[-1])),
            "cg_to_front_axle": old.cg_to_front_axle,
            "cg_height": old.cg_height,
        }
        given = {**base, **given}
        if tyre is None:
            tyre = old.tyre
    return _wrap(t, "wheels", lambda: vehicle.with_wheels(tyre=tyre, **given))


def _angle_tables(rows: list[_Table]) -> dict[str, list[tuple[float, float]]]:
    """The rows' (time, angle) tables by their ``wheels`` ("linkage": through the steering
    linkage, the rows without ``wheels``)."""
    out: dict[str, list[tuple[float, float]]] = {}
    for r in rows:
        where = r.string("wheels", "linkage")
        out.setdefault(where, []).append(
            (r.quantity("time", "time"), r.quantity("angle", "angle"))
        )
        r.finish()
    return out


def _inputs(t: _Table) -> DriverInputs | None:
    """The [vehicles.inputs] table: tables of rows with units."""
    i = t.table("inputs", INPUT_KEYS)
    if i is None:
        return None
    kwargs: dict[str, Any] = {}
    steer = _angle_tables(_rows(i, "steer", STEER_KEYS))
    wheel = _angle_tables(_rows(i, "steering_wheel", STEER_KEYS))
    if "linkage" in steer and len(steer) > 1:
        i.fail("steer", "give steer rows for the linkage (no wheels) or per wheel, not both")
    if steer:
        kwargs["steer"] = steer["linkage"] if "linkage" in steer else steer
    if set(wheel) - {"linkage"}:
        i.fail("steering_wheel", "the steering wheel turns the linkage: its rows take no wheels")
    if wheel:
        kwargs["steering_wheel"] = wheel["linkage"]
    if i.has("steering_ratio"):
        kwargs["steering_ratio"] = i.number("steering_ratio")
    i.taken.add("steering_ratio")
    _path_inputs(i, kwargs)
    brakes = _brake_inputs(i)
    if brakes:
        kwargs["brake"] = brakes
    drives: dict[str, list[tuple[float, float]]] = {}
    for r in _rows(i, "drive", DRIVE_KEYS):
        where = r.string("wheels", "all")
        drives.setdefault(where, []).append(
            (r.quantity("time", "time"), r.quantity("force", "force"))
        )
        r.finish()
    if drives:
        kwargs["drive"] = drives
    states = _wheel_state_inputs(i)
    if states:
        kwargs["wheel_states"] = states
    i.taken.update(INPUT_KEYS)
    i.finish()
    return _wrap(i, None, lambda: DriverInputs(**kwargs))


def _path_inputs(i: _Table, kwargs: dict[str, Any]) -> None:
    """The inputs' path to follow ([x, y] points, lengths) and its preview and
    min_distance into ``kwargs``; those two without a path are an error."""
    if i.has("path"):
        points = i.raw("path")
        if not isinstance(points, list) or not all(
            isinstance(p, list) and len(p) == 2 for p in points
        ):
            i.fail(
                "path",
                'expected a list of [x, y] points (lengths, e.g. [0, 0] or ["5 m", "1 m"])',
            )
        xy = []
        for k, point in enumerate(points):
            sub = _Table({"x": point[0], "y": point[1]}, i.key(f"path[{k}]"), i.file)
            xy.append((sub.quantity("x", "length"), sub.quantity("y", "length")))
        kwargs["path"] = xy
        if i.has("preview"):
            kwargs["preview"] = i.quantity("preview", "time", low="> 0")
        if i.has("min_distance"):
            kwargs["min_distance"] = i.quantity("min_distance", "length", low="> 0")
    elif i.has("preview") or i.has("min_distance"):
        i.fail("preview" if i.has("preview") else "min_distance", "this is for a path: give path")
    i.taken.update(("path", "preview", "min_distance"))


def _brake_inputs(i: _Table) -> dict[str, Brake]:
    """The inputs' brake rows by their wheels ("all": the whole vehicle): a fraction of the
    friction, a deceleration, or a deceleration split front/rear (front_share)."""
    brakes: dict[str, tuple[str, list[tuple[float, float]]]] = {}
    shares: dict[str, float] = {}
    for r in _rows(i, "brake", BRAKE_KEYS):
        kinds = [k for k in ("fraction", "deceleration") if r.has(k)]
        if len(kinds) != 1:
            r.fail(None, "give fraction (of the friction, 0-1) or deceleration, one of them")
        kind = kinds[0]
        value = r.number(kind) if kind == "fraction" else r.quantity(kind, "acceleration")
        r.taken.update(("fraction", "deceleration"))
        where = r.string("wheels", "all")
        if r.has("front_share"):
            if kind != "deceleration" or where != "all":
                r.fail("front_share", "a front/rear split is for the whole vehicle's deceleration")
            share = r.number("front_share")
            if shares.get(where, share) != share:
                r.fail("front_share", "give the same front_share on every row")
            shares[where] = share
            kind = "distributed"
        row = (r.quantity("time", "time"), value)
        r.finish()
        if where in brakes and brakes[where][0] != kind:
            r.fail(kind, f'the brake rows of "{where}" mix kinds (fraction, deceleration, split)')
        brakes.setdefault(where, (kind, []))[1].append(row)
    return {
        w: _wrap(i, None, lambda k=k, w=w, rows=rows: named_brake(
            k, np.array(rows), f"brake[{w!r}]", shares.get(w)))
        for w, (k, rows) in brakes.items()
    }  # fmt: skip


def _wheel_state_inputs(i: _Table) -> list[tuple[str, str, Any, float | None]]:
    """The inputs' wheel-state switches: (wheel, state, when: a time or ("exchange", n),
    fraction or None)."""
    states = []
    for r in _rows(i, "wheel_states", STATE_KEYS):
        wheel = r.string("wheel")
        state = r.string("state", choices=("free", "locked", "braked"))
        if r.has("time") == r.has("exchange"):
            r.fail(None, "give time (the switch's time) or exchange (its exchange, from 1)")
        if r.has("time"):
            at: Any = r.quantity("time", "time")
        else:
            n = r.raw("exchange")
            if isinstance(n, bool) or not isinstance(n, int) or n < 1:
                r.fail("exchange", f"expected a whole number from 1, got {_show(n)}")
            at = ("exchange", n)
        r.taken.update(("time", "exchange"))
        fraction = r.number("fraction") if r.has("fraction") else None
        r.finish()
        states.append((wheel, state, at, fraction))
    return states
