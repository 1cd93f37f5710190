"""Joints through the Python API (issue 21, docs/joints.md): Scene.join, the joints' records
and limit events, closed forms (a pendulum's period, a towed car's coupling force), pairs of
joined vehicles, refusals by name, the spec's JSON and pickle round trips."""

from __future__ import annotations

import dataclasses
import math
import pickle

import crashsim as cs
import numpy as np
import pytest
from crashsim import _core
from crashsim.errors import ParameterError, SceneError

G = 9.80665
HIGH = 30.0  # a pendulum's pivot height (m): the ground is far below


def _rod(name: str = "rod") -> cs.Vehicle:
    return cs.Vehicle.box(1.0, 0.05, 0.05, mass=5.0, name=name)


def _pendulum(angle: float, **join: object) -> cs.Scene:
    """A 1 m rod hanging from a hinge about world y at its top end, tilted ``angle`` rad."""
    scene = cs.Scene(ground=cs.Ground())
    c = (0.5 * math.sin(angle), 0.0, HIGH - 0.5 * math.cos(angle))
    # body x along the rod, pointing down the rod from the pivot
    pitch = math.pi / 2 - angle
    q = (math.cos(pitch / 2), 0.0, math.sin(pitch / 2), 0.0)
    scene.add(_rod(), c, orientation=q)
    # the hinge turns about its z axis: world y
    axes = (math.cos(-math.pi / 4), math.sin(-math.pi / 4), 0.0, 0.0)
    scene.join("rod", at=(0.0, 0.0, HIGH), kind="revolute", axes=axes, **join)
    return scene


def test_a_pendulum_swings_with_its_closed_form_period() -> None:
    theta0 = math.radians(5.0)
    result = _pendulum(theta0).run(4.0)
    i_o = 5.0 / 12.0 * (1.0 + 0.05**2) + 5.0 * 0.25
    expected = 2 * math.pi * math.sqrt(i_o / (5.0 * G * 0.5)) * (1 + theta0**2 / 16)
    record = result.joints["rod-world"]
    assert record.kind == "revolute" and record.angle_names == ("angle",)
    c = result.trajectory("rod").position
    angle = np.arctan2(c[:, 0], HIGH - c[:, 2])  # from the vertical
    # The hinge's own angle is the swing from where it was made.
    assert np.allclose(record.angle("angle"), angle - theta0, atol=1e-6)
    up = np.flatnonzero((angle[:-1] < 0) & (angle[1:] >= 0))
    t = result.t
    crossings = t[up] - angle[up] * (t[up + 1] - t[up]) / (angle[up + 1] - angle[up])
    period = np.diff(crossings).mean()
    assert period == pytest.approx(expected, rel=1e-3)
    # The rod hangs on the hinge: its force on the world (body 2) is its weight, down, plus
    # its swing's small centripetal pull (within 1 %).
    assert record.force[:, 2].mean() == pytest.approx(-5.0 * G, rel=1e-2)


def test_a_limit_stops_the_swing_and_is_an_event() -> None:
    limit = math.radians(10.0)
    result = _pendulum(math.radians(30.0), limits={"angle": (-limit, limit)}).run(1.0)
    assert result.joint_events, "no limit hit"
    first = result.joint_events[0]
    assert first.joint == "rod-world" and first.angle == "angle"
    angle = result.joints["rod-world"].angle("angle")
    # Released at 30 deg: stopped at 10 deg, where it stays (an inelastic stop under gravity).
    assert np.abs(angle).max() <= math.radians(30.0) + 1e-9
    assert np.abs(angle[result.t > first.time]).max() < limit + 1e-3


def test_a_joint_resting_on_its_limit_is_held_by_the_limits_reaction() -> None:
    # Released at 30 deg from the vertical, stopped 10 deg from where it was made: it rests
    # at 20 deg, where the limit carries the rod's moment about the hinge, m g (L / 2) sin 20
    # (5 kg, 1 m), and holds it still (the limit is a reaction while the joint rests on it,
    # not a stop after each sub-step: a lying pedestrian's joints jittered at 15 deg/s).
    limit = math.radians(10.0)
    result = _pendulum(math.radians(30.0), limits={"angle": (-limit, limit)}).run(1.5)
    record = result.joints["rod-world"]
    resting = result.t > 1.0
    assert np.allclose(record.angle("angle")[resting], -limit, atol=1e-9)
    moment = 5.0 * G * 0.5 * math.sin(math.radians(20.0))
    assert np.abs(record.torque[resting, 1]) == pytest.approx(moment, rel=1e-6)
    spin = result.trajectory("rod").angular_velocity[resting]
    assert np.abs(spin).max() < 1e-9


def test_a_ball_joints_cone_stops_the_swing_and_records_swing_and_twist() -> None:
    # Released at 40 deg from the vertical on a ball joint whose cone (20 deg) is centred on
    # where it was made: gravity swings it 20 deg towards the vertical, where the cone stops it.
    cone = math.radians(20.0)
    scene = _pendulum(math.radians(40.0))
    scene._joints = []
    scene.join("rod", at=(0.0, 0.0, HIGH), kind="spherical", limits={"swing": (0.0, cone)})
    result = scene.run(1.0)
    record = result.joints["rod-world"]
    assert record.kind == "spherical" and record.angle_names == ("swing", "twist")
    first = result.joint_events[0]
    assert (first.joint, first.angle) == ("rod-world", "swing") and first.rate > 0.0
    swing = record.angle("swing")
    # The swing is the rod's turn from where it was made (a planar swing: no twist).
    c = result.trajectory("rod").position
    turned = math.radians(40.0) - np.arctan2(c[:, 0], HIGH - c[:, 2])
    assert np.allclose(swing, np.abs(turned), atol=1e-6)
    assert swing.max() < cone + 1e-3 and swing.max() > cone - 1e-3
    assert np.abs(record.angle("twist")).max() < 1e-9


def test_a_ball_joints_cone_may_lie_off_the_start_with_axes2() -> None:
    # A rod hanging on a ball whose cone (half-angle 50 deg) is turned 40 deg towards +x from
    # the rod: the rod's frame (axes) straight down, the world's (axes2, the second side)
    # the cone's. It may swing 90 deg towards +x but only 10 deg towards -x, where a kick
    # that way stops it.
    scene = cs.Scene(ground=cs.Ground())
    q = (math.cos(math.pi / 4), 0.0, math.sin(math.pi / 4), 0.0)  # body x down
    scene.add(_rod(), (0.0, 0.0, HIGH - 0.5), orientation=q,
              velocity=(-1.5, 0.0, 0.0), angular_velocity=(0.0, 3.0, 0.0))
    down = np.array([[1.0, 0, 0], [0, -1.0, 0], [0, 0, -1.0]])  # z straight down
    tilt = math.radians(40.0)  # the cone's axis: down, turned towards +x
    c, s = math.cos(tilt), math.sin(tilt)
    cone = np.array([[c, 0.0, s], [0.0, -1.0, 0.0], [s, 0.0, -c]])
    scene.join("rod", at=(0.0, 0.0, HIGH), kind="spherical", axes=down, axes2=cone,
               limits={"swing": (0.0, math.radians(50.0))})
    result = scene.run(0.6)
    record = result.joints["rod-world"]
    assert record.angle("swing")[0] == pytest.approx(tilt, abs=1e-9)
    first = result.joint_events[0]
    assert first.angle == "swing"
    x = result.trajectory("rod").position[:, 0]
    back = np.degrees(np.arcsin(np.clip(-x.min() / 0.5, -1.0, 1.0)))
    assert back == pytest.approx(10.0, abs=0.1)
    with pytest.raises(ParameterError, match="axes2 is for a spherical joint"):
        scene.join("rod", at=(0.0, 0.0, HIGH), kind="revolute", axes2=down, name="other")


def test_a_no_contact_pair_passes_through_and_takes_no_parameters() -> None:
    # Two boxes overlapping at the start: refused, unless they never collide; a third still
    # strikes one of them; the engine's document keeps the pair.
    scene = cs.Scene(ground=cs.Ground())
    for name, x, vx in (("a", 0.0, 0.0), ("b", 0.9, 0.0), ("c", 4.0, -8.0)):
        box = cs.Vehicle.box(1.0, 0.5, 0.5, mass=5.0, name=name)
        scene.add(box, (x, 0, HIGH), velocity=(vx, 0, 0))
    with pytest.raises(cs.errors.InitialOverlapError):
        scene.run(0.1)
    scene.no_contact("b", "a")
    assert {frozenset(p[:2]) for p in scene.pairs()} == {frozenset("ac"), frozenset("bc")}
    result = scene.run(0.5)
    assert [set(i.vehicles) for i in result.impacts] == [{"b", "c"}]
    spec = scene.to_spec(0.5)
    assert spec.no_contact == [(0, 1)]
    assert _core.SceneSpec.from_json(spec.to_json()).no_contact == [(0, 1)]
    with pytest.raises(SceneError, match="never collide"):
        scene.contact("a", "b", restitution=0.2)
    scene.contact("a", "c", restitution=0.2)
    with pytest.raises(SceneError, match="takes none"):
        scene.no_contact("c", "a")


def test_an_overlap_at_the_start_names_only_pairs_that_collide() -> None:
    scene = cs.Scene(ground=cs.Ground())
    for name, x in (("a", 0.0), ("b", 0.9), ("c", 1.7)):
        scene.add(cs.Vehicle.box(1.0, 0.5, 0.5, mass=5.0, name=name), (x, 0, HIGH))
    scene.no_contact("a", "b")
    with pytest.raises(cs.errors.InitialOverlapError) as info:
        scene.run(0.1)
    assert str(info.value).startswith("vehicles 'b' and 'c' already overlap at t = 0")


def _towed(brake: float = 0.3) -> tuple[cs.Scene, float]:
    car = cs.Vehicle.generate("sedan", name="car")
    towed = cs.Vehicle.generate("sedan", name="towed")
    lo, hi = car.mesh.bounds - car.cg
    scene = cs.Scene(ground=cs.Ground(friction=0.8))
    scene.add(car, (0, 0), heading=0.0, velocity=(15, 0, 0), inputs=cs.DriverInputs(brake=brake))
    gap = 0.6
    scene.add(towed, (lo[0] - gap - hi[0], 0), heading=0.0, velocity=(15, 0, 0))
    scene.join("car", "towed", at=(lo[0] - gap / 2, 0.0, 0.5), name="bar")
    return scene, towed.mass


def test_a_towed_car_is_braked_through_the_bar_as_newton_says() -> None:
    # The car brakes, the towed car does not: the bar decelerates it with the pair, F = m a.
    scene, m_towed = _towed()
    result = scene.run(2.0)
    bar = result.joints["bar"]
    v = result.trajectory("car").velocity[:, 0]
    t = result.t
    steady = (t > 0.8) & (t < 1.8)
    a = np.gradient(v, t)[steady].mean()
    assert a < -1.0
    assert bar.force[steady, 0].mean() == pytest.approx(m_towed * a, rel=1e-2)
    # Both keep together: the anchors meet (the drift stays below 1 mm).
    assert result.contacts == [] and result.impacts == []


def test_joined_vehicles_form_no_pair_unless_they_collide() -> None:
    scene, _ = _towed()
    assert all({"car", "towed"} != {a, b} for a, b, _ in scene.pairs())
    with pytest.raises(SceneError, match="already joined"):
        scene.join("towed", "car", at=(0, 0, 0.5))
    other, _ = _towed()
    other._joints = []
    other.join("car", "towed", at=(-3.1, 0.0, 0.5), collide=True)
    assert any({"car", "towed"} == {a, b} for a, b, _ in other.pairs())


@pytest.mark.parametrize(
    ("join", "error", "match"),
    [
        ({"kind": "weld"}, ParameterError, "kind 'weld' is unknown"),
        ({"kind": "revolute", "limits": {"pitch": (-1, 1)}}, ParameterError, 'no angle "pitch"'),
        ({"kind": "spherical", "limits": {"angle": (-1, 1)}}, ParameterError, "no angle"),
        ({"kind": "spherical", "limits": {"swing": (-0.1, 1)}}, ParameterError, "never negative"),
        ({"stiffness": -5.0}, ParameterError, "stiffness"),
        ({"kind": "revolute", "limits": {"angle": (0.5, 1)}}, ParameterError, "lower limit"),
        ({"at": (0, 0)}, ParameterError, "3 finite numbers"),
    ],
)
def test_bad_joints_are_refused_at_the_call_by_name(
    join: dict[str, object], error: type[Exception], match: str
) -> None:
    scene = cs.Scene(ground=cs.Ground())
    scene.add(_rod(), (0, 0, HIGH - 0.5))
    args = {"at": (0.0, 0.0, HIGH), **join}
    with pytest.raises(error, match=match) as raised:
        scene.join("rod", **args)  # type: ignore[arg-type]
    if join.get("stiffness") is not None:  # the engine's rule: the joint and the parameter
        assert raised.value.loc == (("part", None, "joint 'rod-world'"),
                                    ("parameter", None, "the joint's stiffness"))  # fmt: skip


def test_join_checks_its_axes_at_the_call() -> None:
    # a zero quaternion was taken by Scene.join and refused only when the scene was built, as
    # a vehicle's "orientation", without the joint's name (a scene file could not name it)
    scene, _ = _towed()
    scene._joints = []
    with pytest.raises(ParameterError, match="joint 'bar': axes: orientation must be a "
                       "finite, non-zero quaternion"):  # fmt: skip
        scene.join("car", "towed", at=(-3.1, 0.0, 0.5), axes=(0, 0, 0, 0), name="bar")
    places = [("part", None, "joint 'bar'"), ("part", None, "axes")]
    with pytest.raises(ParameterError) as raised:
        scene.join("car", "towed", at=(-3.1, 0.0, 0.5), axes=(0, 0, 0, 0), name="bar")
    assert list(raised.value.loc[:2]) == places
    with pytest.raises(ParameterError, match="joint 'car-towed': axes: the orientation matrix "
                       "is a reflection"):  # fmt: skip
        scene.join("car", "towed", at=(-3.1, 0.0, 0.5), axes=np.diag([1.0, 1.0, -1.0]))
    assert scene.joints == []


def test_joints_need_a_ground_agreeing_velocities_and_no_obstacle() -> None:
    scene = cs.Scene()
    scene.add(_rod(), (0, 0, HIGH - 0.5))
    scene.join("rod", at=(-0.5, 0.0, HIGH - 0.5))
    with pytest.raises(ParameterError, match="ground"):
        scene.run(0.1)
    moving, _ = _towed()
    moving._placements[1] = dataclasses.replace(
        moving._placements[1], velocity=np.array([14.0, 0.0, 0.0])
    )
    with pytest.raises(ParameterError, match="joint \"bar\".s bodies move apart at the start"):
        moving.run(0.1)
    walled = cs.Scene(ground=cs.Ground())
    walled.add(_rod(), (0, 0, HIGH - 0.5))
    walled.add_obstacle(cs.Obstacle.wall(length=2.0, height=1.0, name="wall"), (5.0, 0.0))
    with pytest.raises(SceneError, match="fixed obstacle"):
        walled.join("wall", at=(5.0, 0.0, 0.5))


def test_a_jointed_spec_round_trips_through_json_and_pickle() -> None:
    scene, _ = _towed()
    spec = scene.to_spec(0.3)
    assert spec.n_joints == 1
    runs = [
        spec.run(),
        _core.SceneSpec.from_json(spec.to_json()).run(),
        pickle.loads(pickle.dumps(spec)).run(),
    ]
    for other in runs[1:]:
        for key in ("position", "joint_force", "joint_angles"):
            assert np.array_equal(other[key], runs[0][key])


# -- passive moments (docs/joints.md, "Passive moments") -----------------------------------


def _held(law: cs.PassiveMoment, damping: float = 5.0) -> cs.Scene:
    """The 1 m rod hanging straight down from its hinge, a passive moment about the hinge's
    angle (positive: the rod swings towards +x) and ``damping`` N m s/rad."""
    return _pendulum(0.0, passive={"angle": law}, damping=damping)


def _balance(law: cs.PassiveMoment) -> float:
    """The angle (rad) where the law carries the rod's weight: M(offset + a) = m g (l/2) sin a,
    by bisection over (0, pi/2)."""
    lo, hi = 0.0, math.pi / 2
    for _ in range(100):
        mid = 0.5 * (lo + hi)
        if float(law.moment(law.offset + mid)) > 5.0 * G * 0.5 * math.sin(mid):
            lo = mid
        else:
            hi = mid
    return 0.5 * (lo + hi)


def test_a_passive_moment_holds_the_rod_where_statics_says() -> None:
    # An exponential law written in its own angle (offset 0.2 where the joint is made) and a
    # constant one: the rod swings out and rests where the moment carries its weight.
    for law in (
        cs.PassiveMoment(terms=((5.0, -3.0, 0.2),), offset=0.2),
        cs.PassiveMoment(constant=10.0),
    ):
        expected = _balance(law)
        assert 0.1 < expected < 0.5  # rad: 0.136 and 0.420
        result = _held(law).run(8.0)
        record = result.joints["rod-world"]
        assert record.angle("angle")[-1] == pytest.approx(expected, abs=1e-6)
    # as made, and in the joint's own description
    scene = _held(cs.PassiveMoment(terms=((5.0, -3.0, 0.2),), constant=-1.0, offset=0.2))
    (joint,) = scene.joints
    assert joint.passive == {
        "angle": cs.PassiveMoment(terms=((5.0, -3.0, 0.2),), constant=-1.0, offset=0.2)
    }
    assert joint.to_dict()["passive"] == {
        "angle": {"terms": [[5.0, -3.0, 0.2]], "constant": -1.0, "offset": 0.2}
    }
    assert "passive" not in _pendulum(0.0).joints[0].to_dict()


def test_passive_moments_round_trip_and_are_reported() -> None:
    import jsonschema
    from crashsim.analysis.report import report_schema

    scene = _held(cs.PassiveMoment(terms=((5.0, -3.0, 0.2), (-0.5, 2.0, 0.1)), offset=0.2))
    spec = scene.to_spec(0.5)
    runs = [
        spec.run(),
        _core.SceneSpec.from_json(spec.to_json()).run(),
        pickle.loads(pickle.dumps(spec)).run(),
        pickle.loads(pickle.dumps(scene)).to_spec(0.5).run(),
    ]
    for other in runs[1:]:
        for key in ("position", "joint_force", "joint_angles"):
            assert np.array_equal(other[key], runs[0][key])
    core = scene.joints[0].core
    assert pickle.loads(pickle.dumps(core)) == core
    assert "passive=[(\"angle\", 0.2, [(5.0, -3.0, 0.2), (-0.5, 2.0, 0.1)], 0.0)]" in repr(core)
    report = cs.report(scene.run(0.2))
    (made,) = report.to_dict()["scene"]["joints"]
    assert made["passive"]["angle"]["terms"] == [[5.0, -3.0, 0.2], [-0.5, 2.0, 0.1]]
    assert ("    passive moment about angle: M = 5 exp(-3 (phi - 0.2)) - 0.5 exp(2 (phi - 0.1)) "
            "N m, phi = 0.2 rad + the angle") in report.summary_table().splitlines()  # fmt: skip
    jsonschema.validate(report.to_dict(), report_schema(), cls=jsonschema.Draft202012Validator)


@pytest.mark.parametrize(
    ("passive", "match"),
    [
        ({"pitch": cs.PassiveMoment(constant=1.0)}, 'no angle "pitch" for a passive moment'),
        ({"angle": "stiff"}, "must be a crashsim.PassiveMoment"),
        ({"angle": cs.PassiveMoment(terms=((1.0, 2.0),))}, "terms of \\(scale N m, rate"),
        ({"angle": cs.PassiveMoment(terms=((1.0, 500.0, 0.0),))}, "rate = 500 1/rad"),
        ({"angle": cs.PassiveMoment(constant=math.nan)}, "constant"),
    ],
)
def test_bad_passive_moments_are_refused_at_the_call(passive: dict, match: str) -> None:
    with pytest.raises(ParameterError, match=match) as raised:
        _pendulum(0.0, passive=passive)
    assert raised.value.loc[0] == ("part", None, "joint 'rod-world'")


def test_a_coupled_term_reads_the_other_joints_angle() -> None:
    # Two rods hanging in a chain; the top hinge's law reads the bottom hinge's angle (a
    # two-joint muscle's form). Along the hinge's axis the top joint's recorded torque is the
    # law alone (the hinge's reactions are across it): at every sample it is the law at the
    # two recorded angles.
    couple = cs.CoupledAngle("bottom", "angle", rate=-2.0, offset=0.3)
    law = cs.PassiveMoment(terms=((1.0, 0.5, 0.0, (couple,)),), constant=3.0)
    scene = _pendulum(0.0, passive={"angle": law})
    q = (math.cos(math.pi / 4), 0.0, math.sin(math.pi / 4), 0.0)  # body x down, as the first
    scene.add(_rod("rod2"), (0.0, 0.0, HIGH - 1.5), orientation=q)
    axes = (math.cos(-math.pi / 4), math.sin(-math.pi / 4), 0.0, 0.0)
    scene.join("rod", "rod2", at=(0.0, 0.0, HIGH - 1.0), kind="revolute", axes=axes,
               name="bottom")  # fmt: skip
    result = scene.run(1.0)
    top, bottom = result.joints["rod-world"], result.joints["bottom"]
    assert np.ptp(bottom.angle("angle")) > 0.05  # the bottom hinge did turn
    expected = law.moment(top.angle("angle"), {("bottom", "angle"): bottom.angle("angle")})
    along = top.torque @ np.array([0.0, 1.0, 0.0])  # the hinge's axis: world y
    assert np.allclose(along, expected, rtol=1e-9, atol=1e-9)  # the sign too: M on the world
    assert not np.allclose(along, law.moment(top.angle("angle")), rtol=1e-3)
    # as made, through pickle and the report, and in the text
    (made,) = [j for j in scene.joints if j.name == "rod-world"]
    assert made.passive == {"angle": law}
    assert pickle.loads(pickle.dumps(made.core)) == made.core
    report = cs.report(result)
    joint = next(j for j in report.to_dict()["scene"]["joints"] if j["name"] == "rod-world")
    assert joint["passive"]["angle"]["coupled"] == [
        {"term": 0, "joint": "bottom", "angle": "angle", "rate": -2.0, "offset": 0.3}
    ]
    import jsonschema
    from crashsim.analysis.report import report_schema

    jsonschema.validate(report.to_dict(), report_schema(), cls=jsonschema.Draft202012Validator)
    assert ("    passive moment about angle: M = 1 exp(0.5 (phi - 0) - 2 (bottom angle + 0.3)) "
            "+ 3 N m, phi = 0 rad + the angle") in report.summary_table().splitlines()  # fmt: skip


def test_a_coupled_angle_must_be_a_joint_of_the_same_set() -> None:
    couple = cs.CoupledAngle("knee", "angle", rate=1.0)
    scene = _pendulum(0.0, passive={"angle": cs.PassiveMoment(terms=((1.0, 0.0, 0.0, (couple,)),))})
    with pytest.raises(ParameterError, match="reads joint \"knee\": no joint of that name"):
        scene.run(0.01)
    bad = cs.PassiveMoment(terms=((1.0, 0.0, 0.0, ("knee", "angle", 1.0)),))
    with pytest.raises(ParameterError, match="CoupledAngle"):
        _pendulum(0.0, passive={"angle": bad})
