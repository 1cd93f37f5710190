"""Wheels, tyres and driver inputs (crashsim.vehicles.wheels, crashsim.vehicles.inputs): the
geometry and springs the engine gets, the defaults read from the engine, and every bad input
as a typed error naming the wheel, the table or the vehicle.

Closed forms written out here: static loads are the axle shares W b / (2 L) and W a / (2 L);
a wheel sprung at f Hz with damping ratio z carrying F has k = (F/g) (2 pi f)^2 and
c = 2 z sqrt(k F/g).
"""

from __future__ import annotations

import math

import crashsim as cs
import numpy as np
import pytest
from crashsim import _core
from crashsim.vehicles.wheels import Tyre, Wheels, dynamics_defaults

G = 9.80665  # m/s^2, standard gravity (the engine's)
A, B, TRACK, H, R = 1.1, 1.6, 1.55, 0.55, 0.3  # m: CG to axles, track, CG height, radius
MASS = 1500.0


def car(**kwargs) -> cs.Vehicle:
    return cs.Vehicle.box(
        4.6,
        1.8,
        1.4,
        mass=MASS,
        name="car",
        ground_clearance=0.15,
        cg_height=H,
        wheelbase=A + B,
        track=TRACK,
        wheel_radius=R,
        cg_to_front_axle=A,
        **kwargs,
    )


def test_four_wheels_at_the_axles_with_the_axle_shares_and_the_sprung_rates() -> None:
    v = car()
    w = v.wheels
    assert w is not None and w.names == ("front_left", "front_right", "rear_left", "rear_right")
    expected = [[A, TRACK / 2, R - H], [A, -TRACK / 2, R - H]]
    expected += [[-B, TRACK / 2, R - H], [-B, -TRACK / 2, R - H]]
    np.testing.assert_allclose(w.centers, expected, rtol=0, atol=1e-15)
    assert w.steerable == (True, True, False, False)
    spec = w.spec(MASS)
    weight = MASS * G
    front, rear = weight * B / (A + B) / 2, weight * A / (A + B) / 2
    np.testing.assert_allclose(spec["static_loads"], [front, front, rear, rear], rtol=1e-12)
    d = dynamics_defaults()
    for f, k, c in zip(spec["static_loads"], spec["spring_rates"], spec["damping"], strict=True):
        m = f / G
        k_expected = m * (2 * math.pi * d["natural_frequency"]) ** 2
        assert k == pytest.approx(k_expected, rel=1e-12)
        assert c == pytest.approx(2 * d["damping_ratio"] * math.sqrt(k_expected * m), rel=1e-12)
    np.testing.assert_allclose(w.contact_points()[:, 2], -H, atol=1e-15)


def test_springs_per_axle_explicit_rates_and_the_rear_steering() -> None:
    w = Wheels(2.7, (1.5, 1.45), 1.2, 0.5, (0.3, 0.32), natural_frequency=(1.2, 1.5),
               damping_ratio=0.25, steer="rear")  # fmt: skip
    spec = w.spec(1000.0)
    loads = spec["static_loads"]
    for k, f in enumerate((1.2, 1.2, 1.5, 1.5)):
        assert spec["spring_rates"][k] == pytest.approx(loads[k] / G * (2 * math.pi * f) ** 2)
    assert w.steerable == (False, False, True, True)
    np.testing.assert_allclose(w.radii, [0.3, 0.3, 0.32, 0.32])
    np.testing.assert_allclose(w.centers[:, 1], [0.75, -0.75, 0.725, -0.725])
    given = Wheels(2.7, 1.5, 1.2, 0.5, 0.3, spring_rates=(30e3, 25e3), damping=2000.0)
    np.testing.assert_array_equal(given.spec(1000.0)["spring_rates"], [30e3, 30e3, 25e3, 25e3])
    np.testing.assert_array_equal(given.spec(1000.0)["damping"], [2000.0] * 4)


def test_wheel_names_short_names_and_axles() -> None:
    w = car().wheels
    assert w is not None
    assert [w.index(n) for n in ("FL", "fr", "rear_left", "Rear Right", 3)] == [0, 1, 2, 3, 3]
    assert w.axle("front") == (0, 1) and w.axle("rear") == (2, 3)
    with pytest.raises(cs.ParameterError, match="unknown wheel 'middle'.*front_left"):
        w.index("middle")
    custom = Wheels.custom([[1, 0, -0.2], [-1, 0.6, -0.2], [-1, -0.6, -0.2]], 0.3,
                           [True, False, False], names=["nose", "left", "right"])  # fmt: skip
    assert custom.index("nose") == 0
    with pytest.raises(cs.ParameterError, match="unknown axle"):
        custom.axle("front")


def test_tyre_defaults_come_from_the_engine_and_bad_tyres_are_named() -> None:
    d = _core.dynamics_defaults()
    resolved = Tyre().resolved()
    # the reconstruction programs' linear tyre: 1 per 10 deg, whatever the road (issue 19)
    assert resolved["cornering"] == d["cornering"] == pytest.approx(180.0 / (10.0 * math.pi))
    assert resolved["relaxation_length"] == d["relaxation_length"]
    assert resolved["rolling_resistance"] == d["rolling_resistance"] == 0.0
    assert resolved["combined"] == "braking_priority" and resolved["load_sensitivity"] == 0.0
    assert Tyre().to_core() == _core.Tyre("linear")
    # the saturation angle at mu = 1 is the cornering coefficient's equivalent input
    assert Tyre(saturation_angle=0.125).resolved()["cornering"] == 8.0
    mf = Tyre("magic_formula", b=10.0, c=1.9, e=0.97)
    assert mf.resolved() == {"model": "magic_formula", "b": 10.0, "c": 1.9, "e": 0.97,
                             "relaxation_length": 0.1, "rolling_resistance": 0.0,
                             "combined": "braking_priority", "load_sensitivity": 0.0}  # fmt: skip
    old = Tyre("linear_friction_scaled").resolved()
    assert old["saturation_angle"] == pytest.approx(math.radians(10.0))
    cases = [
        ({"model": "bald"}, "tyre model \"bald\" is unknown"),
        ({"relaxation_length": -1.0}, "tyre: relaxation_length = -1 is invalid"),
        ({"model": "magic_formula", "c": 3.0}, "C in \\(0, 2\\)"),
        ({"b": 10.0}, "b do\\(es\\) not belong to model \"linear\""),
        ({"model": "magic_formula", "saturation_angle": 0.2}, "not belong to model"),
        ({"cornering": 5.0, "saturation_angle": 0.2}, "not both"),
        ({"cornering": 0.0}, "cornering_coefficient = 0 is invalid"),
        ({"combined": "ellipse"}, "combined = \"ellipse\" is unknown"),
        ({"load_sensitivity": 1.0}, "load_sensitivity = 1 is invalid"),
        ({"rolling_resistance": "low"}, "must be a number"),
        # issue 24: 5 was accepted (and capped by the friction)
        ({"rolling_resistance": 5.0}, r"rolling_resistance = 5 is invalid: .* \[0, 0.3\]"),
    ]
    for kwargs, match in cases:
        with pytest.raises(cs.ParameterError, match=match):
            Tyre(**kwargs)
    with pytest.raises(cs.ParameterError, match="unknown tyre parameter"):
        Tyre.coerce({"grip": 1.0})


@pytest.mark.parametrize(
    "kwargs, match",
    [
        (
            {"track": 2.5},
            r"vehicle 'car': wheel 'front_left': its centre at \(1.100, 1.250\) m .* outside",
        ),
        ({"cg_to_front_axle": 3.0}, "vehicle 'car': .* the CG is not over the wheels"),
        ({"spring_rates": -5.0}, "wheel 'front_left': spring_rate = -5 is invalid"),
        ({"damping": (-1.0, 10.0)}, "wheel 'front_left': damping = -1 is invalid"),
        ({"radius": 0.0}, "wheel 'front_left': radius = 0 is invalid"),
        ({"natural_frequency": -1.0}, "wheel 'front_left': natural_frequency = -1"),
        # issue 24: 1e4 ran a locked car 47 m, 1e6 flipped it; 1000 Hz left it at 3 m/s
        ({"damping_ratio": 1e4}, r"wheel 'front_left': damping_ratio = 10000 .* \[0, 5\]"),
        ({"natural_frequency": 1000.0}, r"natural_frequency = 1000 Hz .* \(0, 20\] Hz"),
        ({"damping": 1e6}, r"wheel 'front_left': damping ratio = [0-9.]+ .* \[0, 5\]"),
        ({"spring_rates": 1e8}, r"wheel 'front_left': natural frequency = [0-9.]+ Hz"),
        ({"track": float("nan")}, "track = nan is invalid"),
        ({"steer": "all"}, "steer = 'all' is unknown"),
    ],
)
def test_bad_wheels_are_parameter_errors_naming_vehicle_and_wheel(kwargs, match) -> None:
    base = cs.Vehicle.box(4.6, 1.8, 1.4, mass=MASS, name="car", ground_clearance=0.15)
    wheels = {"wheelbase": A + B, "track": TRACK, "radius": R, "cg_to_front_axle": A}
    with pytest.raises(cs.ParameterError, match=match) as e:
        base.with_wheels(**{**wheels, **kwargs})
    assert isinstance(e.value, ValueError)
    assert base.wheels is None  # unchanged


def test_a_cg_beside_the_wheels_names_the_wheel_that_would_lift() -> None:
    # three wheels all ahead of the CG: the engine's static loads refuse it
    lifts = "wheel 'wheel_2': the centre of gravity is not over the wheels"
    with pytest.raises(cs.ParameterError, match=lifts):
        Wheels.custom([[1, 0.7, -0.2], [1, -0.7, -0.2], [2, 0, -0.2]], 0.3, [True] * 3)


def test_constructors_refuse_incomplete_or_conflicting_wheels() -> None:
    with pytest.raises(cs.ParameterError, match="wheel_radius, cg_to_front_axle missing"):
        cs.Vehicle.box(4.6, 1.8, 1.4, mass=MASS, ground_clearance=0.15, wheelbase=2.7, track=1.5)
    with pytest.raises(cs.ParameterError, match="needs ground_clearance > 0"):
        cs.Vehicle.box(4.6, 1.8, 1.4, mass=MASS, wheelbase=2.7, track=1.5, wheel_radius=0.3,
                       cg_to_front_axle=1.1)  # fmt: skip
    v = car()
    with pytest.raises(cs.ParameterError, match="not both"):
        v.with_wheels(v.wheels, wheelbase=2.0)
    # a mesh whose CG is not above z = 0 cannot stand on its model frame's ground
    floating = cs.Vehicle.box(4.6, 1.8, 1.4, mass=MASS, name="low", cg_height=0.0)
    with pytest.raises(cs.ParameterError, match="ground=True, or give cg_height"):
        floating.with_wheels(wheelbase=2.7, track=1.5, radius=0.3, cg_to_front_axle=1.1)


def test_from_mesh_and_with_wheels_keep_everything_else() -> None:
    box = cs.Vehicle.box(4.6, 1.8, 1.4, mass=MASS, ground_clearance=0.15)
    v = cs.Vehicle.from_mesh(
        box.mesh,
        mass=MASS,
        name="m",
        wheelbase=2.7,
        track=1.5,
        wheel_radius=0.3,
        cg_to_front_axle=1.2,
        tyre={"relaxation_length": 0.2},
    )
    assert v.wheels is not None and v.wheels.tyre.relaxation_length == 0.2
    assert v.wheels.cg_height == pytest.approx(box.cg[2])
    assert "wheels: wheelbase 2.700 m" in v.summary()
    plain = cs.Vehicle.from_mesh(box.mesh, mass=MASS, name="m")
    assert plain.wheels is None
    on = plain.with_wheels(wheelbase=2.7, track=1.5, radius=0.3, cg_to_front_axle=1.2)
    assert on.wheels is not None and plain.wheels is None
    assert on.mass == plain.mass and np.array_equal(on.inertia, plain.inertia)
    assert on.renamed("n").wheels is on.wheels


@pytest.mark.parametrize("preset", ["sedan", "suv", "pickup", "van", "bus"])
def test_generated_vehicles_stand_on_their_bodys_axles_with_the_class_track(preset) -> None:
    v = cs.Vehicle.generate(preset)
    vc = cs.vehicle_class(preset)
    p = v.generator_params
    w = v.wheels
    assert w is not None and p is not None
    assert w.wheelbase == pytest.approx(p.wheelbase, rel=1e-12)
    assert w.track == pytest.approx((vc.track_front.value, vc.track_rear.value), rel=1e-12)
    np.testing.assert_allclose(w.radii, p.wheel_radius)
    front_axle = p.length / 2 - p.front_overhang
    np.testing.assert_allclose(w.centers[:2, 0] + v.cg[0], front_axle, atol=1e-12)
    # the wheel centres at the tyre radius above the model frame's ground
    np.testing.assert_allclose(w.centers[:, 2] + v.cg[2], p.wheel_radius, atol=1e-12)
    assert w.source.startswith(f"track: class table ({preset})")
    wide = cs.Vehicle.generate(preset, width=1.1 * vc.width.value)
    assert wide.wheels is not None and wide.wheels.track is not None
    assert wide.wheels.track[0] == pytest.approx(1.1 * vc.track_front.value, rel=1e-12)


def test_wheels_from_a_class() -> None:
    vc = cs.vehicle_class("suv")
    w = Wheels.from_class("suv", wheelbase=2.0 * vc.wheelbase.value)
    assert w.wheelbase == pytest.approx(2.0 * vc.wheelbase.value)
    assert w.cg_to_front_axle == pytest.approx(2.0 * vc.cg_to_front_axle.value)
    np.testing.assert_allclose(w.radii, vc.tyre_radius.value)
    assert w.source == "class table (suv)"


# -- driver inputs -----------------------------------------------------------------------------


def test_inputs_resolve_axles_wheels_and_the_steering_ratio() -> None:
    w = car().wheels
    assert w is not None
    inputs = cs.DriverInputs(
        steering_wheel=[(0.0, 0.0), (1.0, 1.6)],
        steering_ratio=16.0,
        brake={
            "all": [(0.0, 0.2)],
            "front": [(0.0, 0.0), (1.0, 1.0)],
            "RR": cs.Brake.deceleration(4.0),
        },  # fmt: skip
        drive={"rear": 2000.0, "FL": [(0.0, 100.0)]},
        wheel_states=[("front", "locked", "exchange 2"), ("RL", "braked", 1.5, 0.5)],
    )
    core = inputs.to_core(w)
    # the steering-wheel angle goes to the engine with the ratio (the linkage divides)
    assert core["steer"][0] == "steering_wheel" and core["steering_ratio"] == 16.0
    np.testing.assert_allclose(core["steer"][1], [[0.0, 0.0], [1.0, 1.6]])
    kinds = [None if b is None else b[0] for b in core["brake"]]
    assert kinds == ["fraction", "fraction", "fraction", "deceleration"]
    np.testing.assert_array_equal(core["brake"][0][1], [[0.0, 0.0], [1.0, 1.0]])
    np.testing.assert_array_equal(core["brake"][2][1], [[0.0, 0.2]])
    assert core["drive"][1] is None
    np.testing.assert_array_equal(core["drive"][0], [[0.0, 100.0]])  # a wheel: its own force
    np.testing.assert_array_equal(core["drive"][2], [[0.0, 1000.0]])  # an axle: split
    assert core["switches"] == [
        (0, "exchange", 2.0, "locked", 1.0),
        (1, "exchange", 2.0, "locked", 1.0),
        (2, "time", 1.5, "braked", 0.5),
    ]
    total = cs.DriverInputs(drive=[(0.0, 4000.0)]).to_core(w)
    assert [float(d[0, 1]) for d in total["drive"]] == [1000.0] * 4


@pytest.mark.parametrize(
    "kwargs, match",
    [
        ({"steer": [(0.0, 0.0), (1.0, 0.1), (0.5, 0.2)]}, r"the steer table's times .*row 2"),
        ({"brake": {"front": [(0.0, 0.0), (0.0, 1.0)]}}, r"the brake\['front'\] table's times"),
        ({"drive": {"rear": [(1.0, 0.0), (0.5, 10.0)]}}, r"the drive\['rear'\] table's times"),
        ({"steer": [(0.0, float("nan"))]}, "steer table value at row 0"),
        ({"brake": "hard"}, "the brake table must be numbers"),
        ({"wheel_states": [("FL", "smashed", 0.0)]}, r"wheel_states\[0\]: state 'smashed'"),
        ({"wheel_states": [("FL", "locked", "exchange 0")]}, "exchanges count from 1"),
        ({"wheel_states": [("FL", "braked", 0.0, 1.5)]},
         r"wheel_states\[0\]: braked wheel fraction = 1.5"),
        ({"wheel_states": [("FL", "locked", float("nan"))]},
         r"wheel_states\[0\]: wheel-state switch time = NaN is invalid"),
        ({"wheel_states": [("FL", "locked", ("exchange", -1))]},
         r"wheel_states\[0\]: a wheel-state switch at exchange -1: give a whole number"),
        ({"steering_wheel": [(0.0, 1.0)], "steering_ratio": 0.5},
         r"steering_ratio = 0.5 is invalid: a steering ratio must lie in \[1, 100\]"),
        ({"wheel_states": [("FL", "locked", 0.0, 0.5)]}, "for the 'braked' state only"),
        # issue 24: "braked" without a fraction ran as locked
        ({"wheel_states": [("FL", "braked", 0.0)]}, "'braked' needs its fraction of the friction"),
    ],
)  # fmt: skip
def test_bad_input_tables_are_errors_naming_the_table(kwargs, match) -> None:
    with pytest.raises(cs.ParameterError, match=match):
        cs.DriverInputs(**kwargs)


@pytest.mark.parametrize(
    "kwargs, match",
    [
        ({"steer": 1.2}, "'car' inputs: the road-wheel steering angle reaches 68.8 deg"),
        ({"steering_wheel": [(0.0, 0.0), (1.0, 3.0)]}, "needs the vehicle's steering ratio"),
        ({"steer": {"RL": 0.1}}, "wheel 'rear_left': it has a steering table but does not steer"),
        ({"brake": {"middle": 1.0}}, r"brake\['middle'\]: unknown wheel 'middle'"),
        ({"wheel_states": [("XX", "locked", 0.0)]}, r"wheel_states\[0\]: unknown wheel 'XX'"),
    ],
)
def test_inputs_out_of_range_are_refused_when_added_to_a_vehicle(kwargs, match) -> None:
    scene = cs.Scene(ground=cs.Ground())
    with pytest.raises(cs.ParameterError, match=match):
        scene.add(car(), (0.0, 0.0), inputs=cs.DriverInputs(**kwargs))
    assert len(scene) == 0


@pytest.mark.parametrize(
    "make, loc, message",
    [
        (lambda: cs.DriverInputs(brake=1.5), (("part", None, "brake"),),
         "brake: a braking fraction must lie in [0, 1] (got 1.5 to 1.5)"),
        (lambda: cs.DriverInputs(brake={"RR": [(0.0, 0.5), (1.0, -0.1)]}),
         (("part", None, "brake['RR']"),),
         "brake['RR']: a braking fraction must lie in [0, 1] (got -0.1 to 0.5)"),
        # issue 24: 100 m/s^2 was accepted and ran as full braking
        (lambda: cs.Brake.deceleration(100.0), (),
         "a braking deceleration must lie in [0, 20] m/s^2 (got 100 to 100): no tyre brakes "
         "harder than about 1.2 g; to brake at the friction limit give a braking fraction of 1"),
        (lambda: cs.Brake("distributed", -1.0, 0.7), (),
         "a braking deceleration must lie in [0, 20] m/s^2 (got -1 to -1): no tyre brakes "
         "harder than about 1.2 g; to brake at the friction limit give a braking fraction of 1"),
        (lambda: cs.Brake.distributed(5.0, 1.5), (),
         "front_share = 1.5 is invalid: the front axle's share of the brake force must lie in "
         "[0, 1] (passenger cars 0.6-0.8)"),
        (lambda: cs.Brake("fraction", 0.5, 0.7), (),
         "front_share is for a distributed brake, not a fraction one"),
        (lambda: cs.Brake("abs", 1.0), (),
         "braking is a 'fraction' of the friction, a 'deceleration' or 'distributed', not 'abs'"),
    ],
)  # fmt: skip
def test_a_brake_is_checked_by_the_engines_rules_when_made(make, loc, message) -> None:
    """Brake is a value checked once, when made, by the core's rules of a braking (the
    vehicle applies the same function, Braking::check, to each wheel's); a table given to
    DriverInputs is placed in its key."""
    with pytest.raises(cs.ParameterError) as raised:
        make()
    assert str(raised.value) == message and raised.value.loc == loc


def test_inputs_need_wheels() -> None:
    scene = cs.Scene()
    box = cs.Vehicle.box(4.6, 1.8, 1.4, mass=MASS)
    with pytest.raises(cs.SceneError, match="driver inputs but no wheels"):
        scene.add(box, (0.0, 0.0, 0.7), inputs=cs.DriverInputs(brake=1.0))
