"""Vehicles: a mesh, a mass, a centre of gravity and an inertia tensor.

Frames: the *model frame* is the mesh file's own (m; x forward, y left, z up; ground at
z = 0 for the usual vehicle mesh). The *body frame* is the model frame shifted so the CG is
the origin (ISO 8855). Inertia is about the CG in body axes (kg m^2).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from os import PathLike
from pathlib import Path

import numpy as np
import trimesh
from numpy.typing import ArrayLike, NDArray

from crashsim import _core
from crashsim.errors import MeshError, ParameterError


def _finite_vector(value: ArrayLike, name: str, size: int = 3) -> NDArray[np.float64]:
    try:
        v = np.asarray(value, dtype=float).reshape(-1)
    except (TypeError, ValueError) as e:
        raise ParameterError(f"{name} must be {size} numbers, got {value!r}") from e
    if v.size != size:
        raise ParameterError(f"{name} must have {size} components, got {v.size}")
    if not np.all(np.isfinite(v)):
        raise ParameterError(f"{name} = {v.tolist()} is invalid: every component must be finite")
    return v


def _check_mass(mass: float) -> float:
    try:
        m = float(mass)
    except (TypeError, ValueError) as e:
        raise ParameterError(f"mass must be a number in kg, got {mass!r}") from e
    if not math.isfinite(m) or m <= 0.0:
        raise ParameterError(f"mass = {mass} is invalid: a mass must be a positive number of kg")
    return m


def _check_inertia(inertia: ArrayLike) -> NDArray[np.float64]:
    i = np.asarray(inertia, dtype=float)
    if i.shape != (3, 3):
        raise ParameterError(f"inertia must be a 3x3 tensor in kg m^2, got shape {i.shape}")
    if not np.all(np.isfinite(i)):
        raise ParameterError("the inertia tensor has a non-finite entry: give finite kg m^2")
    if not np.allclose(i, i.T, rtol=1e-9, atol=0.0):
        raise ParameterError("the inertia tensor is not symmetric: I[i][j] must equal I[j][i]")
    moments = np.linalg.eigvalsh(i)
    if moments.min() <= 0.0:
        raise ParameterError(
            f"the inertia tensor is not positive definite (principal moments {moments}): "
            "every principal moment must be positive"
        )
    return i


def _load_mesh(source: str | PathLike[str] | trimesh.Trimesh) -> trimesh.Trimesh:
    if isinstance(source, trimesh.Trimesh):
        mesh = source.copy()
    else:
        path = Path(source)
        if not path.is_file():
            raise MeshError(f"no mesh file at {path}: check the path")
        try:
            # force="mesh" flattens a scene (GLB/glTF) with its node transforms applied.
            mesh = trimesh.load(path, force="mesh", process=True)
        except Exception as e:  # trimesh raises many kinds; say which file failed
            raise MeshError(f"could not read the mesh {path}: {e}") from e
    if not isinstance(mesh, trimesh.Trimesh) or len(mesh.faces) == 0:
        raise MeshError("the mesh has no triangles: a vehicle needs a surface")
    if not np.all(np.isfinite(mesh.vertices)):
        raise MeshError("the mesh has non-finite (NaN or inf) vertices: repair or remove them")
    return mesh


def _box_inertia(mass: float, length: float, width: float, height: float) -> NDArray[np.float64]:
    return np.diag(
        [
            mass / 12.0 * (width**2 + height**2),
            mass / 12.0 * (length**2 + height**2),
            mass / 12.0 * (length**2 + width**2),
        ]
    )


@dataclass(eq=False)
class Vehicle:
    """A rigid vehicle: model-frame mesh, mass (kg), CG (model frame, m) and inertia about
    the CG in body axes (kg m^2). `sources` says where the CG and inertia came from."""

    name: str
    mass: float
    mesh: trimesh.Trimesh
    cg: NDArray[np.float64]
    inertia: NDArray[np.float64]
    sources: dict[str, str] = field(default_factory=dict)
    _shape: _core.Shape | None = field(default=None, init=False, repr=False)

    def __post_init__(self) -> None:
        self.mass = _check_mass(self.mass)
        self.cg = _finite_vector(self.cg, "cg")
        self.inertia = _check_inertia(self.inertia)
        if not self.name:
            raise ParameterError("a vehicle needs a non-empty name")

    @classmethod
    def from_mesh(
        cls,
        source: str | PathLike[str] | trimesh.Trimesh,
        mass: float,
        name: str | None = None,
        cg: ArrayLike | None = None,
        inertia: ArrayLike | None = None,
    ) -> Vehicle:
        """A vehicle from a mesh file (any format trimesh reads) or a Trimesh, in metres with
        x forward, y left, z up. Without `cg` or `inertia`, they come from the mesh as a
        uniform solid scaled to `mass` (its convex hull when the mesh is not a closed volume,
        as most real vehicle meshes are not)."""
        mass = _check_mass(mass)
        mesh = _load_mesh(source)
        if name is None:
            name = Path(source).stem if not isinstance(source, trimesh.Trimesh) else "vehicle"
        solid, solid_name = (mesh, "mesh volume") if mesh.is_volume else (None, "convex hull")
        if solid is None:
            try:
                solid = mesh.convex_hull
            except Exception as e:
                raise MeshError(f"the mesh has no volume to take mass properties from: {e}") from e
            if solid.volume <= 0.0:
                raise MeshError("the mesh has no volume: give cg and inertia explicitly")
        sources = {}
        solid_cg = np.asarray(solid.center_mass, dtype=float)
        if cg is None:
            cg_v = solid_cg
            sources["cg"] = solid_name
        else:
            cg_v = _finite_vector(cg, "cg")
            sources["cg"] = "user"
        if inertia is None:
            # trimesh: inertia about center_mass for density 1; scale to the mass, then move
            # to the chosen CG (parallel axes).
            i_cm = np.asarray(solid.moment_inertia, dtype=float) * (mass / solid.mass)
            d = cg_v - solid_cg
            i_v = i_cm + mass * (np.dot(d, d) * np.eye(3) - np.outer(d, d))
            sources["inertia"] = f"{solid_name}, uniform density scaled to the mass"
        else:
            i_v = _check_inertia(inertia)
            sources["inertia"] = "user"
        return cls(name=name, mass=mass, mesh=mesh, cg=cg_v, inertia=i_v, sources=sources)

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
    ) -> Vehicle:
        """A box vehicle (m): x in [-L/2, L/2], y in [-W/2, W/2], z from the ground clearance
        up by the height. CG at the box centre unless `cg_height` (m above ground) is given;
        inertia of the uniform box about that CG."""
        dims = _finite_vector([length, width, height], "box dimensions")
        if np.any(dims <= 0.0):
            raise ParameterError(f"box dimensions {dims.tolist()} must all be positive (m)")
        if not math.isfinite(ground_clearance) or ground_clearance < 0.0:
            raise ParameterError(f"ground_clearance = {ground_clearance} must be >= 0 m")
        mass = _check_mass(mass)
        mesh = trimesh.creation.box(extents=dims)
        mesh.apply_translation([0.0, 0.0, ground_clearance + dims[2] / 2.0])
        centre_z = ground_clearance + dims[2] / 2.0
        inertia = _box_inertia(mass, *dims)
        sources = {"cg": "box centre", "inertia": "uniform box"}
        cg = np.array([0.0, 0.0, centre_z])
        if cg_height is not None:
            cg = _finite_vector([0.0, 0.0, cg_height], "cg_height")
            dz = cg_height - centre_z
            inertia = inertia + mass * dz * dz * np.diag([1.0, 1.0, 0.0])
            sources = {"cg": "user", "inertia": "uniform box, moved to the CG"}
        return cls(
            name=name or "box",
            mass=mass,
            mesh=mesh,
            cg=cg,
            inertia=inertia,
            sources=sources,
        )

    @property
    def body_vertices(self) -> NDArray[np.float64]:
        """Mesh vertices in the body frame (m, origin at the CG)."""
        return np.asarray(self.mesh.vertices, dtype=float) - self.cg

    @property
    def shape(self) -> _core.Shape:
        """The engine's shape (built once, cached)."""
        if self._shape is None:
            self._shape = _core.Shape(self.body_vertices, np.asarray(self.mesh.faces))
        return self._shape

    @property
    def extents(self) -> NDArray[np.float64]:
        """Length, width, height of the mesh's bounding box (m)."""
        return np.asarray(self.mesh.extents, dtype=float)

    def summary(self) -> str:
        """A short human-readable description with the origin of every number."""
        i = np.diag(self.inertia)
        length, width, height = self.extents
        return (
            f"{self.name}: {self.mass:.1f} kg, {length:.2f} x {width:.2f} x {height:.2f} m, "
            f"{len(self.mesh.faces)} triangles\n"
            f"  CG (model frame) {np.round(self.cg, 3).tolist()} m  [{self.sources.get('cg')}]\n"
            f"  Ixx, Iyy, Izz {np.round(i, 1).tolist()} kg m^2  [{self.sources.get('inertia')}]"
        )
