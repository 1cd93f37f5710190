"""The pedestrian's leg carries Riener and Edrich's (1999) passive elastic moments
(data/pedestrian.toml [passive]; docs/human.md, "The multibody pedestrian"): the laws against
the published equations written out here, the anatomical angles they read at the start
against the pose, and the engine's knee torque against the equation at the angles it ran
through."""

from __future__ import annotations

import math

import crashsim as cs
import numpy as np
import pytest
from crashsim.errors import ParameterError
from crashsim.human.pedestrian import PedestrianJoint
from crashsim.result import rotation_matrix

DAMPING = 1.0  # N m s/rad, every joint's (data/pedestrian.toml [resistance])


def exp(x: float) -> float:
    return math.exp(x)


# Riener and Edrich's equations (angles in degrees: hip and knee positive in flexion, the
# ankle in plantarflexion; N m positive in the joint's positive direction).
def hip_moment(h: float, k: float) -> float:
    return exp(1.4655 - 0.0034 * k - 0.0750 * h) - exp(1.3403 - 0.0226 * k + 0.0305 * h) + 8.072


def knee_moment(h: float, k: float, a: float) -> float:
    return (exp(1.800 - 0.0460 * a - 0.0352 * k + 0.0217 * h)
            - exp(-3.971 - 0.0004 * a + 0.0495 * k - 0.0128 * h)
            - 4.820 + exp(2.220 - 0.150 * k))  # fmt: skip


def ankle_moment(k: float, a: float) -> float:
    return exp(2.1016 - 0.0843 * a - 0.0176 * k) - exp(-7.9763 + 0.1949 * a + 0.0008 * k) - 1.792


def rotation_vector(r: np.ndarray) -> np.ndarray:
    """The rotation vector (rad) of the rotation matrix r (angle below pi)."""
    angle = math.acos(max(-1.0, min(1.0, (np.trace(r) - 1.0) / 2.0)))
    vee = np.array([r[2, 1] - r[1, 2], r[0, 2] - r[2, 0], r[1, 0] - r[0, 1]])
    return vee * (0.5 if angle < 1e-12 else angle / (2.0 * math.sin(angle)))


def leg(p: cs.Pedestrian, side: str) -> dict[str, PedestrianJoint]:
    return {j.name.split("_")[0]: j for j in p.joints if j.name.endswith(side)
            and j.name.split("_")[0] in ("hip", "knee", "ankle")}  # fmt: skip


@pytest.mark.parametrize("side", ["left", "right"])
def test_the_laws_are_riener_and_edrichs_equations(side: str) -> None:
    p = cs.Pedestrian(pose="walking")
    joints = leg(p, side)
    names = {"hip": "y", "knee": "angle", "ankle": "angle"}
    laws = {n: j.passive[names[n]] for n, j in joints.items()}
    assert set(laws) == {"hip", "knee", "ankle"}
    assert all(not j.passive for j in p.joints if j.name.split("_")[0] not in laws)
    for h, k, a in [(0.0, 0.0, 0.0), (30.0, 40.0, -10.0), (-15.0, 5.0, 25.0),
                    (90.0, 120.0, 35.0), (10.0, -5.0, -20.0)]:  # fmt: skip
        anatomical = {"hip": h, "knee": k, "ankle": a}
        # each joint's own angle in the engine: 0 where it was made (phi = offset + angle)
        engine = {(f"{n}_{side}", names[n]): math.radians(anatomical[n]) - laws[n].offset
                  for n in laws}  # fmt: skip
        got = {n: float(laws[n].moment(math.radians(anatomical[n]), engine)) for n in laws}
        assert got["hip"] == pytest.approx(hip_moment(h, k), rel=1e-12, abs=1e-12)
        assert got["knee"] == pytest.approx(knee_moment(h, k, a), rel=1e-12, abs=1e-12)
        assert got["ankle"] == pytest.approx(ankle_moment(k, a), rel=1e-12, abs=1e-12)


@pytest.mark.parametrize(
    ("pose", "side", "hip", "knee", "ankle"),
    [("walking", "left", 20.0, 5.0, 0.0), ("walking", "right", -15.0, 15.0, 10.0),
     ("standing", "left", 0.0, 0.0, 0.0), ("running", "right", -10.0, 90.0, 25.0)],
)  # fmt: skip
def test_the_laws_start_at_the_poses_angles(
    pose: str, side: str, hip: float, knee: float, ankle: float
) -> None:
    # pedestrian.toml's poses: the lead (left) and trailing (right) legs' angles (degrees)
    joints = leg(cs.Pedestrian(pose=pose), side)
    assert math.degrees(joints["knee"].passive["angle"].offset) == pytest.approx(knee, abs=1e-9)
    assert math.degrees(joints["ankle"].passive["angle"].offset) == pytest.approx(ankle, abs=1e-9)
    # the hip's ball: its rotation-vector y at the start (between its two frames) plus the
    # offset is the pose's flexion, the thigh forward positive
    hip_joint = joints["hip"]
    y = rotation_vector(hip_joint.axes.T @ hip_joint.child_axes)
    start = math.degrees(y[1] + hip_joint.passive["y"].offset)
    assert start == pytest.approx(hip, abs=1e-9)
    assert abs(y[0]) < 1e-12 and abs(y[2]) < 1e-12  # no abduction, no twist in the poses


def test_the_engine_turns_the_knee_by_the_law() -> None:
    # A standing person falls (no vehicle). Along each knee's axis the torque of the thigh on
    # the shank is Riener and Edrich's moment at the hip's, knee's and ankle's anatomical
    # angles of that sample less the joint's damping times the knee's rate (the hinge's
    # reactions lie across its axis), until the knee first meets a limit.
    p = cs.Pedestrian(pose="walking")
    scene = cs.Scene()
    scene.ground = cs.Ground()
    scene.add(p, (0.0, 0.0))
    result = scene.run(0.4, dt=1e-3)
    made = {j.name: j for j in scene.joints}
    for side in ("left", "right"):
        joints = leg(p, side)
        knee = result.joints[f"pedestrian/knee_{side}"]
        hip_made, knee_made = made[f"pedestrian/hip_{side}"], made[f"pedestrian/knee_{side}"]
        pelvis, thigh = (result.trajectory(n) for n in hip_made.vehicles)
        shank = result.trajectory(knee_made.vehicles[1])
        ankle = result.joints[f"pedestrian/ankle_{side}"]
        limit_hits = [e.time for e in result.joint_events
                      if e.joint == f"pedestrian/knee_{side}"]  # fmt: skip
        end = min(limit_hits, default=math.inf)
        checked = 0
        for k, t in enumerate(knee.t):
            if t >= end:
                break
            r_pelvis = rotation_matrix(pelvis.orientation[k])
            r_thigh = rotation_matrix(thigh.orientation[k])
            f1 = r_pelvis @ rotation_matrix(hip_made.frames[0][1])
            f2 = r_thigh @ rotation_matrix(hip_made.frames[1][1])
            h = math.degrees(rotation_vector(f1.T @ f2)[1] + joints["hip"].passive["y"].offset)
            kn = math.degrees(knee.angle("angle")[k] + joints["knee"].passive["angle"].offset)
            an = math.degrees(ankle.angle("angle")[k] + joints["ankle"].passive["angle"].offset)
            axis = r_thigh @ rotation_matrix(knee_made.frames[0][1])[:, 2]
            rate = float((shank.angular_velocity[k] - thigh.angular_velocity[k]) @ axis)
            expected = knee_moment(h, kn, an) - DAMPING * rate
            assert float(knee.torque[k] @ axis) == pytest.approx(expected, rel=1e-6, abs=1e-6)
            checked += 1
        assert checked > 50
        # the knee turned enough for the law's own angle to matter
        assert np.ptp(knee.angle("angle")[:checked]) > math.radians(5.0)


def test_the_factor_scales_every_law_and_zero_removes_them() -> None:
    base, half = cs.Pedestrian(pose="walking"), cs.Pedestrian(pose="walking", passive_moments=0.5)
    assert half.passive_moments == 0.5 and half.arguments["passive_moments"] == 0.5
    for j, k in zip(base.joints, half.joints, strict=True):
        assert set(j.passive) == set(k.passive)
        for angle, law in j.passive.items():
            coupled = {(c.joint, c.angle): 0.1 for term in law.terms if len(term) > 3
                       for c in term[3]}  # fmt: skip
            for phi in (-0.3, 0.0, 0.4, 1.2):
                assert float(k.passive[angle].moment(phi, coupled)) == pytest.approx(
                    0.5 * float(law.moment(phi, coupled)), rel=1e-12, abs=1e-12)
    assert not any(j.passive for j in cs.Pedestrian(passive_moments=0.0).joints)
    assert sum(1 for j in base.joints if j.passive) == 6


@pytest.mark.parametrize("bad", [-0.1, 10.5, math.nan, math.inf, True, "1"])
def test_a_bad_factor_is_refused(bad: object) -> None:
    with pytest.raises(ParameterError, match="passive_moments = .*: give a factor from 0"):
        cs.Pedestrian(passive_moments=bad)  # type: ignore[arg-type]
