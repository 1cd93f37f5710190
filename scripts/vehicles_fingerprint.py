"""Everything crashsim's vehicle and trailer builders make, written to a folder and hashed, so
that a refactoring of crashsim.vehicles can be shown not to change it:

    python3 scripts/vehicles_fingerprint.py /tmp/before     # on the old code
    python3 scripts/vehicles_fingerprint.py /tmp/after      # on the new code
    diff -r /tmp/before /tmp/after                          # empty: nothing changed

The last line printed is the sha256 of all the files (the same on both sides when nothing
changed). One file per case: the vehicles of Vehicle.from_mesh (in-memory meshes, closed and
open, every solid= rule, and the shared meshes in ../shared/meshes when they are there),
Vehicle.box, Vehicle.generate (every preset and alias, each cg= and inertia= rule, scaled,
with tracks, tyres and shape parameters), with_wheels, with_hitch, renamed, the trailers of
Trailer.generate, Trailer.box, Trailer.drawbar and Trailer.from_vehicle, tractor,
rigid_truck and the combination presets of Vehicle.generate; for each, every public property
(floats as float.hex, arrays as their bytes' sha256), its private state, summary(), repr(),
the plausibility warnings raised while it was built (category, message, file and line) and
the engine's scene spec of it on a ground (``to_json()``); bad inputs give their error's type
and message. The body generator (crashsim.vehicles.generator) on its own: its public names and
tables, every preset at resolutions 0.25 to 8 (the parameters, the loft's stations and sections,
the mesh's vertex and face bytes and its binary PLY), every shape parameter given to every
preset, each dimension scaled (moving the adaptive defaults), every check's error for bad input,
loft on hand-made sections and its errors, ply_bytes with comments; private names are read from
wherever they are defined (generator_name). Then a few scenes run in the engine (impacts, a
tractor and semitrailer, a car and caravan, a rigid truck and drawbar trailer) and their raw
output is hashed.
"""

from __future__ import annotations

import dataclasses
import hashlib
import sys
import warnings
from collections.abc import Callable
from pathlib import Path
from typing import Any

import crashsim as cs
import numpy as np
import trimesh
from crashsim import _core

ROOT = Path(__file__).resolve().parent.parent
SHARED_MESHES = ROOT.parent / "shared" / "meshes"
# Kerb masses of the shared meshes' vehicles (kg), as tests/conftest.py's MESH_MASS.
# The sedan class's CRASH3 A and B (a dict, as Stiffness.coerce takes it).
SEDAN = cs.vehicle_data.vehicle_class("sedan").stiffness.to_dict()
MESH_MASS = {
    "sedan_quaternius_normalcar1": 1450.0,
    "suv_quaternius_suv": 1900.0,
    "hatchback_gazebo": 1200.0,
    "pickup_gazebo": 2200.0,
    "van_gazebo_ambulance": 4500.0,
    "bus_gazebo": 12000.0,
}


def dump(x: Any, depth: int = 0) -> str:
    """A text of ``x`` that changes when any bit of it does."""
    if depth > 6:
        return f"<{type(x).__name__}>"
    if x is None or isinstance(x, bool | int | str):
        return repr(x)
    if isinstance(x, float | np.floating):
        return float(x).hex()
    if isinstance(x, np.ndarray):
        data = np.ascontiguousarray(x).tobytes()
        return f"array {x.dtype} {x.shape} {hashlib.sha256(data).hexdigest()}"
    if isinstance(x, dict):
        return "{" + ", ".join(f"{k!r}: {dump(v, depth + 1)}" for k, v in x.items()) + "}"
    if isinstance(x, list | tuple):
        return "[" + ", ".join(dump(v, depth + 1) for v in x) + "]"
    if isinstance(x, trimesh.Trimesh):
        return f"Trimesh(vertices={dump(x.vertices)}, faces={dump(np.asarray(x.faces))})"
    if isinstance(x, _core.Shape):
        return f"Shape({dump(x.vertices)}, {dump(x.triangles)}, {dump(x.aabb())})"
    if isinstance(x, _core.Tyre):
        return f"core.Tyre({dump(x.resolved(), depth + 1)})"
    if dataclasses.is_dataclass(x) and not isinstance(x, type):
        fields = {f.name: getattr(x, f.name) for f in dataclasses.fields(x)}
        return f"{type(x).__qualname__}({dump(fields, depth + 1)})"
    if type(x).__module__.startswith("crashsim") and not hasattr(x, "__dict__"):
        # the engine's objects (an Impact, ...): every public attribute that is no method
        names = [n for n in dir(x) if not n.startswith("_") and not callable(getattr(x, n))]
        fields = {n: getattr(x, n) for n in names}
        return f"{type(x).__qualname__}({dump(fields, depth + 1)})"
    if hasattr(x, "__dict__") and not callable(x):
        return f"{type(x).__qualname__}({dump(dict(sorted(vars(x).items())), depth + 1)})"
    return repr(x)


PUBLIC = (
    "name",
    "mass",
    "mass_source",
    "mesh",
    "cg",
    "inertia",
    "sources",
    "generator_params",
    "stiffness",
    "quality",
    "body_vertices",
    "extents",
    "shape",
    "wheels",
    "hitch",
    "coupler",
)


def describe_vehicle(v: cs.Vehicle) -> list[str]:
    """Every public property, the private state, summary, repr, the wheels' own description
    and the engine's spec of the vehicle alone on a ground."""
    lines = [f"type: {type(v).__module__}.{type(v).__qualname__}"]
    lines += [f"{p}: {dump(getattr(v, p))}" for p in PUBLIC]
    lines.append(f"state: {dump(dict(sorted(vars(v).items())))}")
    lines += ["summary:", v.summary(), f"repr: {v!r}"]
    if v.wheels is not None:
        lines.append(f"wheels.describe: {dump(v.wheels.describe(v.mass))}")
        lines.append(f"wheels.static_loads: {dump(v.wheels.static_loads(v.mass))}")
    lines.append(f"spec: {spec_of(lambda: cs.Scene(ground=cs.Ground()).add(v, (0.0, 0.0)))}")
    return lines


def spec_of(build: Callable[[], cs.Scene]) -> str:
    try:
        return build().to_spec(0.5, 1e-3).to_json()
    except Exception as e:  # noqa: BLE001 - the error is the fingerprint
        return f"{type(e).__module__}.{type(e).__qualname__}: {e}"


def case(make: Callable[[], Any]) -> str:
    """The text of what ``make()`` gives (a vehicle, a tuple of them or anything else) with
    the warnings it raised, or of the error it raises."""
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        try:
            made = make()
        except Exception as e:  # noqa: BLE001 - the error is the fingerprint
            made = None
            lines = [f"error: {type(e).__module__}.{type(e).__qualname__}: {e}"]
        else:
            units = made if isinstance(made, tuple) else (made,)
            lines = []
            for unit in units:
                if isinstance(unit, cs.Vehicle):
                    lines += describe_vehicle(unit)
                else:
                    lines.append(dump(unit))
    for w in caught:
        lines.append(
            f"warning: {w.category.__qualname__}: {w.message} [{Path(w.filename).name}:{w.lineno}]"
        )
    return "\n".join(lines) + "\n"


def open_box() -> trimesh.Trimesh:
    """A 4 x 2 x 1 m box standing on z = 0 with its top's two triangles gone."""
    box = trimesh.creation.box(extents=(4.0, 2.0, 1.0))
    box.apply_translation((0.0, 0.0, 0.5))
    top = np.where(box.triangles_center[:, 2] > 0.99)[0]
    keep = np.setdiff1d(np.arange(len(box.faces)), top)
    return trimesh.Trimesh(box.vertices, box.faces[keep], process=False)


def two_shells() -> trimesh.Trimesh:
    """A closed box and an open box beside it, one mesh."""
    closed = trimesh.creation.box(extents=(2.0, 1.0, 1.0))
    closed.apply_translation((1.5, 0.0, 0.5))
    return trimesh.util.concatenate([closed, open_box()])


def mesh_cases() -> dict[str, Callable[[], Any]]:
    V = cs.Vehicle
    box = lambda: trimesh.creation.box(extents=(4.0, 2.0, 1.2))  # noqa: E731
    out: dict[str, Callable[[], Any]] = {
        "mesh-closed": lambda: V.from_mesh(box(), mass=1000.0),
        "mesh-closed-lb": lambda: V.from_mesh(box(), weight_lb=2500.0, name="lb"),
        "mesh-cg-given": lambda: V.from_mesh(box(), mass=1000.0, cg=(0.1, 0.0, -0.2)),
        "mesh-all-given": lambda: V.from_mesh(
            box(), mass=1000.0, cg=(0, 0, 0), inertia=np.eye(3) * 700.0
        ),
        "mesh-empirical": lambda: V.from_mesh(
            box(), mass=1500.0, inertia="empirical", wheelbase=2.7
        ),
        "mesh-open-auto": lambda: V.from_mesh(open_box(), mass=1000.0),
        "mesh-open-hull": lambda: V.from_mesh(open_box(), mass=1000.0, solid="convex hull"),
        "mesh-open-shells": lambda: V.from_mesh(two_shells(), mass=1000.0, solid="closed shells"),
        "mesh-two-shells-winding": lambda: V.from_mesh(two_shells(), mass=1000.0),
        "mesh-units-axes": lambda: V.from_mesh(
            trimesh.creation.box(extents=(180.0, 120.0, 420.0)),
            mass=1000.0,
            units="cm",
            up="y",
            forward="z",
            ground=True,
            center=True,
        ),
        "mesh-wheels": lambda: V.from_mesh(
            trimesh.creation.box(extents=(4.2, 1.8, 1.2)).apply_translation((0, 0, 0.8)),
            mass=1400.0,
            wheelbase=2.6,
            track=1.5,
            wheel_radius=0.3,
            cg_to_front_axle=1.1,
            tyre={"model": "linear"},
            stiffness=SEDAN,
        ),
        "mesh-implausible": lambda: V.from_mesh(box(), mass=50.0),
        "mesh-flat-error": lambda: V.from_mesh(
            trimesh.Trimesh([[0, 0, 0], [1, 0, 0], [0, 1, 0]], [[0, 1, 2]]), mass=1.0
        ),
        "mesh-inward-error": lambda: V.from_mesh(_inverted(), mass=1.0),
        "mesh-both-masses-error": lambda: V.from_mesh(box(), mass=1.0, weight_lb=2.2),
        "mesh-no-mass-error": lambda: V.from_mesh(box()),
        "mesh-bad-solid-error": lambda: V.from_mesh(box(), mass=1.0, solid="sphere"),
        "mesh-bad-inertia-error": lambda: V.from_mesh(box(), mass=1.0, inertia="class"),
        "mesh-empirical-no-wb-error": lambda: V.from_mesh(box(), mass=1.0, inertia="empirical"),
        "mesh-wb-alone-error": lambda: V.from_mesh(box(), mass=1000.0, wheelbase=2.0),
        "mesh-impossible-error": lambda: V.from_mesh(
            box(), mass=1.0, inertia=np.diag([1.0, 1.0, 5.0])
        ),
        "mesh-empirical-impossible-error": lambda: V.from_mesh(
            box(), mass=1000.0, inertia="empirical", wheelbase=3.9
        ),
        "mesh-bad-cg-error": lambda: V.from_mesh(box(), mass=1000.0, cg=(0, "a", 0)),
        "mesh-wheels-missing-error": lambda: V.from_mesh(box(), mass=1000.0, track=1.5),
    }
    for path in sorted(SHARED_MESHES.glob("*.ply")):
        mass = MESH_MASS.get(path.stem, 1500.0)
        out[f"shared-{path.stem}"] = lambda p=path, m=mass: V.from_mesh(p, mass=m)
        out[f"shared-{path.stem}-hull"] = lambda p=path, m=mass: V.from_mesh(
            p, mass=m, solid="convex hull"
        )
        out[f"shared-{path.stem}-shells"] = lambda p=path, m=mass: V.from_mesh(
            p, mass=m, solid="closed shells"
        )
        out[f"shared-{path.stem}-empirical"] = lambda p=path, m=mass: V.from_mesh(
            p, mass=m, cg=(0.0, 0.0, 0.55), inertia="empirical", wheelbase=2.6
        )
    return out


def _inverted() -> trimesh.Trimesh:
    box = trimesh.creation.box(extents=(4.0, 2.0, 1.2))
    box.invert()
    return box


def box_cases() -> dict[str, Callable[[], Any]]:
    V = cs.Vehicle
    return {
        "box-default": lambda: V.box(4.5, 1.8, 1.4, 1500.0),
        "box-cg-height": lambda: V.box(
            4.0, 1.8, 1.2, 1000.0, "b", cg_height=0.5, ground_clearance=0.2
        ),
        "box-empirical": lambda: V.box(
            4.5, 1.7, 1.4, weight_lb=3300.0, inertia="empirical", wheelbase=2.7
        ),
        "box-given-inertia": lambda: V.box(
            4.0, 2.0, 1.0, 900.0, inertia=np.diag([500.0, 1500, 1800])
        ),
        "box-stiffness": lambda: V.box(4.0, 1.8, 1.3, 1200.0, stiffness=SEDAN),
        "box-wheels": lambda: V.box(
            4.2,
            1.8,
            1.2,
            1400.0,
            ground_clearance=0.2,
            wheelbase=2.6,
            track=(1.5, 1.48),
            wheel_radius=(0.31, 0.3),
            cg_to_front_axle=1.1,
            tyre=cs.Tyre(),
        ),
        "box-wheels-given": lambda: V.box(
            4.2,
            1.8,
            1.2,
            1400.0,
            ground_clearance=0.2,
            wheels=cs.Wheels(2.6, 1.5, 1.1, 0.5, 0.3, natural_frequency=1.4),
        ),
        "box-zero-clearance-wheels-error": lambda: V.box(
            4.2, 1.8, 1.2, 1400.0, wheelbase=2.6, track=1.5, wheel_radius=0.3, cg_to_front_axle=1.1
        ),
        "box-negative-error": lambda: V.box(-4.0, 1.8, 1.2, 1000.0),
        "box-huge-error": lambda: V.box(4e5, 1.8, 1.2, 1000.0),
        "box-bad-mass-error": lambda: V.box(4.0, 1.8, 1.2, -3.0),
        "box-str-mass-error": lambda: V.box(4.0, 1.8, 1.2, "heavy"),
        "box-bad-name-error": lambda: V.box(4.0, 1.8, 1.2, 1000.0, name="a/b"),
        "box-bad-wheelbase-error": lambda: V.box(
            4.0, 1.8, 1.2, 1000.0, inertia="empirical", wheelbase=9.0
        ),
        "box-empirical-no-wb-error": lambda: V.box(4.0, 1.8, 1.2, 1000.0, inertia="empirical"),
    }


def generate_cases() -> dict[str, Callable[[], Any]]:
    G = cs.Vehicle.generate
    out: dict[str, Callable[[], Any]] = {}
    from crashsim.vehicles.generator import PRESETS

    for preset in PRESETS:
        out[f"gen-{preset}"] = lambda p=preset: G(p)
        out[f"gen-{preset}-mesh-rules"] = lambda p=preset: G(p, cg="mesh", inertia="mesh")
        out[f"gen-{preset}-empirical"] = lambda p=preset: G(p, inertia="empirical")
    out |= {
        "gen-alias": lambda: G("mid_car", name="alias"),
        "gen-scaled": lambda: G("sedan", mass=1600.0, length=4.9, wheelbase=2.9, height=1.5),
        "gen-lb": lambda: G("suv", weight_lb=4400.0, width=1.95),
        "gen-track": lambda: G("van", track=(1.7, 1.68), tyre={"model": "magic_formula"}),
        "gen-track-one": lambda: G("pickup", track=1.7),
        "gen-shape": lambda: G(
            "sedan", front_overhang=0.95, ground_clearance=0.16, wheel_radius=0.33, resolution=0.6
        ),
        "gen-cg-point": lambda: G("sedan", cg=(0.2, 0.0, 0.5)),
        "gen-cg-class-inertia-given": lambda: G(
            "sedan", cg="class", inertia=np.diag([500.0, 2400.0, 2600.0])
        ),
        "gen-stiffness": lambda: G("bus", stiffness={"front": {"A": 50000.0, "B": 900000.0}}),
        "gen-high-res": lambda: G("suv", resolution=1.5),
        "gen-tractor": lambda: G("tractor"),
        "gen-tractor-6x4": lambda: G("tractor_6x4", mass=8500.0, length=6.2, name="t2"),
        "gen-rigid": lambda: G("rigid_truck"),
        "gen-rigid-mass": lambda: G("rigid_truck", mass=11000.0, name="r2"),
        "gen-tractor-extra-error": lambda: G("tractor", width=2.4, resolution=2.0),
        "gen-rigid-extra-error": lambda: G("rigid_truck", inertia="mesh"),
        "gen-unknown-error": lambda: G("spaceship"),
        "gen-huge-error": lambda: G("sedan", length=2e4),
        "gen-bad-cg-error": lambda: G("sedan", cg="middle"),
        "gen-bad-inertia-error": lambda: G("sedan", inertia="box"),
        "gen-impossible-error": lambda: G("sedan", length=3.0, wheelbase=2.99),
        "gen-bad-dims-error": lambda: G("sedan", wheelbase=6.0),
        "gen-two-masses-error": lambda: G("sedan", mass=1.0, weight_lb=2.0),
    }
    return out


def generator_name(name: str) -> Any:
    """A name of the body generator: from crashsim.vehicles.generator, where every one stood
    before issue 20 split it, else from the module of its package that defines it."""
    import importlib
    import pkgutil

    gen = importlib.import_module("crashsim.vehicles.generator")
    modules = [gen]
    if hasattr(gen, "__path__"):  # a package since the split
        modules += [
            importlib.import_module(f"{gen.__name__}.{m.name}")
            for m in pkgutil.iter_modules(gen.__path__)
        ]
    for module in modules:
        if name in vars(module):
            return vars(module)[name]
    raise AttributeError(name)


# The generator's fixed numbers and tables (private names, read wherever they are defined).
GENERATOR_CONSTANTS = (
    "_DEFAULTS",
    "_SILL_RADIUS",
    "_STEP",
    "_SHOULDER_MIN",
    "_CROWN",
    "_MARGIN",
    "_ARCH_RAMP_DEG",
    "_FILLET",
    "_FILLET_MAX",
    "_PROFILE_SAMPLES",
    "_DIMS",
    "_NUMBERS",
    "_ARCH_BUMPER",
    "_ARCH_CLEARANCE",
    "_WHEEL_LEAST_SHARE",
    "_CLEARANCE_SHARE",
    "_CORNER_SHARE",
)
RESOLUTIONS = (0.25, 0.5, 0.7, 1.0, 1.7, 3.0, 8.0)


def body_text(p: Any, resolution: float) -> dict[str, Any]:
    """The parameters of a body, its loft (stations and sections) and its mesh, with the
    sha256 of its binary PLY."""
    g = generator_name
    x, sections = g("body_sections")(p, resolution)
    mesh = g("generate_body")(p, resolution)
    return {
        "params": p,
        "repr": repr(p),
        "as_dict": p.as_dict(),
        "rear_overhang": p.rear_overhang,
        "arch_radius": p.arch_radius,
        "x": x,
        "sections": sections,
        "mesh": mesh,
        "ply": hashlib.sha256(g("ply_bytes")(mesh)).hexdigest(),
    }


def body_private(p: Any) -> dict[str, Any]:
    """What the private geometry of a body gives: the checking stations, the profiles there,
    the stations and point counts at every resolution."""
    g = generator_name
    d = g("_check_stations")(p)
    return {
        "check_stations": d,
        "profiles": g("_profiles")(p, d),
        "stations": [g("_stations")(p, r) for r in RESOLUTIONS],
        "counts": [g("_counts")(r) for r in RESOLUTIONS],
        "top": g("_top_points")(p),
        "bottom": g("_bottom_points")(p),
        "near_axle": [g("_near_axle")(p, float(v)) for v in d[::50]],
    }


def generator_cases() -> dict[str, Callable[[], Any]]:
    """crashsim.vehicles.generator itself: its public names and tables, every preset at every
    resolution, every shape parameter given to every preset, dimensions that move the
    adaptive defaults, and every error of body_params, BodyParams, generate_body, loft and
    ply_bytes."""
    import importlib

    gen = importlib.import_module("crashsim.vehicles.generator")
    g = generator_name
    presets = g("PRESETS")
    bp, dims = g("body_params"), g("default_dims")
    out: dict[str, Callable[[], Any]] = {
        "body-api": lambda: {
            "all": list(gen.__all__),
            "all_names": [(n, type(getattr(gen, n)).__name__) for n in gen.__all__],
            "PRESETS": g("PRESETS"),
            "SHAPE_PARAMETERS": g("SHAPE_PARAMETERS"),
            "fields": [(f.name, str(f.type)) for f in dataclasses.fields(g("BodyParams"))],
            "dims": {p: dims(p) for p in presets},
            "constants": {n: g(n) for n in GENERATOR_CONSTANTS},
            "adaptive": [name for name, _ in g("_ADAPTIVE")],
            "may_be_zero": sorted(g("_MAY_BE_ZERO")),
        },
        "body-elementary": lambda: {
            "cos_sin": g("_cos_sin")(np.arange(1001, dtype=np.float64) * (np.pi / 1000)),
            "interp": g("_interp")(
                np.linspace(0.0, 3.0, 97), np.array([0.0, 0.5, 2.0, 3.0]), np.array([1, 2, 2, 0.5])
            ),
            "filleted": [
                g("_filleted")([(0.0, 1.0), (1.0, 1.3), (2.5, 1.3), (3.0, 0.2)], n) for n in (2, 16)
            ],
            "arc_stations": [g("_arc_stations")(r, n) for r in (0.1, 0.37) for n in (3, 5, 40)],
        },
    }
    for preset in presets:
        out[f"body-{preset}-private"] = lambda pr=preset: body_private(bp(pr, **dims(pr)))
        for r in RESOLUTIONS:
            out[f"body-{preset}-res-{r}"] = lambda pr=preset, r=r: body_text(bp(pr, **dims(pr)), r)
        # every shape parameter given, 4 % above its default (some give errors: fingerprinted)
        for name in g("SHAPE_PARAMETERS"):

            def shaped(pr: str = preset, name: str = name) -> Any:
                nominal = bp(pr, **dims(pr)).as_dict()[name]
                value = nominal * 1.04 if nominal > 0.0 else 0.01
                return body_text(bp(pr, **dims(pr), **{name: value}), 0.5)

            out[f"body-{preset}-shape-{name}"] = shaped
        # each dimension scaled (the adaptive defaults move; far ones are refused)
        for dim in ("length", "width", "height", "wheelbase"):
            for f in (0.7, 0.85, 1.15, 1.3):

                def scaled(pr: str = preset, dim: str = dim, f: float = f) -> Any:
                    given = dims(pr)
                    given[dim] *= f
                    return body_text(bp(pr, **given), 0.5)

                out[f"body-{preset}-{dim}-{f}"] = scaled
    # the adaptive defaults at short, low bodies with long wheelbases (every rule moves)
    out |= {
        "body-adapt-sedan-short": lambda: body_text(
            bp("sedan", length=3.6, width=1.6, height=1.2, wheelbase=2.6), 1.0
        ),
        "body-adapt-van-low": lambda: body_text(
            bp("van", length=4.2, width=1.7, height=1.35, wheelbase=2.9), 1.0
        ),
        "body-adapt-pickup-narrow": lambda: body_text(
            bp("pickup", length=4.6, width=1.5, height=1.5, wheelbase=3.3), 1.0
        ),
        "body-adapt-suv-given-wheel": lambda: body_text(
            bp("suv", length=3.8, width=1.7, height=1.5, wheelbase=2.7, wheel_radius=0.3), 1.0
        ),
        "body-adapt-clearance": lambda: body_text(
            bp("pickup", **dims("pickup"), wheel_radius=0.28), 1.0
        ),
        "body-adapt-bumper-bottom": lambda: body_text(
            bp("sedan", **dims("sedan"), ground_clearance=0.3), 1.0
        ),
        "body-adapt-edge": lambda: body_text(
            bp("sedan", **dims("sedan"), front_overhang=0.43, wheel_radius=0.31), 1.0
        ),
        "body-tumblehome-zero": lambda: body_text(bp("sedan", **dims("sedan"), tumblehome=0), 1),
        "body-numpy-numbers": lambda: body_text(
            bp("suv", length=np.float32(4.6), width=np.int64(2), height=1.7, wheelbase=2.7), 1.0
        ),
        "body-replace": lambda: body_text(
            dataclasses.replace(bp("bus", **dims("bus")), beltline=1.3, tumblehome=0.06), 1.0
        ),
        "body-direct": lambda: body_text(g("BodyParams")(**bp("van", **dims("van")).as_dict()), 1),
    }
    out |= generator_error_cases()
    out |= loft_cases()
    return out


def generator_error_cases() -> dict[str, Callable[[], Any]]:
    """Every ParameterError of the generator's parameters, with its message."""
    g = generator_name
    bp, dims = g("body_params"), g("default_dims")
    sedan = dims("sedan")
    L, wb = sedan["length"], sedan["wheelbase"]

    def sedan_with(**shape: Any) -> Any:
        return bp("sedan", **{**sedan, **shape})

    def replaced(**changes: Any) -> Any:
        return dataclasses.replace(bp("sedan", **sedan), **changes)

    bad_numbers = {
        "bool": True,
        "str": "4.8",
        "none": None,
        "nan": float("nan"),
        "inf": float("inf"),
        "negative": -1.0,
        "zero": 0.0,
    }
    out: dict[str, Callable[[], Any]] = {
        f"body-error-length-{k}": (lambda v=v: sedan_with(length=v)) for k, v in bad_numbers.items()
    }
    out |= {
        f"body-error-shape-{k}": (lambda v=v: sedan_with(arch_gap=v))
        for k, v in bad_numbers.items()
    }
    out |= {
        "body-error-tumblehome-negative": lambda: sedan_with(tumblehome=-0.01),
        "body-error-preset": lambda: bp("tank", **sedan),
        "body-error-preset-type": lambda: bp(3, **sedan),
        "body-error-dims-preset": lambda: dims("tank"),
        "body-error-direct-preset": lambda: g("BodyParams")(
            **{**bp("sedan", **sedan).as_dict(), "preset": "tank"}
        ),
        "body-error-unknown-shape": lambda: sedan_with(spoiler=0.1, fin=0.2),
        "body-error-wheelbase": lambda: sedan_with(wheelbase=L),
        "body-error-replace-wheelbase": lambda: replaced(wheelbase=L + 0.1),
        "body-error-replace-number": lambda: replaced(height="tall"),
        "body-error-rear-overhang-none": lambda: sedan_with(front_overhang=L - wb + 0.1),
        "body-error-front-overhang": lambda: sedan_with(front_overhang=0.3, wheel_radius=0.31),
        "body-error-rear-overhang": lambda: sedan_with(
            front_overhang=L - wb - 0.3, wheel_radius=0.31
        ),
        "body-error-wheelbase-arches": lambda: sedan_with(wheelbase=0.75, wheel_radius=0.31),
        "body-error-clearance": lambda: sedan_with(ground_clearance=0.4, wheel_radius=0.31),
        "body-error-bumper-bottom": lambda: sedan_with(bumper_bottom=0.1, ground_clearance=0.14),
        "body-error-beltline-high": lambda: sedan_with(beltline=sedan["height"]),
        "body-error-beltline-low": lambda: sedan_with(beltline=0.1),
        "body-error-arch-beltline": lambda: sedan_with(beltline=0.4),
        "body-error-beltline-ends": lambda: sedan_with(
            wheel_radius=0.16,
            arch_gap=0.01,
            ground_clearance=0.1,
            bumper_bottom=0.45,
            edge_radius=0.05,
            beltline=0.4,
        ),
        "body-error-nose": lambda: sedan_with(nose_height=sedan["height"] + 0.1),
        "body-error-hood": lambda: sedan_with(hood_height=sedan["height"] + 0.1),
        "body-error-deck": lambda: sedan_with(deck_height=sedan["height"] + 0.1),
        "body-error-tail": lambda: sedan_with(tail_height=sedan["height"] + 0.1),
        "body-error-windshield": lambda: sedan_with(windshield_base=0.005),
        "body-error-roof-start": lambda: replaced(roof_start=replaced().windshield_base),
        "body-error-roof-end": lambda: replaced(roof_end=replaced().roof_start + 0.005),
        "body-error-rear-window": lambda: replaced(rear_window_end=replaced().roof_end),
        "body-error-rear-window-far": lambda: sedan_with(rear_window_end=L + 0.2),
        "body-error-bumper-radius-width": lambda: sedan_with(bumper_radius=sedan["width"] / 2),
        "body-error-bumper-radius-front": lambda: sedan_with(front_overhang=0.7, bumper_radius=0.8),
        "body-error-bumper-radius-rear": lambda: sedan_with(front_overhang=1.4, bumper_radius=0.8),
        "body-error-arch-depth-small": lambda: sedan_with(arch_depth=0.05),
        "body-error-arch-depth-large": lambda: sedan_with(arch_depth=0.8),
        "body-error-tumblehome": lambda: sedan_with(tumblehome=0.5),
        "body-error-edge-radius": lambda: sedan_with(edge_radius=0.7),
        "body-error-front-face": lambda: sedan_with(nose_height=0.35),
        "body-error-rear-face": lambda: sedan_with(tail_height=0.35),
        "body-error-arch-fit": lambda: sedan_with(wheel_radius=0.45, arch_gap=0.1),
        "body-error-too-low": lambda: sedan_with(
            rear_window_end=4.5, deck_height=0.2, wheel_radius=0.31
        ),
        "body-error-adapt-refused": lambda: bp(
            "sedan", length=2.6, width=1.6, height=1.0, wheelbase=2.2
        ),
        "body-error-resolution-bool": lambda: g("generate_body")(bp("sedan", **sedan), True),
        "body-error-resolution-str": lambda: g("generate_body")(bp("sedan", **sedan), "1"),
        "body-error-resolution-nan": lambda: g("generate_body")(bp("sedan", **sedan), np.nan),
        "body-error-resolution-low": lambda: g("generate_body")(bp("sedan", **sedan), 0.2),
        "body-error-resolution-high": lambda: g("body_sections")(bp("sedan", **sedan), 8.5),
        "body-error-generate-type": lambda: g("generate_body")(sedan),
        "body-error-degenerate-section": lambda: g("_check_sections")(
            np.array([[[0.0, 0.0], [1.0, 0.5], [0.5, 0.2], [0.0, 1.0], [-1.0, 0.5]]]),
            bp("sedan", **sedan),
        ),
    }
    return out


def loft_cases() -> dict[str, Callable[[], Any]]:
    """loft on small hand-made sections, its errors, and ply_bytes with comments."""
    g = generator_name
    square = np.array([[-1.0, 0.0], [1.0, 0.0], [1.0, 1.0], [-1.0, 1.0]])
    x = np.array([0.0, 0.5, 2.0])
    secs = np.stack([square, square * 1.2, square * 0.8])
    loft, ply = g("loft"), g("ply_bytes")
    body = lambda: g("generate_body")(g("body_params")("van", **g("default_dims")("van")), 0.4)  # noqa: E731

    def ply_text(mesh: trimesh.Trimesh, comments: Any) -> Any:
        data = ply(mesh, comments)
        return {"sha256": hashlib.sha256(data).hexdigest(), "head": data[:400]}

    return {
        "loft-squares": lambda: loft(x, secs),
        "loft-lists": lambda: loft([0, 1], [square.tolist(), square.tolist()]),
        "loft-error-x-2d": lambda: loft(x[None, :], secs),
        "loft-error-one": lambda: loft(x[:1], secs[:1]),
        "loft-error-count": lambda: loft(x[:2], secs),
        "loft-error-shape": lambda: loft(x, secs[:, :, :1]),
        "loft-error-two-points": lambda: loft(x, secs[:, :2]),
        "loft-error-nan": lambda: loft(x, np.where(secs > 1.1, np.nan, secs)),
        "loft-error-inf-x": lambda: loft(np.array([0.0, 1.0, np.inf]), secs),
        "loft-error-order": lambda: loft(np.array([0.0, 2.0, 1.0]), secs),
        "loft-error-clockwise": lambda: loft(x, secs[:, ::-1]),
        "ply-plain": lambda: ply_text(body(), None),
        "ply-comments": lambda: ply_text(
            body(), {"generator": "fingerprint", "length": 4.5, "n": 3, "ok": True}
        ),
        "ply-error-newline": lambda: ply(body(), {"a": "one\ntwo"}),
    }


def derived_cases() -> dict[str, Callable[[], Any]]:
    def sedan() -> cs.Vehicle:
        return cs.Vehicle.generate("sedan", name="car")

    def with_wheels_numbers() -> cs.Vehicle:
        return cs.Vehicle.box(4.0, 1.8, 1.2, 1200.0, ground_clearance=0.2).with_wheels(
            wheelbase=2.5,
            track=1.5,
            radius=0.3,
            cg_to_front_axle=1.2,
            natural_frequency=(1.3, 1.5),
            damping_ratio=0.4,
            steer="both",
            source="mine",
        )

    def with_wheels_object() -> cs.Vehicle:
        w = cs.Wheels(2.5, 1.5, 1.2, 0.8, 0.3)
        return cs.Vehicle.box(4.0, 1.8, 1.2, 1200.0, ground_clearance=0.2).with_wheels(
            w, tyre={"model": "linear_friction_scaled"}
        )

    return {
        "derived-renamed": lambda: sedan().renamed("car2"),
        "derived-hitch-ball": lambda: sedan().with_hitch((-2.45, 0.0, 0.45), "ball"),
        "derived-hitch-fifth": lambda: cs.Vehicle.box(6.0, 2.5, 3.0, 8000.0).with_hitch(
            (-1.0, 0.0, 1.2), "fifth_wheel"
        ),
        "derived-hitch-far-error": lambda: sedan().with_hitch((-9.0, 0.0, 0.45)),
        "derived-hitch-kind-error": lambda: sedan().with_hitch((-2.4, 0.0, 0.45), "hook"),
        "derived-with-wheels-numbers": with_wheels_numbers,
        "derived-with-wheels-object": with_wheels_object,
        "derived-with-wheels-missing-error": lambda: sedan().with_wheels(wheelbase=2.5),
        "derived-with-wheels-clash-error": lambda: sedan().with_wheels(
            cs.Wheels(2.5, 1.5, 1.2, 0.5, 0.3), wheelbase=2.5
        ),
        "derived-with-wheels-type-error": lambda: sedan().with_wheels("four"),  # type: ignore[arg-type]
        "derived-with-wheels-outside-error": lambda: sedan().with_wheels(
            wheelbase=9.0, track=1.5, radius=0.3, cg_to_front_axle=1.2
        ),
        "derived-with-wheels-floating-error": lambda: cs.Vehicle.box(
            4.0, 1.8, 1.2, 1000.0, cg_height=-0.5
        ).with_wheels(wheelbase=2.5, track=1.5, radius=0.3, cg_to_front_axle=1.2),
        "derived-solid-properties": lambda: mass_function("solid_properties")(
            trimesh.creation.box(extents=(4.0, 2.0, 1.0))
        ),
        "derived-empirical-inertia": lambda: mass_function("empirical_inertia")(
            1500.0, 2.7, 4.5, 1.8, 1.4
        ),
    }


def mass_function(name: str) -> Callable[..., Any]:
    """A mass-property function of crashsim.vehicles, from vehicle.py where it stood before
    issue 20 split it, else from mass_properties.py, its home since."""
    import importlib

    for module in ("crashsim.vehicles.vehicle", "crashsim.vehicles.mass_properties"):
        found = getattr(importlib.import_module(module), name, None)
        if found is not None:
            return found  # type: ignore[no-any-return]
    raise AttributeError(name)


def trailer_cases() -> dict[str, Callable[[], Any]]:
    T = cs.Trailer
    semi = dict(
        length=13.6,
        width=2.5,
        height=2.7,
        mass=12000.0,
        ground_clearance=1.25,
        coupler=1.0,
        coupler_height=1.2,
        axles=[11.0],
        track=2.0,
        radius=0.5,
        cg_height=2.0,
    )
    caravan = dict(
        length=3.0,
        width=1.6,
        height=1.2,
        mass=750.0,
        ground_clearance=0.4,
        coupler=1.2,
        coupler_height=0.45,
        axles=[1.7],
        track=1.4,
        radius=0.3,
    )
    drawbar = dict(
        length=7.0,
        width=2.5,
        height=2.5,
        mass=9000.0,
        ground_clearance=1.1,
        turntable=1.0,
        rear_axles=[5.5, 6.8],
        drawbar=2.5,
        eye_height=0.8,
        track=2.0,
        radius=0.5,
        dolly_mass=800.0,
    )
    out: dict[str, Callable[[], Any]] = {}
    for preset in ("box_van", "flatbed", "tanker", "caravan"):
        out[f"trailer-{preset}"] = lambda p=preset: T.generate(p)
    out |= {
        "trailer-box_van-empty": lambda: T.generate("box_van", laden=False, name="empty"),
        "trailer-box_van-override": lambda: T.generate(
            "box_van", coupler_height=1.2, natural_frequency=1.6, abs=False
        ),
        "trailer-flatbed-empty": lambda: T.generate("flatbed", laden=False),
        "trailer-flatbed-mass": lambda: T.generate(
            "flatbed", mass=25000.0, load_height=1.4, load_sharing=False, track=2.05
        ),
        "trailer-tanker-empty-mass": lambda: T.generate("tanker", laden=False, mass=9000.0),
        "trailer-tanker-empty-error": lambda: T.generate("tanker", laden=False),
        "trailer-flatbed-unknown-error": lambda: T.generate("flatbed", width=2.0),
        "trailer-flatbed-low-deck-error": lambda: T.generate("flatbed", coupler_height=3.0),
        "trailer-caravan-empty": lambda: T.generate("caravan", laden=False, coupler_height=0.5),
        "trailer-unknown-error": lambda: T.generate("dolly"),
        "trailer-no-builder-error": lambda: T.generate("drawbar_trailer"),
        "trailer-box-semi": lambda: T.box("semitrailer", name="semi", **semi),
        "trailer-box-semi-tridem": lambda: T.box(
            "semitrailer",
            **{**semi, "axles": [9.9, 11.2, 12.5], "mass": 20000.0},
            yaw_inertia=400000.0,
            tyre={"model": "magic_formula"},
        ),
        "trailer-box-centre-axle": lambda: T.box("centre_axle", cg_from_front=1.5, **caravan),
        "trailer-box-drawbar-body": lambda: T.box("drawbar_body", **semi),
        "trailer-box-kind-error": lambda: T.box("lowboy", **semi),
        "trailer-box-no-axle-error": lambda: T.box("semitrailer", **{**semi, "axles": []}),
        "trailer-box-kingpin-error": lambda: T.box("semitrailer", **{**semi, "coupler": 20.0}),
        "trailer-box-clearance-error": lambda: T.box(
            "semitrailer", **{**semi, "ground_clearance": 0.0}
        ),
        "trailer-box-mass-error": lambda: T.box("semitrailer", **{**semi, "mass": "x"}),
        "trailer-drawbar": lambda: T.drawbar(name="dt", **drawbar),
        "trailer-drawbar-cg": lambda: T.drawbar(cg_height=2.2, cg_from_front=3.2, **drawbar),
        "trailer-from-vehicle": lambda: T.from_vehicle(
            cs.Vehicle.box(5.0, 2.2, 2.0, 2500.0, ground_clearance=0.5),
            "centre_axle",
            coupler_at=(3.4, 0.0, 0.5),
            axles=[0.0],
            track=1.8,
            radius=0.35,
        ),
        "trailer-from-vehicle-kind-error": lambda: T.from_vehicle(
            cs.Vehicle.box(5.0, 2.2, 2.0, 2500.0),
            "x",
            coupler_at=(0, 0, 0),
            axles=[0.0],
            track=1.8,
            radius=0.35,
        ),
        "trailer-from-vehicle-point-error": lambda: T.from_vehicle(
            cs.Vehicle.box(5.0, 2.2, 2.0, 2500.0),
            "semitrailer",
            coupler_at=(0, 0),
            axles=[0.0],
            track=1.8,
            radius=0.35,
        ),
        "trailer-from-vehicle-far-error": lambda: T.from_vehicle(
            cs.Vehicle.box(5.0, 2.2, 2.0, 2500.0, ground_clearance=0.5),
            "semitrailer",
            coupler_at=(9.0, 0.0, 1.0),
            axles=[-1.0],
            track=1.8,
            radius=0.35,
        ),
    }
    return out


def truck_cases() -> dict[str, Callable[[], Any]]:
    tractor = dict(
        mass=7000.0,
        wheelbase=3.8,
        tandem_spread=1.3,
        fifth_wheel_ahead=0.3,
        fifth_wheel_height=1.2,
        cg_to_front_axle=1.6,
        cg_height=1.0,
        track=2.0,
        radius=0.5,
        length=6.0,
    )
    rigid = dict(
        mass=12000.0,
        wheelbase=5.0,
        cg_to_front_axle=2.6,
        track=2.0,
        radius=0.5,
        length=9.0,
        width=2.5,
        height=3.6,
        front_overhang=1.4,
    )
    return {
        "tractor-preset": lambda: cs.tractor("tractor_6x4"),
        "tractor-preset-override": lambda: cs.tractor(
            "tractor_6x4", mass=9000.0, inertia=np.diag([5e3, 3e4, 3e4])
        ),
        "tractor-4x2": lambda: cs.tractor(
            driven_axles=1, steering_reference="centre", name="t42", **tractor
        ),
        "tractor-6x4-custom": lambda: cs.tractor(
            load_sharing=False,
            steering_ratio=18.0,
            abs=False,
            **{**tractor, "radius": (0.5, 0.52)},
        ),
        "tractor-missing-error": lambda: cs.tractor(mass=7000.0),
        "tractor-axles-error": lambda: cs.tractor(driven_axles=3, **tractor),
        "tractor-unknown-preset-error": lambda: cs.tractor("tractor_8x4"),
        "rigid-preset": lambda: cs.rigid_truck("rigid_truck"),
        "rigid-custom": lambda: cs.rigid_truck(
            cg_height=1.3,
            hitch_height=0.7,
            floor_height=1.2,
            tyre={"model": "magic_formula"},
            name="r",
            **rigid,
        ),
        "rigid-missing-error": lambda: cs.rigid_truck(mass=1.0),
        "rigid-overhang-error": lambda: cs.rigid_truck(**{**rigid, "wheelbase": 9.0}),
        "rigid-floor-error": lambda: cs.rigid_truck(floor_height=5.0, **rigid),
        "public-names": lambda: [(n, type(getattr(cs, n)).__name__) for n in sorted(cs.__all__)],
    }


def scenes() -> dict[str, Callable[[], Any]]:
    """A few scenes run in the engine: the raw output of ``SceneSpec.run()``."""

    def run(scene: cs.Scene, duration: float, **kw: Any) -> dict[str, Any]:
        return scene.to_spec(duration, 1e-3, **kw).run()

    def cars() -> dict[str, Any]:
        a = cs.Vehicle.generate("sedan", name="a")
        b = cs.Vehicle.generate("suv", name="b")
        scene = cs.Scene(ground=cs.Ground(friction=0.8))
        scene.add(a, (-3.2, 0.0), heading=0.0, velocity=(15.0, 0.0, 0.0))
        scene.add(b, (0.0, 0.3), heading=1.5708)
        return run(scene, 0.4, record_interval=0.01)

    def boxes() -> dict[str, Any]:
        a = cs.Vehicle.box(4.5, 1.8, 1.4, 1500.0, name="a", stiffness=SEDAN)
        b = cs.Vehicle.from_mesh(open_box(), mass=1200.0, name="b", stiffness=SEDAN)
        scene = cs.Scene()
        scene.add(a, (-3.5, 0.0, 0.7), velocity=(10.0, 0.0, 0.0))
        scene.add(b, (1.5, 0.5, 0.7), heading=1.0)
        return run(scene, 0.3)

    def jackknife() -> dict[str, Any]:
        tractor = cs.Vehicle.generate("tractor")
        semi = cs.Trailer.generate("box_van")
        steer = cs.DriverInputs(steer=np.array([[0.0, 0.0], [0.3, 0.05], [1.5, 0.05]]))
        scene = cs.Scene(ground=cs.Ground(friction=0.35))
        scene.add(tractor, (0.0, 0.0), velocity=(20.0, 0.0, 0.0), inputs=steer, trailers=[semi])
        return run(scene, 1.5, record_interval=0.01)

    def caravan() -> dict[str, Any]:
        car = cs.Vehicle.generate("sedan", name="car")
        lo = (car.mesh.bounds[0] - car.cg)[0]
        car = car.with_hitch(car.cg + [lo - 0.15, 0.0, 0.45 - car.cg[2]], "ball")
        van = cs.Trailer.generate("caravan", coupler_height=0.45)
        brake = cs.DriverInputs(brake=0.4)
        scene = cs.Scene(ground=cs.Ground(friction=0.8))
        scene.add(car, (0.0, 0.0), velocity=(14.0, 0.0, 0.0), inputs=brake, trailers=[van])
        return run(scene, 1.0, record_interval=0.01)

    def drawbar() -> dict[str, Any]:
        truck = cs.rigid_truck("rigid_truck")
        dolly, body = cs.Trailer.drawbar(
            length=7.0,
            width=2.5,
            height=2.5,
            mass=9000.0,
            ground_clearance=1.1,
            turntable=1.0,
            rear_axles=[5.5, 6.8],
            drawbar=2.5,
            eye_height=float((truck.hitch.point + truck.cg)[2]),
            track=2.0,
            radius=0.5,
            dolly_mass=800.0,
        )
        steer = cs.DriverInputs(steer=np.array([[0.0, 0.0], [0.5, 0.08], [1.0, 0.08]]))
        scene = cs.Scene(ground=cs.Ground(friction=0.8))
        scene.add(
            truck, (0.0, 0.0), velocity=(12.0, 0.0, 0.0), inputs=steer, trailers=[dolly, body]
        )
        return run(scene, 1.0, record_interval=0.01)

    def flatbed_tanker_specs() -> list[str]:
        out = []
        for preset in ("flatbed", "tanker"):
            scene = cs.Scene(ground=cs.Ground())
            scene.add(cs.tractor("tractor_6x4"), (0.0, 0.0), trailers=[cs.Trailer.generate(preset)])
            out.append(scene.to_spec(1.0, 1e-3).to_json())
        return out

    out: dict[str, Callable[[], Any]] = {
        "scene-cars": cars,
        "scene-boxes": boxes,
        "scene-jackknife": jackknife,
        "scene-caravan": caravan,
        "scene-drawbar": drawbar,
        "scene-flatbed-tanker-specs": flatbed_tanker_specs,
    }
    for path in sorted(SHARED_MESHES.glob("*.ply"))[:2]:

        def mesh_crash(p: Path = path) -> dict[str, Any]:
            a = cs.Vehicle.from_mesh(
                p, mass=MESH_MASS.get(p.stem, 1500.0), name="a", stiffness=SEDAN
            )
            b = cs.Vehicle.generate("sedan", name="b")
            scene = cs.Scene()
            half = float(a.extents[0]) / 2.0 + float(b.cg[0]) + 2.5
            scene.add(a, (-half, 0.0, float(a.cg[2])), velocity=(12.0, 0.0, 0.0))
            scene.add(b, (0.0, 0.4, float(b.cg[2])), heading=1.5708)
            return run(scene, 0.3)

        out[f"scene-mesh-{path.stem}"] = mesh_crash
    return out


def main(out: Path) -> None:
    out.mkdir(parents=True, exist_ok=True)
    groups = (
        mesh_cases,
        box_cases,
        generate_cases,
        generator_cases,
        derived_cases,
        trailer_cases,
        truck_cases,
        scenes,
    )
    total = hashlib.sha256()
    for group in groups:
        for name, make in group().items():
            text = case(make)
            (out / f"{name}.txt").write_text(text, encoding="utf-8")
            total.update(name.encode() + b"\0" + text.encode() + b"\0")
    files = sorted(out.glob("*.txt"))
    print(f"{len(files)} cases; shared meshes: {len(list(SHARED_MESHES.glob('*.ply')))}")
    print(f"sha256 {total.hexdigest()}")


if __name__ == "__main__":
    if len(sys.argv) != 2:
        sys.exit("usage: vehicles_fingerprint.py OUTPUT_FOLDER")
    main(Path(sys.argv[1]))
