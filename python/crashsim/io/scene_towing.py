"""Articulated vehicles in a scene file (docs/scene-format.md): generated tractors and rigid
trucks, trailers, hitches, the couplings of towed vehicles, and the towing chains
(``towed_by``) placed in the scene as one Scene.add each.
"""

from __future__ import annotations

from typing import Any

from crashsim.io.scene_bodies import _check_joint_options, _joint_options
from crashsim.io.scene_common import _reject, _wrap
from crashsim.io.scene_vehicles import _STATE_KEYS, _inputs, _mass, _preset_table, _state, _tyre
from crashsim.io.tomlvalues import _or, _show, _split_vector, _Table
from crashsim.scene import Scene
from crashsim.units import POUND
from crashsim.vehicles.coupling import JOINT_OF, TOWING, check_coupling
from crashsim.vehicles.inputs import DriverInputs
from crashsim.vehicles.trailer import TRAILER_KINDS, TRAILER_PRESETS, Trailer
from crashsim.vehicles.trucks import RIGID_PRESETS, TRACTOR_PRESETS, rigid_truck, tractor
from crashsim.vehicles.vehicle import Vehicle

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
