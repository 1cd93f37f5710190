"""Plausibility checks of a vehicle: its size, its density and its inertia tensor.

A mesh read in the wrong units or with the wrong up axis, or a mass in the wrong unit, runs
without complaint and gives nonsense (a 4.6 cm, 1450 kg car reported 8 impacts). These
checks catch such input where the vehicle is built (:meth:`Vehicle.from_mesh` and
:meth:`Vehicle.generate`; a :meth:`Vehicle.box` is an idealised body whose dimensions are
typed in metres, so only its inertia is checked).

Two kinds of finding:

- **impossible** (a typed error): an inertia tensor whose largest principal moment exceeds
  the sum of the other two (no body has one: ParameterError); a density above any
  material's or below air's (ParameterError); a largest extent below 1 mm or above 10 km, or
  a coordinate beyond 1e9 (MeshError; see :data:`MAX_COORDINATE`).
- **implausible** for a road vehicle but possible (a 40 m road train, a 0.3 m toy): one
  :class:`crashsim.errors.PlausibilityWarning` naming the likely mistake (which units or
  which up axis would make the vehicle plausible) and how to silence it.

The ranges are those of road vehicles, with margin; every bound below says where it comes
from.
"""

from __future__ import annotations

import warnings

import numpy as np
from numpy.typing import ArrayLike, NDArray

from crashsim.errors import MeshError, ParameterError, PlausibilityWarning

# This module imports nothing else of crashsim: meshio (loading) and vehicle both use it.

__all__ = [
    "DENSITY_IMPOSSIBLE",
    "DENSITY_PLAUSIBLE",
    "HEIGHT",
    "INERTIA_TOLERANCE",
    "LENGTH",
    "SIZE_IMPOSSIBLE",
    "WIDTH",
    "check_density",
    "check_inertia",
    "check_size",
    "size_findings",
    "unit_hints",
    "warn",
]

Array = NDArray[np.float64]

# -- bounds ---------------------------------------------------------------------------------

# Plausible extents of a road vehicle (m): length from a kick scooter or a quadricycle (about
# 1 m) to a rigid truck with a full trailer (18.75 m in the EU; 25.25 m for an EU modular
# combination; longer Australian road trains warn: possible, but worth a second look); width
# and height from a bicycle's 0.3-0.6 m to the legal 2.55-2.6 m width and 4-4.6 m height
# limits of heavy vehicles, with margin to 5 m.
LENGTH = (1.0, 30.0)
WIDTH = (0.3, 5.0)
HEIGHT = (0.3, 5.0)

# No vehicle is shorter than 1 mm or longer than 10 km: a largest extent outside this is a
# wrong unit (a car in mm read as m is 4.5 km long, one read as km 4.5 mm), an error.
SIZE_IMPOSSIBLE = (1e-3, 1e4)

# Mass over the volume of the body solid (kg/m^3). Measured: the six shared meshes at their
# real masses (sedan 1450 kg / 4.42 m^3 = 328; SUV 1900 / 6.81 = 279; hatchback 1200 / 7.14 =
# 168; pickup 2200 / 10.48 = 210; ambulance 4500 / 37.87 = 119; bus 12000 / 97.36 = 123) and
# the generator's presets at their class masses (140-226). Lightest real vehicles: empty
# caravans and box semi-trailers, about 40 (1300 kg in a 6.5 x 2.3 x 2.2 m body); heaviest:
# a main battle tank, about 1400 (60 t in about 43 m^3), a loaded dump truck about 700.
# The bounds keep a margin of about 1.5 below and above those.
DENSITY_PLAUSIBLE = (25.0, 2000.0)
# Impossible: lighter than the air the body displaces (1.2 kg/m^3 at sea level; it would
# float) or denser than osmium (22,590 kg/m^3, the densest element). Only a unit mistake
# (mesh or mass) gets there.
DENSITY_IMPOSSIBLE = (1.2, 22_590.0)

# Each principal moment of inertia is at most the sum of the other two (equal for a flat
# body); this relative slack lets round-off and a flat body's exact equality through.
INERTIA_TOLERANCE = 1e-6

# (metres per unit) of the units a mesh file comes in, for the hints.
_UNITS = {"m": 1.0, "cm": 0.01, "mm": 0.001, "in": 0.0254, "ft": 0.3048}
_AXIS_WORDS = ("x (roll, Ixx)", "y (pitch, Iyy)", "z (yaw, Izz)")
_LETTERS = "xyz"
SILENCE = (
    "if the vehicle is meant to be so, silence this with "
    'warnings.filterwarnings("ignore", category=crashsim.PlausibilityWarning)'
)


def _dims(extents: ArrayLike) -> str:
    e = np.asarray(extents, dtype=np.float64)
    return " x ".join(f"{x:.3g}" for x in e) + " m"


def _inside(x: float, bounds: tuple[float, float]) -> bool:
    return bounds[0] <= x <= bounds[1]


def _plausible_sorted(extents: Array) -> bool:
    """True when the extents, longest taken as the length, fit a road vehicle (m)."""
    e = np.sort(np.asarray(extents, dtype=np.float64))[::-1]
    return _inside(e[0], LENGTH) and _inside(e[1], WIDTH) and _inside(e[2], HEIGHT)


# -- size and axes --------------------------------------------------------------------------


def unit_hints(extents: ArrayLike, scale: float) -> list[str]:
    """The unit names under which the file would give a plausible road vehicle: the model
    extents (m) were read at ``scale`` metres per file unit."""
    file_extents = np.asarray(extents, dtype=np.float64) / scale
    return [
        u
        for u, metres in _UNITS.items()
        if not np.isclose(metres, scale) and _plausible_sorted(file_extents * metres)
    ]


def _unit_text(extents: Array, scale: float, current: str) -> str:
    hints = unit_hints(extents, scale)
    if not hints:
        return ""
    options = " or ".join(
        f"units={u!r} ({_dims(np.sort(extents / scale * _UNITS[u])[::-1])})" for u in hints
    )
    return f": if the file is not in {current}, pass {options}"


def check_size(extents: ArrayLike, what: str, scale: float = 1.0, units: str = "m") -> None:
    """MeshError when the largest extent (m) is outside :data:`SIZE_IMPOSSIBLE`: no vehicle
    is that small or large, the file's units are wrong (the message says which fit)."""
    e = np.asarray(extents, dtype=np.float64)
    longest = float(e.max())
    lo, hi = SIZE_IMPOSSIBLE
    if not lo <= longest <= hi:
        hint = _unit_text(e, scale, units) or ": check the file's units"
        raise MeshError(
            f"{what} is {_dims(e)} as read (units {units}): no vehicle is "
            f"{'shorter than 1 mm' if longest < lo else 'longer than 10 km'}{hint}"
        )


def size_findings(
    extents: ArrayLike,
    scale: float = 1.0,
    units: str = "m",
    rotation: ArrayLike | None = None,
) -> list[str]:
    """What looks wrong with a vehicle's model-frame extents (length x, width y, height z;
    m) for a road vehicle: the longest extent not along x (a wrong up or forward axis; with
    ``rotation``, the file-to-model rotation of load_mesh, the hint names the file's axes),
    or a length, width or height outside :data:`LENGTH`, :data:`WIDTH`, :data:`HEIGHT` (a
    wrong unit when another unit fits; ``scale`` is the metres per file unit used)."""
    e = np.asarray(extents, dtype=np.float64)
    out: list[str] = []
    longest = int(np.argmax(e))
    axes_ok = e[0] >= e[longest]  # ties count as along x
    if not axes_ok:
        rot = np.eye(3) if rotation is None else np.asarray(rotation, dtype=np.float64)
        file_axis = _LETTERS[int(np.argmax(np.abs(rot[longest])))]  # model axis k <- file axis
        if longest == 2:
            up = "y" if file_axis != "y" else "z"
            out.append(
                f"the longest extent ({e[2]:.3g} m) is vertical (the file's {file_axis} axis, "
                f"read as up): is the mesh {up}-up? pass up={up!r} and "
                f"forward={file_axis!r} (or '-{file_axis}')"
            )
        else:
            out.append(
                f"the longest extent ({e[1]:.3g} m) is across the vehicle (the file's "
                f"{file_axis} axis, read as left): is its front along {file_axis}? pass "
                f"forward={file_axis!r} (or '-{file_axis}')"
            )
        if not _plausible_sorted(e):
            out.append(
                f"its extents {_dims(np.sort(e)[::-1])} fit no road vehicle in any "
                f"orientation{_unit_text(e, scale, units)}"
            )
        return out
    bad = [
        f"{name} {x:.3g} m outside {lo:g}-{hi:g} m"
        for name, x, (lo, hi) in zip(
            ("length", "width", "height"), e, (LENGTH, WIDTH, HEIGHT), strict=True
        )
        if not lo <= x <= hi
    ]
    if bad:
        out.append(f"its {', '.join(bad)} (a road vehicle's range){_unit_text(e, scale, units)}")
    return out


# -- density ------------------------------------------------------------------------------------


def check_density(
    mass: float, volume: float | None, label: str, hints: list[str] | None = None
) -> list[str]:
    """The finding about mass (kg) / volume (m^3) of the body solid (``label`` says which
    solid), [] when plausible or when there is no volume to judge; ParameterError when it is
    impossible (:data:`DENSITY_IMPOSSIBLE`). ``hints``: the size findings, repeated in the
    error (the usual cause is the mesh's units)."""
    if volume is None or not np.isfinite(volume) or volume <= 0.0:
        return []
    rho = mass / volume
    text = f"{mass:.6g} kg in {volume:.4g} m^3 ({label}) is {rho:.3g} kg/m^3"
    extra = f"; also {'; '.join(hints)}" if hints else ""
    lo, hi = DENSITY_IMPOSSIBLE
    if rho > hi:
        raise ParameterError(
            f"{text}, denser than any material (osmium, the densest, is 22,590 kg/m^3): the "
            f"mesh is too small for the mass or the mass too large; check the mesh's units "
            f"and the mass (kg){extra}"
        )
    if rho < lo:
        raise ParameterError(
            f"{text}, lighter than air (1.2 kg/m^3: it would float): the mesh is too large "
            f"for the mass or the mass too small; check the mesh's units and the mass (kg; "
            f"{mass:g} t would be mass={mass * 1e3:g}){extra}"
        )
    lo, hi = DENSITY_PLAUSIBLE
    if rho < lo:
        return [
            f"{text}, below the {lo:g} kg/m^3 of the lightest road vehicles (empty caravans "
            f"and semi-trailers, about 40): check the mass (kg) and the mesh's units"
        ]
    if rho > hi:
        return [
            f"{text}, above the {hi:g} kg/m^3 of the densest road vehicles (a tank, about "
            f"1400): check the mass (kg) and the mesh's units"
        ]
    return []


def warn(what: str, findings: list[str], stacklevel: int = 3) -> None:
    """One PlausibilityWarning with every finding (none: nothing)."""
    if findings:
        warnings.warn(
            f"{what} looks implausible for a road vehicle: {'; '.join(findings)}. "
            f"{SILENCE[0].upper()}{SILENCE[1:]}.",
            PlausibilityWarning,
            stacklevel=stacklevel,
        )


# -- inertia ------------------------------------------------------------------------------------


def check_inertia(inertia: ArrayLike, source: str | None = None) -> None:
    """ParameterError when the largest principal moment of a symmetric inertia tensor
    (kg m^2) exceeds the sum of the other two by more than INERTIA_TOLERANCE of itself:
    for any body I_z = sum m (x^2 + y^2) <= sum m (x^2 + z^2) + sum m (y^2 + z^2) = I_x + I_y
    in principal axes (equal only for a flat body), so no body has such a tensor.
    ``source`` (where the tensor came from) is named in the message."""
    tensor = np.asarray(inertia, dtype=np.float64).reshape(3, 3)
    # scaled to its largest entry: moments near 1e308 must not overflow (the engine has
    # already refused a non-finite or non-positive-definite tensor)
    scale = float(np.max(np.abs(tensor)))
    if not (np.isfinite(scale) and scale > 0.0):
        return
    values, vectors = np.linalg.eigh(0.5 * (tensor / scale + (tensor / scale).T))  # ascending
    small, middle, big = (float(v) * scale for v in values)
    if values[2] - (values[0] + values[1]) <= INERTIA_TOLERANCE * abs(values[2]):
        return
    axis = vectors[:, 2]
    k = int(np.argmax(np.abs(axis)))
    if abs(axis[k]) > 0.999:
        about = f"about body {_AXIS_WORDS[k]}"
    else:
        about = f"about the principal axis {np.round(axis, 3).tolist()} (body frame)"
    diagonal = np.diag(tensor)
    names = ("Ixx", "Iyy", "Izz")
    others = " and ".join(names[i] for i in range(3) if i != k)
    origin = f" (inertia from: {source})" if source else ""
    raise ParameterError(
        f"the inertia tensor{origin} is impossible: its principal moment {about}, "
        f"{big:.6g} kg m^2, exceeds the sum of the other two, {small:.6g} + {middle:.6g} = "
        f"{(values[0] + values[1]) * scale:.6g} kg m^2; no body has that (each principal "
        "moment is at most the sum of the other two, equal only for a flat body). Check the "
        "values and their axes "
        f"(given: Ixx, Iyy, Izz = {', '.join(f'{d:.6g}' for d in diagonal)} kg m^2; "
        f"{others} may be too small or {names[k]} too large)"
    )
