"""Joints between vehicles, or a vehicle and the world (docs/joints.md).

A joint is made where the vehicles stand at t = 0 (:meth:`crashsim.Scene.join`): its anchor
``at`` (world point, m) and its axes (the joint frame, world; by default the first vehicle's
body frame then: x forward, y left, z up). The kinds (the engine's):

- "spherical" (a ball: a hitch ball), every rotation free;
- "revolute" (a hinge about the joint frame's z axis: a drawbar's pivot), angle "angle";
- "fixed", the two move as one;
- "fifth_wheel", a tractor's coupling: the trailer turns about its kingpin (the frame's z) and
  the plate pitches about its pivot (the frame's y); angles "articulation" and "pitch".

Limits (rad) stop an angle with an inelastic impulse and are reported
(:attr:`crashsim.Result.joint_events`); ``stiffness`` (N m/rad), ``damping`` (N m s/rad)
and ``friction`` (N m) resist the free rotation (the fifth wheel's and the hinge's about
their axis); a :class:`PassiveMoment` per angle adds a nonlinear moment, the form published
passive (relaxed) human joints take. The two vehicles' meshes do not collide with each
other unless ``collide``. The kind, limits and resistance are checked by the engine when the
joint is made.
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass
from typing import Any, NamedTuple

import numpy as np
from numpy.typing import ArrayLike, NDArray

from crashsim import _core
from crashsim.errors import ParameterError, SceneError
from crashsim.errors import at as error_at

__all__ = ["JOINT_KINDS", "CoupledAngle", "Joint", "JointEvent", "JointRecord", "PassiveMoment"]

JOINT_KINDS = ("spherical", "revolute", "fixed", "fifth_wheel")
"""The kinds of joint, as :meth:`crashsim.Scene.join` names them."""

Array = NDArray[np.float64]


@dataclass(frozen=True)
class CoupledAngle:
    """Another joint's angle a passive moment's term reads (a two-joint muscle: Riener and
    Edrich's knee moment reads the hip's and the ankle's angles): the exponent gains
    ``rate * (offset + that angle)``; ``joint`` is its name in the scene (a joint of the same
    jointed set, checked when the scene runs), ``angle`` its angle's name, ``rate`` 1/rad,
    ``offset`` rad (that angle's value where the joints are made)."""

    joint: str
    angle: str
    rate: float
    offset: float = 0.0


@dataclass(frozen=True)
class PassiveMoment:
    """A nonlinear passive moment about one of a joint's angles (docs/joints.md, "Passive
    moments"), the engine's law:

        M(phi) = sum(scale * exp(rate * (phi - centre) + coupled) for each term) + constant

    (N m) with ``phi = offset + the joint's angle`` (rad; the angle is 0 where the joint is
    made, so ``offset`` is phi there and a law published in anatomical angles is used as
    published; a ball joint made with ``axes2`` starts at the rotation between its frames).
    ``terms``: ((scale N m, rate 1/rad, centre rad), ...), a term optionally with a fourth
    item, its :class:`CoupledAngle` s (``coupled`` is the sum of their ``rate * (offset +
    angle)``). A positive M turns the second vehicle against the first towards a larger
    angle. The engine checks the numbers when the joint is made (rates within 200 /rad,
    sizes within 1e6 N m, offsets and centres within 2 pi)."""

    terms: tuple[tuple[Any, ...], ...] = ()
    constant: float = 0.0
    offset: float = 0.0

    def moment(
        self, phi: ArrayLike, coupled: Mapping[tuple[str, str], float] | None = None
    ) -> Array:
        """M (N m) at ``phi`` (rad, the law's own angle: offset included), each coupled angle
        at ``coupled[(joint, angle)]`` (rad, the joint's own angle: 0 where it was made, the
        default)."""
        x = np.asarray(phi, dtype=np.float64)
        total = np.full_like(x, float(self.constant))
        for term in self.terms:
            scale, rate, centre = term[:3]
            extra = sum(
                c.rate * (c.offset + (coupled or {}).get((c.joint, c.angle), 0.0))
                for c in (term[3] if len(term) > 3 else ())
            )
            total = total + scale * np.exp(rate * (x - centre) + extra)
        return total

    def to_dict(self) -> dict[str, Any]:
        d: dict[str, Any] = {
            "terms": [[float(v) for v in term[:3]] for term in self.terms],
            "constant": float(self.constant),
            "offset": float(self.offset),
        }
        coupled = [
            {"term": k, "joint": c.joint, "angle": c.angle, "rate": float(c.rate),
             "offset": float(c.offset)}
            for k, term in enumerate(self.terms)
            for c in (term[3] if len(term) > 3 else ())
        ]  # fmt: skip
        if coupled:
            d["coupled"] = coupled
        return d


@dataclass(frozen=True, eq=False)
class Joint:
    """A joint of a scene: ``vehicles`` (the first, and the second or None for the world),
    ``at`` (3,) the anchor (world, m, as made), ``axes`` (4,) the joint frame's orientation
    (world, quaternion w, x, y, z, as made), ``frames`` the same frame in each vehicle's body
    frame (anchor m, axes quaternion; the second in the world's for a joint to the world):
    what the engine gets, so a study that moves a combination as one keeps the joint where it
    was made on each body; and the engine's value (``kind``, ``limits``, ``stiffness``,
    ``damping``, ``friction``, ``collide``)."""

    name: str
    vehicles: tuple[str, str | None]
    at: Array
    axes: Array
    frames: tuple[tuple[Array, Array], tuple[Array, Array]]
    core: _core.Joint

    @property
    def kind(self) -> str:
        return str(self.core.kind)

    @property
    def angle_names(self) -> tuple[str, ...]:
        """The kind's angles (the columns of :attr:`JointRecord.angles` they fill)."""
        return tuple(self.core.angle_names)

    @property
    def passive(self) -> dict[str, PassiveMoment]:
        """{angle name: its passive moment}, as made."""
        couplings: dict[tuple[str, int], list[CoupledAngle]] = {}
        for law_angle, k, joint, angle, offset, rate in self.core.coupled:
            couplings.setdefault((law_angle, k), []).append(
                CoupledAngle(joint, angle, float(rate), float(offset))
            )
        out = {}
        for angle, offset, terms, constant in self.core.passive:
            rows: list[tuple[Any, ...]] = []
            for k, (a, b, c) in enumerate(terms):
                row: tuple[Any, ...] = (float(a), float(b), float(c))
                if (angle, k) in couplings:
                    row = (*row, tuple(couplings[(angle, k)]))
                rows.append(row)
            out[angle] = PassiveMoment(
                terms=tuple(rows), constant=float(constant), offset=float(offset)
            )
        return out

    def to_dict(self) -> dict[str, Any]:
        d: dict[str, Any] = {
            "name": self.name,
            "kind": self.kind,
            "vehicles": list(self.vehicles),
            "at": [float(x) for x in self.at],
            "axes": [float(x) for x in self.axes],
            "limits": {n: [lo, hi] for n, lo, hi in self.core.limits},
        }
        if self.core.passive:
            d["passive"] = {angle: law.to_dict() for angle, law in self.passive.items()}
        return d


def _vector(value: ArrayLike, size: int, what: str) -> Array:
    try:
        a = np.asarray(value, dtype=float).reshape(-1)
    except (TypeError, ValueError) as err:
        raise ParameterError(f"{what} must be {size} numbers, got {value!r}") from err
    if a.shape != (size,) or not np.all(np.isfinite(a)):
        raise ParameterError(f"{what} must be {size} finite numbers, got {value!r}")
    a.setflags(write=False)
    return a


def make_joint(
    name: str,
    vehicles: tuple[str, str | None],
    *,
    kind: str,
    at: ArrayLike,
    axes: ArrayLike,
    frames: tuple[tuple[ArrayLike, ArrayLike], tuple[ArrayLike, ArrayLike]],
    limits: Mapping[str, tuple[float, float]] | None,
    stiffness: float,
    damping: float,
    friction: float,
    collide: bool,
    passive: Mapping[str, PassiveMoment] | None = None,
) -> Joint:
    """A Joint, its kind, limits and resistance checked by the engine (errors name it)."""
    if kind not in JOINT_KINDS:
        raise ParameterError(
            f"joint {name!r}: kind {kind!r} is unknown; give one of {', '.join(JOINT_KINDS)}"
        )
    rows = []
    for angle, bounds in (limits or {}).items():
        try:
            lo, hi = (float(b) for b in bounds)
        except (TypeError, ValueError) as err:
            raise ParameterError(
                f"joint {name!r}: the {angle!r} limit must be (lower, upper) in rad, got {bounds!r}"
            ) from err
        rows.append((str(angle), lo, hi))
    if not isinstance(collide, bool):
        raise ParameterError(f"joint {name!r}: collide must be True or False, got {collide!r}")
    where = ("part", None, f"joint {name!r}")
    laws, coupled = [], []
    for angle, law in (passive or {}).items():
        if not isinstance(law, PassiveMoment):
            raise error_at(ParameterError(
                f"joint {name!r}: the passive moment about {angle!r} must be a "
                f"crashsim.PassiveMoment, got {law!r}"
            ), where)  # fmt: skip
        terms = []
        for k, term in enumerate(law.terms):
            try:
                if len(term) not in (3, 4):
                    raise ValueError
                terms.append((float(term[0]), float(term[1]), float(term[2])))
                for c in term[3] if len(term) == 4 else ():
                    if not isinstance(c, CoupledAngle):
                        raise ValueError
                    coupled.append((str(angle), k, str(c.joint), str(c.angle), float(c.offset),
                                    float(c.rate)))  # fmt: skip
            except (TypeError, ValueError) as err:
                raise error_at(ParameterError(
                    f"joint {name!r}: the passive moment about {angle!r} needs terms of (scale "
                    f"N m, rate 1/rad, centre rad[, (crashsim.CoupledAngle, ...)]), got {term!r}"
                ), where) from err  # fmt: skip
        laws.append((str(angle), float(law.offset), terms, float(law.constant)))
    try:
        core = _core.Joint(
            kind,
            limits=rows,
            stiffness=float(stiffness),
            damping=float(damping),
            friction=float(friction),
            collide=collide,
            passive=laws,
            coupled=coupled,
        )
    except ParameterError as err:
        raise error_at(err, ("part", None, f"joint {name!r}")) from err
    anchor, q = checked_frame(name, at, axes)
    in_bodies = tuple(
        (_vector(p, 3, f"joint {name!r}: anchor"), _vector(r, 4, f"joint {name!r}: axes"))
        for p, r in frames
    )
    return Joint(
        name=name, vehicles=vehicles, at=anchor, axes=q, frames=in_bodies, core=core
    )


def checked_frame(name: str, at: ArrayLike, axes: ArrayLike) -> tuple[Array, Array]:
    """A joint's anchor (3 finite numbers, m) and axes (a quaternion), ParameterError naming
    the joint otherwise."""
    return (
        _vector(at, 3, f"joint {name!r}: at"),
        _vector(axes, 4, f"joint {name!r}: axes (a quaternion w, x, y, z)"),
    )


def check_new(joints: list[Joint], joint: Joint) -> None:
    """A SceneError when the scene already has a joint of that name or between the same
    two vehicles."""
    for j in joints:
        if j.name == joint.name:
            raise SceneError(f"the scene already has a joint named {joint.name!r}")
        if joint.vehicles[1] is not None and set(j.vehicles) == set(joint.vehicles):
            raise SceneError(
                f"{joint.vehicles[0]!r} and {joint.vehicles[1]!r} are already joined by "
                f"{j.name!r}: one joint per pair"
            )


class JointRecord(NamedTuple):
    """One joint over a run (world frame, SI): ``name``, ``kind``, ``vehicles``, ``angle_names``;
    at the sample times ``t`` (k,): ``angles`` (k, 3) the kind's angles (rad, in the order of
    ``angle_names``: revolute ``angle``, fifth wheel ``articulation`` and ``pitch``, spherical
    ``swing`` and ``twist``; the rest 0), ``force`` (k, 3) the force of the first vehicle on
    the second through the joint (N; the coupling force), ``torque`` (k, 3) its torque about
    the anchor (N m)."""

    name: str
    kind: str
    vehicles: tuple[str, str | None]
    angle_names: tuple[str, ...]
    t: Array
    angles: Array
    force: Array
    torque: Array

    def angle(self, name: str) -> Array:
        """One angle over time (rad), by name (e.g. "articulation")."""
        if name not in self.angle_names:
            raise ParameterError(
                f"joint {self.name!r} ({self.kind}) has no angle {name!r}: its angles are "
                f"{list(self.angle_names) or 'none'}"
            )
        return self.angles[:, self.angle_names.index(name)]


class JointEvent(NamedTuple):
    """A joint's limit hit: the joint, the limited angle's name, when (s) and the relative
    angular rate the stop took out (rad/s)."""

    joint: str
    angle: str
    time: float
    rate: float

    def to_dict(self) -> dict[str, Any]:
        return {"joint": self.joint, "angle": self.angle, "time": self.time, "rate": self.rate}
