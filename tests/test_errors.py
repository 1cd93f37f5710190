"""Typed errors: every input mistake raises a crashsim error (a ValueError) that names what is
wrong, at the call that made it; the classes are the engine's own."""

from __future__ import annotations

import math

import crashsim as cs
import numpy as np
import pytest
from crashsim import _core


def two_cars() -> tuple[cs.Scene, cs.Vehicle, cs.Vehicle]:
    a = cs.Vehicle.box(4.0, 1.8, 1.4, mass=1000.0, name="a")
    b = cs.Vehicle.box(4.0, 1.8, 1.4, mass=1000.0, name="b")
    scene = cs.Scene()
    scene.add(a, position=(0.0, 0.0, 0.7)).add(b, position=(10.0, 0.0, 0.7))
    return scene, a, b


def test_the_exception_tree() -> None:
    for name in ("CrashsimError", "InputError", "MeshError", "ParameterError",
                 "InitialOverlapError", "SimulationError"):  # fmt: skip
        assert getattr(cs, name) is getattr(_core, name)  # defined once, in the engine
    for cls in (cs.InputError, cs.MeshError, cs.ParameterError, cs.InitialOverlapError):
        assert issubclass(cls, cs.CrashsimError) and issubclass(cls, ValueError)
    assert issubclass(cs.SceneError, cs.InputError)
    assert issubclass(cs.SimulationError, RuntimeError)
    assert not issubclass(cs.SimulationError, ValueError)


BAD_PARAMETERS = [
    ({"depth_of_penetration": 0.07}, r"depth_of_penetration = 0\.07.*\[0, 0\.060\]"),
    ({"depth_of_penetration": -0.01}, r"depth_of_penetration = -0\.01"),
    ({"depth_of_penetration": float("nan")}, "depth_of_penetration"),
    ({"restitution": 1.5}, r"restitution = 1\.5.*\[0, 1\]"),
    ({"restitution": -0.1}, "restitution"),
    ({"friction": -0.1}, r"friction = -0\.1.*>= 0"),
    ({"friction": float("inf")}, "friction"),
    ({"friction": "high"}, "friction"),
    ({"restitution_mode": "bouncy"}, "restitution_mode"),
    ({"normal": "sideways"}, "normal"),
    ({"normal": (0.0, 0.0, 0.0)}, "normal"),
    ({"normal": (1.0, float("nan"), 0.0)}, "normal"),
    ({"pitch": 2.0}, "pitch"),
    ({"centroid": (0.0, float("nan"), 0.0)}, "centroid"),
    ({"centroid": "middle"}, "centroid"),
]


@pytest.mark.parametrize("params, match", BAD_PARAMETERS)
def test_bad_scene_defaults_raise_at_construction(params, match) -> None:
    with pytest.raises(cs.ParameterError, match=match):
        cs.Scene(**params)


@pytest.mark.parametrize("params, match", BAD_PARAMETERS)
def test_bad_pair_parameters_raise_at_contact_and_change_nothing(params, match) -> None:
    scene, a, b = two_cars()
    with pytest.raises(cs.ParameterError, match=match):
        scene.contact(a, b, **params)
    assert scene.contact_parameters(a, b) == scene.defaults
    assert scene.run(0.01).impacts == []


@pytest.mark.parametrize(
    "state, match",
    [
        ({"velocity": (math.nan, 0.0, 0.0)}, r"velocity = \[NaN"),
        ({"angular_velocity": (0.0, 0.0, math.inf)}, "angular_velocity"),
        ({"position": (0.0, 0.0)}, "position must have 3 components"),
        ({"position": (0.0, math.nan, 0.7)}, "position"),
        ({"heading": math.nan}, "heading"),
        ({"orientation": (0.0, 0.0, 0.0, 0.0)}, "quaternion"),
        ({"orientation": np.diag([1.0, 1.0, 2.0])}, "orthonormal"),
        ({"orientation": np.diag([1.0, 1.0, -1.0])}, "reflection"),
        ({"heading": 0.1, "orientation": (1.0, 0.0, 0.0, 0.0)}, "not both"),
    ],
)
def test_bad_initial_states_raise_at_add(state, match) -> None:
    scene = cs.Scene()
    car = cs.Vehicle.box(4.0, 1.8, 1.4, mass=1000.0, name="a")
    kwargs = {"position": (0.0, 0.0, 0.7), **state}
    with pytest.raises(cs.ParameterError, match=match) as error:
        scene.add(car, **kwargs)
    assert isinstance(error.value, ValueError)
    assert len(scene) == 0  # nothing was added


def test_scene_mistakes_are_scene_errors() -> None:
    scene, a, b = two_cars()
    with pytest.raises(cs.SceneError, match="'ghost' is not in the scene") as error:
        scene.contact(a, "ghost")
    assert isinstance(error.value, cs.InputError) and isinstance(error.value, ValueError)
    with pytest.raises(cs.SceneError, match="already in the scene"):
        scene.add(a, position=(0.0, 5.0, 0.7))
    twin = cs.Vehicle.box(4.0, 1.8, 1.4, mass=1000.0, name="a")  # another object, same name
    with pytest.raises(cs.SceneError, match="names must be unique"):
        scene.add(twin, position=(0.0, 5.0, 0.7))
    with pytest.raises(cs.SceneError, match="two different vehicles"):
        scene.contact(a, "a")
    outsider = cs.Vehicle.box(4.0, 1.8, 1.4, mass=1000.0, name="c")
    scene.add(outsider, position=(0.0, 10.0, 0.7))
    with pytest.raises(cs.SceneError, match="not in the pair"):
        scene.contact(a, b, centroid=(outsider, (0.0, 0.0, 0.0)))
    with pytest.raises(cs.SceneError, match="no vehicles"):
        cs.Scene().run(0.1)
    with pytest.raises(TypeError, match="Vehicle"):
        cs.Scene().add("a", position=(0, 0, 0))  # type: ignore[arg-type]
    with pytest.raises(cs.SceneError, match="no vehicle named 'ghost'"):
        scene.run(0.01).trajectory("ghost")


def test_bad_run_arguments_are_parameter_errors() -> None:
    scene, _, _ = two_cars()
    with pytest.raises(cs.ParameterError, match="dt"):
        scene.run(0.1, dt=0.0)
    with pytest.raises(cs.ParameterError, match="duration"):
        scene.run(-1.0)
    with pytest.raises(cs.ParameterError, match="duration"):
        scene.run(math.nan)


def test_vehicles_overlapping_at_the_start_raise_initial_overlap_error() -> None:
    a = cs.Vehicle.box(4.0, 1.8, 1.4, mass=1000.0, name="a")
    b = cs.Vehicle.box(4.0, 1.8, 1.4, mass=1000.0, name="b")
    far = cs.Vehicle.box(4.0, 1.8, 1.4, mass=1000.0, name="far")
    scene = cs.Scene()
    scene.add(a, position=(0.0, 0.0, 0.7)).add(b, position=(3.0, 0.5, 0.7), heading=0.3)
    scene.add(far, position=(0.0, 20.0, 0.7))
    with pytest.raises(cs.InitialOverlapError, match="'a' and 'b' already overlap") as error:
        scene.run(0.1)
    assert isinstance(error.value, ValueError)
    assert "'far'" not in str(error.value)
    # one inside the other, surfaces apart, is an overlap too
    small = cs.Vehicle.box(1.0, 0.5, 0.5, mass=100.0, name="small")
    inside = cs.Scene().add(a, position=(0.0, 0.0, 0.7)).add(small, position=(0.0, 0.0, 0.7))
    with pytest.raises(cs.InitialOverlapError, match="'a' and 'small'"):
        inside.run(0.1)


BAD_NAMES = [
    ("red\n", r"U\+000A"),  # a newline split the CSV header
    ("red\u202e", r"U\+202E \(RIGHT-TO-LEFT OVERRIDE\)"),
    ("\u2066red", r"U\+2066 \(LEFT-TO-RIGHT ISOLATE\)"),
    ("r\u200fed", r"U\+200F \(RIGHT-TO-LEFT MARK\)"),
    ("r\ted", r"U\+0009"),
    ("r\x85ed", r"U\+0085"),  # NEL: a C1 control
    ("r\u2028ed", r"U\+2028 \(LINE SEPARATOR\)"),
    ("  ", "non-blank name"),
]


@pytest.mark.parametrize(("name", "why"), BAD_NAMES)
def test_names_with_control_or_bidirectional_characters_are_refused(name: str, why: str) -> None:
    # issue 24: names with a newline or U+202E were accepted; every name goes through
    # crashsim.names.check_name, which names the character's code point
    box = cs.Vehicle.box(4.0, 1.8, 1.4, mass=1000.0, name="a")
    wall = cs.Obstacle.wall(length=10.0, name="w")
    makers = {
        "a vehicle": lambda: cs.Vehicle.box(4.0, 1.8, 1.4, mass=1000.0, name=name),
        "a vehicle renamed": lambda: box.renamed(name),
        "an obstacle": lambda: cs.Obstacle.wall(length=10.0, name=name),
        "an obstacle renamed": lambda: wall.renamed(name),
        "a zone": lambda: cs.FrictionZone([(0, 0), (1, 0), (1, 1)], 0.5, name=name),
        "a wheel": lambda: cs.Wheels.custom([(1.2, 0.7, 0.0), (1.2, -0.7, 0.0), (-1.5, 0.0, 0.0)],
                                            0.3, [True, True, False], names=["one", "two", name]),
    }
    for what, make in makers.items():
        with pytest.raises(cs.ParameterError, match=why) as e:
            make()
        assert what.split(" renamed")[0] in str(e.value), what
    cs.Vehicle.box(4.0, 1.8, 1.4, mass=1000.0, name="Äpfel 1 (rot)")  # printable text is fine
