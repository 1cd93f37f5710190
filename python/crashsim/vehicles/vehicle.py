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

The constructors (:meth:`Vehicle.from_mesh`, :meth:`Vehicle.box`, :meth:`Vehicle.generate`)
are in :mod:`crashsim.vehicles.builders`, which Vehicle inherits; mass properties and the names
of where numbers came from in :mod:`crashsim.vehicles.mass_properties`; the checks of given
numbers in :mod:`crashsim.vehicles.checks`.

Mass and inertia are validated by the engine itself (`_check_mass_properties`), so the
accepted ranges and their messages live in one place (crates/crashsim-core).
"""

from __future__ import annotations

import copy
from typing import Any

import numpy as np
import trimesh
from numpy.typing import ArrayLike, NDArray

from crashsim import _core
from crashsim.errors import MeshError, ParameterError, at, vehicle_place
from crashsim.names import check_name
from crashsim.vehicles import plausibility
from crashsim.vehicles.builders import VehicleBuilders
from crashsim.vehicles.checks import _as_float, _check_mass_properties, _point, _read_only
from crashsim.vehicles.coupling import Hitch
from crashsim.vehicles.generator.params import BodyParams
from crashsim.vehicles.mass_properties import USER
from crashsim.vehicles.meshio import MeshQuality, check_mesh, mesh_quality
from crashsim.vehicles.stiffness import FACES, Stiffness
from crashsim.vehicles.wheels import Tyre, Wheels

__all__ = ["Vehicle"]

Array = NDArray[np.float64]


class Vehicle(VehicleBuilders):
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
                raise at(
                    ParameterError(
                        f"wheels need {', '.join(missing)} (m): give wheelbase, track, radius "
                        "and cg_to_front_axle, or a crashsim.Wheels"
                    ),
                    vehicle_place(self._name),
                )
            if cg_height is None:
                cg_height = float(self._cg[2])
                if cg_height <= 0.0:
                    raise at(
                        ParameterError(
                            f"its CG is {cg_height:.3f} m above the model frame's ground "
                            "(z = 0): the mesh is not standing on z = 0; load it with "
                            "ground=True, or give cg_height (m above the ground)"
                        ),
                        vehicle_place(self._name),
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
                raise at(e, vehicle_place(self._name)) from e
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
        wheels.check_on(self.shape, self._mass, self._name)
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

    def with_mass(self, mass: float) -> Vehicle:
        """The same vehicle with another mass (kg; a new Vehicle sharing this one's mesh and
        engine shape): the inertia scaled by the same ratio (its radii of gyration kept), and
        the wheels keep their natural frequencies (explicit spring rates and damping scaled
        by the ratio; rates from natural frequencies follow the static loads). ParameterError
        for a mass the engine refuses. A study's ``<vehicle>.mass`` path uses it."""
        ratio = mass / self._mass
        inertia = np.asarray(self._inertia, dtype=np.float64) * ratio
        _check_mass_properties(mass, inertia)  # the engine's checks (ParameterError)
        other = copy.copy(self)
        other._mass = float(mass)
        other._inertia = _read_only(inertia)
        if self._wheels is not None:
            other._wheels = self._wheels.with_mass_ratio(ratio)
        return other

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
            raise at(
                ParameterError(
                    f"its {what} lies {outside:.2f} m outside the body's box (at most 1 m): "
                    "give it in the model frame (m), where the mesh is"
                ),
                vehicle_place(self._name),
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
