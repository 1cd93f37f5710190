"""An independent check of a run's contacts with python-fcl (FCL's BVH mesh collision).

For every first-overlap instant t0 of a :class:`~crashsim.result.Result` (the contact log's
"first_overlap" events and every primary impact's ``first_contact_time``), FCL is asked about
the engine's own meshes (each vehicle's body-frame vertices and triangles) at the run's poses:

- **first overlap**: no collision at ``t0 - delta``, a collision at ``t0 + delta``. The pose
  before is the run's own (``Result.state``); the pose after is the pre-t0 state carried by
  torque-free motion, i.e. the motion without any exchange at or after t0 (exact while the
  timer runs, and still the right question when the timer is shorter than ``delta``).
- **overlap region**: at every impact's exchange instant FCL must find the meshes colliding,
  and every crossing point of every triangle pair FCL reports as intersecting must lie in the
  engine's overlap box (``region_min`` .. ``region_max`` in the contact frame) grown by
  ``abs_tol + rel_tol * diagonal`` (m).

FCL tests surfaces only: a mesh wholly inside the other has no intersecting triangles, so such
a state is reported "not checkable" (with the engine's own inside test as the reason), never
as a disagreement. See docs/cross-check.md for the tolerances and how to read the output.

Frames and units: world frame, SI (m, s). Crossing points are computed here (numpy) from the
triangle pairs FCL reports: FCL's own contact positions are vertices of the intersecting
triangles (its "deepest points"), which can lie metres outside the overlap.
"""

from __future__ import annotations

import math
import weakref
from dataclasses import asdict, dataclass
from typing import TYPE_CHECKING, Any

import numpy as np
from numpy.typing import NDArray

from crashsim import _core
from crashsim.errors import ParameterError, SceneError
from crashsim.records import Impact, rotation_matrix
from crashsim.result import Result

if TYPE_CHECKING:
    from crashsim.vehicles.vehicle import Vehicle

__all__ = ["Check", "CrossCheck", "cross_check"]

Array = NDArray[np.float64]

DELTA = 1e-3  # s either side of a first-overlap instant
ABS_TOL = 1e-3  # m added to every side of the overlap box
REL_TOL = 1e-3  # of the overlap box's diagonal, added as well
MAX_PAIRS = 1_000_000  # intersecting triangle pairs asked of FCL per query

PASS, FAIL, NOT_CHECKABLE = "pass", "fail", "not checkable"

# Two triangles whose normals are closer to parallel than this (sine of the angle) are treated
# as coplanar: their common part is a polygon, clipped in their plane.
_COPLANAR_SINE = 1e-9

# fcl models per vehicle (built once; a Vehicle's mesh is immutable).
_MODELS: weakref.WeakKeyDictionary[Vehicle, Any] = weakref.WeakKeyDictionary()


@dataclass(frozen=True)
class Check:
    """One comparison of the engine with FCL.

    ``kind`` is "first_overlap" (the bracket of a first-overlap instant ``time``) or
    "region" (the overlap box of the exchange at ``time``). ``status`` is "pass", "fail" or
    "not checkable"; ``fcl`` says in words what FCL found, ``detail`` why the status.

    first_overlap: ``before_time`` / ``after_time`` (s) are the instants FCL was asked about,
    ``before_pairs`` / ``after_pairs`` the number of intersecting triangle pairs it found
    there (0: no collision).

    region: ``pairs`` intersecting triangle pairs FCL found at the exchange, ``points`` the
    crossing points checked (end points of the pairs' crossing segments, vertices of coplanar
    overlaps), ``worst_outside`` the largest distance of a point outside the engine's box (m,
    0 when all are in), ``tolerance`` the allowed distance (m).
    """

    kind: str
    vehicles: tuple[str, str]
    time: float
    status: str
    fcl: str
    detail: str = ""
    before_time: float | None = None
    after_time: float | None = None
    before_pairs: int | None = None
    after_pairs: int | None = None
    pairs: int | None = None
    points: int | None = None
    worst_outside: float | None = None
    tolerance: float | None = None

    @property
    def passed(self) -> bool:
        return self.status == PASS

    def to_dict(self) -> dict[str, Any]:
        out = asdict(self)
        out["vehicles"] = list(self.vehicles)
        return out


@dataclass(frozen=True)
class CrossCheck:
    """The cross-check of one run: ``checks`` in time order, and the settings used (``delta``
    s, ``abs_tol`` m, ``rel_tol``). ``ok`` is True when no check failed ("not checkable" ones
    do not fail; count them with ``not_checkable``). ``str()`` is a table, ``to_dict()`` JSON."""

    checks: tuple[Check, ...]
    delta: float
    abs_tol: float
    rel_tol: float

    @property
    def ok(self) -> bool:
        return all(c.status != FAIL for c in self.checks)

    @property
    def failures(self) -> list[Check]:
        return [c for c in self.checks if c.status == FAIL]

    @property
    def not_checkable(self) -> list[Check]:
        return [c for c in self.checks if c.status == NOT_CHECKABLE]

    @property
    def worst_outside(self) -> float:
        """The largest distance of an FCL crossing point outside an engine box (m)."""
        return max((c.worst_outside or 0.0 for c in self.checks), default=0.0)

    def to_dict(self) -> dict[str, Any]:
        return {
            "ok": self.ok,
            "delta": self.delta,
            "abs_tol": self.abs_tol,
            "rel_tol": self.rel_tol,
            "checks": [c.to_dict() for c in self.checks],
        }

    def __str__(self) -> str:
        head = ("check", "vehicles", "t (s)", "FCL", "outside (mm)", "tol (mm)", "status")
        rows = [head]
        for c in self.checks:
            rows.append(
                (
                    c.kind,
                    f"{c.vehicles[0]} - {c.vehicles[1]}",
                    f"{c.time:.6f}",
                    c.fcl,
                    "" if c.worst_outside is None else f"{1e3 * c.worst_outside:.3f}",
                    "" if c.tolerance is None else f"{1e3 * c.tolerance:.3f}",
                    c.status,
                )
            )
        widths = [max(len(r[i]) for r in rows) for i in range(len(head))]
        lines = [
            "  ".join(s.ljust(w) for s, w in zip(r, widths, strict=True)).rstrip() for r in rows
        ]
        lines.insert(1, "  ".join("-" * w for w in widths))
        n_fail, n_nc = len(self.failures), len(self.not_checkable)
        lines.append(
            f"{len(self.checks)} checks: {len(self.checks) - n_fail - n_nc} passed, "
            f"{n_fail} failed, {n_nc} not checkable (delta = {1e3 * self.delta:g} ms, "
            f"tolerance = {1e3 * self.abs_tol:g} mm + {self.rel_tol:g} x box diagonal)"
        )
        for c in self.checks:
            if c.status != PASS and c.detail:
                lines.append(
                    f"  {c.kind} {c.vehicles[0]} - {c.vehicles[1]} at {c.time:.6f} s: {c.detail}"
                )
        return "\n".join(lines)


# -- fcl -----------------------------------------------------------------------------------


def _fcl() -> Any:
    try:
        import fcl
    except ImportError as e:  # pragma: no cover - depends on the environment
        raise ImportError("the cross-check needs python-fcl: pip install python-fcl") from e
    return fcl


def _model(vehicle: Any) -> Any:
    """The engine mesh of a Vehicle or Obstacle (its frame, m) as an fcl.BVHModel, built
    once."""
    model = _MODELS.get(vehicle)
    if model is None:
        fcl = _fcl()
        shape = vehicle.shape
        vertices = np.ascontiguousarray(shape.vertices, dtype=np.float64)
        triangles = np.ascontiguousarray(shape.triangles, dtype=np.int64)
        model = fcl.BVHModel()
        model.beginModel(len(vertices), len(triangles))
        model.addSubModel(vertices, triangles)
        model.endModel()
        _MODELS[vehicle] = model
    return model


Pose = tuple[Array, Array]  # (CG position (3,) m, orientation (w, x, y, z) body -> world)


def _fcl_pairs(models: tuple[Any, Any], poses: tuple[Pose, Pose], max_pairs: int) -> Array:
    """The (i, j) triangle pairs of the two posed meshes that FCL finds intersecting, (k, 2)."""
    fcl = _fcl()
    objs = [
        fcl.CollisionObject(m, fcl.Transform(rotation_matrix(q), np.asarray(p)))
        for m, (p, q) in zip(models, poses, strict=True)
    ]
    request = fcl.CollisionRequest(num_max_contacts=max_pairs, enable_contact=False)
    result = fcl.CollisionResult()
    fcl.collide(objs[0], objs[1], request, result)
    return np.array([(c.b1, c.b2) for c in result.contacts], dtype=np.int64).reshape(-1, 2)


# -- crossing points of triangle pairs (numpy, independent of the engine) -------------------

_EDGES = ((0, 1), (1, 2), (2, 0))


def _plane_cut(tri: Array, origin: Array, normal: Array) -> tuple[Array, Array]:
    """Where triangles (k, 3, 3) meet planes (points (k, 3), normals (k, 3)): candidate
    points (k, 6, 3) (edge crossings, then vertices on the plane) and their validity (k, 6)."""
    d = np.einsum("kij,kj->ki", tri - origin[:, None, :], normal)
    points, valid = [], []
    for i, j in _EDGES:
        di, dj = d[:, i], d[:, j]
        crosses = di * dj < 0.0
        w = np.where(crosses, di / np.where(crosses, di - dj, 1.0), 0.0)
        points.append(tri[:, i] + w[:, None] * (tri[:, j] - tri[:, i]))
        valid.append(crosses)
    for i in range(3):
        points.append(tri[:, i])
        valid.append(d[:, i] == 0.0)
    return np.stack(points, axis=1), np.stack(valid, axis=1)


def _clip_coplanar(a: Array, b: Array, normal: Array) -> Array:
    """Vertices of the common part of two coplanar triangles (3, 3) (Sutherland-Hodgman:
    a clipped by b's edges), (m, 3); empty when they do not overlap."""
    nb = np.cross(b[1] - b[0], b[2] - b[0])
    if nb @ normal < 0.0:
        b = b[::-1]
        nb = -nb
    poly = list(a)
    for i, j in _EDGES:
        edge = b[j] - b[i]
        side = [float(np.cross(edge, p - b[i]) @ nb) for p in poly]
        out = []
        for k, p in enumerate(poly):
            q, sp, sq = poly[(k + 1) % len(poly)], side[k], side[(k + 1) % len(poly)]
            if sp >= 0.0:
                out.append(p)
            if sp * sq < 0.0:
                out.append(p + (q - p) * (sp / (sp - sq)))
        poly = out
        if not poly:
            break
    return np.asarray(poly, dtype=np.float64).reshape(-1, 3)


def crossing_points(a: Array, b: Array) -> tuple[Array, int]:
    """The common points of triangle pairs a[k], b[k] (each (k, 3, 3), world frame, m): the
    two end points of each crossing segment and the polygon vertices of coplanar overlaps.
    Returns (points (m, 3), number of pairs with no common point)."""
    na = np.cross(a[:, 1] - a[:, 0], a[:, 2] - a[:, 0])
    nb = np.cross(b[:, 1] - b[:, 0], b[:, 2] - b[:, 0])
    line = np.cross(na, nb)
    scale = np.linalg.norm(na, axis=1) * np.linalg.norm(nb, axis=1)
    coplanar = np.linalg.norm(line, axis=1) <= _COPLANAR_SINE * scale
    out: list[Array] = []
    empty = 0
    g = ~coplanar
    if np.any(g):
        pa, va = _plane_cut(a[g], b[g][:, 0], nb[g])  # a's part in b's plane
        pb, vb = _plane_cut(b[g], a[g][:, 0], na[g])
        sa = np.einsum("kij,kj->ki", pa, line[g])
        sb = np.einsum("kij,kj->ki", pb, line[g])
        lo_a = np.where(va, sa, np.inf).min(axis=1)
        hi_a = np.where(va, sa, -np.inf).max(axis=1)
        lo_b = np.where(vb, sb, np.inf).min(axis=1)
        hi_b = np.where(vb, sb, -np.inf).max(axis=1)
        meets = np.maximum(lo_a, lo_b) <= np.minimum(hi_a, hi_b)
        rows = np.arange(pa.shape[0])
        # the segment's ends: the later of the two starts, the earlier of the two ends
        start = np.where(
            (lo_a >= lo_b)[:, None],
            pa[rows, np.argmin(np.where(va, sa, np.inf), axis=1)],
            pb[rows, np.argmin(np.where(vb, sb, np.inf), axis=1)],
        )
        end = np.where(
            (hi_a <= hi_b)[:, None],
            pa[rows, np.argmax(np.where(va, sa, -np.inf), axis=1)],
            pb[rows, np.argmax(np.where(vb, sb, -np.inf), axis=1)],
        )
        out += [start[meets], end[meets]]
        empty += int(np.count_nonzero(~meets))
    for k in np.flatnonzero(coplanar):
        if scale[k] == 0.0:  # a zero-area triangle: no plane to work in
            empty += 1
            continue
        # within the coplanar angle, triangles that meet are within that angle times their
        # size of each other's plane: farther is parallel and apart
        size = max(np.ptp(a[k], axis=0).max(), np.ptp(b[k], axis=0).max())
        apart = np.max(np.abs((a[k] - b[k][0]) @ nb[k])) / np.linalg.norm(nb[k])
        poly = (
            np.empty((0, 3))
            if apart > 2.0 * _COPLANAR_SINE * size
            else _clip_coplanar(a[k], b[k], na[k])
        )
        empty += int(poly.shape[0] == 0)
        out.append(poly)
    points = np.concatenate(out, axis=0) if out else np.empty((0, 3))
    return points, empty


def box_distance(points: Array, frame: Array, lo: Array, hi: Array) -> Array:
    """Distances (m) of world points (k, 3) outside the box lo..hi of the frame whose rows
    are its axes (0 inside or on it)."""
    q = np.asarray(points, dtype=np.float64) @ np.asarray(frame).T
    gap = np.maximum(np.maximum(lo - q, q - hi), 0.0)
    return np.linalg.norm(gap, axis=1)


# -- states ----------------------------------------------------------------------------------


def _free_pose(result: Result, name: str, t0: float, t: float) -> Pose:
    """The pose at t (s) of the motion a vehicle had just before t0: its last sample strictly
    before t0 (the first sample when t0 is the run's start) carried by torque-free motion,
    so no exchange at or after t0 acts (exact; the engine's own free-motion integrator)."""
    tr = result.trajectory(name)
    if result.is_obstacle(name):  # fixed
        return np.asarray(tr.position[0]), np.asarray(tr.orientation[0])
    if result.on_ground:  # forces act between samples: the run's own (interpolated) pose
        return _pose(result, name, t)
    k = max(int(np.searchsorted(tr.t, t0, side="left")) - 1, 0)
    v = result.vehicle(name)
    p, q, _, _ = _core.free_motion(
        v.mass,
        v.inertia,
        tr.position[k],
        tr.orientation[k],
        tr.velocity[k],
        tr.angular_velocity[k],
        float(t - tr.t[k]),
    )
    return np.asarray(p, dtype=np.float64), np.asarray(q, dtype=np.float64)


def _body(result: Result, name: str) -> Any:
    """The Vehicle or Obstacle of a name (both have the engine's shape)."""
    return result.obstacle(name) if result.is_obstacle(name) else result.vehicle(name)


def _pose(result: Result, name: str, t: float) -> Pose:
    """The run's pose at t (s): Result.state (positions are continuous through exchanges)."""
    s = result.state(name, t)
    return np.asarray(s["position"]), np.asarray(s["orientation"])


def _one_inside(vehicles: tuple[Any, Any], poses: tuple[Pose, Pose]) -> bool:
    """The engine's own test (surfaces crossing or one mesh inside the other)."""
    (p1, q1), (p2, q2) = poses
    return bool(_core.shapes_overlap(vehicles[0].shape, p1, q1, vehicles[1].shape, p2, q2))


# -- the checks ------------------------------------------------------------------------------


def _positive(value: Any, name: str, unit: str, allow_zero: bool = False) -> float:
    try:
        x = float(value)
    except (TypeError, ValueError) as e:
        raise ParameterError(f"{name} must be a number ({unit}), got {value!r}") from e
    if not math.isfinite(x) or x < 0.0 or (x == 0.0 and not allow_zero):
        need = "finite and >= 0" if allow_zero else "finite and > 0"
        raise ParameterError(f"{name} = {value!r} {unit} is invalid: it must be {need}")
    return x


def _first_overlaps(result: Result) -> list[tuple[tuple[str, str], float]]:
    """Every first-overlap instant: the log's and the primary impacts' (pair, t0), once."""
    seen: dict[tuple[frozenset[str], float], tuple[tuple[str, str], float]] = {}
    for c in result.contacts:
        if c.kind == "first_overlap":
            seen.setdefault((frozenset(c.vehicles), c.time), (c.vehicles, c.time))
    for imp in result.impacts:
        if not imp.secondary:
            t0 = imp.first_contact_time
            seen.setdefault((frozenset(imp.vehicles), t0), (imp.vehicles, t0))
    return sorted(seen.values(), key=lambda x: x[1])


def _check_first_overlap(
    result: Result, pair: tuple[str, str], t0: float, delta: float, max_pairs: int
) -> Check:
    vehicles = (_body(result, pair[0]), _body(result, pair[1]))
    models = (_model(vehicles[0]), _model(vehicles[1]))
    t_start = float(result.t[0])
    t_before = max(t0 - delta, t_start)
    # a separation of the same pair inside the bracket: ask halfway between it and t0
    for c in result.contacts:
        if c.kind == "separation" and set(c.vehicles) == set(pair) and t_before <= c.time < t0:
            t_before = 0.5 * (c.time + t0)
    t_after = t0 + delta
    before = (_pose(result, pair[0], t_before), _pose(result, pair[1], t_before))
    after = (_free_pose(result, pair[0], t0, t_after), _free_pose(result, pair[1], t0, t_after))
    n_before = len(_fcl_pairs(models, before, max_pairs))
    n_after = len(_fcl_pairs(models, after, max_pairs))
    said = (
        f"{'collision' if n_before else 'none'} at -{1e3 * (t0 - t_before):.3g} ms, "
        f"{'collision' if n_after else 'none'} at +{1e3 * delta:.3g} ms"
    )
    common = dict(
        kind="first_overlap",
        vehicles=pair,
        time=t0,
        fcl=said,
        before_time=t_before,
        after_time=t_after,
        before_pairs=n_before,
        after_pairs=n_after,
    )
    if n_before:
        return Check(
            status=FAIL,
            detail=f"FCL finds {n_before} intersecting triangle pairs {t0 - t_before:.3g} s "
            "before the engine's first overlap",
            **common,
        )
    if n_after:
        return Check(status=PASS, **common)
    if _one_inside(vehicles, after):
        return Check(
            status=NOT_CHECKABLE,
            detail="no surfaces cross after the first overlap but the engine finds one mesh "
            "inside the other: FCL tests surface intersections only",
            **common,
        )
    return Check(
        status=FAIL,
        detail=f"FCL finds no collision {delta:.3g} s after the engine's first overlap (and "
        "the engine's own test agrees there is none): a wrong instant, or a graze shorter "
        "than delta",
        **common,
    )


def _check_region(
    result: Result, imp: Impact, abs_tol: float, rel_tol: float, max_pairs: int
) -> Check:
    pair = imp.vehicles
    vehicles = (_body(result, pair[0]), _body(result, pair[1]))
    models = (_model(vehicles[0]), _model(vehicles[1]))
    poses = (_pose(result, pair[0], imp.time), _pose(result, pair[1], imp.time))
    lo, hi = np.asarray(imp.region_min), np.asarray(imp.region_max)
    tol = abs_tol + rel_tol * float(np.linalg.norm(hi - lo))
    found = _fcl_pairs(models, poses, max_pairs)
    common = dict(kind="region", vehicles=pair, time=imp.time, pairs=len(found), tolerance=tol)
    if len(found) == 0:
        if _one_inside(vehicles, poses):
            return Check(
                status=NOT_CHECKABLE,
                fcl="no collision",
                detail="no surfaces cross at the exchange, one mesh lies inside the other "
                "(the engine's test): FCL tests surface intersections only",
                **common,
            )
        return Check(
            status=FAIL,
            fcl="no collision",
            detail="FCL finds no collision at the exchange instant",
            **common,
        )
    tri = []
    for (p, q), v, idx in zip(poses, vehicles, found.T, strict=True):
        shape = v.shape
        world = np.asarray(shape.vertices) @ rotation_matrix(q).T + p
        tri.append(world[np.asarray(shape.triangles, dtype=np.int64)[idx]])
    points, empty = crossing_points(tri[0], tri[1])
    dist = box_distance(points, imp.contact_frame, lo, hi)
    worst = float(dist.max()) if dist.size else 0.0
    said = f"{len(found)} triangle pairs, {len(points)} crossing points"
    if len(found) >= max_pairs:
        said += " (truncated: raise max_pairs)"
    ok = worst <= tol and len(points) > 0
    detail = ""
    if worst > tol:
        k = int(np.argmax(dist))
        detail = (
            f"{int(np.count_nonzero(dist > tol))} crossing points lie outside the overlap box "
            f"grown by {tol:.3g} m, the worst {worst:.3g} m (at {np.round(points[k], 4).tolist()})"
        )
    elif len(points) == 0:
        detail = f"FCL reports {len(found)} intersecting pairs but none has a common point"
    if empty:
        detail = (detail + "; " if detail else "") + (
            f"{empty} reported pairs have no common point here (a touch, or a zero-area triangle)"
        )
    return Check(
        status=PASS if ok else FAIL,
        fcl=said,
        detail=detail,
        points=len(points),
        worst_outside=worst,
        **common,
    )


def cross_check(
    result: Result,
    delta: float = DELTA,
    abs_tol: float = ABS_TOL,
    rel_tol: float = REL_TOL,
    max_pairs: int = MAX_PAIRS,
) -> CrossCheck:
    """Re-test a run's first overlaps and overlap regions with python-fcl.

    delta: s either side of each first-overlap instant (default 1 ms). abs_tol (m) and
    rel_tol (of the box diagonal): how far an FCL crossing point may lie outside the engine's
    overlap box. max_pairs: the most intersecting triangle pairs FCL lists per query.
    Raises SceneError for a result without its scene (it needs the vehicles' meshes).
    """
    if not isinstance(result, Result):
        raise TypeError(f"cross_check() needs a crashsim.Result, got {type(result).__name__}")
    if result.scene is None:
        raise SceneError(
            "this result has no scene, so no meshes to check: cross-check a result returned "
            "by Scene.run()"
        )
    delta = _positive(delta, "delta", "s")
    abs_tol = _positive(abs_tol, "abs_tol", "m", allow_zero=True)
    rel_tol = _positive(rel_tol, "rel_tol", "(a fraction)", allow_zero=True)
    if isinstance(max_pairs, bool) or not isinstance(max_pairs, int) or max_pairs < 1:
        raise ParameterError(f"max_pairs = {max_pairs!r} is invalid: give a positive integer")
    checks = [
        _check_first_overlap(result, pair, t0, delta, max_pairs)
        for pair, t0 in _first_overlaps(result)
    ]
    checks += [_check_region(result, imp, abs_tol, rel_tol, max_pairs) for imp in result.impacts]
    checks.sort(key=lambda c: (c.time, c.kind))
    return CrossCheck(checks=tuple(checks), delta=delta, abs_tol=abs_tol, rel_tol=rel_tol)
