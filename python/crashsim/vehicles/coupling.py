"""Couplings between a towing vehicle and its trailer (docs/joints.md, "Articulated vehicles").

A towing vehicle has a :class:`Hitch` of kind "ball" (a tow ball: a car, a van, a rigid
truck's drawbar coupling), "fifth_wheel" (a tractor) or "turntable" (a drawbar trailer's
dolly, under the trailer's front); a trailer has one of kind "coupler" (the drawbar's eye or
cup, on a ball: a centre-axle trailer, a caravan, a dolly), "kingpin" (a semitrailer, on a
fifth wheel) or "ring" (a drawbar trailer's body, on its dolly's turntable). A coupler goes on
a ball and makes a spherical joint; a kingpin goes on a fifth wheel and makes a fifth-wheel
joint (yaw free, pitch about the plate's pivot, no roll between the units); a ring goes on a
turntable and makes a revolute joint about the vertical (the dolly steers the body's front).
:meth:`crashsim.Scene.add` with ``trailers=`` puts each trailer's coupler on the hitch before
it and joins them.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike, NDArray

from crashsim.errors import ParameterError, SceneError

__all__ = ["HITCH_KINDS", "JOINT_OF", "Hitch", "check_coupling"]

Array = NDArray[np.float64]

TOWING = ("ball", "fifth_wheel", "turntable")
"""A towing vehicle's hitch kinds."""
TOWED = ("coupler", "kingpin", "ring")
HITCH_KINDS = TOWING + TOWED
"""A towing vehicle's hitch kinds, then a trailer's."""

MATES = {"coupler": "ball", "kingpin": "fifth_wheel", "ring": "turntable"}
"""Which towing hitch each trailer coupling goes on."""

JOINT_OF = {"coupler": "spherical", "kingpin": "fifth_wheel", "ring": "revolute"}
"""The joint a trailer's coupling makes with its hitch."""


@dataclass(frozen=True)
class Hitch:
    """A hitch: ``kind`` (see HITCH_KINDS) and ``point`` (3,), the body-frame point (m from
    the CG: x forward, y left, z up) where the two units meet: the tow ball's centre, the
    kingpin's lock in the fifth wheel."""

    kind: str
    point: Array

    @classmethod
    def at(cls, kind: str, point: ArrayLike, *, towing: bool) -> Hitch:
        """A hitch of ``kind`` at the body-frame ``point`` (m); ``towing``: the towing
        vehicle's (ball, fifth_wheel) rather than a trailer's (coupler, kingpin)."""
        kinds = TOWING if towing else TOWED
        if kind not in kinds:
            whose = "a towing vehicle's hitch" if towing else "a trailer's coupling"
            raise ParameterError(f"{whose} kind {kind!r} is unknown: give one of {kinds}")
        p = np.array(point, dtype=np.float64).reshape(-1)
        if p.shape != (3,) or not np.all(np.isfinite(p)):
            raise ParameterError(f"the {kind}'s point must be 3 finite numbers (m), got {point!r}")
        p.setflags(write=False)
        return cls(kind, p)

    def mates(self, hitch: Hitch) -> bool:
        """True when this trailer coupling goes on ``hitch``."""
        return MATES.get(self.kind) == hitch.kind

    def to_dict(self) -> dict[str, object]:
        return {"kind": self.kind, "point": [float(x) for x in self.point]}


def check_coupling(tower: str, hitch: Hitch | None, trailer: str, coupler: Hitch | None) -> None:
    """SceneError unless vehicle ``trailer``'s ``coupler`` goes on vehicle ``tower``'s
    ``hitch`` (a kingpin on a fifth wheel, a drawbar's coupler on a ball)."""
    who = f"{tower!r} towing {trailer!r}"
    if hitch is None:
        raise SceneError(f"{who}: {tower!r} has no hitch (vehicle.with_hitch)")
    if coupler is None:
        raise SceneError(f"{who}: {trailer!r} has no coupler (build it with Trailer)")
    if not coupler.mates(hitch):
        raise SceneError(
            f"{who}: a {coupler.kind} does not go on a {hitch.kind} (a kingpin goes on a "
            "fifth wheel, a drawbar's coupler on a ball)"
        )
