"""Vehicles: a triangle mesh, a mass, a centre of gravity, an inertia tensor and face stiffness.

Frames: the *model frame* is the vehicle's own (m; x forward, y left, z up; ground at z = 0 for
the usual vehicle mesh); :func:`crashsim.vehicles.meshio.load_mesh` brings a file in other units and
axes into it. The *body frame* is the model frame shifted so the CG is the origin (ISO 8855):
body vertices = model vertices - cg. The inertia tensor is about the CG in body axes (kg m^2).

Where every number came from is kept (``mass_source``, ``sources``) and printed by
``summary()``. Mass properties "from the mesh" treat the vehicle as a uniform solid scaled to
its mass; the solid is the mesh itself when it is a closed volume, else a documented stand-in
(``solid=``: convex hull, union of the closed shells, or the region the engine counts as inside,
generalized winding number > 1/2). See docs/meshes.md.

:meth:`Vehicle.generate` builds a vehicle without a mesh file: a body from
:mod:`crashsim.vehicles.generator` and every number from the built-in class table
(:mod:`crashsim.vehicles.vehicle_data`), scaled to the dimensions given; see docs/generator.md.

Mass and inertia are validated by the engine itself (`_check_mass_properties`), so the
accepted ranges and their messages live in one place (crates/crashsim-core).
"""

from __future__ import annotations

import contextlib
import functools
import math
from collections.abc import Callable, Iterator
from pathlib import Path
from typing import Any

import numpy as np
import trimesh
from numpy.typing import ArrayLike, NDArray

from crashsim import _core
from crashsim.errors import MeshError, ParameterError
from crashsim.names import check_name
from crashsim.units import POUND
from crashsim.vehicles import plausibility
from crashsim.vehicles.coupling import Hitch
from crashsim.vehicles.generator import PRESETS, BodyParams, body_params, generate_body
from crashsim.vehicles.meshio import (
    MeshQuality,
    MeshSource,
    axes_rotation,
    check_mesh,
    closed_shells,
    describe,
    load_mesh,
    mesh_quality,
    shell_labels,
    unit_scale,
)
from crashsim.vehicles.stiffness import FACES, Stiffness
from crashsim.vehicles.vehicle_data import ALIASES, VehicleClass, vehicle_class
from crashsim.vehicles.wheels import Tyre, Wheels

__all__ = ["Vehicle", "solid_properties"]

Array = NDArray[np.float64]

# Where a vehicle's numbers came from (values of Vehicle.sources and Vehicle.mass_source).
USER = "user"
WEIGHT_LB = "weight in lb"
MESH_VOLUME = "mesh volume"
CLOSED_SHELLS = "closed shells"
CONVEX_HULL = "convex hull"
WINDING_SOLID = "winding-number solid"
UNIFORM_BOX = "uniform box"
EMPIRICAL = "empirical"
GENERATED_SOLID = "uniform solid of the generated body"

# solid= choices of from_mesh: the solid that stands for an open mesh.
SOLIDS = ("auto", "convex hull", "closed shells", "winding number")

# Cells of the grid over the mesh's box on which the winding-number solid is integrated.
WINDING_GRID_CELLS = 50_000
# A mesh whose smallest extent is at most this fraction of its largest is flat: no solid.
FLAT_RATIO = 1e-9

_ZERO3 = (0.0, 0.0, 0.0)
_IDENTITY = (1.0, 0.0, 0.0, 0.0)  # quaternion (w, x, y, z)


@functools.cache
def _probe_shape() -> _core.Shape:
    """A one-triangle shape for asking the engine to validate numbers (never simulated)."""
    return _core.Shape(np.array([[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]]), [[0, 1, 2]])


def _as_float(value: Any, name: str, unit: str) -> float:
    """A Python float, or a ParameterError saying what was expected."""
    if isinstance(value, str):
        raise ParameterError(f"{name} must be a number ({unit}), got {value!r}")
    try:
        return float(value)
    except (TypeError, ValueError) as e:
        raise ParameterError(f"{name} must be a number ({unit}), got {value!r}") from e


def _check_mass_properties(mass: float, inertia: ArrayLike) -> None:
    """Raises ParameterError unless mass (kg) is finite and positive and inertia (kg m^2) is
    a finite, symmetric, positive definite 3x3 tensor: the engine's own checks."""
    _core.SceneSpec().add_body(_probe_shape(), mass, inertia, _ZERO3, _IDENTITY, _ZERO3, _ZERO3)


def _point(value: ArrayLike, name: str) -> Array:
    """A finite 3-vector (m) as a float array."""
    try:
        p = np.array(value, dtype=np.float64).reshape(-1)
    except (TypeError, ValueError) as e:
        raise ParameterError(f"{name} must be 3 numbers (x, y, z), got {value!r}") from e
    if p.size != 3:
        raise ParameterError(f"{name} must be 3 numbers (x, y, z), got {p.size}")
    if not np.all(np.isfinite(p)):
        raise ParameterError(f"{name} = {p.tolist()} is invalid: every component must be finite")
    return p


def _read_only(a: ArrayLike) -> Array:
    out = np.array(a, dtype=np.float64)
    out.setflags(write=False)
    return out


def _mass(mass: Any, weight_lb: Any) -> tuple[float, str]:
    """(kg, where it came from) from exactly one of mass (kg) and weight_lb (lb)."""
    if mass is not None and weight_lb is not None:
        raise ParameterError(
            f"both mass = {mass!r} kg and weight_lb = {weight_lb!r} lb were given: they "
            "conflict; give exactly one of them"
        )
    if mass is None and weight_lb is None:
        raise ParameterError("the vehicle needs its mass: give mass (kg) or weight_lb (lb)")
    if weight_lb is not None:
        pounds = _as_float(weight_lb, "weight_lb", "lb")
        value, source = pounds * POUND, f"{WEIGHT_LB} ({pounds:g} lb)"
    else:
        value, source = _as_float(mass, "mass", "kg"), USER
    _check_mass_properties(value, np.eye(3))  # a bad mass is reported before any mesh work
    return value, source


def _parallel_axis(inertia_cm: Array, mass: float, d: Array) -> Array:
    """Inertia about a point displaced by d (m) from the centre of mass (kg m^2).
    ParameterError when it overflows (a CG absurdly far from the body)."""
    with np.errstate(over="ignore", invalid="ignore"):
        out = inertia_cm + mass * (float(d @ d) * np.eye(3) - np.outer(d, d))
    if not np.all(np.isfinite(inertia_cm)):
        raise ParameterError(
            f"the inertia of a {mass:g} kg body is not finite: give the mass in kg"
        )
    if not np.all(np.isfinite(out)):
        raise ParameterError(
            f"the CG is {float(np.linalg.norm(d)):.3g} m from the centre of the body's solid: "
            "the inertia about it is not finite; give a CG on the vehicle (m, model frame) and "
            "its dimensions in metres"
        )
    return out


def _box_inertia(mass: float, length: float, width: float, height: float) -> Array:
    """Uniform solid box about its centre, axes along its edges (kg m^2); an absurd mass
    overflows to inf without a warning, and the engine's check refuses it."""
    with np.errstate(over="ignore", invalid="ignore"):
        return (mass / 12.0) * np.diag(
            [width**2 + height**2, length**2 + height**2, length**2 + width**2]
        )


# The empirical rule's yaw moment m (WB/2)^2 stays below the box's Ixx + Iyy only while
# 3 WB^2 <= L^2 + W^2 + 2 H^2 (a wheelbase up to about 0.7 of a car's length).
_EMPIRICAL_FIX = (
    "a shorter wheelbase (the rule needs 3 WB^2 <= L^2 + W^2 + 2 H^2), inertia='mesh', or "
    "the inertia"
)


@contextlib.contextmanager
def _rule_hint(mode: str, fix: str) -> Iterator[None]:
    """Adds to an impossible-inertia ParameterError that a rule ("class", "empirical") made
    the tensor and what to give instead (``fix``)."""
    try:
        yield
    except ParameterError as e:
        if mode in ("class", "empirical") and "is impossible" in str(e):
            raise ParameterError(
                f"{e}. The {mode!r} rule gave this tensor for these dimensions: give {fix}"
            ) from e
        raise


def _dims(extents: ArrayLike) -> str:
    """'4.22 x 1.81 x 1.18 m' (length x width x height)."""
    return " x ".join(f"{float(x):.3g}" for x in np.asarray(extents)) + " m"


def _volume_estimate(mesh: trimesh.Trimesh) -> tuple[float | None, str]:
    """(m^3, what it is) of the solid a mesh stands for when its mass properties were not
    needed (cg and inertia given): the mesh's own volume when it is closed, else its convex
    hull's (at least the solid's: the density from it is low by up to 1.8x on the shared
    meshes, well inside the plausible range's margin); None when it has none (flat)."""
    if mesh.is_watertight and mesh.is_winding_consistent:
        volume = solid_properties(mesh)[0]
        if volume > 0.0:
            return volume, "the mesh volume"
    try:
        with np.errstate(all="ignore"):
            hull = mesh.convex_hull
            volume = float(hull.volume)
    except Exception:  # qhull refuses flat or degenerate point sets: nothing to judge
        return None, ""
    return (volume, "its convex hull") if volume > 0.0 else (None, "")


def _wheelbase(wheelbase: Any, length: float) -> float:
    wb = _as_float(wheelbase, "wheelbase", "m")
    if not math.isfinite(wb) or wb <= 0.0 or wb > length:
        raise ParameterError(
            f"wheelbase = {wb} m is invalid: it must be positive and no longer than the "
            f"vehicle ({length:.3f} m); check its unit (m)"
        )
    return wb


def empirical_inertia(
    mass: float, wheelbase: float, length: float, width: float, height: float
) -> Array:
    """Inertia about the CG from dimensions (kg m^2), body axes, no products of inertia.

    Yaw: Izz = m (0.5 WB)^2, the measured yaw radius of gyration of passenger cars being
    0.47-0.52 of the wheelbase (shared/data/reference-cases.md section 3). Roll and pitch: the
    uniform solid box of the vehicle's extents, Ixx = m (W^2 + H^2) / 12, Iyy = m (L^2 + H^2)
    / 12 (the same box's yaw moment over-estimates the measured one of the reference cars by
    about 40 %, so these two are likely high as well).
    """
    box = _box_inertia(mass, length, width, height)
    return np.diag([box[0, 0], box[1, 1], mass * (0.5 * wheelbase) ** 2])


# -- mass properties of solids -----------------------------------------------------------------


def solid_properties(mesh: trimesh.Trimesh) -> tuple[float, Array, Array]:
    """(volume m^3, centroid m, inertia about the centroid for unit density (3, 3)) of a
    closed, outward-wound mesh, by the divergence theorem in the engine
    (``_core.solid_properties``; trimesh's mass properties are the independent check in the
    tests). Callers check the volume: a mesh enclosing none (open or flat; the engine
    refuses it) gives volume 0 and a centroid and inertia that are not finite."""
    try:
        props = _core.solid_properties(
            np.asarray(mesh.vertices, dtype=np.float64), np.asarray(mesh.faces, dtype=np.int64)
        )
    except MeshError:
        return 0.0, np.full(3, np.nan), np.full((3, 3), np.nan)
    return (
        float(props["volume"]),
        np.asarray(props["centroid"], dtype=np.float64),
        np.asarray(props["inertia"], dtype=np.float64),
    )


def _combine(parts: list[tuple[float, Array, Array]]) -> tuple[float, Array, Array]:
    """The union of solids as the sum of their mass properties (unit density)."""
    volume = sum(p[0] for p in parts)
    centroid = sum(p[0] * p[1] for p in parts) / volume
    inertia = sum(_parallel_axis(p[2], p[0], p[1] - centroid) for p in parts)
    return float(volume), np.asarray(centroid), np.asarray(inertia)


def _grid_counts(ext: Array, cells: int) -> NDArray[np.int64]:
    """Cells per axis of a grid of about ``cells`` near-cubic cells over a box of extents
    ``ext`` (m). An axis thinner than one cell gets a single cell and the others share the
    budget (a bare cube root would give a thin box millions of cells along its long sides:
    a 1 x 2e-16 x 1 m mesh asked for 3.7e13 of them and ran out of memory)."""
    counts = np.ones(3, dtype=np.int64)
    free = np.ones(3, dtype=bool)
    for _ in range(3):
        budget = cells / float(np.prod(counts[~free]))
        side = (float(np.prod(ext[free])) / budget) ** (1.0 / int(free.sum()))
        wanted = np.ceil(ext / side)
        thin = free & (wanted <= 1.0)
        counts[free] = np.maximum(1, wanted[free]).astype(np.int64)
        if not thin.any() or thin.all():
            break
        free &= ~thin
        counts[thin] = 1
    return counts


def _winding_solid(mesh: trimesh.Trimesh, what: str) -> tuple[float, Array, Array]:
    """Mass properties (unit density) of the region where the engine's generalized winding
    number exceeds 1/2, integrated on a grid of about WINDING_GRID_CELLS cells over the mesh's
    box (each inside cell a uniform small box)."""
    lo, hi = mesh.bounds
    ext = hi - lo
    if not float(ext.min()) > FLAT_RATIO * float(ext.max()):
        raise MeshError(
            f"{what} encloses no volume (it is flat: {_dims(ext)}): give cg and inertia "
            'explicitly, or use inertia="empirical" with a wheelbase'
        )
    counts = _grid_counts(ext, WINDING_GRID_CELLS)
    cell = ext / counts
    axes = [lo[i] + (np.arange(counts[i]) + 0.5) * cell[i] for i in range(3)]
    grid = np.stack(np.meshgrid(*axes, indexing="ij"), axis=-1).reshape(-1, 3)
    shape = _core.Shape(np.asarray(mesh.vertices, dtype=np.float64), np.asarray(mesh.faces))
    inside = grid[shape.winding_numbers(grid) > 0.5]
    dv = float(np.prod(cell))
    if len(inside) == 0:
        raise MeshError(
            f"{what} encloses no volume: no point of a {counts.tolist()} grid over its box "
            "has a winding number above 1/2 (a single open sheet?); give cg and inertia "
            'explicitly, or use inertia="empirical" with a wheelbase'
        )
    centroid = inside.mean(axis=0)
    d = inside - centroid
    inertia = (np.eye(3) * float(np.sum(d * d)) - d.T @ d) * dv
    sq = cell**2  # each cell's own inertia about its centre: a uniform small box
    inertia += np.diag([sq[1] + sq[2], sq[0] + sq[2], sq[0] + sq[1]]) * dv * len(inside) / 12.0
    return dv * len(inside), centroid, inertia


def _solid(
    mesh: trimesh.Trimesh, what: str, solid: str
) -> tuple[tuple[float, Array, Array], str, str]:
    """(unit-density mass properties, source, detail) of the solid standing for the mesh."""
    if solid not in SOLIDS:
        raise ParameterError(f"solid = {solid!r} is unknown: use one of {', '.join(SOLIDS)}")
    if mesh.is_watertight and mesh.is_winding_consistent:
        props = solid_properties(mesh)
        if props[0] < 0.0:
            raise MeshError(
                f"{what} is closed but its faces point inwards (volume {props[0]:.4g} m^3): "
                "the engine needs outward faces; invert it (trimesh: mesh.invert()) and load "
                "again"
            )
        if props[0] > 0.0:
            return props, MESH_VOLUME, f"{MESH_VOLUME} {props[0]:.4g} m^3"
    if solid == "convex hull":
        try:
            hull = mesh.convex_hull
        except Exception as e:  # qhull fails on flat or degenerate point sets
            raise MeshError(
                f"{what} is not a closed volume and its convex hull failed ({e}): it encloses "
                'no volume; give cg and inertia explicitly, or inertia="empirical" with a '
                "wheelbase"
            ) from e
        if not hull.is_volume or hull.volume <= 0.0:
            raise MeshError(
                f"{what} encloses no volume (flat or degenerate): give cg and inertia "
                'explicitly, or inertia="empirical" with a wheelbase'
            )
        props = solid_properties(hull)
        return props, CONVEX_HULL, f"{CONVEX_HULL} {props[0]:.4g} m^3 (the mesh is open)"
    if solid == "closed shells":
        shells = closed_shells(mesh)
        parts = [solid_properties(s) for s in shells]
        parts = [p for p in parts if p[0] > 0.0]
        if not parts:
            raise MeshError(
                f"{what} has no closed shell enclosing a volume: use solid='convex hull' or "
                "'winding number', or give cg and inertia explicitly"
            )
        props = _combine(parts)
        n = int(shell_labels(mesh).max()) + 1
        return (
            props,
            CLOSED_SHELLS,
            (f"{CLOSED_SHELLS}: {len(parts)} of {n}, {props[0]:.4g} m^3 (open shells ignored)"),
        )
    props = _winding_solid(mesh, what)
    return props, WINDING_SOLID, f"{WINDING_SOLID} {props[0]:.4g} m^3 (grid integration)"


COMBINATION_PRESETS: dict[str, Callable[..., Vehicle]] = {}
"""Presets of Vehicle.generate built elsewhere ("tractor": crashsim.vehicles.trailer registers
its builder when imported, so this module does not import that one, which imports it)."""


class Vehicle:
    """A rigid vehicle.

    Attributes (read-only): ``name``; ``mass`` (kg); ``mesh`` (trimesh.Trimesh, model frame,
    m; treat it as read-only: the engine's copy is built from it once); ``cg`` (model-frame
    point, m); ``inertia`` ((3, 3) about the CG in body axes, kg m^2); ``sources`` ({"cg": ...,
    "inertia": ...}: "user", "mesh volume", "closed shells", "convex hull",
    "winding-number solid", "uniform box" or "empirical"); ``mass_source`` ("user" or
    "weight in lb (... lb)"); ``stiffness`` (a crashsim.vehicles.stiffness.Stiffness);
    ``quality`` (the
    mesh's :class:`crashsim.vehicles.meshio.MeshQuality`); ``generator_params`` (the
    :class:`crashsim.vehicles.generator.BodyParams` of a generated body, else None).

    Build one with :meth:`from_mesh`, :meth:`box` or :meth:`generate`.
    """

    def __init__(
        self,
        mesh: trimesh.Trimesh,
        mass: float,
        cg: ArrayLike,
        inertia: ArrayLike,
        name: str = "vehicle",
        sources: dict[str, str] | None = None,
        stiffness: Stiffness | dict[str, Any] | None = None,
    ) -> None:
        if not isinstance(mesh, trimesh.Trimesh):
            raise MeshError(f"mesh must be a trimesh.Trimesh, got {type(mesh).__name__}")
        check_name(name, "a vehicle")
        check_mesh(mesh, "the mesh")
        mass = _as_float(mass, "mass", "kg")
        cg_v = _point(cg, "cg")
        source = (sources or {}).get("inertia", USER)
        try:
            _check_mass_properties(mass, inertia)
        except ParameterError as e:
            if "impossible" in str(e):  # the engine's triangle inequality: name the axis
                plausibility.check_inertia(inertia, None if source == USER else source)
            raise
        self._name = name
        self._mass = mass
        self._mesh = mesh
        self._cg = _read_only(cg_v)
        self._inertia = _read_only(inertia)
        self._sources = dict(sources or {"cg": USER, "inertia": USER})
        self._stiffness = Stiffness.coerce(stiffness)
        self._mass_source = USER
        self._details: dict[str, str] = {}
        self._quality: MeshQuality | None = None
        self._shape: _core.Shape | None = None
        self._generator_params: BodyParams | None = None
        self._wheels: Wheels | None = None
        # Where it tows (a tow ball, a fifth wheel) and where it is towed (a trailer's coupler
        # or kingpin): crashsim.vehicles.coupling.
        self._hitch: Hitch | None = None
        self._coupler: Hitch | None = None

    # -- constructors --------------------------------------------------------------------

    @classmethod
    def from_mesh(
        cls,
        source: MeshSource,
        mass: float | None = None,
        name: str | None = None,
        cg: ArrayLike | str | None = None,
        inertia: ArrayLike | str | None = None,
        *,
        weight_lb: float | None = None,
        wheelbase: float | None = None,
        solid: str = "auto",
        units: str | float = "m",
        up: str = "z",
        forward: str = "x",
        ground: bool = False,
        center: bool = False,
        stiffness: Stiffness | dict[str, Any] | None = None,
        track: float | tuple[float, float] | None = None,
        wheel_radius: float | tuple[float, float] | None = None,
        cg_to_front_axle: float | None = None,
        tyre: Tyre | dict[str, Any] | None = None,
        wheels: Wheels | None = None,
    ) -> Vehicle:
        """A vehicle from a mesh file (any format trimesh reads; a scene is flattened with
        its node transforms) or a trimesh.Trimesh / trimesh.Scene.

        Geometry (see crashsim.vehicles.meshio.load_mesh): units = metres per file unit ("m", "cm",
        "mm", "in", "ft" or a number; default "m"); up, forward = the file axes pointing up
        and to the front (default "z", "x": the file is already in the model frame);
        ground = True puts the lowest point at z = 0, center = True centres the box at
        x = y = 0 (both default False: the mesh stays where the file has it).

        Mass: exactly one of ``mass`` (kg) and ``weight_lb`` (lb).
        name: defaults to the file's stem ("vehicle" for an in-memory mesh).
        cg: a model-frame point (m), or None / "mesh": the centroid of the uniform solid.
        inertia: (3, 3) about the CG in body axes (kg m^2); None / "mesh": the uniform
        solid's, scaled to the mass and moved to the CG by the parallel-axis theorem;
        "empirical": :func:`empirical_inertia` from ``wheelbase`` (m) and the mesh's extents.
        solid: what stands for the vehicle's solid when the mesh is not a closed volume (a
        closed, outward mesh is always its own solid): "auto" = "winding number" (default:
        the region the engine itself counts as inside, integrated on a grid; the study in
        docs/meshes.md found it right where the alternatives were not), "convex hull" (fills
        wheel gaps, the underbody and a pickup's bed) or "closed shells" (union of the closed
        shells; open shells ignored, overlaps counted twice).
        stiffness: face stiffness, see crashsim.vehicles.stiffness.Stiffness.coerce.

        Wheels (for a scene with a ground; see :meth:`with_wheels`): ``wheelbase``,
        ``track`` (one or (front, rear)), ``wheel_radius`` (tyre radius, one or (front,
        rear)) and ``cg_to_front_axle`` (m), all four, and optionally ``tyre``; or a ready
        :class:`crashsim.vehicles.wheels.Wheels` as ``wheels``. The CG's height above the
        ground is its model-frame z (the model frame's ground is z = 0: load with
        ground=True if the file's is not).
        """
        mass_kg, mass_source = _mass(mass, weight_lb)
        stiff = Stiffness.coerce(stiffness)
        wheel_keys = _wheel_keys(wheelbase, track, wheel_radius, cg_to_front_axle, tyre, wheels)
        if solid not in SOLIDS:
            raise ParameterError(f"solid = {solid!r} is unknown: use one of {', '.join(SOLIDS)}")
        cg_mode = _mode(cg, "cg", ("mesh",))
        inertia_mode = _mode(inertia, "inertia", ("mesh", "empirical"))
        if wheelbase is not None and inertia_mode != "empirical" and wheel_keys is None:
            raise ParameterError(
                'wheelbase is only used by inertia="empirical" and by wheels: drop it, ask for '
                "that rule, or give the wheels' track, wheel_radius and cg_to_front_axle too"
            )
        if inertia_mode == "empirical" and wheelbase is None:
            raise ParameterError('inertia="empirical" needs the wheelbase (m): give wheelbase=')
        what = describe(source)
        mesh = load_mesh(source, units=units, up=up, forward=forward, ground=ground, center=center)
        scale = unit_scale(units)
        units_name = units.strip().lower() if isinstance(units, str) else f"{scale:g} m per unit"
        if name is None:
            if isinstance(source, trimesh.Trimesh | trimesh.Scene):
                name = "vehicle"
            else:
                name = Path(source).stem
        sources: dict[str, str] = {}
        details: dict[str, str] = {}
        solid_props = None
        if cg_mode == "mesh" or inertia_mode == "mesh":
            solid_props, kind, detail = _solid(mesh, what, solid)
        if cg_mode == "mesh":
            assert solid_props is not None
            cg_v, sources["cg"], details["cg"] = solid_props[1], kind, detail
        else:
            cg_v, sources["cg"] = _point(cg, "cg"), USER
        inertia_v: ArrayLike
        if inertia_mode == "mesh":
            assert solid_props is not None
            volume, centroid, unit_inertia = solid_props
            scaled = unit_inertia * (mass_kg / volume)
            inertia_v = _parallel_axis(scaled, mass_kg, cg_v - centroid)
            sources["inertia"], details["inertia"] = kind, detail
        elif inertia_mode == "empirical":
            length, width, height = (float(e) for e in mesh.extents)
            wb = _wheelbase(wheelbase, length)
            inertia_v = empirical_inertia(mass_kg, wb, length, width, height)
            sources["inertia"] = EMPIRICAL
            details["inertia"] = (
                f"{EMPIRICAL}: Izz = m (0.5 WB)^2 with WB = {wb:.3f} m; Ixx, Iyy of the "
                f"uniform {length:.2f} x {width:.2f} x {height:.2f} m box"
            )
        else:
            inertia_v, sources["inertia"] = np.asarray(inertia, dtype=np.float64), USER
        with _rule_hint(inertia_mode, _EMPIRICAL_FIX):
            vehicle = cls(
                mesh, mass_kg, cg_v, inertia_v, name=name, sources=sources, stiffness=stiff
            )
        vehicle._mass_source, vehicle._details = mass_source, details
        if wheel_keys is not None:
            vehicle = vehicle.with_wheels(**wheel_keys)
        findings = plausibility.size_findings(
            mesh.extents, scale, units_name, axes_rotation(up, forward)
        )
        if solid_props is not None:
            volume, label = solid_props[0], f"the {kind}"
        else:
            volume, label = _volume_estimate(mesh)
        findings += plausibility.check_density(mass_kg, volume, label, findings)
        plausibility.warn(f"{what} ({name!r}, {_dims(mesh.extents)})", findings, stacklevel=3)
        return vehicle

    @classmethod
    def box(
        cls,
        length: float,
        width: float,
        height: float,
        mass: float | None = None,
        name: str | None = None,
        cg_height: float | None = None,
        ground_clearance: float = 0.0,
        inertia: ArrayLike | str | None = None,
        *,
        weight_lb: float | None = None,
        wheelbase: float | None = None,
        stiffness: Stiffness | dict[str, Any] | None = None,
        track: float | tuple[float, float] | None = None,
        wheel_radius: float | tuple[float, float] | None = None,
        cg_to_front_axle: float | None = None,
        tyre: Tyre | dict[str, Any] | None = None,
        wheels: Wheels | None = None,
    ) -> Vehicle:
        """A closed box (m) in the model frame: x in [-L/2, L/2], y in [-W/2, W/2],
        z in [ground_clearance, ground_clearance + height].

        Mass: exactly one of ``mass`` (kg) and ``weight_lb`` (lb). CG at the box centre, or
        at (0, 0, cg_height) (m above the ground).
        inertia: None / "mesh" (default): the uniform solid box's about its centre
        (m/12 (W^2 + H^2), ...), moved to the CG by the parallel-axis theorem when cg_height
        is given; "empirical": :func:`empirical_inertia` with ``wheelbase`` (m); or (3, 3).
        stiffness: face stiffness, see crashsim.vehicles.stiffness.Stiffness.coerce.
        Wheels: ``wheelbase``, ``track``, ``wheel_radius`` and ``cg_to_front_axle`` (m), and
        optionally ``tyre``, or ``wheels`` (see :meth:`from_mesh`, :meth:`with_wheels`); a
        box on wheels needs ground_clearance > 0 (its underside would rest on the road).
        """
        wheel_keys = _wheel_keys(wheelbase, track, wheel_radius, cg_to_front_axle, tyre, wheels)
        named = {"length": length, "width": width, "height": height}
        dims = np.array([_as_float(v, k, "m") for k, v in named.items()])
        if not np.all(np.isfinite(dims)) or np.any(dims <= 0.0):
            raise ParameterError(
                f"box dimensions (length, width, height) = {dims.tolist()} are invalid: "
                "each must be a finite, positive number of metres"
            )
        lo, hi = plausibility.SIZE_IMPOSSIBLE
        if not lo <= float(dims.max()) <= hi:  # also keeps m L^2 / 12 from overflowing
            raise ParameterError(
                f"box dimensions (length, width, height) = {dims.tolist()} m: no vehicle is "
                f"{'shorter than 1 mm' if dims.max() < lo else 'longer than 10 km'}; give "
                "metres"
            )
        clearance = _as_float(ground_clearance, "ground_clearance", "m")
        if not math.isfinite(clearance) or clearance < 0.0:
            raise ParameterError(
                f"ground_clearance = {clearance} is invalid: give a finite height >= 0 m"
            )
        mass_kg, mass_source = _mass(mass, weight_lb)
        stiff = Stiffness.coerce(stiffness)
        inertia_mode = _mode(inertia, "inertia", ("mesh", "empirical"))
        if wheelbase is not None and inertia_mode != "empirical" and wheel_keys is None:
            raise ParameterError(
                'wheelbase is only used by inertia="empirical" and by wheels: drop it, ask for '
                "that rule, or give the wheels' track, wheel_radius and cg_to_front_axle too"
            )
        if wheel_keys is not None and clearance <= 0.0:
            raise ParameterError(
                "a box on wheels needs ground_clearance > 0 m: with 0 its underside rests on "
                "the road and the body, not the wheels, would carry it (give e.g. "
                "ground_clearance=0.15)"
            )
        centre = np.array([0.0, 0.0, clearance + dims[2] / 2.0])
        mesh = trimesh.creation.box(extents=dims)
        mesh.apply_translation(centre)
        sources = {"cg": UNIFORM_BOX, "inertia": UNIFORM_BOX}
        details: dict[str, str] = {}
        cg = centre
        if cg_height is not None:
            cg = _point([0.0, 0.0, _as_float(cg_height, "cg_height", "m")], "cg")
            sources["cg"] = USER
        inertia_v: ArrayLike
        if inertia_mode == "mesh":
            inertia_v = _parallel_axis(_box_inertia(mass_kg, *dims), mass_kg, cg - centre)
        elif inertia_mode == "empirical":
            if wheelbase is None:
                raise ParameterError('inertia="empirical" needs the wheelbase (m): give wheelbase=')
            wb = _wheelbase(wheelbase, float(dims[0]))
            inertia_v = empirical_inertia(mass_kg, wb, *(float(d) for d in dims))
            sources["inertia"] = EMPIRICAL
            details["inertia"] = (
                f"{EMPIRICAL}: Izz = m (0.5 WB)^2 with WB = {wb:.3f} m; Ixx, Iyy of the uniform box"
            )
        else:
            inertia_v, sources["inertia"] = np.asarray(inertia, dtype=np.float64), USER
        with _rule_hint(inertia_mode, _EMPIRICAL_FIX):
            vehicle = cls(
                mesh, mass_kg, cg, inertia_v, name=name or "box", sources=sources, stiffness=stiff
            )
        vehicle._mass_source, vehicle._details = mass_source, details
        if wheel_keys is not None:
            vehicle = vehicle.with_wheels(**wheel_keys)
        return vehicle

    @classmethod
    def generate(
        cls,
        preset: str = "sedan",
        *,
        name: str | None = None,
        mass: float | None = None,
        weight_lb: float | None = None,
        length: float | None = None,
        width: float | None = None,
        height: float | None = None,
        wheelbase: float | None = None,
        cg: ArrayLike | str | None = None,
        inertia: ArrayLike | str | None = None,
        stiffness: Stiffness | dict[str, Any] | None = None,
        resolution: float = 1.0,
        track: float | tuple[float, float] | None = None,
        tyre: Tyre | dict[str, Any] | None = None,
        **shape: float,
    ) -> Vehicle:
        """A vehicle of a built-in class on a generated body: ``cs.Vehicle.generate("sedan")``
        needs nothing else; every number not given comes from the class table
        (:func:`crashsim.vehicles.vehicle_data.vehicle_class`), scaled to the dimensions given.

        preset: one of crashsim.vehicles.generator.PRESETS ("sedan", "suv", "pickup", "van",
        "bus"; an
        alias of the table such as "mid_car" is accepted). name: defaults to the preset.

        Body (crashsim.vehicles.generator.body_params and generate_body; model frame, m: x forward,
        y left, z up, ground z = 0, box centred in x and y): length, width, height (roof above
        the ground) and wheelbase (m) default to the class's; the shape parameters of
        crashsim.vehicles.generator.SHAPE_PARAMETERS (front_overhang, bumper_radius, ...) pass
        through.
        resolution: the mesh's (1 = a few thousand triangles).

        Mass: exactly one of ``mass`` (kg) and ``weight_lb`` (lb), else the class's.

        cg: a model-frame point (m); None / "class" (default): from the class, keeping its
        ratios: x = front axle (length/2 - front_overhang) - cg_to_front_axle x WB/WB_class,
        y = 0, z = cg_height x H/H_class; "mesh": the centroid of the body as a uniform solid
        (too high for a real vehicle).

        inertia: (3, 3) about the CG in body axes (kg m^2); None / "class" (default): Ixx,
        Iyy and Ixy of the body as a uniform solid, scaled to the mass and moved to the CG
        (parallel axes), and Izz = yaw_inertia_class x (m / m_class) x (WB / WB_class)^2 (the
        class figures follow a yaw radius of gyration proportional to the wheelbase); the yaw
        products Ixz and Iyz are zero (the class has no figure for them, and so the tensor is
        positive definite for any CG). "mesh": the whole uniform solid's tensor at the CG;
        "empirical": :func:`empirical_inertia` with the body's wheelbase and extents.

        stiffness: the class's CRASH3 A and B (front, rear, side -> left and right) unless
        given; a given value replaces all of them (see crashsim.vehicles.stiffness.Stiffness.coerce;
        to change one face, start from ``vehicle_class(preset).stiffness.to_dict()``).

        Wheels (used when the scene has a ground): the body's axles (front_overhang,
        wheelbase) and tyre radius (the ``wheel_radius`` shape parameter: the arches are made
        for it), the class's track (:attr:`VehicleClass.track_front`, ``track_rear``) scaled
        to the width unless ``track`` (m, one or (front, rear)) is given, the front axle
        steering, springs at the engine's natural frequency and damping ratio, and ``tyre``
        (default: the reconstruction tyre). :meth:`with_wheels` changes them.

        ``sources`` names the origin of every number ("cg", "inertia", "mass", "dimensions",
        "body", "stiffness"; the wheels' is ``wheels.source``) and ``summary()`` prints
        them; ``generator_params`` keeps the
        BodyParams. Raises ParameterError for an unknown preset (listing the presets), a bad
        number, or dimensions that give no valid body (the generator's message).

        ``"tractor"`` (or "tractor_6x4") is a tractor with its fifth wheel from the combination
        class (:func:`crashsim.tractor`, ``preset="tractor_6x4"``; ``mass`` and ``length`` pass
        through); ``"rigid_truck"`` a two-axle rigid truck laden to its class's 18 t with a
        rear hitch (:func:`crashsim.rigid_truck`); trailers come from
        :meth:`crashsim.Trailer.generate`.
        """
        if preset in COMBINATION_PRESETS:
            others = {
                "weight_lb": weight_lb,
                "width": width,
                "height": height,
                "wheelbase": wheelbase,
                "cg": cg,
                "inertia": inertia,
                "stiffness": stiffness,
                "track": track,
                "tyre": tyre,
                **shape,
            }
            given = [k for k, v in others.items() if v is not None] + (
                ["resolution"] if resolution != 1.0 else []
            )
            if given:
                raise ParameterError(
                    f"Vehicle.generate({preset!r}) takes mass, length and name; give "
                    f"{', '.join(given)} to crashsim.{COMBINATION_PRESETS[preset].__name__}"
                    f"({preset!r}, ...) instead"
                )
            return COMBINATION_PRESETS[preset](mass=mass, length=length, name=name)
        vc, key = _preset_class(preset)
        table = f"class table ({key})"
        if mass is None and weight_lb is None:
            mass_kg, mass_source = vc.mass.value, table
        else:
            mass_kg, mass_source = _mass(mass, weight_lb)
        if stiffness is None:
            stiff, stiffness_source = vc.stiffness, table
        else:
            stiff, stiffness_source = Stiffness.coerce(stiffness), USER
        cg_mode = "class" if cg is None else _mode(cg, "cg", ("class", "mesh"))
        inertia_mode = "class" if inertia is None else _mode(inertia, "inertia", _INERTIA_WORDS)
        asked = {"length": length, "width": width, "height": height, "wheelbase": wheelbase}
        dims = {k: getattr(vc, k).value if v is None else v for k, v in asked.items()}
        for k, v in {**dims, **shape}.items():  # the generator's geometry fails beyond it
            if isinstance(v, int | float) and not isinstance(v, bool):
                if math.isfinite(v) and abs(v) > plausibility.SIZE_IMPOSSIBLE[1]:
                    raise ParameterError(
                        f"{k} = {v:g} m: no vehicle is longer than 10 km; give metres"
                    )
        params = body_params(key, **dims, **shape)
        mesh = generate_body(params, resolution)
        # Ratios to the class (exactly 1.0 for the class's own numbers).
        wb_ratio = params.wheelbase / vc.wheelbase.value
        h_ratio = params.height / vc.height.value
        m_ratio = mass_kg / vc.mass.value
        sources: dict[str, str] = {}
        details: dict[str, str] = {}
        solid = solid_properties(mesh)  # closed and outward by construction: volume > 0
        volume, centroid, unit_inertia = solid
        if cg_mode == "class":
            front_axle = params.length / 2.0 - params.front_overhang
            to_axle = vc.cg_to_front_axle.value * wb_ratio
            cg_v = np.array([front_axle - to_axle, 0.0, vc.cg_height.value * h_ratio])
            scaled = _scaled_to(
                ("wheelbase", wb_ratio, params.wheelbase, "m"),
                ("height", h_ratio, params.height, "m"),
            )
            sources["cg"] = table + scaled
            details["cg"] = (
                f"{table}{scaled}: {to_axle:.3f} m behind the front axle, "
                f"{cg_v[2]:.3f} m above the ground"
            )
        elif cg_mode == "mesh":
            cg_v, sources["cg"] = centroid, GENERATED_SOLID
            details["cg"] = f"{GENERATED_SOLID} ({volume:.4g} m^3)"
        else:
            cg_v, sources["cg"] = _point(cg, "cg"), USER
        inertia_v: ArrayLike
        if inertia_mode in ("class", "mesh"):
            inertia_v = _parallel_axis(unit_inertia * (mass_kg / volume), mass_kg, cg_v - centroid)
            if inertia_mode == "class":
                izz = vc.yaw_inertia.value * m_ratio * wb_ratio**2
                inertia_v[2, 2] = izz
                inertia_v[0, 2] = inertia_v[2, 0] = inertia_v[1, 2] = inertia_v[2, 1] = 0.0
                scaled = _scaled_to(
                    ("mass", m_ratio, mass_kg, "kg"),
                    ("wheelbase", wb_ratio, params.wheelbase, "m"),
                )
                sources["inertia"] = f"Izz {table}{scaled}; Ixx, Iyy: {GENERATED_SOLID}"
                details["inertia"] = (
                    f"Izz {table}{scaled}; Ixx, Iyy, Ixy: {GENERATED_SOLID} "
                    f"({volume:.4g} m^3) at the CG; Ixz = Iyz = 0"
                )
            else:
                sources["inertia"] = GENERATED_SOLID
                details["inertia"] = f"{GENERATED_SOLID} ({volume:.4g} m^3) at the CG"
        elif inertia_mode == "empirical":
            ext_l, ext_w, ext_h = (float(e) for e in mesh.extents)
            inertia_v = empirical_inertia(mass_kg, params.wheelbase, ext_l, ext_w, ext_h)
            sources["inertia"] = EMPIRICAL
            details["inertia"] = (
                f"{EMPIRICAL}: Izz = m (0.5 WB)^2 with WB = {params.wheelbase:.3f} m; Ixx, Iyy "
                f"of the uniform {ext_l:.2f} x {ext_w:.2f} x {ext_h:.2f} m box"
            )
        else:
            inertia_v, sources["inertia"] = np.asarray(inertia, dtype=np.float64), USER
        sources["mass"] = mass_source
        sources["dimensions"] = _given_or(asked, table)
        defaults = f"generator defaults ({key})"
        sources["body"] = f"{USER} ({', '.join(sorted(shape))}); {defaults}" if shape else defaults
        sources["stiffness"] = stiffness_source
        fix = (
            "a wheelbase in proportion to the length (the class's yaw moment scales with the "
            "wheelbase squared, the body's pitch moment with its length), inertia='mesh', or "
            "the inertia"
        )
        with _rule_hint(inertia_mode, fix):
            vehicle = cls(
                mesh,
                mass_kg,
                cg_v,
                inertia_v,
                name=key if name is None else name,
                sources=sources,
                stiffness=stiff,
            )
        vehicle._mass_source, vehicle._details = mass_source, details
        vehicle._generator_params = params
        w_ratio = params.width / vc.width.value
        if track is None:
            track_v: float | tuple[float, float] = (
                vc.track_front.value * w_ratio,
                vc.track_rear.value * w_ratio,
            )
            wheel_source = f"track: {table}" + _scaled_to(("width", w_ratio, params.width, "m"))
        else:
            track_v, wheel_source = track, "track: user"
        wheel_source += "; axles and tyre radius: the generated body"
        wheel_source += f"; anti-roll bars: the roll gradient of {table}"
        front_axle = params.length / 2.0 - params.front_overhang
        vehicle = vehicle.with_wheels(
            wheelbase=params.wheelbase,
            track=track_v,
            radius=params.wheel_radius,
            cg_to_front_axle=front_axle - float(vehicle.cg[0]),
            cg_height=float(vehicle.cg[2]),
            tyre=tyre,
            source=wheel_source,
            roll_gradient=vc.roll_gradient.value,
        )
        findings = plausibility.size_findings(mesh.extents)
        findings += plausibility.check_density(
            mass_kg, volume, "the generated body's solid", findings
        )
        plausibility.warn(
            f"the generated {key} ({vehicle.name!r}, {_dims(mesh.extents)})", findings, stacklevel=3
        )
        return vehicle

    # -- properties ----------------------------------------------------------------------

    @property
    def name(self) -> str:
        return self._name

    @property
    def mass(self) -> float:
        """kg."""
        return self._mass

    @property
    def mass_source(self) -> str:
        """Where the mass came from: "user" (kg) or "weight in lb (... lb)"."""
        return self._mass_source

    @property
    def mesh(self) -> trimesh.Trimesh:
        """The mesh in the model frame (m). Do not modify it: build a new Vehicle instead."""
        return self._mesh

    @property
    def cg(self) -> Array:
        """Centre of gravity, model frame (m)."""
        return self._cg

    @property
    def inertia(self) -> Array:
        """(3, 3) inertia tensor about the CG, body axes (kg m^2)."""
        return self._inertia

    @property
    def sources(self) -> dict[str, str]:
        """Where "cg" and "inertia" came from: "user", "mesh volume", "closed shells",
        "convex hull", "winding-number solid", "uniform box" or "empirical"; for a generated
        vehicle (:meth:`generate`) "class table (<preset>)" (", scaled to ..." when scaled),
        "uniform solid of the generated body" or a mix for the inertia, and also "mass",
        "dimensions", "body" (the shape parameters) and "stiffness"."""
        return dict(self._sources)

    @property
    def generator_params(self) -> BodyParams | None:
        """The crashsim.vehicles.generator.BodyParams the body was made from (:meth:`generate`), or
        None for a vehicle from a mesh or a box."""
        return self._generator_params

    @property
    def stiffness(self) -> Stiffness:
        """Face stiffness (CRASH3 A, B per face; a face without data is None)."""
        return self._stiffness

    @property
    def quality(self) -> MeshQuality:
        """The mesh's quality report (computed on first use, then kept)."""
        if self._quality is None:
            self._quality = mesh_quality(self._mesh)
        return self._quality

    @property
    def body_vertices(self) -> Array:
        """Mesh vertices in the body frame (m, origin at the CG): vertices - cg."""
        return np.asarray(self._mesh.vertices, dtype=np.float64) - self._cg

    @property
    def extents(self) -> Array:
        """Length, width, height of the mesh's axis-aligned bounding box (m)."""
        return np.asarray(self._mesh.extents, dtype=np.float64)

    @property
    def shape(self) -> _core.Shape:
        """The engine's shape: body-frame mesh and its BVH (built once, then cached)."""
        if self._shape is None:
            faces = np.asarray(self._mesh.faces, dtype=np.int64)
            self._shape = _core.Shape(self.body_vertices, faces)
        return self._shape

    @property
    def wheels(self) -> Wheels | None:
        """The wheels and tyre (a :class:`crashsim.vehicles.wheels.Wheels`), used when the scene
        has a ground; None for a vehicle without wheels (it then slides on its body there)."""
        return self._wheels

    def with_wheels(
        self,
        wheels: Wheels | None = None,
        *,
        wheelbase: float | None = None,
        track: float | tuple[float, float] | None = None,
        radius: float | tuple[float, float] | None = None,
        cg_to_front_axle: float | None = None,
        cg_height: float | None = None,
        tyre: Tyre | dict[str, Any] | None = None,
        source: str | None = None,
        **springs: Any,
    ) -> Vehicle:
        """The same vehicle on wheels (a new Vehicle; this one is unchanged).

        Either a ready :class:`crashsim.vehicles.wheels.Wheels`, or its numbers: ``wheelbase``,
        ``track`` (one or (front, rear)), ``radius`` (tyre radius, one or (front, rear)) and
        ``cg_to_front_axle`` (m), with ``cg_height`` (m above the ground; default the CG's
        model-frame z, the model frame's ground being z = 0), ``tyre`` and the springs
        (``natural_frequency``, ``damping_ratio``, ``spring_rates``, ``damping``, ``steer``:
        see Wheels). The wheels' centre line is the mesh's (its bounding box's middle in y).
        With ``wheels`` given, ``tyre`` (if given) replaces its tyre.

        The engine checks them on this body: ParameterError naming the vehicle and the wheel
        for a wheel outside the body's outline, a CG not over the wheels, a negative rate, ...
        """
        if wheels is None:
            given = {
                "wheelbase": wheelbase,
                "track": track,
                "radius": radius,
                "cg_to_front_axle": cg_to_front_axle,
            }
            missing = [k for k, v in given.items() if v is None]
            if missing:
                raise ParameterError(
                    f"vehicle {self._name!r}: wheels need {', '.join(missing)} (m): give "
                    "wheelbase, track, radius and cg_to_front_axle, or a crashsim.Wheels"
                )
            if cg_height is None:
                cg_height = float(self._cg[2])
                if cg_height <= 0.0:
                    raise ParameterError(
                        f"vehicle {self._name!r}: its CG is {cg_height:.3f} m above the model "
                        "frame's ground (z = 0): the mesh is not standing on z = 0; load it "
                        "with ground=True, or give cg_height (m above the ground)"
                    )
            lo, hi = self._mesh.bounds
            centerline = float(lo[1] + hi[1]) / 2.0 - float(self._cg[1])
            try:
                wheels = Wheels(
                    wheelbase,  # type: ignore[arg-type]
                    track,  # type: ignore[arg-type]
                    cg_to_front_axle,  # type: ignore[arg-type]
                    cg_height,
                    radius,  # type: ignore[arg-type]
                    centerline_y=centerline,
                    tyre=tyre,
                    **springs,
                )
            except ParameterError as e:
                raise ParameterError(f"vehicle {self._name!r}: {e}") from e
        else:
            if not isinstance(wheels, Wheels):
                raise ParameterError(
                    f"wheels must be a crashsim.Wheels, got {type(wheels).__name__}"
                )
            extra = {"wheelbase": wheelbase, "track": track, "radius": radius}
            extra.update(cg_to_front_axle=cg_to_front_axle, cg_height=cg_height, **springs)
            clash = [k for k, v in extra.items() if v is not None]
            if clash:
                raise ParameterError(
                    f"give a Wheels or its numbers, not both ({', '.join(clash)} given too)"
                )
            if tyre is not None:
                import copy

                wheels = copy.copy(wheels)
                wheels.tyre = Tyre.coerce(tyre)
        wheels.check_on(self.shape, self._mass, f"vehicle {self._name!r}")
        if source is not None:
            import copy

            wheels = copy.copy(wheels)
            wheels.source = source
        other = self._copy(self._name)
        other._wheels = wheels
        return other

    @property
    def hitch(self) -> Hitch | None:
        """Where this vehicle tows a trailer (a tow ball or a fifth wheel), if it does."""
        return self._hitch

    @property
    def coupler(self) -> Hitch | None:
        """Where this vehicle (a trailer) rests on its tractor: its coupler or kingpin."""
        return self._coupler

    def with_hitch(self, at: ArrayLike, kind: str = "ball") -> Vehicle:
        """The same vehicle with a hitch (a new Vehicle): ``at`` the model-frame point (m)
        of the tow ball's centre, the fifth wheel's kingpin lock or a dolly's turntable,
        ``kind`` "ball", "fifth_wheel" or "turntable" (crashsim.vehicles.coupling). It must
        lie within 1 m of the body."""
        hitch = Hitch.at(kind, _point(at, "hitch") - self._cg, towing=True)
        self._check_reach(hitch, "hitch")
        other = self._copy(self._name)
        other._hitch = hitch
        return other

    def _check_reach(self, hitch: Hitch, what: str) -> None:
        """A ParameterError when ``hitch`` lies more than 1 m outside the body's box (the
        engine's joint rule, crashsim-core world/joints.rs ANCHOR_REACH)."""
        lo, hi = self.body_vertices.min(axis=0), self.body_vertices.max(axis=0)
        gap = np.maximum(0.0, np.maximum(lo - hitch.point, hitch.point - hi))
        outside = float(np.linalg.norm(gap))
        if outside > 1.0:
            raise ParameterError(
                f"vehicle {self._name!r}: its {what} lies {outside:.2f} m outside the body's "
                "box (at most 1 m): give it in the model frame (m), where the mesh is"
            )

    def _copy(self, name: str) -> Vehicle:
        other = Vehicle(
            self._mesh,
            self._mass,
            self._cg,
            self._inertia,
            name,
            self._sources,
            stiffness=self._stiffness,
        )
        other._mass_source, other._details = self._mass_source, dict(self._details)
        other._quality = self._quality
        other._generator_params = self._generator_params
        other._shape = self.shape
        other._wheels = self._wheels
        other._hitch, other._coupler = self._hitch, self._coupler
        return other

    def renamed(self, name: str) -> Vehicle:
        """The same vehicle under another name (shares the mesh, the engine's shape, the
        stiffness, the wheels and the quality report), e.g. to put two identical cars in one
        scene."""
        return self._copy(name)

    def summary(self) -> str:
        """A short human-readable description with the origin of every number."""
        length, width, height = self.extents
        moments = np.diag(self._inertia)
        q = self.quality
        closed = "watertight" if q.watertight else f"open ({q.open_edges} open edges)"
        lines = [
            f"{self._name}: {self._mass:.1f} kg [{self._mass_source}], "
            f"{length:.2f} x {width:.2f} x {height:.2f} m, {len(self._mesh.faces)} triangles",
            f"  mesh: {q.shells} shells ({q.closed_shells} closed), {closed}, "
            f"{q.nonmanifold_edges} non-manifold edges",
            f"  CG (model frame) {np.round(self._cg, 3).tolist()} m  "
            f"[{self._details.get('cg', self._sources['cg'])}]",
            f"  Ixx, Iyy, Izz {np.round(moments, 1).tolist()} kg m^2  "
            f"[{self._details.get('inertia', self._sources['inertia'])}]",
        ]
        off = self._inertia - np.diag(moments)
        if np.max(np.abs(off)) > 1e-9 * np.max(moments):  # products beyond round-off
            products = [self._inertia[0, 1], self._inertia[0, 2], self._inertia[1, 2]]
            lines.append(f"  Ixy, Ixz, Iyz {np.round(products, 1).tolist()} kg m^2")
        faces = []
        for f in FACES:
            s = self._stiffness.face(f)
            if s is not None:
                faces.append(f"{f} A = {s.A:.4g} N/m, B = {s.B:.4g} N/m^2")
        p = self._generator_params
        if p is not None:
            lines.append(
                f"  body: crashsim.vehicles.generator {p.preset}, "
                f"L {p.length:.3f} x W {p.width:.3f} x "
                f"H {p.height:.3f} m (roof above the ground), wheelbase {p.wheelbase:.3f} m, "
                f"front overhang {p.front_overhang:.3f} m, wheel radius {p.wheel_radius:.3f} m"
                f"  [dimensions: {self._sources.get('dimensions', USER)}; shape: "
                f"{self._sources.get('body', USER)}]"
            )
        w = self._wheels
        if w is not None:
            if w.wheelbase is not None and w.track is not None:
                layout = (
                    f"wheelbase {w.wheelbase:.3f} m, track {w.track[0]:.3f} / {w.track[1]:.3f} "
                    f"m, CG {w.cg_to_front_axle:.3f} m behind the front axle and "
                    f"{w.cg_height:.3f} m above the ground, tyre radius "
                    f"{float(w.radii[0]):.3f} / {float(w.radii[-1]):.3f} m"
                )
            else:
                layout = f"{len(w)} wheels ({', '.join(w.names)})"
            lines.append(f"  wheels: {layout}, tyre {w.tyre.model}  [{w.source}]")
        stiffness_line = "  stiffness: " + ("; ".join(faces) if faces else "no data")
        if "stiffness" in self._sources:
            stiffness_line += f"  [{self._sources['stiffness']}]"
        lines.append(stiffness_line)
        return "\n".join(lines)

    def __repr__(self) -> str:
        return (
            f"Vehicle(name={self._name!r}, mass={self._mass:g} kg, "
            f"triangles={len(self._mesh.faces)}, cg={np.round(self._cg, 4).tolist()})"
        )


_INERTIA_WORDS = ("class", "mesh", "empirical")


def _wheel_keys(
    wheelbase: Any, track: Any, wheel_radius: Any, cg_to_front_axle: Any, tyre: Any, wheels: Any
) -> dict[str, Any] | None:
    """with_wheels keywords from a constructor's wheel keywords; None when no wheels are
    asked for (none of track, wheel_radius, cg_to_front_axle, tyre, wheels given)."""
    if wheels is not None:
        if any(v is not None for v in (track, wheel_radius, cg_to_front_axle)):
            raise ParameterError(
                "give wheels or track, wheel_radius and cg_to_front_axle, not both"
            )
        return {"wheels": wheels, "tyre": tyre}
    asked = {"track": track, "wheel_radius": wheel_radius, "cg_to_front_axle": cg_to_front_axle}
    if all(v is None for v in asked.values()) and tyre is None:
        return None
    missing = [k for k, v in {"wheelbase": wheelbase, **asked}.items() if v is None]
    if missing:
        raise ParameterError(
            f"wheels need wheelbase, track, wheel_radius and cg_to_front_axle (m): "
            f"{', '.join(missing)} missing"
        )
    return {
        "wheelbase": wheelbase,
        "track": track,
        "radius": wheel_radius,
        "cg_to_front_axle": cg_to_front_axle,
        "tyre": tyre,
    }


def _preset_class(preset: Any) -> tuple[VehicleClass, str]:
    """The class table entry and the generator preset of a preset name (or table alias)."""
    key = preset.strip().lower() if isinstance(preset, str) else None
    key = ALIASES.get(key, key) if key is not None else None
    if key not in PRESETS:
        raise ParameterError(
            f"unknown preset {preset!r}: use one of {', '.join(PRESETS)} (the vehicle classes "
            "that have a generated body)"
        )
    return vehicle_class(key), key


def _scaled_to(*parts: tuple[str, float, float, str]) -> str:
    """The text ', scaled to mass 1600.0 kg and wheelbase 2.900 m' for the parts whose ratio
    to the class is not 1 (each part: name, ratio, value, unit); "" when none is."""
    changed = [
        f"{name} {value:.1f} {unit}" if unit == "kg" else f"{name} {value:.3f} {unit}"
        for name, ratio, value, unit in parts
        if ratio != 1.0
    ]
    return f", scaled to {' and '.join(changed)}" if changed else ""


def _given_or(values: dict[str, Any], default: str) -> str:
    """The text 'user (a, b); <default> for the rest' for the names given (not None), "user"
    when all are, else default."""
    given = [k for k, v in values.items() if v is not None]
    if not given:
        return default
    if len(given) == len(values):
        return USER
    return f"{USER} ({', '.join(given)}); {default} for the rest"


def _mode(value: Any, name: str, words: tuple[str, ...]) -> str:
    """The rule asked for: "user" for numbers, else the word (None means "mesh")."""
    if value is None:
        return "mesh"
    if isinstance(value, str):
        if value not in words:
            choices = ", ".join(repr(w) for w in words)
            raise ParameterError(f"{name} = {value!r} is unknown: give numbers or one of {choices}")
        return value
    return "user"
