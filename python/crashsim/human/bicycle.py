"""A bicycle for the multibody cyclist (docs/human.md, "The cyclist"): a rigid frame (frame,
fork, handlebar, saddle, cranks and pedals: no steering, no crank rotation) and two wheels
joined to it by hinges ("revolute") at the axles, so the wheels roll on the road with the
engine's body-ground contact.

Mass data from measurements of a Dutch city bicycle (data/bicycle.toml, with sources): the
frame's mass, centre of mass and inertia are those of the measured rear frame and front
frame combined; each wheel's mass, rolling radius and inertias its own. The contact meshes
(tubes as capsules, the saddle and pedals as boxes, each wheel a thin cylinder of the tyre's
width) follow the measured geometry where it was measured and stated sizes elsewhere; they
do not change the mass data.

Bicycle frame: x forward, y left, z up (m), origin on the ground midway between the two
wheels' contact points. ``Scene.add(bicycle, (x, y), heading=, velocity=)`` puts that origin
at (x, y) on the ground (the wheels CLEARANCE above it), every body moving at ``velocity``
and the wheels turning at the forward speed over their radius (rolling).
"""

from __future__ import annotations

import math
import tomllib
from dataclasses import dataclass, field
from functools import cache
from importlib import resources
from typing import Any

import numpy as np
import trimesh
from numpy.typing import ArrayLike, NDArray

from crashsim.errors import ParameterError
from crashsim.names import check_name
from crashsim.small_linalg import by_libm, dot, matmul, norm, rotation_about, transform_points
from crashsim.vehicles.vehicle import Vehicle

__all__ = ["KINDS", "Bicycle", "BicycleFit", "Parts"]

Array = NDArray[np.float64]
KINDS = ("city",)
CLEARANCE = 1e-3  # m, the wheels' lowest points above the ground at the start
_WHEEL_SECTIONS = 96  # the wheel's polygon: a vertex every 3.75 deg of its rim
_TUBE_COUNT = (8, 8)  # trimesh capsule resolution


@cache
def _table() -> dict[str, Any]:
    path = resources.files("crashsim.human").joinpath("data", "bicycle.toml")
    return tomllib.loads(path.read_text(encoding="utf-8"))


@dataclass(frozen=True)
class BicycleFit:
    """Where the rider's contact points put the saddle, handlebar and pedals (bicycle
    frame, m): ``saddle`` (x, z) the saddle's top at its middle, ``handlebar`` (x, z) the
    bar's axis at the mid-plane, ``pedal_offset`` a pedal's centre from the mid-plane; the
    cranks stand vertical, the left pedal down; ``pedal_tilt`` (left, right) each pedal's
    turn about the bicycle's y axis (rad, + toes down: a pedal turns on its spindle to lie
    under the sole)."""

    saddle: tuple[float, float]
    handlebar: tuple[float, float]
    pedal_offset: float
    pedal_tilt: tuple[float, float] = (0.0, 0.0)


@dataclass
class Parts:
    """What a scene adds for a bicycle or a cyclist: ``bodies`` [(vehicle, CG m, rotation
    body -> world, velocity m/s, angular velocity rad/s)] (world), ``joints`` [Scene.join's
    arguments], ``no_contact`` [(name, name)], ``soft`` [(name, name, stiffness N/m,
    damping ratio, contact parameters)]."""

    bodies: list[tuple[Vehicle, Array, Array, Array, Array]] = field(default_factory=list)
    joints: list[dict[str, Any]] = field(default_factory=list)
    no_contact: list[tuple[str, str]] = field(default_factory=list)
    soft: list[tuple[str, str, float, float, dict[str, Any]]] = field(default_factory=list)


def _yaw(heading: float) -> Array:
    c, s = math.cos(heading), math.sin(heading)
    return np.array([[c, -s, 0.0], [s, c, 0.0], [0.0, 0.0, 1.0]])


def _tube(a: ArrayLike, b: ArrayLike, radius: float) -> trimesh.Trimesh:
    """A capsule of ``radius`` whose cap centres are the points a and b (m)."""
    a, b = np.asarray(a, dtype=np.float64), np.asarray(b, dtype=np.float64)
    length = float(norm(b - a))
    mesh = trimesh.creation.capsule(height=max(length, 1e-6), radius=radius,
                                    count=list(_TUBE_COUNT))  # fmt: skip
    # trimesh's capsule lies along z, centred at the origin: turn z onto a -> b (about z x d
    # by the angle between them)
    d = (b - a) / length
    k = np.array([-d[1], d[0], 0.0])  # z x d
    s, c = float(norm(k)), float(d[2])
    turn = np.eye(3)
    if s > 1e-12:
        turn = rotation_about(k / s, s, c)
    elif c < 0.0:
        turn = np.diag([1.0, -1.0, -1.0])  # half a turn about x
    transform = np.eye(4)
    transform[:3, :3], transform[:3, 3] = turn, (a + b) / 2.0
    return trimesh.Trimesh(transform_points(mesh.vertices, transform), mesh.faces, process=False)


def _box(centre: ArrayLike, size: ArrayLike, tilt: float = 0.0) -> trimesh.Trimesh:
    """A box of ``size`` (x, y, z) m centred at ``centre``, turned by ``tilt`` rad about y
    (+: its front end down)."""
    mesh = trimesh.creation.box(extents=np.asarray(size, dtype=np.float64))
    c, s = math.cos(tilt), math.sin(tilt)
    transform = np.eye(4)
    transform[:3, :3] = [[c, 0.0, s], [0.0, 1.0, 0.0], [-s, 0.0, c]]
    transform[:3, 3] = np.asarray(centre, dtype=np.float64)
    return trimesh.Trimesh(transform_points(mesh.vertices, transform), mesh.faces, process=False)


def _wheel_mesh(radius: float, width: float) -> trimesh.Trimesh:
    """A thin cylinder about the y axis (the axle), centred at the hub, a rim vertex at the
    bottom; its two faces bulge 1 mm at the hub so that the convex hull (the ground contact's
    points) fans every face from the hub and gives each rim vertex the same area."""
    n = _WHEEL_SECTIONS
    angles = -math.pi / 2.0 + 2.0 * math.pi * np.arange(n) / n  # the first at the bottom
    cos, sin = by_libm(math.cos, angles), by_libm(math.sin, angles)
    ring = np.column_stack([radius * cos, np.zeros(n), radius * sin])
    half = width / 2.0
    left, right = ring + [0.0, half, 0.0], ring + [0.0, -half, 0.0]
    hubs = np.array([[0.0, half + 1e-3, 0.0], [0.0, -half - 1e-3, 0.0]])
    vertices = np.vstack([left, right, hubs])
    faces = []
    for i in range(n):
        j = (i + 1) % n
        faces += [[i, j, n + j], [i, n + j, n + i]]  # the tread
        faces += [[2 * n, j, i], [2 * n + 1, n + i, n + j]]  # the faces, fanned from the hubs
    mesh = trimesh.Trimesh(vertices, np.asarray(faces), process=False)
    trimesh.repair.fix_normals(mesh)
    return mesh


def _benchmark_body(b: dict[str, Any], wheelbase: float) -> tuple[float, Array, Array]:
    """A measured body's mass, CG (bicycle frame) and inertia (3, 3) about it (crashsim's
    axes: the benchmark's y and z reversed, so its xz product changes sign)."""
    cg = np.array([float(b["x"]) - wheelbase / 2.0, 0.0, -float(b["z"])])
    ixz = -float(b["Ixz"])
    inertia = np.array([[float(b["Ixx"]), 0.0, ixz], [0.0, float(b["Iyy"]), 0.0],
                        [ixz, 0.0, float(b["Izz"])]])  # fmt: skip
    return float(b["mass"]), cg, inertia


def _combined(parts: list[tuple[float, Array, Array]]) -> tuple[float, Array, Array]:
    """Mass, CG and inertia about that CG of rigidly joined bodies (parallel axes)."""
    mass = sum(m for m, _, _ in parts)
    cg = sum(m * c for m, c, _ in parts) / mass
    inertia = np.zeros((3, 3))
    for m, c, i in parts:
        d = c - cg
        inertia += i + m * (float(dot(d, d)) * np.eye(3) - np.outer(d, d))
    return mass, cg, inertia


class Bicycle:
    """A bicycle (module docstring) of the measured ``kind`` (KINDS: "city"), named ``name``
    (its bodies "<name>/frame", "<name>/rear_wheel", "<name>/front_wheel"; its axle
    hinges "<name>/rear_axle", "<name>/front_axle"). ``fit`` places the saddle, handlebar
    and pedals (a :class:`BicycleFit`; None: the measured seat post length, the stated stem);
    :class:`crashsim.Cyclist` fits them to its rider.

    Attributes: ``frame``, ``rear_wheel``, ``front_wheel`` (:class:`crashsim.Vehicle`),
    ``bodies`` (those three), ``mass`` (kg), ``wheelbase`` (m), ``axles`` {"rear", "front":
    (3,) bicycle frame, m}, ``bracket`` (3,), ``seat_cluster`` (3,), ``data`` (the kind's
    table)."""

    def __init__(self, kind: str = "city", name: str = "bicycle", fit: BicycleFit | None = None):
        check_name(name, "a bicycle")
        if kind not in KINDS:
            raise ParameterError(
                f"bicycle kind {kind!r} is not known: give one of {', '.join(map(repr, KINDS))}"
            )
        d = _table()["bicycles"][kind]
        self._kind, self._name, self._data = kind, name, d
        g = d["geometry"]
        w = float(d["wheelbase"])
        r_rear, r_front = float(d["rear_wheel"]["radius"]), float(d["front_wheel"]["radius"])
        self._axles = {"rear": np.array([-w / 2.0, 0.0, r_rear]),
                       "front": np.array([w / 2.0, 0.0, r_front])}  # fmt: skip
        drop = r_rear - float(g["bottom_bracket_height"])
        stay = float(g["chain_stay"])
        self._bracket = np.array([-w / 2.0 + math.sqrt(stay * stay - drop * drop), 0.0,
                                  float(g["bottom_bracket_height"])])  # fmt: skip
        st = float(g["seat_tube_angle"])
        self._seat_dir = np.array([-math.cos(st), 0.0, math.sin(st)])
        self._seat_cluster = self._bracket + float(g["seat_tube"]) * self._seat_dir
        self._fit = fit if fit is not None else self._default_fit()
        self._check_fit(self._fit)
        mass, cg, inertia = _combined([_benchmark_body(d["rear_frame"], w),
                                       _benchmark_body(d["front_frame"], w)])  # fmt: skip
        self._frame = Vehicle(
            self._frame_mesh(),
            mass,
            cg,
            inertia,
            name=f"{name}/frame",
            sources={"cg": "Moore (Crescendo)", "inertia": "Moore (Crescendo)"},
        )
        self._wheels = {end: self._wheel(end) for end in ("rear", "front")}

    # -- what it is ----------------------------------------------------------------------

    @property
    def name(self) -> str:
        return self._name

    @property
    def kind(self) -> str:
        return self._kind

    @property
    def data(self) -> dict[str, Any]:
        return self._data

    @property
    def fit(self) -> BicycleFit:
        return self._fit

    @property
    def frame(self) -> Vehicle:
        return self._frame

    @property
    def rear_wheel(self) -> Vehicle:
        return self._wheels["rear"]

    @property
    def front_wheel(self) -> Vehicle:
        return self._wheels["front"]

    @property
    def bodies(self) -> tuple[Vehicle, Vehicle, Vehicle]:
        return (self._frame, self._wheels["rear"], self._wheels["front"])

    @property
    def segments(self) -> tuple[Vehicle, Vehicle, Vehicle]:
        """Its bodies, as a pedestrian's segments (crashsim.analysis.pedestrian reads them:
        segment_contacts(result, bicycle, car) gives each body's first contact)."""
        return self.bodies

    @property
    def mass(self) -> float:
        """The whole bicycle's mass (kg)."""
        return sum(b.mass for b in self.bodies)

    @property
    def wheelbase(self) -> float:
        return float(self._data["wheelbase"])

    @property
    def axles(self) -> dict[str, Array]:
        return {k: v.copy() for k, v in self._axles.items()}

    @property
    def bracket(self) -> Array:
        return self._bracket.copy()

    @property
    def seat_cluster(self) -> Array:
        return self._seat_cluster.copy()

    @property
    def crank_length(self) -> float:
        return float(self._data["assumed"]["crank_length"])

    @property
    def seat_tube_angle(self) -> float:
        """rad, to the horizontal."""
        return float(self._data["geometry"]["seat_tube_angle"])

    def cg(self) -> Array:
        """The whole bicycle's centre of mass (bicycle frame, m)."""
        total = self._frame.mass * np.asarray(self._frame.cg)
        for end, wheel in self._wheels.items():
            total = total + wheel.mass * self._axles[end]
        return total / self.mass

    def fitted(self, fit: BicycleFit, name: str | None = None) -> Bicycle:
        """The same bicycle with its saddle, handlebar and pedals at ``fit``."""
        return Bicycle(self._kind, self._name if name is None else name, fit)

    # -- its parts -----------------------------------------------------------------------

    def _default_fit(self) -> BicycleFit:
        a = self._data["assumed"]
        saddle = self._seat_cluster + float(self._data["geometry"]["seat_post"]) * self._seat_dir
        top = self._steer_point(self._head_bottom_z() + float(a["head_tube"]))
        return BicycleFit(
            saddle=(float(saddle[0]), float(saddle[2])),
            handlebar=(float(top[0] + a["stem_reach"]), float(top[2] + a["stem_rise"])),
            pedal_offset=float(a["pedal_offset"]),
        )

    def _steer_point(self, z: float) -> Array:
        """The steer axis's point at height z (m): the axis meets the ground the trail ahead
        of the front wheel's contact point, tilted back by the steer axis tilt."""
        d = self._data
        x0 = self.wheelbase / 2.0 + float(d["trail"])
        return np.array([x0 - z * math.tan(float(d["steer_axis_tilt"])), 0.0, z])

    def _head_bottom_z(self) -> float:
        r = float(self._data["front_wheel"]["radius"])
        return 2.0 * r + float(self._data["assumed"]["crown_clearance"])

    def _check_fit(self, fit: BicycleFit) -> None:
        """ParameterError when the saddle or the handlebar cannot be where ``fit`` puts
        them on this frame."""
        a = self._data["assumed"]
        post_top = fit.saddle[1] - float(a["saddle"][2])
        if post_top < self._seat_cluster[2] + 0.02:
            raise ParameterError(
                f"the saddle's top would be at {fit.saddle[1]:.3f} m, below this bicycle's seat "
                f"tube top ({self._seat_cluster[2]:.3f} m) plus the saddle: the rider is too short "
                f"for the {self._kind} bicycle's frame (its legs need a lower saddle)"
            )
        out = (post_top - self._seat_cluster[2]) / self._seat_dir[2]  # along the seat tube
        if out > float(a["seat_post_max"]):
            raise ParameterError(
                f"the seat post would stand {out:.3f} m out of the seat tube, more than "
                f"{float(a['seat_post_max']):.2f} m: the rider is too tall for the {self._kind} "
                "bicycle's frame"
            )
        head_top = self._steer_point(self._head_bottom_z() + float(a["head_tube"]))
        if fit.handlebar[1] < self._head_bottom_z() or fit.handlebar[0] <= fit.saddle[0]:
            raise ParameterError(
                f"the handlebar would be at x {fit.handlebar[0]:.3f}, z {fit.handlebar[1]:.3f} m, "
                f"below the head tube or behind the saddle (x {fit.saddle[0]:.3f} m): the rider "
                "does not fit this bicycle"
            )
        if fit.handlebar[0] > self._axles["front"][0] + 0.1 or (
            np.hypot(fit.handlebar[0] - head_top[0], fit.handlebar[1] - head_top[2]) > 0.6
        ):
            raise ParameterError(
                f"the handlebar would be at x {fit.handlebar[0]:.3f}, z {fit.handlebar[1]:.3f} m, "
                "more than 0.6 m from the head tube's top or 0.1 m past the front axle: the "
                "rider is too large for this bicycle"
            )

    def _frame_mesh(self) -> trimesh.Trimesh:
        """The frame's contact mesh, bicycle frame (module docstring)."""
        a, g = self._data["assumed"], self._data["geometry"]
        r, spread = float(a["tube_radius"]), float(a["stay_spread"])
        head_bottom = self._steer_point(self._head_bottom_z())
        head_top = self._steer_point(self._head_bottom_z() + float(a["head_tube"]))
        bb, seat, rear, front = self._bracket, self._seat_cluster, *self._axles.values()
        side = np.array([0.0, 1.0, 0.0])
        parts = [
            _tube(head_bottom, head_top, r),
            _tube(seat, head_top - [0.0, 0.0, 0.03], r),  # top tube
            _tube(bb, head_bottom + [0.0, 0.0, 0.03], r),  # down tube
            _tube(bb, seat, r),
        ]
        for s in (1.0, -1.0):
            parts += [_tube(bb + s * spread * side, rear + s * spread * side, 0.7 * r),
                      _tube(seat, rear + s * spread * side, 0.7 * r),
                      _tube(head_bottom, front + s * spread * side, 0.8 * r)]  # fmt: skip
        # the seat post up the seat tube's line to the saddle's underside, the saddle
        fit = self._fit
        saddle_size = np.asarray(a["saddle"], dtype=np.float64)
        under = fit.saddle[1] - saddle_size[2]
        post_top = seat + (under - seat[2]) / self._seat_dir[2] * self._seat_dir
        saddle = np.array([fit.saddle[0], 0.0, fit.saddle[1] - saddle_size[2] / 2.0])
        parts += [_tube(seat, post_top, 0.8 * r), _tube(post_top, saddle, 0.8 * r),
                  _box(saddle, saddle_size)]  # fmt: skip
        # the stem and the handlebar (straight, across)
        bar = np.array([fit.handlebar[0], 0.0, fit.handlebar[1]])
        half = float(g["handlebar_width"]) / 2.0
        parts += [
            _tube(head_top, bar, r),
            _tube(bar - half * side, bar + half * side, float(a["bar_radius"])),
        ]
        # the cranks (vertical, the left pedal down; inboard of the feet at 0.4 of the
        # pedal's offset) and the pedals, their tops at the soles' contact points
        crank, pedal = self.crank_length, np.asarray(a["pedal"], dtype=np.float64)
        for s, up, tilt in ((1.0, -1.0, fit.pedal_tilt[0]), (-1.0, 1.0, fit.pedal_tilt[1])):
            contact = bb + [0.0, s * fit.pedal_offset, up * crank]
            # the pedal's top normal, turned by its tilt about y (+z turns towards +x)
            normal = np.array([math.sin(tilt), 0.0, math.cos(tilt)])
            centre = contact - normal * pedal[2] / 2.0
            inboard = 0.4 * fit.pedal_offset * side * s
            parts += [
                _tube(bb + inboard, [bb[0], 0.0, centre[2]] + inboard, 0.6 * r),
                _box(centre, pedal, tilt),
            ]
        return trimesh.util.concatenate(parts)

    def _wheel(self, end: str) -> Vehicle:
        w = self._data[f"{end}_wheel"]
        ixx, iyy = float(w["Ixx"]), float(w["Iyy"])
        mesh = _wheel_mesh(float(w["radius"]), float(self._data["assumed"]["tyre_width"]))
        return Vehicle(
            mesh,
            float(w["mass"]),
            np.zeros(3),
            np.diag([ixx, iyy, ixx]),
            name=f"{self._name}/{end}_wheel",
            sources={"cg": "the hub", "inertia": "Moore (Crescendo)"},
        )

    # -- in a scene ----------------------------------------------------------------------

    def placement(
        self, position: ArrayLike, heading: float, velocity: ArrayLike, ground: float
    ) -> Parts:
        """The bodies, hinges and pairs a scene adds (:class:`Parts`): the bicycle frame's
        origin at (x, y) on the ground of height ``ground`` (m; the wheels CLEARANCE above
        it) or at the world point (x, y, z); its x axis at ``heading`` (rad); every body
        moving at ``velocity`` (m/s, world), the wheels turning at its forward part over
        their radius."""
        origin, yaw, v = self.origin(position, heading, velocity, ground)
        forward = float(dot(v, matmul(yaw, [1.0, 0.0, 0.0])))
        parts = Parts()
        cg = origin + matmul(yaw, self._frame.cg)
        parts.bodies.append((self._frame, cg, yaw, v, np.zeros(3)))
        # the hinge's frame: its z along the axle (the bicycle's y), its x forward
        axes = matmul(yaw, np.column_stack([[1.0, 0.0, 0.0], [0.0, 0.0, -1.0], [0.0, 1.0, 0.0]]))
        for end, wheel in self._wheels.items():
            radius = float(self._data[f"{end}_wheel"]["radius"])
            at = origin + matmul(yaw, self._axles[end])
            spin = matmul(yaw, np.array([0.0, forward / radius, 0.0]))
            parts.bodies.append((wheel, at, yaw, v, spin))
            parts.joints.append(dict(vehicle1=self._frame.name, vehicle2=wheel.name, at=at,
                                     kind="revolute", axes=axes,
                                     name=f"{self._name}/{end}_axle"))  # fmt: skip
        parts.no_contact.append((self.rear_wheel.name, self.front_wheel.name))
        return parts

    def origin(
        self, position: ArrayLike, heading: float, velocity: ArrayLike, ground: float
    ) -> tuple[Array, Array, Array]:
        """The bicycle frame's origin in the world (m), its rotation (heading about z) and the
        velocity (m/s) as arrays; ParameterError for a position or velocity of the wrong
        size."""
        p = np.asarray(position, dtype=np.float64).reshape(-1)
        v = np.asarray(velocity, dtype=np.float64).reshape(-1)
        if (
            p.size not in (2, 3)
            or v.size != 3
            or not (np.all(np.isfinite(p)) and np.all(np.isfinite(v)))
        ):
            raise ParameterError(
                f"a bicycle's position is (x, y) or (x, y, z) m and its velocity (vx, vy, vz) "
                f"m/s, finite, got {position!r} and {velocity!r}"
            )
        origin = p.copy() if p.size == 3 else np.array([p[0], p[1], ground + CLEARANCE])
        return origin, _yaw(heading), v

    def __repr__(self) -> str:
        return f"Bicycle(kind={self._kind!r}, name={self._name!r}, mass={self.mass:.2f})"
