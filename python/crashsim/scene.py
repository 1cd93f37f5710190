"""Scenes: vehicles with initial states, contact parameters per pair, and runs.

World frame: right-handed, z up, SI (m, s, rad). A vehicle's position is its CG's; heading is
the yaw of its body x axis from world x (rad, counter-clockwise seen from above); orientations
are quaternions (w, x, y, z) rotating body-frame vectors into the world.

Ranges (depth of penetration in [0, 0.060] s, restitution in [0, 1], friction >= 0, finite
states, ...) are checked by the engine itself, at the call that sets them, so the accepted
ranges and their messages live in one place (crates/crashsim-core).
"""

from __future__ import annotations

import dataclasses
import enum
import math
import re
import warnings
from collections.abc import Callable, Iterator, Mapping, Sequence
from dataclasses import dataclass
from itertools import combinations
from typing import Any, Literal, TypeAlias

import numpy as np
from numpy.typing import ArrayLike, NDArray

from crashsim import _core
from crashsim.environment.ground import Ground
from crashsim.environment.obstacles import Obstacle
from crashsim.errors import InitialOverlapError, ParameterError, SceneError, SimulationError
from crashsim.human.bicycle import Bicycle
from crashsim.human.cyclist import Cyclist
from crashsim.human.pedestrian import Pedestrian
from crashsim.joints import Joint, check_new, checked_frame, make_joint
from crashsim.result import Result, rotation_matrix
from crashsim.vehicles.checks import _as_float, _probe_shape
from crashsim.vehicles.coupling import JOINT_OF, check_coupling
from crashsim.vehicles.inputs import DriverInputs
from crashsim.vehicles.stiffness import FACES
from crashsim.vehicles.vehicle import Vehicle
from crashsim.vehicles.wheels import Wheels

__all__ = ["DEFAULT_MAX_DURATION", "DepthOfPenetrationWarning", "RestNotReachedWarning", "Scene"]

MAX_TRAILER_RATIO = 10.0
"""A trailer may weigh at most this many times the vehicle that tows it (a 7 t tractor with a
40 t semitrailer is 5.7): more is taken for a wrong mass."""

DEFAULT_MAX_DURATION = 60.0
"""Longest run (s) of ``Scene.run(until="rest")`` when no max_duration is given."""


class RestNotReachedWarning(UserWarning):
    """A run until rest ended at its max_duration with a vehicle still moving (its
    ``Result.rest`` is None): raise max_duration."""


class DepthOfPenetrationWarning(UserWarning):
    """An automatic depth of penetration outside the seed's typical 10-60 ms (or clamped to
    the accepted 60 ms): the report of that impact says so too."""


Array = NDArray[np.float64]
VehicleRef: TypeAlias = Vehicle | Obstacle | str
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


def _in_body(frame: tuple[Array, Array], placement: _Placement) -> tuple[Array, Array]:
    """A world frame (anchor, m; axes, quaternion w, x, y, z) in the body frame of a placed
    vehicle: what a joint keeps of it."""
    anchor, axes = frame
    rot = rotation_matrix(placement.orientation)
    local = _quaternion_from_matrix(rot.T @ rotation_matrix(axes))
    return rot.T @ (anchor - placement.position), local


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


def _position(position: ArrayLike, orientation: ArrayLike | None) -> tuple[Any, bool]:
    """(position, True) with z = 0 for now when only (x, y) is given (the caller puts it on
    the ground); the position as given otherwise (the engine checks it)."""
    try:
        p = np.asarray(position, dtype=np.float64).reshape(-1)
    except (TypeError, ValueError):
        return position, False
    if p.size == 2:
        if orientation is not None:
            raise ParameterError(
                "with an orientation give the position's x, y and z (m): only a heading "
                "leaves z to the ground"
            )
        return np.array([p[0], p[1], 0.0]), True
    return position, False


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
    inputs: DriverInputs | None = None
    # Given as (x, y): z is the CG's static height above the ground there (re-read when the
    # scene's ground changes; without a ground the model frame's ground on z = 0).
    z_from_ground: bool = False
    # The heading-only orientation and the (x, y) given (a vehicle on wheels on a terrain is
    # tilted to it, which moves its CG a little off (x, y)).
    level: Array | None = None
    anchor: tuple[float, float] | None = None


@dataclass(frozen=True)
class _ObstaclePlacement:
    """An obstacle and its pose (world frame, SI)."""

    obstacle: Obstacle
    position: Array  # the obstacle frame's origin, m
    orientation: Array  # (w, x, y, z)
    z_from_ground: bool = False


def _static_height(vehicle: Vehicle) -> float:
    """The CG's height above level ground at static ride height (m): its wheels', else the
    model frame's (ground at z = 0)."""
    w = vehicle.wheels
    if w is None:
        return float(vehicle.cg[2])
    if w.cg_height is not None:
        return float(w.cg_height)
    return float(np.mean(w.radii - w.centers[:, 2]))


def _check_state(position: Any, orientation: Any, velocity: Any, angular_velocity: Any) -> None:
    """The engine's checks of an initial state (ParameterError naming the bad input)."""
    _core.SceneSpec().add_body(
        _probe_shape(), 1.0, _EYE3, position, orientation, velocity, angular_velocity
    )


CONTACT_KEYS = (
    "depth_of_penetration",
    "restitution",
    "friction",
    "restitution_mode",
    "normal",
    "pitch",
    "centroid",
)
"""The seven contact parameters of a pair (meanings, units and ranges: :class:`Scene`)."""

_DEFAULTS = _core.ContactParams()
"""The engine's defaults of a pair's parameters (crates/crashsim-core/src/contact.rs)."""


def _needs_stiffness(params: dict[str, Any]) -> bool:
    return (
        isinstance(params["depth_of_penetration"], str) and params["depth_of_penetration"] == "auto"
    ) or (isinstance(params["centroid"], str) and params["centroid"] == "stiffness")


def _check_stiffness(
    params: dict[str, Any], vehicles: tuple[Vehicle | Obstacle, Vehicle | Obstacle]
) -> None:
    """ParameterError when the pair's parameters need face stiffness a vehicle lacks. An
    obstacle without any stiffness is rigid (the core's World::is_rigid)."""
    if not _needs_stiffness(params):
        return
    for v in vehicles:
        missing = [f for f in FACES if v.stiffness.face(f) is None]
        if missing:
            if isinstance(v, Obstacle):
                if len(missing) == len(FACES):
                    continue  # rigid: the vehicle's spring alone, no crush of its own
                raise ParameterError(
                    f"obstacle {v.name!r} has no stiffness on its {', '.join(missing)} "
                    'face(s): depth_of_penetration="auto" and centroid="stiffness" need CRASH3 '
                    "A and B on every face of an obstacle that has any: give them all (one "
                    "stiffness=(A, B) sets every face), or none for a rigid obstacle"
                )
            raise ParameterError(
                f"vehicle {v.name!r} has no stiffness on its {', '.join(missing)} face(s): "
                'depth_of_penetration="auto" and centroid="stiffness" need CRASH3 A and B on '
                "every face of both vehicles; give the vehicle stiffness=... (or build it from "
                "a vehicle class), or use a fixed depth of penetration and the automatic centroid"
            )



def _per_trailer(
    coupling: Mapping[str, Any] | Sequence[Mapping[str, Any] | None] | None, n: int
) -> list[Mapping[str, Any] | None]:
    """Scene.add's ``coupling`` as one entry per trailer: one mapping for every joint, or a
    sequence with one (or None) per trailer."""
    if coupling is None or isinstance(coupling, Mapping):
        return [coupling] * n
    if isinstance(coupling, str) or not isinstance(coupling, Sequence):
        raise SceneError(
            "coupling must be join's keywords (a dict) for every trailer, or a list of them "
            f"(or None) one per trailer, got {coupling!r}"
        )
    entries = list(coupling)
    if len(entries) != n:
        raise SceneError(
            f"coupling has {len(entries)} entries for {n} trailer(s): give one per trailer "
            "(None for the defaults), or one dict for all"
        )
    for k, entry in enumerate(entries):
        if entry is not None and not isinstance(entry, Mapping):
            raise SceneError(
                f"coupling[{k}] must be join's keywords (a dict) or None, got {entry!r}"
            )
    return entries

class Scene:
    """Vehicles with initial states, and the contact parameters of every pair.

    The keyword arguments are the defaults of every pair (override per pair with
    :meth:`contact`):

    - depth_of_penetration: s, in [0, 0.060]; the time from first overlap to the exchange.
      Or "auto": per impact dt_p = sqrt(m'/k') from the vehicles' effective masses along the
      normal at the centroid and the series stiffness k' of the struck faces (k = B W, W the
      overlap width), clamped to 60 ms; a DepthOfPenetrationWarning outside 10-60 ms. Needs
      face stiffness on both vehicles; an obstacle without any is rigid (k' = the vehicle's).
    - restitution: in [0, 1]. friction: inter-vehicle, >= 0.
    - restitution_mode: "total" (Kudlich-Slibar, on the whole compression impulse) or
      "normal" (Newton/Brach, on the normal relative velocity).
    - normal: None (horizontal part of the overlap's volume normal, tilted up by ``pitch``
      rad), "volume" (full 3-D) or a world vector; it points from vehicle 1 into vehicle 2.
    - centroid: None (centre of the overlap region), "stiffness" (that centre moved along
      the normal so the crush splits as C1 : C2 = k2 : k1; needs face stiffness; on the face
      of an obstacle without any, which is rigid: docs/glancing.md section 7), a world
      point (m), or ``(vehicle_or_name, (x, y, z))``, a point fixed in that vehicle's body
      frame (m from its CG).

    ``ground``: a :class:`crashsim.Ground` (or set ``scene.ground`` later): the vehicles then
    move under gravity on their wheels (:meth:`crashsim.Vehicle.with_wheels`; a vehicle
    without wheels slides on its body) with their driver inputs, and runs may go on until
    every vehicle is at rest. Without a ground every body moves torque-free between
    exchanges, exactly as before. Fixed obstacles are added with :meth:`add_obstacle`; they
    pair with every vehicle (never with each other) and take the pair parameters like one.
    """

    def __init__(
        self,
        depth_of_penetration: float | Literal["auto"] = float(_DEFAULTS.depth_of_penetration),
        restitution: float = _DEFAULTS.restitution,
        friction: float = _DEFAULTS.friction,
        restitution_mode: str = _DEFAULTS.restitution_mode,
        normal: NormalSpec = None,
        pitch: float = _DEFAULTS.pitch,
        centroid: CentroidSpec = None,
        ground: Ground | None = None,
    ) -> None:
        defaults = dict(
            zip(
                CONTACT_KEYS,
                (
                    depth_of_penetration,
                    restitution,
                    friction,
                    restitution_mode,
                    normal,
                    pitch,
                    centroid,
                ),
                strict=True,
            )
        )
        self._core_params(defaults, None)  # the engine's checks, at the call
        self._defaults = defaults
        self._placements: list[_Placement] = []
        self._obstacles: list[_ObstaclePlacement] = []
        # (name1, name2) -> overridden parameters; the normal points from name1 into name2.
        self._overrides: dict[tuple[str, str], dict[str, Any]] = {}
        self._ground: Ground | None = None
        self.ground = ground
        self._joints: list[Joint] = []
        # Pairs of vehicles (names) that never collide.
        self._no_contact: set[frozenset[str]] = set()
        # Pairs (names) with a compliant contact: (stiffness N/m, damping ratio).
        self._soft: dict[frozenset[str], tuple[float, float]] = {}
        # The pedestrians, cyclists and bicycles added, by name.
        self._pedestrians: dict[str, Pedestrian] = {}
        self._cyclists: dict[str, Cyclist | Bicycle] = {}
        # Where each was added: (position as given, heading rad, velocity m/s).
        self._pedestrian_places: dict[str, tuple[Array, float, Array]] = {}

    # -- ground and obstacles ------------------------------------------------------------

    @property
    def ground(self) -> Ground | None:
        """The ground (a :class:`crashsim.Ground`), or None: torque-free motion between
        exchanges. Setting it re-reads the heights of the vehicles and obstacles placed at
        (x, y) only."""
        return self._ground

    @ground.setter
    def ground(self, ground: Ground | None) -> None:
        if ground is not None and not isinstance(ground, Ground):
            raise SceneError(f"ground must be a crashsim.Ground or None, got {ground!r}")
        self._ground = ground
        self._placements = [
            p if not p.z_from_ground else self._resting(p) for p in self._placements
        ]
        self._obstacles = [p if not p.z_from_ground else self._grounded(p) for p in self._obstacles]

    def _ground_height(self, x: float, y: float, what: str) -> float:
        """The ground's height at (x, y) (0 without a ground); SceneError off the terrain."""
        if self._ground is None:
            return 0.0
        h = self._ground.height_at(x, y)
        if h is None:
            raise SceneError(
                f"{what} at ({x:.2f}, {y:.2f}) m has no ground under it: the terrain does not "
                "reach there (extend it, or place it on the terrain)"
            )
        return h

    def _resting(self, p: _Placement) -> _Placement:
        """p with its CG at its static height above the ground at its (x, y); a vehicle on
        wheels on a terrain is also tilted so its wheels stand on the plane fitted through
        the terrain's heights under them."""
        x, y = (float(p.position[0]), float(p.position[1])) if p.anchor is None else p.anchor
        what = f"vehicle {p.vehicle.name!r}"
        level = p.orientation if p.level is None else p.level
        wheels = p.vehicle.wheels
        h = _static_height(p.vehicle)
        if self._ground is None or self._ground.terrain is None or wheels is None:
            z = self._ground_height(x, y, what)
            return dataclasses.replace(
                p,
                position=_read_only([x, y, z + h]),
                orientation=level,
                level=level,
                anchor=(x, y),
            )
        yaw = rotation_matrix(level)
        feet = np.array([x, y]) + wheels.contact_points()[:, :2] @ yaw[:2, :2].T
        heights = []
        for k, (fx, fy) in enumerate(feet):
            height = self._ground.height_at(fx, fy)
            if height is None:
                raise SceneError(
                    f"{what} wheel {wheels.names[k]!r} at ({fx:.2f}, {fy:.2f}) m has no ground "
                    "under it: the terrain does not reach there (extend it, or place the "
                    "vehicle on it)"
                )
            heights.append(height)
        # the plane z = a + b x + c y through the ground under the wheels (least squares)
        design = np.c_[np.ones(len(feet)), feet]
        a, b, c = np.linalg.lstsq(design, np.asarray(heights), rcond=None)[0]
        n = np.array([-b, -c, 1.0]) / math.sqrt(b * b + c * c + 1.0)
        axis = np.cross([0.0, 0.0, 1.0], n)
        sin, cos = float(np.linalg.norm(axis)), float(n[2])
        tilt = np.eye(3)
        if sin > 0.0:
            k_ = axis / sin
            cross = np.array([[0, -k_[2], k_[1]], [k_[2], 0, -k_[0]], [-k_[1], k_[0], 0]])
            tilt = np.eye(3) + sin * cross + (1.0 - cos) * cross @ cross
        q = _quaternion_from_matrix(tilt @ yaw)
        cg = np.array([x, y, a + b * x + c * y]) + h * n
        return dataclasses.replace(
            p, position=_read_only(cg), orientation=_read_only(q), level=level, anchor=(x, y)
        )

    def _grounded(self, p: _ObstaclePlacement) -> _ObstaclePlacement:
        x, y = float(p.position[0]), float(p.position[1])
        z = self._ground_height(x, y, f"obstacle {p.obstacle.name!r}")
        return dataclasses.replace(p, position=_read_only([x, y, z]))

    @property
    def obstacles(self) -> list[Obstacle]:
        """The fixed obstacles, in the order added (the engine's bodies after the
        vehicles)."""
        return [p.obstacle for p in self._obstacles]

    def add_obstacle(
        self,
        obstacle: Obstacle,
        position: ArrayLike,
        heading: float | None = None,
        orientation: ArrayLike | None = None,
    ) -> Scene:
        """Place a fixed obstacle; returns the scene. ``position``: where its frame's origin
        (the middle of its base, for the primitives) goes (m, world); with (x, y) only, on
        the ground there (z = 0 without a ground). ``heading``: yaw of its frame about world
        z (rad), or ``orientation`` (quaternion (w, x, y, z) or 3x3 rotation)."""
        if not isinstance(obstacle, Obstacle):
            raise TypeError(
                f"add_obstacle() needs a crashsim.Obstacle, got {type(obstacle).__name__}"
            )
        self._check_name(obstacle.name, obstacle, "an obstacle")
        pos, flat = _position(position, orientation)
        q = _orientation(heading, orientation)
        try:
            _core.SceneSpec().add_obstacle(obstacle.shape, pos, q)
        except ParameterError as e:
            raise ParameterError(f"obstacle {obstacle.name!r}: {e}") from e
        placement = _ObstaclePlacement(obstacle, _read_only(pos), _read_only(q), flat)
        self._obstacles.append(self._grounded(placement) if flat else placement)
        return self

    def _check_name(self, name: str, thing: object, what: str) -> None:
        for p in self._placements:
            if p.vehicle is thing:
                raise SceneError(f"vehicle {name!r} is already in the scene")
        for o in self._obstacles:
            if o.obstacle is thing:
                raise SceneError(f"obstacle {name!r} is already in the scene")
        taken = [p.vehicle.name for p in self._placements]
        taken += [o.obstacle.name for o in self._obstacles]
        if name in taken:
            raise SceneError(
                f"{what} named {name!r} is already in the scene: names must be unique among "
                "vehicles and obstacles (use .renamed(...) for a second copy)"
            )

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
        vehicle: Vehicle | Pedestrian | Cyclist | Bicycle,
        position: ArrayLike,
        heading: float | None = None,
        velocity: ArrayLike = (0.0, 0.0, 0.0),
        angular_velocity: ArrayLike = (0.0, 0.0, 0.0),
        orientation: ArrayLike | None = None,
        inputs: DriverInputs | None = None,
        trailers: Sequence[Vehicle | tuple[Vehicle, DriverInputs | None]] = (),
        coupling: Mapping[str, Any] | Sequence[Mapping[str, Any] | None] | None = None,
    ) -> Scene:
        """Place a vehicle (and the trailers it tows); returns the scene (calls chain).

        position: the CG in the world (m); in a scene with a ground (set it first), (x, y)
        only (with a heading) puts the CG at its static height above the ground at (x, y):
        the wheels' CG height, else the model frame's ground (z = 0) on the ground; on a
        terrain a vehicle on wheels is also tilted to the plane fitted through the ground
        under its wheels (pitch and roll; the heading kept).
        heading: yaw about world z (rad; 0 = body x along world x), or instead orientation: a
        quaternion (w, x, y, z) or a 3x3 rotation matrix (body -> world). velocity (m/s) and
        angular_velocity (rad/s): world frame. inputs: the driver's
        (:class:`crashsim.DriverInputs`; needs wheels; used when the scene has a ground).
        trailers: the trailers it tows, in order (each a Vehicle with a ``coupler``, or
        ``(trailer, inputs)`` for its brakes): each is put in line behind the one before, its
        coupler on that one's ``hitch`` (crashsim.vehicles.coupling; a kingpin on a fifth
        wheel, a coupler on a ball; their heights within 5 cm), moving with it, and joined to
        it (a fifth-wheel or a spherical joint named "tower-trailer"; see :meth:`join`).
        coupling: :meth:`join`'s keywords for every trailer's joint (``limits``, e.g.
        {"articulation": (-1.5, 1.5)} rad, ``stiffness``, ``damping``, ``friction``,
        ``collide``), or a sequence of them, one per trailer in order (None: the defaults).

        A :class:`crashsim.Pedestrian` (needs a ground) is placed with its body frame's
        origin (on the ground midway between the feet) at ``position`` (x, y), or at the world
        point (x, y, z), facing ``heading``, every segment moving at ``velocity``: each segment
        is a vehicle named "<pedestrian>/<segment>", the segments joined by its joints (named
        the same way). A first version: docs/human.md lists what its contacts still lack.
        A :class:`crashsim.Cyclist` or :class:`crashsim.Bicycle` (needs a ground) is placed
        with its bicycle frame's origin (on the ground midway between the wheels' contact
        points) at ``position``, riding towards ``heading``, every body moving at
        ``velocity`` and the wheels rolling (docs/human.md, "The cyclist").
        """
        if isinstance(vehicle, Pedestrian):
            return self._add_pedestrian(vehicle, position, heading, velocity)
        if isinstance(vehicle, (Cyclist, Bicycle)):
            return self._add_bicycle(vehicle, position, heading, velocity)
        if not isinstance(vehicle, Vehicle):
            raise TypeError(f"add() needs a crashsim.Vehicle, got {type(vehicle).__name__}")
        self._check_name(vehicle.name, vehicle, "a vehicle")
        pos, flat = position, False
        if self._ground is not None:  # without a ground the engine wants x, y and z
            pos, flat = _position(position, orientation)
        q = _orientation(heading, orientation)
        _check_state(pos, q, velocity, angular_velocity)
        if inputs is not None:
            if not isinstance(inputs, DriverInputs):
                raise SceneError(f"inputs must be a crashsim.DriverInputs, got {inputs!r}")
            if vehicle.wheels is None:
                raise SceneError(
                    f"vehicle {vehicle.name!r} has driver inputs but no wheels: give it wheels "
                    "(vehicle.with_wheels(...)) or drop the inputs"
                )
            inputs.to_core(vehicle.wheels, f"vehicle {vehicle.name!r} inputs")
        placement = _Placement(
            vehicle=vehicle,
            position=_read_only(pos),
            orientation=_read_only(q),
            velocity=_read_only(velocity),
            angular_velocity=_read_only(angular_velocity),
            inputs=inputs,
            z_from_ground=flat,
        )
        couplings = _per_trailer(coupling, len(trailers))
        self._placements.append(self._resting(placement) if flat else placement)
        tower = self._placements[-1]
        for item, options in zip(trailers, couplings, strict=True):
            trailer, trailer_inputs = item if isinstance(item, tuple) else (item, None)
            if isinstance(trailer, Vehicle) and trailer.mass > MAX_TRAILER_RATIO * vehicle.mass:
                raise SceneError(
                    f"trailer {trailer.name!r} ({trailer.mass:.0f} kg) is more than "
                    f"{MAX_TRAILER_RATIO:g} times as heavy as {vehicle.name!r} ({vehicle.mass:.0f} "
                    "kg), which tows it: check both masses (kg)"
                )
            tower = self._tow(tower, trailer, trailer_inputs, dict(options or {}))
        return self

    def _add_pedestrian(
        self, pedestrian: Pedestrian, position: ArrayLike, heading: float | None,
        velocity: ArrayLike,
    ) -> Scene:
        """Places a pedestrian's segments and joins them (:meth:`add`)."""
        what = f"pedestrian {pedestrian.name!r}"
        if self._ground is None:
            raise SceneError(f"{what} needs a ground: set scene.ground = crashsim.Ground(...)")
        xy = np.asarray(position, dtype=np.float64).reshape(-1)[:2]
        ground = self._ground_height(float(xy[0]), float(xy[1]), what)
        h = 0.0 if heading is None else _as_float(heading, "heading", "rad")
        bodies, joints = pedestrian.placement(position, h, velocity, ground)
        for body, cg, rotation, v in bodies:
            self.add(body, cg, orientation=rotation, velocity=v)
        for j, at, axes, child_axes in joints:
            self.join(
                f"{pedestrian.name}/{j.parent}",
                f"{pedestrian.name}/{j.child}",
                at=at,
                kind=j.kind,
                axes=axes,
                limits=j.limits,
                stiffness=j.stiffness,
                damping=j.damping,
                friction=j.friction,
                name=f"{pedestrian.name}/{j.name}",
                axes2=child_axes,
            )
        # A passive body's segments never strike each other (the joints hold the neighbours).
        names = [body.name for body, *_ in bodies]
        self._pedestrians[pedestrian.name] = pedestrian
        self._pedestrian_places[pedestrian.name] = (_read_only(position), h, _read_only(velocity))
        joined = {frozenset((f"{pedestrian.name}/{j.parent}", f"{pedestrian.name}/{j.child}"))
                  for j, *_ in joints}  # fmt: skip
        for a, b in combinations(names, 2):
            if frozenset((a, b)) not in joined:
                self.no_contact(a, b)
        return self

    def _add_bicycle(
        self, thing: Cyclist | Bicycle, position: ArrayLike, heading: float | None,
        velocity: ArrayLike,
    ) -> Scene:
        """Places a cyclist's or a bicycle's bodies, joins them and sets their pairs (the
        rider's soft contacts with the frame, the pairs that never collide) (:meth:`add`)."""
        what = f"{type(thing).__name__.lower()} {thing.name!r}"
        if self._ground is None:
            raise SceneError(f"{what} needs a ground: set scene.ground = crashsim.Ground(...)")
        if thing.name in self._cyclists or thing.name in self._pedestrians:
            raise SceneError(f"{what} is already in the scene: names must be unique")
        xy = np.asarray(position, dtype=np.float64).reshape(-1)[:2]
        ground = self._ground_height(float(xy[0]), float(xy[1]), what)
        h = 0.0 if heading is None else _as_float(heading, "heading", "rad")
        parts = thing.placement(position, h, velocity, ground)
        for body, cg, rotation, v, w in parts.bodies:
            self.add(body, cg, orientation=rotation, velocity=v, angular_velocity=w)
        for j in parts.joints:
            j = dict(j)
            self.join(j.pop("vehicle1"), j.pop("vehicle2"), **j)
        for a, b in parts.no_contact:
            self.no_contact(a, b)
        for a, b, k, zeta, params in parts.soft:
            self.contact(a, b, **params)
            self.soft_contact(a, b, stiffness=k, damping_ratio=zeta)
        self._cyclists[thing.name] = thing
        return self

    def _tow(
        self,
        tower: _Placement,
        trailer: Vehicle,
        inputs: DriverInputs | None,
        coupling: dict[str, Any],
    ) -> _Placement:
        """Places ``trailer`` behind ``tower`` with its coupler on the tower's hitch, moving
        with it, and joins them; returns the trailer's placement."""
        if not isinstance(trailer, Vehicle):
            raise TypeError(f"a trailer must be a crashsim.Vehicle, got {type(trailer).__name__}")
        hitch, coupler = tower.vehicle.hitch, trailer.coupler
        check_coupling(tower.vehicle.name, hitch, trailer.name, coupler)
        assert hitch is not None and coupler is not None
        who = f"{tower.vehicle.name!r} towing {trailer.name!r}"
        rot = rotation_matrix(tower.orientation)
        at = tower.position + rot @ hitch.point
        position = at - rot @ coupler.point
        if self._ground is not None and trailer.wheels is not None:
            ground = self._ground_height(float(position[0]), float(position[1]), "a trailer")
            rest = ground + float(trailer.cg[2])  # its CG's height at static ride height
            if abs(position[2] - rest) > 0.05:
                raise SceneError(
                    f"{who}: the coupler stands {position[2] - rest:+.3f} m from its height at "
                    "rest over the hitch (at most 5 cm): give the trailer's coupler_height the "
                    f"hitch's height above the road, {at[2] - ground:.3f} m"
                )
        omega = np.asarray(tower.angular_velocity, dtype=np.float64)
        velocity = np.asarray(tower.velocity, dtype=np.float64) + np.cross(
            omega, position - tower.position
        )
        self.add(
            trailer,
            position,
            orientation=tower.orientation,
            velocity=velocity,
            angular_velocity=omega,
            inputs=inputs,
        )
        self.join(
            tower.vehicle.name,
            trailer.name,
            at=at,
            kind=JOINT_OF[coupler.kind],
            axes=tower.orientation,
            **coupling,
        )
        return self._placements[-1]

    def join(
        self,
        vehicle1: VehicleRef,
        vehicle2: VehicleRef | None = None,
        *,
        at: ArrayLike,
        kind: str = "spherical",
        axes: ArrayLike | None = None,
        limits: Mapping[str, tuple[float, float]] | None = None,
        stiffness: float = 0.0,
        damping: float = 0.0,
        friction: float = 0.0,
        collide: bool = False,
        name: str | None = None,
        axes2: ArrayLike | None = None,
    ) -> Scene:
        """Join two vehicles (``vehicle2`` None: ``vehicle1`` to the world) by a joint made
        where they stand at t = 0 (add them first); returns the scene (calls chain).

        ``at``: the anchor, a world point (m) (a tow ball, a kingpin). ``kind``:
        "spherical", "revolute", "fixed" or "fifth_wheel" (crashsim.joints). ``axes``: the
        joint frame's orientation (world, quaternion w, x, y, z, or a 3x3 rotation matrix;
        default ``vehicle1``'s orientation: x forward, y left, z up), a revolute joint
        turning about its z axis, a fifth wheel yawing about z and pitching about y.
        ``limits``: {angle name: (lower, upper)} rad ("angle"; "articulation", "pitch").
        ``stiffness`` N m/rad, ``damping`` N m s/rad, ``friction`` N m resist the free
        rotation. ``collide``: the two vehicles' meshes still collide with each other
        (default no). ``axes2``: a spherical joint's frame on ``vehicle2`` (world, at t = 0;
        default ``axes``): its swing is the angle between the two frames' z axes, so a cone
        (``limits={"swing": (0, half-angle)}``) about ``axes``'s z need not hold the start
        at its middle (a hip: flexion 125 deg, extension 30 deg). Needs a ground when the
        scene runs; the joined vehicles must start with velocities that agree (a trailer
        moving with its tractor)."""
        first = self._placement(vehicle1)
        second = None if vehicle2 is None else self._placement(vehicle2)
        names = (first.vehicle.name, None if second is None else second.vehicle.name)
        if names[0] == names[1]:
            raise SceneError(f"join() needs two different vehicles, got {names[0]!r} twice")
        label = name if name is not None else f"{names[0]}-{names[1] or 'world'}"
        q = first.orientation
        if axes is not None:
            try:  # a matrix made a quaternion, a quaternion checked by the engine, at the call
                q = _orientation(None, axes)
                _check_state(np.zeros(3), q, np.zeros(3), np.zeros(3))
            except ParameterError as e:
                raise ParameterError(f"joint {label!r}: axes: {e}") from e
        anchor, axes_q = checked_frame(label, at, q)
        world = (anchor, axes_q)
        world2 = world
        if axes2 is not None:
            if kind != "spherical":
                raise ParameterError(
                    f"joint {label!r}: axes2 is for a spherical joint (a {kind} joint's frames "
                    "coincide at the start): drop it"
                )
            try:
                q2 = _orientation(None, axes2)
                _check_state(np.zeros(3), q2, np.zeros(3), np.zeros(3))
            except ParameterError as e:
                raise ParameterError(f"joint {label!r}: axes2: {e}") from e
            world2 = checked_frame(label, at, q2)
        joint = make_joint(
            label,
            names,
            kind=kind,
            at=anchor,
            axes=axes_q,
            frames=(
                _in_body(world, first),
                world2 if second is None else _in_body(world2, second),
            ),
            limits=limits,
            stiffness=stiffness,
            damping=damping,
            friction=friction,
            collide=collide,
        )
        check_new(self._joints, joint)
        self._joints = [*self._joints, joint]
        return self

    @property
    def joints(self) -> list[Joint]:
        """The joints, in the order made."""
        return list(self._joints)

    @property
    def pedestrians(self) -> dict[str, Pedestrian]:
        """The pedestrians added (each one's segments are vehicles of the scene), by name."""
        return dict(self._pedestrians)

    @property
    def cyclists(self) -> dict[str, Cyclist]:
        """The cyclists added (each one's rider segments and bicycle bodies are vehicles of
        the scene), by name."""
        return {k: v for k, v in self._cyclists.items() if isinstance(v, Cyclist)}

    @property
    def bicycles(self) -> dict[str, Bicycle]:
        """The bicycles added on their own (a cyclist's is its ``bicycle``), by name."""
        return {k: v for k, v in self._cyclists.items() if isinstance(v, Bicycle)}

    def _placement(self, vehicle: VehicleRef) -> _Placement:
        i = self._index(vehicle)
        if i >= len(self._placements):
            raise SceneError(
                f"{self._bodies()[i].name!r} is a fixed obstacle: join the vehicle to the world "
                "instead (no second vehicle)"
            )
        return self._placements[i]

    def inputs(self, vehicle: VehicleRef) -> DriverInputs | None:
        """A vehicle's driver inputs (None without)."""
        i = self._index(vehicle)
        if i >= len(self._placements):
            raise SceneError("an obstacle has no driver inputs")
        return self._placements[i].inputs

    def _bodies(self) -> list[Vehicle | Obstacle]:
        """Vehicles then obstacles: the engine's bodies in order."""
        return [p.vehicle for p in self._placements] + [o.obstacle for o in self._obstacles]

    def _index(self, vehicle: VehicleRef) -> int:
        """The engine's index of a vehicle or obstacle (object or name) in the scene."""
        for i, b in enumerate(self._bodies()):
            if isinstance(vehicle, str):
                if b.name == vehicle:
                    return i
            elif b is vehicle:
                return i
        name = vehicle if isinstance(vehicle, str) else getattr(vehicle, "name", vehicle)
        known = [b.name for b in self._bodies()]
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
        bodies = self._bodies()
        n = len(self._placements)
        if i >= n and j >= n:
            raise SceneError("two obstacles never meet: a contact needs a vehicle")
        names = (bodies[i].name, bodies[j].name)
        if frozenset(names) in self._no_contact:
            raise SceneError(
                f"{names[0]!r} and {names[1]!r} never collide (scene.no_contact): they take no "
                "contact parameters"
            )
        given = dict(
            zip(
                CONTACT_KEYS,
                (
                    depth_of_penetration,
                    restitution,
                    friction,
                    restitution_mode,
                    normal,
                    pitch,
                    centroid,
                ),
                strict=True,
            )
        )
        overrides = dict(self._overrides.get(names, {}))
        overrides.update({k: v for k, v in given.items() if v is not UNSET})
        merged = {**self._defaults, **overrides}
        self._core_params(merged, (i, j))
        _check_stiffness(merged, (bodies[i], bodies[j]))
        self._overrides.pop((names[1], names[0]), None)
        self._overrides[names] = overrides
        return self

    def no_contact(self, vehicle1: VehicleRef, vehicle2: VehicleRef) -> Scene:
        """Make two vehicles (or a vehicle and an obstacle; objects or names) never collide:
        their meshes pass through each other, with no contact and no exchange, as joined
        vehicles do (a pedestrian's segments among themselves). Returns the scene."""
        i, j = self._index(vehicle1), self._index(vehicle2)
        if i == j:
            raise SceneError("no_contact needs two different vehicles")
        bodies = self._bodies()
        if i >= len(self._placements) and j >= len(self._placements):
            raise SceneError("two obstacles never meet: no_contact needs a vehicle")
        names = (bodies[i].name, bodies[j].name)
        if frozenset(names) in self._soft:
            raise SceneError(
                f"{names[0]!r} and {names[1]!r} have a soft contact (scene.soft_contact): a pair "
                "that never collides takes none"
            )
        if names in self._overrides or names[::-1] in self._overrides:
            raise SceneError(
                f"{names[0]!r} and {names[1]!r} have contact parameters (scene.contact): a pair "
                "that never collides takes none"
            )
        self._no_contact.add(frozenset(names))
        return self

    def soft_contact(
        self,
        vehicle1: VehicleRef | Pedestrian | Cyclist | Bicycle,
        vehicle2: VehicleRef | Pedestrian | Cyclist | Bicycle,
        stiffness: float,
        damping_ratio: float = 0.5,
    ) -> Scene:
        """Give a pair a compliant contact in place of the depth-of-penetration timer and the
        impulse exchange (docs/human.md, "Soft contacts"): while their meshes overlap, a
        normal force ``max(0, k d + c v)`` (``d`` the overlap's depth, m; ``v`` its closing
        speed, m/s; ``c = 2 damping_ratio sqrt(k m)``) acts at its centre of pressure with
        friction up to the pair's ``friction`` times it. ``stiffness`` k in N/m (up to 1e8),
        ``damping_ratio`` in [0, 2] (0.5: a head-on restitution of about 0.16). Either side
        may be a :class:`crashsim.Pedestrian` in the scene: every segment of it (a
        :class:`crashsim.Cyclist` or :class:`crashsim.Bicycle`: every body of it). The pair's
        normal and friction are its contact parameters (:meth:`contact`; ``normal="volume"``
        for contacts from above). The run refuses a step too long for the stiffness
        (``sqrt(k / m) dt`` above 0.2, m the lighter body's mass). Returns the scene."""
        k = _as_float(stiffness, "stiffness", "N/m")
        zeta = _as_float(damping_ratio, "damping_ratio", "1")
        _core.check_soft_contact(k, zeta)

        def names(v: VehicleRef | Pedestrian | Cyclist | Bicycle) -> list[str]:
            if isinstance(v, Pedestrian):
                return [s.name for s in v.segments]
            if isinstance(v, (Cyclist, Bicycle)):
                return [b.name for b in v.bodies]
            return [self._bodies()[self._index(v)].name]

        for a in names(vehicle1):
            for b in names(vehicle2):
                i, j = self._index(a), self._index(b)
                if i == j:
                    raise SceneError("a soft contact needs two different vehicles")
                if i >= len(self._placements) and j >= len(self._placements):
                    raise SceneError("two obstacles never meet: a soft contact needs a vehicle")
                if frozenset((a, b)) in self._no_contact:
                    raise SceneError(
                        f"{a!r} and {b!r} never collide (scene.no_contact): they take no soft "
                        "contact"
                    )
                self._soft[frozenset((a, b))] = (k, zeta)
        return self

    def pairs(self) -> list[tuple[str, str, dict[str, Any]]]:
        """Every pair of vehicles as the engine gets it: (vehicle 1, vehicle 2, parameters),
        vehicle 1 being the one the normal points away from (the first argument of the last
        :meth:`contact` call for the pair, else the one added first)."""
        names = [b.name for b in self._bodies()]
        n = len(self._placements)
        joined = {frozenset(j.vehicles) for j in self._joints if not j.core.collide}
        joined |= self._no_contact
        out = []
        for i, j in combinations(range(len(names)), 2):
            if i >= n and j >= n:
                continue  # two obstacles never meet
            a, b = names[i], names[j]
            if frozenset((a, b)) in joined:
                continue  # joined vehicles (and no-contact pairs) pass through each other
            if (b, a) in self._overrides:
                a, b = b, a
            out.append((a, b, {**self._defaults, **self._overrides.get((a, b), {})}))
        return out

    def contact_parameters(self, vehicle1: VehicleRef, vehicle2: VehicleRef) -> dict[str, Any]:
        """The parameters the pair will run with (defaults merged with overrides), as seen
        from vehicle1 (the normal points from vehicle1 into vehicle2 when set that way)."""
        i, j = self._index(vehicle1), self._index(vehicle2)
        bodies = self._bodies()
        names = (bodies[i].name, bodies[j].name)
        overrides = self._overrides.get(names, self._overrides.get(names[::-1], {}))
        return {**self._defaults, **overrides}

    def _core_params(
        self, params: dict[str, Any], pair: tuple[int, int] | None
    ) -> _core.ContactParams:
        """The engine's ContactParams of one pair (body indices (i, j)) from the scene's
        parameter values, checked by the engine (ParameterError naming the bad one). Pair None
        means the scene defaults, before any vehicle is known (a centroid fixed in a vehicle
        is then checked as a point; its vehicle when a pair takes it)."""
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
            and isinstance(centroid[0], Vehicle | Obstacle | str)
        ):
            if pair is None:  # a scene default fixed in a vehicle: checked per pair
                kw.update(centroid="world", centroid_point=centroid[1])
            else:
                body = self._index(centroid[0])
                if body not in pair:
                    bodies = self._bodies()
                    a, b = (bodies[k].name for k in pair)
                    raise SceneError(
                        f"the centroid is fixed in {bodies[body].name!r}, "
                        f"which is not in the pair ({a!r}, {b!r}): fix it in one of the two"
                    )
                kw.update(centroid="body", centroid_body=body, centroid_point=centroid[1])
        elif isinstance(centroid, str):
            raise ParameterError(
                f"centroid = {centroid!r} is unknown: use None (automatic), 'stiffness', a world "
                "point (x, y, z) or (vehicle, (x, y, z)) fixed in a vehicle"
            )
        else:
            kw.update(centroid="world", centroid_point=centroid)
        return _core.ContactParams(**kw)

    # -- running -------------------------------------------------------------------------

    def to_spec(
        self,
        duration: float | None = None,
        dt: float = 1e-3,
        *,
        until: Literal["rest"] | None = None,
        max_duration: float | None = None,
        record_interval: float | None = None,
        max_history_bytes: int | None = None,
    ) -> _core.SceneSpec:
        """The scene as the engine's value (``_core.SceneSpec``): vehicles in the order added
        (with their names), then the obstacles, every pair in :meth:`pairs` order with the
        defaults merged with its overrides, face stiffness, and, with a ground, the ground and
        each vehicle's wheels, tyre and driver inputs; the run's options as :meth:`run` takes
        them. The one path from a scene to the engine: :meth:`run` and
        :func:`crashsim.batch.run_batch` run this value. It serialises
        (``to_json()``, ``_core.SceneSpec.from_json``) and pickles."""
        settings = self._run_settings(
            duration, dt, until, max_duration, record_interval, max_history_bytes
        )
        if not self._placements:
            raise SceneError("the scene has no vehicles: add some with scene.add(...)")
        spec = _core.SceneSpec()
        for p in self._placements:
            v = p.vehicle
            spec.add_body(
                v.shape,
                v.mass,
                v.inertia,
                p.position,
                p.orientation,
                p.velocity,
                p.angular_velocity,
                name=v.name,
            )
        for o in self._obstacles:
            spec.add_obstacle(o.obstacle.shape, o.position, o.orientation, name=o.obstacle.name)
        bodies = self._bodies()
        for i, b in enumerate(bodies):
            faces = b.stiffness
            spec.set_stiffness(
                i,
                **{f: None if (s := faces.face(f)) is None else (s.A, s.B) for f in FACES},
            )
        for a, b, params in self.pairs():
            i, j = self._index(a), self._index(b)
            _check_stiffness(params, (bodies[i], bodies[j]))
            spec.set_contact(i, j, self._core_params(params, (i, j)))
        for pair in sorted(tuple(sorted(self._index(n) for n in p)) for p in self._no_contact):
            spec.set_no_contact(*pair)
        for names, (k, zeta) in self._soft.items():
            a, b = sorted(self._index(n) for n in names)
            spec.set_soft_contact(a, b, k, zeta)
        if self._ground is not None:
            spec.set_ground(**self._ground.core_kwargs())
            for i, p in enumerate(self._placements):
                w = p.vehicle.wheels
                if w is None:
                    continue
                self._check_terrain_under(p, w)
                what = f"vehicle {p.vehicle.name!r}"
                inputs = {} if p.inputs is None else p.inputs.to_core(w, f"{what} inputs")
                try:
                    # the inputs' steering ratio (if given) replaces the wheels'
                    spec.set_vehicle(i, **{**w.spec(p.vehicle.mass), **inputs})
                except ParameterError as e:  # pragma: no cover - checked when put together
                    raise ParameterError(f"{what}: {e}") from e
        for joint in self._joints:
            a, b = joint.vehicles
            spec.add_joint(
                joint.core,
                self._index(a),
                None if b is None else self._index(b),
                joint.frames[0],
                joint.frames[1],
                name=joint.name,
            )
        duration_s, dt_s, until_rest, interval, max_bytes = settings
        spec.set_run(
            duration_s,
            dt_s,
            record_interval=interval,
            max_history_bytes=max_bytes,
            until_rest=until_rest,
        )
        return spec

    def build_world(self) -> _core.World:
        """A fresh engine world holding this scene (``to_spec().build()``)."""
        return self.to_spec().build()

    def _run_settings(
        self,
        duration: float | None,
        dt: float,
        until: str | None,
        max_duration: float | None,
        record_interval: float | None,
        max_history_bytes: int | None,
    ) -> tuple[float, float, bool, float | None, int | None]:
        """(duration s, dt s, until rest, record_interval s, max_history_bytes) of a run,
        checked as :meth:`run` documents."""
        if until is not None and until != "rest":
            raise ParameterError(f'until = {until!r} is unknown: use until="rest" or a duration')
        if until == "rest":
            if self._ground is None:
                raise SceneError(
                    "a run until rest needs a ground (without one nothing slows the vehicles): "
                    "set scene.ground = crashsim.Ground(...)"
                )
            if duration is not None and max_duration is not None:
                raise ParameterError('with until="rest" give max_duration (or duration), not both')
            limit = max_duration if max_duration is not None else duration
            duration = DEFAULT_MAX_DURATION if limit is None else limit
        elif max_duration is not None:
            raise ParameterError('max_duration is for until="rest": give duration instead')
        duration = _as_float(1.0 if duration is None else duration, "duration", "s")
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
        if max_history_bytes is not None:
            max_history_bytes = int(max_history_bytes)
        return duration, dt, until == "rest", record_interval, max_history_bytes

    def _check_terrain_under(self, p: _Placement, wheels: Wheels) -> None:
        """SceneError when a wheel starts over a hole in the terrain."""
        ground = self._ground
        if ground is None or ground.terrain is None:
            return
        r = rotation_matrix(p.orientation)
        points = p.position + wheels.contact_points() @ r.T
        for k in ground.holes(points):
            x, y = points[k][:2]
            raise SceneError(
                f"vehicle {p.vehicle.name!r} wheel {wheels.names[k]!r} starts at "
                f"({x:.2f}, {y:.2f}) m where the terrain has no surface: extend the terrain "
                "under the vehicle, or move the vehicle onto it"
            )

    def run(
        self,
        duration: float | None = None,
        dt: float = 1e-3,
        progress: Callable[[float], object] | None = None,
        record_interval: float | None = None,
        max_history_bytes: int | None = None,
        *,
        until: Literal["rest"] | None = None,
        max_duration: float | None = None,
    ) -> Result:
        """Run the scene from t = 0 for ``duration`` s (default 1 s) with steps of at most
        ``dt`` s; or, with ``until="rest"`` (needs a ground), until every vehicle is at rest
        (the engine's rest thresholds, ``crashsim.vehicles.wheels.dynamics_defaults()``) or
        ``max_duration`` s have passed (default DEFAULT_MAX_DURATION, 60 s; ``duration`` may
        stand for it), with a RestNotReachedWarning when a vehicle is still moving then.

        Every call starts afresh from the initial states (a new engine world). Raises
        InitialOverlapError when two bodies already overlap at t = 0, SceneError when a wheel
        starts over a hole in a terrain, SimulationError (naming the vehicle and wheel) when a
        wheel leaves the terrain during the run. ``progress``, if given, is called with the
        simulated time reached (s) about every 0.1 s of wall time; it cannot change the
        results (an exception it raises stops the run; so does Ctrl-C).

        The result keeps every step's states unless the run is long: ``record_interval`` (s,
        rounded down to whole steps) spaces the kept samples (default: every step for runs
        of at most 100,000 steps, else about 100,000 samples); the start, the end, every
        first overlap and every exchange are kept whatever the interval. A run whose history
        would exceed ``max_history_bytes`` (default 2**30, 1 GiB) is refused before it starts
        with a ParameterError that gives the interval that fits."""
        spec = self.to_spec(
            duration,
            dt,
            until=until,
            max_duration=max_duration,
            record_interval=record_interval,
            max_history_bytes=max_history_bytes,
        )
        duration, dt, _ = spec.run_options
        try:
            raw = spec.run(progress)
        except InitialOverlapError as e:
            raise self._named_overlap_error(e) from e
        except SimulationError as e:
            raise self._named_simulation_error(e) from e
        result = Result(
            raw,
            [b.name for b in self._bodies()],
            scene=self,
            duration=duration,
            dt=dt,
            record_interval=float(raw["record_interval"]),
            obstacles=[o.obstacle.name for o in self._obstacles],
            wheel_names={
                p.vehicle.name: p.vehicle.wheels.names
                for p in self._placements
                if p.vehicle.wheels is not None
            },
            on_ground=self._ground is not None,
            joints=self._joints,
        )
        for imp in result.impacts:
            for note in imp.notes:
                warnings.warn(
                    f"{imp.vehicles[0]!r} - {imp.vehicles[1]!r} at t = {imp.time:.6f} s: {note}",
                    DepthOfPenetrationWarning,
                    stacklevel=2,
                )
        if until == "rest":
            moving = [n for n in result.vehicles if result.rest(n) is None]
            if moving:
                warnings.warn(
                    f"the run reached max_duration = {duration:g} s with {moving} still "
                    "moving: their rest is None; raise max_duration",
                    RestNotReachedWarning,
                    stacklevel=2,
                )
        return result

    def _named_simulation_error(self, error: SimulationError) -> SimulationError:
        """The engine's error with the vehicle's and wheel's names ("body i: wheel k left the
        terrain ...": the bodies are the placements in order)."""
        m = re.match(r"body (\d+): wheel (\d+) left the terrain (.*)", str(error), re.DOTALL)
        if m is None:
            return error
        i, k = int(m.group(1)), int(m.group(2))
        if i >= len(self._placements):
            return error
        vehicle = self._placements[i].vehicle
        wheel = vehicle.wheels.names[k] if vehicle.wheels is not None else f"wheel {k}"
        return SimulationError(f"vehicle {vehicle.name!r} ({wheel}) left the terrain {m.group(3)}")

    def _named_overlap_error(self, error: InitialOverlapError) -> InitialOverlapError:
        """The engine's error with the vehicles' names instead of body indices."""
        m = re.match(r"body (\d+) starts (.*)", str(error), re.DOTALL)
        if m is not None and int(m.group(1)) < len(self._placements):
            name = self._placements[int(m.group(1))].vehicle.name
            return InitialOverlapError(f"vehicle {name!r} starts {m.group(2)}")
        pairs = []
        placed = [(p.vehicle, p.position, p.orientation) for p in self._placements]
        placed += [(o.obstacle, o.position, o.orientation) for o in self._obstacles]
        # Only the pairs the engine searches (joined and no-contact ones pass through).
        searched = {frozenset(p[:2]) for p in self.pairs()}
        for a, b in combinations(placed, 2):
            if frozenset((a[0].name, b[0].name)) not in searched:
                continue
            if _core.shapes_overlap(a[0].shape, a[1], a[2], b[0].shape, b[1], b[2]):
                pairs.append(f"{a[0].name!r} and {b[0].name!r}")
        if not pairs:
            return error
        return InitialOverlapError(
            f"vehicles {', '.join(pairs)} already overlap at t = 0: place them apart (the "
            "engine starts every contact at a first overlap it observes)"
        )

    def with_(self, changes: Mapping[str, Any] | None = None, /, **more: Any) -> Scene:
        """A new Scene with some inputs changed, named by parameter paths (SI):
        ``scene.with_({"red.speed": 20.0, "red.heading": 0.1, "restitution": 0.2})`` or
        ``scene.with_(restitution=0.2)``; this scene is unchanged. The paths and their rules
        are crashsim.studies.paths's (StudyError for an unknown one, listing the valid ones);
        the new scene runs bit for bit as that variant of a study's batch does."""
        from crashsim.studies.paths import with_

        return with_(self, {**(changes or {}), **more})

    def __repr__(self) -> str:
        names = [p.vehicle.name for p in self._placements]
        extra = ""
        if self._obstacles:
            extra += f", obstacles={[o.obstacle.name for o in self._obstacles]}"
        if self._ground is not None:
            extra += f", ground={self._ground!r}"
        return f"Scene(vehicles={names}{extra}, defaults={self._defaults})"
