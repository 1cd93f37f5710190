"""Studies written as text: the command line's ``--vary`` and ``--dist`` and a scene file's
``[study]`` table (docs/studies.md), with units as scene files have them.

Values of a sweep (``--vary PATH=VALUES``, ``[study.vary]``):

- ``"10:20:5 mph"``: 5 values evenly spaced from 10 to 20 mph, both included
  (start:stop:count);
- ``"0, 0.1, 0.2"`` or a TOML list ``["10 mph", "15 mph"]``: these values;
- ``"15 mph"``: one value.

A unit after the last value applies to every value written without one; a plain number
without any unit is SI (m/s, rad, m, kg, s); restitution and the frictions are plain numbers.
A depth of penetration may be ``auto``.

Distributions of a Monte Carlo study (``--dist PATH=DIST``, ``[study.distributions]``):
``uniform(lo, hi)``, ``normal(mean, sd)``, ``normal(mean, sd, lo, hi)`` (truncated),
``triangular(lo, mode, hi)``, each number with its unit or one unit after the closing
parenthesis (``normal(15, 1) m/s``), and ``class(sedan)`` / ``class(sedan, mass)``: a figure of
the vehicle-class table (crashsim.studies.distributions.ClassTable).
"""

from __future__ import annotations

import math
import re
from collections.abc import Mapping
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any

from crashsim.errors import CrashsimError, StudyError
from crashsim.io.tomlvalues import SceneFileError, parse_quantity
from crashsim.studies import paths
from crashsim.studies.design import Linspace
from crashsim.studies.distributions import (
    ClassTable,
    Distribution,
    Normal,
    Triangular,
    Uniform,
)

if TYPE_CHECKING:
    from crashsim.scene import Scene

__all__ = ["KINDS", "StudySpec", "parse_assignment", "parse_distribution", "parse_values",
           "read_study"]

KINDS = ("sweep", "montecarlo")
STUDY_KEYS = ("kind", "n", "seed", "vary", "distributions")

_NUMBER = re.compile(r"\s*([+-]?(?:\d+(?:\.\d*)?|\.\d+)(?:[eE][+-]?\d+)?)\s*(.*?)\s*$", re.DOTALL)
_CALL = re.compile(r"^\s*([A-Za-z_]+)\s*\((.*)\)\s*(.*?)\s*$", re.DOTALL)


@dataclass(frozen=True)
class StudySpec:
    """A study as a file or command line gives it: ``kind`` ("sweep" or "montecarlo"),
    ``vary`` ({path: values or Linspace}, SI), ``distributions`` ({path: Distribution}, SI),
    ``n`` and ``seed`` (Monte Carlo)."""

    kind: str
    vary: dict[str, Any] = field(default_factory=dict)
    distributions: dict[str, Distribution] = field(default_factory=dict)
    n: int | None = None
    seed: int | None = None


def _si(text: str, dimension: str | None, unit: str | None, key: str) -> float:
    """A number with an optional unit (else ``unit``, else SI) in SI."""
    m = _NUMBER.match(text)
    if m is None:
        raise StudyError(f'"{key}": {text.strip()!r} is not a number (with a unit)', key)
    number, own = m.group(1), m.group(2)
    given = own or unit
    if dimension is None:
        if given:
            raise StudyError(
                f'"{key}": {text.strip()!r}: this is a plain number, write it without a unit', key
            )
        return float(number)
    try:
        return parse_quantity(float(number) if not given else f"{number} {given}", dimension)
    except CrashsimError as e:
        raise StudyError(f'"{key}": {e}', key) from None


def _trailing_unit(last: str, key: str) -> tuple[str, str | None]:
    """(the last part's number, its unit or None)."""
    m = _NUMBER.match(last)
    if m is None:
        raise StudyError(f'"{key}": {last.strip()!r} is not a number (with a unit)', key)
    return m.group(1), (m.group(2) or None)


def parse_values(key: str, value: Any, dimension: str | None) -> list[float] | Linspace:
    """A sweep's values of one path from text or a TOML value (see the module docstring), SI."""
    if isinstance(value, bool):
        raise StudyError(f'"{key}": true/false is not a value to sweep', key)
    if isinstance(value, int | float):
        return [float(value)]
    if isinstance(value, list):
        if not value:
            raise StudyError(f'"{key}": no values to sweep: give at least one', key)
        return [v for item in value for v in _as_list(parse_values(key, item, dimension))]
    if not isinstance(value, str):
        raise StudyError(f'"{key}": expected values such as "10:20:5 mph" or a list, got '
                         f"{value!r}", key)
    text = value.strip()
    if text.lower() == "auto":
        if not key.endswith("depth_of_penetration"):
            raise StudyError(f'"{key}": "auto" is only a depth of penetration', key)
        return [math.nan]
    if ":" in text:
        parts = text.split(":")
        if len(parts) != 3:
            raise StudyError(
                f'"{key}": {text!r}: write start:stop:count, e.g. "10:20:5 mph" (5 values from '
                "10 to 20 mph)",
                key,
            )
        count_text, unit = _trailing_unit(parts[2], key)
        try:
            count = int(count_text)
        except ValueError:
            raise StudyError(f'"{key}": the count {count_text!r} must be a whole number', key) \
                from None
        if count < 1:
            raise StudyError(f'"{key}": the count {count} must be >= 1', key)
        start = _si(parts[0], dimension, unit, key)
        stop = _si(parts[1], dimension, unit, key)
        return Linspace(start, stop, count)
    parts = [p for p in text.split(",")]
    if any(not p.strip() for p in parts):
        raise StudyError(f'"{key}": {text!r} has an empty value between commas', key)
    _, unit = _trailing_unit(parts[-1], key)
    return [_si(p, dimension, unit, key) for p in parts]


def _as_list(v: list[float] | Linspace) -> list[float]:
    return list(v.values()) if isinstance(v, Linspace) else v


def parse_distribution(key: str, text: Any, dimension: str | None) -> Distribution:
    """A distribution of one path from text (see the module docstring), SI."""
    if not isinstance(text, str):
        raise StudyError(f'"{key}": expected a distribution such as "normal(15 m/s, 1 m/s)", '
                         f"got {text!r}", key)
    m = _CALL.match(text)
    if m is None:
        raise StudyError(
            f'"{key}": {text.strip()!r} is not a distribution: write uniform(lo, hi), '
            "normal(mean, sd), normal(mean, sd, lo, hi), triangular(lo, mode, hi) or "
            "class(sedan)",
            key,
        )
    name, args, unit = m.group(1).lower(), [a.strip() for a in m.group(2).split(",")], m.group(3)
    unit = unit or None
    if name in ("class", "class_table"):
        if unit or not 1 <= len(args) <= 2:
            raise StudyError(f'"{key}": write class(<vehicle class>) or class(<class>, <figure>)',
                             key)
        dist = ClassTable(args[0], args[1] if len(args) > 1 else "mass")
        if dimension is not None and dist.dimension != dimension:
            raise StudyError(
                f'"{key}": the class table\'s {dist.figure} is a {dist.dimension}, and {key} '
                f"takes a {dimension}",
                key,
            )
        return dist
    counts = {"uniform": (2,), "normal": (2, 4), "triangular": (3,)}
    if name not in counts:
        raise StudyError(
            f'"{key}": unknown distribution {name!r}: use uniform, normal, triangular or class',
            key,
        )
    if len(args) not in counts[name]:
        want = " or ".join(str(c) for c in counts[name])
        raise StudyError(f'"{key}": {name} takes {want} numbers, got {len(args)}', key)
    # a spread (sd) is a difference: an offset unit would be wrong, but every unit here is a
    # pure factor, so sd converts as the mean does
    x = [_si(a, dimension, unit, key) for a in args]
    if name == "uniform":
        return Uniform(x[0], x[1])
    if name == "triangular":
        return Triangular(x[0], x[1], x[2])
    return Normal(x[0], x[1], *(x[2:] if len(x) == 4 else ()))


def parse_assignment(text: str, option: str) -> tuple[str, str]:
    """``PATH=VALUE`` of an option (StudyError otherwise)."""
    key, eq, value = text.partition("=")
    if not eq or not key.strip() or not value.strip():
        raise StudyError(f"{option} {text!r}: write PATH=VALUE, e.g. {option} red.speed=10:20:5")
    return key.strip(), value.strip()


def _flatten(table: Mapping[str, Any], prefix: str = "") -> dict[str, Any]:
    """TOML's dotted keys (red.speed = ... is {"red": {"speed": ...}}) back to paths."""
    out: dict[str, Any] = {}
    for k, v in table.items():
        name = f"{prefix}.{k}" if prefix else str(k)
        if isinstance(v, dict):
            out.update(_flatten(v, name))
        else:
            out[name] = v
    return out


def read_study(data: Any, scene: Scene, file: str) -> StudySpec:
    """A scene file's ``[study]`` table (already parsed TOML) against its scene; a
    SceneFileError naming the file and the key (``study.vary.red.speed``) for every mistake."""
    def fail(key: str, reason: str) -> SceneFileError:
        return SceneFileError(reason, file=file, key=key)

    if not isinstance(data, dict):
        raise fail("study", "expected a table ([study])")
    for k in data:
        if k not in STUDY_KEYS:
            raise fail(f"study.{k}", f"unknown key (the keys here: {', '.join(STUDY_KEYS)})")
    kind = data.get("kind")
    if kind not in KINDS:
        raise fail("study.kind", f'{kind!r}: give kind = "sweep" or "montecarlo"')
    wrong = "distributions" if kind == "sweep" else "vary"
    if wrong in data:
        right = "vary" if kind == "sweep" else "distributions"
        raise fail(f"study.{wrong}", f'a {kind} study takes [study.{right}], not [study.{wrong}]')
    n = data.get("n")
    seed = data.get("seed")
    if kind == "sweep":
        for k in ("n", "seed"):
            if k in data:
                raise fail(f"study.{k}", "a sweep's variants are its grid: n and seed are for "
                           'kind = "montecarlo"')
    else:
        for k, v, low in (("n", n, 1), ("seed", seed, 0)):
            if v is not None and (isinstance(v, bool) or not isinstance(v, int) or v < low):
                raise fail(f"study.{k}", f"{v!r}: give a whole number >= {low}")
    table = data.get("vary" if kind == "sweep" else "distributions", {})
    if not isinstance(table, dict):
        raise fail(f"study.{'vary' if kind == 'sweep' else 'distributions'}", "expected a table")
    entries = _flatten(table)
    section = "vary" if kind == "sweep" else "distributions"
    vary: dict[str, Any] = {}
    dists: dict[str, Distribution] = {}
    for path, value in entries.items():
        key = f"study.{section}.{path}"
        try:
            dim = paths.parse_path(scene, path).dimension
            if kind == "sweep":
                vary[path] = parse_values(path, value, dim)
            else:
                dists[path] = parse_distribution(path, value, dim)
                dists[path].check(path)
        except StudyError as e:
            raise fail(key, str(e)) from None
    return StudySpec(kind=kind, vary=vary, distributions=dists, n=n, seed=seed)
