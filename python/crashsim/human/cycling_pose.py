"""The seated cycling pose of the multibody human (docs/human.md, "The cyclist"): its joint
angles solved from bike-fit targets (data/pedestrian.toml, ``[poses.cycling]``).

The targets: the trunk's angle to the horizontal (the line from the hip joints to the
shoulder joints), the knee's flexion and the ankle's plantarflexion with the crank at bottom
dead centre (the left leg), the shoulder's and elbow's flexion (hands forward on the
handlebar) and the neck's extension. The crank is vertical: the left pedal at the bottom, the
right at the top. The pose is fitted to a bicycle whose seat tube has the angle
``seat_tube_angle`` to the horizontal and whose cranks are ``crank_length`` long: the hip
joints lie on the seat tube's line through the bottom bracket.

Every angle here is in the sagittal plane (a rotation about the body's y axis), so the
geometry is two-dimensional: points (x, z) of the body frame (x forward, z up, m) in the
standing reference posture, turned about y. ``_turn(v, a)`` turns (x, z) as a rotation by
``a`` rad about +y does (+z towards +x): a hip's or shoulder's flexion is a turn by minus
its angle, a knee's flexion and an ankle's plantarflexion by plus theirs.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Mapping, Sequence
from typing import TYPE_CHECKING

import numpy as np

from crashsim.errors import ParameterError
from crashsim.small_linalg import norm

if TYPE_CHECKING:
    from crashsim.human.anthropometry import Segment

__all__ = ["CYCLING_KEYS", "cycling_angles", "pedal_points"]

# The angles cycling_angles returns (degrees), as the pose's rotations read them.
CYCLING_KEYS = (
    "lumbar_flexion",
    "neck_extension",
    "shoulder_flexion",
    "elbow_flexion",
    "hip_flexion_left",
    "knee_flexion_left",
    "ankle_plantarflexion_left",
    "hip_flexion_right",
    "knee_flexion_right",
    "ankle_plantarflexion_right",
)

Vec = np.ndarray


def _turn(v: Vec, a: float) -> Vec:
    """(x, z) turned as a rotation by ``a`` rad about +y turns it (+z towards +x)."""
    c, s = math.cos(a), math.sin(a)
    return np.array([v[0] * c + v[1] * s, -v[0] * s + v[1] * c])


def _angle(v: Vec) -> float:
    """The direction of (x, z) from +x towards +z (rad)."""
    return math.atan2(float(v[1]), float(v[0]))


def _wrap(a: float) -> float:
    """An angle (rad) brought into (-pi, pi]."""
    return math.atan2(math.sin(a), math.cos(a))


def _xz(p: Sequence[float]) -> Vec:
    return np.array([float(p[0]), float(p[2])])


def _bisect(f: Callable[[float], float], lo: float, hi: float, what: str) -> float:
    """The root of an increasing-or-decreasing f in [lo, hi] (rad), to 1e-13 rad."""
    flo, fhi = f(lo), f(hi)
    if flo * fhi > 0.0:
        raise ParameterError(
            f"the cycling pose has no {what} between {math.degrees(lo):.0f} and "
            f"{math.degrees(hi):.0f} deg: check the pose's angles in pedestrian.toml"
        )
    for _ in range(200):
        mid = 0.5 * (lo + hi)
        fm = f(mid)
        if (fm < 0.0) == (flo < 0.0):
            lo, flo = mid, fm
        else:
            hi = mid
        if hi - lo < 1e-13:
            break
    return 0.5 * (lo + hi)


class _Leg:
    """One leg's standing points (x, z): hip, knee and ankle joints, the ball of the foot on
    its sole (the pedal's contact point)."""

    def __init__(self, seg: Mapping[str, Segment], side: str, ball: float) -> None:
        thigh, shank, foot = seg[f"thigh_{side}"], seg[f"shank_{side}"], seg[f"foot_{side}"]
        assert thigh.joint is not None and shank.joint is not None and foot.joint is not None
        self.hip = _xz(thigh.joint.position)
        self.knee = _xz(shank.joint.position)
        self.ankle = _xz(foot.joint.position)
        heel, toe = _xz(foot.origin), _xz(foot.end)
        # the sole lies one capsule radius under the foot's axis (heel to toe tip)
        self.ball = heel + ball * (toe - heel) - np.array([0.0, foot.contact.radius])

    def posed(self, hip: float, knee: float, ankle: float) -> tuple[Vec, Vec, Vec]:
        """The knee, ankle and ball of the foot (x, z) for hip flexion, knee flexion and
        plantarflexion (rad)."""
        k = self.hip + _turn(self.knee - self.hip, -hip)
        a = k + _turn(self.ankle - self.knee, -hip + knee)
        b = a + _turn(self.ball - self.ankle, -hip + knee + ankle)
        return k, a, b


def cycling_angles(data: Sequence[Segment], pose: Mapping[str, float]) -> dict[str, float]:
    """The cycling pose's joint angles (degrees, CYCLING_KEYS) for the segments ``data``
    (body_segments') and the pose's targets (degrees, m; ``[poses.cycling]``)."""
    seg = {s.name: s for s in data}
    rad = math.radians
    out = {
        "neck_extension": float(pose["neck_extension"]),
        "shoulder_flexion": float(pose["shoulder_flexion"]),
        "elbow_flexion": float(pose["elbow_flexion"]),
    }
    # The trunk: the lower torso (and all above it) leans at the lumbar joint until the line
    # from the hips to the shoulders makes the torso angle with the horizontal.
    lumbar = _xz(seg["lower_torso"].joint.position)  # type: ignore[union-attr]
    shoulder = _xz(seg["upper_arm_left"].joint.position)  # type: ignore[union-attr]
    hips = _xz(seg["thigh_left"].joint.position)  # type: ignore[union-attr]
    torso = rad(float(pose["torso_angle"]))

    def trunk(phi: float) -> float:
        return _wrap(_angle(lumbar + _turn(shoulder - lumbar, phi) - hips) - torso)

    out["lumbar_flexion"] = math.degrees(_bisect(trunk, 0.0, rad(90.0), "trunk lean"))
    # The left leg at bottom dead centre: knee and ankle as given, the hip flexed until the
    # hip joint lies on the seat tube's line through the bottom bracket (the crank's length
    # above the pedal's contact point).
    ball = float(pose["ball_of_foot"])
    crank = float(pose["crank_length"])
    seat_line = math.pi - rad(float(pose["seat_tube_angle"]))  # from the bracket to the hip
    knee, ankle = rad(float(pose["knee_flexion_bdc"])), rad(float(pose["ankle_plantarflexion"]))
    left = _Leg(seg, "left", ball)

    def on_seat_line(hip: float) -> float:
        bracket = left.posed(hip, knee, ankle)[2] + np.array([0.0, crank])
        return _wrap(_angle(left.hip - bracket) - seat_line)

    hip_left = _bisect(on_seat_line, rad(-30.0), rad(85.0), "hip flexion at bottom dead centre")
    out.update(
        hip_flexion_left=math.degrees(hip_left),
        knee_flexion_left=math.degrees(knee),
        ankle_plantarflexion_left=math.degrees(ankle),
    )
    # The right leg at top dead centre: its ball of the foot two crank lengths above the
    # left's, the same plantarflexion (assumed); hip and knee from the two-link chain (thigh,
    # and the shank with the foot held to it), the knee forward.
    right = _Leg(seg, "right", ball)
    target = left.posed(hip_left, knee, ankle)[2] + np.array([0.0, 2.0 * crank])
    link = (right.ankle - right.knee) + _turn(right.ball - right.ankle, ankle)  # shank frame
    l1, l2 = float(norm(right.knee - right.hip)), float(norm(link))
    to_target = target - right.hip
    d = float(norm(to_target))
    if not abs(l1 - l2) < d < l1 + l2:
        raise ParameterError(
            f"the cycling pose cannot reach the top pedal: it is {d:.3f} m from the hip, the "
            f"leg reaches {abs(l1 - l2):.3f} to {l1 + l2:.3f} m: check the crank length and "
            "the knee angle at bottom dead centre"
        )
    spread = math.acos((l1 * l1 + d * d - l2 * l2) / (2.0 * l1 * d))
    knees = [right.hip + l1 * np.array([math.cos(_angle(to_target) + s),
                                        math.sin(_angle(to_target) + s)])
             for s in (spread, -spread)]  # fmt: skip
    knee_at = max(knees, key=lambda k: float(k[0]))  # the knee forward
    thigh_turn = _wrap(_angle(right.knee - right.hip) - _angle(knee_at - right.hip))
    shank_turn = _wrap(_angle(link) - _angle(target - knee_at))
    out.update(
        hip_flexion_right=math.degrees(-thigh_turn),
        knee_flexion_right=math.degrees(shank_turn - thigh_turn),
        ankle_plantarflexion_right=math.degrees(ankle),
    )
    return out


def pedal_points(
    data: Sequence[Segment], pose: Mapping[str, float], angles: Mapping[str, float]
) -> dict[str, Vec]:
    """Where the pose puts the balls of the feet on their soles, (x, z) in the standing body
    frame's coordinates (m): ``left`` (bottom dead centre), ``right`` (top), and the bottom
    bracket (``bracket``) the crank's length above the left."""
    seg = {s.name: s for s in data}
    ball = float(pose["ball_of_foot"])
    out = {}
    for side in ("left", "right"):
        leg = _Leg(seg, side, ball)
        out[side] = leg.posed(*(math.radians(float(angles[f"{j}_{side}"]))
                                for j in ("hip_flexion", "knee_flexion",
                                          "ankle_plantarflexion")))[2]  # fmt: skip
    out["bracket"] = out["left"] + np.array([0.0, float(pose["crank_length"])])
    return out
