"""Evidence for a fit (crashsim.studies.fit, docs/fitting.md): what was found at the scene,
each item with its tolerance, in SI units and radians.

=====================  =================================================  =================
item                   residual (in its unit; divided by ``tolerance``)   tolerance unit
=====================  =================================================  =================
RestPosition           rest CG (x, y) minus (x, y)                        m
RestHeading            rest heading minus heading, wrapped to (-pi, pi]   rad
EDRDeltaV              impact ``impact``'s delta-V in the body frame       m/s
                       (longitudinal + forward, lateral + to the
                       right, as event data recorders report them: -y of ISO 8855)
ImpactPoint            impact ``impact``'s centroid (x, y) minus (x, y)    m
TyreMark               mean 2-D distance of the mark's points to the       m
                       wheel's path (its contact patch over the run)
PostImpactSpeed        CG speed at the vehicle's separation after impact   m/s
                       ``impact`` (which it must be in) minus speed
PedestrianRest         a pedestrian's whole-body CG (x, y) at the end of   m
                       the run minus (x, y)
HeadStrike             where the pedestrian's head first touched the       m
                       vehicle, (x, y, z) in the vehicle's model frame,
                       minus (x, y, z)
WrapAround             that point's wrap-around distance minus distance    m
ThrowDistance          the pedestrian's throw distance minus distance      m
=====================  =================================================  =================

The tolerance plays the part of one standard deviation: a fit's objective is the sum of the
squared residuals divided by their tolerances (dimensionless), and its 95 % ranges are
+-1.96 sigma of that model. A run with no rest (the run ended first) is read at its last
sample; an item that the run cannot give (no such impact, an impact the vehicle is not in,
no separation) has the residual MISSING (in tolerances) so that the fit moves away from it,
and ``absent(result)`` says why: a fit whose fitted run cannot give an item does not fit
(crashsim.studies.verdict). ``caveat(result)``: a rest item's vehicle still moving when a
run until rest ended (a poor fit).

Rest positions, headings and EDR delta-V are read from the batch engine's columns
(``uses_result = False``), so a fit with only these evaluates its candidates as batches; an
impact point, a tyre mark, a post-impact speed or a pedestrian's item needs each run's Result.
A pedestrian's items read its figures as a study records them (crashsim.studies.pedestrians:
crashsim.analysis.pedestrian and crashsim.analysis.throw); a PedestrianRest whose person is
still moving at the end (0.1 m/s or more) makes a poor fit, whatever the run's length.
"""

from __future__ import annotations

import math
from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any, ClassVar

import numpy as np
from numpy.typing import NDArray

from crashsim.errors import ParameterError, StudyError

if TYPE_CHECKING:
    from crashsim.result import Result
    from crashsim.scene import Scene

__all__ = [
    "EDRDeltaV",
    "Evidence",
    "HeadStrike",
    "FitError",
    "ImpactPoint",
    "MISSING",
    "PedestrianRest",
    "PostImpactSpeed",
    "RestHeading",
    "RestPosition",
    "ThrowDistance",
    "TyreMark",
    "WrapAround",
    "check_evidence",
]

Array = NDArray[np.float64]

MISSING = 100.0  # residual (in tolerances) of an item the run cannot give


class FitError(StudyError):
    """A mistake in a fit's input: bounds with lo >= hi, an unknown parameter path, evidence
    naming a vehicle the scene does not have, a tolerance <= 0. ``key`` names the unknown
    or the evidence item at fault (e.g. ``"evidence[2] RestPosition(blue)"``)."""


def _wrap(a: float) -> float:
    """An angle wrapped to (-pi, pi] (rad)."""
    return math.pi - (math.pi - a) % (2.0 * math.pi)


def _finite(label: str, name: str, value: Any, size: int | None = None) -> Any:
    try:
        a = np.asarray(value, dtype=np.float64)
    except (TypeError, ValueError) as e:
        raise FitError(f"{label}: {name} must be numbers (SI), got {value!r}", key=label) from e
    if size is not None and a.shape != (size,):
        raise FitError(f"{label}: {name} must be {size} numbers, got {value!r}", key=label)
    if not np.all(np.isfinite(a)):
        raise FitError(f"{label}: {name} must be finite, got {value!r}", key=label)
    return a


@dataclass(frozen=True)
class Evidence:
    """Base of the evidence items. ``tolerance`` > 0 in the item's unit (``unit``)."""

    unit: ClassVar[str] = ""
    uses_result: ClassVar[bool] = False  # True: needs the run's Result, not the columns
    caveat_always: ClassVar[bool] = False  # its caveat holds in runs of a fixed length too

    @property
    def label(self) -> str:
        v = getattr(self, "vehicle", None)
        return f"{type(self).__name__}({v})" if v is not None else type(self).__name__

    @property
    def size(self) -> int:
        return len(self.components)

    @property
    def components(self) -> tuple[str, ...]:
        return ("",)

    def check(self, scene: Scene, label: str) -> None:
        """FitError naming ``label`` for a tolerance <= 0, non-finite values or a vehicle
        the scene does not have."""
        tol = getattr(self, "tolerance", None)
        try:
            ok = tol is not None and math.isfinite(float(tol)) and float(tol) > 0.0
        except (TypeError, ValueError):
            ok = False
        if not ok:
            raise FitError(
                f"{label}: the tolerance must be a finite number > 0 ({self.unit}), got {tol!r}",
                key=label,
            )
        v = getattr(self, "vehicle", None)
        if v is not None:
            names = [x.name for x in scene.vehicles]
            if v not in names:
                raise FitError(
                    f"{label}: the scene has no vehicle {v!r} (its vehicles: "
                    f"{', '.join(names)})",
                    key=label,
                )
        imp = getattr(self, "impact", 1)
        if isinstance(imp, bool) or not isinstance(imp, int) or imp < 1:
            raise FitError(f"{label}: impact must be an integer >= 1, got {imp!r}", key=label)

    def measured(self, columns: Mapping[str, np.ndarray], i: int) -> Array:
        """The run's figure (in the item's unit) from batch columns (variant ``i``)."""
        raise NotImplementedError

    def from_result(self, result: Result) -> Array:
        """The run's figure (in the item's unit) from a Result (NaN where it has none)."""
        raise NotImplementedError

    def target(self) -> Array:
        raise NotImplementedError

    def absent(self, result: Result) -> str | None:
        """Why ``result`` cannot give this item (its residual is then no residual: a fit
        to it does not fit), or None when it can."""
        return None

    def caveat(self, result: Result) -> str | None:
        """What makes the figure ``result`` gives for this item doubtful in a run until rest
        (a poor fit), or None."""
        return None

    def difference(self, measured: Array) -> Array:
        """Residual in the item's unit (measured - evidence); NaN where the run has none."""
        return np.asarray(measured, dtype=np.float64) - self.target()

    def normalised(self, diff: Array) -> Array:
        """The residual in tolerances; MISSING where the run gave nothing."""
        out = np.asarray(diff, dtype=np.float64) / float(self.tolerance)  # type: ignore[attr-defined]
        return np.where(np.isfinite(out), out, MISSING)


def _no_impact(result: Result, impact: int, vehicle: str | None = None) -> str | None:
    """Why ``result`` has no impact number ``impact`` (of ``vehicle``), or None."""
    n = len(result.impacts)
    if n < impact:
        had = "no impact" if n == 0 else f"{n} impact{'s' if n > 1 else ''}"
        return f"the fitted run has {had}, the evidence is of impact {impact}"
    pair = result.impacts[impact - 1].vehicles
    if vehicle is not None and vehicle not in pair:
        return (f"impact {impact} of the fitted run is between {pair[0]} and {pair[1]}, not "
                f"{vehicle}")  # fmt: skip
    return None


def _still_moving(result: Result, vehicle: str) -> str | None:
    if result.rest(vehicle) is not None:
        return None
    return (f"{vehicle} was still moving when the fitted run ended ({result.t[-1]:.3g} s): its "
            "rest is read at the last sample (a longer max_duration?)")  # fmt: skip


def _col(columns: Mapping[str, np.ndarray], key: str, i: int) -> float:
    c = columns.get(key)
    return math.nan if c is None else float(c[i])


@dataclass(frozen=True)
class RestPosition(Evidence):
    """Where ``vehicle``'s CG came to rest, (x, y) m in the world frame; tolerance m (per
    coordinate)."""

    vehicle: str
    x: float
    y: float
    tolerance: float
    unit: ClassVar[str] = "m"

    @property
    def components(self) -> tuple[str, ...]:
        return ("x", "y")

    def target(self) -> Array:
        return np.array([self.x, self.y], dtype=np.float64)

    def measured(self, columns: Mapping[str, np.ndarray], i: int) -> Array:
        out = []
        for c in ("x", "y"):
            v = _col(columns, f"{self.vehicle}.rest_{c}", i)
            out.append(v if math.isfinite(v) else _col(columns, f"{self.vehicle}.final_{c}", i))
        return np.array(out)

    def from_result(self, result: Result) -> Array:
        p = result.trajectory(self.vehicle).position[-1]
        return np.array([p[0], p[1]], dtype=np.float64)

    def caveat(self, result: Result) -> str | None:
        return _still_moving(result, self.vehicle)


@dataclass(frozen=True)
class RestHeading(Evidence):
    """``vehicle``'s heading at rest (rad, yaw of the body x axis from world x,
    counter-clockwise); tolerance rad. The residual is wrapped to (-pi, pi]."""

    vehicle: str
    heading: float
    tolerance: float
    unit: ClassVar[str] = "rad"

    def target(self) -> Array:
        return np.array([self.heading], dtype=np.float64)

    def difference(self, measured: Array) -> Array:
        d = float(np.asarray(measured)[0]) - self.heading
        return np.array([_wrap(d) if math.isfinite(d) else math.nan])

    def measured(self, columns: Mapping[str, np.ndarray], i: int) -> Array:
        v = _col(columns, f"{self.vehicle}.rest_heading_deg", i)
        if not math.isfinite(v):
            v = _col(columns, f"{self.vehicle}.final_heading_deg", i)
        return np.array([math.radians(v)])

    def from_result(self, result: Result) -> Array:
        from crashsim.result import _heading

        return np.array([_heading(result.trajectory(self.vehicle).orientation[-1])])

    def caveat(self, result: Result) -> str | None:
        return _still_moving(result, self.vehicle)


@dataclass(frozen=True)
class EDRDeltaV(Evidence):
    """An event data recorder's delta-V of ``vehicle`` in impact ``impact`` (the run's
    k-th impulse exchange in time order, 1 = the first), in the vehicle's body frame at the
    exchange, as event data recorders report it: ``longitudinal`` (+ forward) and ``lateral``
    (+ to the right, i.e. -y of ISO 8855's x forward, y left), m/s; tolerance m/s (per
    component). The batch's ``delta_v_long`` / ``delta_v_lat`` columns, the same numbers."""

    vehicle: str
    longitudinal: float
    lateral: float
    tolerance: float
    impact: int = 1
    unit: ClassVar[str] = "m/s"

    @property
    def components(self) -> tuple[str, ...]:
        return ("longitudinal", "lateral")

    def target(self) -> Array:
        return np.array([self.longitudinal, self.lateral], dtype=np.float64)

    def measured(self, columns: Mapping[str, np.ndarray], i: int) -> Array:
        pre = f"impact{self.impact}.{self.vehicle}."
        return np.array([_col(columns, pre + "delta_v_long", i),
                         _col(columns, pre + "delta_v_lat", i)])  # fmt: skip

    def from_result(self, result: Result) -> Array:
        if len(result.impacts) < self.impact:
            return np.full(2, math.nan)
        imp = result.impacts[self.impact - 1]
        if self.vehicle not in imp.delta_v:
            return np.full(2, math.nan)
        body = np.asarray(result.delta_v_body(imp, self.vehicle), dtype=np.float64)
        return np.array([body[0], -body[1]])  # EDR: lateral + right

    def absent(self, result: Result) -> str | None:
        return _no_impact(result, self.impact, self.vehicle)


@dataclass(frozen=True)
class ImpactPoint(Evidence):
    """Where impact ``impact`` happened, (x, y) m in the world frame (the exchange's overlap
    centroid); tolerance m (per coordinate)."""

    x: float
    y: float
    tolerance: float
    impact: int = 1
    unit: ClassVar[str] = "m"
    uses_result: ClassVar[bool] = True

    @property
    def components(self) -> tuple[str, ...]:
        return ("x", "y")

    def target(self) -> Array:
        return np.array([self.x, self.y], dtype=np.float64)

    def from_result(self, result: Result) -> Array:
        if len(result.impacts) < self.impact:
            return np.full(2, math.nan)
        c = result.impacts[self.impact - 1].centroid
        return np.array([c[0], c[1]], dtype=np.float64)

    def absent(self, result: Result) -> str | None:
        return _no_impact(result, self.impact)


@dataclass(frozen=True)
class TyreMark(Evidence):
    """A tyre mark that ``vehicle``'s ``wheel`` ("FL", "front_left" or an index) left:
    ``polyline`` (k, 2) points (m, world x, y). The residual is the mean distance (m) of the
    polyline's points to the wheel's path over the run (its contact patch, seen from
    above); tolerance m."""

    vehicle: str
    wheel: str | int
    polyline: Any
    tolerance: float
    unit: ClassVar[str] = "m"
    uses_result: ClassVar[bool] = True

    def check(self, scene: Scene, label: str) -> None:
        super().check(scene, label)
        p = _finite(label, "polyline", self.polyline)
        if p.ndim != 2 or p.shape[0] < 1 or p.shape[1] not in (2, 3):
            raise FitError(
                f"{label}: polyline must be (k, 2) points (m), got shape {p.shape}", key=label
            )
        v = next(x for x in scene.vehicles if x.name == self.vehicle)
        if v.wheels is None:
            raise FitError(f"{label}: vehicle {self.vehicle!r} has no wheels", key=label)
        try:
            v.wheels.index(self.wheel)
        except ParameterError as e:  # it lists the wheels
            raise FitError(f"{label}: {e}", key=label) from None

    def target(self) -> Array:
        return np.zeros(1)

    def from_result(self, result: Result) -> Array:
        path = np.asarray(result.wheel_path(self.vehicle, self.wheel), dtype=np.float64)[:, :2]
        pts = np.asarray(self.polyline, dtype=np.float64)[:, :2]
        return np.array([float(np.mean(_distances(pts, path)))])


def _distances(points: Array, path: Array) -> Array:
    """Distance (m) of each point (k, 2) to the polyline ``path`` (m, 2)."""
    if len(path) == 1:
        return np.linalg.norm(points - path[0], axis=1)
    a, b = path[:-1], path[1:]  # (s, 2) segments
    ab = b - a
    length2 = np.einsum("ij,ij->i", ab, ab)
    ap = points[:, None, :] - a[None, :, :]  # (k, s, 2)
    t = np.einsum("ksj,sj->ks", ap, ab) / np.where(length2 > 0.0, length2, 1.0)
    t = np.clip(t, 0.0, 1.0)
    nearest = a[None] + t[..., None] * ab[None]
    return np.min(np.linalg.norm(points[:, None, :] - nearest, axis=2), axis=1)


@dataclass(frozen=True)
class PostImpactSpeed(Evidence):
    """``vehicle``'s CG speed (m/s) when it separates after impact ``impact`` (its first
    separation at or after the exchange); tolerance m/s."""

    vehicle: str
    speed: float
    tolerance: float
    impact: int = 1
    unit: ClassVar[str] = "m/s"
    uses_result: ClassVar[bool] = True

    def target(self) -> Array:
        return np.array([self.speed], dtype=np.float64)

    def from_result(self, result: Result) -> Array:
        t = self._separation(result)
        return np.array([math.nan if t is None else t.speed])

    def _separation(self, result: Result) -> Any:
        """The vehicle's first separation at or after impact ``impact`` (None: none)."""
        if _no_impact(result, self.impact, self.vehicle) is not None:
            return None
        t = result.impacts[self.impact - 1].time
        return next((s for s in result.separations(self.vehicle) if s.time >= t), None)

    def absent(self, result: Result) -> str | None:
        why = _no_impact(result, self.impact, self.vehicle)
        if why is None and self._separation(result) is None:
            why = f"{self.vehicle} does not separate after impact {self.impact} in the fitted run"
        return why


class _PedestrianItem(Evidence):
    """Base of a pedestrian's items: ``pedestrian`` (its name in the scene) and, where the
    item is about a contact, ``vehicle`` (the striking vehicle's name)."""

    uses_result: ClassVar[bool] = True

    @property
    def label(self) -> str:
        v = getattr(self, "vehicle", None)
        who = self.pedestrian if v is None else f"{self.pedestrian}, {v}"  # type: ignore[attr-defined]
        return f"{type(self).__name__}({who})"

    def check(self, scene: Scene, label: str) -> None:
        super().check(scene, label)
        person = self.pedestrian  # type: ignore[attr-defined]
        if person not in scene.pedestrians:
            have = ", ".join(scene.pedestrians) or "none"
            raise FitError(f"{label}: the scene has no pedestrian {person!r} (its pedestrians: "
                           f"{have})", key=label)  # fmt: skip
        v = getattr(self, "vehicle", None)
        if v is not None and any(s.name == v for s in scene.pedestrians[person].segments):
            raise FitError(f"{label}: {v!r} is a segment of {person!r}: name the vehicle that "
                           "struck it", key=label)  # fmt: skip

    def _figures(self, result: Result) -> dict[str, float]:
        """The pedestrian's figures against ``vehicle`` in the run (NaN where none)."""
        from crashsim.studies.pedestrians import pedestrian_figures

        scene = result.scene
        assert scene is not None
        person = scene.pedestrians[self.pedestrian]  # type: ignore[attr-defined]
        car = next(v for v in scene.vehicles if v.name == self.vehicle)  # type: ignore[attr-defined]
        return pedestrian_figures(result, person, car)

    def absent(self, result: Result) -> str | None:
        f = self._figures(result)
        who, v = self.pedestrian, self.vehicle  # type: ignore[attr-defined]
        if not math.isfinite(f["first_contact_time"]):
            return f"{v} never touched {who} in the fitted run"
        if not math.isfinite(f["head_time"]) and isinstance(self, HeadStrike | WrapAround):
            return f"the head of {who} never touched {v} in the fitted run"
        if not math.isfinite(f["head_wrap_around"]) and isinstance(self, WrapAround):
            return (f"the head of {who} struck {v} off its front and top (no wrap-around "
                    "distance)")  # fmt: skip
        return None


@dataclass(frozen=True)
class PedestrianRest(_PedestrianItem):
    """Where ``pedestrian``'s whole-body centre of mass came to rest, (x, y) m in the world
    frame (read at the run's last sample); tolerance m (per coordinate). A person still
    moving at 0.1 m/s or more at the end makes a poor fit (a longer duration)."""

    pedestrian: str
    x: float
    y: float
    tolerance: float
    unit: ClassVar[str] = "m"
    caveat_always: ClassVar[bool] = True

    @property
    def components(self) -> tuple[str, ...]:
        return ("x", "y")

    def target(self) -> Array:
        return np.array([self.x, self.y], dtype=np.float64)

    def _end(self, result: Result) -> tuple[Array, float]:
        from crashsim.analysis.pedestrian import rest_of

        assert result.scene is not None
        return rest_of(result, result.scene.pedestrians[self.pedestrian])

    def from_result(self, result: Result) -> Array:
        x, _ = self._end(result)
        return np.array([x[0], x[1]], dtype=np.float64)

    def absent(self, result: Result) -> str | None:
        return None

    def caveat(self, result: Result) -> str | None:
        from crashsim.studies.pedestrians import REST_SPEED

        _, speed = self._end(result)
        if speed < REST_SPEED:
            return None
        return (f"{self.pedestrian}'s centre of mass still moves at {speed:.2g} m/s when the "
                f"fitted run ends ({result.t[-1]:.3g} s): its rest is read at the last sample "
                "(a longer duration?)")  # fmt: skip


@dataclass(frozen=True)
class HeadStrike(_PedestrianItem):
    """Where ``pedestrian``'s head first touched ``vehicle``: (x, y, z) m in the vehicle's
    model frame (x forward from the body's middle, y left, z up from the road: the mesh's
    coordinates), the vehicle's surface point nearest the head's CG at the first overlap
    (crashsim.analysis.pedestrian.segment_contacts); tolerance m (per coordinate)."""

    pedestrian: str
    vehicle: str
    x: float
    y: float
    z: float
    tolerance: float
    unit: ClassVar[str] = "m"

    @property
    def components(self) -> tuple[str, ...]:
        return ("x", "y", "z")

    def target(self) -> Array:
        return np.array([self.x, self.y, self.z], dtype=np.float64)

    def from_result(self, result: Result) -> Array:
        f = self._figures(result)
        return np.array([f["head_x"], f["head_y"], f["head_z"]], dtype=np.float64)


@dataclass(frozen=True)
class WrapAround(_PedestrianItem):
    """The wrap-around distance (m) of the head's first contact with ``vehicle``
    (crashsim.analysis.pedestrian.wrap_around_distance at the HeadStrike point); tolerance
    m."""

    pedestrian: str
    vehicle: str
    distance: float
    tolerance: float
    unit: ClassVar[str] = "m"

    def target(self) -> Array:
        return np.array([self.distance], dtype=np.float64)

    def from_result(self, result: Result) -> Array:
        return np.array([self._figures(result)["head_wrap_around"]], dtype=np.float64)


@dataclass(frozen=True)
class ThrowDistance(_PedestrianItem):
    """The pedestrian's throw distance (m): its whole-body CG's horizontal travel from the
    first contact with ``vehicle`` to the end of the run (crashsim.analysis.throw); tolerance
    m."""

    pedestrian: str
    vehicle: str
    distance: float
    tolerance: float
    unit: ClassVar[str] = "m"

    def target(self) -> Array:
        return np.array([self.distance], dtype=np.float64)

    def from_result(self, result: Result) -> Array:
        return np.array([self._figures(result)["throw_distance"]], dtype=np.float64)


_VALUES = {
    RestPosition: ("x", "y"),
    RestHeading: ("heading",),
    EDRDeltaV: ("longitudinal", "lateral"),
    ImpactPoint: ("x", "y"),
    PostImpactSpeed: ("speed",),
    TyreMark: (),
    PedestrianRest: ("x", "y"),
    HeadStrike: ("x", "y", "z"),
    WrapAround: ("distance",),
    ThrowDistance: ("distance",),
}


def check_evidence(scene: Scene, evidence: Sequence[Evidence]) -> list[str]:
    """Check every item against the scene; their labels ("evidence[2] RestPosition(blue)").
    FitError naming the item at fault."""
    if isinstance(evidence, Evidence):
        evidence = [evidence]
    items = list(evidence)
    if not items:
        raise FitError("give at least one evidence item (crashsim.studies.evidence)")
    labels = []
    for k, e in enumerate(items):
        if not isinstance(e, Evidence):
            raise FitError(
                f"evidence[{k}]: {e!r} is not an evidence item (RestPosition, RestHeading, "
                "EDRDeltaV, ImpactPoint, TyreMark, PostImpactSpeed, PedestrianRest, "
                "HeadStrike, WrapAround, ThrowDistance)",
                key=f"evidence[{k}]",
            )
        label = f"evidence[{k}] {e.label}"
        for name in _VALUES.get(type(e), ()):
            _finite(label, name, getattr(e, name))
        e.check(scene, label)
        labels.append(label)
    return labels
