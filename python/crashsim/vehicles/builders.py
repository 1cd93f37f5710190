"""The constructors of :class:`crashsim.vehicles.vehicle.Vehicle`:
:meth:`~VehicleBuilders.from_mesh` (a mesh file or a trimesh), :meth:`~VehicleBuilders.box` (a
closed box) and :meth:`~VehicleBuilders.generate` (a body from :mod:`crashsim.vehicles.generator`
and every number from the built-in class table, :mod:`crashsim.vehicles.vehicle_data`;
docs/generator.md), and the helpers that read their keywords. Vehicle inherits them
(``Vehicle.from_mesh`` and so on): a mixin, so that the class, about 800 lines with them, is
read in two files of one concept each. Frames and units as crashsim.vehicles.vehicle's.
"""

from __future__ import annotations

import contextlib
import dataclasses
import math
from collections.abc import Callable, Iterator
from pathlib import Path
from typing import Any, Self

import numpy as np
import trimesh
from numpy.typing import ArrayLike

from crashsim.errors import ParameterError
from crashsim.vehicles import plausibility
from crashsim.vehicles.checks import _as_float, _mass, _point, _wheelbase
from crashsim.vehicles.generator import body_params, generate_body
from crashsim.vehicles.generator.presets import PRESETS
from crashsim.vehicles.mass_properties import (
    EMPIRICAL,
    GENERATED_SOLID,
    SOLIDS,
    UNIFORM_BOX,
    USER,
    _box_inertia,
    _dims,
    _parallel_axis,
    _solid,
    _volume_estimate,
    empirical_inertia,
    solid_properties,
)
from crashsim.vehicles.meshio import MeshSource, axes_rotation, describe, load_mesh, unit_scale
from crashsim.vehicles.stiffness import Stiffness
from crashsim.vehicles.vehicle_data import ALIASES, VehicleClass, vehicle_class
from crashsim.vehicles.wheels import Tyre, Wheels

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


COMBINATION_PRESETS: dict[str, Callable[..., VehicleBuilders]] = {}
"""Presets of Vehicle.generate built elsewhere ("tractor": crashsim.vehicles.trucks registers
its builder when imported, so this module does not import that one, which imports it)."""


class VehicleBuilders:
    """The constructors of :class:`crashsim.vehicles.vehicle.Vehicle` (which inherits them;
    ``cls`` is Vehicle): :meth:`from_mesh`, :meth:`box` and :meth:`generate`."""

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
    ) -> Self:
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
        cg_mode, inertia_mode = _mesh_rules(solid, cg, inertia, wheelbase, wheel_keys)
        what = describe(source)
        mesh = load_mesh(source, units=units, up=up, forward=forward, ground=ground, center=center)
        scale = unit_scale(units)
        units_name = units.strip().lower() if isinstance(units, str) else f"{scale:g} m per unit"
        if name is None:
            name = _mesh_name(source)
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
        if inertia_mode == "mesh":
            assert solid_props is not None
            volume, centroid, unit_inertia = solid_props
            scaled = unit_inertia * (mass_kg / volume)
            inertia_v: ArrayLike = _parallel_axis(scaled, mass_kg, cg_v - centroid)
            sources["inertia"], details["inertia"] = kind, detail
        else:
            inertia_v = _mesh_inertia(inertia_mode, inertia, mesh, mass_kg, wheelbase, sources,
                                      details)  # fmt: skip
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
    ) -> Self:
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
    # Over 100 lines: the docstring (72 lines) documents every keyword and rule; the body is 78.
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
    ) -> Self:
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
            _check_combination_keywords(preset, others, resolution)
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
        _check_generator_sizes({**dims, **shape})
        params = body_params(key, **dims, **shape)
        mesh = generate_body(params, resolution)
        # Ratios to the class (exactly 1.0 for the class's own numbers).
        ratios = _ClassRatios(
            wb=params.wheelbase / vc.wheelbase.value,
            h=params.height / vc.height.value,
            m=mass_kg / vc.mass.value,
        )
        sources: dict[str, str] = {}
        details: dict[str, str] = {}
        solid = solid_properties(mesh)  # closed and outward by construction: volume > 0
        volume = solid[0]
        cg_v = _generated_cg(cg_mode, cg, vc, params, table, ratios, solid, sources, details)
        inertia_v = _generated_inertia(
            inertia_mode, inertia, vc, params, mesh, mass_kg, cg_v, table, ratios, solid,
            sources, details,
        )  # fmt: skip
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
        vehicle = _with_generated_wheels(vehicle, vc, params, table, track, tyre)
        findings = plausibility.size_findings(mesh.extents)
        findings += plausibility.check_density(
            mass_kg, volume, "the generated body's solid", findings
        )
        plausibility.warn(
            f"the generated {key} ({vehicle.name!r}, {_dims(mesh.extents)})", findings, stacklevel=3
        )
        return vehicle


_INERTIA_WORDS = ("class", "mesh", "empirical")


def _mesh_rules(
    solid: Any, cg: Any, inertia: Any, wheelbase: Any, wheel_keys: dict[str, Any] | None
) -> tuple[str, str]:
    """Vehicle.from_mesh's cg and inertia rules ("mesh", "user"; "empirical" for the inertia)
    after checking ``solid`` and that the wheelbase is given exactly when it is used."""
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
    return cg_mode, inertia_mode


def _mesh_name(source: MeshSource) -> str:
    """Vehicle.from_mesh's default name: the file's stem, "vehicle" for an in-memory mesh."""
    if isinstance(source, trimesh.Trimesh | trimesh.Scene):
        return "vehicle"
    return Path(source).stem


def _mesh_inertia(
    inertia_mode: str,
    inertia: Any,
    mesh: trimesh.Trimesh,
    mass_kg: float,
    wheelbase: Any,
    sources: dict[str, str],
    details: dict[str, str],
) -> ArrayLike:
    """Vehicle.from_mesh's inertia about the CG (body axes, kg m^2) by the "empirical" rule
    (from the wheelbase and the mesh's extents) or the user's tensor; writes its source and
    details."""
    if inertia_mode == "empirical":
        length, width, height = (float(e) for e in mesh.extents)
        wb = _wheelbase(wheelbase, length)
        inertia_v = empirical_inertia(mass_kg, wb, length, width, height)
        sources["inertia"] = EMPIRICAL
        details["inertia"] = (
            f"{EMPIRICAL}: Izz = m (0.5 WB)^2 with WB = {wb:.3f} m; Ixx, Iyy of the "
            f"uniform {length:.2f} x {width:.2f} x {height:.2f} m box"
        )
        return inertia_v
    inertia_v, sources["inertia"] = np.asarray(inertia, dtype=np.float64), USER
    return inertia_v


def _check_combination_keywords(preset: str, others: dict[str, Any], resolution: float) -> None:
    """ParameterError when Vehicle.generate of a combination preset ("tractor", ...) is given
    a keyword other than mass, length and name (a resolution other than 1 counts)."""
    given = [k for k, v in others.items() if v is not None] + (
        ["resolution"] if resolution != 1.0 else []
    )
    if given:
        raise ParameterError(
            f"Vehicle.generate({preset!r}) takes mass, length and name; give "
            f"{', '.join(given)} to crashsim.{COMBINATION_PRESETS[preset].__name__}"
            f"({preset!r}, ...) instead"
        )


def _check_generator_sizes(values: dict[str, Any]) -> None:
    """ParameterError for a dimension or shape parameter (m) beyond any vehicle's size: the
    generator's geometry fails beyond it."""
    for k, v in values.items():
        if isinstance(v, int | float) and not isinstance(v, bool):
            if math.isfinite(v) and abs(v) > plausibility.SIZE_IMPOSSIBLE[1]:
                raise ParameterError(f"{k} = {v:g} m: no vehicle is longer than 10 km; give metres")


@dataclasses.dataclass(frozen=True)
class _ClassRatios:
    """A generated vehicle's numbers over its class's (exactly 1.0 for the class's own)."""

    wb: float  # wheelbase
    h: float  # height
    m: float  # mass


def _generated_cg(
    cg_mode: str,
    cg: Any,
    vc: VehicleClass,
    params: Any,
    table: str,
    ratios: _ClassRatios,
    solid: tuple[float, Any, Any],
    sources: dict[str, str],
    details: dict[str, str],
) -> Any:
    """Vehicle.generate's CG (model frame, m) by its rule ("class", "mesh" or the user's
    point); writes its source and details."""
    volume, centroid, _ = solid
    if cg_mode == "class":
        front_axle = params.length / 2.0 - params.front_overhang
        to_axle = vc.cg_to_front_axle.value * ratios.wb
        cg_v = np.array([front_axle - to_axle, 0.0, vc.cg_height.value * ratios.h])
        scaled = _scaled_to(
            ("wheelbase", ratios.wb, params.wheelbase, "m"),
            ("height", ratios.h, params.height, "m"),
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
    return cg_v


def _generated_inertia(
    inertia_mode: str,
    inertia: Any,
    vc: VehicleClass,
    params: Any,
    mesh: trimesh.Trimesh,
    mass_kg: float,
    cg_v: Any,
    table: str,
    ratios: _ClassRatios,
    solid: tuple[float, Any, Any],
    sources: dict[str, str],
    details: dict[str, str],
) -> ArrayLike:
    """Vehicle.generate's inertia about the CG (body axes, kg m^2) by its rule ("class",
    "mesh", "empirical" or the user's tensor); writes its source and details."""
    volume, centroid, unit_inertia = solid
    inertia_v: ArrayLike
    if inertia_mode in ("class", "mesh"):
        inertia_v = _parallel_axis(unit_inertia * (mass_kg / volume), mass_kg, cg_v - centroid)
        if inertia_mode == "class":
            izz = vc.yaw_inertia.value * ratios.m * ratios.wb**2
            inertia_v[2, 2] = izz
            inertia_v[0, 2] = inertia_v[2, 0] = inertia_v[1, 2] = inertia_v[2, 1] = 0.0
            scaled = _scaled_to(
                ("mass", ratios.m, mass_kg, "kg"),
                ("wheelbase", ratios.wb, params.wheelbase, "m"),
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
    return inertia_v


def _with_generated_wheels(
    vehicle: Any, vc: VehicleClass, params: Any, table: str, track: Any, tyre: Any
) -> Any:
    """The generated vehicle on wheels: the body's axles and tyre radius, the class's track
    scaled to the width (unless ``track``, m), the class's roll gradient."""
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
    return vehicle.with_wheels(
        wheelbase=params.wheelbase,
        track=track_v,
        radius=params.wheel_radius,
        cg_to_front_axle=front_axle - float(vehicle.cg[0]),
        cg_height=float(vehicle.cg[2]),
        tyre=tyre,
        source=wheel_source,
        roll_gradient=vc.roll_gradient.value,
    )


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
