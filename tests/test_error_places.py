"""Errors carry where they happened (``.loc``) as data from the core, and the layers above
name the places from it (issue 20): the text is rebuilt from ``loc`` and ``message``, never
parsed."""

from __future__ import annotations

import pickle

import crashsim as cs
import numpy as np
import pytest
from crashsim import _core
from crashsim.batch import run_batch
from crashsim.errors import describe, naming, renamed, text


def _two_boxes(x_red: float = -3.65) -> cs.Scene:
    red = cs.Vehicle.box(4.5, 1.8, 1.4, mass=1450.0, name="red")
    blue = cs.Vehicle.box(4.6, 1.8, 1.45, mass=1500.0, name="blue")
    scene = cs.Scene(depth_of_penetration=0.03, restitution=0.1, friction=0.6)
    scene.add(red, (x_red, 0.3, 0.7), heading=0.0, velocity=(13.4112, 0.0, 0.0))
    scene.add(blue, (0.0, 0.0, 0.725), heading=np.pi / 2)
    return scene


def test_the_core_gives_the_place_and_the_message_apart() -> None:
    zones = [([(0, 0), (10, 0), (10, 10), (0, 10)], 0.5), ([(0, 0), (1, 0)], 0.4)]
    with pytest.raises(cs.ParameterError) as raised:
        _core.Ground(height=0.0, tyre_friction=0.8, body_friction=0.5, zones=zones)
    e = raised.value
    assert e.loc == (("zone", 1, None),)
    assert e.message == "it has 2 corners: a polygon needs at least 3"
    assert str(e) == "friction zone 1: " + e.message
    # an error raised with a text alone has no places
    assert cs.ParameterError("x").loc == () and cs.ParameterError("x").message is None


def test_a_bad_ground_value_names_the_ground_in_its_places() -> None:
    with pytest.raises(cs.ParameterError) as raised:
        cs.Ground(friction=-1)
    e = raised.value
    # the parameter is the innermost place; the message names it with its value, so the text
    # does not write it before the message
    assert e.loc == (("part", None, "ground"), ("parameter", None, "tyre-road friction"))
    assert e.message.startswith("tyre-road friction = -1 is invalid")
    assert str(e) == "ground: " + e.message


def test_a_vehicles_wheel_error_names_the_vehicle_and_the_wheel_in_its_places() -> None:
    box = cs.Vehicle.box(4.5, 1.8, 1.25, mass=1450.0, name="car", cg_height=0.55,
                         ground_clearance=0.15)  # fmt: skip
    with pytest.raises(cs.ParameterError) as raised:  # the front axle 0.75 m ahead of the box
        box.with_wheels(wheelbase=6.0, track=1.5, radius=0.3, cg_to_front_axle=3.0)
    e = raised.value
    assert e.loc == (("part", None, "vehicle 'car'"), ("wheel", 0, None))
    assert e.message.startswith("its centre at (3.000, 0.750) m (body frame, from the CG)")
    assert str(e) == "vehicle 'car': wheel 'front_left': " + e.message
    with pytest.raises(cs.ParameterError) as raised:  # the engine's own check of a value
        box.with_wheels(wheelbase=2.7, track=1.5, radius=-0.3, cg_to_front_axle=1.2)
    assert raised.value.loc == (("part", None, "vehicle 'car'"), ("wheel", 0, None),
                                ("parameter", None, "radius"))  # fmt: skip
    assert str(raised.value).startswith("vehicle 'car': wheel 'front_left': radius = -0.3")
    with pytest.raises(cs.ParameterError) as raised:  # the vehicle's own check in Python
        box.with_wheels(wheelbase=2.7)
    assert raised.value.loc == (("part", None, "vehicle 'car'"),)
    assert raised.value.message.startswith("wheels need track, radius, cg_to_front_axle (m)")
    assert str(raised.value) == "vehicle 'car': " + raised.value.message


def test_renamed_rebuilds_the_text_from_the_places_and_keeps_them() -> None:
    zones = [
        cs.FrictionZone([(0, 0), (10, 0), (10, 10), (0, 10)], 0.5, name="puddle"),
        cs.FrictionZone([(5, 5), (15, 5), (15, 15), (5, 15)], 0.3),
    ]
    with pytest.raises(cs.ParameterError) as raised:
        cs.Ground(zones=zones)
    e = raised.value
    assert e.loc == (("part", None, "ground"), ("zones", (0, 1), None))
    assert str(e) == "ground: friction zones 'puddle' and 1: " + e.message
    # a message that happens to read like a place is left alone: only loc is named
    fake = cs.ParameterError("wheel 0 is fine")
    assert str(renamed(fake, naming(wheel=lambda k: "front left"))) == "wheel 0 is fine"


def test_a_wheel_is_named_by_its_vehicle_in_a_scene_run() -> None:
    car = cs.Vehicle.box(4.5, 1.8, 1.25, mass=1450.0, name="car", cg_height=0.55,
                         ground_clearance=0.15).with_wheels(
        wheelbase=2.7, track=1.5, radius=0.3, cg_to_front_axle=1.2)
    import trimesh

    terrain = trimesh.creation.box(extents=(40.0, 40.0, 1.0))
    terrain.apply_translation((0.0, 0.0, -0.5))
    scene = cs.Scene(ground=cs.Ground(terrain=terrain))
    scene.add(car, (10.0, 0.0), heading=0.0, velocity=(10.0, 0.0, 0.0))
    with pytest.raises(cs.SimulationError) as raised:
        scene.run(2.0)
    e = raised.value
    kinds = [p[0] for p in e.loc]
    assert kinds == ["body", "wheel", "time"] and e.loc[0][1] == 0
    wheel, t = car.wheels.names[e.loc[1][1]], e.loc[2][1]
    assert str(e).startswith(f"vehicle 'car': wheel {wheel!r}: t = {t:.6f} s: it left")
    # the place survives pickling (Dask sends errors between processes)
    back = pickle.loads(pickle.dumps(e))
    assert back.loc == e.loc and back.message == e.message and str(back) == str(e)


def test_a_batch_error_names_the_variant_and_the_bodies_and_shifts_as_data() -> None:
    scene = _two_boxes()
    positions = np.array([[[-3.65, 0.3, 0.7], [0.0, 0.0, 0.725]],
                          [[-2.0, 0.3, 0.7], [0.0, 0.0, 0.725]]])  # (variant, body, xyz) m
    b = run_batch(scene, {"position": positions}, duration=0.05, dt=1e-3)
    (err,) = b.errors
    assert err.index == 1 and err.kind == "InitialOverlapError"
    assert err.loc == (("variant", 1, None), ("bodies", (0, 1), ("red", "blue")))
    assert err.message == f'variant 1: bodies 0 ("red") and 1 ("blue"): {err.reason}'
    assert err.within() == f'bodies 0 ("red") and 1 ("blue"): {err.reason}'
    moved = err.shifted(40)
    assert moved.index == 41 and moved.loc[0] == ("variant", 41, None)
    assert moved.message == f'variant 41: bodies 0 ("red") and 1 ("blue"): {err.reason}'
    assert describe(("bodies", (0, 1), (None, None))) == "bodies 0 and 1"


def test_single_values_are_checked_by_the_core_without_a_probe_scene() -> None:
    eye = np.eye(3)
    _core.check_mass(1450.0, eye * 2000.0)
    with pytest.raises(cs.ParameterError, match="mass"):
        _core.check_mass(-1.0, eye)
    _core.check_state((0, 0, 0.5), (1, 0, 0, 0), (10, 0, 0), (0, 0, 0))
    with pytest.raises(cs.ParameterError, match="position"):
        _core.check_state((float("nan"), 0, 0), (1, 0, 0, 0), (0, 0, 0), (0, 0, 0))
    with pytest.raises(cs.ParameterError, match="velocity"):
        _core.check_state((0, 0, 0), (1, 0, 0, 0), (0, float("inf"), 0), (0, 0, 0))
    _core.check_pose((1, 2, 0), (1, 0, 0, 0))
    with pytest.raises(cs.ParameterError):
        _core.check_pose((1, 2, float("nan")), (1, 0, 0, 0))
    _core.check_table([[0.0, 1.0], [1.0, 2.0]], "throttle")
    with pytest.raises(cs.ParameterError, match="the throttle table's times must increase"):
        _core.check_table([[1.0, 1.0], [0.0, 2.0]], "throttle")


@pytest.mark.parametrize(
    ("place", "text"),
    [
        (("variant", 7, None), "variant 7"),
        (("body", 0, "red"), 'body 0 ("red")'),
        (("body", 2, None), "body 2"),
        (("bodies", (0, 1, 4), ("a", None, "c")), 'bodies 0 ("a"), 1 and 4 ("c")'),
        (("wheel", 3, None), "wheel 3"),
        (("zone", 1, None), "friction zone 1"),
        (("zones", (1, 3), None), "friction zones 1 and 3"),
        (("part", None, "ground.zones[2]"), "ground.zones[2]"),
        (("time", 0.0625, None), "t = 0.062500 s"),
        (("parameter", None, "friction"), ""),  # the message names it, with its value
    ],
)
def test_describe_is_the_engines_rendering_of_each_kind(place, text) -> None:
    """One rendering of a place, the core's (``Place``'s Display through
    ``_core.describe_place``): the same text the engine's messages carry."""
    assert describe(place) == text


def test_a_parameter_error_has_its_parameter_in_loc_and_its_text_once() -> None:
    """The parameter at fault is data (``("parameter", None, name)``, innermost), as the
    engine's rule names it; the text names it once, in the message with its value, also when
    the layers above rebuild the text from the places (:func:`renamed`, a batch's
    variant)."""
    with pytest.raises(cs.ParameterError) as raised:
        _core.check_mass(-1.0, np.eye(3))
    e = raised.value
    assert e.loc == (("parameter", None, "mass"),)
    assert str(e) == e.message and e.message.startswith("mass = -1 is invalid")
    assert str(renamed(e, naming(wheel=lambda k: "x"))) == str(e)
    scene = _two_boxes(-8.0)
    b = run_batch(scene, {"contact.restitution": np.array([[0.1], [1.5]])}, duration=0.05,
                  dt=1e-3)
    (err,) = b.errors
    assert err.loc[0] == ("variant", 1, None) and err.loc[-1][0] == "parameter"
    assert err.message == f"variant 1: {err.within()}" and err.message.count("restitution =") == 1
    assert err.within() == text(err.loc[1:], err.reason)


def test_a_runs_settings_are_the_engines_rules_checked_when_the_spec_is_made() -> None:
    """RunSpec::check, at to_spec (set_run): a batch, a scene's run and a spec all refuse
    the same values with the same error, before any world is built."""
    scene = _two_boxes(-8.0)
    for settings, name in (({"dt": 0.0}, "dt"), ({"duration": -1.0}, "duration"),
                           ({"record_interval": -1.0}, "record_interval")):  # fmt: skip
        with pytest.raises(cs.ParameterError) as by_spec:
            scene.to_spec(**{"duration": 0.05, "dt": 1e-3, **settings})
        assert by_spec.value.loc == (("parameter", None, name),)
        with pytest.raises(cs.ParameterError) as by_run:
            scene.run(**{"duration": 0.05, "dt": 1e-3, **settings})
        assert str(by_run.value) == str(by_spec.value)
    with pytest.raises(cs.ParameterError, match="dt = 0 is invalid: the time step must be > 0"):
        run_batch(scene, {"contact.restitution": np.array([[0.1]])}, duration=0.05, dt=0.0)


def test_describe_refuses_what_is_no_place() -> None:
    for bad in (("lane", 1, None), ("wheel", "front", None), ("body", 0)):
        with pytest.raises(ValueError, match="is no place"):
            describe(bad)
