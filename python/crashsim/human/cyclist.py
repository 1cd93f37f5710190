"""The multibody cyclist (docs/human.md, "The cyclist"): a rider (a :class:`Pedestrian` in
the seated "cycling" pose) on a :class:`Bicycle` fitted to it.

The fit: the bicycle's bottom bracket goes the crank's length above the ball of the rider's
lower foot (the cranks vertical), the saddle's top 1 mm under the pelvis's contact sphere, the
handlebar's axis under the middle of the hands, the pedals 1 mm under the soles. The pose put
the hip joints on the seat tube's line through the bracket (cycling_pose.py), so the bracket,
saddle and hips lie as the bike-fit targets say.

How the rider is held: by contact only, no joint (the engine has no joint that breaks). The
pelvis on the saddle, the hands on the handlebar and the feet on the pedals have soft
contacts with the frame (Scene.soft_contact: a spring-damper while the meshes overlap, with
friction; data in the SADDLE, HANDS and FEET tuples below, assumed); every other pair of a
rider's segment and a bicycle's body never collides (Scene.no_contact), as the rider's
unjoined segments among themselves. So the rider sits and is carried by friction, and leaves
the bicycle when struck. Without muscles (the joints have only the pedestrian's damping and
the leg's passive moments of a relaxed subject) the rider slumps over the handlebar within a
fraction of a second; the strikes reach it sooner.
"""

from __future__ import annotations

import math

import numpy as np
from numpy.typing import ArrayLike, NDArray

from crashsim.errors import ParameterError
from crashsim.human.bicycle import Bicycle, BicycleFit, Parts
from crashsim.human.cycling_pose import pedal_points
from crashsim.human.pedestrian import ROAD_FRICTION, Pedestrian
from crashsim.names import check_name
from crashsim.small_linalg import matmul, norm
from crashsim.vehicles.vehicle import Vehicle

__all__ = ["CONTACTS", "Cyclist"]

Array = NDArray[np.float64]
GAP = 1e-3  # m, between each contact point of the rider and the bicycle at the start
# The rider's soft contacts with the frame: segments, stiffness N/m, damping ratio, friction.
# Assumed (no published saddle, grip or pedal stiffness was read): the saddle sinks about
# 5 mm under the whole upper body; hands and feet are softer so that a 1 ms step suits their
# light segments with no sub-steps (Scene.soft_contact: sqrt(k / m) dt <= 0.2).
SADDLE = (("pelvis",), 1.0e5, 0.5, 0.5)
HANDS = (("hand_left", "hand_right"), 1.5e4, 0.5, 0.5)
FEET = (("foot_left", "foot_right"), 3.0e4, 0.5, 0.5)
CONTACTS = (SADDLE, HANDS, FEET)


class Cyclist:
    """A rider on a bicycle (module docstring). ``rider``: a :class:`Pedestrian` in the
    "cycling" pose, or None to make one from ``height`` (m), ``mass`` (kg), ``sex``,
    ``percentile``, ``passive_moments`` (the factor on its leg's passive joint moments,
    :class:`Pedestrian`'s), ``road_friction`` (its segments' friction sliding on the road,
    :class:`Pedestrian`'s); ``bicycle``: a :class:`Bicycle` (its kind is used; the cyclist fits a
    copy to the rider), default the city bicycle; ``name`` (default the rider's name, else
    "cyclist") names the rider's segments "<name>/head", ... and the bicycle's bodies
    "<name>/frame", "<name>/rear_wheel", "<name>/front_wheel".

    Attributes: ``rider`` (the :class:`Pedestrian`), ``bicycle`` (the fitted
    :class:`Bicycle`), ``bodies`` (every body: the rider's segments, then the bicycle's),
    ``rider_offset`` (3,) the rider's body frame origin in the bicycle frame (m), ``mass``,
    ``name``."""

    def __init__(
        self,
        rider: Pedestrian | None = None,
        bicycle: Bicycle | None = None,
        *,
        height: float = 1.75,
        mass: float = 75.0,
        sex: str = "male",
        percentile: float | None = None,
        name: str | None = None,
        passive_moments: float = 1.0,
        road_friction: float = ROAD_FRICTION,
    ) -> None:
        if rider is not None and not isinstance(rider, Pedestrian):
            raise ParameterError(f"rider must be a crashsim.Pedestrian, got {type(rider).__name__}")
        if bicycle is not None and not isinstance(bicycle, Bicycle):
            raise ParameterError(
                f"bicycle must be a crashsim.Bicycle, got {type(bicycle).__name__}"
            )
        if name is None:
            name = rider.name if rider is not None else "cyclist"
        check_name(name, "a cyclist")
        if rider is None:
            rider = Pedestrian(height, mass, sex, percentile, pose="cycling", name=name,
                               passive_moments=passive_moments, road_friction=road_friction)
        elif rider.pose != "cycling":
            raise ParameterError(
                f"the rider's pose is {rider.pose!r}: a cyclist's rider needs "
                'Pedestrian(..., pose="cycling")'
            )
        elif rider.name != name:
            raise ParameterError(
                f"the rider is named {rider.name!r} and the cyclist {name!r}: give them the same "
                "name (it prefixes every body's name), or leave the cyclist's name out"
            )
        kind = "city" if bicycle is None else bicycle.kind
        base = Bicycle(kind, name)
        angles = rider.pose_angles
        for key, value in (
            ("crank_length", base.crank_length),
            ("seat_tube_angle", math.degrees(base.seat_tube_angle)),
        ):
            if abs(angles[key] - value) > 1e-9:
                raise ParameterError(
                    f"the rider's cycling pose is fitted to a {key} of {angles[key]:g}, the "
                    f"{kind} bicycle has {value:g}: they must agree (pedestrian.toml's "
                    "[poses.cycling] and bicycle.toml)"
                )
        self._rider, self._name = rider, name
        self._offset, fit = _fit(rider, base)
        self._bicycle = base.fitted(fit)

    @property
    def name(self) -> str:
        return self._name

    @property
    def rider(self) -> Pedestrian:
        return self._rider

    @property
    def bicycle(self) -> Bicycle:
        return self._bicycle

    @property
    def bodies(self) -> tuple[Vehicle, ...]:
        return (*self._rider.segments, *self._bicycle.bodies)

    @property
    def mass(self) -> float:
        """Rider and bicycle (kg)."""
        return self._rider.mass + self._bicycle.mass

    @property
    def rider_offset(self) -> Array:
        return self._offset.copy()

    def cg(self) -> Array:
        """The rider and bicycle's centre of mass in the bicycle frame (m)."""
        rider = self._rider.cg() + self._offset
        return (self._rider.mass * rider + self._bicycle.mass * self._bicycle.cg()) / self.mass

    def placement(
        self, position: ArrayLike, heading: float, velocity: ArrayLike, ground: float
    ) -> Parts:
        """What a scene adds (:class:`Parts`): the bicycle as :meth:`Bicycle.placement`
        puts it, the rider's segments and joints on it (all moving at ``velocity``), the
        rider's soft contacts with the frame and the pairs that never collide."""
        parts = self._bicycle.placement(position, heading, velocity, ground)
        origin, yaw, v = self._bicycle.origin(position, heading, velocity, ground)
        seat = origin + matmul(yaw, self._offset)
        bodies, joints = self._rider.placement(seat, heading, v, ground)
        parts.bodies = [(b, cg, rot, vel, np.zeros(3)) for b, cg, rot, vel in bodies] + parts.bodies
        prefix = f"{self._name}/"
        parts.joints = [dict(
            vehicle1=prefix + j.parent, vehicle2=prefix + j.child, at=at, kind=j.kind,
            axes=axes, limits=j.limits, stiffness=j.stiffness, damping=j.damping,
            friction=j.friction, name=prefix + j.name, axes2=child_axes,
            passive=j.passive_in(prefix),
        ) for j, at, axes, child_axes in joints] + parts.joints  # fmt: skip
        segments = [s.name for s in self._rider.segments]
        joined = {frozenset((prefix + j.parent, prefix + j.child)) for j, *_ in joints}
        for i, a in enumerate(segments):
            for b in segments[i + 1 :]:
                if frozenset((a, b)) not in joined:
                    parts.no_contact.append((a, b))
        frame = self._bicycle.frame.name
        held = {}
        for names, k, zeta, mu in CONTACTS:
            for n in names:
                held[prefix + n] = (k, zeta, mu)
        for s in segments:
            for body in self._bicycle.bodies:
                if body.name == frame and s in held:
                    k, zeta, mu = held[s]
                    parts.soft.append((frame, s, k, zeta, {"normal": "volume", "friction": mu}))
                else:
                    parts.no_contact.append((body.name, s))
        return parts

    def __repr__(self) -> str:
        return (
            f"Cyclist(name={self._name!r}, rider height={self._rider.height:.3f} m, mass="
            f"{self._rider.mass:.1f} kg, bicycle={self._bicycle.kind!r})"
        )


def _fit(rider: Pedestrian, bicycle: Bicycle) -> tuple[Array, BicycleFit]:
    """The rider's body frame origin in the bicycle frame (m) and where the saddle, handlebar
    and pedals go (module docstring)."""
    data = rider.data
    pedals = pedal_points(data, rider.pose_angles, rider.pose_angles)
    bracket = bicycle.bracket
    # the bracket the crank's length above the lower pedal's contact, less the gap
    offset = np.array([bracket[0] - pedals["bracket"][0], 0.0,
                       bracket[2] - pedals["bracket"][1] + GAP])  # fmt: skip
    # the saddle under the pelvis's contact sphere (its centre halfway along the segment)
    pelvis = next(s for s in data if s.name == "pelvis")
    centre, _ = rider.posed("pelvis")
    centre = centre - np.asarray(pelvis.cg_body) + (np.add(pelvis.origin, pelvis.end) / 2.0)
    saddle = centre + offset - [0.0, 0.0, pelvis.contact.radius + GAP]
    # the handlebar under the middle of the left hand's axis, across it
    hand = next(s for s in data if s.name == "hand_left")
    cg, rot = rider.posed("hand_left")
    ends = [cg + matmul(rot, np.asarray(p) - hand.cg_body) for p in (hand.origin, hand.end)]
    axis = (ends[1] - ends[0]) / norm(ends[1] - ends[0])
    up = np.array([-axis[2], 0.0, axis[0]]) * (1.0 if axis[0] > 0 else -1.0)
    radius = float(bicycle.data["assumed"]["bar_radius"])
    bar = (ends[0] + ends[1]) / 2.0 + offset - (hand.contact.radius + radius + GAP) * up
    foot = next(s for s in data if s.name == "foot_left")
    a = rider.pose_angles
    tilt = [
        math.radians(
            -a[f"hip_flexion_{s}"] + a[f"knee_flexion_{s}"] + a[f"ankle_plantarflexion_{s}"]
        )
        for s in ("left", "right")
    ]
    fit = BicycleFit(
        saddle=(float(saddle[0]), float(saddle[2])),
        handlebar=(float(bar[0]), float(bar[2])),
        pedal_offset=float(foot.origin[1]),
        pedal_tilt=(tilt[0], tilt[1]),
    )
    return offset, fit
