"""The multibody pedestrian (crashsim.Pedestrian, docs/human.md "The multibody pedestrian"):
its segments and joints as the data give them, its placement in a scene, and physical checks
(free fall of the whole body's centre of mass, momentum through an exchange with a car)."""

from __future__ import annotations

import math

import crashsim as cs
import numpy as np
import pytest
from crashsim.errors import ParameterError, SceneError
from crashsim.human import body_segments
from crashsim.result import rotation_matrix

G = 9.80665  # m/s^2, the engine's gravity


@pytest.fixture(scope="module")
def standing() -> cs.Pedestrian:
    return cs.Pedestrian(height=1.75, mass=75.0, sex="male")


def joint(p: cs.Pedestrian, name: str):
    return next(j for j in p.joints if j.name == name)


def feet(p: cs.Pedestrian) -> tuple[np.ndarray, np.ndarray]:
    """The left and right feet's CGs in the pose (body frame, m)."""
    return p.posed("foot_left")[0], p.posed("foot_right")[0]


def lowest_point(result: cs.Result, segments, k: int) -> float:
    """The lowest point (m) of the segments' meshes at sample k."""
    return min(
        float((result.trajectory(v.name).position[k] + v.body_vertices
               @ rotation_matrix(result.trajectory(v.name).orientation[k]).T)[:, 2].min())
        for v in segments
    )  # fmt: skip


def largest_joint_gap(scene: cs.Scene, result: cs.Result) -> tuple[float, str]:
    """The largest distance (m) between a joint's anchors on its two bodies at the last
    sample, and that joint's name."""
    gaps = []
    for j in scene.joints:
        (pa, _), (pb, _) = j.frames
        ta, tb = result.trajectory(j.vehicles[0]), result.trajectory(j.vehicles[1])
        wa = ta.position[-1] + rotation_matrix(ta.orientation[-1]) @ pa
        wb = tb.position[-1] + rotation_matrix(tb.orientation[-1]) @ pb
        gaps.append((float(np.linalg.norm(wa - wb)), j.name))
    return max(gaps)


def test_mass_height_and_segments(standing: cs.Pedestrian) -> None:
    data = body_segments(1.75, 75.0, "male")
    assert len(standing.segments) == 16 and len(standing.joints) == 15
    assert sum(v.mass for v in standing.segments) == pytest.approx(75.0, abs=1e-9)
    for v, s in zip(standing.segments, data, strict=True):
        assert v.name == f"pedestrian/{s.name}"
        assert v.mass == s.mass
        np.testing.assert_array_equal(np.diag(v.inertia), s.inertia)
        np.testing.assert_array_equal(v.cg, s.cg)
    # the capsules stand the stature: vertex on top, the feet's capsules under it (their
    # 8-sided section's lowest vertex on the ground)
    z = standing.vertices()[:, 2]
    assert standing.height == pytest.approx(1.75, abs=1e-12)
    assert z.max() == pytest.approx(1.75, abs=1e-9)
    assert 0.0 <= z.min() < 2e-3


def test_joints_meet_their_segments(standing: cs.Pedestrian) -> None:
    """Each joint sits where the data put it on its child, moved into the pose, and where the
    chain joints' parent ends (the hip, shoulder and ankle sit off their parent's ends)."""
    walking = cs.Pedestrian(pose="walking")
    for p in (standing, walking):
        for j in p.joints:
            child = next(s for s in p.data if s.name == j.child)
            parent = next(s for s in p.data if s.name == j.parent)
            cg, rot = p.posed(child.name)
            # the data's joint position moved with the child's pose
            at_child = cg + rot @ (np.asarray(child.joint.position) - child.cg_body)
            np.testing.assert_allclose(at_child, j.at, atol=1e-12)
            if j.name.split("_")[0] in ("hip", "shoulder", "ankle"):
                continue
            pcg, prot = p.posed(parent.name)
            ends = [pcg + prot @ (np.asarray(e) - parent.cg_body) for e in
                    (parent.origin, parent.end)]
            assert min(np.linalg.norm(e - j.at) for e in ends) < 1e-12, j.name


def test_kinds_and_limits_from_the_ranges(standing: cs.Pedestrian) -> None:
    deg = math.radians
    kinds = {j.name: j.kind for j in standing.joints}
    for name in ("knee_left", "elbow_right", "ankle_left"):
        assert kinds[name] == "revolute"
    for name in ("hip_left", "shoulder_right", "neck", "lumbar", "thoracic", "wrist_left"):
        assert kinds[name] == "spherical"
    # Castori (2012): knee hyperextension 0 (men), ankle 20 / 50, neck 45; the normal-ROM
    # table: knee flexion 140, elbow 145, hip flexion 125 and extension 30 (the cone),
    # rotations 60 / 40
    assert joint(standing, "knee_left").limits["angle"] == pytest.approx((0.0, deg(140)))
    assert joint(standing, "elbow_left").limits["angle"] == pytest.approx((-deg(10), deg(145)))
    assert joint(standing, "ankle_right").limits["angle"] == pytest.approx((-deg(20), deg(50)))
    assert joint(standing, "neck").limits["swing"] == pytest.approx((0.0, deg(45)))
    assert joint(standing, "lumbar").limits["swing"] == pytest.approx((0.0, deg(17.5)))
    hip_l, hip_r = joint(standing, "hip_left"), joint(standing, "hip_right")
    # the hip's cone: half-angle (125 + 30) / 2 about the standing thigh turned forward by
    # (125 - 30) / 2, so the thigh stops at 125 deg forward and 30 deg back
    assert hip_l.limits["swing"] == pytest.approx((0.0, deg(77.5)))
    cone, limb = hip_l.axes[:, 2], hip_l.child_axes[:, 2]
    assert math.degrees(math.acos(cone @ limb)) == pytest.approx(47.5)
    assert cone[0] > 0.7  # forward
    assert hip_l.limits["twist"] == pytest.approx((-deg(60), deg(40)))  # mirrored sides
    assert hip_r.limits["twist"] == pytest.approx((-deg(40), deg(60)))
    assert "swing" not in joint(standing, "shoulder_left").limits  # 180 deg: no cone
    female = cs.Pedestrian(1.65, 60.0, "female")
    assert joint(female, "knee_left").limits["angle"] == pytest.approx((-deg(10), deg(140)))
    # a ball's frame runs along its child: the knee below the hip
    z = joint(standing, "hip_left").child_axes[:, 2]
    assert z[2] < -0.99
    assert joint(standing, "neck").child_axes is None  # its cone centred on the pose


def test_walking_pose_shifts_the_hinges_limits() -> None:
    p = cs.Pedestrian(pose="walking")
    deg = math.radians
    # the lead knee starts flexed 5 deg, the trailing one 15 deg: their ranges stay the
    # standing posture's
    assert joint(p, "knee_left").limits["angle"] == pytest.approx((-deg(5), deg(135)))
    assert joint(p, "knee_right").limits["angle"] == pytest.approx((-deg(15), deg(125)))
    assert joint(p, "elbow_left").limits["angle"] == pytest.approx((-deg(30), deg(125)))
    # legs apart: the left foot ahead of the right
    left, right = feet(p)
    assert left[0] - right[0] > 0.4


def test_running_pose_lands_on_the_lead_foot_with_the_trailing_leg_swung_back() -> None:
    p = cs.Pedestrian(pose="running")
    a = p.pose_angles
    # pedestrian.toml's [poses.running]: the lead foot's strike, the trailing leg in early swing
    assert (a["lead_hip_flexion"], a["lead_knee_flexion"], a["trail_hip_extension"],
            a["trail_knee_flexion"], a["trail_ankle_plantarflexion"]) == (50, 21, 10, 90, 25)
    deg = math.radians
    # hinge limits: the standing ranges less the pose's starting angles
    assert joint(p, "knee_left").limits["angle"] == pytest.approx((-deg(21), deg(119)))
    assert joint(p, "knee_right").limits["angle"] == pytest.approx((-deg(90), deg(50)))
    assert joint(p, "elbow_left").limits["angle"] == pytest.approx((-deg(100), deg(55)))
    # the lead foot far ahead of the trailing one (a longer stride than walking's), the
    # trailing foot above it
    left, right = feet(p)
    walking_left, walking_right = feet(cs.Pedestrian(pose="walking"))
    assert left[0] - right[0] > 1.0 > walking_left[0] - walking_right[0]
    assert right[2] > left[2] + 0.1
    scene = cs.Scene(ground=cs.Ground())
    scene.add(p, (0.0, 0.0), velocity=(3.0, 0.0, 0.0))
    result = scene.run(0.2, dt=1e-3)
    # at the start the lead foot is the body's lowest point, 1 mm above the road, and the
    # trailing foot is in the air
    assert lowest_point(result, [p.segment("foot_left")], 0) == pytest.approx(1e-3, abs=1e-9)
    assert lowest_point(result, p.segments, 0) == pytest.approx(1e-3, abs=1e-9)
    assert lowest_point(result, [p.segment("foot_right")], 0) > 0.1
    # it runs on at about its speed for 0.2 s, and the joints hold
    pelvis = result.trajectory("pedestrian/pelvis")
    assert 0.4 < pelvis.position[-1, 0] - pelvis.position[0, 0] < 0.65
    gap, name = largest_joint_gap(scene, result)
    assert gap < 1e-6, name


def test_scene_runs_and_names_segments(standing: cs.Pedestrian) -> None:
    scene = cs.Scene(ground=cs.Ground())
    scene.add(standing, (1.0, 2.0), heading=0.3)
    assert len(scene.vehicles) == 16 and len(scene.joints) == 15
    # its segments never strike each other: no pair among them (15 joined, 105 no-contact)
    assert scene.pairs() == [] and len(scene.to_spec(0.05).no_contact) == 105
    result = scene.run(0.05)
    head = result.trajectory("pedestrian/head")
    assert head.position[0, 2] > 1.5
    # the joints hold: the anchors on both bodies together
    gap, name = largest_joint_gap(scene, result)
    assert gap < 1e-9, name
    # the body frame's origin at (1, 2), the lowest point 1 mm above the ground
    assert lowest_point(result, standing.segments, 0) == pytest.approx(1e-3, abs=1e-9)


def test_whole_body_falls_freely(standing: cs.Pedestrian) -> None:
    """High above the ground, the jointed body's centre of mass falls as g t^2 / 2 (the
    joints' forces are internal) and the joints stay together."""
    scene = cs.Scene(ground=cs.Ground())
    scene.add(standing, (0.0, 0.0, 20.0), velocity=(1.0, 0.0, 0.0))
    result = scene.run(0.5)
    trajectories = [result.trajectory(v.name) for v in standing.segments]
    masses = np.array([v.mass for v in standing.segments])
    cg = np.einsum("i,ikj->kj", masses, np.array([t.position for t in trajectories])) / 75.0
    t = trajectories[0].t
    expected_z = cg[0, 2] - 0.5 * G * t**2
    np.testing.assert_allclose(cg[:, 2], expected_z, atol=1e-9)
    np.testing.assert_allclose(cg[:, 0], cg[0, 0] + 1.0 * t, atol=1e-9)
    assert not result.impacts  # nothing moved relative to anything else


def test_momentum_kept_through_an_exchange_with_a_car(standing: cs.Pedestrian) -> None:
    """The struck segment's impulse reaches the whole body through the joints: between the
    samples before and after the first exchange (dt_p 0) the pedestrian's horizontal momentum
    changes by the impulse and the car's by minus it (both in the air: gravity acts vertically,
    nothing else acts horizontally), while the struck segment itself takes
    only part of it."""
    car = cs.Vehicle.box(length=4.0, width=1.7, height=1.0, mass=1200.0, name="car",
                         ground_clearance=0.3, cg_height=0.8)
    scene = cs.Scene(ground=cs.Ground())
    # Both 1 m above the road, falling together: the ground touches neither over the 20 ms
    # (its friction on the feet would act horizontally).
    scene.add(car, (0.0, 0.0, 1.8), velocity=(10.0, 0.0, 0.0))
    scene.add(standing, (2.4, 0.0, 1.0), heading=math.pi / 2)
    for seg in standing.segments:
        scene.contact(car, seg, depth_of_penetration=0.0)
    result = scene.run(0.02)
    first = result.impacts[0]
    struck = next(n for n in first.vehicles if n != "car")
    # the left arm, hanging at the side nearest the car
    assert struck in {f"pedestrian/{s}_left" for s in ("upper_arm", "forearm", "hand")}
    t = result.trajectory("car").t
    k = int(np.flatnonzero(t == first.time)[0])  # the state after the exchange; k - 1 before
    assert first.time - t[k - 1] < 1e-3

    def momentum(names: list[str], sample: int) -> np.ndarray:
        return sum(result.trajectory(n).velocity[sample] * m for n, m in
                   ((n, next(v.mass for v in [car, *standing.segments] if v.name == n))
                    for n in names))

    body = [v.name for v in standing.segments]
    impulse = first.impulse_on(struck)
    assert impulse[0] > 10.0
    np.testing.assert_allclose((momentum(body, k) - momentum(body, k - 1))[:2], impulse[:2],
                               rtol=0, atol=1e-9)
    np.testing.assert_allclose((momentum(["car"], k) - momentum(["car"], k - 1))[:2],
                               -impulse[:2], rtol=0, atol=1e-9)
    hand = momentum([struck], k) - momentum([struck], k - 1)
    assert 0.0 < hand[0] < 0.5 * impulse[0]


def test_bad_input() -> None:
    with pytest.raises(ParameterError, match="pose 'jogging' is not known: give one of "
                       "'standing', 'walking', 'cycling', 'running'"):
        cs.Pedestrian(pose="jogging")
    with pytest.raises(ParameterError, match="height_m"):
        cs.Pedestrian(height=3.0)
    with pytest.raises(ParameterError, match="mass_kg"):
        cs.Pedestrian(mass=5.0)
    with pytest.raises(SceneError, match="needs a ground"):
        cs.Scene().add(cs.Pedestrian(), (0.0, 0.0))
    scene = cs.Scene(ground=cs.Ground())
    p = cs.Pedestrian()
    scene.add(p, (0.0, 0.0))
    with pytest.raises(SceneError, match="already in the scene"):
        scene.add(p, (5.0, 0.0))


def test_where_a_pedestrian_was_added_is_read_back(standing: cs.Pedestrian) -> None:
    scene = cs.Scene(ground=cs.Ground())
    scene.add(standing, (2.4, -1.0), heading=0.5, velocity=(1.0, 0.2, 0.0))
    position, heading, velocity = scene.pedestrian_place("pedestrian")
    assert list(position) == [2.4, -1.0] and heading == 0.5
    assert list(velocity) == [1.0, 0.2, 0.0]
    with pytest.raises(SceneError, match="no pedestrian 'bob' .pedestrians: 'pedestrian'"):
        scene.pedestrian_place("bob")


def test_soft_contacts_are_checked_and_reach_every_segment(standing: cs.Pedestrian) -> None:
    car = cs.Vehicle.box(length=4.0, width=1.7, height=1.0, mass=1200.0, name="car",
                         ground_clearance=0.3, cg_height=0.8)
    scene = cs.Scene(ground=cs.Ground())
    scene.add(car, (0.0, 0.0), velocity=(10.0, 0.0, 0.0))
    scene.add(standing, (2.4, 0.0), heading=math.pi / 2)
    with pytest.raises(ParameterError, match="soft contact stiffness"):
        scene.soft_contact(car, standing, stiffness=-1.0)
    with pytest.raises(ParameterError, match="damping ratio"):
        scene.soft_contact(car, standing, stiffness=1e5, damping_ratio=3.0)
    with pytest.raises(SceneError, match="never collide"):
        scene.soft_contact("pedestrian/hand_left", "pedestrian/thigh_left", stiffness=1e5)
    scene.soft_contact(car, standing, stiffness=1e5, damping_ratio=0.5)
    soft = scene.to_spec(0.1).soft_contacts
    assert len(soft) == 16 and {(a, k, z) for a, _, k, z in soft} == {(0, 1e5, 0.5)}
    # read back per pair, either way round; None for a pair without one
    assert scene.soft_contact_of("pedestrian/head", car) == (1e5, 0.5)
    assert scene.soft_contact_of(car, "pedestrian/foot_left") == (1e5, 0.5)
    assert scene.soft_contact_of("pedestrian/head", "pedestrian/upper_torso") is None
    # 1 ms is too long for 1e5 N/m on a hand (about 0.5 rad a step): the run presses in
    # sub-steps; at 50 ms the segments would need more than 50: refused, with what fits
    scene.run(0.01)
    with pytest.raises(ParameterError, match="too stiff for the step.*more than 50 sub-steps"):
        scene.run(0.01, dt=0.05)


def test_a_softly_struck_pedestrian_keeps_momentum_and_rides_the_car(
    standing: cs.Pedestrian,
) -> None:
    """Soft contacts (no timer, no exchange): every force between the car and the person is
    an equal and opposite pair, so in the air (no ground force) the two's horizontal momentum
    is kept to rounding; the segments press on the car's front without passing into it."""
    car = cs.Vehicle.box(length=4.0, width=1.7, height=1.0, mass=1200.0, name="car",
                         ground_clearance=0.3, cg_height=0.8)
    scene = cs.Scene(ground=cs.Ground(), normal="volume", friction=0.3)
    scene.add(car, (0.0, 0.0, 1.8), velocity=(10.0, 0.0, 0.0))
    scene.add(standing, (2.4, 0.0, 1.0), heading=math.pi / 2)
    scene.soft_contact(car, standing, stiffness=1e5, damping_ratio=0.5)
    result = scene.run(0.08, dt=2e-4)
    assert result.impacts == []
    firsts = [c for c in result.contacts if c.kind == "first_overlap"]
    assert firsts and firsts[0].vehicles[0] == "car"
    bodies = [car, *standing.segments]
    p = sum(result.trajectory(v.name).velocity[:, :2] * v.mass for v in bodies)
    np.testing.assert_allclose(p, np.broadcast_to(p[0], p.shape), rtol=0, atol=1e-6)
    # the person was pushed: its centre of mass moves at about the car's speed (a little more
    # where the contact gave some back: restitution about 0.16 at damping ratio 0.5)
    v_person = sum(result.trajectory(v.name).velocity[-1, 0] * v.mass
                   for v in standing.segments) / 75.0
    assert 2.0 < v_person < 10.0 * 1.2
    # the legs and pelvis, below the car's top, stay ahead of its front face (x = CG + 2 m):
    # pressed, not passed through (the head and arms may go over the roof)
    front = result.trajectory("car").position[:, 0] + 2.0
    for name in ("pelvis", "thigh_left", "thigh_right", "shank_left", "shank_right"):
        x = result.trajectory(f"pedestrian/{name}").position[:, 0]
        assert np.all(x > front - 0.05), name


def test_the_picture_from_above_draws_a_pedestrian_as_one(standing: cs.Pedestrian) -> None:
    from crashsim.plots import plot_trajectories

    car = cs.Vehicle.box(length=4.0, width=1.7, height=1.0, mass=1200.0, name="car",
                         ground_clearance=0.3, cg_height=0.8)
    scene = cs.Scene(ground=cs.Ground())
    scene.add(car, (0.0, 0.0), velocity=(10.0, 0.0, 0.0))
    scene.add(standing, (2.4, 0.0), heading=math.pi / 2)
    assert scene.pedestrians == {"pedestrian": standing}
    result = scene.run(0.05)
    fig = plot_trajectories(result)
    caption = fig._suptitle.get_text()
    assert "pedestrian (its centre of mass) at (" in caption
    # segments are named only in the impacts' lines, no run-out line per segment
    assert caption.count("pedestrian/") == caption.count("car-pedestrian/")
    texts = [t.get_text() for t in fig.axes[0].texts]
    assert "pedestrian (start)" in texts and not any("pedestrian/" in t for t in texts)


def test_a_strike_at_1_ms_presses_in_sub_steps_as_the_run_at_0_2_ms_does() -> None:
    """A sedan at 40 km/h braking into a walking man, soft contacts 1e5 N/m (0.5 rad per
    1 ms step on a hand: 3 sub-steps while a segment presses), the first 0.25 s at 1 ms and at
    0.2 ms (no sub-steps): the head's first contact within 2 ms (measured 0.85 ms) and its
    speed relative to the car within 3 % (1.2 %), the pelvis within 2 cm (9 mm) and 0.15 m/s
    (0.09 m/s) at the end."""
    from crashsim.analysis.pedestrian import segment_contacts

    car = cs.Vehicle.generate("sedan", name="car")
    ahead = float(car.mesh.bounds[1, 0] - car.cg[0])

    def run(dt: float) -> tuple[float, float, np.ndarray, np.ndarray]:
        ped = cs.Pedestrian(height=1.75, mass=75.0, pose="walking")
        scene = cs.Scene(ground=cs.Ground(friction=0.8))
        scene.add(car, (0.0, 0.0), velocity=(cs.kmh(40.0), 0.0, 0.0),
                  inputs=cs.DriverInputs(brake=[(0.0, 1.0), (1.0, 1.0)]))
        scene.add(ped, (ahead + 0.05 + 0.2192, 0.0), heading=math.pi / 2)
        for seg in ped.segments:
            scene.contact(car, seg, depth_of_penetration=0.0, restitution=0.1, friction=0.3,
                          normal="volume")
        scene.soft_contact(car, ped, stiffness=1e5, damping_ratio=0.5)
        result = scene.run(0.25, dt=dt, record_interval=2e-3)
        head = segment_contacts(result, ped, car)["head"]
        pelvis = result.trajectory("pedestrian/pelvis")
        return head.time, head.relative_speed, pelvis.position[-1], pelvis.velocity[-1]

    t1, v1, x1, u1 = run(1e-3)
    t0, v0, x0, u0 = run(2e-4)
    assert abs(t1 - t0) < 2e-3
    assert abs(v1 / v0 - 1.0) < 0.03
    assert np.linalg.norm(x1 - x0) < 0.02
    assert np.linalg.norm(u1 - u0) < 0.15
