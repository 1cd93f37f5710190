"""Scenes: vehicles with initial states, contact parameters per pair, and runs.

World frame: right-handed, z up, SI (m, s, rad). A vehicle's position is its CG's; heading is
the yaw of its body x axis from world x (rad, counter-clockwise seen from above); orientations
are quaternions (w, x, y, z) rotating body-frame vectors into the world.

Ranges (depth of penetration in [0, 0.060] s, restitution in [0, 1], friction >= 0, finite
states, ...) are checked by the engine itself, at the call that sets them, so the accepted
ranges and their messages live in one place (crates/crashsim-core).
"""

from __future__ import annotations

import copy
import math
import warnings
from collections.abc import Callable, Iterator, Mapping, Sequence
from typing import Any, Literal

import numpy as np
from numpy.typing import ArrayLike, NDArray

from crashsim import _core
from crashsim.contacts import (
    _DEFAULTS,
    CONTACT_KEYS,
    CentroidSpec,
    NormalSpec,
    VehicleRef,
    _core_params,
)
from crashsim.environment.ground import Ground
from crashsim.environment.obstacles import Obstacle
from crashsim.errors import (
    CrashsimError,
    InitialOverlapError,
    ParameterError,
    SceneError,
    renamed,
)
from crashsim.errors import at as error_at
from crashsim.human.bicycle import Bicycle
from crashsim.human.cyclist import Cyclist
from crashsim.human.pedestrian import Pedestrian
from crashsim.joints import Joint, PassiveMoment, check_new, checked_frame, make_joint
from crashsim.people import _People
from crashsim.placement import (
    Placement,
    _check_state,
    _ground_height,
    _grounded,
    _in_body,
    _ObstaclePlacement,
    _orientation,
    _position,
    _read_only,
    _resting,
)
from crashsim.records import rotation_matrix
from crashsim.result import Result
from crashsim.small_linalg import matmul, norm
from crashsim.spec import (
    DEFAULT_MAX_DURATION,
    _build_spec,
    _named_overlap_error,
    _run_settings,
    _scene_naming,
)
from crashsim.vehicles.coupling import JOINT_OF, check_coupling
from crashsim.vehicles.inputs import DriverInputs
from crashsim.vehicles.vehicle import Vehicle

# Pickles of scenes made while _Placement and _ObstaclePlacement lived here name them
# crashsim.scene._Placement (._ObstaclePlacement): these names keep those loading.
_Placement = Placement

__all__ = ["DEFAULT_MAX_DURATION", "DepthOfPenetrationWarning", "RestNotReachedWarning", "Scene"]

MAX_TRAILER_RATIO = 10.0
"""A trailer may weigh at most this many times the vehicle that tows it (a 7 t tractor with a
40 t semitrailer is 5.7): more is taken for a wrong mass."""


class RestNotReachedWarning(UserWarning):
    """A run until rest ended at its max_duration with a vehicle still moving (its
    ``Result.rest`` is None): raise max_duration. The message gives each such body's CG
    speed and angular speed at the end (a person's limb toppling slowly about its joint
    against a car still sliding)."""


def _end_speeds(result: Result, names: list[str]) -> str:
    """Each body's CG speed (m/s) and angular speed (deg/s) at the run's end, as a
    RestNotReachedWarning shows them (a crawling limb of a person against a sliding car)."""
    parts = []
    for name in names:
        trajectory = result.trajectory(name)
        speed = float(norm(trajectory.velocity[-1]))
        turn = math.degrees(float(norm(trajectory.angular_velocity[-1])))
        parts.append(f"{name}: {speed:.3g} m/s, {turn:.3g} deg/s")
    return "; ".join(parts) + " at the end"


class DepthOfPenetrationWarning(UserWarning):
    """An automatic depth of penetration outside the seed's typical 10-60 ms (or clamped to
    the accepted 60 ms): the report of that impact says so too."""


Array = NDArray[np.float64]


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


class Scene(_People):
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
        _core_params(defaults, None, self._index, self._bodies)  # the engine's checks, at the call
        self._defaults = defaults
        self._placements: list[Placement] = []
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
            p if not p.z_from_ground else _resting(self._ground, p) for p in self._placements
        ]
        self._obstacles = [
            p if not p.z_from_ground else _grounded(self._ground, p) for p in self._obstacles
        ]

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
            _core.check_pose(pos, q)
        except ParameterError as e:
            raise error_at(e, ("part", None, f"obstacle {obstacle.name!r}")) from e
        placement = _ObstaclePlacement(obstacle, _read_only(pos), _read_only(q), flat)
        self._obstacles.append(_grounded(self._ground, placement) if flat else placement)
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
        placement = Placement(
            vehicle=vehicle,
            position=_read_only(pos),
            orientation=_read_only(q),
            velocity=_read_only(velocity),
            angular_velocity=_read_only(angular_velocity),
            inputs=inputs,
            z_from_ground=flat,
        )
        couplings = _per_trailer(coupling, len(trailers))
        self._placements.append(_resting(self._ground, placement) if flat else placement)
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

    def _tow(
        self,
        tower: Placement,
        trailer: Vehicle,
        inputs: DriverInputs | None,
        coupling: dict[str, Any],
    ) -> Placement:
        """Places ``trailer`` behind ``tower`` with its coupler on the tower's hitch, moving
        with it, and joins them; returns the trailer's placement."""
        if not isinstance(trailer, Vehicle):
            raise TypeError(f"a trailer must be a crashsim.Vehicle, got {type(trailer).__name__}")
        hitch, coupler = tower.vehicle.hitch, trailer.coupler
        check_coupling(tower.vehicle.name, hitch, trailer.name, coupler)
        assert hitch is not None and coupler is not None
        who = f"{tower.vehicle.name!r} towing {trailer.name!r}"
        rot = rotation_matrix(tower.orientation)
        at = tower.position + matmul(rot, hitch.point)
        position = at - matmul(rot, coupler.point)
        if self._ground is not None and trailer.wheels is not None:
            ground = _ground_height(
                self._ground, float(position[0]), float(position[1]), "a trailer"
            )
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
        passive: Mapping[str, PassiveMoment] | None = None,
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
        at its middle (a hip: flexion 125 deg, extension 30 deg). ``passive``: {angle name:
        crashsim.PassiveMoment}, a nonlinear moment about that angle (a hinge's "angle", a
        fifth wheel's "articulation" or "pitch", a ball joint's rotation-vector components
        "x", "y", "z" in its frame; docs/joints.md, "Passive moments"). Needs a ground when the
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
                where = ("part", None, f"joint {label!r}")
                raise error_at(error_at(e, ("part", None, "axes")), where) from e
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
                where = ("part", None, f"joint {label!r}")
                raise error_at(error_at(e, ("part", None, "axes2")), where) from e
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
            passive=passive,
        )
        check_new(self._joints, joint)
        self._joints = [*self._joints, joint]
        return self

    @property
    def joints(self) -> list[Joint]:
        """The joints, in the order made."""
        return list(self._joints)

    @property
    def placements(self) -> tuple[Placement, ...]:
        """Each vehicle (a pedestrian's segments and a bicycle's parts among them) with its
        initial state, in the order added; obstacles are not placements."""
        return tuple(self._placements)

    def _placement(self, vehicle: VehicleRef) -> Placement:
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
        settings = _run_settings(
            self._ground, duration, dt, until, max_duration, record_interval, max_history_bytes
        )
        if not self._placements:
            raise SceneError("the scene has no vehicles: add some with scene.add(...)")
        return _build_spec(
            placements=self._placements,
            obstacles=self._obstacles,
            bodies=self._bodies(),
            pairs=self.pairs(),
            no_contact=self._no_contact,
            soft=self._soft,
            ground=self._ground,
            joints=self._joints,
            index=self._index,
            settings=settings,
            ground_friction=self._ground_frictions(),
        )

    def build_world(self) -> _core.World:
        """A fresh engine world holding this scene (``to_spec().build()``)."""
        return self.to_spec().build()

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
            raise _named_overlap_error(e, self._placements, self._obstacles, self.pairs) from e
        except CrashsimError as e:
            raise renamed(e, _scene_naming(self._placements, self._obstacles)) from e
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
                    f"moving ({_end_speeds(result, moving)}): their rest is None; raise "
                    "max_duration",
                    RestNotReachedWarning,
                    stacklevel=2,
                )
        return result

    def with_(self, changes: Mapping[str, Any] | None = None, /, **more: Any) -> Scene:
        """A new Scene with some inputs changed, named by parameter paths (SI):
        ``scene.with_({"red.speed": 20.0, "red.heading": 0.1, "restitution": 0.2})`` or
        ``scene.with_(restitution=0.2)``; this scene is unchanged. The paths and their rules
        are crashsim.studies.paths's (StudyError for an unknown one, listing the valid ones);
        the new scene runs bit for bit as that variant of a study's batch does."""
        from crashsim.studies.paths import with_

        return with_(self, {**(changes or {}), **more})

    def _varied(
        self,
        placements: list[Placement],
        pair_changes: Mapping[tuple[str, str], Mapping[str, Any]],
        ground: Ground | None = None,
    ) -> Scene:
        """A copy of this scene for one variant of a study (crashsim.studies.paths): the same
        vehicles, meshes and engine shapes, with these placements, the pairs' contact
        parameters changed by ``pair_changes`` ({(a, b) as Scene.pairs names them: {parameter:
        value}}), and ``ground`` when given. Nothing is checked here: the engine checks the
        values when the variant runs, as the batch does."""
        new = copy.copy(self)
        new._placements = placements
        new._overrides = {k: dict(v) for k, v in self._overrides.items()}
        for pair, changes in pair_changes.items():
            new._overrides.setdefault(pair, {}).update(changes)
        if ground is not None:
            new._ground = ground
        return new

    def __repr__(self) -> str:
        names = [p.vehicle.name for p in self._placements]
        extra = ""
        if self._obstacles:
            extra += f", obstacles={[o.obstacle.name for o in self._obstacles]}"
        if self._ground is not None:
            extra += f", ground={self._ground!r}"
        return f"Scene(vehicles={names}{extra}, defaults={self._defaults})"
