"""Wheels and driver inputs checked by the core's own rules with no probe scene (issue 20):
``_core.check_vehicle`` applies SceneSpec.set_vehicle's rules to set_vehicle's keywords and a
mass (kg), with the body's shape when given. Every bad value still raises the typed error,
message and place (``.loc``) the old probe body gave (each case below was run on both; only
a non-finite wheel centre changed, see its test)."""

from __future__ import annotations

import crashsim as cs
import numpy as np
import pytest
from crashsim import _core
from crashsim.vehicles import wheels as wheels_module
from crashsim.vehicles.wheels import Wheels

MASS = 1500.0  # kg
# four wheels, body frame (m): wheelbase 2.7, track 1.6, centres 0.25 m below the CG
C4 = [[1.2, 0.8, -0.25], [1.2, -0.8, -0.25], [-1.5, 0.8, -0.25], [-1.5, -0.8, -0.25]]
FLAGS = [True, True, False, False]
WHEELS = {"wheelbase": 2.7, "track": 1.55, "radius": 0.3, "cg_to_front_axle": 1.1}


def _body() -> cs.Vehicle:
    """A 4.6 x 1.8 x 1.4 m box of MASS kg (outline x +-2.3 m, y +-0.9 m about its CG)."""
    return cs.Vehicle.box(4.6, 1.8, 1.4, mass=MASS, name="car", ground_clearance=0.15,
                          cg_height=0.55)  # fmt: skip


def _add(**inputs) -> None:
    car = _body().with_wheels(**WHEELS)
    cs.Scene(ground=cs.Ground()).add(car, (0.0, 0.0), inputs=cs.DriverInputs(**inputs))


FRONT_LEFT, REAR_LEFT, REAR_RIGHT = ("wheel", 0, None), ("wheel", 2, None), ("wheel", 3, None)
# the vehicle's place while it is built, and its inputs' in a scene (crashsim.errors.vehicle_place)
CAR, CAR_INPUTS = ("part", None, "vehicle 'car'"), ("part", None, "vehicle 'car' inputs")


def _parameter(name: str) -> tuple[str, None, str]:
    """The place of the parameter ``name`` (innermost; its message names it)."""
    return ("parameter", None, name)

OUTSIDE = (
    "its centre at ({}) m (body frame, from the CG) lies outside the body, whose outline "
    "spans x -2.300 to 2.300 m and y -0.900 to 0.900 m: wheel positions are measured from the "
    "CG, x forward, y left"
)

# (what, call, the message, loc): the wheels alone, on a body, and driver inputs
CASES = [
    ("radius", lambda: Wheels(2.7, 1.5, 1.1, 0.55, (0.3, -0.3)),
     "wheel 'rear_left': radius = -0.3 is invalid: a tyre radius must be > 0 m",
     (REAR_LEFT, _parameter("radius"))),
    ("ackermann", lambda: Wheels(2.7, 1.5, 1.1, 0.55, 0.3, ackermann=3.0),
     "ackermann = 3 is invalid: the Ackermann fraction must lie in [0, 1.5] (1 full "
     "Ackermann, 0 parallel steer)", (_parameter("ackermann"),)),
    ("steering ratio", lambda: Wheels(2.7, 1.5, 1.1, 0.55, 0.3, steering_ratio=0.5),
     "steering_ratio = 0.5 is invalid: a steering ratio must lie in [1, 100] (about 16 for a "
     "car, 20-30 for a truck)", (_parameter("steering_ratio"),)),
    ("cg ahead", lambda: Wheels.custom([[1, 0.7, -0.2], [1, -0.7, -0.2], [2, 0, -0.2]], 0.3,
                                       [True] * 3),
     "wheel 'wheel_2': the centre of gravity is not over the wheels: this wheel would carry "
     "-9.8 N (check the wheel positions, which are measured from the CG)", (("wheel", 2, None),)),
    ("groups", lambda: Wheels.custom(C4, 0.3, FLAGS, load_groups=[[0, 2], [2, 3]]),
     "wheel 'wheel_2': it is in two load groups: a wheel shares its load in one group",
     (("wheel", 2, None),)),
    ("custom radius", lambda: Wheels.custom(C4, [0.3, 0.3, 0.3, -1.0], FLAGS),
     "wheel 'wheel_3': radius = -1 is invalid: a tyre radius must be > 0 m",
     (("wheel", 3, None), _parameter("radius"))),
    ("outside", lambda: _body().with_wheels(**{**WHEELS, "track": 2.5}),
     "vehicle 'car': wheel 'front_left': " + OUTSIDE.format("1.100, 1.250"), (CAR, FRONT_LEFT)),
    ("rates", lambda: _body().with_wheels(**WHEELS, damping=(10.0, -1.0)),
     "vehicle 'car': wheel 'rear_left': damping = -1 is invalid: a damping coefficient must be "
     ">= 0 N s/m", (CAR, REAR_LEFT, _parameter("damping"))),
    ("shared bar", lambda: _body().with_wheels(
        Wheels.custom(C4, 0.3, FLAGS, anti_roll=[(0, 1, 1e4), (0, 3, 1e4)])),
     "vehicle 'car': anti-roll bar 1 shares a wheel with another bar: one bar per wheel",
     (CAR,)),
    ("steer", lambda: _add(steer=1.2),
     "vehicle 'car' inputs: the road-wheel steering angle reaches 68.8 deg: road wheels turn "
     "at most 60 deg (a steering-wheel angle goes with the steering ratio)", (CAR_INPUTS,)),
    ("steer a fixed wheel", lambda: _add(steer={"RL": 0.1}),
     "vehicle 'car' inputs: wheel 'rear_left': it has a steering table but does not steer "
     "(make it steerable)", (CAR_INPUTS, REAR_LEFT)),
    ("brake", lambda: _add(brake={"RR": 1.5}),  # refused when the inputs are made
     "brake['RR']: a braking fraction must lie in [0, 1] (got 1.5 to 1.5)",
     (("part", None, "brake['RR']"),)),
    ("brake rows", lambda: Wheels(2.7, 1.5, 1.1, 0.55, 0.3).check_inputs(
        brake=[("fraction", np.array([[0.0, 0.5]]), None)] * 3),
     "braking is given for 3 wheels but the vehicle has 4", ()),
]  # fmt: skip


@pytest.mark.parametrize("what, call, message, loc", CASES, ids=[c[0] for c in CASES])
def test_each_bad_value_raises_the_error_and_place_the_probe_gave(what, call, message, loc):
    with pytest.raises(cs.ParameterError) as raised:
        call()
    assert type(raised.value) is cs.ParameterError
    assert str(raised.value) == message
    assert raised.value.loc == loc


def test_no_probe_scene_or_shape_is_made(monkeypatch) -> None:
    assert not hasattr(wheels_module, "_probe_world") and not hasattr(Wheels, "_probe")
    car = _body()
    car.shape  # the vehicle's own shape, made before the watch starts  # noqa: B018

    def made(*args, **kwargs):
        raise AssertionError("a probe was made")

    monkeypatch.setattr(_core, "SceneSpec", made)
    monkeypatch.setattr(_core, "Shape", made)
    w = Wheels(2.7, 1.55, 1.1, 0.55, 0.3)
    Wheels.custom(C4, 0.3, FLAGS, anti_roll=[(0, 1, 1e4)])
    w.check_inputs(steer=("road_wheel", np.array([[0.0, 0.0], [1.0, 0.1]])))
    car.with_wheels(w)
    with pytest.raises(cs.ParameterError, match="a braking fraction"):
        w.check_inputs(brake=[("fraction", np.array([[0.0, 1.5]]), None)] * 4)


def test_a_non_finite_wheel_centre_is_named_by_its_wheel() -> None:
    # The probe's box, sized from the centres, gave a MeshError about its own vertex 0
    # ("vertex 0 is not finite ([-1.81, NaN, -0.56])"); now the core's wheel_loads names
    # the wheel.
    c = np.array(C4)
    c[1, 1] = np.nan
    with pytest.raises(cs.ParameterError) as raised:
        Wheels.custom(c, 0.3, FLAGS)
    assert (
        str(raised.value)
        == "wheel 'wheel_1': centre y = NaN is invalid: it must be a finite number"
    )
    assert raised.value.loc == (("wheel", 1, None), _parameter("centre y"))


def _scene_error(mass: float, shape: _core.Shape, **kw) -> cs.ParameterError:
    spec = _core.SceneSpec()
    spec.add_body(shape, mass, np.eye(3) * mass, (0, 0, 0), (1, 0, 0, 0), (0, 0, 0), (0, 0, 0))
    with pytest.raises(cs.ParameterError) as raised:
        spec.set_vehicle(0, **kw)
    return raised.value


def test_check_vehicle_applies_set_vehicles_rules_with_and_without_the_body() -> None:
    car = _body().with_wheels(**WHEELS)
    assert car.wheels is not None
    good = car.wheels.spec(MASS)
    _core.check_vehicle(MASS, **good)
    _core.check_vehicle(MASS, shape=car.shape, **good)
    # a wheel 0.4 m past the body's side (margin 0.1 m) needs the body to be seen
    wide = {**good, "centers": good["centers"] + np.array([0.0, 0.4, 0.0])}
    _core.check_vehicle(MASS, **wide)
    bad = [
        (MASS, wide),
        (MASS, {**good, "radii": [0.3, 0.3, 0.0, 0.3]}),
        (2.0 * MASS, good),  # loads for 1500 kg do not carry 3000 kg
        (MASS, {**good, "brake": [None, ("fraction", np.array([[0.0, 2.0]]), None), None, None]}),
    ]
    for mass, kw in bad:
        with pytest.raises(cs.ParameterError) as raised:
            _core.check_vehicle(mass, shape=car.shape, **kw)
        by_scene = _scene_error(mass, car.shape, **kw)
        assert (str(raised.value), raised.value.loc) == (str(by_scene), by_scene.loc)
    with pytest.raises(cs.ParameterError) as raised:
        _core.check_vehicle(MASS, shape=car.shape, **wide)
    assert raised.value.loc == (FRONT_LEFT,) and "lies outside the body" in str(raised.value)
    # the mass is checked as a body's is (a scene checks it when the body is added)
    for mass in (-1.0, float("nan")):
        with pytest.raises(cs.ParameterError) as raised:
            _core.check_vehicle(mass, **good)
        with pytest.raises(cs.ParameterError) as by_body:
            _core.check_mass(mass, np.eye(3))
        assert str(raised.value) == str(by_body.value)


@pytest.mark.parametrize(
    ("springs", "loc", "start"),
    [
        ({"natural_frequency": -1.0}, (FRONT_LEFT, _parameter("natural_frequency")),
         "natural_frequency = -1 Hz is invalid"),
        ({"damping_ratio": [0.3, 0.3, 0.3, 9.0]}, (REAR_RIGHT, _parameter("damping_ratio")),
         "damping_ratio = 9 is invalid"),
    ],
)
def test_a_bad_spring_is_placed_at_its_wheel(springs, loc, start) -> None:
    """A natural frequency or damping ratio the engine's ``suspension`` refuses: the wheel's
    place is data (``.loc``), as the engine's own checks give it, inside the vehicle's place,
    whose name stays before it in the text (before: ``.loc`` was empty, the place only in the
    text)."""
    with pytest.raises(cs.ParameterError) as caught:
        _body().with_wheels(**WHEELS, **springs)
    e = caught.value
    assert e.loc == (CAR, *loc)
    assert e.message.startswith(start)
    name = wheels_module.STANDARD_NAMES[loc[0][1]]
    assert str(e) == f"vehicle 'car': wheel '{name}': {e.message}"


def test_at_puts_a_place_outermost_as_the_engine_does() -> None:
    from crashsim.errors import at

    inner = cs.ParameterError("x = -1 is invalid")  # made in Python: no places
    outer = at(at(inner, ("wheel", 2, None)), ("body", 1, "red"))
    assert outer.loc == (("body", 1, "red"), ("wheel", 2, None))
    assert outer.message == "x = -1 is invalid"
    assert str(outer) == 'body 1 ("red"): wheel 2: x = -1 is invalid'
    assert type(outer) is cs.ParameterError
