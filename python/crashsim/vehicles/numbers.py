"""The one check of a plain number given to a vehicle's wheels or tyre: a finite float, with a
ParameterError naming the value and its unit otherwise (the engine checks its range)."""

from __future__ import annotations

import math
from typing import Any

from crashsim.errors import ParameterError


def finite(value: Any, name: str, unit: str) -> float:
    if isinstance(value, bool | str):
        raise ParameterError(f"{name} must be a number ({unit}), got {value!r}")
    try:
        x = float(value)
    except (TypeError, ValueError) as e:
        raise ParameterError(f"{name} must be a number ({unit}), got {value!r}") from e
    if not math.isfinite(x):
        raise ParameterError(f"{name} = {x} is invalid: give a finite number ({unit})")
    return x
