"""The scene API: closed forms through the whole stack, contact options per pair, scene
defaults reaching the engine, orientations, results and the command line."""

from __future__ import annotations

import json
import math
import subprocess
import sys

import crashsim as cs
import numpy as np
import pytest


def head_on(eps: float, m1: float = 1450.0, m2: float = 1800.0, v: float = 15.0, **scene_kw):
    """Two boxes on the x axis, CGs at the same y and z (a central collinear impact): a at
    v m/s into b at rest."""
    a = cs.Vehicle.box(4.0, 1.8, 1.4, mass=m1, name="a")
    # a lower, longer box lifted so its CG is at a's height: the impact stays central
    b = cs.Vehicle.box(4.6, 1.7, 1.3, mass=m2, name="b", ground_clearance=0.05)
    scene = cs.Scene(restitution=eps, **scene_kw)
    scene.add(a, position=(0.0, 0.0, 0.7), velocity=(v, 0.0, 0.0))
    scene.add(b, position=(4.5, 0.0, 0.7))
    return scene


@pytest.mark.parametrize("eps", [0.0, 0.1, 0.5, 1.0])
def test_central_collinear_impact_matches_the_closed_form(eps: float) -> None:
    m1, m2, v = 1450.0, 1800.0, 15.0
    imp = head_on(eps).run(duration=0.2, dt=1e-3).impacts[0]
    assert not imp.sliding
    assert np.allclose(imp.normal, [1.0, 0.0, 0.0], rtol=0, atol=1e-12)
    expected = (1.0 + eps) * m2 / (m1 + m2) * v  # delta-V1 (docs/model.md invariant)
    assert -imp.delta_v["a"][0] == pytest.approx(expected, rel=1e-9)
    assert imp.speed_change("a") == pytest.approx(expected, rel=1e-9)
    assert imp.delta_v["b"][0] == pytest.approx((1.0 + eps) * m1 / (m1 + m2) * v, rel=1e-9)
    assert np.allclose(imp.delta_omega["a"], 0.0, atol=1e-9)
    # momentum conserved; energy lost (1 - eps^2) m1 m2 / (m1 + m2) v^2 / 2
    p_after = m1 * imp.velocity_after["a"] + m2 * imp.velocity_after["b"]
    assert np.allclose(p_after, [m1 * v, 0.0, 0.0], rtol=1e-12, atol=1e-9)
    lost = 0.5 * (1.0 - eps**2) * m1 * m2 / (m1 + m2) * v * v
    assert imp.energy_dissipated == pytest.approx(lost, rel=1e-9, abs=1e-6)
    assert imp.closing_speed == pytest.approx(v, rel=1e-12)
    assert np.array_equal(imp.impulse_on("a"), -imp.impulse)
    assert np.array_equal(imp.impulse_on("b"), imp.impulse)


def test_newton_restitution_equals_total_for_a_central_impact() -> None:
    total = head_on(0.3).run(0.2).impacts[0]
    normal = head_on(0.3, restitution_mode="normal").run(0.2).impacts[0]
    assert np.allclose(normal.impulse, total.impulse, rtol=1e-12, atol=1e-9)


def test_scene_defaults_and_pair_overrides_reach_the_engine() -> None:
    scene = head_on(0.0, depth_of_penetration=0.010)
    imp = scene.run(0.2).impacts[0]
    assert imp.time - imp.first_contact_time == pytest.approx(0.010, abs=1e-12)
    scene.contact("a", "b", depth_of_penetration=0.045)
    scene.contact("a", "b", restitution=0.5)  # adds to the pair's overrides
    params = scene.contact_parameters("a", "b")
    assert params["depth_of_penetration"] == 0.045 and params["restitution"] == 0.5
    imp = scene.run(0.2).impacts[0]
    assert imp.time - imp.first_contact_time == pytest.approx(0.045, abs=1e-12)
    assert -imp.delta_v["a"][0] == pytest.approx(1.5 * 1800 / 3250 * 15.0, rel=1e-9)


def test_the_normal_points_from_vehicle1_into_vehicle2() -> None:
    scene = head_on(0.1)
    scene.contact("b", "a")  # reversed pair: b is vehicle 1
    imp = scene.run(0.2).impacts[0]
    assert imp.vehicles == ("b", "a") and imp.bodies == (1, 0)
    assert np.allclose(imp.normal, [-1.0, 0.0, 0.0], atol=1e-12)
    assert imp.impulse[0] < 0.0  # on a, pushing it back
    assert imp.closing_speed == pytest.approx(15.0, rel=1e-12)


def side_scene(**contact) -> cs.Scene:
    red = cs.Vehicle.box(4.5, 1.8, 1.4, mass=1450.0, name="red")
    blue = cs.Vehicle.box(4.6, 1.8, 1.45, mass=1500.0, name="blue")
    scene = cs.Scene()
    scene.add(red, position=(-3.65, 0.3, 0.7), velocity=(cs.mph(30.0), 0.0, 0.0))
    scene.add(blue, position=(0.0, 0.0, 0.725), heading=cs.deg(90.0))
    if contact:
        scene.contact(red, blue, **contact)
    return scene


def test_normal_options() -> None:
    n = side_scene().run(0.1).impacts[0].normal
    assert np.allclose(n, [1.0, 0.0, 0.0], atol=1e-12)  # the struck face's
    tilted = side_scene(pitch=cs.deg(10.0)).run(0.1).impacts[0].normal
    assert np.allclose(tilted, [math.cos(cs.deg(10.0)), 0.0, math.sin(cs.deg(10.0))], atol=1e-12)
    given = side_scene(normal=(2.0, 2.0, 0.0)).run(0.1).impacts[0].normal
    assert np.allclose(given, [math.sqrt(0.5), math.sqrt(0.5), 0.0], atol=1e-15)
    volume = side_scene(normal="volume").run(0.1).impacts[0].normal
    assert np.linalg.norm(volume) == pytest.approx(1.0, abs=1e-12) and volume[0] > 0.9


def test_centroid_options() -> None:
    world = side_scene(centroid=(-0.5, 0.2, 0.6)).run(0.1).impacts[0]
    assert np.array_equal(world.centroid, [-0.5, 0.2, 0.6])
    scene = side_scene(centroid=("red", (2.25, -0.1, 0.0)))  # red's front face, body frame
    result = scene.run(0.1)
    imp = result.impacts[0]
    red = result.state_at("red", imp.time)["position"]  # heading 0: body axes = world axes
    assert np.allclose(imp.centroid, red + [2.25, -0.1, 0.0], rtol=0, atol=1e-12)
    auto = side_scene(centroid=None).run(0.1).impacts[0]
    assert auto.centroid[1] == pytest.approx(0.3, abs=1e-9)


def test_heading_quaternion_and_matrix_give_the_same_run() -> None:
    h = cs.deg(90.0)
    rotation = np.array([[math.cos(h), -math.sin(h), 0], [math.sin(h), math.cos(h), 0], [0, 0, 1]])
    quaternion = (math.cos(h / 2), 0.0, 0.0, math.sin(h / 2))
    impacts = []
    for pose in ({"heading": h}, {"orientation": quaternion}, {"orientation": rotation}):
        red = cs.Vehicle.box(4.5, 1.8, 1.4, mass=1450.0, name="red")
        blue = cs.Vehicle.box(4.6, 1.8, 1.45, mass=1500.0, name="blue")
        scene = cs.Scene()
        scene.add(red, position=(-3.65, 0.3, 0.7), velocity=(cs.mph(30.0), 0.0, 0.0))
        scene.add(blue, position=(0.0, 0.0, 0.725), **pose)
        impacts.append(scene.run(0.1).impacts[0])
    for imp in impacts[1:]:
        assert imp.first_contact_time == pytest.approx(impacts[0].first_contact_time, abs=1e-9)
        assert np.allclose(imp.impulse, impacts[0].impulse, rtol=1e-9, atol=1e-6)


def test_result_trajectories_and_log() -> None:
    scene = side_scene()
    result = scene.run(duration=0.2, dt=1e-3)
    assert result.vehicles == ["red", "blue"]
    imp = result.impacts[0]
    tr = result.trajectory("red")
    k = tr.t.size
    assert tr.position.shape == (k, 3) and tr.orientation.shape == (k, 4)
    assert tr.velocity.shape == (k, 3) and tr.angular_velocity.shape == (k, 3)
    assert tr.t[0] == 0.0 and tr.t[-1] == pytest.approx(0.2, abs=1e-12)
    assert np.all(np.diff(tr.t) >= 0.0) and np.all(np.diff(tr.t) <= 1e-3 + 1e-12)
    assert imp.first_contact_time in tr.t and imp.time in tr.t
    assert np.array_equal(tr.position, result.trajectory(scene.vehicles[0]).position)
    assert np.allclose(np.linalg.norm(tr.orientation, axis=1), 1.0, atol=1e-12)
    # before the first overlap red coasts at 30 mph; after the exchange its velocity is the
    # impact's velocity_after
    before = tr.t < imp.first_contact_time
    assert np.allclose(tr.velocity[before], [cs.mph(30.0), 0.0, 0.0], atol=1e-12)
    after = result.state_at("red", imp.time)["velocity"]
    assert np.array_equal(after, imp.velocity_after["red"])
    assert result.contacts[0].kind == "first_overlap"
    assert result.contacts[0].vehicles == ("red", "blue")
    assert result.contacts[0].time == imp.first_contact_time
    with pytest.raises(ValueError):
        tr.position[0, 0] = 1.0  # results are read-only
    text = json.dumps(result.to_dict(trajectories=True))
    back = json.loads(text)
    assert back["impacts"][0]["delta_v"]["red"] == imp.delta_v["red"].tolist()
    assert len(back["trajectories"]["blue"]["t"]) == k


def test_a_three_vehicle_scene_sets_every_pair() -> None:
    a = cs.Vehicle.box(4.0, 1.8, 1.4, mass=1000.0, name="a")
    b = cs.Vehicle.box(4.0, 1.8, 1.4, mass=1000.0, name="b")
    c = cs.Vehicle.box(4.0, 1.8, 1.4, mass=1000.0, name="c")
    scene = cs.Scene(restitution=0.0)
    scene.add(a, position=(0.0, 0.0, 0.7), velocity=(10.0, 0.0, 0.0))
    scene.add(b, position=(4.5, 0.0, 0.7))
    scene.add(c, position=(9.0, 0.0, 0.7))
    scene.contact(b, c, restitution=1.0)
    result = scene.run(duration=0.5, dt=1e-3)
    pairs = [imp.vehicles for imp in result.impacts]
    assert pairs[:2] == [("a", "b"), ("b", "c")]
    first, second = result.impacts[:2]
    assert first.delta_v["b"][0] == pytest.approx(5.0, rel=1e-9)  # plastic, equal masses
    assert second.delta_v["c"][0] == pytest.approx(5.0, rel=1e-9)  # elastic: b stops
    assert second.velocity_after["b"][0] == pytest.approx(0.0, abs=1e-9)


def test_scene_runs_are_repeatable_and_independent() -> None:
    scene = side_scene()
    first = scene.run(0.1)
    second = scene.run(0.1)  # a fresh engine world: starts again from the initial states
    assert np.array_equal(first.trajectory("red").position, second.trajectory("red").position)
    assert len(second.impacts) == len(first.impacts) == 1


def test_demo_command(capsys: pytest.CaptureFixture[str]) -> None:
    from crashsim.cli import main

    assert main(["demo", "--impact-only"]) == 0
    out = capsys.readouterr().out
    assert "red's travel past first overlap: 0.4023 m = 1.320 ft" in out
    assert "delta-V red" in out and "delta-V blue" in out and "energy dissipated" in out
    assert "mph" in out and "kJ" in out
    with pytest.raises(SystemExit) as done:
        main(["--help"])
    assert done.value.code == 0
    assert "demo" in capsys.readouterr().out


def test_python_dash_m_crashsim_demo() -> None:
    out = subprocess.run(
        [sys.executable, "-m", "crashsim", "demo", "--impact-only", "--json"],
        capture_output=True, text=True, check=True, timeout=120,
    )  # fmt: skip
    data = json.loads(out.stdout)
    imp = data["impacts"][0]
    assert imp["vehicles"] == ["red", "blue"]
    assert imp["time"] - imp["first_contact_time"] == pytest.approx(0.030, abs=1e-12)
