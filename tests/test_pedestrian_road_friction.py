"""A person's own friction with the road (Pedestrian(road_friction=), docs/human.md, "Road
friction"): each segment slides with it in place of the ground's body friction (a car
body's), through the API, the engine's spec, scene files and a cyclist's rider; the physics
is the core's (motion/ground_contact.rs: a body with its own friction slides and holds by
it)."""

from __future__ import annotations

import json
import warnings

import crashsim as cs
import numpy as np
import pytest
import trimesh
from crashsim import _core
from crashsim.errors import ParameterError
from crashsim.human.pedestrian import ROAD_FRICTION
from crashsim.io.scenefile import SceneFileError, loads_scene


def fallen(road_friction: float = ROAD_FRICTION, body_friction: float = 0.45) -> cs.Scene:
    """A standing man given 3 m/s forward: he falls and slides on the road."""
    ped = cs.Pedestrian(pose="standing", road_friction=road_friction)
    scene = cs.Scene(ground=cs.Ground(friction=0.8, body_friction=body_friction))
    scene.add(ped, (0.0, 0.0), heading=0.0, velocity=(3.0, 0.0, 0.0))
    return scene


def frictions(scene: cs.Scene) -> dict[str, float | None]:
    doc = json.loads(scene.to_spec(0.1).to_json())
    return {b["name"]: b.get("ground_friction") for b in doc["bodies"]}


def same_output(a: object, b: object) -> bool:
    """The engine's run dicts equal, arrays bit for bit."""
    if isinstance(a, dict) and isinstance(b, dict):
        return a.keys() == b.keys() and all(same_output(a[k], b[k]) for k in a)
    if isinstance(a, (list, tuple)) and isinstance(b, (list, tuple)):
        return len(a) == len(b) and all(same_output(x, y) for x, y in zip(a, b, strict=True))
    if isinstance(a, np.ndarray) or isinstance(b, np.ndarray):
        return np.array_equal(np.asarray(a), np.asarray(b))
    return bool(a == b)


def test_the_default_is_a_clothed_persons_and_every_segment_takes_it() -> None:
    ped = cs.Pedestrian()
    assert ped.road_friction == ROAD_FRICTION == 0.66
    assert ped.arguments["road_friction"] == 0.66 and "road_friction=0.66" in repr(ped)
    car = cs.Vehicle.generate("sedan", name="car")
    scene = fallen(0.6)
    scene.add(car, (-6.0, 0.0))
    own = frictions(scene)
    assert {k: v for k, v in own.items() if k.startswith("pedestrian/")} == {
        s.name: 0.6 for s in scene.pedestrians["pedestrian"].segments}
    assert own["car"] is None  # a vehicle slides (on its body) with the ground's
    # pickled and rebuilt from its arguments, bit for bit
    assert cs.Pedestrian(**ped.arguments).arguments == ped.arguments


@pytest.mark.parametrize("bad", [0.0, -0.2, 2.5, float("nan"), float("inf"), "0.6", True])
def test_a_bad_road_friction_is_refused_when_made(bad: object) -> None:
    with pytest.raises(ParameterError, match="road_friction"):
        cs.Pedestrian(road_friction=bad)  # type: ignore[arg-type]
    with pytest.raises(ParameterError, match="road_friction"):
        cs.Cyclist(road_friction=bad)  # type: ignore[arg-type]


def test_the_core_refuses_a_bad_ground_friction_and_an_obstacle() -> None:
    spec = fallen(0.6).to_spec(0.1)
    with pytest.raises(ParameterError, match="ground friction"):
        spec.set_ground_friction(0, 3.0)
    box = trimesh.creation.box((1.0, 1.0, 1.0))
    wall = _core.Shape(box.vertices, box.faces)
    k = spec.add_obstacle(wall, (20.0, 0.0, 0.5), (1.0, 0.0, 0.0, 0.0))
    with pytest.raises(ParameterError, match="fixed obstacle"):
        spec.set_ground_friction(k, 0.5)


def test_a_road_friction_equal_to_the_grounds_runs_the_same_bits() -> None:
    """Its own friction replaces the ground's, nothing else: 0.45 on a ground of 0.45 runs
    the spec without any own friction, bit for bit; 0.66 slides shorter."""
    same = fallen(0.45)
    doc = json.loads(same.to_spec(1.5).to_json())
    for b in doc["bodies"]:
        b.pop("ground_friction")
    plain = _core.SceneSpec.from_json(json.dumps(doc))
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        a = same.to_spec(1.5).run()
        b = plain.run()
        rough = fallen().run(1.5, record_interval=1e-2)
        smooth = fallen(0.45).run(1.5, record_interval=1e-2)
    assert same_output(a, b)
    pelvis = "pedestrian/pelvis"
    travel = {name: r.trajectory(pelvis).position[-1, 0] for name, r in
              (("rough", rough), ("smooth", smooth))}
    assert travel["rough"] < travel["smooth"] - 0.05, travel


def test_scene_files_and_a_cyclists_rider_take_it() -> None:
    text = """
format_version = 1
[ground]
friction = 0.8
[[vehicles]]
name = "car"
generate = "sedan"
mass = "1450 kg"
position = [-10, 0]
[[pedestrians]]
name = "walker"
position = [0, 0]
road_friction = 0.55
[[cyclists]]
name = "rider"
position = [0, 5]
road_friction = 0.6
"""
    scene = loads_scene(text).scene
    assert scene.pedestrians["walker"].road_friction == 0.55
    rider = scene.cyclists["rider"]
    assert rider.rider.road_friction == 0.6
    own = frictions(scene)
    assert all(own[s.name] == 0.55 for s in scene.pedestrians["walker"].segments)
    assert all(own[s.name] == 0.6 for s in rider.rider.segments)
    # the bicycle's frame and wheels slide with the ground's body friction
    assert all(own[f"rider/{b}"] is None for b in ("frame", "rear_wheel", "front_wheel"))
    default = loads_scene(text.replace("road_friction = 0.55\n", "")).scene
    assert default.pedestrians["walker"].road_friction == ROAD_FRICTION
    with pytest.raises(SceneFileError, match=r"pedestrians\[0\].*road_friction"):
        loads_scene(text.replace("road_friction = 0.55", "road_friction = 3"))


def test_a_study_varies_it() -> None:
    scene = fallen()
    variant = scene.with_({"pedestrian.road_friction": 0.5})
    assert variant.pedestrians["pedestrian"].road_friction == 0.5
    assert frictions(variant) == {k: 0.5 for k in frictions(scene)}
    assert np.all(np.array(list(frictions(scene).values())) == ROAD_FRICTION)
