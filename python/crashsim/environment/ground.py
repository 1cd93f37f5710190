"""The ground a scene's vehicles run on: a plane or a terrain mesh, tyre-road and body-ground
friction, and friction zones.

World frame: right-handed, z up, SI (m). A plane is z = ``height``; a terrain is a triangle
mesh in world coordinates (any format trimesh reads, brought to metres and z up by
:func:`crashsim.vehicles.meshio.load_mesh`) whose upper surface, seen from above, is the
ground. Friction zones are polygons seen from above (corners (x, y) in order, m) with their
own tyre-road friction; they may share edges but not overlap (a point of the road has one
friction). Frictions are numbers or surface names of the built-in table
(:mod:`crashsim.environment.surfaces`, docs/ground.md). Gravity (the engine's 9.80665 m/s^2)
acts along -z in a scene with a ground.

The engine checks every number (frictions in (0, 2], simple polygons, zones that do not
overlap, a terrain spread in x and y); its messages are passed on with the zones' names.
"""

from __future__ import annotations

import copy
from collections.abc import Iterable, Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np
import trimesh
from numpy.typing import ArrayLike, NDArray

from crashsim import _core
from crashsim.environment.surfaces import friction as as_friction
from crashsim.errors import MeshError, ParameterError, Place, at, naming, renamed
from crashsim.names import check_name
from crashsim.vehicles.meshio import MeshSource, describe, load_mesh

__all__ = ["FrictionZone", "Ground"]

Array = NDArray[np.float64]


@dataclass(frozen=True, eq=False, init=False)
class FrictionZone:
    """A ground polygon with its own tyre-road friction.

    ``polygon``: (k, 2) corners (x, y) in order around it (m, world; k >= 3, not crossing
    itself). ``friction``: a coefficient, or a surface name of the built-in table
    ("wet_asphalt", "gravel", "grass", ...; docs/ground.md). ``name`` labels it in messages
    (default: the surface name, else "zone <k>"). Checked when made, by the engine's rules of
    a zone (``_core.check_friction_zone``): a bad value raises ParameterError placed in the
    part "friction zone" (or "friction zone 'name'"); a ground checks that its zones do not
    overlap."""

    polygon: Array
    friction: float
    name: str | None = None
    surface: str | None = None

    def __init__(self, polygon: ArrayLike, friction: float | str, name: str | None = None):
        name = None if name is None else check_name(name, "a zone")
        part = "friction zone" if name is None else f"friction zone {name!r}"
        _fill_zone(self, polygon, friction, name, ("part", None, part))

    def label(self, index: int) -> str:
        """How messages name the zone."""
        if self.name:
            return f"zone {self.name!r}"
        if self.surface:
            return f"zone {index} ({self.surface})"
        return f"zone {index}"

    def contains(self, x: float, y: float) -> bool:
        """True when (x, y) (m) lies inside the polygon or on its edge (the engine's test)."""
        return _core.point_in_polygon(float(x), float(y), self.polygon)


def _fill_zone(zone: FrictionZone, polygon: ArrayLike, friction: float | str,
               name: str | None, place: Place) -> None:
    """Sets a new zone's fields, checked by the engine's rules of a zone; an error is put in
    ``place``."""
    try:
        try:
            poly = np.array(polygon, dtype=np.float64)
        except (TypeError, ValueError) as e:
            raise ParameterError(f"its polygon must be (k, 2) corners (x, y) in m: {e}") from e
        if poly.ndim != 2 or poly.shape[1] != 2:
            raise ParameterError(
                f"its polygon must have shape (k, 2) (corners x, y in m), got {poly.shape}"
            )
        mu = as_friction(friction, "friction")
        _core.check_friction_zone(poly, mu)
    except ParameterError as e:
        raise at(e, place) from e
    poly.setflags(write=False)
    object.__setattr__(zone, "polygon", poly)
    object.__setattr__(zone, "friction", mu)
    object.__setattr__(zone, "surface", friction if isinstance(friction, str) else None)
    object.__setattr__(zone, "name", name)


def _zone(value: Any, index: int) -> FrictionZone:
    """A ground's zone ``index`` from a FrictionZone or a (polygon, friction) pair, whose
    errors are placed at the zone's index as the engine's are (the ground's place is added by
    the ground)."""
    if isinstance(value, FrictionZone):
        return value
    if isinstance(value, tuple | list) and len(value) == 2:
        zone = object.__new__(FrictionZone)
        _fill_zone(zone, value[0], value[1], None, ("zone", index, None))
        return zone
    raise ParameterError(
        f"friction zone {index} must be a crashsim.FrictionZone or (polygon, friction), got "
        f"{value!r}"
    )


_GROUND: Place = ("part", None, "ground")  # the place of the ground's errors


class Ground:
    """The ground of a scene.

    ``height``: the plane z = height (m; default 0), or instead ``terrain``: a mesh file
    (any format trimesh reads) or a trimesh.Trimesh / Scene in world coordinates, brought to
    metres and z up with ``units``, ``up`` and ``forward`` as
    :func:`crashsim.vehicles.meshio.load_mesh` does (its upper surface seen from above is the
    ground; a wheel that leaves it stops the run with a SimulationError).
    ``friction``: tyre-road friction outside every zone, a number or a surface name (None:
    the engine's default, dry asphalt 0.8). ``body_friction``: a vehicle body sliding on the
    ground (None: the engine's 0.45). ``zones``: FrictionZone values or (polygon, friction)
    pairs.
    """

    def __init__(
        self,
        height: float = 0.0,
        *,
        terrain: MeshSource | None = None,
        units: str | float = "m",
        up: str = "z",
        forward: str = "x",
        friction: float | str | None = None,
        body_friction: float | str | None = None,
        zones: Iterable[FrictionZone | tuple[ArrayLike, float | str]] = (),
    ) -> None:
        if isinstance(height, bool | str):
            raise ParameterError(f"ground height must be a number (m), got {height!r}")
        try:
            self.height = float(height)
        except (TypeError, ValueError) as e:
            raise ParameterError(f"ground height must be a number (m), got {height!r}") from e
        self.terrain: trimesh.Trimesh | None = None
        self._shape: _core.Shape | None = None
        self.terrain_source: str | None = None
        if terrain is not None:
            if height != 0.0:
                raise ParameterError(
                    "give a ground height or a terrain, not both (a terrain's heights are its "
                    "own: move the mesh instead)"
                )
            self.terrain = load_mesh(terrain, units=units, up=up, forward=forward)
            self.terrain_source = describe(terrain)
            self._shape = _core.Shape(
                np.asarray(self.terrain.vertices, dtype=np.float64),
                np.asarray(self.terrain.faces, dtype=np.int64),
            )
        self.surface = friction if isinstance(friction, str) else None
        self.friction = None if friction is None else as_friction(friction, "ground friction")
        self.body_friction = (
            None if body_friction is None else as_friction(body_friction, "body_friction")
        )
        try:
            self.zones: tuple[FrictionZone, ...] = tuple(
                _zone(z, k) for k, z in enumerate(zones)
            )
        except ParameterError as e:
            raise at(e, _GROUND) from e
        self.core = self._checked(self._core_kwargs())

    def _checked(self, kwargs: dict[str, Any]) -> _core.Ground:
        """The engine's ground of these keywords, checked once by the core."""
        try:
            return _core.Ground(**kwargs)
        except MeshError as e:
            raise MeshError(f"the terrain ({self.terrain_source}): {e}") from e
        except ParameterError as e:
            raise self._named(e) from e

    def with_friction(
        self, friction: float | None = None, body_friction: float | None = None
    ) -> Ground:
        """A copy with another tyre-road and/or body-ground friction (a study's variant),
        checked by the engine; the terrain and zones are shared."""
        new = copy.copy(self)
        if friction is not None:
            new.friction, new.surface = float(friction), None
        if body_friction is not None:
            new.body_friction = float(body_friction)
        new.core = self._checked(new._core_kwargs())
        return new

    def __getstate__(self) -> dict[str, Any]:  # the engine's value is rebuilt, not pickled
        return {k: v for k, v in self.__dict__.items() if k != "core"}

    def __setstate__(self, state: dict[str, Any]) -> None:
        self.__dict__.update(state)
        self.core = self._checked(self._core_kwargs())

    def _named(self, error: ParameterError) -> ParameterError:
        """The engine's error with its zone places named, one place further out: the ground
        (``loc`` starts with ("part", None, "ground"); the text with "ground: ")."""

        def label(k: int) -> str:  # "zone 'wet'" or "zone 2"
            return self.zones[k].label(k)[5:]

        name = naming(
            zone=lambda k: "friction " + self.zones[k].label(k),
            zones=lambda ab: f"friction zones {label(ab[0])} and {label(ab[1])}",
        )
        return at(renamed(error, name), _GROUND)

    def _core_kwargs(self) -> dict[str, Any]:
        """_core.Ground keywords (frictions left None take the engine's defaults there)."""
        out: dict[str, Any] = {
            "tyre_friction": self.friction,
            "body_friction": self.body_friction,
            "zones": [(z.polygon, z.friction) for z in self.zones],
        }
        if self._shape is not None:
            out["terrain"] = self._shape
        else:
            out["height"] = self.height
        return out

    @property
    def tyre_friction(self) -> float:
        """Tyre-road friction outside every zone (the engine's default when not given)."""
        return self.core.tyre_friction

    def height_at(self, x: float, y: float) -> float | None:
        """The ground's height at (x, y) (m, world): the plane's, or the terrain's highest
        surface there; None off the terrain."""
        if self._shape is None or self.terrain is None:
            return self.height
        top = float(self.terrain.bounds[1][2]) + 1.0
        hits = self._shape.ray_hits((float(x), float(y), top), (0.0, 0.0, -1.0))
        return None if len(hits) == 0 else top - float(hits[0])

    def friction_at(self, x: float, y: float) -> float:
        """Tyre-road friction at (x, y): the first zone holding the point, else the
        ground's (the engine's lookup)."""
        return self.core.friction_at(float(x), float(y))

    def holes(self, points: Sequence[ArrayLike]) -> list[int]:
        """Indices of the world points (x, y[, z]) with no ground under or over them."""
        return [k for k, p in enumerate(points) if self.height_at(p[0], p[1]) is None]

    def __repr__(self) -> str:
        where = (
            f"terrain={self.terrain_source}"
            if self.terrain is not None
            else f"height={self.height:g}"
        )
        mu = "default" if self.friction is None else f"{self.friction:g}"
        return f"Ground({where}, friction={mu}, zones={len(self.zones)})"
