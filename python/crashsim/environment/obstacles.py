"""Fixed obstacles: walls, poles, barriers, kerbs, trees, or any mesh.

An obstacle is a closed triangle mesh in its own frame (m; z up, x and y horizontal) that the
engine keeps fixed in the world with infinite mass and inertia. It takes part in first-overlap
detection, the depth-of-penetration timer and the exchange exactly like a vehicle (1/m = 0,
I^-1 = 0 in the collision matrix). Its face stiffness (CRASH3 A, B per face front +x, rear
-x, left +y, right -y of its frame) is used by ``depth_of_penetration="auto"`` and the
stiffness centroid like a vehicle's; an obstacle without any stiffness is rigid (an infinite
spring: dt_p from the vehicle's face alone, the stiffness centroid on the obstacle's surface,
the vehicle takes all the crush and energy in the report).

Primitives (built with trimesh, closed and outward): each stands on z = 0 of its frame and is
centred on its frame's z axis; :meth:`crashsim.Scene.add_obstacle` places that base point in
the world (on the ground at (x, y) when no z is given) and turns the frame by ``heading``.

- :meth:`Obstacle.wall`: a box, ``thickness`` along x, ``length`` along y: at heading 0 its
  faces +x and -x face a vehicle driving along world x.
- :meth:`Obstacle.barrier`: a concrete safety barrier of trapezoid cross-section (New Jersey
  shape simplified), along y.
- :meth:`Obstacle.kerb`: a low box along y.
- :meth:`Obstacle.pole`, :meth:`Obstacle.tree`: vertical cylinders (a tree is its trunk).
"""

from __future__ import annotations

import math
from pathlib import Path
from typing import Any

import numpy as np
import trimesh
from numpy.typing import NDArray

from crashsim import _core
from crashsim.errors import MeshError, ParameterError
from crashsim.names import check_name
from crashsim.vehicles.meshio import MeshSource, check_mesh, load_mesh
from crashsim.vehicles.stiffness import FACES, FaceStiffness, Stiffness

__all__ = ["Obstacle"]

Array = NDArray[np.float64]

# Facets of the cylinders of poles and trees (a 32-gon is within 0.5 % of the circle's radius).
CYLINDER_SECTIONS = 32


def _length(value: Any, name: str) -> float:
    if isinstance(value, bool | str):
        raise ParameterError(f"{name} must be a number of metres, got {value!r}")
    try:
        x = float(value)
    except (TypeError, ValueError) as e:
        raise ParameterError(f"{name} must be a number of metres, got {value!r}") from e
    if not math.isfinite(x) or x <= 0.0:
        raise ParameterError(f"{name} = {x} m is invalid: it must be a finite length > 0 m")
    if x > 1e4:
        raise ParameterError(f"{name} = {x:g} m: no obstacle is longer than 10 km; give metres")
    return x


def _stiffness(value: Any) -> Stiffness:
    """A Stiffness from None, a Stiffness, a face mapping, or one (A, B) pair for every
    face."""
    if value is None or isinstance(value, Stiffness | dict):
        return Stiffness.coerce(value)
    face = FaceStiffness.coerce(value, "obstacle's")
    return Stiffness(front=face, rear=face, left=face, right=face)


class Obstacle:
    """A fixed obstacle: ``name``, ``mesh`` (trimesh.Trimesh in its own frame, m), ``kind``
    ("wall", "pole", "barrier", "kerb", "tree" or "mesh"), ``stiffness`` (CRASH3 A, B per
    face; a single (A, B) pair sets every face) and ``shape`` (the engine's). Build one with
    the class methods."""

    def __init__(
        self,
        mesh: trimesh.Trimesh,
        name: str = "obstacle",
        stiffness: Any = None,
        kind: str = "mesh",
    ) -> None:
        if not isinstance(mesh, trimesh.Trimesh):
            raise MeshError(f"an obstacle's mesh must be a trimesh.Trimesh, got {type(mesh)}")
        check_name(name, "an obstacle")
        check_mesh(mesh, f"obstacle {name!r}")
        self._mesh = mesh
        self._name = name
        self._kind = kind
        self._stiffness = _stiffness(stiffness)
        self._shape = _core.Shape(
            np.asarray(mesh.vertices, dtype=np.float64), np.asarray(mesh.faces, dtype=np.int64)
        )

    # -- primitives ------------------------------------------------------------------------

    @classmethod
    def wall(
        cls,
        length: float,
        thickness: float = 0.3,
        height: float = 2.0,
        *,
        name: str = "wall",
        stiffness: Any = None,
    ) -> Obstacle:
        """A wall: a box ``thickness`` along x, ``length`` along y, ``height`` up (m)."""
        dims = [_length(thickness, "thickness"), _length(length, "length")]
        dims.append(_length(height, "height"))
        mesh = trimesh.creation.box(extents=dims)
        mesh.apply_translation((0.0, 0.0, dims[2] / 2.0))
        return cls(mesh, name, stiffness, "wall")

    @classmethod
    def kerb(
        cls,
        length: float,
        height: float = 0.15,
        width: float = 0.3,
        *,
        name: str = "kerb",
        stiffness: Any = None,
    ) -> Obstacle:
        """A kerb: a low box ``width`` along x, ``length`` along y, ``height`` up (m)."""
        return cls(cls.wall(length, width, height)._mesh, name, stiffness, "kerb")

    @classmethod
    def barrier(
        cls,
        length: float,
        height: float = 0.81,
        base_width: float = 0.61,
        top_width: float = 0.15,
        *,
        name: str = "barrier",
        stiffness: Any = None,
    ) -> Obstacle:
        """A concrete safety barrier along y: a trapezoid cross-section ``base_width`` wide at
        the ground and ``top_width`` at ``height`` (m; the defaults are the usual New Jersey
        barrier's 32 in, 24 in and 6 in, its curved face simplified to a straight slope)."""
        length = _length(length, "length")
        h = _length(height, "height")
        b = _length(base_width, "base_width")
        t = _length(top_width, "top_width")
        if t > b:
            raise ParameterError(
                f"top_width = {t} m is wider than base_width = {b} m: a barrier narrows upwards"
            )
        profile = [(-b / 2, 0.0), (b / 2, 0.0), (t / 2, h), (-t / 2, h)]  # (x, z)
        v = [(x, y, z) for y in (-length / 2, length / 2) for x, z in profile]
        # Faces outward: bottom, top, the two slopes and the two ends.
        f = [
            (0, 4, 5), (0, 5, 1),  # bottom (z = 0), normal -z
            (3, 2, 6), (3, 6, 7),  # top, normal +z
            (1, 5, 6), (1, 6, 2),  # +x slope
            (0, 3, 7), (0, 7, 4),  # -x slope
            (0, 1, 2), (0, 2, 3),  # y = -L/2, normal -y
            (4, 7, 6), (4, 6, 5),  # y = +L/2, normal +y
        ]  # fmt: skip
        mesh = trimesh.Trimesh(np.array(v, dtype=np.float64), np.array(f), process=False)
        if mesh.volume < 0.0:  # pragma: no cover - the winding above is outward
            mesh.invert()
        return cls(mesh, name, stiffness, "barrier")

    @classmethod
    def pole(
        cls,
        diameter: float,
        height: float = 6.0,
        *,
        name: str = "pole",
        stiffness: Any = None,
    ) -> Obstacle:
        """A pole: a vertical cylinder of ``diameter`` and ``height`` (m)."""
        d = _length(diameter, "diameter")
        h = _length(height, "height")
        mesh = trimesh.creation.cylinder(radius=d / 2.0, height=h, sections=CYLINDER_SECTIONS)
        mesh.apply_translation((0.0, 0.0, h / 2.0))
        return cls(mesh, name, stiffness, "pole")

    @classmethod
    def tree(
        cls,
        diameter: float,
        height: float = 5.0,
        *,
        name: str = "tree",
        stiffness: Any = None,
    ) -> Obstacle:
        """A tree: its trunk, a vertical cylinder of ``diameter`` (at bumper height) and
        ``height`` (m; the crown is above any vehicle and is left out)."""
        out = cls.pole(diameter, height, name=name, stiffness=stiffness)
        out._kind = "tree"
        return out

    @classmethod
    def from_mesh(
        cls,
        source: MeshSource,
        *,
        units: str | float = "m",
        up: str = "z",
        forward: str = "x",
        ground: bool = False,
        center: bool = False,
        name: str | None = None,
        stiffness: Any = None,
    ) -> Obstacle:
        """An obstacle from a mesh file (any format trimesh reads) or a trimesh object,
        brought to metres and z up like a vehicle's (:func:`load_mesh`: ``units``, ``up``,
        ``forward``, ``ground``, ``center``). It should be closed (the engine's inside test
        is sound on open meshes, but a closed one is what a solid obstacle is)."""
        mesh = load_mesh(source, units=units, up=up, forward=forward, ground=ground, center=center)
        if name is None:
            if isinstance(source, trimesh.Trimesh | trimesh.Scene):
                name = "obstacle"
            else:
                name = Path(source).stem
        return cls(mesh, name, stiffness, "mesh")

    # -- properties -------------------------------------------------------------------------

    @property
    def name(self) -> str:
        return self._name

    @property
    def kind(self) -> str:
        """ "wall", "pole", "barrier", "kerb", "tree" or "mesh"."""
        return self._kind

    @property
    def mesh(self) -> trimesh.Trimesh:
        """The mesh in the obstacle's frame (m). Treat it as read-only."""
        return self._mesh

    @property
    def shape(self) -> _core.Shape:
        """The engine's shape (the mesh in the obstacle's frame)."""
        return self._shape

    @property
    def stiffness(self) -> Stiffness:
        """Face stiffness (CRASH3 A, B per face of the obstacle's frame; None without data)."""
        return self._stiffness

    @property
    def extents(self) -> Array:
        """Extents of the mesh's bounding box along x, y, z (m)."""
        return np.asarray(self._mesh.extents, dtype=np.float64)

    def renamed(self, name: str) -> Obstacle:
        """The same obstacle under another name (e.g. a row of identical poles)."""
        other = Obstacle.__new__(Obstacle)
        other.__dict__.update(self.__dict__)
        other._name = check_name(name, "an obstacle")
        return other

    def with_stiffness(self, stiffness: Any) -> Obstacle:
        """The same obstacle with other face stiffness (one (A, B) pair sets every face)."""
        other = self.renamed(self._name)
        other._stiffness = _stiffness(stiffness)
        return other

    def stiffness_faces(self) -> dict[str, tuple[float, float] | None]:
        """SceneSpec.set_stiffness keywords."""
        return {f: None if (s := self._stiffness.face(f)) is None else (s.A, s.B) for f in FACES}

    def __repr__(self) -> str:
        e = self.extents
        return (
            f"Obstacle(name={self._name!r}, kind={self._kind!r}, "
            f"extents={e[0]:.3g} x {e[1]:.3g} x {e[2]:.3g} m)"
        )
