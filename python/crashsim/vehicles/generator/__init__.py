"""Parametric vehicle bodies: a closed, watertight, single-shell mesh from a vehicle's dimensions.

Users often have no mesh, only a vehicle's length, width, height and wheelbase. This package
builds a plausible body for the classes in :data:`PRESETS` from those dimensions and a few shape
parameters (every one in metres, with a per-class default; the defaults of the wheel radius and
four other parameters adapt to the dimensions, so any dimensions a vehicle of the class can have
give a valid body: see :func:`body_params`). ``crashsim.Vehicle.generate`` makes a whole
vehicle (mass, CG, inertia, stiffness from the class table) on such a body::

    from crashsim.vehicles.generator import body_params, generate_body
    p = body_params("sedan", length=4.8, width=1.82, height=1.45, wheelbase=2.75)
    mesh = generate_body(p)          # trimesh.Trimesh, model frame

Model frame (m): x forward, y left, z up; the ground is z = 0. The body's bounding box is centred
in x and y and spans x in [-length/2, length/2], y in [-width/2, width/2] and
z in [ground_clearance, height]: ``height`` is the roof height above the ground (as in a
vehicle's specification), and the body floats at ``ground_clearance`` because it has no separate
wheels (it is one shell). Distances along the body (``windshield_base``, ``roof_start``, ...)
are measured rearwards from the front face, d = length/2 - x.

Construction: a loft of cross-sections along x. Each section is a simple polygon in the y-z
plane with the same number of points and the same structure (underside, wheel-arch notch, sill
rounding, side wall, greenhouse leaning in by the tumblehome, rounded roof or hood, mirrored in
y), its heights taken from a side-view profile (hood, windshield, roof, rear window, deck) and
its widths scaled by the plan-view rounding of the corners. The two end sections are closed by
fans. Wheel arches are notches in the lower outer part of the sections at both axles, sized from
the wheel radius. Only +, -, *, / and sqrt are used on the coordinates (sin and cos come from a
fixed polynomial), so the same parameters give the same bits on any IEEE-754 machine.

The package's modules, one way down: this face (body_params, generate_body) -> sections (the
cross-sections), adaptive (the adaptive defaults) -> params (BodyParams, its checks, the side and
plan views and the stations) -> presets (the class table, SHAPE_PARAMETERS) and elementary
(fixed-arithmetic cos, sin, interpolation, fillets); mesh (loft, ply_bytes) stands alone. The
public names are those of ``__all__``, imported from here as before the package was split.
"""

from __future__ import annotations

import trimesh

from crashsim.errors import ParameterError
from crashsim.vehicles.generator.adaptive import _ADAPTIVE
from crashsim.vehicles.generator.mesh import loft, ply_bytes
from crashsim.vehicles.generator.params import _DIMS, BodyParams, _number
from crashsim.vehicles.generator.presets import _DEFAULTS, PRESETS, SHAPE_PARAMETERS, default_dims
from crashsim.vehicles.generator.sections import body_sections

__all__ = [
    "PRESETS",
    "default_dims",
    "SHAPE_PARAMETERS",
    "BodyParams",
    "body_params",
    "body_sections",
    "generate_body",
    "loft",
    "ply_bytes",
]


def body_params(
    preset: str,
    *,
    length: float,
    width: float,
    height: float,
    wheelbase: float,
    **shape: float,
) -> BodyParams:
    """Validated parameters of a body of class ``preset`` (one of :data:`PRESETS`).

    length, width, height (roof above the ground) and wheelbase are in metres. Any shape
    parameter of :data:`SHAPE_PARAMETERS` may be given (m); the others take the preset's
    default, scaled to the dimensions, and five defaults adapt so that any dimensions of a
    vehicle of the class give a valid body (each only where the nominal value would not fit,
    and only after the given numbers are in place):

    - wheel_radius: the preset's tyre radius, or the largest radius (to the mm below) with
      which each arch leaves 0.08 m of body before the end of the body, the arches leave
      0.1 m between them, and over each arch's whole length the top of the body side (the
      beltline, or the hood, roof or deck line less 0.05 m) stays 0.07 m above the arch's
      top (wheel_radius + arch radius). Never below half the preset's radius: dimensions that
      need less are refused.
    - ground_clearance: at most 0.75 wheel_radius. bumper_bottom: at least ground_clearance.
    - edge_radius: at most the body between an arch and the end of the body, and at most 0.45
      of what the lower end face leaves beside its fixed details.
    - bumper_radius: at most 0.8 of the shorter overhang.

    Raises ParameterError, naming the parameter and how to fix it, for a non-finite or
    non-positive number, an unknown preset or parameter, or a combination that gives no valid
    body (axles beyond the body, arches that do not fit, a beltline above the roof, ...).
    """
    if not isinstance(preset, str) or preset not in PRESETS:
        raise ParameterError(f"unknown preset {preset!r}: use one of {', '.join(PRESETS)}")
    unknown = sorted(set(shape) - set(SHAPE_PARAMETERS))
    if unknown:
        raise ParameterError(
            f"unknown shape parameter(s) {', '.join(unknown)}: the shape parameters are "
            f"{', '.join(SHAPE_PARAMETERS)}"
        )
    dims = {"length": length, "width": width, "height": height, "wheelbase": wheelbase}
    values: dict[str, float] = {k: _number(v, k) for k, v in dims.items()}
    L, W, H, wb = (values[k] for k in _DIMS)
    if wb >= L:
        raise ParameterError(
            f"wheelbase = {wb} m is not shorter than length = {L} m: give a shorter wheelbase"
        )
    given = {name: _number(value, name) for name, value in shape.items()}
    nominal: dict[str, float] = {}
    for name, (rule, factor) in _DEFAULTS[preset].items():
        scale = {"m": 1.0, "L": L, "W": W, "H": H, "overhang": L - wb}[rule]
        nominal[name] = factor * scale
    values.update(nominal)
    values.update(given)
    # The adaptive defaults, in this order (each sees the values fixed before it).
    for name, adapt in _ADAPTIVE:
        if name not in given:
            values[name] = adapt(values, nominal[name])
    return BodyParams(preset=preset, **values)


def generate_body(p: BodyParams, resolution: float = 1.0) -> trimesh.Trimesh:
    """The closed, watertight, single-shell body of ``p`` (from :func:`body_params`) as a
    trimesh.Trimesh in the model frame (m; x forward, y left, z up, ground z = 0; bounding box
    x in [-length/2, length/2], y in [-width/2, width/2], z in [ground_clearance, height]).

    resolution scales the number of sections and of points per section (1: a few thousand
    triangles; the count grows about as resolution squared). Deterministic: the same
    parameters give the same vertex and face arrays, bit for bit."""
    if not isinstance(p, BodyParams):
        raise ParameterError(
            f"generate_body needs a BodyParams from body_params(...), got {type(p).__name__}"
        )
    x, sections = body_sections(p, resolution)
    return loft(x, sections)
