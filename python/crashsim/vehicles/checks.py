"""The checks on the numbers a vehicle is given: a number, a point (m), a mass (kg, or a weight
in lb), a wheelbase (m), and a mass and inertia tensor by the engine's own rules (the accepted
ranges and their messages live in one place, crates/crashsim-core). Each raises a
ParameterError that says what is wrong and how to fix it."""

from __future__ import annotations

import math
from typing import Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

from crashsim import _core
from crashsim.errors import ParameterError
from crashsim.units import POUND
from crashsim.vehicles.mass_properties import USER, WEIGHT_LB

Array = NDArray[np.float64]



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
    _core.check_mass(mass, inertia)


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


def _wheelbase(wheelbase: Any, length: float) -> float:
    wb = _as_float(wheelbase, "wheelbase", "m")
    if not math.isfinite(wb) or wb <= 0.0 or wb > length:
        raise ParameterError(
            f"wheelbase = {wb} m is invalid: it must be positive and no longer than the "
            f"vehicle ({length:.3f} m); check its unit (m)"
        )
    return wb
