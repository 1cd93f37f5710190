"""Scene files: a collision case as a TOML file (the reference is docs/scene-format.md).

    format_version = 1

    [run]
    duration = "0.3 s"
    dt = "1 ms"

    [contact]                       # every pair's parameters unless a [[pairs]] entry overrides
    depth_of_penetration = "30 ms"

    [[vehicles]]
    name = "red"
    box = { length = "4.5 m", width = "1.8 m", height = "1.4 m" }
    mass = "1450 kg"
    position = ["-3.65 m", "0.3 m"]  # the CG (x, y); z: the CG's height in the model frame
    heading = "0 deg"
    speed = "30 mph"

Every quantity is a plain number in SI units (m, kg, s, rad, m/s, rad/s, N, kg m^2, N/m,
N/m^2) or a string with a number and a unit ("30 mph", "3200 lb", "90 deg", "30 ms"); the
unit must fit the quantity (:data:`UNITS`, :func:`parse_quantity`). File paths are relative
to the scene file. Unknown keys are errors, so a typo is never silently ignored.

Frames: world right-handed, z up, ground z = 0; headings and directions are counter-clockwise
from world x seen from above. A vehicle's model frame is x forward, y left, z up (ISO 8855).

Every mistake raises :class:`SceneFileError` (a crashsim SceneError, hence a ValueError) with
a one-line message ``<file>: <key path>: <what is wrong and what is expected>``; key paths
count array entries from 0 (``vehicles[1].mass`` is the second vehicle's mass).
"""

from __future__ import annotations

import math
import re
import tomllib
from collections.abc import Callable, Iterator
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np
from numpy.typing import NDArray

from crashsim import _core
from crashsim.environment.ground import FrictionZone, Ground
from crashsim.environment.obstacles import Obstacle
from crashsim.errors import CrashsimError, ParameterError
from crashsim.filekind import special_file
from crashsim.io.fitfile import read_fit
from crashsim.io.studyfile import read_study
from crashsim.io.tomlvalues import (
    DIMENSIONS,
    STANDARD_GRAVITY,
    UNITS,
    SceneFileError,
    Unit,
    _check_low,
    _Invalid,
    _or,
    _quantity,
    _show,
    _split_vector,
    _Table,
    parse_quantity,
)
from crashsim.names import check_name
from crashsim.result import Result
from crashsim.scene import DEFAULT_MAX_DURATION, Scene
from crashsim.units import POUND
from crashsim.vehicles.coupling import JOINT_OF, TOWING, check_coupling
from crashsim.vehicles.generator import PRESETS, SHAPE_PARAMETERS
from crashsim.vehicles.inputs import Brake, DriverInputs
from crashsim.vehicles.meshio import axes_rotation, unit_scale
from crashsim.vehicles.stiffness import FACES
from crashsim.vehicles.trailer import (
    RIGID_PRESETS,
    TRACTOR_PRESETS,
    TRAILER_KINDS,
    TRAILER_PRESETS,
    Trailer,
    rigid_truck,
    tractor,
)
from crashsim.vehicles.tyre import TYRE_MODELS, TYRE_PARAMETERS, Tyre
from crashsim.vehicles.vehicle import SOLIDS, Vehicle
from crashsim.vehicles.vehicle_data import vehicle_class

__all__ = [
    "DIMENSIONS",
    "FORMAT_VERSION",
    "UNITS",
    "OutputSettings",
    "RunSettings",
    "SceneFile",
    "SceneFileError",
    "Unit",
    "load_scene",
    "loads_scene",
    "parse_quantity",
]

Array = NDArray[np.float64]

FORMAT_VERSION = 1
"""The scene-file format this module reads (the file's ``format_version``)."""


# -- settings --------------------------------------------------------------------------------


@dataclass(frozen=True)
class RunSettings:
    """The run: ``duration`` (s) simulated from t = 0 with steps of at most ``dt`` (s), keeping
    a sample every ``record_interval`` (s; None: the engine's default, every step for runs of
    at most 100,000 steps). With ``until`` = "rest" (a scene with a ground) the run goes on
    until every vehicle is at rest or ``max_duration`` (s; None: the Scene's default, 60 s)
    has passed."""

    duration: float = 1.0
    dt: float = 1e-3
    record_interval: float | None = None
    until: str | None = None
    max_duration: float | None = None

    @property
    def longest(self) -> float:
        """The longest the run may take (s): duration, or max_duration until rest."""
        if self.until == "rest":
            return DEFAULT_MAX_DURATION if self.max_duration is None else self.max_duration
        return self.duration


@dataclass(frozen=True)
class OutputSettings:
    """What ``crashsim run`` writes: ``dir`` (None: the command's default) and switches for the
    report (report.json), the time histories (CSV), the top-down pictures (PNG) and the
    3-D motion (GLB)."""

    dir: Path | None = None
    report: bool = True
    csv: bool = True
    pictures: bool = True
    glb: bool = True


@dataclass(frozen=True)
class SceneFile:
    """A loaded scene file: the :class:`~crashsim.scene.Scene`, its run and output settings,
    the file (None when read from a string), title and description. Unpacks as
    ``scene, run, output = load_scene(path)``."""

    scene: Scene
    run: RunSettings = field(default_factory=RunSettings)
    output: OutputSettings = field(default_factory=OutputSettings)
    path: Path | None = None
    title: str = ""
    description: str = ""
    study: Any = None  # a crashsim.io.studyfile.StudySpec from the [study] table, or None
    fit: Any = None  # a crashsim.io.fitfile.FitSpec from [fit] and [[evidence]], or None

    def __iter__(self) -> Iterator[Any]:
        return iter((self.scene, self.run, self.output))

    def simulate(
        self,
        duration: float | None = None,
        dt: float | None = None,
        progress: Callable[[float], object] | None = None,
        record_interval: float | None = None,
    ) -> Result:
        """Run the scene with the file's settings (``duration``, ``dt``, ``record_interval`` in
        s override them; until rest, ``duration`` overrides max_duration)."""
        interval = self.run.record_interval if record_interval is None else record_interval
        step = self.run.dt if dt is None else dt
        if self.run.until == "rest":
            return self.scene.run(
                dt=step,
                progress=progress,
                record_interval=interval,
                until="rest",
                max_duration=self.run.longest if duration is None else duration,
            )
        return self.scene.run(
            duration=self.run.duration if duration is None else duration,
            dt=step,
            progress=progress,
            record_interval=interval,
        )


# -- the scene ---------------------------------------------------------------------------------

_GEOMETRY = ("box", "mesh", "generate", "trailer")
# The keys of every table (docs/scene-format.md describes each one).
TOP_KEYS = (
    "format_version",
    "title",
    "description",
    "run",
    "contact",
    "pairs",
    "vehicles",
    "output",
    "ground",
    "obstacles",
    "pedestrians",
    "joints",
    "study",
    "fit",
    "evidence",
)
RUN_KEYS = ("duration", "dt", "record_interval", "until", "max_duration")
PEDESTRIAN_KEYS = (
    "name",
    "height",
    "mass",
    "sex",
    "percentile",
    "pose",
    "position",
    "heading",
    "speed",
    "direction",
    "soft_contact",
)
SOFT_CONTACT_KEYS = ("with", "stiffness", "damping_ratio")
OUTPUT_KEYS = ("dir", "report", "csv", "pictures", "glb")
CONTACT_KEYS = (
    "depth_of_penetration",
    "restitution",
    "friction",
    "restitution_mode",
    "normal",
    "pitch",
    "centroid",
)
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
GROUND_KEYS = ("height", "terrain", "friction", "body_friction", "zones")
TERRAIN_KEYS = ("file", "units", "up", "forward")
ZONE_KEYS = ("polygon", "friction", "name")
_OBSTACLE_SHAPES = ("wall", "pole", "barrier", "kerb", "tree", "mesh")
OBSTACLE_KEYS = ("name", *_OBSTACLE_SHAPES, "position", "heading", "stiffness")
OBSTACLE_SHAPE_KEYS = {
    "wall": ("length", "thickness", "height"),
    "pole": ("diameter", "height"),
    "barrier": ("length", "height", "base_width", "top_width"),
    "kerb": ("length", "height", "width"),
    "tree": ("diameter", "height"),
}
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
# generate = { preset = "rigid_truck", ... }: crashsim.rigid_truck's keywords a scene may give
RIGID_KEYS = ("preset", "length")
# generate = { preset = "tractor", ... }: crashsim.tractor's keywords
TRACTOR_KEYS = (
    "preset",
    "length",
    "width",
    "cab_height",
    "front_overhang",
    "wheelbase",
    "tandem_spread",
    "driven_axles",
    "fifth_wheel_ahead",
    "fifth_wheel_height",
    "cg_to_front_axle",
    "cg_height",
    "track",
    "radius",
    "natural_frequency",
    "damping_ratio",
    "steering_ratio",
    "steering_reference",
    "abs",
    "load_sharing",
)
# trailer = { preset = "box_van", ... } or { kind = "semitrailer", ... }: Trailer.box's keywords
TRAILER_KEYS = (
    "preset",
    "laden",
    "kind",
    "length",
    "width",
    "height",
    "ground_clearance",
    "coupler",
    "coupler_height",
    "axles",
    "track",
    "radius",
    "cg_from_front",
    "cg_height",
    "yaw_inertia",
    "natural_frequency",
    "damping_ratio",
    "abs",
    "load_sharing",
)
# Trailer.box's keywords without a default: required with a kind (a preset gives them all)
_TRAILER_REQUIRED = (
    "length",
    "width",
    "height",
    "ground_clearance",
    "coupler",
    "coupler_height",
    "axles",
    "track",
    "radius",
)
HITCH_KEYS = ("at", "kind")
COUPLING_KEYS = ("limits", "stiffness", "damping", "friction", "collide")
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
)
# a joint's resistance to its free rotation: key, quantity
_JOINT_RESISTANCE = (
    ("stiffness", "rotational stiffness"),
    ("damping", "rotational damping"),
    ("friction", "torque"),
)
_MOMENTS = ("Ixx", "Iyy", "Izz")
_STIFFNESS_FACES = ("front", "rear", "left", "right", "side")


def _wrap(t: _Table, k: str | None, action: Callable[[], Any]) -> Any:
    """Run action; a crashsim input error becomes a SceneFileError at key k of table t."""
    try:
        return action()
    except SceneFileError:
        raise
    except CrashsimError as e:
        if not isinstance(e, ValueError):  # a SimulationError is not the file's fault
            raise
        raise t.error(k, str(e)) from e


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


def _reject(t: _Table, keys: tuple[str, ...], why: str) -> None:
    for k in keys:
        if t.has(k):
            t.fail(k, why)


def _vehicle(t: _Table, base: Path) -> Vehicle:
    """The vehicle of a [[vehicles]] table: its body, wheels and tyre, and its hitch."""
    name = t.string("name")
    _wrap(t, "name", lambda: check_name(name, "a vehicle"))
    given = [g for g in _GEOMETRY if t.has(g)]
    t.taken.update(_GEOMETRY)
    if len(given) != 1:
        what = "none" if not given else " and ".join(given)
        t.fail(
            None, f"give exactly one of box, mesh, generate or trailer for the shape (got {what})"
        )
    geometry = given[0]
    generate: tuple[_Table, str] | None = None
    if geometry == "generate":  # a body's preset, or a tractor's: its name read first
        value = t.raw("generate")
        preset = value.get("preset") if isinstance(value, dict) else value
        is_tractor = isinstance(preset, str) and preset in TRACTOR_PRESETS
        is_rigid = isinstance(preset, str) and preset in RIGID_PRESETS
        keys = TRACTOR_KEYS if is_tractor else RIGID_KEYS if is_rigid else GENERATE_KEYS
        presets = PRESETS + tuple(TRACTOR_PRESETS) + tuple(RIGID_PRESETS)
        generate = _preset_table(t, "generate", keys, presets)
    if geometry == "trailer":
        vehicle = _trailer(t, name)
    elif generate is not None and generate[1] in TRACTOR_PRESETS:
        vehicle = _tractor(t, name, *generate)
    elif generate is not None and generate[1] in RIGID_PRESETS:
        vehicle = _rigid(t, name, *generate)
    else:
        vehicle = _wheels(t, _body(t, base, name, geometry, generate))
    return _hitch(t, vehicle)


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


def _unit_mass(t: _Table, required: bool) -> dict[str, float]:
    """A tractor's or trailer's mass keyword (kg), none when not given (its class's)."""
    given = _mass(t, required)
    if "weight_lb" in given:
        return {"mass": given["weight_lb"] * POUND}
    return given


def _reject_unit_keys(t: _Table, what: str, table: str) -> None:
    """The keys a tractor or a trailer (``what``) takes from its builder, refused."""
    _reject(
        t,
        ("cg", "cg_height", "inertia", "wheelbase"),
        f"a {what}'s CG, inertia and axles come from its builder: give them in its {table} "
        "table (docs/scene-format.md)",
    )
    _reject(
        t,
        ("wheels",),
        f"a {what}'s wheels come from its builder: give their track, radius and springs in "
        f"its {table} table (its tyre in [vehicles.tyre])",
    )
    _reject(t, ("stiffness",), f"a {what} has no crush stiffness in scene files yet")


def _rigid(t: _Table, name: str, g: _Table, preset: str) -> Vehicle:
    """generate = "rigid_truck" or { preset = "rigid_truck", length = ... } (g, RIGID_KEYS):
    crashsim.rigid_truck with the combination class's numbers (laden to its maximum mass);
    mass (or weight) the vehicle's, default the class's."""
    _reject_unit_keys(t, "rigid truck", "generate")
    mass = _unit_mass(t, required=False)
    tyre = _tyre(t)
    args: dict[str, Any] = {}
    if g.has("length"):
        args["length"] = g.quantity("length", "length", low="> 0")
    g.finish()
    return _wrap(
        t,
        "generate",
        lambda: rigid_truck(RIGID_PRESETS[preset], name=name, tyre=tyre, **mass, **args),
    )


def _tractor(t: _Table, name: str, g: _Table, preset: str) -> Vehicle:
    """generate = { preset = "tractor", ... } (g, read with TRACTOR_KEYS): crashsim.tractor
    with the combination class's numbers, the table's replacing them; mass (or weight) the
    vehicle's, default the class's."""
    _reject_unit_keys(t, "tractor", "generate")
    mass = _unit_mass(t, required=False)
    tyre = _tyre(t)
    args: dict[str, Any] = {}
    for k in (
        "length",
        "width",
        "cab_height",
        "front_overhang",
        "wheelbase",
        "tandem_spread",
        "fifth_wheel_height",
        "cg_to_front_axle",
        "cg_height",
        "track",
    ):
        if g.has(k):
            args[k] = g.quantity(k, "length", low="> 0")
    if g.has("fifth_wheel_ahead"):  # ahead of the rear axles' centre (< 0: behind it)
        args["fifth_wheel_ahead"] = g.quantity("fifth_wheel_ahead", "length")
    if g.has("radius"):  # one, or [front, rear]
        if isinstance(g.raw("radius"), list):
            front, rear = g.vector("radius", "length", sizes=(2,))
            for i, r in enumerate((front, rear)):
                if not r > 0.0:
                    g.fail(f"radius[{i}]", f"{_show(g.raw('radius')[i])} must be positive")
            args["radius"] = (float(front), float(rear))
        else:
            args["radius"] = g.quantity("radius", "length", low="> 0")
    if g.has("driven_axles"):
        n = g.raw("driven_axles")
        if isinstance(n, bool) or n not in (1, 2):
            g.fail("driven_axles", f"expected 1 (a 4x2) or 2 (a 6x4), got {_show(n)}")
        args["driven_axles"] = n
    if g.has("natural_frequency"):
        args["natural_frequency"] = g.quantity("natural_frequency", "frequency", low="> 0")
    for k in ("damping_ratio", "steering_ratio"):
        if g.has(k):
            args[k] = g.number(k)
    if g.has("steering_reference"):
        args["steering_reference"] = g.string("steering_reference", choices=("outer", "centre"))
    for k in ("abs", "load_sharing"):
        if g.has(k):
            args[k] = g.boolean(k, True)
    g.finish()
    return _wrap(
        t,
        "generate",
        lambda: tractor(TRACTOR_PRESETS[preset], name=name, tyre=tyre, **mass, **args),
    )


def _trailer(t: _Table, name: str) -> Vehicle:
    """trailer = "box_van", { preset = "box_van", laden = ..., ... } (Trailer.generate, the
    table's keys replacing the class's numbers) or { kind = "semitrailer", ... } (Trailer.box,
    every dimension given); mass (or weight) the vehicle's (with a preset default the
    class's)."""
    _reject_unit_keys(t, "trailer", "trailer")
    kind: str | None = None
    preset: str | None = None
    if isinstance(t.raw("trailer"), dict):
        tt = t.table("trailer", TRAILER_KEYS)  # its unknown keys first
        assert tt is not None
        if tt.has("kind") and tt.has("preset"):
            tt.fail("kind", "give preset (a class's trailer) or kind (every dimension), not both")
        if tt.has("kind"):
            kind = tt.string("kind", choices=TRAILER_KINDS)
            _reject(tt, ("laden",), "laden is for a preset: give this trailer's mass")
        elif tt.has("preset"):
            preset = tt.string("preset", choices=TRAILER_PRESETS)
        else:
            tt.fail(
                None,
                f"give preset (a class's trailer: {_or(TRAILER_PRESETS)}) or kind "
                f"({_or(TRAILER_KINDS)}: every dimension given)",
            )
    else:
        tt, preset = _preset_table(t, "trailer", TRAILER_KEYS, TRAILER_PRESETS)
    mass = _unit_mass(t, required=kind is not None)
    tyre = _tyre(t)
    args: dict[str, Any] = {}
    for k in TRAILER_KEYS[3:]:
        if not tt.has(k) and (preset is not None or k not in _TRAILER_REQUIRED):
            continue
        if k == "axles":
            value = tt.raw("axles")
            n = len(value) if isinstance(value, list) else 0
            if isinstance(value, str):
                n = len(_split_vector(value) or ())
            if n == 0:
                tt.fail(
                    "axles",
                    "expected a list of each axle's distance behind the body's front "
                    f'(lengths), e.g. ["10 m", "11.3 m", "12.6 m"], got {_show(value)}',
                )
            axles = tt.vector("axles", "length", sizes=(n,))
            for i, a in enumerate(axles):
                if not a > 0.0:
                    tt.fail(f"axles[{i}]", f"{a:g} m must be positive (behind the front)")
            args[k] = [float(a) for a in axles]
        elif k in ("coupler", "cg_from_front"):  # m behind (kingpin) or ahead of the front
            args[k] = tt.quantity(k, "length", low=">= 0")
        elif k == "yaw_inertia":
            args[k] = tt.quantity(k, "moment of inertia", low="> 0")
        elif k == "natural_frequency":
            args[k] = tt.quantity(k, "frequency", low="> 0")
        elif k == "damping_ratio":
            args[k] = tt.number(k)
        elif k in ("abs", "load_sharing"):
            args[k] = tt.boolean(k, True)
        else:
            args[k] = tt.quantity(k, "length", low="> 0")
    if preset is not None:
        laden = tt.boolean("laden", True)
        tt.finish()
        return _wrap(
            t,
            "trailer",
            lambda: Trailer.generate(preset, laden=laden, name=name, tyre=tyre, **mass, **args),
        )
    tt.finish()
    assert kind is not None
    return _wrap(t, "trailer", lambda: Trailer.box(kind, name=name, tyre=tyre, **mass, **args))


def _hitch(t: _Table, vehicle: Vehicle) -> Vehicle:
    """hitch = { at = [x, y, z] (the model frame, lengths), kind = "ball" }: the vehicle with
    that hitch (Vehicle.with_hitch; on a tractor it replaces the fifth wheel)."""
    h = t.table("hitch", HITCH_KEYS)
    if h is None:
        return vehicle
    at = h.vector("at", "length")
    kind = h.string("kind", "ball", choices=TOWING)
    h.finish()
    return _wrap(h, "at", lambda: vehicle.with_hitch(at, kind))


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


def _input_file(where: _Table, key: str, name: str, base: Path, what: str) -> Path:
    """The file ``name`` (relative to the scene file's folder ``base``) that a ``what`` key
    names, checked to be a file there (a folder, a named pipe or a device is not read)."""
    path = Path(name).expanduser()
    path = path if path.is_absolute() else base / path
    kind = special_file(path)
    if kind is not None:
        where.fail(key, f'{what} file "{name}" is {kind}, not a file (at {path.resolve()})')
    if not path.is_file():
        where.fail(
            key,
            f'{what} file "{name}" does not exist (looked for {path.resolve()}); paths are '
            "relative to the scene file",
        )
    return path


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


def _towing(tables: list[_Table], names: list[str], obstacles: list[str]) -> dict[int, int]:
    """Each towed vehicle's tower, as indices of ``tables`` (the [[vehicles]] tables, whose
    vehicles are ``names``), from their ``towed_by``: a name that is no vehicle, a second
    trailer on one hitch and a cycle are refused at the key."""
    tower: dict[int, int] = {}
    for i, t in enumerate(tables):
        by = t.string("towed_by", None)
        if by is None:
            continue
        if by in obstacles:
            t.fail("towed_by", f'"{by}" is a fixed obstacle, which tows nothing')
        if by not in names:
            t.fail("towed_by", f'no vehicle named "{by}" (the vehicles: {", ".join(names)})')
        j = names.index(by)
        if j == i:
            t.fail("towed_by", "a vehicle cannot tow itself")
        if j in tower.values():
            first = names[next(k for k, v in tower.items() if v == j)]
            t.fail(
                "towed_by",
                f'"{by}" already tows "{first}" (one trailer on a hitch): hang this one behind '
                f'it, towed_by = "{first}"',
            )
        tower[i] = j
    for i in tower:  # each chain ends at a vehicle nobody tows
        chain = [i]
        while chain[-1] in tower and tower[chain[-1]] not in chain:
            chain.append(tower[chain[-1]])
        if chain[-1] in tower and tower[chain[-1]] == i:
            loop = " towed by ".join(f'"{names[k]}"' for k in [*chain, i])
            tables[i].fail(
                "towed_by",
                f"the vehicles tow each other in a ring ({loop}): a chain of trailers starts "
                "at a vehicle that is not towed",
            )
    return tower


def _coupling(t: _Table, kind: str) -> dict[str, Any]:
    """A towed vehicle's [vehicles.coupling] (its joint with its tower, of ``kind``): Scene.add's
    coupling keywords (SI), each value checked by the engine at its key."""
    c = t.table("coupling", COUPLING_KEYS)
    c = _Table({}, t.key("coupling"), t.file) if c is None else c
    options = _joint_options(c)
    c.finish()
    _check_joint_options(c, kind, options)
    return options


def _place_all(
    tables: list[_Table], vehicles: list[Vehicle], tower: dict[int, int], scene: Scene
) -> None:
    """Every vehicle in the scene, in the file's order, each towed one right behind the one
    towing it: a chain (a vehicle nobody tows and its trailers, each towing the next) is one
    Scene.add(..., trailers=[...], coupling=[one per trailer])."""
    if tower and scene.ground is None:
        tables[min(tower)].fail("towed_by", "towing needs a ground: add a [ground] table")
    trailer_of = {j: i for i, j in tower.items()}
    for head in range(len(tables)):
        if head in tower:
            continue
        chain = [head]
        while chain[-1] in trailer_of:
            chain.append(trailer_of[chain[-1]])
        _place_chain([tables[k] for k in chain], [vehicles[k] for k in chain], scene)
        for k in chain:
            tables[k].finish()


def _place_chain(tables: list[_Table], vehicles: list[Vehicle], scene: Scene) -> None:
    """A vehicle (tables[0]) and the trailers it tows, each towing the next."""
    t, vehicle = tables[0], vehicles[0]
    if vehicle.coupler is not None:
        t.taken.add("towed_by")
        t.fail(
            "towed_by",
            'a trailer rests on the vehicle towing it: give its name, towed_by = "<the tractor '
            'or car>"',
        )
    if t.has("coupling"):
        t.fail("coupling", "this is a towed vehicle's joint (with towed_by): give it the trailer")
    state = _state(t, scene, vehicle)
    trailers: list[tuple[Vehicle, DriverInputs | None]] = []
    couplings: list[dict[str, Any]] = []
    for tt, towing, towed in zip(tables[1:], vehicles, vehicles[1:], strict=False):
        _reject(
            tt,
            _STATE_KEYS,
            f'a towed vehicle starts where "{towing.name}" (towed_by) puts it, moving with it: '
            "drop this key",
        )
        _wrap(
            tt,
            "towed_by",
            lambda a=towing, b=towed: check_coupling(a.name, a.hitch, b.name, b.coupler),
        )
        assert towed.coupler is not None
        couplings.append(_coupling(tt, JOINT_OF[towed.coupler.kind]))
        inputs = _inputs(tt)
        if inputs is not None:  # checked here, to name the trailer's table
            _wrap(
                tt,
                None,
                lambda i=inputs, v=towed: i.to_core(v.wheels, f"vehicle {v.name!r} inputs"),
            )
        trailers.append((towed, inputs))
    _wrap(t, None, lambda: scene.add(vehicle, **state, trailers=trailers, coupling=couplings))


# -- wheels, tyre and driver inputs ----------------------------------------------------------


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
    for k in ("b", "c", "e", "rolling_resistance", "load_sensitivity"):
        if ty.has(k):
            values[k] = ty.number(k)
        ty.taken.add(k)
    if ty.has("combined"):
        values["combined"] = ty.string("combined", choices=("braking_priority", "circle"))
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


def _rows(t: _Table, k: str, keys: tuple[str, ...]) -> list[_Table]:
    return t.tables(k, keys) if t.has(k) else []


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
    if brakes:
        kwargs["brake"] = {
            w: Brake.distributed(np.array(rows), shares[w])
            if k == "distributed"
            else Brake(k, np.array(rows))
            for w, (k, rows) in brakes.items()
        }
    drives: dict[str, list[tuple[float, float]]] = {}
    for r in _rows(i, "drive", DRIVE_KEYS):
        where = r.string("wheels", "all")
        drives.setdefault(where, []).append(
            (r.quantity("time", "time"), r.quantity("force", "force"))
        )
        r.finish()
    if drives:
        kwargs["drive"] = drives
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
    if states:
        kwargs["wheel_states"] = states
    i.taken.update(INPUT_KEYS)
    i.finish()
    return _wrap(i, None, lambda: DriverInputs(**kwargs))


# -- ground and obstacles ----------------------------------------------------------------------


def _ground(t: _Table | None, base: Path) -> Ground | None:
    if t is None:
        return None
    kwargs: dict[str, Any] = {}
    if t.has("height") and t.has("terrain"):
        t.fail("terrain", "give height (a plane) or terrain (a mesh), not both")
    if t.has("height"):
        kwargs["height"] = t.quantity("height", "length")
    t.taken.add("height")
    if t.has("terrain"):
        value = t.raw("terrain")
        if isinstance(value, str):
            name, where, key = value, t, "terrain"
        else:
            m = t.table("terrain", TERRAIN_KEYS)
            assert m is not None
            name, where, key = m.string("file"), m, "file"
            if m.has("units"):
                kwargs["units"] = m.raw("units")
            m.taken.add("units")
            for k in ("up", "forward"):
                if m.has(k):
                    kwargs[k] = m.string(k)
            m.finish()
        kwargs["terrain"] = _input_file(where, key, name, base, "terrain")
    t.taken.add("terrain")
    for k in ("friction", "body_friction"):
        if t.has(k):
            value = t.raw(k)
            kwargs[k] = value if isinstance(value, str) else t.number(k)
        t.taken.add(k)
    zones = []
    for z in t.tables("zones", ZONE_KEYS):
        value = z.raw("polygon")
        if not isinstance(value, list) or len(value) < 3:
            z.fail("polygon", f"expected 3 or more corners [x, y] (lengths), got {_show(value)}")
        corners = [
            _Table({f"polygon[{c}]": v}, z.path, z.file).vector(f"polygon[{c}]", "length", (2,))
            for c, v in enumerate(value)
        ]
        mu = z.raw("friction")
        mu = mu if isinstance(mu, str) else z.number("friction")
        name = z.string("name", None)
        if name is not None:
            _wrap(z, "name", lambda n=name: check_name(n, "a zone"))
        z.finish()
        zones.append(_wrap(z, None, lambda c=corners, mu=mu, n=name: FrictionZone(c, mu, n)))
    kwargs["zones"] = zones
    t.finish()
    return _wrap(t, None, lambda: Ground(**kwargs))


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
    name = t.string("name", None)
    if name is not None:
        _wrap(t, "name", lambda: check_name(name, "a joint"))
    t.finish()
    _wrap(t, "kind", lambda: _core.Joint(kind))
    _check_joint_options(t, kind, options)
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


def _check_joint_options(t: _Table, kind: str, options: dict[str, Any]) -> None:
    """The engine's checks of each limit and resistance for a joint of ``kind``, one key at a
    time, so a refusal names its key."""
    for a, (lo, hi) in options["limits"].items():
        _wrap(t, f"limits.{a}", lambda a=a, lo=lo, hi=hi: _core.Joint(kind, limits=[(a, lo, hi)]))
    for k, _ in _JOINT_RESISTANCE:
        _wrap(t, k, lambda k=k: _core.Joint(kind, **{k: options[k]}))


def _contact_values(t: _Table, names: list[str]) -> dict[str, Any]:
    """The contact keys given in table t, as Scene keywords (SI)."""
    out: dict[str, Any] = {}
    if t.has("depth_of_penetration"):
        value = t.raw("depth_of_penetration")
        if isinstance(value, str) and value.strip() == "auto":
            out["depth_of_penetration"] = "auto"
        else:
            out["depth_of_penetration"] = t.quantity("depth_of_penetration", "time", low=">= 0")
    for k in ("restitution", "friction"):
        if t.has(k):
            out[k] = t.number(k)
    if t.has("restitution_mode"):
        out["restitution_mode"] = t.string("restitution_mode", choices=("total", "normal"))
    if t.has("pitch"):
        out["pitch"] = t.quantity("pitch", "angle")
    if t.has("normal"):
        value = t.raw("normal")
        if isinstance(value, str):
            out["normal"] = t.string("normal", choices=("horizontal", "volume"))
        else:
            out["normal"] = t.vector("normal", None)
    if t.has("centroid"):
        value = t.raw("centroid")
        if isinstance(value, str) and not value.lstrip().startswith(("(", "[")):
            mode = t.string("centroid", choices=("auto", "stiffness"))
            out["centroid"] = None if mode == "auto" else mode
        elif isinstance(value, dict):
            c = t.table("centroid", ("vehicle", "point"))
            assert c is not None
            owner = c.string("vehicle")
            if owner not in names:
                c.fail("vehicle", f'no vehicle named "{owner}" (the vehicles: {", ".join(names)})')
            point = c.vector("point", "length")
            c.finish()
            out["centroid"] = (owner, point)
        else:
            out["centroid"] = t.vector("centroid", "length")
    t.taken.update(CONTACT_KEYS)
    return out


def _defaults(t: _Table | None, names: list[str]) -> Scene:
    if t is None:
        return Scene()
    values = _contact_values(t, names)
    t.finish()
    for k, v in values.items():  # one key at a time, so a bad value is named
        _wrap(t, k, lambda k=k, v=v: Scene(**{k: v}))
    return _wrap(t, None, lambda: Scene(**values))


def _pedestrian(t: _Table, scene: Scene, names: list[str]) -> None:
    """A [[pedestrians]] entry: crashsim.Pedestrian's keywords (SI), placed by Scene.add
    (its body frame's origin on the ground at position (x, y), or at the world point (x, y, z),
    facing heading, moving at speed along direction (default the heading)), and its soft
    contacts with the vehicles named."""
    name = t.string("name")
    if name in names:
        t.fail("name", f'a vehicle or obstacle named "{name}" is already in the scene: names '
               "must be unique")  # fmt: skip
    if scene.ground is None:
        t.fail("name", "a pedestrian needs a ground: add a [ground] table")
    kwargs: dict[str, Any] = {"name": name}
    if t.has("percentile"):
        kwargs["percentile"] = t.number("percentile")
    else:
        kwargs["height"] = t.quantity("height", "length", 1.75, low="> 0")
    kwargs["mass"] = t.quantity("mass", "mass", 75.0, low="> 0")
    kwargs["sex"] = t.string("sex", "male", choices=("male", "female"))
    kwargs["pose"] = t.string("pose", "standing", choices=("standing", "walking"))
    from crashsim.human.pedestrian import Pedestrian

    person = _wrap(t, None, lambda: Pedestrian(**kwargs))
    position = t.vector("position", "length", sizes=(2, 3))
    heading = t.quantity("heading", "angle", 0.0)
    speed = t.quantity("speed", "speed", 0.0, low=">= 0")
    direction = t.quantity("direction", "angle", heading)
    velocity = speed * np.array([math.cos(direction), math.sin(direction), 0.0])
    for segment in person.segments:
        if segment.name in names:
            t.fail("name", f'its segment "{segment.name}" has the name of a vehicle: rename one')
    _wrap(t, None, lambda: scene.add(person, position, heading=heading, velocity=velocity))
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
            _wrap(c, "stiffness", lambda o=other, law=law: scene.soft_contact(o, person, **law))
    t.finish()


def _pair(t: _Table, scene: Scene, names: list[str], seen: set[frozenset[str]]) -> None:
    pair = t.raw("vehicles")
    if not (isinstance(pair, list) and len(pair) == 2 and all(isinstance(p, str) for p in pair)):
        t.fail("vehicles", f'expected two vehicle names, e.g. ["red", "blue"], got {_show(pair)}')
    for i, n in enumerate(pair):
        if n not in names:
            t.fail(f"vehicles[{i}]", f'no vehicle named "{n}" (the vehicles: {", ".join(names)})')
    if pair[0] == pair[1]:
        t.fail("vehicles", "a pair needs two different vehicles")
    if frozenset(pair) in seen:
        t.fail("vehicles", f"the pair {pair[0]}, {pair[1]} is given twice: merge the entries")
    seen.add(frozenset(pair))
    joints = [j.name for j in scene.joints if set(j.vehicles) == set(pair)]
    if joints and frozenset(pair) not in {frozenset(p[:2]) for p in scene.pairs()}:
        t.fail(
            "vehicles",
            f'{pair[0]} and {pair[1]} are joined by "{joints[0]}", so their meshes never meet: '
            "give the joint collide = true for these parameters to apply, or drop this entry",
        )
    values = _contact_values(t, names)
    t.finish()
    for k, v in values.items():  # one key at a time, so a bad value is named
        _wrap(t, k, lambda k=k, v=v: scene.contact(pair[0], pair[1], **{k: v}))


def _run(t: _Table | None) -> RunSettings:
    if t is None:
        return RunSettings()
    default = RunSettings()
    until = t.string("until", None, choices=("rest",))
    if until is None and t.has("max_duration"):
        t.fail("max_duration", 'max_duration is for until = "rest": give duration instead')
    if until is not None and t.has("duration"):
        t.fail("duration", 'with until = "rest" give max_duration (the longest run), not duration')
    run = RunSettings(
        duration=t.quantity("duration", "time", default.duration, low="> 0"),
        dt=t.quantity("dt", "time", default.dt, low="> 0"),
        record_interval=t.quantity("record_interval", "time", None, low="> 0"),
        until=until,
        max_duration=t.quantity("max_duration", "time", None, low="> 0"),
    )
    t.finish()
    return run


def _output(t: _Table | None, base: Path) -> OutputSettings:
    if t is None:
        return OutputSettings()
    folder = t.string("dir", None)
    if folder is not None and not folder.strip():
        t.fail("dir", "the output folder name is empty")
    out = OutputSettings(
        dir=None if folder is None else base / Path(folder).expanduser(),
        report=t.boolean("report", True),
        csv=t.boolean("csv", True),
        pictures=t.boolean("pictures", True),
        glb=t.boolean("glb", True),
    )
    t.finish()
    return out


def _check_stiffness_needs(top: _Table, scene: Scene) -> None:
    """The scene defaults depth_of_penetration = "auto" and centroid = "stiffness" need
    stiffness on every face of both vehicles of every pair that uses them (a [[pairs]] entry
    is checked where it is read)."""
    defaults = scene.defaults
    needs = [
        k
        for k, v in (("depth_of_penetration", "auto"), ("centroid", "stiffness"))
        if isinstance(defaults[k], str) and defaults[k] == v
    ]
    vehicles = scene.vehicles
    pairs = {frozenset(p[:2]) for p in scene.pairs()}
    for k in needs:
        for i, a in enumerate(vehicles):
            for b in vehicles[i + 1 :]:
                if frozenset((a.name, b.name)) not in pairs:
                    continue  # joined: their meshes never meet
                if scene.contact_parameters(a, b)[k] != defaults[k]:
                    continue  # the pair overrides it
                for v in (a, b):
                    missing = [f for f in FACES if v.stiffness.face(f) is None]
                    if missing:
                        top.fail(
                            f"contact.{k}",
                            f'"{defaults[k]}" needs stiffness on every face of both vehicles, '
                            f'and vehicle "{v.name}" has none on its {", ".join(missing)} '
                            'face(s): give it stiffness = "<vehicle class>" or a stiffness '
                            "table, or override this pair in [[pairs]]",
                        )


def _syntax_error(e: tomllib.TOMLDecodeError, file: str) -> SceneFileError:
    text = str(e)
    m = re.search(r"\s*\(at line (\d+), column (\d+)\)\s*$", text)
    if m is None:
        return SceneFileError(f"not valid TOML: {text}", file=file)
    return SceneFileError(
        f"not valid TOML: {text[: m.start()]}",
        file=file,
        line=int(m.group(1)),
        column=int(m.group(2)),
    )


def loads_scene(
    text: str, base_dir: str | Path = ".", source: str = "<scene>", path: Path | None = None
) -> SceneFile:
    """A :class:`SceneFile` from TOML text; relative mesh paths and the output folder are
    taken from ``base_dir``; ``source`` names the text in error messages."""
    try:
        data = tomllib.loads(text)
    except tomllib.TOMLDecodeError as e:
        raise _syntax_error(e, source) from None
    base = Path(base_dir)
    top = _Table(data, "", source, TOP_KEYS)
    version = top.raw("format_version", None)
    if version is None:
        top.fail(
            "format_version", f"missing: start the file with format_version = {FORMAT_VERSION}"
        )
    if isinstance(version, bool) or version != FORMAT_VERSION:
        top.fail(
            "format_version",
            f"{_show(version)} is not a version this crashsim reads: it reads "
            f"format_version = {FORMAT_VERSION}",
        )
    title = top.string("title", "")
    description = top.string("description", "")
    vehicle_tables = top.tables("vehicles", VEHICLE_KEYS)
    if not vehicle_tables:
        top.fail("vehicles", "the scene has no vehicles: add [[vehicles]] sections")
    names: list[str] = []
    for v in vehicle_tables:
        name = v.string("name")
        if name in names:
            v.fail(
                "name", f'a vehicle named "{name}" is already in the scene: names must be unique'
            )
        names.append(name)
    obstacle_tables = top.tables("obstacles", OBSTACLE_KEYS)
    for o in obstacle_tables:
        name = o.string("name")
        if name in names:
            o.fail(
                "name",
                f'a vehicle or obstacle named "{name}" is already in the scene: names must be '
                "unique",
            )
        names.append(name)
    towers = _towing(vehicle_tables, names[: len(vehicle_tables)], names[len(vehicle_tables) :])
    scene = _defaults(top.table("contact", CONTACT_KEYS), names)
    scene.ground = _ground(top.table("ground", GROUND_KEYS), base)
    vehicles = [_vehicle(v, base) for v in vehicle_tables]
    _place_all(vehicle_tables, vehicles, towers, scene)
    for o in obstacle_tables:
        _obstacle(o, scene, base)
    obstacles = [o.name for o in scene.obstacles]
    for p in top.tables("pedestrians", PEDESTRIAN_KEYS):
        _pedestrian(p, scene, names)
    for j in top.tables("joints", JOINT_KEYS):
        _joint(j, scene, obstacles)
    seen: set[frozenset[str]] = set()
    for p in top.tables("pairs", ("vehicles", *CONTACT_KEYS)):
        _pair(p, scene, names, seen)
    run = _run(top.table("run", RUN_KEYS))
    if run.until == "rest" and scene.ground is None:
        top.fail("run.until", "a run until rest needs a ground: add a [ground] table")
    output = _output(top.table("output", OUTPUT_KEYS), base)
    study = None
    if top.has("study"):
        study = read_study(top.raw("study"), scene, source)
    top.taken.add("study")
    fit = None
    if top.has("fit") or top.has("evidence"):
        fit = read_fit(top.raw("fit", None), top.raw("evidence", None), scene, source)
    top.taken.update(("fit", "evidence"))
    top.finish()
    _check_stiffness_needs(top, scene)
    _wrap(top, None, scene.build_world)  # what only the whole scene can tell (stiffness needs)
    return SceneFile(
        scene=scene,
        run=run,
        output=output,
        path=path,
        title=title,
        description=description,
        study=study,
        fit=fit,
    )


def load_scene(path: str | Path) -> SceneFile:
    """Read a scene file (TOML, UTF-8; see docs/scene-format.md). Raises SceneFileError with a
    one-line message naming the file and the key for every mistake in it."""
    p = Path(path)
    kind = special_file(p)
    if kind is not None:  # never opened: a named pipe would wait, /dev/zero never end
        raise SceneFileError(f"is {kind}, not a scene file", file=str(p))
    try:
        text = p.read_text(encoding="utf-8")
    except FileNotFoundError:
        raise SceneFileError("no such file", file=str(p)) from None
    except (OSError, UnicodeDecodeError) as e:
        raise SceneFileError(f"cannot read it ({e})", file=str(p)) from None
    return loads_scene(text, base_dir=p.parent, source=str(p), path=p)
