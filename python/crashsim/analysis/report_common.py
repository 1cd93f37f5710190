"""What the report's parts share (crashsim.analysis.report): the words the report uses (also
the schema's enums), JSON-ready copies of numbers and arrays, and the freezing of a report
dataclass's arrays."""

from __future__ import annotations

from dataclasses import fields
from typing import Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

from crashsim.errors import ParameterError

Array = NDArray[np.float64]

# Words used in the report (and in the schema's enums).
FULL, SLIDING = "full", "sliding"
BY_STIFFNESS = "stiffness"
UNKNOWN = "unknown"
# An obstacle's struck face as the side of its own frame it is on: the engine names faces
# with a vehicle's words (front +x, rear -x, left +y, right -y), which mean nothing on a pole.
FACE_SIDES = {"front": "+x", "rear": "-x", "left": "+y", "right": "-y", UNKNOWN: UNKNOWN}
EQUAL_SHARES = "equal (stiffness unknown)"
RIGID_OBSTACLE = "rigid obstacle"


# -- small conversions ----------------------------------------------------------------------


def _vec(a: ArrayLike) -> list[float]:
    return [float(x) for x in np.asarray(a, dtype=np.float64).reshape(-1)]


def _mat(a: ArrayLike) -> list[list[float]]:
    return [[float(x) for x in row] for row in np.asarray(a, dtype=np.float64)]


def _opt(x: float | None) -> float | None:
    return None if x is None else float(x)


def _plain(value: Any) -> Any:
    """A JSON-ready copy: numpy scalars and arrays become floats / ints / lists, tuples lists,
    a Vehicle its name; anything else unrepresentable raises ParameterError."""
    if value is None or isinstance(value, bool | str):
        return value
    if isinstance(value, int | np.integer):
        return int(value)
    if isinstance(value, float | np.floating):
        return float(value)
    if isinstance(value, np.ndarray):
        return _plain(value.tolist())
    if isinstance(value, dict):
        return {str(k): _plain(v) for k, v in value.items()}
    if isinstance(value, list | tuple):
        return [_plain(v) for v in value]
    name = getattr(value, "name", None)
    if isinstance(name, str):  # a Vehicle (e.g. the body of a fixed centroid)
        return name
    raise ParameterError(f"cannot put a {type(value).__name__} into a JSON report: {value!r}")


def _freeze_arrays(obj: Any) -> None:
    """Make a report dataclass's arrays read-only copies (float64), as Result's are."""
    for f in fields(obj):
        value = getattr(obj, f.name)
        if isinstance(value, np.ndarray):
            frozen = np.array(value, dtype=np.float64)
            frozen.setflags(write=False)
            object.__setattr__(obj, f.name, frozen)
