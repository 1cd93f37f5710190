"""Type stub of the compiled engine module ``crashsim._core`` (crates/crashsim-py).

Everything here is SI (m, kg, s, rad, N s). Frames: world is right-handed with z up;
a body frame has its origin at the body's centre of gravity (ISO 8855: x forward,
y left, z up). Quaternions are (w, x, y, z) and rotate body-frame vectors into the world.
Users should not need this module: the public API is ``crashsim.Scene``.
"""

from collections.abc import Callable, Sequence
from typing import Any, final

import numpy as np
from numpy.typing import ArrayLike, NDArray

__version__: str
__all__ = [
    "CrashsimError",
    "InitialOverlapError",
    "InputError",
    "MeshError",
    "ParameterError",
    "Shape",
    "SimulationError",
    "World",
    "__version__",
    "dynamics_defaults",
    "free_motion",
    "overlap_region",
    "shapes_overlap",
    "solid_properties",
    "static_loads",
    "suspension",
]

class CrashsimError(Exception):
    """Root of every error the engine raises."""

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

def static_loads(xy: ArrayLike, weight: float) -> NDArray[np.float64]:
    """Static loads (N) of wheels at body-frame (x, y) positions (m from the CG) carrying
    weight (N) on level ground: each axle its share."""

def suspension(
    static_load: float, natural_frequency: float | None = None, damping_ratio: float | None = None
) -> tuple[float, float]:
    """(spring rate N/m, damping N s/m) of a wheel carrying static_load N sprung at
    natural_frequency Hz (None: the engine's 1.3) with damping_ratio (None: 0.3)."""

def dynamics_defaults() -> dict[str, float]:
    """The engine's defaults for the ground, wheels and tyres (gravity, natural_frequency,
    damping_ratio, saturation_angle, relaxation_length, rolling_resistance, tyre_friction,
    body_friction, magic_formula_b, magic_formula_c, magic_formula_e) and its rest thresholds (rest_speed m/s, rest_yaw_rate rad/s,
    rest_time s)."""

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
class World:
    """A set of rigid bodies with meshes and the contact parameters of each pair."""

    def __new__(cls) -> World: ...
    @property
    def time(self) -> float: ...
    @property
    def n_bodies(self) -> int: ...
    def add_body(
        self,
        shape: Shape,
        mass: float,
        inertia: ArrayLike,
        position: ArrayLike,
        orientation: ArrayLike,
        velocity: ArrayLike,
        angular_velocity: ArrayLike,
    ) -> int:
        """Add a body; returns its index. inertia: (3, 3) about the CG in the body frame (kg m^2);
        position of the CG (m), orientation (w, x, y, z), velocity (m/s) and angular velocity
        (rad/s) in the world frame."""
    def add_obstacle(self, shape: Shape, position: ArrayLike, orientation: ArrayLike) -> int:
        """Add a fixed obstacle (infinite mass and inertia, never moves) with its mesh at a pose
        (position m, quaternion (w, x, y, z)); returns its index. Obstacles form no pair with
        each other."""
    def set_ground(
        self,
        *,
        height: float = 0.0,
        terrain: Shape | None = None,
        tyre_friction: float | None = None,
        body_friction: float | None = None,
        zones: list[tuple[ArrayLike, float]] = ...,
    ) -> None:
        """Put the world on the ground (gravity along -z): the plane z = height (m), or a
        terrain mesh in world coordinates; tyre-road and body-ground friction (None: the
        engine's 0.8 and 0.45); friction zones as ((k, 2) polygon in m, friction)."""
    def set_vehicle(
        self,
        body: int,
        *,
        centers: ArrayLike,
        radii: ArrayLike,
        steerable: Sequence[bool],
        static_loads: ArrayLike,
        spring_rates: ArrayLike,
        damping: ArrayLike,
        tyre: dict[str, Any] | None = None,
        steer: ArrayLike | None = None,
        brake: list[tuple[str, ArrayLike] | None] = ...,
        drive: list[ArrayLike | None] = ...,
        switches: list[tuple[int, str, float, str, float]] = ...,
    ) -> None:
        """Give a body wheels: centres (n, 3) m in the body frame at static ride height, radii
        (m), steerable flags, static loads (N), spring rates (N/m), damping (N s/m); a tyre
        dict (model "linear" with saturation_angle rad, or "magic_formula" with b, c, e;
        relaxation_length m, rolling_resistance); the road-wheel steering angle table (k, 2)
        of (s, rad); per wheel braking None or ("fraction" | "deceleration", (k, 2) table of
        (s, fraction) or (s, m/s^2)) and drive-force tables (s, N); wheel-state switches
        (wheel, "time" | "exchange", when, "free" | "locked" | "braked", braked fraction)."""
    def set_contact(
        self,
        body1: int,
        body2: int,
        *,
        depth_of_penetration: float | str | None = None,
        restitution: float = 0.1,
        friction: float = 0.6,
        restitution_mode: str = "total",
        centroid: str = "auto",
        centroid_point: ArrayLike | None = None,
        centroid_body: int | None = None,
        normal: str = "horizontal",
        normal_vector: ArrayLike | None = None,
        pitch: float = 0.0,
    ) -> None:
        """Parameters of the pair (body1, body2); every pair of bodies collides with the
        defaults unless set here. The normal points from body1 into body2.

        depth_of_penetration: a time in s in [0, 0.060] (None: 0.030) or "auto"
        (sqrt(m'/k') per impact; needs stiffness on every face of both bodies).
        restitution_mode: "total" (Kudlich-Slibar, restitution on the whole compression
        impulse) or "normal" (Newton/Brach: on the normal relative velocity).
        centroid: "auto" (centre of the overlap region in the contact frame), "stiffness" (that
        centre moved along n so the crush splits as C1 : C2 = k2 : k1), "world" (the
        fixed world point centroid_point) or "body" (centroid_point fixed in the frame of
        body centroid_body, which must be body1 or body2).
        normal: "horizontal" (horizontal part of the volume normal, tilted up by pitch rad),
        "volume" (the full 3-D volume normal) or "vector" (normal_vector, world frame).
        """
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
        ``impacts``: a list of dicts, one per impulse exchange, with keys
        ``body1``, ``body2``, ``first_contact_time``, ``time``, ``depth_of_penetration``,
        ``secondary`` (bool), ``centroid`` (3,), ``normal`` (3,), ``impulse`` (3,) the impulse
        on body2 (body1 gets its negative), ``sliding`` (bool), ``velocity_before``,
        ``velocity_after``, ``angular_velocity_before``, ``angular_velocity_after`` (2, 3)
        rows for body1 and body2, ``relative_velocity_before``, ``relative_velocity_after``
        (3,) velocity of body1's point minus body2's at the centroid, ``energy_dissipated``
        (J), ``region_points`` (p, 3), ``contact_frame`` (3, 3) rows n, t, b,
        ``region_min``, ``region_max`` (3,) extent of the region in the contact frame,
        ``depth_of_penetration_mode`` ("fixed" or "auto"), ``struck_faces`` (face of body1,
        face of body2), ``overlap_width`` (m), ``spring_rates`` ((k1, k2) N/m or None),
        ``effective_mass`` ((m1, m2) kg along n at the centroid), ``notes`` (list of str),
        ``normal_time`` (s: when the overlap's volume normal behind ``normal`` was taken);
        ``contacts``: a list of dicts ``body1``, ``body2``, ``time``, ``kind``
        ("first_overlap", "closing_again", "separation" or "no_exchange") and ``reason``
        (str or None); the wheels of the bodies on the ground (W in all, body after body):
        ``wheel_counts`` (per body), ``wheel_contact`` (W, k, 3) m, ``wheel_load`` (W, k) N,
        ``wheel_force`` (W, k, 3) N (the ground's force on the tyre), ``wheel_sliding``
        (W, k) bool; ``rest`` per body: when it came to rest (s) or None.
        """
