"""The values of scene, study and fit files: quantities with units (:data:`UNITS`,
:func:`parse_quantity`), the checked TOML tables every reader walks (unknown keys refused with
the nearest known one, every key read remembered) and the one error they raise,
:class:`SceneFileError`. crashsim.io.scenefile (with its scene_* modules), studyfile and fitfile
read through it; it imports none of them.
"""

from __future__ import annotations

import difflib
import math
import re
from collections.abc import Callable, Mapping
from dataclasses import dataclass
from typing import Any, NoReturn

import numpy as np
from numpy.typing import NDArray

from crashsim.errors import ParameterError, SceneError
from crashsim.units import FOOT, MILE_PER_HOUR, POUND

Array = NDArray[np.float64]

class SceneFileError(SceneError):
    """A mistake in a scene file. ``str(error)`` is one line,
    ``"<file>: [line L, column C: ]<key path>: <what is wrong>"``; the parts are kept as
    ``file``, ``line`` and ``column`` (TOML syntax errors only), ``key`` and ``reason``."""

    def __init__(
        self,
        reason: str,
        *,
        file: str | None = None,
        key: str | None = None,
        line: int | None = None,
        column: int | None = None,
    ) -> None:
        self.reason = _one_line(reason)
        self.file = file
        self.key = key
        self.line = line
        self.column = column
        at = None
        if line is not None:
            at = f"line {line}" + ("" if column is None else f", column {column}")
        where = [file, at, key or None]
        super().__init__(": ".join([*(w for w in where if w), self.reason]))


def _one_line(text: str) -> str:
    return " ".join(str(text).split())


# -- units -------------------------------------------------------------------------------------

STANDARD_GRAVITY = 9.80665  # m/s^2, exact by definition; 1 lbf = 1 lb x standard gravity
INCH = 0.0254  # m, exact
POUND_FORCE = POUND * STANDARD_GRAVITY  # N (4.4482216152605 N)


@dataclass(frozen=True)
class Unit:
    """A unit: the quantity it measures (a key of :data:`DIMENSIONS`) and its size in SI
    units (value_SI = number * factor)."""

    dimension: str
    factor: float


DIMENSIONS: dict[str, str] = {
    # dimension: its SI unit (what a plain number means)
    "length": "m",
    "mass": "kg",
    "time": "s",
    "speed": "m/s",
    "angle": "rad",
    "angular velocity": "rad/s",
    "force": "N",
    "moment of inertia": "kg m^2",
    "force per width": "N/m",  # CRASH3 A; also a spring rate (force per deflection)
    "force per width per crush": "N/m^2",  # CRASH3 B
    "acceleration": "m/s^2",
    "frequency": "Hz",
    "damping": "N s/m",
    "rotational stiffness": "N m/rad",  # moment per angle: an anti-roll bar's, a joint's
    "rotational damping": "N m s/rad",  # moment per angular rate: a joint's
    "torque": "N m",  # a moment: a joint's dry friction
    "per angle": "1/rad",  # a tyre's cornering coefficient (cornering stiffness per load)
    "roll gradient": "rad/g",  # roll per g of lateral acceleration
}

UNITS: dict[str, Unit] = {
    # length
    "m": Unit("length", 1.0),
    "cm": Unit("length", 0.01),
    "mm": Unit("length", 0.001),
    "km": Unit("length", 1000.0),
    "in": Unit("length", INCH),
    "ft": Unit("length", FOOT),
    # mass (lb is the pound-mass)
    "kg": Unit("mass", 1.0),
    "g": Unit("mass", 0.001),
    "t": Unit("mass", 1000.0),
    "lb": Unit("mass", POUND),
    "lbm": Unit("mass", POUND),
    # time
    "s": Unit("time", 1.0),
    "ms": Unit("time", 0.001),
    # speed
    "m/s": Unit("speed", 1.0),
    "km/h": Unit("speed", 1.0 / 3.6),
    "kph": Unit("speed", 1.0 / 3.6),
    "mph": Unit("speed", MILE_PER_HOUR),
    "ft/s": Unit("speed", FOOT),
    "fps": Unit("speed", FOOT),
    # angle
    "rad": Unit("angle", 1.0),
    "deg": Unit("angle", math.pi / 180.0),
    # angular velocity
    "rad/s": Unit("angular velocity", 1.0),
    "deg/s": Unit("angular velocity", math.pi / 180.0),
    "rpm": Unit("angular velocity", 2.0 * math.pi / 60.0),
    # force (a weight given as a force is turned into a mass with standard gravity)
    "N": Unit("force", 1.0),
    "kN": Unit("force", 1000.0),
    "lbf": Unit("force", POUND_FORCE),
    # moment of inertia (lb ft s^2: pound-force foot second squared = slug ft^2)
    "kg m^2": Unit("moment of inertia", 1.0),
    "lb ft s^2": Unit("moment of inertia", POUND_FORCE * FOOT),
    "lbf ft s^2": Unit("moment of inertia", POUND_FORCE * FOOT),
    "slug ft^2": Unit("moment of inertia", POUND_FORCE * FOOT),
    # CRASH3 stiffness: A (force per width), B (force per width per crush); lb = lbf here
    "N/m": Unit("force per width", 1.0),
    "kN/m": Unit("force per width", 1000.0),
    "lb/in": Unit("force per width", POUND_FORCE / INCH),
    "lbf/in": Unit("force per width", POUND_FORCE / INCH),
    "N/m^2": Unit("force per width per crush", 1.0),
    "kN/m^2": Unit("force per width per crush", 1000.0),
    "lb/in^2": Unit("force per width per crush", POUND_FORCE / INCH**2),
    "lbf/in^2": Unit("force per width per crush", POUND_FORCE / INCH**2),
    "psi": Unit("force per width per crush", POUND_FORCE / INCH**2),
    # acceleration (a braking deceleration)
    "m/s^2": Unit("acceleration", 1.0),
    "ft/s^2": Unit("acceleration", FOOT),
    # frequency (a suspension's natural frequency)
    "Hz": Unit("frequency", 1.0),
    # damping (a suspension's damper)
    "N s/m": Unit("damping", 1.0),
    "kN s/m": Unit("damping", 1000.0),
    # rotational stiffness (an anti-roll bar's, a joint's)
    "N m/rad": Unit("rotational stiffness", 1.0),
    "N m/deg": Unit("rotational stiffness", 180.0 / math.pi),
    "kN m/rad": Unit("rotational stiffness", 1000.0),
    # rotational damping (a joint's)
    "N m s/rad": Unit("rotational damping", 1.0),
    "N m s/deg": Unit("rotational damping", 180.0 / math.pi),
    "kN m s/rad": Unit("rotational damping", 1000.0),
    # torque (a joint's friction; lbf ft: pound-force foot)
    "N m": Unit("torque", 1.0),
    "kN m": Unit("torque", 1000.0),
    "lbf ft": Unit("torque", POUND_FORCE * FOOT),
    # per angle (a tyre's cornering coefficient: cornering stiffness per unit load)
    "1/rad": Unit("per angle", 1.0),
    "1/deg": Unit("per angle", 180.0 / math.pi),
    # roll gradient (roll per g of steady lateral acceleration)
    "rad/g": Unit("roll gradient", 1.0),
    "deg/g": Unit("roll gradient", math.pi / 180.0),
}

# Other spellings of the units above, after whitespace is collapsed and "*", "·" become " ".
_ALIASES: dict[str, str] = {
    "°": "deg",
    "degree": "deg",
    "degrees": "deg",
    "°/s": "deg/s",
    "kmh": "km/h",
    "km/hr": "km/h",
    "m/s2": "m/s^2",
    "ft/s2": "ft/s^2",
    "Ns/m": "N s/m",
    "Nm/deg": "N m/deg",
    "Nm/rad": "N m/rad",
    "Nms/rad": "N m s/rad",
    "Nms/deg": "N m s/deg",
    "Nm": "N m",
    "kNm": "kN m",
    "ft lbf": "lbf ft",
    "/deg": "1/deg",
    "/rad": "1/rad",
    "kNs/m": "kN s/m",
    "kg m2": "kg m^2",
    "kg m²": "kg m^2",
    "slug ft2": "slug ft^2",
    "N/m2": "N/m^2",
    "kN/m2": "kN/m^2",
    "lb/in2": "lb/in^2",
    "lbf/in2": "lbf/in^2",
    "lb ft s2": "lb ft s^2",
    "lbf ft s2": "lbf ft s^2",
}
_ALIASES = {k: v for k, v in _ALIASES.items() if v}
# Case-insensitive look-up (the table has no two units that differ only in case).
_LOWER: dict[str, str] = {k.lower(): k for k in [*UNITS, *_ALIASES]}
assert len(_LOWER) == len(UNITS) + len(_ALIASES)

_NUMBER = re.compile(r"\s*([+-]?(?:\d+(?:\.\d*)?|\.\d+)(?:[eE][+-]?\d+)?)(.*)$", re.DOTALL)


def _units_of(dimension: str) -> str:
    return ", ".join(k for k, u in UNITS.items() if u.dimension == dimension)


def _unit(text: str) -> str | None:
    """The key of :data:`UNITS` a unit string names, or None."""
    t = " ".join(text.replace("*", " ").replace("·", " ").split())
    t = re.sub(r"\s*/\s*", "/", t)
    key = _LOWER.get(t.lower())
    if key is None:
        return None
    return _ALIASES.get(key, key)


class _Invalid(ValueError):
    """A value that does not fit (the loader adds the file and the key path)."""


def _expected(dimension: str) -> str:
    return (
        f"expected a {dimension} such as {_example(dimension)} (units: {_units_of(dimension)}) "
        f"or a plain number of {DIMENSIONS[dimension]}"
    )


def _example(dimension: str) -> str:
    return {
        "length": '"12 ft"',
        "mass": '"1450 kg"',
        "time": '"30 ms"',
        "speed": '"30 mph"',
        "angle": '"90 deg"',
        "angular velocity": '"15 deg/s"',
        "force": '"14.2 kN"',
        "moment of inertia": '"2500 kg m^2"',
        "force per width": '"356 lb/in"',
        "force per width per crush": '"34 lb/in^2"',
        "acceleration": '"7 m/s^2"',
        "frequency": '"1.3 Hz"',
        "damping": '"2000 N s/m"',
        "rotational stiffness": '"600 N m/deg"',
        "rotational damping": '"50 N m s/rad"',
        "torque": '"20 N m"',
        "per angle": '"0.1 1/deg"',
        "roll gradient": '"6 deg/g"',
    }[dimension]


def _quantity(value: Any, dimension: str) -> tuple[float, float, str | None]:
    """(value in SI, the number as written, the unit key or None for a plain number)."""
    if isinstance(value, bool) or not isinstance(value, int | float | str):
        kind = {bool: "true/false", dict: "a table", list: "a list"}.get(
            type(value), type(value).__name__
        )
        raise _Invalid(f"got {kind}; {_expected(dimension)}")
    if isinstance(value, int | float):
        x = float(value)
        if not math.isfinite(x):
            raise _Invalid(f"{value} is not a finite number; {_expected(dimension)}")
        return x, x, None
    m = _NUMBER.match(value)
    if m is None:
        raise _Invalid(f"{_show(value)} does not start with a number; {_expected(dimension)}")
    number, rest = float(m.group(1)), m.group(2).strip()
    if not rest:
        raise _Invalid(
            f"{_show(value)} has no unit: write e.g. {_example(dimension)}, or the number without "
            f"quotes for {DIMENSIONS[dimension]}"
        )
    key = _unit(rest)
    if key is None:
        raise _Invalid(f'{_show(value)}: unknown unit "{rest}"; {_expected(dimension)}')
    unit = UNITS[key]
    if unit.dimension != dimension:
        raise _Invalid(
            f"{_show(value)} is a {unit.dimension}, not a {dimension}; {_expected(dimension)}"
        )
    return number * unit.factor, number, key


def parse_quantity(value: Any, dimension: str) -> float:
    """The SI value of a quantity: a plain number (already SI) or a string "<number> <unit>"
    whose unit measures ``dimension`` (a key of :data:`DIMENSIONS`). Raises ParameterError
    saying what was expected (e.g. for "30 mph" given as a length)."""
    if dimension not in DIMENSIONS:
        raise ParameterError(f"unknown dimension {dimension!r}: use one of {', '.join(DIMENSIONS)}")
    try:
        return _quantity(value, dimension)[0]
    except _Invalid as e:
        raise ParameterError(str(e)) from None


# -- reading tables ----------------------------------------------------------------------------

_MISSING: Any = object()


class _Table:
    """A TOML table being read. Keys outside ``keys`` are refused when it is made (with the
    nearest known key as a hint); every key read is remembered, so :meth:`finish` can refuse
    one that was given but does not apply. Errors carry the file and the key path."""

    def __init__(
        self, data: Mapping[str, Any], path: str, file: str, keys: tuple[str, ...] | None = None
    ) -> None:
        self.data = data
        self.path = path
        self.file = file
        self.taken: set[str] = set()
        if keys is not None:  # unknown keys first: a typo explains a "missing" key
            for k in data:
                if k not in keys:
                    close = difflib.get_close_matches(k, keys, n=1, cutoff=0.6)
                    hint = f'did you mean "{close[0]}"? ' if close else ""
                    self.fail(k, f"unknown key: {hint}(the keys here: {', '.join(keys)})")

    def key(self, k: str) -> str:
        return f"{self.path}.{k}" if self.path else k

    def error(self, k: str | None, message: str) -> SceneFileError:
        return SceneFileError(message, file=self.file, key=self.path if k is None else self.key(k))

    def fail(self, k: str | None, message: str) -> NoReturn:
        raise self.error(k, message)

    def has(self, k: str) -> bool:
        return k in self.data

    def raw(self, k: str, default: Any = _MISSING) -> Any:
        self.taken.add(k)
        if k in self.data:
            return self.data[k]
        if default is _MISSING:
            self.fail(k, "this key is required and missing")
        return default

    def _convert(self, k: str, fn: Callable[[Any], Any], value: Any) -> Any:
        try:
            return fn(value)
        except _Invalid as e:
            self.fail(k, str(e))

    def quantity(
        self, k: str, dimension: str, default: Any = _MISSING, *, low: str | None = None
    ) -> Any:
        """SI value; low: None, ">= 0" or "> 0" (checked here, to name the key)."""
        if k not in self.data and default is not _MISSING:
            self.taken.add(k)
            return default
        value = self.raw(k)
        si = self._convert(k, lambda v: _quantity(v, dimension)[0], value)
        _check_low(self, k, value, si, low)
        return si

    def quantity_with_unit(self, k: str, dimension: str) -> tuple[float, float, str | None]:
        value = self.raw(k)
        out = self._convert(k, lambda v: _quantity(v, dimension), value)
        _check_low(self, k, value, out[0], "> 0")
        return out

    def number(self, k: str, default: Any = _MISSING) -> Any:
        """A plain (dimensionless) number."""
        if k not in self.data and default is not _MISSING:
            self.taken.add(k)
            return default
        value = self.raw(k)
        if isinstance(value, bool) or not isinstance(value, int | float):
            self.fail(k, f"expected a plain number (no unit), got {_show(value)}")
        if not math.isfinite(value):
            self.fail(k, f"{value} is not a finite number")
        return float(value)

    def string(
        self, k: str, default: Any = _MISSING, choices: tuple[str, ...] | None = None
    ) -> Any:
        value = self.raw(k, default)
        if value is default and k not in self.data:
            return value
        if not isinstance(value, str):
            self.fail(k, f"expected a string in quotes, got {_show(value)}")
        if choices is not None and value not in choices:
            self.fail(k, f"{_show(value)} is not one of {_or(choices)}")
        return value

    def boolean(self, k: str, default: bool) -> bool:
        value = self.raw(k, default)
        if not isinstance(value, bool):
            self.fail(k, f"expected true or false, got {_show(value)}")
        return value

    def vector(self, k: str, dimension: str | None, sizes: tuple[int, ...] = (3,)) -> Array:
        """A list of quantities (or plain numbers with dimension None), or with a dimension
        also a string "(x, y, z) unit"."""
        value = self.raw(k)
        want = " or ".join(str(n) for n in sizes)
        if dimension is not None and isinstance(value, str):
            items = _split_vector(value)
            if items is None:
                self.fail(
                    k,
                    f"{_show(value)} is not a vector: give a list such as "
                    f"{_vector_example(dimension)}"
                    f' or a string "(x, y, z) {DIMENSIONS[dimension]}"',
                )
            value = items
        if not isinstance(value, list):
            what = f"{want} numbers" if dimension is None else f"{want} {dimension}s"
            self.fail(k, f"expected a list of {what}, got {_show(value)}")
        if len(value) not in sizes:
            self.fail(k, f"expected {want} components, got {len(value)}")
        out = []
        for i, item in enumerate(value):
            try:
                if dimension is None:
                    if isinstance(item, bool) or not isinstance(item, int | float):
                        raise _Invalid(f"expected a plain number (no unit), got {_show(item)}")
                    if not math.isfinite(item):
                        raise _Invalid(f"{item} is not a finite number")
                    out.append(float(item))
                else:
                    out.append(_quantity(item, dimension)[0])
            except _Invalid as e:
                self.fail(f"{k}[{i}]", str(e))
        return np.asarray(out, dtype=np.float64)

    def matrix(self, k: str, dimension: str | None) -> Array:
        """A 3 x 3 list of lists."""
        value = self.raw(k)
        if not (
            isinstance(value, list)
            and len(value) == 3
            and all(isinstance(row, list) and len(row) == 3 for row in value)
        ):
            self.fail(k, f"expected 3 rows of 3 values ([[..], [..], [..]]), got {_show(value)}")
        rows = []
        for i, row in enumerate(value):  # errors name the element: inertia[0][1]
            name = f"{k}[{i}]"
            rows.append(_Table({name: row}, self.path, self.file).vector(name, dimension))
        return np.vstack(rows)

    def table(self, k: str, keys: tuple[str, ...] | None) -> _Table | None:
        value = self.raw(k, None)
        if value is None:
            return None
        if not isinstance(value, dict):
            self.fail(k, f"expected a table, got {_show(value)}")
        return _Table(value, self.key(k), self.file, keys)

    def tables(self, k: str, keys: tuple[str, ...]) -> list[_Table]:
        value = self.raw(k, [])
        if not isinstance(value, list) or not all(isinstance(v, dict) for v in value):
            self.fail(k, f"expected an array of tables ([[{k}]] sections), got {_show(value)}")
        return [_Table(v, f"{self.key(k)}[{i}]", self.file, keys) for i, v in enumerate(value)]

    def finish(self) -> None:
        """SceneFileError for a key that was given but not used (one that does not apply
        where it was given)."""
        for k in self.data:
            if k not in self.taken:
                self.fail(k, "this key does not apply here (see docs/scene-format.md)")


def _check_low(t: _Table, k: str, value: Any, si: float, low: str | None) -> None:
    if low == "> 0" and not si > 0.0:
        t.fail(k, f"{_show(value)} must be positive")
    if low == ">= 0" and not si >= 0.0:
        t.fail(k, f"{_show(value)} must not be negative")


def _show(value: Any) -> str:
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, dict):
        return "a table"
    if isinstance(value, list):
        return f"a list of {len(value)}"
    if isinstance(value, str):
        return f'"{value}"'
    return repr(value)


def _or(choices: tuple[str, ...]) -> str:
    quoted = [f'"{c}"' for c in choices]
    return ", ".join(quoted[:-1]) + f" or {quoted[-1]}" if len(quoted) > 1 else quoted[0]


def _split_vector(text: str) -> list[str] | None:
    """'(1, 2, 3) ft' -> ['1 ft', '2 ft', '3 ft']; None if it is not of that form."""
    m = re.fullmatch(r"\s*[(\[]([^()\[\]]*)[)\]]\s*(.*?)\s*", text)
    if m is None:
        return None
    parts = [p.strip() for p in m.group(1).split(",")]
    if not all(parts):
        return None
    unit = m.group(2)
    return [f"{p} {unit}" if unit else p for p in parts]


def _vector_example(dimension: str) -> str:
    return {
        "length": '["-3.65 m", "0.3 m", "0.7 m"]',
        "speed": '["30 mph", 0, 0]',
        "angular velocity": '[0, 0, "15 deg/s"]',
    }.get(dimension, "[x, y, z]")
