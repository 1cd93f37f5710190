"""Many variants of one scene, as columns: ``run_batch`` (the batch contract,
notes/batch-contract.md).

PROVISIONAL, pure-Python implementation (branch h-studies): each variant is built as its own
Scene (the base scene with the variant's override values) and run through ``Scene.run``;
the columns are read from its Result. It is correct and follows the contract, but slow (one
Python Scene and Result per variant, threads only where the engine releases the GIL); the
batch engine of h-batch replaces this file, with the same names and semantics.

Overrides (core level; first axis = variant; V vehicles, P = len(scene.pairs()) pairs):
``position`` (n, V, 3) m; ``orientation`` (n, V, 4) quaternion (w, x, y, z); ``velocity``
(n, V, 3) m/s; ``angular_velocity`` (n, V, 3) rad/s; ``mass`` (n, V) kg (inertia scaled by the
same ratio, wheels keep their natural frequencies); ``contact.restitution``,
``contact.friction``, ``contact.depth_of_penetration`` (s, NaN = "auto"), ``contact.pitch``
(rad): (n, P) in ``scene.pairs()`` order; ``ground.tyre_friction``, ``ground.body_friction``
(n,). Units of the columns: m, m/s, s, J; angles in degrees where the name ends ``_deg``.
"""

from __future__ import annotations

import concurrent.futures
import copy
import dataclasses
import math
import os
import threading
import warnings
from collections.abc import Callable, Mapping
from dataclasses import dataclass, field
from typing import Any

import numpy as np
from numpy.typing import NDArray

from crashsim.analysis.report import pdof
from crashsim.errors import CrashsimError, ParameterError
from crashsim.result import Result
from crashsim.scene import Scene

__all__ = ["BatchResult", "VariantError", "run_batch"]

Array = NDArray[np.float64]

_STATE_KEYS = {"position": 3, "orientation": 4, "velocity": 3, "angular_velocity": 3}
_PAIR_KEYS = ("restitution", "friction", "depth_of_penetration", "pitch")
_GROUND_KEYS = ("ground.tyre_friction", "ground.body_friction")
_IMPACT_VEHICLE = ("delta_v", "delta_v_x", "delta_v_y", "delta_v_long", "delta_v_lat", "pdof_deg")
_VEHICLE = (
    "total_delta_v",
    "final_x",
    "final_y",
    "final_heading_deg",
    "final_speed",
    "rest_time",
    "rest_x",
    "rest_y",
    "rest_heading_deg",
)


@dataclass(frozen=True)
class VariantError:
    """A variant that failed: its index, the crashsim exception class name (``kind``) and
    the message ("variant 17: ...")."""

    index: int
    kind: str
    message: str


@dataclass(frozen=True)
class BatchResult:
    """The outputs of ``run_batch``: ``columns`` {name: (n,) array} in the contract's order
    (failed or unfinished variants: NaN in float columns, -1 in int columns), ``errors``
    (the failed variants), ``finished`` (n,) bool (False for variants not run because the
    batch was interrupted) and ``interrupted``."""

    n: int
    columns: dict[str, np.ndarray]
    errors: list[VariantError] = field(default_factory=list)
    finished: np.ndarray = field(default_factory=lambda: np.zeros(0, dtype=bool))
    interrupted: bool = False


def _column_names(scene: Scene, max_impacts: int = 2) -> list[str]:
    """The columns of a batch of ``scene``, in order."""
    names = [v.name for v in scene.vehicles]
    out = ["n_impacts"]
    for k in range(1, max_impacts + 1):
        out += [f"impact{k}.time", f"impact{k}.energy"]
        out += [f"impact{k}.{n}.{c}" for n in names for c in _IMPACT_VEHICLE]
    out += [f"{n}.{c}" for n in names for c in _VEHICLE]
    return out


def _check_overrides(
    scene: Scene, overrides: Mapping[str, Any], n: int | None
) -> tuple[dict[str, Array], int]:
    v, p = len(scene.vehicles), len(scene.pairs())
    shapes: dict[str, tuple[int, ...]] = {k: (v, d) for k, d in _STATE_KEYS.items()}
    shapes["mass"] = (v,)
    shapes.update({f"contact.{k}": (p,) for k in _PAIR_KEYS})
    shapes.update(dict.fromkeys(_GROUND_KEYS, ()))
    out: dict[str, Array] = {}
    count = n
    for key, value in overrides.items():
        if key not in shapes:
            raise ParameterError(
                f"unknown override {key!r}: the keys are {', '.join(shapes)}"
            )
        if key in _GROUND_KEYS and scene.ground is None:
            raise ParameterError(f"override {key!r} needs a ground, and the scene has none")
        try:
            a = np.asarray(value, dtype=np.float64)
        except (TypeError, ValueError) as e:
            raise ParameterError(f"override {key!r}: not an array of numbers ({e})") from e
        if a.ndim == 0 or a.shape[1:] != shapes[key] or (count is not None and a.shape[0] != count):
            want = ("n",) + shapes[key] if count is None else (count,) + shapes[key]
            raise ParameterError(
                f"override {key!r} has shape {a.shape}, expected {want} (first axis: variant)"
            )
        count = a.shape[0]
        out[key] = a
    if count is None:
        raise ParameterError("give n (the number of variants) when there are no overrides")
    if isinstance(count, bool) or count < 0:
        raise ParameterError(f"n = {count!r} is invalid: give a number of variants >= 0")
    return out, int(count)


def _read_only(a: Any) -> Array:
    out = np.array(a, dtype=np.float64)
    out.setflags(write=False)
    return out


def _with_mass(vehicle: Any, mass: float) -> Any:
    from crashsim.vehicles.vehicle import _check_mass_properties

    ratio = mass / vehicle.mass
    inertia = np.asarray(vehicle.inertia, dtype=np.float64) * ratio
    _check_mass_properties(mass, inertia)
    other = copy.copy(vehicle)
    other._mass = float(mass)
    other._inertia = _read_only(inertia)
    wheels = vehicle.wheels
    if wheels is not None and (wheels._rates is not None or wheels._damping is not None):
        wheels = copy.copy(wheels)
        if wheels._rates is not None:
            wheels._rates = wheels._rates * ratio
        if wheels._damping is not None:
            wheels._damping = wheels._damping * ratio
        other._wheels = wheels
    return other


def _variant(scene: Scene, arrays: Mapping[str, Array], i: int) -> Scene:
    """Variant i as a Scene (the base's vehicles, meshes and shapes shared)."""
    new = copy.copy(scene)
    placements = list(scene._placements)
    for j, p in enumerate(placements):
        changes: dict[str, Any] = {}
        for key in _STATE_KEYS:
            if key in arrays:
                changes[key] = _read_only(arrays[key][i, j])
        if "mass" in arrays and float(arrays["mass"][i, j]) != p.vehicle.mass:
            changes["vehicle"] = _with_mass(p.vehicle, float(arrays["mass"][i, j]))
        if changes:
            placements[j] = dataclasses.replace(p, **changes)
    new._placements = placements
    new._overrides = {k: dict(v) for k, v in scene._overrides.items()}
    for parameter in _PAIR_KEYS:
        arr = arrays.get(f"contact.{parameter}")
        if arr is None:
            continue
        for k, (a, b, params) in enumerate(scene.pairs()):
            value: Any = float(arr[i, k])
            if parameter == "depth_of_penetration" and math.isnan(value):
                value = "auto"
            if value != params[parameter] or isinstance(value, str):
                new._overrides.setdefault((a, b), {})[parameter] = value
    if any(k in arrays for k in _GROUND_KEYS):
        g = copy.copy(scene.ground)
        if "ground.tyre_friction" in arrays:
            g.friction = float(arrays["ground.tyre_friction"][i])
            g.surface = None
        if "ground.body_friction" in arrays:
            g.body_friction = float(arrays["ground.body_friction"][i])
        new._ground = g
    return new


def _yaw_deg(q: Any) -> float:
    w, x, y, z = (float(c) for c in q)
    return math.degrees(math.atan2(2.0 * (w * z + x * y), 1.0 - 2.0 * (y * y + z * z)))


def _figures(result: Result, names: list[str], max_impacts: int) -> dict[str, float]:
    """One variant's columns from its Result."""
    out: dict[str, float] = {"n_impacts": len(result.impacts)}
    for k in range(1, max_impacts + 1):
        imp = result.impacts[k - 1] if k <= len(result.impacts) else None
        out[f"impact{k}.time"] = math.nan if imp is None else imp.time
        out[f"impact{k}.energy"] = math.nan if imp is None else imp.energy_dissipated
        for n in names:
            pre = f"impact{k}.{n}."
            if imp is None or n not in imp.delta_v:
                out.update({pre + c: math.nan for c in _IMPACT_VEHICLE})
                continue
            dv = np.asarray(imp.delta_v[n], dtype=np.float64)
            body = np.asarray(result.delta_v_body(imp, n), dtype=np.float64)
            angle = pdof(body)
            out[pre + "delta_v"] = float(np.linalg.norm(dv))
            out[pre + "delta_v_x"] = float(dv[0])
            out[pre + "delta_v_y"] = float(dv[1])
            out[pre + "delta_v_long"] = float(body[0])
            out[pre + "delta_v_lat"] = float(body[1])
            out[pre + "pdof_deg"] = math.nan if angle is None else float(angle)
    for n in names:
        tr = result.trajectory(n)
        out[f"{n}.total_delta_v"] = float(
            sum(float(np.linalg.norm(i.delta_v[n])) for i in result.impacts if n in i.delta_v)
        )
        out[f"{n}.final_x"] = float(tr.position[-1][0])
        out[f"{n}.final_y"] = float(tr.position[-1][1])
        out[f"{n}.final_heading_deg"] = _yaw_deg(tr.orientation[-1])
        out[f"{n}.final_speed"] = float(np.linalg.norm(tr.velocity[-1]))
        rest = result.rest(n) if result.on_ground else None
        out[f"{n}.rest_time"] = math.nan if rest is None else rest.time
        out[f"{n}.rest_x"] = math.nan if rest is None else float(rest.position[0])
        out[f"{n}.rest_y"] = math.nan if rest is None else float(rest.position[1])
        out[f"{n}.rest_heading_deg"] = math.nan if rest is None else math.degrees(rest.heading)
    return out


class _Stopped(Exception):
    """Raised from a run's progress callback when the batch was interrupted."""


def run_batch(
    scene: Scene,
    overrides: Mapping[str, np.ndarray] | None = None,
    *,
    n: int | None = None,
    duration: float,
    dt: float,
    until: str | None = None,
    threads: int | None = None,
    progress: Callable[[int, int], None] | None = None,
    max_impacts: int = 2,
) -> BatchResult:
    """Run ``n`` variants of ``scene`` (the base scene with each variant's override values)
    for ``duration`` s with steps of ``dt`` s (with ``until="rest"``: until every vehicle is
    at rest, ``duration`` being the longest a run may take) and return their figures as
    columns (BatchResult). ``threads``: None = all cores. ``progress(done, n)`` is called
    from the caller's thread. A variant whose values the engine refuses, or that fails
    (e.g. vehicles overlapping at t = 0), is listed in ``errors`` and the others run; Ctrl-C
    stops the batch and returns what finished (``interrupted``). Results equal running the
    variant alone through ``Scene.run``, bit for bit, whatever ``threads`` is."""
    if until is not None and until != "rest":
        raise ParameterError(f'until = {until!r} is unknown: use until="rest" or None')
    if isinstance(max_impacts, bool) or not isinstance(max_impacts, int) or max_impacts < 0:
        raise ParameterError(f"max_impacts = {max_impacts!r} is invalid: give an integer >= 0")
    if threads is not None and (isinstance(threads, bool) or not isinstance(threads, int)
                                or threads < 1):
        raise ParameterError(f"threads = {threads!r} is invalid: give an integer >= 1 or None")
    arrays, count = _check_overrides(scene, overrides or {}, n)
    names = [v.name for v in scene.vehicles]
    columns_order = _column_names(scene, max_impacts)
    columns: dict[str, np.ndarray] = {
        c: np.full(count, -1, dtype=np.int64) if c == "n_impacts" else np.full(count, np.nan)
        for c in columns_order
    }
    finished = np.zeros(count, dtype=bool)
    errors: list[VariantError] = []
    stop = threading.Event()

    def check(_t: float) -> None:
        if stop.is_set():
            raise _Stopped

    def one(i: int) -> tuple[int, dict[str, float] | None, VariantError | None]:
        try:
            variant = _variant(scene, arrays, i)
            if until == "rest":
                result = variant.run(dt=dt, progress=check, until="rest", max_duration=duration)
            else:
                result = variant.run(duration=duration, dt=dt, progress=check)
        except CrashsimError as e:
            return i, None, VariantError(i, type(e).__name__, f"variant {i}: {e}")
        return i, _figures(result, names, max_impacts), None

    def take(i: int, figures: dict[str, float] | None, error: VariantError | None) -> None:
        finished[i] = True
        if error is not None:
            errors.append(error)
        else:
            assert figures is not None
            for c in columns_order:
                columns[c][i] = figures[c]

    workers = (os.cpu_count() or 1) if threads is None else threads
    interrupted = False
    done = 0
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # the columns carry what the runs' warnings say
        pool = concurrent.futures.ThreadPoolExecutor(max_workers=max(1, min(workers, count or 1)))
        try:
            pending = {pool.submit(one, i) for i in range(count)}
            while pending:
                ready, pending = concurrent.futures.wait(pending, timeout=0.1)
                for f in ready:
                    try:
                        take(*f.result())
                    except _Stopped:
                        continue
                    done += 1
                if ready and progress is not None:
                    progress(done, count)
        except KeyboardInterrupt:
            interrupted = True
            stop.set()
            for f in pending:
                f.cancel()
            for f in concurrent.futures.as_completed([f for f in pending if not f.cancelled()]):
                try:
                    take(*f.result())
                except _Stopped:
                    pass
        finally:
            pool.shutdown(wait=True, cancel_futures=True)
    errors.sort(key=lambda e: e.index)
    return BatchResult(
        n=count, columns=columns, errors=errors, finished=finished, interrupted=interrupted
    )
