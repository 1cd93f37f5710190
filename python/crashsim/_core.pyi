"""Type stub of the compiled engine module ``crashsim._core`` (crates/crashsim-py).

Everything here is SI (m, kg, s, rad, N s). Frames: world is right-handed with z up;
a body frame has its origin at the body's centre of gravity (ISO 8855: x forward,
y left, z up). Quaternions are (w, x, y, z) and rotate body-frame vectors into the world.
Users should not need this module: the public API is ``crashsim.Scene``.
"""

from collections.abc import Callable, Sequence
from typing import Any, NotRequired, TypedDict, Unpack, final

import numpy as np
from numpy.typing import ArrayLike, NDArray

__version__: str
__all__ = [
    "ContactParams",
    "CrashsimError",
    "InitialOverlapError",
    "InputError",
    "Joint",
    "MeshError",
    "ParameterError",
    "SceneSpec",
    "Shape",
    "SimulationError",
    "World",
    "__version__",
    "Tyre",
    "Ground",
    "check_soft_contact",
    "dynamics_defaults",
    "free_motion",
    "overlap_region",
    "run_batch",
    "shapes_overlap",
    "solid_properties",
    "static_loads",
    "suspension",
    "wheel_loads",
    "check_table",
    "check_friction_zone",
    "check_ground_friction",
    "check_brake",
    "check_wheel_switch",
    "check_steering_ratio",
    "check_face_stiffness",
    "point_in_polygon",
    "check_mass",
    "check_state",
    "check_pose",
    "check_contact_stiffness",
    "check_vehicle",
    "describe_place",
]

class CrashsimError(Exception):
    """Root of every error the engine raises. ``loc``: where it happened, outermost first,
    (kind, index, name) places; ``message``: the text without the places (None when the
    engine gave no places)."""

    loc: tuple[tuple[Any, Any, Any], ...]
    message: str | None

class InputError(CrashsimError, ValueError):
    """The input is at fault (a value, a mesh, a parameter)."""

class MeshError(InputError):
    """A mesh is empty, has non-finite vertices or out-of-range triangle indices."""

class ParameterError(InputError):
    """A number is non-finite or outside its accepted range."""

class InitialOverlapError(InputError):
    """Two bodies of a contact pair overlap when the run starts."""

class SimulationError(CrashsimError, RuntimeError):
    """The engine could not complete a run (an internal limit was hit)."""

@final
class Shape:
    """An immutable triangle mesh in a body frame (m) with its bounding-volume hierarchy."""

    def __new__(cls, vertices: ArrayLike, triangles: ArrayLike) -> Shape:
        """vertices: (n, 3) float64 in the body frame; triangles: (m, 3) integer indices."""
    @property
    def n_vertices(self) -> int: ...
    @property
    def n_triangles(self) -> int: ...
    @property
    def vertices(self) -> NDArray[np.float64]: ...
    @property
    def triangles(self) -> NDArray[np.uint32]: ...
    def __reduce__(
        self,
    ) -> tuple[type[Shape], tuple[NDArray[np.float64], NDArray[np.uint32]]]:
        """Pickled as its vertices and triangles (the rebuilt hierarchy is the same)."""
    def aabb(self) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
        """(mins, maxs) of the vertices, body frame."""
    def solid_properties(self) -> dict[str, Any]:
        """The mesh as a uniform solid of unit density, body frame: ``volume`` (m^3, signed:
        positive for an outward-wound closed mesh), ``centroid`` (3,) m, ``inertia`` (3, 3)
        about the centroid (kg m^2 per kg/m^3). Meaningful for closed meshes only."""
    def ray_hits(
        self, origin: ArrayLike, direction: ArrayLike, max_distance: float = ...
    ) -> NDArray[np.float64]:
        """Distances (m, ascending) at which the ray from origin along direction (body frame)
        crosses the mesh, up to max_distance (default: no limit); a shared edge counts once."""
    def winding_numbers(self, points: ArrayLike) -> NDArray[np.float64]:
        """Generalized winding number of each body-frame point, (k,). About 1 inside, 0 outside."""

def check_soft_contact(stiffness: float, damping_ratio: float) -> None:
    """Checks a soft contact's stiffness (N/m) and damping ratio (ParameterError)."""

def shapes_overlap(
    shape1: Shape,
    position1: ArrayLike,
    orientation1: ArrayLike,
    shape2: Shape,
    position2: ArrayLike,
    orientation2: ArrayLike,
) -> bool:
    """True when the two posed meshes' surfaces intersect or one lies inside the other."""

def overlap_region(
    shape1: Shape,
    position1: ArrayLike,
    orientation1: ArrayLike,
    shape2: Shape,
    position2: ArrayLike,
    orientation2: ArrayLike,
) -> dict[str, Any]:
    """The overlap region S of DESIGN.md section 1 for two posed meshes (world frame).

    Keys: ``points`` (k, 3) the set S; ``volume_normal`` (3,) the unit area-weighted
    normal from body 1 into body 2 (zeros if undefined); ``segment_count`` (int) the number
    of triangle-triangle intersection segments; ``inside_vertices`` (int) vertices of either
    mesh inside the other.
    """

def solid_properties(vertices: ArrayLike, triangles: ArrayLike) -> dict[str, Any]:
    """The solid bounded by a closed, outward-wound mesh, unit density (no BVH is built):
    ``volume`` (m^3, signed), ``centroid`` (3,) m, ``inertia`` (3, 3) about the centroid."""

def static_loads(
    xy: ArrayLike, weight: float, towed: tuple[tuple[float, float], float] | None = None
) -> NDArray[np.float64]:
    """Static loads (N) of wheels at body-frame (x, y) positions (m from the CG) carrying
    weight (N) on level ground (each axle its share), and with ``towed`` ((x, y), N) the load
    a trailer puts on the hitch there."""

def check_mass(mass: float, inertia: ArrayLike) -> None:
    """The engine's checks of a body's mass (kg, finite, positive) and inertia (kg m^2, a
    finite, symmetric, positive definite 3x3 tensor): ParameterError otherwise."""

def check_state(
    position: ArrayLike, orientation: ArrayLike, velocity: ArrayLike, angular_velocity: ArrayLike
) -> None:
    """The engine's checks of a moving body's initial state (world frame; m, quaternion
    (w, x, y, z) or 3x3 rotation, m/s, rad/s): ParameterError otherwise."""

def check_pose(position: ArrayLike, orientation: ArrayLike) -> None:
    """The engine's checks of a fixed body's pose: ParameterError otherwise."""

def describe_place(place: tuple[Any, Any, Any]) -> str:
    """The text one place of an error's ``loc`` puts before its message ("wheel 2",
    'body 0 ("red")', "friction zones 1 and 3", "t = 0.125000 s"), the rendering the
    engine's messages use; "" for a parameter (the message names it with its value);
    ValueError for a tuple that is no place."""

def check_contact_stiffness(
    params: ContactParams,
    faces1: list[tuple[float, float] | None],
    obstacle1: bool,
    faces2: list[tuple[float, float] | None],
    obstacle2: bool,
) -> None:
    """The engine's check that a pair's parameters have the face stiffness they need (auto
    depth of penetration, the stiffness centroid): each side's faces (A N/m, B N/m^2) or None
    in the order front, rear, left, right, and whether it is a fixed obstacle; a
    ParameterError placed at body 0 or 1, the side that lacks it."""

class _VehicleKeywords(TypedDict):
    """SceneSpec.set_vehicle's and check_vehicle's keywords (the binding's VehicleArgs): the
    first six needed, the others optional (None, empty, or ABS on when not given)."""

    centers: ArrayLike
    radii: ArrayLike
    steerable: Sequence[bool]
    static_loads: ArrayLike
    spring_rates: ArrayLike
    damping: ArrayLike
    tyre: NotRequired[Tyre | None]
    steering_ratio: NotRequired[float | None]
    ackermann: NotRequired[float | None]
    steering_reference: NotRequired[str | None]
    steering_interpolation: NotRequired[str | None]
    anti_roll: NotRequired[list[tuple[int, int, float]]]
    abs: NotRequired[bool]
    steer: NotRequired[tuple[str, Any] | None]
    brake: NotRequired[list[tuple[str, ArrayLike, float | None] | None]]
    drive: NotRequired[list[ArrayLike | None]]
    switches: NotRequired[list[tuple[int, str, float, str, float]]]
    coupling: NotRequired[ArrayLike | None]
    hitch_load: NotRequired[tuple[ArrayLike, float] | None]
    load_groups: NotRequired[list[list[int]]]

def check_vehicle(
    mass: float,
    *,
    shape: Shape | None = None,
    **keywords: Unpack[_VehicleKeywords],
) -> None:
    """The engine's checks of wheels, tyre, linkage, bars and driver inputs (SceneSpec.
    set_vehicle's keywords) for a vehicle of ``mass`` kg, with no scene: every rule
    set_vehicle applies but the wheels' place in the body's outline, which is checked too
    when the body's ``shape`` is given. ParameterError (``loc``: the wheel) otherwise."""

def point_in_polygon(x: float, y: float, polygon: Any) -> bool:
    """True when (x, y) (m) lies inside the polygon ((k, 2) corners, m) or on its edge: the
    engine's friction-zone test."""

def check_friction_zone(polygon: ArrayLike, friction: float) -> None:
    """The engine's rules of one friction zone: (k, 2) corners (m, world), at least 3, finite,
    not crossing itself; friction in (0, 2]. ParameterError otherwise."""

def check_ground_friction(friction: float, name: str) -> None:
    """The core's rule of a body's own friction with the ground, in (0, 2]: a ParameterError
    naming it ``name`` (crashsim.Pedestrian's road friction)."""

def check_brake(kind: str, table: Any) -> None:
    """The engine's rules of one braking demand: kind "fraction" (in [0, 1]) or
    "deceleration" (m/s^2, in [0, 20]), a (time s, value) table. ParameterError otherwise."""

def check_wheel_switch(trigger: str, when: float, state: str, fraction: float) -> None:
    """The engine's rules of one wheel-state switch: at a finite ``"time"`` (s) or the
    vehicle's ``"exchange"`` n (a whole number from 1), ``state`` "free", "locked" or
    "braked" (``fraction`` of the friction in [0, 1]). ParameterError otherwise."""

def check_steering_ratio(ratio: float) -> None:
    """The engine's rule of a steering ratio: finite, in [1, 100]. ParameterError otherwise."""

def check_face_stiffness(a: float, b: float) -> None:
    """The engine's rules of a face's CRASH3 coefficients: A (N/m) finite and >= 0, B
    (N/m^2) finite and > 0. ParameterError otherwise."""

def check_table(table: Any, name: str) -> None:
    """Checks a (k, 2) table of (time s, value) by the core's rules (increasing times,
    finite numbers, at least one row): a ParameterError naming it ``name`` otherwise."""

def wheel_loads(
    xy: Sequence[tuple[float, float]],
    weight: float,
    groups: list[list[int]] = ...,
    coupling: tuple[float, float] | None = None,
    towed: tuple[tuple[float, float], float] | None = None,
) -> tuple[list[float], float]:
    """Static loads (N) of wheels at body-frame (x, y) positions carrying weight N at rest,
    with groups of wheels sharing their load (index lists), a trailer's coupling (x, y) and a
    towed load ((x, y), N) on its hitch: each wheel's load and the coupling's."""

@final
class Joint:
    """A joint's kind ("spherical", "revolute", "fixed", "fifth_wheel"), limits (angle name,
    lower rad, upper rad), stiffness N m/rad, damping N m s/rad, friction N m, whether the
    two bodies still collide and its passive moments (angle name, offset rad, [(scale N m,
    rate 1/rad, centre rad), ...], constant N m); checked by the engine when made."""
    def __new__(
        cls,
        kind: str,
        *,
        limits: list[tuple[str, float, float]] = ...,
        stiffness: float = 0.0,
        damping: float = 0.0,
        friction: float = 0.0,
        collide: bool = False,
        passive: list[tuple[str, float, list[tuple[float, float, float]], float]] = ...,
        coupled: list[tuple[str, int, str, str, float, float]] = ...,
    ) -> Joint: ...
    @property
    def kind(self) -> str: ...
    @property
    def collide(self) -> bool: ...
    @property
    def resistance(self) -> tuple[float, float, float]:
        """(stiffness N m/rad, damping N m s/rad, friction N m)."""
    @property
    def angle_names(self) -> list[str]:
        """The kind's angles, in the order of the records' angle columns."""
    @property
    def limits(self) -> list[tuple[str, float, float]]: ...
    @property
    def passive(self) -> list[tuple[str, float, list[tuple[float, float, float]], float]]:
        """Per passive moment: (angle name, offset rad, [(scale N m, rate 1/rad, centre rad),
        ...], constant N m)."""
    @property
    def coupled(self) -> list[tuple[str, int, str, str, float, float]]:
        """Per coupled angle: (the law's angle name, the term's index, the other joint's name,
        its angle's name, offset rad, rate 1/rad)."""
    @property
    def passive_names(self) -> list[str]:
        """The names of the angles a passive moment may act about."""
    def __eq__(self, other: object, /) -> bool: ...

def suspension(
    static_load: float, natural_frequency: float | None = None, damping_ratio: float | None = None
) -> tuple[float, float]:
    """(spring rate N/m, damping N s/m) of a wheel carrying static_load N sprung at
    natural_frequency Hz (None: the engine's 1.3) with damping_ratio (None: 0.3)."""

def dynamics_defaults() -> dict[str, float]:
    """The engine's defaults for the ground, wheels and tyres (gravity, natural_frequency,
    damping_ratio, cornering (1/rad), load_sensitivity, ackermann, relaxation_length,
    rolling_resistance, tyre_friction, body_friction, magic_formula_b, magic_formula_c,
    magic_formula_e) and its rest thresholds (rest_speed m/s, rest_yaw_rate rad/s,
    rest_turn_speed m/s: a small body's yaw limit times its reach, rest_time s)."""

@final
class Ground:
    """The ground, checked by the core once, when it is made."""

    def __new__(
        cls,
        *,
        height: float = 0.0,
        terrain: Shape | None = None,
        tyre_friction: float | None = None,
        body_friction: float | None = None,
        zones: list[tuple[ArrayLike, float]] = ...,
    ) -> Ground:
        """The plane z = height (m), or a terrain mesh in world coordinates; tyre-road and
        body-ground friction (None: the engine's 0.8 and 0.45); friction zones as ((k, 2)
        polygon in m, friction)."""
    @property
    def tyre_friction(self) -> float: ...
    @property
    def body_friction(self) -> float: ...
    def friction_at(self, x: float, y: float) -> float:
        """Tyre-road friction at (x, y) (m, world): the first zone holding the point, else
        the ground's."""
    def with_friction(self, tyre_friction: float, body_friction: float) -> Ground:
        """The same ground with other frictions, checked by the core."""

@final
class Tyre:
    """A tyre, checked by the engine when made: model "linear" (cornering 1/rad, or its
    saturation_angle at mu = 1, rad), "linear_friction_scaled" (saturation_angle rad) or
    "magic_formula" (b 1/rad, c, e); relaxation_length (m), rolling_resistance, combined
    ("braking_priority" | "circle" | "nicolas_comstock"), load_sensitivity,
    longitudinal_stiffness (nicolas_comstock's Cs per unit load, 1 per unit slip; None: the
    cornering stiffness). None: the engine's default."""

    def __new__(
        cls,
        model: str = "linear",
        *,
        cornering: float | None = None,
        saturation_angle: float | None = None,
        b: float | None = None,
        c: float | None = None,
        e: float | None = None,
        relaxation_length: float | None = None,
        rolling_resistance: float | None = None,
        combined: str | None = None,
        load_sensitivity: float | None = None,
        longitudinal_stiffness: float | None = None,
    ) -> Tyre: ...
    def resolved(self) -> dict[str, Any]:
        """Every parameter as the engine runs it."""
    def __eq__(self, value: object, /) -> bool: ...

def free_motion(
    mass: float,
    inertia: ArrayLike,
    position: ArrayLike,
    orientation: ArrayLike,
    velocity: ArrayLike,
    angular_velocity: ArrayLike,
    dt: float,
) -> tuple[NDArray[np.float64], NDArray[np.float64], NDArray[np.float64], NDArray[np.float64]]:
    """A body's state after dt s of torque-free motion (negative dt runs it back):
    (position, orientation (w, x, y, z), velocity, angular_velocity), world frame."""

@final
class ContactParams:
    """One vehicle pair's contact parameters, checked by the engine when made (ranges in
    crates/crashsim-core/src/contact.rs). Immutable; None takes the engine's default.

    depth_of_penetration: a time in s in [0, 0.060] (default 0.030) or "auto"
    (sqrt(m'/k') per impact; needs stiffness on every face of both bodies).
    restitution: in [0, 1] (default 0.1). friction: inter-vehicle, >= 0 (default 0.6).
    restitution_mode: "total" (Kudlich-Slibar, restitution on the whole compression
    impulse) or "normal" (Newton/Brach: on the normal relative velocity).
    centroid: "auto" (centre of the overlap region in the contact frame), "stiffness" (that
    centre moved along n so the crush splits as C1 : C2 = k2 : k1), "world" (the
    fixed world point centroid_point, m) or "body" (centroid_point fixed in the frame of
    body centroid_body, which must be one of the pair's).
    normal: "horizontal" (horizontal part of the volume normal, tilted up by pitch rad, in
    [-pi/2, pi/2], default 0), "volume" (the full 3-D volume normal) or "vector"
    (normal_vector, world frame).
    """

    def __new__(
        cls,
        *,
        depth_of_penetration: float | str | None = None,
        restitution: float | None = None,
        friction: float | None = None,
        restitution_mode: str = "total",
        centroid: str = "auto",
        centroid_point: ArrayLike | None = None,
        centroid_body: int | None = None,
        normal: str = "horizontal",
        normal_vector: ArrayLike | None = None,
        pitch: float | None = None,
    ) -> ContactParams: ...
    @property
    def depth_of_penetration(self) -> float | str: ...
    @property
    def restitution(self) -> float: ...
    @property
    def friction(self) -> float: ...
    @property
    def restitution_mode(self) -> str: ...
    @property
    def centroid(self) -> str: ...
    @property
    def centroid_point(self) -> NDArray[np.float64] | None: ...
    @property
    def centroid_body(self) -> int | None: ...
    @property
    def normal(self) -> str: ...
    @property
    def normal_vector(self) -> NDArray[np.float64] | None: ...
    @property
    def pitch(self) -> float: ...
    @property
    def needs_stiffness(self) -> bool:
        """True for depth_of_penetration "auto" or centroid "stiffness"."""
    def __eq__(self, value: object, /) -> bool: ...
    def __ne__(self, value: object, /) -> bool: ...
    __hash__: None  # type: ignore[assignment]

@final
class SceneSpec:
    """A whole scene as a value (the core's SceneSpec): bodies (moving, then fixed
    obstacles, in the engine's order), face stiffness, the ground, wheels, tyres and driver
    inputs, per-pair contact parameters and the run's options. Every value is checked by the
    engine at the call that sets it. Serialisable: to_json / from_json (meshes as vertices
    and triangles, each shared mesh once) and pickle, the same scene bit for bit."""

    def __new__(cls) -> SceneSpec: ...
    @property
    def n_bodies(self) -> int: ...
    @property
    def names(self) -> list[str]:
        """The bodies' names, in order ("body i" when none was given)."""
    @property
    def run_options(self) -> tuple[float, float, bool]:
        """(duration s, dt s, until_rest) of the run."""
    def add_body(
        self,
        shape: Shape,
        mass: float,
        inertia: ArrayLike,
        position: ArrayLike,
        orientation: ArrayLike,
        velocity: ArrayLike,
        angular_velocity: ArrayLike,
        name: str | None = None,
    ) -> int:
        """Add a moving body; returns its index. inertia: (3, 3) about the CG in the body
        frame (kg m^2); position of the CG (m), orientation (w, x, y, z), velocity (m/s) and
        angular velocity (rad/s) in the world frame."""
    def add_obstacle(
        self, shape: Shape, position: ArrayLike, orientation: ArrayLike, name: str | None = None
    ) -> int:
        """Add a fixed obstacle (infinite mass and inertia, never moves) with its mesh at a
        pose (position m, quaternion (w, x, y, z)); returns its index. Obstacles form no pair
        with each other."""
    def set_ground(self, ground: Ground) -> None:
        """Put the scene on the ground (gravity along -z), checked when it was made."""
    def set_vehicle(
        self,
        body: int,
        **keywords: Unpack[_VehicleKeywords],
    ) -> None:
        """Give a body wheels: centres (n, 3) m in the body frame at static ride height, radii
        (m), steerable flags, static loads (N), spring rates (N/m), damping (N s/m); a Tyre;
        the steering linkage (steering ratio, Ackermann fraction, the input's reference wheel
        "outer" or "centre"); anti-roll bars (left wheel, right wheel, roll stiffness N m/rad);
        ABS; the steering input ("road_wheel" | "steering_wheel", (k, 2) table of (s, rad)) or
        ("per_wheel", [table or None per wheel]); per wheel braking None or ("fraction" |
        "deceleration", (k, 2) table of (s, fraction) or (s, m/s^2), None) or ("distributed",
        (s, m/s^2) table, the wheel's share of the vehicle's brake force) and drive-force
        tables (s, N); wheel-state switches (wheel, "time" | "exchange", when, "free" |
        "locked" | "braked", braked fraction)."""
    def add_joint(
        self,
        joint: Joint,
        body1: int,
        body2: int | None,
        frame1: tuple[ArrayLike, ArrayLike],
        frame2: tuple[ArrayLike, ArrayLike],
        name: str | None = None,
    ) -> int:
        """Adds ``joint`` between body1 and body2 (None: the world): frame1 (anchor m, axes
        quaternion w, x, y, z) in body1's frame, frame2 in body2's (or the world's), the same
        frame when the run starts; name for the engine's messages. Returns its index."""
    @property
    def n_joints(self) -> int: ...
    def set_contact(self, body1: int, body2: int, params: ContactParams) -> None:
        """Parameters of the pair (body1, body2); every pair of bodies but two obstacles
        collides with the defaults unless set here. The normal points from body1 into body2.
        Face stiffness the parameters need is checked when the scene is built."""
    def set_no_contact(self, body1: int, body2: int) -> None:
        """Makes the two bodies never collide (no overlap search, contact or exchange)."""
    @property
    def no_contact(self) -> list[tuple[int, int]]:
        """The pairs that never collide, (lower index, higher)."""
    def set_soft_contact(
        self, body1: int, body2: int, stiffness: float, damping_ratio: float
    ) -> None:
        """A compliant contact (N/m, damping ratio) in place of the timer and the exchange."""
    @property
    def soft_contacts(self) -> list[tuple[int, int, float, float]]:
        """The soft pairs, (lower index, higher, stiffness N/m, damping ratio)."""
    def set_stiffness(
        self,
        body: int,
        *,
        front: tuple[float, float] | None = None,
        rear: tuple[float, float] | None = None,
        left: tuple[float, float] | None = None,
        right: tuple[float, float] | None = None,
    ) -> None:
        """A body's face stiffness: each face (A, B) in (N/m, N/m^2), or None without data."""
    def set_ground_friction(self, body: int, friction: float) -> None:
        """A moving body's own friction with the ground, in (0, 2], in place of the ground's
        body friction: a person's clothing on the road (ParameterError out of range,
        SceneError for a fixed obstacle)."""
    def set_run(
        self,
        duration: float,
        dt: float,
        *,
        record_interval: float | None = None,
        max_history_bytes: int | None = None,
        until_rest: bool = False,
    ) -> None:
        """The run: duration (s; with until_rest the longest it may take), largest step dt
        (s), record_interval and max_history_bytes as World.run takes them. Default 1 s at
        1 ms. The duration, step and record_interval are checked here (ParameterError); a
        run until rest's ground and the history's size when the scene runs."""
    def build(self) -> World:
        """A fresh engine world holding the scene at t = 0 (every value checked)."""
    def run(self, progress: Callable[[float], object] | None = None) -> dict[str, Any]:
        """Build and run with the run's options; World.run's dict."""
    def to_json(self) -> str:
        """The scene as JSON text."""
    @staticmethod
    def from_json(text: str) -> SceneSpec:
        """A scene from to_json's text, checked as the setup calls check (ParameterError,
        MeshError)."""
    @staticmethod
    def _from_json_bytes(data: bytes) -> SceneSpec: ...
    def __reduce__(self) -> tuple[Callable[[bytes], SceneSpec], tuple[bytes]]:
        """Pickled as its JSON."""

def run_batch(
    spec: SceneSpec,
    overrides: dict[str, ArrayLike] | None,
    n: int,
    *,
    threads: int | None = None,
    progress: Callable[[int, int], object] | None = None,
    max_impacts: int = 2,
) -> dict[str, Any]:
    """Run n variants of spec (its run options), each single-threaded, on a pool of threads
    (None: one per core), the GIL released; overrides: {key: (n, ...) array} (the keys and
    shapes of python/crashsim/batch.py; an unknown key or a wrong shape is a ParameterError
    naming it). progress(done, n) is called from the caller's thread; Ctrl-C stops the
    batch and keeps what finished. Returns ``columns`` [(name, (n,) array)], ``errors``
    [(index, kind, message, loc, message without the places)], ``finished`` (n,) bool,
    ``interrupted`` bool."""

@final
class World:
    """A running world, made by SceneSpec.build()."""

    @property
    def time(self) -> float: ...
    @property
    def n_bodies(self) -> int: ...
    def run(
        self,
        duration: float,
        dt: float,
        progress: Callable[[float], object] | None = None,
        record_interval: float | None = None,
        max_history_bytes: int | None = None,
        until_rest: bool = False,
    ) -> dict[str, Any]:
        """Advance the world by duration (s) with steps of at most dt (s). progress, if given,
        is called with the current time (s) at most every 0.1 s of wall time (Ctrl-C is
        honoured then); an exception it raises stops the run and propagates.
        record_interval (s; None: every step for runs of at most 100,000 steps, else about
        100,000 samples) spaces the kept samples; a run whose history would exceed
        max_history_bytes (None: 2**30) is refused with a ParameterError. until_rest stops the
        run once every body on the ground is at rest (duration is then the longest it may
        take; needs a ground).

        Returns a dict: ``t`` (k,) sample times (the kept step ends, every first overlap and
        every exchange; the state at an exchange is the one after it); ``record_interval``
        the spacing of the kept step ends (s); ``position``,
        ``velocity``, ``angular_velocity`` (n_bodies, k, 3); ``orientation`` (n_bodies, k, 4);
        ``impacts``: one dict per impulse exchange, in time order, keyed by the core record's
        field names (crates/crashsim-core/src/world/events.rs ``Impact``; vectors as lists
        [x, y, z], per-body values as [body 1, body 2]; python/crashsim/records.py reads it);
        ``contacts``: a list of dicts ``body1``, ``body2``, ``time``, ``kind``
        ("first_overlap", "closing_again", "separation" or "no_exchange") and, for
        "no_exchange" only, ``reason`` (str); the wheels of the bodies on the ground (W in
        all, body after body): ``wheel_counts`` (per body), ``wheel_contact`` (W, k, 3) m,
        ``wheel_load`` (W, k) N, ``wheel_force`` (W, k, 3) N (the ground's force on the
        tyre), ``wheel_sliding`` (W, k) bool; ``rest`` per body: when it came to rest (s) or None.
        """
