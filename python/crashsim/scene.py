"""Scenes: vehicles with initial states, contact parameters per pair, and runs.

World frame: right-handed, z up, SI (m, s, rad). A vehicle's position is its CG's; heading is
the yaw of its body x axis from world x (rad, counter-clockwise seen from above); orientations
are quaternions (w, x, y, z) rotating body-frame vectors into the world.

Ranges (depth of penetration in [0, 0.060] s, restitution in [0, 1], friction >= 0, finite
states, ...) are checked by the engine itself, at the call that sets them, so the accepted
ranges and their messages live in one place (crates/crashsim-core).
"""

from __future__ import annotations

import enum
import math
import warnings
from collections.abc import Callable, Iterator
from dataclasses import dataclass
from itertools import combinations
from typing import Any, Literal, TypeAlias

import numpy as np
from numpy.typing import ArrayLike, NDArray

from crashsim import _core
from crashsim.errors import InitialOverlapError, ParameterError, SceneError
from crashsim.result import Result
from crashsim.vehicles.stiffness import FACES
from crashsim.vehicles.vehicle import Vehicle, _as_float, _probe_shape

__all__ = ["DepthOfPenetrationWarning", "Scene"]


class DepthOfPenetrationWarning(UserWarning):
    """An automatic depth of penetration outside the seed's typical 10-60 ms (or clamped to
    the accepted 60 ms): the report of that impact says so too."""


Array = NDArray[np.float64]
VehicleRef: TypeAlias = Vehicle | str
# None: horizontal part of the volume normal tilted by pitch; "volume": the full 3-D one;
# a 3-vector: a fixed world direction from vehicle 1 into vehicle 2.
NormalSpec: TypeAlias = None | Literal["horizontal", "volume"] | ArrayLike
# None: automatic; a 3-vector: a fixed world point (m); (vehicle, (x, y, z)): a point fixed in
# that vehicle's body frame (m from its CG).
CentroidSpec: TypeAlias = None | ArrayLike | tuple[VehicleRef, ArrayLike]


class _Unset(enum.Enum):
    UNSET = "unset"


UNSET = _Unset.UNSET
"""Marks a contact parameter that is not overridden (the scene default applies)."""

_EYE3 = np.eye(3)


def _quaternion_from_matrix(r: Array) -> Array:
    """(w, x, y, z) of a proper rotation matrix (columns: body axes in world)."""
    if not np.all(np.isfinite(r)) or not np.allclose(r @ r.T, np.eye(3), rtol=0.0, atol=1e-9):
        raise ParameterError(
            "the orientation matrix is not orthonormal: give a 3x3 rotation matrix "
            "(columns are the body x, y, z axes in world coordinates)"
        )
    if np.linalg.det(r) <= 0.0:
        raise ParameterError("the orientation matrix is a reflection (det = -1): give a rotation")
    t = float(np.trace(r))
    if t > 0.0:
        s = 2.0 * math.sqrt(t + 1.0)
        q = [0.25 * s, (r[2, 1] - r[1, 2]) / s, (r[0, 2] - r[2, 0]) / s, (r[1, 0] - r[0, 1]) / s]
    else:  # largest diagonal element first, for accuracy
        i = int(np.argmax(np.diag(r)))
        j, k = (i + 1) % 3, (i + 2) % 3
        s = 2.0 * math.sqrt(1.0 + r[i, i] - r[j, j] - r[k, k])
        q = [0.0, 0.0, 0.0, 0.0]
        q[0] = (r[k, j] - r[j, k]) / s
        q[1 + i] = 0.25 * s
        q[1 + j] = (r[j, i] + r[i, j]) / s
        q[1 + k] = (r[k, i] + r[i, k]) / s
    return np.asarray(q, dtype=np.float64)


def _orientation(heading: float | None, orientation: ArrayLike | None) -> Any:
    """The quaternion (w, x, y, z) for a heading (rad about world z) or a full orientation
    (quaternion or 3x3 rotation matrix). Quaternion checks are the engine's."""
    if orientation is None:
        h = 0.0 if heading is None else _as_float(heading, "heading", "rad")
        if not math.isfinite(h):
            raise ParameterError(f"heading = {h} is invalid: give a finite angle in rad")
        return np.array([math.cos(h / 2.0), 0.0, 0.0, math.sin(h / 2.0)])
    if heading is not None:
        raise ParameterError("give heading or orientation, not both")
    try:
        o = np.asarray(orientation, dtype=np.float64)
    except (TypeError, ValueError):
        return orientation  # the engine says what it expected
    return _quaternion_from_matrix(o) if o.shape == (3, 3) else o


def _read_only(a: ArrayLike) -> Array:
    out = np.array(a, dtype=np.float64)
    out.setflags(write=False)
    return out


@dataclass(frozen=True)
class _Placement:
    """A vehicle and its initial state (world frame, SI)."""

    vehicle: Vehicle
    position: Array  # CG, m
    orientation: Array  # (w, x, y, z), body -> world
    velocity: Array  # CG, m/s
    angular_velocity: Array  # rad/s


def _check_state(position: Any, orientation: Any, velocity: Any, angular_velocity: Any) -> None:
    """The engine's checks of an initial state (ParameterError naming the bad input)."""
    _core.World().add_body(
        _probe_shape(), 1.0, _EYE3, position, orientation, velocity, angular_velocity
    )


def _check_contact(kwargs: dict[str, Any]) -> None:
    """The engine's checks of one pair's parameters (ParameterError naming the bad one).
    Body indices in kwargs must be 0 (vehicle 1) or 1 (vehicle 2). The probe bodies have
    stiffness on every face: whether the real vehicles have it is checked when the world is
    built (_check_stiffness), with their names."""
    world = _core.World()
    probe = (0.0, 1.0)  # (A, B): any valid pair
    for i in range(2):
        world.add_body(_probe_shape(), 1.0, _EYE3, (0, 0, 0), (1, 0, 0, 0), (0, 0, 0), (0, 0, 0))
        world.set_stiffness(i, **dict.fromkeys(FACES, probe))
    world.set_contact(0, 1, **kwargs)


def _needs_stiffness(params: dict[str, Any]) -> bool:
    return (
        isinstance(params["depth_of_penetration"], str) and params["depth_of_penetration"] == "auto"
    ) or (isinstance(params["centroid"], str) and params["centroid"] == "stiffness")


def _check_stiffness(params: dict[str, Any], vehicles: tuple[Vehicle, Vehicle]) -> None:
    """ParameterError when the pair's parameters need face stiffness a vehicle lacks."""
    if not _needs_stiffness(params):
        return
    for v in vehicles:
        missing = [f for f in FACES if v.stiffness.face(f) is None]
        if missing:
            raise ParameterError(
                f"vehicle {v.name!r} has no stiffness on its {', '.join(missing)} face(s): "
                'depth_of_penetration="auto" and centroid="stiffness" need CRASH3 A and B on '
                "every face of both vehicles; give the vehicle stiffness=... (or build it from "
                "a vehicle class), or use a fixed depth of penetration and the automatic centroid"
            )


class Scene:
    """Vehicles with initial states, and the contact parameters of every pair.

    The keyword arguments are the defaults of every pair (override per pair with
    :meth:`contact`):

    - depth_of_penetration: s, in [0, 0.060]; the time from first overlap to the exchange.
      Or "auto": per impact dt_p = sqrt(m'/k') from the vehicles' effective masses along the
      normal at the centroid and the series stiffness k' of the struck faces (k = B W, W the
      overlap width), clamped to 60 ms; a DepthOfPenetrationWarning outside 10-60 ms. Needs
      face stiffness on both vehicles.
    - restitution: in [0, 1]. friction: inter-vehicle, >= 0.
    - restitution_mode: "total" (Kudlich-Slibar, on the whole compression impulse) or
      "normal" (Newton/Brach, on the normal relative velocity).
    - normal: None (horizontal part of the overlap's volume normal, tilted up by ``pitch``
      rad), "volume" (full 3-D) or a world vector; it points from vehicle 1 into vehicle 2.
    - centroid: None (centre of the overlap region), "stiffness" (that centre moved along
      the normal so the crush splits as C1 : C2 = k2 : k1; needs face stiffness), a world
      point (m), or ``(vehicle_or_name, (x, y, z))``, a point fixed in that vehicle's body
      frame (m from its CG).
    """

    def __init__(
        self,
        depth_of_penetration: float | Literal["auto"] = 0.030,
        restitution: float = 0.1,
        friction: float = 0.6,
        restitution_mode: str = "total",
        normal: NormalSpec = None,
        pitch: float = 0.0,
        centroid: CentroidSpec = None,
    ) -> None:
        defaults = {
            "depth_of_penetration": depth_of_penetration,
            "restitution": restitution,
            "friction": friction,
            "restitution_mode": restitution_mode,
            "normal": normal,
            "pitch": pitch,
            "centroid": centroid,
        }
        _check_contact(self._core_kwargs(defaults, None, check_only=True))
        self._defaults = defaults
        self._placements: list[_Placement] = []
        # (name1, name2) -> overridden parameters; the normal points from name1 into name2.
        self._overrides: dict[tuple[str, str], dict[str, Any]] = {}

    # -- vehicles ------------------------------------------------------------------------

    @property
    def vehicles(self) -> list[Vehicle]:
        """The vehicles, in the order added (the engine's body order)."""
        return [p.vehicle for p in self._placements]

    @property
    def defaults(self) -> dict[str, Any]:
        """The contact parameters every pair gets unless overridden."""
        return dict(self._defaults)

    def __iter__(self) -> Iterator[Vehicle]:
        return iter(self.vehicles)

    def __len__(self) -> int:
        return len(self._placements)

    def add(
        self,
        vehicle: Vehicle,
        position: ArrayLike,
        heading: float | None = None,
        velocity: ArrayLike = (0.0, 0.0, 0.0),
        angular_velocity: ArrayLike = (0.0, 0.0, 0.0),
        orientation: ArrayLike | None = None,
    ) -> Scene:
        """Place a vehicle; returns the scene (calls chain).

        position: the CG in the world (m). heading: yaw about world z (rad; 0 = body x along
        world x), or instead orientation: a quaternion (w, x, y, z) or a 3x3 rotation matrix
        (body -> world). velocity (m/s) and angular_velocity (rad/s): world frame.
        """
        if not isinstance(vehicle, Vehicle):
            raise TypeError(f"add() needs a crashsim.Vehicle, got {type(vehicle).__name__}")
        for p in self._placements:
            if p.vehicle is vehicle:
                raise SceneError(f"vehicle {vehicle.name!r} is already in the scene")
            if p.vehicle.name == vehicle.name:
                raise SceneError(
                    f"a vehicle named {vehicle.name!r} is already in the scene: names must be "
                    "unique (use vehicle.renamed(...) for a second copy)"
                )
        q = _orientation(heading, orientation)
        _check_state(position, q, velocity, angular_velocity)
        self._placements.append(
            _Placement(
                vehicle=vehicle,
                position=_read_only(position),
                orientation=_read_only(q),
                velocity=_read_only(velocity),
                angular_velocity=_read_only(angular_velocity),
            )
        )
        return self

    def _index(self, vehicle: VehicleRef) -> int:
        """Index of a vehicle (object or name) in the scene."""
        for i, p in enumerate(self._placements):
            if isinstance(vehicle, str):
                if p.vehicle.name == vehicle:
                    return i
            elif p.vehicle is vehicle:
                return i
        name = vehicle if isinstance(vehicle, str) else getattr(vehicle, "name", vehicle)
        known = [p.vehicle.name for p in self._placements]
        raise SceneError(
            f"vehicle {name!r} is not in the scene (it holds {known}): add it with scene.add"
        )

    # -- contact parameters --------------------------------------------------------------

    def contact(
        self,
        vehicle1: VehicleRef,
        vehicle2: VehicleRef,
        *,
        depth_of_penetration: float | Literal["auto"] | _Unset = UNSET,
        restitution: float | _Unset = UNSET,
        friction: float | _Unset = UNSET,
        restitution_mode: str | _Unset = UNSET,
        normal: NormalSpec | _Unset = UNSET,
        pitch: float | _Unset = UNSET,
        centroid: CentroidSpec | _Unset = UNSET,
    ) -> Scene:
        """Override parameters of one pair (vehicles or names); the rest keep the scene's
        defaults. The normal points from vehicle1 into vehicle2. Calling again for the same
        ordered pair adds to its overrides; calling with the pair reversed replaces them.
        Meanings and units are those of :class:`Scene`. Returns the scene."""
        i, j = self._index(vehicle1), self._index(vehicle2)
        if i == j:
            raise SceneError("a contact needs two different vehicles")
        names = (self._placements[i].vehicle.name, self._placements[j].vehicle.name)
        given = {
            "depth_of_penetration": depth_of_penetration,
            "restitution": restitution,
            "friction": friction,
            "restitution_mode": restitution_mode,
            "normal": normal,
            "pitch": pitch,
            "centroid": centroid,
        }
        overrides = dict(self._overrides.get(names, {}))
        overrides.update({k: v for k, v in given.items() if v is not UNSET})
        merged = {**self._defaults, **overrides}
        _check_contact(self._core_kwargs(merged, (i, j), check_only=True))
        _check_stiffness(merged, (self._placements[i].vehicle, self._placements[j].vehicle))
        self._overrides.pop((names[1], names[0]), None)
        self._overrides[names] = overrides
        return self

    def pairs(self) -> list[tuple[str, str, dict[str, Any]]]:
        """Every pair of vehicles as the engine gets it: (vehicle 1, vehicle 2, parameters),
        vehicle 1 being the one the normal points away from (the first argument of the last
        :meth:`contact` call for the pair, else the one added first)."""
        names = [p.vehicle.name for p in self._placements]
        out = []
        for i, j in combinations(range(len(names)), 2):
            a, b = names[i], names[j]
            if (b, a) in self._overrides:
                a, b = b, a
            out.append((a, b, {**self._defaults, **self._overrides.get((a, b), {})}))
        return out

    def contact_parameters(self, vehicle1: VehicleRef, vehicle2: VehicleRef) -> dict[str, Any]:
        """The parameters the pair will run with (defaults merged with overrides), as seen
        from vehicle1 (the normal points from vehicle1 into vehicle2 when set that way)."""
        i, j = self._index(vehicle1), self._index(vehicle2)
        names = (self._placements[i].vehicle.name, self._placements[j].vehicle.name)
        overrides = self._overrides.get(names, self._overrides.get(names[::-1], {}))
        return {**self._defaults, **overrides}

    def _core_kwargs(
        self, params: dict[str, Any], pair: tuple[int, int] | None, check_only: bool = False
    ) -> dict[str, Any]:
        """World.set_contact keywords for a pair of body indices (i, j). With check_only the
        body indices become 0 and 1 (the probe world of _check_contact); pair None means the
        scene defaults, before any vehicle is known."""
        dtp = params["depth_of_penetration"]
        kw: dict[str, Any] = {
            "depth_of_penetration": dtp
            if isinstance(dtp, str)
            else _as_float(dtp, "depth_of_penetration", "s"),
            "restitution": _as_float(params["restitution"], "restitution", "1"),
            "friction": _as_float(params["friction"], "friction", "1"),
            "restitution_mode": params["restitution_mode"],
            "pitch": _as_float(params["pitch"], "pitch", "rad"),
        }
        if not isinstance(kw["restitution_mode"], str):
            raise ParameterError(
                f'restitution_mode must be "total" or "normal", got {kw["restitution_mode"]!r}'
            )
        normal = params["normal"]
        if normal is None or (isinstance(normal, str) and normal == "horizontal"):
            kw["normal"] = "horizontal"
        elif isinstance(normal, str):
            if normal != "volume":
                raise ParameterError(
                    f"normal = {normal!r} is unknown: use None (horizontal, tilted by pitch), "
                    "'volume' (full 3-D) or a world vector (x, y, z)"
                )
            kw["normal"] = "volume"
        else:
            kw["normal"] = "vector"
            kw["normal_vector"] = normal
        centroid = params["centroid"]
        if centroid is None or (isinstance(centroid, str) and centroid == "auto"):
            kw["centroid"] = "auto"
        elif isinstance(centroid, str) and centroid == "stiffness":
            kw["centroid"] = "stiffness"
        elif (
            isinstance(centroid, tuple | list)
            and len(centroid) == 2
            and isinstance(centroid[0], Vehicle | str)
        ):
            if pair is None:  # a scene default fixed in a vehicle: checked per pair at run
                kw.update(centroid="world", centroid_point=centroid[1])
            else:
                body = self._index(centroid[0])
                if body not in pair:
                    a, b = (self._placements[k].vehicle.name for k in pair)
                    raise SceneError(
                        f"the centroid is fixed in {self._placements[body].vehicle.name!r}, "
                        f"which is not in the pair ({a!r}, {b!r}): fix it in one of the two"
                    )
                kw["centroid"] = "body"
                kw["centroid_body"] = pair.index(body) if check_only else body
                kw["centroid_point"] = centroid[1]
        elif isinstance(centroid, str):
            raise ParameterError(
                f"centroid = {centroid!r} is unknown: use None (automatic), 'stiffness', a world "
                "point (x, y, z) or (vehicle, (x, y, z)) fixed in a vehicle"
            )
        else:
            kw.update(centroid="world", centroid_point=centroid)
        return kw

    # -- running -------------------------------------------------------------------------

    def build_world(self) -> _core.World:
        """A fresh engine world holding this scene: bodies in the order added, and every pair
        with the defaults merged with its overrides."""
        if not self._placements:
            raise SceneError("the scene has no vehicles: add some with scene.add(...)")
        world = _core.World()
        for i, p in enumerate(self._placements):
            v = p.vehicle
            world.add_body(
                v.shape,
                v.mass,
                v.inertia,
                p.position,
                p.orientation,
                p.velocity,
                p.angular_velocity,
            )
            faces = v.stiffness
            world.set_stiffness(
                i,
                **{f: None if (s := faces.face(f)) is None else (s.A, s.B) for f in FACES},
            )
        for a, b, params in self.pairs():
            i, j = self._index(a), self._index(b)
            _check_stiffness(params, (self._placements[i].vehicle, self._placements[j].vehicle))
            world.set_contact(i, j, **self._core_kwargs(params, (i, j)))
        return world

    def run(
        self,
        duration: float = 1.0,
        dt: float = 1e-3,
        progress: Callable[[float], object] | None = None,
        record_interval: float | None = None,
        max_history_bytes: int | None = None,
    ) -> Result:
        """Run the scene from t = 0 for ``duration`` s with steps of at most ``dt`` s.

        Every call starts afresh from the initial states (a new engine world). Raises
        InitialOverlapError when two vehicles already overlap at t = 0. ``progress``, if
        given, is called with the simulated time reached (s) about every 0.1 s of wall time;
        it cannot change the results (an exception it raises stops the run).

        The result keeps every step's states unless the run is long: ``record_interval`` (s,
        rounded down to whole steps) spaces the kept samples (default: every step for runs
        of at most 100,000 steps, else about 100,000 samples); the start, the end, every
        first overlap and every exchange are kept whatever the interval. A run whose history
        would exceed ``max_history_bytes`` (default 2**30, 1 GiB) is refused before it starts
        with a ParameterError that gives the interval that fits."""
        duration = _as_float(duration, "duration", "s")
        dt = _as_float(dt, "dt", "s")
        if record_interval is not None:
            record_interval = _as_float(record_interval, "record_interval", "s")
        if max_history_bytes is not None and (
            isinstance(max_history_bytes, bool)
            or not isinstance(max_history_bytes, int | np.integer)
            or max_history_bytes < 1
        ):
            raise ParameterError(
                f"max_history_bytes = {max_history_bytes!r} is invalid: give a positive whole "
                "number of bytes (e.g. 2**30)"
            )
        world = self.build_world()
        try:
            raw = world.run(duration, dt, progress, record_interval, max_history_bytes)
        except InitialOverlapError as e:
            raise self._named_overlap_error(e) from e
        result = Result(
            raw,
            [p.vehicle.name for p in self._placements],
            scene=self,
            duration=duration,
            dt=dt,
            record_interval=float(raw["record_interval"]),
        )
        for imp in result.impacts:
            for note in imp.notes:
                warnings.warn(
                    f"{imp.vehicles[0]!r} - {imp.vehicles[1]!r} at t = {imp.time:.6f} s: {note}",
                    DepthOfPenetrationWarning,
                    stacklevel=2,
                )
        return result

    def _named_overlap_error(self, error: InitialOverlapError) -> InitialOverlapError:
        """The engine's error with the vehicles' names instead of body indices."""
        pairs = []
        for a, b in combinations(self._placements, 2):
            if _core.shapes_overlap(
                a.vehicle.shape,
                a.position,
                a.orientation,
                b.vehicle.shape,
                b.position,
                b.orientation,
            ):
                pairs.append(f"{a.vehicle.name!r} and {b.vehicle.name!r}")
        if not pairs:
            return error
        return InitialOverlapError(
            f"vehicles {', '.join(pairs)} already overlap at t = 0: place them apart (the "
            "engine starts every contact at a first overlap it observes)"
        )

    def __repr__(self) -> str:
        names = [p.vehicle.name for p in self._placements]
        return f"Scene(vehicles={names}, defaults={self._defaults})"
