"""The multibody cyclist (crashsim.Cyclist, crashsim.Bicycle; docs/human.md "The cyclist"):
the bicycle's mass data against its table, the cycling pose's angles against its targets,
the placement, the joints over a short run, strikes by a sedan from the side and from behind,
momentum through a soft strike in the air, and the refusals."""

from __future__ import annotations

import math
import tomllib
from importlib import resources

import crashsim as cs
import numpy as np
import pytest
from crashsim.analysis.pedestrian import segment_contacts
from crashsim.analysis.throw import throw_distance
from crashsim.errors import InitialOverlapError, ParameterError, SceneError
from crashsim.human.bicycle import CLEARANCE
from crashsim.human.cyclist import GAP
from crashsim.io.scenefile import SceneFileError, loads_scene
from crashsim.result import rotation_matrix

TABLE = tomllib.loads(
    resources.files("crashsim.human").joinpath("data", "bicycle.toml").read_text("utf-8")
)["bicycles"]["city"]


@pytest.fixture(scope="module")
def cyclist() -> cs.Cyclist:
    return cs.Cyclist(height=1.75, mass=75.0)


def joint_gap(scene: cs.Scene, result: cs.Result) -> float:
    """The largest distance (m) between a joint's anchor on its two bodies over the run."""
    worst = 0.0
    for j in scene.joints:
        (pa, _), (pb, _) = j.frames
        ta, tb = result.trajectory(j.vehicles[0]), result.trajectory(j.vehicles[1])
        wa = ta.position + np.einsum("nij,j->ni", rotation_matrix(ta.orientation), pa)
        wb = tb.position + np.einsum("nij,j->ni", rotation_matrix(tb.orientation), pb)
        worst = max(worst, float(np.linalg.norm(wa - wb, axis=1).max()))
    return worst


def test_bicycle_mass_and_cg_against_its_data() -> None:
    """The frame is the measured rear and front frames joined: their masses summed, the CG
    their weighted mean (benchmark frame: origin at the rear contact, z down), the inertia
    about the sagittal axis each one's plus its mass times its squared distance."""
    bike = cs.Bicycle()
    rear, front, w = TABLE["rear_frame"], TABLE["front_frame"], TABLE["wheelbase"]
    m = rear["mass"] + front["mass"]
    x = (rear["mass"] * rear["x"] + front["mass"] * front["x"]) / m
    z = (rear["mass"] * rear["z"] + front["mass"] * front["z"]) / m
    assert bike.frame.mass == pytest.approx(13.75, abs=1e-12)
    np.testing.assert_allclose(bike.frame.cg, [x - w / 2.0, 0.0, -z], atol=1e-12)
    iyy = sum(b["Iyy"] + b["mass"] * ((b["x"] - x) ** 2 + (b["z"] - z) ** 2) for b in (rear, front))
    assert bike.frame.inertia[1, 1] == pytest.approx(iyy, rel=1e-12)
    # the benchmark's y and z reversed: the xz product changes sign
    ixz = sum(b["Ixz"] - b["mass"] * (b["x"] - x) * (b["z"] - z) for b in (rear, front))
    assert bike.frame.inertia[0, 2] == pytest.approx(-ixz, rel=1e-12)
    assert bike.mass == pytest.approx(9.18 + 4.57 + 3.96 + 3.545, abs=1e-12)
    for end in ("rear", "front"):
        wheel, data = getattr(bike, f"{end}_wheel"), TABLE[f"{end}_wheel"]
        assert wheel.mass == data["mass"]
        np.testing.assert_array_equal(np.diag(wheel.inertia), [data["Ixx"], data["Iyy"],
                                                               data["Ixx"]])  # fmt: skip
        # the axle at its radius, the tyre's lowest vertex on the ground
        assert bike.axles[end][2] == data["radius"]
        assert wheel.mesh.vertices[:, 2].min() == pytest.approx(-data["radius"], abs=1e-12)
    assert bike.axles["front"][0] - bike.axles["rear"][0] == pytest.approx(1.101, abs=1e-12)
    # the whole bicycle's CG: frame and wheels (at their axles) weighted
    total = bike.frame.mass * bike.frame.cg + sum(
        TABLE[f"{e}_wheel"]["mass"] * bike.axles[e] for e in ("rear", "front")
    )
    np.testing.assert_allclose(bike.cg(), total / bike.mass, atol=1e-12)
    # the bracket: the chain stay's length from the rear axle, at its measured height
    g = TABLE["geometry"]
    assert np.linalg.norm(bike.bracket - bike.axles["rear"]) == pytest.approx(g["chain_stay"])
    assert bike.bracket[2] == g["bottom_bracket_height"]


def test_cycling_pose_meets_its_targets(cyclist: cs.Cyclist) -> None:
    rider = cyclist.rider
    a = rider.pose_angles
    joints = {j.name: j for j in rider.joints}

    def at(name: str) -> np.ndarray:
        return joints[name].at

    # the trunk: the line from the hips to the shoulders 55 deg above the horizontal
    hips = (at("hip_left") + at("hip_right")) / 2.0
    shoulders = (at("shoulder_left") + at("shoulder_right")) / 2.0
    d = shoulders - hips
    assert math.degrees(math.atan2(d[2], d[0])) == pytest.approx(55.0, abs=1e-9)

    def axis(name: str) -> np.ndarray:
        _, rot = rider.posed(name)
        s = next(s for s in rider.data if s.name == name)
        v = rot @ (np.asarray(s.end) - np.asarray(s.origin))
        return v / np.linalg.norm(v)

    def between(u: np.ndarray, v: np.ndarray) -> float:
        return math.degrees(math.acos(np.clip(u @ v, -1.0, 1.0)))

    # the knee at bottom dead centre 30 deg, the elbows 25 deg, the ankles 13 deg past the
    # standing right angle between shank and foot
    assert between(axis("thigh_left"), axis("shank_left")) == pytest.approx(30.0, abs=1e-9)
    assert between(axis("upper_arm_left"), axis("forearm_left")) == pytest.approx(25.0, abs=1e-9)
    for side in ("left", "right"):
        assert between(axis(f"shank_{side}"), axis(f"foot_{side}")) == pytest.approx(
            90.0 - 13.0, abs=1e-9
        )
    # the upper arm 85 deg from the trunk (the upper torso's axis, pointing down)
    assert between(axis("upper_torso"), axis("upper_arm_left")) == pytest.approx(85.0, abs=1e-9)
    # the hips on the seat tube's line (70.8 deg) through the bracket (the rider sits GAP
    # above the pedals)
    bike = cyclist.bicycle
    to_hip = hips + cyclist.rider_offset - (bike.bracket + [0.0, 0.0, GAP])
    assert math.degrees(math.atan2(to_hip[2], -to_hip[0])) == pytest.approx(
        math.degrees(TABLE["geometry"]["seat_tube_angle"]), abs=1e-9
    )
    # the top knee within its range and the bike-fit's least included angle (70 deg) nearly
    assert 100.0 < a["knee_flexion_right"] < 120.0
    assert a["hip_flexion_right"] < 125.0  # the hip's published flexion
    with pytest.raises(ParameterError, match="pose 'riding'"):
        cs.Pedestrian(pose="riding")


def test_placement_on_the_saddle_wheels_on_the_ground(cyclist: cs.Cyclist) -> None:
    heading, v = 0.3, cs.kmh(15.0)
    velocity = (v * math.cos(heading), v * math.sin(heading), 0.0)
    scene = cs.Scene(ground=cs.Ground(friction=0.8))
    scene.add(cyclist, (2.0, -1.0), heading=heading, velocity=velocity)
    assert scene.cyclists == {"cyclist": cyclist}
    spec = scene.to_spec(0.1)
    assert len(spec.soft_contacts) == 5  # pelvis, hands, feet on the frame
    result = scene.run(0.1)
    first = {b.name: (result.trajectory(b.name), b) for b in cyclist.bodies}
    for name, (tr, body) in first.items():
        np.testing.assert_allclose(tr.velocity[0], velocity, atol=1e-12, err_msg=name)
        lowest = (tr.position[0] + np.asarray(body.mesh.vertices - body.cg)
                  @ rotation_matrix(tr.orientation[0]).T)[:, 2].min()  # fmt: skip
        if name.endswith("wheel"):
            assert lowest == pytest.approx(CLEARANCE, abs=1e-9)
            radius = TABLE[name.split("/")[1]]["radius"]
            spin = rotation_matrix(tr.orientation[0]).T @ tr.angular_velocity[0]
            np.testing.assert_allclose(spin, [0.0, v / radius, 0.0], atol=1e-12)
        else:
            assert lowest > 0.05, name
    # the pelvis's sphere 1 mm over the saddle's top (bicycle frame)
    pelvis = next(s for s in cyclist.rider.data if s.name == "pelvis")
    centre = cyclist.rider.posed("pelvis")[0] - pelvis.cg_body + np.add(pelvis.origin,
                                                                      pelvis.end) / 2.0
    bottom = centre[2] + cyclist.rider_offset[2] - pelvis.contact.radius
    assert bottom - cyclist.bicycle.fit.saddle[1] == pytest.approx(GAP, abs=1e-12)
    # no exchange, the rider still seated after 0.1 s (the pelvis sunk into the saddle by
    # under 1 cm: 1e5 N/m under about 45 kg sinks 4.4 mm; within 1.5 cm of where it sat on
    # the frame), the joints held
    assert result.impacts == []
    frame, pel = result.trajectory("cyclist/frame"), result.trajectory("cyclist/pelvis")
    rel = [rotation_matrix(frame.orientation[k]).T @ (pel.position[k] - frame.position[k])
           for k in (0, -1)]  # fmt: skip
    assert -0.01 < rel[1][2] - rel[0][2] < 0.0
    assert np.linalg.norm(rel[1] - rel[0]) < 0.015
    assert joint_gap(scene, result) < 1e-6


def test_bicycle_alone_rolls(tmp_path) -> None:
    """At 5 m/s the wheels roll (their spin stays the speed over the radius within 1 %); the
    body-ground contact's losses slow it (docs/human.md gives 0.50 m/s in 1 s)."""
    scene = cs.Scene(ground=cs.Ground(friction=0.8))
    bike = cs.Bicycle()
    scene.add(bike, (0.0, 0.0), heading=0.0, velocity=(5.0, 0.0, 0.0))
    assert scene.bicycles == {"bicycle": bike} and scene.cyclists == {}
    result = scene.run(0.5)
    frame, wheel = result.trajectory("bicycle/frame"), result.trajectory("bicycle/rear_wheel")
    speed = frame.velocity[-1, 0]
    assert 4.5 < speed < 5.0
    spin = (rotation_matrix(wheel.orientation[-1]).T @ wheel.angular_velocity[-1])[1]
    assert spin * TABLE["rear_wheel"]["radius"] == pytest.approx(speed, rel=0.01)
    assert joint_gap(scene, result) < 1e-6


def strike(kind: str, duration: float) -> tuple[cs.Scene, cs.Result, cs.Cyclist, cs.Vehicle]:
    car = cs.Vehicle.generate("sedan", name="car")
    cyclist = cs.Cyclist()
    scene = cs.Scene(ground=cs.Ground(friction=0.8), normal="volume", friction=0.3)
    front = float(car.mesh.bounds[1, 0] - car.cg[0])
    scene.add(car, (0.0, 0.0), heading=0.0, velocity=(cs.kmh(40.0), 0.0, 0.0))
    v = cs.kmh(15.0)
    if kind == "side":
        scene.add(cyclist, (front + 0.33, 0.0), heading=math.pi / 2, velocity=(0.0, v, 0.0))
    else:
        back = cyclist.bicycle.wheelbase / 2.0 + TABLE["rear_wheel"]["radius"]
        scene.add(cyclist, (front + 0.05 + back, 0.0), heading=0.0, velocity=(v, 0.0, 0.0))
    scene.soft_contact(car, cyclist, stiffness=1e5, damping_ratio=0.5)
    return scene, scene.run(duration, dt=2e-4), cyclist, car


def test_side_strike_at_40_kmh() -> None:
    scene, result, cyclist, car = strike("side", 0.22)
    assert result.impacts == []  # soft contacts only
    contacts = segment_contacts(result, cyclist.rider, car)
    assert next(iter(contacts)) in ("shank_left", "thigh_left", "foot_left")
    head = contacts["head"]
    assert 0.1 < head.time < 0.22 and head.wrap_around is not None
    assert head.relative_speed > 3.0
    bike = segment_contacts(result, cyclist.bicycle, car)
    assert {"frame", "front_wheel"} <= set(bike)
    assert throw_distance(result, "car", cyclist.rider) > 0.5
    assert joint_gap(scene, result) < 1e-6


def test_rear_strike_at_40_kmh() -> None:
    scene, result, cyclist, car = strike("rear", 0.12)
    assert result.impacts == []
    bike = segment_contacts(result, cyclist.bicycle, car)
    assert next(iter(bike)) == "rear_wheel"
    first = bike["rear_wheel"]
    # closing at 40 - 15 km/h; the wheel's back turns upwards at up to its forward speed
    assert cs.kmh(25.0) < first.relative_speed < math.hypot(cs.kmh(25.0), cs.kmh(15.0))
    contacts = segment_contacts(result, cyclist.rider, car)
    assert "thigh_left" in contacts or "shank_left" in contacts
    assert throw_distance(result, "car", cyclist.rider) > 0.1
    assert joint_gap(scene, result) < 1e-6


def test_momentum_kept_through_a_soft_strike_in_the_air() -> None:
    """In the air (no ground force) every force between the car, the bicycle and the rider
    is an equal and opposite pair (soft contacts, joints), so their horizontal momentum is
    kept to rounding through the strike."""
    car = cs.Vehicle.box(length=4.0, width=1.7, height=1.0, mass=1200.0, name="car",
                         ground_clearance=0.3, cg_height=0.8)  # fmt: skip
    cyclist = cs.Cyclist()
    scene = cs.Scene(ground=cs.Ground(), normal="volume", friction=0.3)
    scene.add(car, (0.0, 0.0, 2.3), velocity=(10.0, 0.0, 0.0))
    scene.add(cyclist, (2.35, 0.0, 1.5), heading=math.pi / 2)
    scene.soft_contact(car, cyclist, stiffness=1e5, damping_ratio=0.5)
    result = scene.run(0.06, dt=2e-4)
    touched = {c.vehicles for c in result.contacts if c.kind == "first_overlap"}
    assert any("car" in pair for pair in touched)
    bodies = [car, *cyclist.bodies]
    p = sum(result.trajectory(b.name).velocity[:, :2] * b.mass for b in bodies)
    np.testing.assert_allclose(p, np.broadcast_to(p[0], p.shape), rtol=0, atol=1e-6)
    v = sum(result.trajectory(b.name).velocity[-1, 0] * b.mass for b in cyclist.bodies)
    assert v / cyclist.mass > 1.0  # the cyclist was pushed


def test_bad_input(cyclist: cs.Cyclist) -> None:
    with pytest.raises(ParameterError, match="bicycle kind 'racing'"):
        cs.Bicycle("racing")
    with pytest.raises(ParameterError, match="pose is 'walking'"):
        cs.Cyclist(rider=cs.Pedestrian(pose="walking"))
    with pytest.raises(ParameterError, match="same name"):
        cs.Cyclist(rider=cs.Pedestrian(pose="cycling", name="rider"), name="cyclist")
    assert cs.Cyclist(rider=cs.Pedestrian(pose="cycling", name="rider")).name == "rider"
    with pytest.raises(ParameterError, match="height_m"):
        cs.Cyclist(height=3.0)
    with pytest.raises(ParameterError, match="too short"):
        cs.Cyclist(height=1.3, mass=40.0)
    with pytest.raises(ParameterError, match="too tall"):
        cs.Cyclist(height=2.15, mass=100.0)
    with pytest.raises(ParameterError, match="must be a crashsim.Bicycle"):
        cs.Cyclist(bicycle="city")  # type: ignore[arg-type]
    with pytest.raises(SceneError, match="needs a ground"):
        cs.Scene().add(cyclist, (0.0, 0.0))
    scene = cs.Scene(ground=cs.Ground())
    scene.add(cyclist, (0.0, 0.0))
    with pytest.raises(SceneError, match="already in the scene"):
        scene.add(cyclist, (5.0, 0.0))
    # placed inside a car: refused when the run starts, naming the pairs (as a pedestrian)
    car = cs.Vehicle.box(length=4.0, width=1.7, height=1.0, mass=1200.0, name="car",
                         ground_clearance=0.3, cg_height=0.8)  # fmt: skip
    scene.add(car, (0.5, 0.0))
    with pytest.raises(InitialOverlapError, match="'cyclist/frame' and 'car'"):
        scene.run(0.01)


SCENE = """
format_version = 1
[run]
duration = "0.02 s"
dt = "0.2 ms"
[ground]
friction = 0.8
[contact]
normal = "volume"
[[vehicles]]
name = "car"
generate = "sedan"
mass = "1450 kg"
position = [0, 0]
speed = "40 km/h"
[[cyclists]]
name = "rider"
height = "1.8 m"
mass = "80 kg"
bicycle = "{bicycle}"
position = ["2.44 m", 0]
heading = "90 deg"
speed = "15 km/h"
[[cyclists.soft_contact]]
with = "car"
stiffness = "100 kN/m"
"""


def test_scene_file_cyclists() -> None:
    file = loads_scene(SCENE.format(bicycle="city"))
    cyclist = file.scene.cyclists["rider"]
    assert cyclist.rider.height == pytest.approx(1.8) and cyclist.rider.mass == pytest.approx(80)
    soft = file.scene.to_spec(0.02).soft_contacts
    assert len(soft) == 5 + len(cyclist.bodies)  # its own five and every body with the car
    with pytest.raises(SceneFileError, match="bicycle"):
        loads_scene(SCENE.format(bicycle="racing"))
    # the rider's passive joint moments: a factor, as Pedestrian(passive_moments=) takes it
    assert cyclist.rider.passive_moments == 1.0
    assert sum(1 for j in cyclist.rider.joints if j.passive) == 6
    relaxed = loads_scene(SCENE.format(bicycle="city").replace(
        'bicycle = "city"', 'bicycle = "city"\npassive_moments = 0.0')).scene.cyclists["rider"]
    assert relaxed.rider.passive_moments == 0.0
    assert not any(j.passive for j in relaxed.rider.joints)
    api = cs.Cyclist(height=1.8, mass=80.0, name="rider", passive_moments=0.0)
    assert [j.passive for j in api.rider.joints] == [j.passive for j in relaxed.rider.joints]
    with pytest.raises(SceneFileError, match="cyclists\\[0\\].*passive_moments = -1.0"):
        loads_scene(SCENE.format(bicycle="city").replace(
            'bicycle = "city"', 'bicycle = "city"\npassive_moments = -1'))
