"""Fits written in a scene file: the ``[fit]`` table and the ``[[evidence]]`` sections
(docs/scene-format.md, docs/fitting.md), read into what :func:`crashsim.fit` takes, with
units as scene files have them.

    [fit]
    method = "least_squares"            # or "global"
    [fit.unknowns]                      # path = [lo, hi], each with its unit (plain: SI)
    "red.speed" = ["30 km/h", "90 km/h"]
    "red.heading" = "(-5, 20) deg"
    [fit.start]                         # optional: where the least-squares solve starts
    "red.speed" = "50 km/h"

    [[evidence]]
    type = "rest_position"
    vehicle = "red"
    position = ["31.04 m", "5.52 m"]
    tolerance = "0.2 m"

The evidence types and their keys (values and tolerance in the units of the quantity):
``rest_position`` (vehicle, position [x, y], tolerance: lengths), ``rest_heading``
(vehicle, heading, tolerance: angles), ``edr_delta_v`` (vehicle, longitudinal, lateral,
tolerance: speeds; impact), ``impact_point`` (position, tolerance: lengths; impact),
``tyre_mark`` (vehicle, wheel, polyline [[x, y], ...], tolerance: lengths),
``post_impact_speed`` (vehicle, speed, tolerance: speeds; impact); ``impact`` is the
exchange's number from 1 (default 1).

Every quantity goes through the scene file's unit machinery (crashsim.io.tomlvalues); every
mistake is a :class:`FitFileError` (a SceneFileError and a crashsim.FitError) whose message
names the file, the key path (``fit.unknowns.red.speed``, ``evidence[2].tolerance``) and, for
evidence, the item's type and vehicle. The run settings of a fit are the file's ``[run]``.
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any

import numpy as np

from crashsim.errors import CrashsimError, StudyError
from crashsim.io.studyfile import _flatten
from crashsim.io.tomlvalues import (
    UNITS,
    SceneFileError,
    _quantity,
    _show,
    _split_vector,
    _Table,
)
from crashsim.studies import paths
from crashsim.studies.evidence import (
    EDRDeltaV,
    Evidence,
    FitError,
    ImpactPoint,
    PostImpactSpeed,
    RestHeading,
    RestPosition,
    TyreMark,
    check_evidence,
)
from crashsim.studies.fit import METHODS, STEP

if TYPE_CHECKING:
    from crashsim.scene import Scene
    from crashsim.studies.fit import FitResult

__all__ = [
    "EVIDENCE_KEYS",
    "FIT_KEYS",
    "FitFileError",
    "FitSpec",
    "format_fit",
    "read_fit",
]

FIT_KEYS = (
    "method",
    "unknowns",
    "start",
    "seed",
    "popsize",
    "maxiter",
    "max_nfev",
    "step",
    "scan",
    "scan_points",
)
_GLOBAL_ONLY = ("seed", "popsize", "maxiter")

# type -> (class, its keys besides "type", the dimension of its tolerance)
EVIDENCE_KEYS: dict[str, tuple[type[Evidence], tuple[str, ...], str]] = {
    "rest_position": (RestPosition, ("vehicle", "position", "tolerance"), "length"),
    "rest_heading": (RestHeading, ("vehicle", "heading", "tolerance"), "angle"),
    "edr_delta_v": (
        EDRDeltaV,
        ("vehicle", "longitudinal", "lateral", "tolerance", "impact"),
        "speed",
    ),
    "impact_point": (ImpactPoint, ("position", "tolerance", "impact"), "length"),
    "tyre_mark": (TyreMark, ("vehicle", "wheel", "polyline", "tolerance"), "length"),
    "post_impact_speed": (PostImpactSpeed, ("vehicle", "speed", "tolerance", "impact"), "speed"),
}


class FitFileError(SceneFileError, FitError):
    """A mistake in a scene file's ``[fit]`` table or ``[[evidence]]`` sections: both a
    SceneFileError (``file``, ``key``, ``reason``; one line ``<file>: <key path>: <reason>``)
    and a crashsim.FitError, so either ``except`` catches it."""

    def __init__(
        self,
        reason: str,
        *,
        file: str | None = None,
        key: str | None = None,
        line: int | None = None,
        column: int | None = None,
    ) -> None:
        super().__init__(reason, file=file, key=key, line=line, column=column)
        self.key = key  # StudyError's __init__ (later in the MRO) set it to None

    def __reduce__(self) -> tuple[Any, ...]:
        return (_fit_file_error, (self.reason, self.file, self.key, self.line, self.column))


def _fit_file_error(
    reason: str, file: str | None, key: str | None, line: int | None, column: int | None
) -> FitFileError:
    return FitFileError(reason, file=file, key=key, line=line, column=column)


class _FitTable(_Table):
    """A table of the fit: its errors are FitFileErrors, their reasons led by ``label``
    (an evidence item's type and vehicle) when it is set."""

    def __init__(
        self,
        data: Mapping[str, Any],
        path: str,
        file: str,
        keys: tuple[str, ...] | None = None,
        label: str = "",
    ) -> None:
        self.label = label
        super().__init__(data, path, file, keys)

    def error(self, k: str | None, message: str) -> SceneFileError:
        reason = f"{self.label}: {message}" if self.label else message
        return FitFileError(reason, file=self.file, key=self.path if k is None else self.key(k))


@dataclass(frozen=True)
class FitSpec:
    """A fit as a scene file gives it, in what :func:`crashsim.fit` takes (SI, radians):
    ``unknowns`` {path: (lo, hi)} (empty when the file has [[evidence]] but no [fit]),
    ``evidence`` the items, ``method``, ``start`` {path: value}, ``options`` (seed, popsize,
    maxiter, max_nfev, step, scan, scan_points as given). For showing the answer in the
    file's own units: ``units`` {path: the unit its bounds were written in, a key of
    tomlvalues.UNITS} and ``evidence_units`` (per item, its tolerance's unit or None: SI),
    ``types`` the items' types as written."""

    unknowns: dict[str, tuple[float, float]] = field(default_factory=dict)
    evidence: list[Evidence] = field(default_factory=list)
    method: str = "least_squares"
    start: dict[str, float] = field(default_factory=dict)
    options: dict[str, Any] = field(default_factory=dict)
    units: dict[str, str] = field(default_factory=dict)
    evidence_units: list[str | None] = field(default_factory=list)
    types: list[str] = field(default_factory=list)

    def kwargs(self) -> dict[str, Any]:
        """method, start and the options, as keywords of crashsim.fit."""
        return {"method": self.method, "start": dict(self.start), **self.options}

    def display_units(self) -> dict[str, tuple[str, float]]:
        """{unknown: (the unit the file wrote its bounds in, SI per unit)}, for
        FitResult.plot: the picture in the units of the printed table."""
        return {n: (u, _factor(u)) for n, u in self.units.items()}


# -- units written ----------------------------------------------------------------------------


def _written_unit(value: Any, dimension: str | None) -> str | None:
    """The unit (a key of UNITS) of the first component of an already checked quantity or
    vector written with one; None for plain numbers."""
    if dimension is None:
        return None
    items = value if isinstance(value, list) else [value]
    if isinstance(value, str):
        items = _split_vector(value) or [value]
    for item in items:
        if isinstance(item, list):
            unit = _written_unit(item, dimension)
            if unit is not None:
                return unit
        elif isinstance(item, str):
            return _quantity(item, dimension)[2]
    return None


# -- [fit] ------------------------------------------------------------------------------------


def _whole(t: _FitTable, k: str, low: int) -> int | None:
    if not t.has(k):
        t.taken.add(k)
        return None
    v = t.raw(k)
    if isinstance(v, bool) or not isinstance(v, int) or v < low:
        t.fail(k, f"{_show(v)}: give a whole number >= {low}")
    return int(v)


def _unknowns(
    fit: _FitTable, scene: Scene
) -> tuple[dict[str, tuple[float, float]], dict[str, str]]:
    value = fit.raw("unknowns")
    if not isinstance(value, dict) or not value:
        fit.fail(
            "unknowns",
            "expected a table of parameter paths and their bounds, e.g. [fit.unknowns] "
            '"red.speed" = ["20 mph", "50 mph"]',
        )
    unknowns: dict[str, tuple[float, float]] = {}
    units: dict[str, str] = {}
    for name, bounds in _flatten(value).items():
        t = _FitTable({name: bounds}, "fit.unknowns", fit.file)
        p = _path(t, scene, name)
        if p.name in unknowns:
            t.fail(name, f"{p.name} is given twice")
        if (
            not isinstance(bounds, list | str)
            or (isinstance(bounds, str) and _split_vector(bounds) is None)
            or (isinstance(bounds, list) and len(bounds) != 2)
        ):
            t.fail(
                name,
                f"expected the bounds [lo, hi], e.g. {_bounds_example(p.dimension)}, got "
                f"{_show(bounds)}",
            )
        lo, hi = (float(v) for v in t.vector(name, p.dimension, (2,)))
        unit = _written_unit(bounds, p.dimension)
        if not lo < hi:
            shown = _in_unit(lo, hi, unit, p.unit)
            t.fail(name, f"the bounds {shown} need lo < hi")
        unknowns[p.name] = (lo, hi)
        if unit is not None:
            units[p.name] = unit
    try:  # conflicting paths (speed and velocity_x of one vehicle): StudyError naming them
        paths.overrides(scene, {n: [0.5 * (a + b)] for n, (a, b) in unknowns.items()}, n=1)
    except StudyError as e:
        fit.fail("unknowns", str(e))
    return unknowns, units


def _path(t: _FitTable, scene: Scene, name: str) -> paths.ParameterPath:
    try:
        return paths.parse_path(scene, name)
    except StudyError as e:
        t.fail(name, str(e))


def _bounds_example(dimension: str | None) -> str:
    return {
        "speed": '["20 mph", "50 mph"] or "(20, 50) mph"',
        "angle": '["80 deg", "100 deg"] or "(80, 100) deg"',
        "length": '["-1 m", "1 m"]',
        "mass": '["1200 kg", "1600 kg"]',
        "time": '["20 ms", "60 ms"]',
        "angular velocity": '["-20 deg/s", "20 deg/s"]',
    }.get(dimension or "", "[0.05, 0.3] (plain numbers)")


def _in_unit(lo: float, hi: float, unit: str | None, si: str) -> str:
    if unit is None:
        return f"({lo:g}, {hi:g}) {si}"
    f = UNITS[unit].factor
    return f"({lo / f:g}, {hi / f:g}) {unit}"


def _start(
    fit: _FitTable,
    scene: Scene,
    unknowns: Mapping[str, tuple[float, float]],
    units: Mapping[str, str],
) -> dict[str, float]:
    value = fit.raw("start", None)
    if value is None:
        return {}
    if not isinstance(value, dict):
        fit.fail("start", 'expected a table of start values, e.g. [fit.start] "red.speed" = '
                 '"40 mph"')  # fmt: skip
    start: dict[str, float] = {}
    for name, v in _flatten(value).items():
        t = _FitTable({name: v}, "fit.start", fit.file)
        p = _path(t, scene, name)
        if p.name not in unknowns:
            t.fail(name, f"not one of the unknowns ({', '.join(unknowns)})")
        x = t.number(name) if p.dimension is None else t.quantity(name, p.dimension)
        lo, hi = unknowns[p.name]
        if not lo <= x <= hi:
            t.fail(name, f"{_show(v)} lies outside the bounds "
                   f"{_in_unit(lo, hi, units.get(p.name), p.unit)}")  # fmt: skip
        start[p.name] = x
    return start


def _fit_table(data: Any, scene: Scene, file: str) -> FitSpec:
    if not isinstance(data, dict):
        raise FitFileError(f"expected a table ([fit]), got {_show(data)}", file=file, key="fit")
    fit = _FitTable(data, "fit", file, FIT_KEYS)
    method = fit.string("method", "least_squares", choices=METHODS)
    if method != "global":
        for k in _GLOBAL_ONLY:
            if fit.has(k):
                fit.fail(k, f'{k} is for method = "global" (differential evolution)')
    unknowns, units = _unknowns(fit, scene)
    start = _start(fit, scene, unknowns, units)
    options: dict[str, Any] = {}
    for k, low in (("seed", 0), ("popsize", 1), ("maxiter", 1), ("max_nfev", 1),
                   ("scan_points", 2)):  # fmt: skip
        v = _whole(fit, k, low)
        if v is not None:
            options[k] = v
    if fit.has("step"):
        step = fit.number("step")
        if not 0.0 < step < 0.5:
            fit.fail("step", f"{step:g}: the difference step is a fraction of each unknown's "
                     f"range: give a number > 0 and < 0.5 (default {STEP:g})")  # fmt: skip
        options["step"] = step
    if fit.has("scan"):
        options["scan"] = fit.boolean("scan", True)
    fit.finish()
    return FitSpec(unknowns=unknowns, method=method, start=start, options=options, units=units)


# -- [[evidence]] -----------------------------------------------------------------------------


def _evidence_item(
    data: Any, k: int, scene: Scene, file: str
) -> tuple[Evidence, str, str | None]:
    path = f"evidence[{k}]"
    if not isinstance(data, dict):
        raise FitFileError(f"expected a table ([[evidence]] section), got {_show(data)}",
                           file=file, key=path)  # fmt: skip
    kinds = tuple(EVIDENCE_KEYS)
    head = _FitTable(data, path, file)
    kind = head.string("type", choices=kinds)
    cls, keys, dim = EVIDENCE_KEYS[kind]
    vehicle = data.get("vehicle") if "vehicle" in keys else None
    label = kind + (f" of {vehicle}" if isinstance(vehicle, str) else "")
    t = _FitTable(data, path, file, ("type", *keys), label)
    t.taken.add("type")
    values: dict[str, Any] = {}
    names = [v.name for v in scene.vehicles]
    if "vehicle" in keys:
        v = t.string("vehicle")
        if v not in names:
            t.fail("vehicle", f'the scene has no vehicle "{v}" (its vehicles: {", ".join(names)})')
        values["vehicle"] = v
    if "position" in keys:
        values["x"], values["y"] = (float(c) for c in t.vector("position", "length", (2,)))
    for name, d in (("heading", "angle"), ("longitudinal", "speed"), ("lateral", "speed"),
                    ("speed", "speed")):  # fmt: skip
        if name in keys:
            values[name] = t.quantity(name, d)
    if "wheel" in keys:
        values["wheel"] = _wheel(t, scene, values["vehicle"])
    if "polyline" in keys:
        values["polyline"] = _polyline(t)
    values["tolerance"] = t.quantity("tolerance", dim, low="> 0")
    if "impact" in keys:
        n = _whole(t, "impact", 1)
        if n is not None:
            values["impact"] = n
    t.finish()
    item = cls(**values)
    try:  # what the Python API checks, should it check more than the above
        check_evidence(scene, [item])
    except FitError as e:  # its message starts with the API's label: "evidence[0] ...: "
        t.fail(None, str(e).split(": ", 1)[-1])
    unit = _written_unit(data["tolerance"], dim)
    return item, kind, unit


def _wheel(t: _FitTable, scene: Scene, vehicle: str) -> str | int:
    w = t.raw("wheel")
    if isinstance(w, bool) or not isinstance(w, str | int):
        t.fail("wheel", f'expected a wheel name such as "FL" or "front_left" or an index, got '
               f"{_show(w)}")  # fmt: skip
    v = next(x for x in scene.vehicles if x.name == vehicle)
    if v.wheels is None:
        t.fail("vehicle", f'vehicle "{vehicle}" has no wheels: a tyre mark needs wheels '
               "([vehicles.wheels])")  # fmt: skip
    try:
        v.wheels.index(w)
    except CrashsimError as e:  # ParameterError listing the wheels
        t.fail("wheel", str(e))
    return w


def _polyline(t: _FitTable) -> np.ndarray:
    value = t.raw("polyline")
    if not isinstance(value, list) or not value:
        t.fail(
            "polyline",
            'expected a list of points [x, y], e.g. [["1 m", "0.9 m"], ["12 m", "2.4 m"]] or '
            f'["(1, 0.9) m", "(12, 2.4) m"], got {_show(value)}',
        )
    rows = []
    for i, point in enumerate(value):
        name = f"polyline[{i}]"
        p = _FitTable({name: point}, t.path, t.file, label=t.label)
        rows.append(p.vector(name, "length", (2,)))
    return np.vstack(rows)


# -- the whole fit ----------------------------------------------------------------------------


def read_fit(fit: Any, evidence: Any, scene: Scene, file: str) -> FitSpec | None:
    """A scene file's ``[fit]`` table and ``[[evidence]]`` sections (already parsed TOML; None
    where the file has none) against its scene: a FitSpec (None when it has neither). A
    [fit] needs [[evidence]]; [[evidence]] alone is checked and kept (the command line's
    --unknown gives the unknowns). FitFileError naming the file and the key for every
    mistake."""
    if fit is None and evidence is None:
        return None
    spec = FitSpec() if fit is None else _fit_table(fit, scene, file)
    if evidence is None:
        raise FitFileError("a fit needs evidence: add [[evidence]] sections (docs/fitting.md)",
                           file=file, key="evidence")  # fmt: skip
    if not isinstance(evidence, list) or not evidence:
        raise FitFileError(
            f"expected [[evidence]] sections (an array of tables), got {_show(evidence)}",
            file=file,
            key="evidence",
        )
    items, types, units = [], [], []
    for k, data in enumerate(evidence):
        item, kind, unit = _evidence_item(data, k, scene, file)
        items.append(item)
        types.append(kind)
        units.append(unit)
    return FitSpec(
        unknowns=spec.unknowns,
        evidence=items,
        method=spec.method,
        start=spec.start,
        options=spec.options,
        units=spec.units,
        evidence_units=units,
        types=types,
    )


# -- the answer in the file's units -----------------------------------------------------------


def _number(x: float, digits: int = 5) -> str:
    return f"{x:.{digits}g}" if math.isfinite(x) else "-"


def _factor(unit: str | None) -> float:
    return 1.0 if unit is None else UNITS[unit].factor


def format_fit(fit: FitResult, spec: FitSpec | None = None) -> str:
    """The fit's answer as text in the units the file wrote (``spec``; SI where it wrote
    plain numbers, or without a spec): every unknown's best value, its 95 % ranges (the
    Jacobian's +-1.96 sigma, all unknowns at once, the sampling's and the scan's chi^2 + 3.84,
    as the verdict quotes them: widened, or its reason where withheld) and its bounds; every
    evidence item's figure, the fitted run's, the residual in the item's unit and in
    tolerances; the verdict with its reasons."""
    spec = spec if spec is not None and len(spec.types) == len(fit.residuals) else None
    head = (
        f"fit ({fit.method}): chi^2 = {fit.objective:.4g} over "
        f"{sum(len(r.normalised) for r in fit.residuals)} residuals, {fit.n_runs} runs, "
        f"{fit.elapsed:.1f} s"
    )
    if fit.interrupted:
        head += "  INTERRUPTED (Ctrl-C): the best so far"
    lines = [
        head,
        "",
        f"{'unknown':<22} {'best':>11}  {'95 % range (Jacobian)':>23}  "
        f"{'all at once':>23}  {'95 % (sampling)':>23}  {'95 % range (scan)':>21}  "
        f"{'bounds':>21}  unit",
    ]
    for n in fit.names:
        unit = spec.units.get(n) if spec is not None else None
        f = _factor(unit)

        def pair(a: float, b: float, f: float = f) -> str:
            return f"{_number(a / f)} .. {_number(b / f)}"

        def cell(ranges: Mapping[str, tuple[float, float] | None] | None, n: str = n) -> str:
            """One kind of range: "-" when not computed, the verdict's few words ("at upper
            bound") where it withholds it."""
            if ranges is None:
                return "-"
            r = ranges.get(n)
            if r is None:
                return (fit.verdict.range_note(n) if fit.verdict is not None else "") or "-"
            return pair(*r)

        si = "" if unit is None else f"  (= {fit.values[n]:.6g} {fit.units[n]})"
        lines.append(
            f"{n:<22} {_number(fit.values[n] / f, 6):>11}  {cell(fit.ranges):>23}  "
            f"{cell(fit.joint_ranges):>23}  {cell(fit.sample_ranges):>23}  "
            f"{cell(fit.scan_ranges):>21}  {pair(*fit.bounds[n]):>21}  "
            f"{unit or fit.units[n]}{si}"
        )
    lines += [
        "",
        f"{'evidence':<34} {'component':<12} {'evidence':>10} {'fitted':>10} {'residual':>10} "
        f"{'in tol.':>8}  unit",
    ]
    for i, r in enumerate(fit.residuals):
        unit = spec.evidence_units[i] if spec is not None else None
        f = _factor(unit)
        label = r.label
        if spec is not None:
            who = getattr(fit.evidence[i], "vehicle", None)
            label = f"evidence[{i}] {spec.types[i]}" + (f" ({who})" if who is not None else "")
        for c, comp in enumerate(r.components):
            if isinstance(fit.evidence[i], TyreMark):
                comp = "mean dist."
            lines.append(
                f"{label:<34} {comp or '-':<12} {_number(r.evidence[c] / f, 4):>10} "
                f"{_number(r.measured[c] / f, 4):>10} {_number(r.residual[c] / f, 3):>10} "
                f"{r.normalised[c]:>8.2f}  {unit or r.unit}"
            )
    if fit.verdict is not None:
        lines += ["", *fit.verdict.lines()]
    if fit.message:
        lines += ["", f"solver: {fit.message}"]
    return "\n".join(lines)
