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

import re
import tomllib
from collections.abc import Callable, Iterator
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np
from numpy.typing import NDArray

from crashsim import _core
from crashsim.contacts import _check_stiffness
from crashsim.environment.ground import FrictionZone, Ground
from crashsim.errors import CrashsimError, ParameterError
from crashsim.errors import text as error_text
from crashsim.filekind import special_file
from crashsim.io.fitfile import read_fit
from crashsim.io.scene_bodies import (
    CYCLIST_KEYS,
    JOINT_KEYS,
    OBSTACLE_KEYS,
    PEDESTRIAN_KEYS,
    _cyclist,
    _joint,
    _obstacle,
    _pedestrian,
)
from crashsim.io.scene_common import _input_file, _wrap
from crashsim.io.scene_towing import COUPLING_KEYS as COUPLING_KEYS  # re-exported
from crashsim.io.scene_towing import HITCH_KEYS as HITCH_KEYS  # re-exported
from crashsim.io.scene_towing import (
    RIGID_KEYS,
    TRACTOR_KEYS,
    _hitch,
    _place_all,
    _rigid,
    _towing,
    _tractor,
    _trailer,
)
from crashsim.io.scene_towing import TRAILER_KEYS as TRAILER_KEYS  # re-exported
from crashsim.io.scene_vehicles import (
    _GEOMETRY,
    GENERATE_KEYS,
    VEHICLE_KEYS,
    _body,
    _preset_table,
    _wheels,
)
from crashsim.io.scene_vehicles import MESH_KEYS as MESH_KEYS  # re-exported
from crashsim.io.studyfile import read_study
from crashsim.io.tomlvalues import (
    DIMENSIONS,
    UNITS,
    SceneFileError,
    Unit,
    _show,
    _Table,
    parse_quantity,
)
from crashsim.names import check_name
from crashsim.result import Result
from crashsim.scene import Scene
from crashsim.spec import DEFAULT_MAX_DURATION
from crashsim.vehicles.generator.presets import PRESETS
from crashsim.vehicles.trucks import RIGID_PRESETS, TRACTOR_PRESETS
from crashsim.vehicles.vehicle import Vehicle

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

# The keys of the top-level tables (docs/scene-format.md describes each one; a vehicle's are in
# crashsim.io.scene_vehicles and scene_towing, the other bodies' in scene_bodies).
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
    "cyclists",
    "joints",
    "study",
    "fit",
    "evidence",
)
RUN_KEYS = ("duration", "dt", "record_interval", "until", "max_duration")
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
GROUND_KEYS = ("height", "terrain", "friction", "body_friction", "zones")
TERRAIN_KEYS = ("file", "units", "up", "forward")
ZONE_KEYS = ("polygon", "friction", "name")


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


# -- the ground ------------------------------------------------------------------------------


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
        zones.append(_file_zone(z, corners, mu, name))
    kwargs["zones"] = zones
    t.finish()
    try:
        return Ground(**kwargs)
    except CrashsimError as e:
        if not isinstance(e, ValueError):
            raise
        raise _ground_error(t, e) from e


def _file_zone(z: _Table, corners: list[Any], friction: float | str,
               name: str | None) -> FrictionZone:
    """A zone of the file, at its key: the zone's own place (the part "friction zone") is
    the key, so its text is what lies inside it."""
    try:
        return FrictionZone(corners, friction, name)
    except ParameterError as e:
        raise z.error(None, error_text(e.loc[1:], e.message or str(e))) from e


def _ground_error(t: _Table, e: CrashsimError) -> SceneFileError:
    """The engine's refusal of a ground at the key it concerns: a zone's error at
    ground.zones[k] (its place, not its text, says which), two overlapping zones at the
    later one, naming the other; anything else at the ground table."""
    place = next((p for p in e.loc if p[0] in ("zone", "zones")), None)
    if place is None or e.message is None:
        return t.error(None, str(e))
    if place[0] == "zone":
        return t.error(f"zones[{place[1]}]", e.message)
    a, b = place[1]
    return t.error(f"zones[{b}]", f"zones[{a}] and zones[{b}]: {e.message}")


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
                try:  # the engine's rule, on parameters that need what k asks for
                    _check_stiffness(_core.ContactParams(**{k: defaults[k]}), (a, b))
                except ParameterError as e:
                    top.fail(f"contact.{k}", f"{e}; or override this pair in [[pairs]]")


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
    for c in top.tables("cyclists", CYCLIST_KEYS):
        _cyclist(c, scene, names)
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
