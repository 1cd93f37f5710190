"""Vehicles: a triangle mesh, a mass, a centre of gravity and an inertia tensor.

Frames: the *model frame* is the mesh file's own (m; x forward, y left, z up; ground at
z = 0 for the usual vehicle mesh). The *body frame* is the model frame shifted so the CG is
the origin (ISO 8855): body vertices = model vertices - cg. The inertia tensor is about the CG
in body axes (kg m^2).

Mass and inertia are validated by the engine itself (`_check_mass_properties`), so the
accepted ranges and their messages live in one place (crates/crashsim-core).
"""

from __future__ import annotations

import functools
import math
from os import PathLike
from pathlib import Path
from typing import Any

import numpy as np
import trimesh
from numpy.typing import ArrayLike, NDArray

from crashsim import _core
from crashsim.errors import MeshError, ParameterError

__all__ = ["Vehicle"]

Array = NDArray[np.float64]
MeshSource = str | PathLike[str] | trimesh.Trimesh | trimesh.Scene

# Where a vehicle's CG and inertia came from (values of Vehicle.sources).
USER = "user"
MESH_VOLUME = "mesh volume"
CONVEX_HULL = "convex hull"
UNIFORM_BOX = "uniform box"

_ZERO3 = (0.0, 0.0, 0.0)
_IDENTITY = (1.0, 0.0, 0.0, 0.0)  # quaternion (w, x, y, z)


@functools.cache
def _probe_shape() -> _core.Shape:
    """A one-triangle shape for asking the engine to validate numbers (never simulated)."""
    return _core.Shape(np.array([[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]]), [[0, 1, 2]])


def _as_float(value: Any, name: str, unit: str) -> float:
    """A Python float, or a ParameterError saying what was expected."""
    try:
        return float(value)
    except (TypeError, ValueError) as e:
        raise ParameterError(f"{name} must be a number ({unit}), got {value!r}") from e


def _check_mass_properties(mass: float, inertia: ArrayLike) -> None:
    """Raises ParameterError unless mass (kg) is finite and positive and inertia (kg m^2) is
    a finite, symmetric, positive definite 3x3 tensor: the engine's own checks."""
    _core.World().add_body(_probe_shape(), mass, inertia, _ZERO3, _IDENTITY, _ZERO3, _ZERO3)


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


def _flatten(loaded: Any, what: str) -> trimesh.Trimesh:
    """One Trimesh from what trimesh returned: a Scene is flattened with its node
    transforms applied; anything else without triangles (a point cloud, a path) is refused."""
    if isinstance(loaded, trimesh.Scene):
        if hasattr(loaded, "to_mesh"):  # trimesh >= 4.6
            loaded = loaded.to_mesh()
        else:
            loaded = loaded.dump(concatenate=True)
    if not isinstance(loaded, trimesh.Trimesh):
        raise MeshError(
            f"{what} holds a {type(loaded).__name__}, not a triangle mesh: "
            "give a surface mesh (PLY, STL, OBJ, GLB, ...)"
        )
    return loaded


def _load_mesh(source: MeshSource) -> tuple[trimesh.Trimesh, str]:
    """The mesh (model frame, m) and a description of where it came from."""
    if isinstance(source, trimesh.Trimesh | trimesh.Scene):
        what = f"the given {type(source).__name__}"
        mesh = _flatten(source, what)
        mesh = mesh.copy()  # the vehicle owns its mesh; later edits of the input do not leak
    else:
        path = Path(source)
        what = f"the mesh file {str(path)!r}"
        if not path.is_file():
            raise MeshError(f"no mesh file at {str(path)!r}: check the path")
        loaded: Any
        try:
            # process=False: check the vertices as written before trimesh repairs anything.
            if hasattr(trimesh, "load_scene"):  # trimesh >= 4.6: typed loaders
                loaded = trimesh.load_scene(path, process=False)
            else:
                loaded = trimesh.load(path, force="mesh", process=False)
        except Exception as e:  # trimesh raises many kinds; name the file that failed
            raise MeshError(
                f"trimesh could not read {what} ({type(e).__name__}: {e}): "
                "give a mesh in a format trimesh loads (PLY, STL, OBJ, GLB, OFF, ...)"
            ) from e
        mesh = _flatten(loaded, what)
    _check_mesh(mesh, what)
    if not isinstance(source, trimesh.Trimesh):
        mesh.merge_vertices()  # what trimesh's default processing does: join shared corners
    return mesh, what


def _check_mesh(mesh: trimesh.Trimesh, what: str) -> None:
    """MeshError unless the mesh has triangles and finite vertices (the engine checks the
    indices when it builds its shape)."""
    if len(mesh.faces) == 0:
        raise MeshError(f"{what} has no triangles: a vehicle needs a surface mesh")
    vertices = np.asarray(mesh.vertices, dtype=np.float64)
    bad = ~np.all(np.isfinite(vertices), axis=1)
    if np.any(bad):
        i = int(np.flatnonzero(bad)[0])
        raise MeshError(
            f"{what} has {int(bad.sum())} non-finite (NaN or inf) vertices, the first is "
            f"vertex {i} = {vertices[i].tolist()}: repair or remove them"
        )


def _parallel_axis(inertia_cm: Array, mass: float, d: Array) -> Array:
    """Inertia about a point displaced by d (m) from the centre of mass (kg m^2)."""
    return inertia_cm + mass * (float(d @ d) * np.eye(3) - np.outer(d, d))


def _box_inertia(mass: float, length: float, width: float, height: float) -> Array:
    """Uniform solid box about its centre, axes along its edges (kg m^2)."""
    return (mass / 12.0) * np.diag(
        [width**2 + height**2, length**2 + height**2, length**2 + width**2]
    )


class Vehicle:
    """A rigid vehicle.

    Attributes (read-only): ``name``; ``mass`` (kg); ``mesh`` (trimesh.Trimesh, model frame,
    m; treat it as read-only: the engine's copy is built from it once); ``cg`` (model-frame
    point, m); ``inertia`` ((3, 3) about the CG in body axes, kg m^2); ``sources`` ({"cg": ...,
    "inertia": ...}, each "user", "mesh volume", "convex hull" or "uniform box").

    Build one with :meth:`from_mesh` or :meth:`box`.
    """

    def __init__(
        self,
        mesh: trimesh.Trimesh,
        mass: float,
        cg: ArrayLike,
        inertia: ArrayLike,
        name: str = "vehicle",
        sources: dict[str, str] | None = None,
    ) -> None:
        if not isinstance(mesh, trimesh.Trimesh):
            raise MeshError(f"mesh must be a trimesh.Trimesh, got {type(mesh).__name__}")
        if not isinstance(name, str) or not name:
            raise ParameterError(f"a vehicle needs a non-empty name (a str), got {name!r}")
        _check_mesh(mesh, "the mesh")
        mass = _as_float(mass, "mass", "kg")
        cg_v = _point(cg, "cg")
        _check_mass_properties(mass, inertia)
        self._name = name
        self._mass = mass
        self._mesh = mesh
        self._cg = _read_only(cg_v)
        self._inertia = _read_only(inertia)
        self._sources = dict(sources or {"cg": USER, "inertia": USER})
        self._shape: _core.Shape | None = None

    # -- constructors --------------------------------------------------------------------

    @classmethod
    def from_mesh(
        cls,
        source: MeshSource,
        mass: float,
        name: str | None = None,
        cg: ArrayLike | None = None,
        inertia: ArrayLike | None = None,
    ) -> Vehicle:
        """A vehicle from a mesh file (any format trimesh loads; a scene is flattened with
        its transforms) or a trimesh.Trimesh / trimesh.Scene, in metres, x forward, y left,
        z up (the model frame, kept as given).

        mass: kg. name: defaults to the file's stem ("vehicle" for an in-memory mesh).
        cg: model-frame point (m); default the centre of mass of the mesh as a uniform solid
        when it is a closed volume, else of its convex hull (real vehicle meshes are rarely
        closed). inertia: (3, 3) about the CG in body axes (kg m^2); default that solid's,
        scaled to ``mass`` and, when ``cg`` is given, moved to it by the parallel-axis theorem.
        """
        mass = _as_float(mass, "mass", "kg")
        _check_mass_properties(mass, np.eye(3))  # a bad mass is reported before mesh work
        mesh, what = _load_mesh(source)
        if name is None:
            if isinstance(source, trimesh.Trimesh | trimesh.Scene):
                name = "vehicle"
            else:
                name = Path(source).stem
        sources: dict[str, str] = {}
        if cg is not None and inertia is not None:
            cg_v, inertia_v = _point(cg, "cg"), inertia
            sources = {"cg": USER, "inertia": USER}
        else:
            solid, kind = _solid(mesh, what)
            # trimesh: moment_inertia is about center_mass, for density 1 (mass = volume).
            solid_cg = np.asarray(solid.center_mass, dtype=np.float64)
            solid_inertia = np.asarray(solid.moment_inertia, dtype=np.float64) * (
                mass / float(solid.mass)
            )
            if cg is None:
                cg_v, sources["cg"] = solid_cg, kind
            else:
                cg_v, sources["cg"] = _point(cg, "cg"), USER
            if inertia is None:
                inertia_v = _parallel_axis(solid_inertia, mass, cg_v - solid_cg)
                sources["inertia"] = kind
            else:
                inertia_v, sources["inertia"] = inertia, USER
        return cls(mesh, mass, cg_v, inertia_v, name=name, sources=sources)

    @classmethod
    def box(
        cls,
        length: float,
        width: float,
        height: float,
        mass: float,
        name: str | None = None,
        cg_height: float | None = None,
        ground_clearance: float = 0.0,
        inertia: ArrayLike | None = None,
    ) -> Vehicle:
        """A closed box (m) in the model frame: x in [-L/2, L/2], y in [-W/2, W/2],
        z in [ground_clearance, ground_clearance + height].

        mass: kg. CG at the box centre, or at (0, 0, cg_height) (m above the ground).
        inertia: default the uniform solid box's about its centre (m/12 (W^2 + H^2), ...),
        moved to the CG by the parallel-axis theorem when cg_height is given.
        """
        named = {"length": length, "width": width, "height": height}
        dims = np.array([_as_float(v, k, "m") for k, v in named.items()])
        if not np.all(np.isfinite(dims)) or np.any(dims <= 0.0):
            raise ParameterError(
                f"box dimensions (length, width, height) = {dims.tolist()} are invalid: "
                "each must be a finite, positive number of metres"
            )
        clearance = _as_float(ground_clearance, "ground_clearance", "m")
        if not math.isfinite(clearance) or clearance < 0.0:
            raise ParameterError(
                f"ground_clearance = {clearance} is invalid: give a finite height >= 0 m"
            )
        mass = _as_float(mass, "mass", "kg")
        _check_mass_properties(mass, np.eye(3))
        centre = np.array([0.0, 0.0, clearance + dims[2] / 2.0])
        mesh = trimesh.creation.box(extents=dims)
        mesh.apply_translation(centre)
        sources = {"cg": UNIFORM_BOX, "inertia": UNIFORM_BOX}
        cg = centre
        if cg_height is not None:
            cg = _point([0.0, 0.0, _as_float(cg_height, "cg_height", "m")], "cg")
            sources["cg"] = USER
        if inertia is None:
            inertia_v: ArrayLike = _parallel_axis(_box_inertia(mass, *dims), mass, cg - centre)
        else:
            inertia_v, sources["inertia"] = inertia, USER
        return cls(mesh, mass, cg, inertia_v, name=name or "box", sources=sources)

    # -- properties ----------------------------------------------------------------------

    @property
    def name(self) -> str:
        return self._name

    @property
    def mass(self) -> float:
        """kg."""
        return self._mass

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
        """Where "cg" and "inertia" came from: "user", "mesh volume", "convex hull" or
        "uniform box"."""
        return dict(self._sources)

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

    def renamed(self, name: str) -> Vehicle:
        """The same vehicle under another name (shares the mesh and the engine's shape), e.g.
        to put two identical cars in one scene."""
        other = Vehicle(self._mesh, self._mass, self._cg, self._inertia, name, self._sources)
        other._shape = self.shape
        return other

    def summary(self) -> str:
        """A short human-readable description with the origin of every number."""
        length, width, height = self.extents
        moments = np.diag(self._inertia)
        return (
            f"{self._name}: {self._mass:.1f} kg, {length:.2f} x {width:.2f} x {height:.2f} m, "
            f"{len(self._mesh.faces)} triangles\n"
            f"  CG (model frame) {np.round(self._cg, 3).tolist()} m  [{self._sources['cg']}]\n"
            f"  Ixx, Iyy, Izz {np.round(moments, 1).tolist()} kg m^2  "
            f"[{self._sources['inertia']}]"
        )

    def __repr__(self) -> str:
        return (
            f"Vehicle(name={self._name!r}, mass={self._mass:g} kg, "
            f"triangles={len(self._mesh.faces)}, cg={np.round(self._cg, 4).tolist()})"
        )


def _solid(mesh: trimesh.Trimesh, what: str) -> tuple[trimesh.Trimesh, str]:
    """The solid whose uniform-density mass properties stand for the vehicle's, and its
    kind: the mesh itself when it is a closed, consistently wound volume, else its convex
    hull."""
    if mesh.is_volume:
        return mesh, MESH_VOLUME
    try:
        hull = mesh.convex_hull
    except Exception as e:  # qhull fails on flat or degenerate point sets
        raise MeshError(
            f"{what} is not a closed volume and its convex hull failed ({e}): "
            "give cg and inertia explicitly"
        ) from e
    if not hull.is_volume or hull.volume <= 0.0:
        raise MeshError(
            f"{what} encloses no volume (flat or degenerate): give cg and inertia explicitly"
        )
    return hull, CONVEX_HULL
