"""Mass properties: where a vehicle's numbers came from (the source names), the uniform solid
box, the parallel-axis theorem, the empirical inertia rule, and the solid that stands for a
mesh (the mesh itself when it is a closed volume, else its convex hull, the union of its closed
shells or the region the engine counts as inside: generalized winding number > 1/2, integrated
on a grid). Units: m, kg, kg m^2; a solid's properties are for unit density. See docs/meshes.md.
"""

from __future__ import annotations

import numpy as np
import trimesh
from numpy.typing import ArrayLike, NDArray

from crashsim import _core
from crashsim.errors import MeshError, ParameterError
from crashsim.small_linalg import dot, matmul, norm
from crashsim.vehicles.meshio import closed_shells, shell_labels

__all__ = ["empirical_inertia", "solid_properties"]

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


def _parallel_axis(inertia_cm: Array, mass: float, d: Array) -> Array:
    """Inertia about a point displaced by d (m) from the centre of mass (kg m^2).
    ParameterError when it overflows (a CG absurdly far from the body)."""
    with np.errstate(over="ignore", invalid="ignore"):
        out = inertia_cm + mass * (float(dot(d, d)) * np.eye(3) - np.outer(d, d))
    if not np.all(np.isfinite(inertia_cm)):
        raise ParameterError(
            f"the inertia of a {mass:g} kg body is not finite: give the mass in kg"
        )
    if not np.all(np.isfinite(out)):
        raise ParameterError(
            f"the CG is {float(norm(d)):.3g} m from the centre of the body's solid: "
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
    inertia = (np.eye(3) * float(np.sum(d * d)) - matmul(d.T, d)) * dv
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
