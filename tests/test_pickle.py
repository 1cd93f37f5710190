"""Scenes and results pickle (studies send them between processes), and a scene run after a
round trip gives the same result bit for bit."""

from __future__ import annotations

import pickle

import crashsim as cs
import numpy as np


def _scene() -> cs.Scene:
    scene = cs.Scene()
    red = cs.Vehicle.box(4.5, 1.8, 1.4, mass=1500, name="red")
    blue = cs.Vehicle.box(4.5, 1.8, 1.4, mass=1200, name="blue")
    scene.add(red, position=(-5.0, 0.0, 0.7), velocity=(20.0, 0.0, 0.0))
    scene.add(blue, position=(0.0, -5.0, 0.7), heading=np.pi / 2, velocity=(0.0, 10.0, 0.0))
    return scene


def test_shape_round_trip_is_exact() -> None:
    shape = cs.Vehicle.box(4.5, 1.8, 1.4, mass=1500).shape
    back = pickle.loads(pickle.dumps(shape))
    assert np.array_equal(back.vertices, shape.vertices)
    assert np.array_equal(back.triangles, shape.triangles)


def test_scene_after_a_round_trip_runs_bit_identical() -> None:
    scene = _scene()
    before = scene.run(duration=0.4, dt=1e-3)
    after = pickle.loads(pickle.dumps(scene)).run(duration=0.4, dt=1e-3)
    assert len(before.impacts) == len(after.impacts) == 1
    for name in ("red", "blue"):
        a, b = before.trajectory(name), after.trajectory(name)
        assert np.array_equal(a.position, b.position)
        assert np.array_equal(a.orientation, b.orientation)
    assert np.array_equal(before.impacts[0].delta_v["red"], after.impacts[0].delta_v["red"])


def test_result_round_trip_keeps_its_figures() -> None:
    result = _scene().run(duration=0.4, dt=1e-3)
    back = pickle.loads(pickle.dumps(result))
    assert np.array_equal(back.trajectory("blue").velocity, result.trajectory("blue").velocity)
    assert back.impacts[0].time == result.impacts[0].time
    assert np.array_equal(back.impacts[0].centroid, result.impacts[0].centroid)


def test_a_scene_with_joints_and_a_pedestrian_round_trips_bit_identical() -> None:
    # Joints (the engine's Joint value) and a Pedestrian (its pose tables are read-only
    # mappings) pickle: a pedestrian struck by a car and its joints, after a round trip,
    # run to the same bits.
    car = cs.Vehicle.generate("sedan", name="car")
    person = cs.Pedestrian(pose="walking")
    scene = cs.Scene(ground=cs.Ground(friction=0.8))
    scene.add(car, (0.0, 0.0), velocity=(8.0, 0.0, 0.0))
    scene.add(person, (2.6, 0.0), heading=np.pi / 2)
    scene.soft_contact(car, person, stiffness=1e5)
    joint = scene.joints[0].core
    assert pickle.loads(pickle.dumps(joint)) == joint
    back = pickle.loads(pickle.dumps(scene))
    assert back.pedestrians["pedestrian"].arguments == person.arguments
    before, after = scene.run(0.05, dt=2e-4), back.run(0.05, dt=2e-4)
    # the car has struck him: his left shank is thrown forward (about 9.5 m/s at 0.05 s)
    assert before.trajectory("pedestrian/shank_left").velocity[-1, 0] > 5.0
    for name in ("car", "pedestrian/head", "pedestrian/thigh_left"):
        assert np.array_equal(before.trajectory(name).position, after.trajectory(name).position)
    hip = "pedestrian/hip_left"
    assert np.array_equal(before.joints[hip].angles, after.joints[hip].angles)
