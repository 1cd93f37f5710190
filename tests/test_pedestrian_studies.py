"""Studies and fits with a pedestrian (docs/studies.md and docs/fitting.md, "Pedestrians"):
its parameter paths and the variants they build, the study's per-variant figures against a
run of the same variant read directly, and the vehicle's speed fitted back from the person's
position and the head-strike point.

The struck scene is benches/pedestrian_strike's (a generated sedan braking from t = 0, soft
car-segment contacts 1e5 N/m, damping ratio 0.5) with short runs at 0.4 ms steps (the soft
contact's limit for a 0.4 kg hand at 1e5 N/m is 0.4 ms): 0.3-0.5 s, a few seconds a run.
"""

from __future__ import annotations

import math
import warnings

import crashsim as cs
import numpy as np
import pytest
from crashsim.analysis.pedestrian import rest_of, segment_contacts
from crashsim.analysis.throw import first_contact_time, throw_distance
from crashsim.errors import ParameterError, StudyError
from crashsim.studies import choice, normal, uniform
from crashsim.studies.evidence import (
    FitError,
    HeadStrike,
    PedestrianRest,
    ThrowDistance,
    WrapAround,
)
from crashsim.studies.paths import base_value, parse_path, valid_paths

DT = 4e-4  # s
CAR = cs.Vehicle.generate("sedan", name="car")
AHEAD = float(CAR.mesh.bounds[1, 0] - CAR.cg[0])  # the car's CG to its front, m
BRAKE = cs.DriverInputs(brake=[(0.0, 1.0), (30.0, 1.0)])


def strike(speed_kmh: float = 40.0, soft: bool = True, **person: object) -> cs.Scene:
    """The sedan at ``speed_kmh`` braking, a walking 1.75 m, 75 kg man's left side 5 cm
    ahead of its front (other Pedestrian arguments in ``person``)."""
    args = {"height": 1.75, "mass": 75.0, "pose": "walking", **person}
    ped = cs.Pedestrian(**args)  # type: ignore[arg-type]
    scene = cs.Scene(ground=cs.Ground(friction=0.8))
    scene.add(CAR, (0.0, 0.0), heading=0.0, velocity=(cs.kmh(speed_kmh), 0.0, 0.0), inputs=BRAKE)
    scene.add(ped, (AHEAD + 0.05 + 0.2192, 0.0), heading=np.pi / 2)
    for seg in ped.segments:
        scene.contact(CAR, seg, depth_of_penetration=0.0, restitution=0.1, friction=0.3,
                      normal="volume")
    if soft:
        scene.soft_contact(CAR, ped, stiffness=1e5, damping_ratio=0.5)
    return scene


def run(scene: cs.Scene, duration: float) -> cs.Result:
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        return scene.run(duration, dt=DT, record_interval=2e-3)


# -- paths ------------------------------------------------------------------------------------


def test_a_pedestrian_scene_has_the_pedestrian_paths() -> None:
    scene = strike()
    paths = valid_paths(scene)
    for p in ("pedestrian.height", "pedestrian.mass", "pedestrian.percentile", "pedestrian.pose",
              "pedestrian.passive_moments", "pedestrian.road_friction", "pedestrian.position_x",
              "pedestrian.position_y",
              "pedestrian.heading", "pedestrian.speed", "car/pedestrian.friction",
              "car/pedestrian.stiffness", "car/pedestrian.damping_ratio", "ground.body_friction",
              "car.speed"):
        assert p in paths
    assert parse_path(scene, "pedestrian.height").kind == "pedestrian"
    assert parse_path(scene, "pedestrian/car.friction").target == ("car", "pedestrian")
    # a segment's own paths (its name holds "/"), and one segment's pair
    assert parse_path(scene, "pedestrian/head.speed").kind == "vehicle"
    assert parse_path(scene, "car/pedestrian/head.friction").target == ("car", "pedestrian/head")
    values = {"pedestrian.height": 1.75, "pedestrian.mass": 75.0, "pedestrian.pose": 1.0,
              "pedestrian.position_x": AHEAD + 0.05 + 0.2192, "pedestrian.position_y": 0.0,
              "pedestrian.heading": np.pi / 2, "pedestrian.speed": 0.0,
              "car/pedestrian.friction": 0.3, "car/pedestrian.stiffness": 1e5,
              "car/pedestrian.damping_ratio": 0.5, "ground.body_friction": 0.45,
              "pedestrian.passive_moments": 1.0, "pedestrian.road_friction": 0.66}
    for p, v in values.items():
        assert base_value(scene, p) == v, p
    assert math.isnan(base_value(scene, "pedestrian.percentile"))


def test_pedestrian_paths_refuse_what_they_cannot_set() -> None:
    scene = strike()
    with pytest.raises(StudyError, match=r'did you mean "pedestrian.height"'):
        parse_path(scene, "pedestrian.heigth")
    with pytest.raises(StudyError, match="soft contact's: give the pair one first"):
        parse_path(strike(soft=False), "car/pedestrian.stiffness")
    with pytest.raises(StudyError, match="set the same input"):
        scene.with_({"pedestrian.height": 1.8, "pedestrian.percentile": 50.0})
    with pytest.raises(StudyError, match="not both"):
        scene.with_({"pedestrian.height": 1.8, "pedestrian/head.speed": 1.0})
    with pytest.raises(StudyError, match="set the same input"):
        scene.with_({"car/pedestrian.friction": 0.2, "car/pedestrian/head.friction": 0.3})
    with pytest.raises(ParameterError, match="pose = 0.5 is not a pose's number"):
        scene.with_({"pedestrian.pose": 0.5})


def test_a_variant_is_the_scene_built_with_those_values() -> None:
    """with_ rebuilds the pedestrian: the engine's document equals that of the scene built
    with the same Pedestrian, place and contacts, character for character."""
    scene = strike()
    same = scene.with_({"pedestrian.height": 1.75, "pedestrian.pose": 1.0})
    assert same.to_spec(1.0, DT).to_json() == scene.to_spec(1.0, DT).to_json()
    taller = scene.with_({"pedestrian.height": 1.86, "pedestrian.mass": 90.0,
                          "pedestrian.pose": 0.0})
    built = strike(height=1.86, mass=90.0, pose="standing")
    assert taller.to_spec(1.0, DT).to_json() == built.to_spec(1.0, DT).to_json()
    assert taller.pedestrians["pedestrian"].height == pytest.approx(1.86, abs=1e-12)
    relaxed = scene.with_({"pedestrian.passive_moments": 0.5})
    halved = strike(passive_moments=0.5).to_spec(1.0, DT).to_json()
    assert relaxed.to_spec(1.0, DT).to_json() == halved != scene.to_spec(1.0, DT).to_json()
    rough = scene.with_({"pedestrian.road_friction": 0.7})
    built = strike(road_friction=0.7).to_spec(1.0, DT).to_json()
    assert rough.to_spec(1.0, DT).to_json() == built != scene.to_spec(1.0, DT).to_json()
    fifth = scene.with_({"pedestrian.percentile": 5.0})
    assert fifth.to_spec(1.0, DT).to_json() == strike(percentile=5.0).to_spec(1.0, DT).to_json()
    # placed elsewhere, facing the other way, walking at 1.4 m/s along its facing
    moved = scene.with_({"pedestrian.position_x": 4.0, "pedestrian.position_y": 0.5,
                         "pedestrian.heading": -np.pi / 2, "pedestrian.speed": 1.4})
    ref = strike(soft=False)
    other = cs.Scene(ground=cs.Ground(friction=0.8))
    other.add(CAR, (0.0, 0.0), heading=0.0, velocity=(cs.kmh(40.0), 0.0, 0.0), inputs=BRAKE)
    person = cs.Pedestrian(height=1.75, mass=75.0, pose="walking")
    other.add(person, (4.0, 0.5), heading=-np.pi / 2, velocity=(1.4 * math.cos(-np.pi / 2),
                                                               1.4 * math.sin(-np.pi / 2), 0.0))
    for seg in person.segments:
        other.contact(CAR, seg, depth_of_penetration=0.0, restitution=0.1, friction=0.3,
                      normal="volume")
    other.soft_contact(CAR, person, stiffness=1e5, damping_ratio=0.5)
    assert moved.to_spec(1.0, DT).to_json() == other.to_spec(1.0, DT).to_json()
    assert ref.to_spec(1.0, DT).to_json() != other.to_spec(1.0, DT).to_json()
    # the contact of the car with every segment
    soft = scene.with_({"car/pedestrian.stiffness": 2e5, "car/pedestrian.friction": 0.5})
    for seg in soft.pedestrians["pedestrian"].segments:
        assert soft.contact_parameters("car", seg.name)["friction"] == 0.5
    stiff = strike()
    stiff.soft_contact("car", stiff.pedestrians["pedestrian"], stiffness=2e5, damping_ratio=0.5)
    for seg in stiff.pedestrians["pedestrian"].segments:
        stiff.contact(CAR, seg, friction=0.5)
    assert soft.to_spec(1.0, DT).to_json() == stiff.to_spec(1.0, DT).to_json()
    # the base scene is unchanged
    assert scene.to_spec(1.0, DT).to_json() == strike().to_spec(1.0, DT).to_json()


# -- a study ----------------------------------------------------------------------------------


def test_monte_carlo_records_the_person_as_a_run_of_that_variant_gives() -> None:
    """A Monte Carlo over the road friction, the pose and the stature (3 variants of 0.3 s):
    each row's figures equal those read off ``scene.with_(inputs).run(...)``, bit for bit."""
    scene = strike()
    dists = {"ground.body_friction": uniform(0.45, 0.7), "pedestrian.pose": choice([0, 1]),
             "pedestrian.height": normal(1.756, 0.0686, 1.55, 1.95)}
    study = cs.monte_carlo(scene, dists, n=3, seed=2, duration=0.3, dt=DT, progress=False)
    assert study.ok.all() and not study.errors
    frame = study.frame
    assert set(frame["pedestrian.pose"]) == {0.0, 1.0}
    assert list(frame.columns[:3]) == list(dists)
    ped_cols = [c for c in frame.columns if c.startswith("pedestrian.")]
    assert "pedestrian.car.head_wrap_around" in ped_cols and "car.final_x" in frame.columns
    assert not any(c.startswith("pedestrian/") for c in frame.columns)  # no segment columns
    for i in range(study.n):
        inputs = {k: float(study[k][i]) for k in dists}
        variant = scene.with_(inputs)
        person = variant.pedestrians["pedestrian"]
        result = run(variant, 0.3)
        head = segment_contacts(result, person, CAR)["head"]
        end, speed = rest_of(result, person)
        car = result.trajectory("car")
        expected = {
            "pedestrian.car.throw_distance": throw_distance(result, "car", person),
            "pedestrian.car.first_contact_time": first_contact_time(result, "car", person),
            "pedestrian.car.head_time": head.time,
            "pedestrian.car.head_x": head.point[0], "pedestrian.car.head_y": head.point[1],
            "pedestrian.car.head_z": head.point[2],
            "pedestrian.car.head_wrap_around": head.wrap_around,
            "pedestrian.car.head_relative_speed": head.relative_speed,
            "pedestrian.final_x": end[0], "pedestrian.final_y": end[1],
            "pedestrian.final_speed": speed,
            "car.final_x": car.position[-1, 0],
            "car.final_speed": np.linalg.norm(car.velocity[-1]),
            "n_impacts": len(result.impacts),
        }
        for k, v in expected.items():
            assert frame[k].iloc[i] == v, (i, k)
        assert speed > 0.1 and math.isnan(frame["pedestrian.rest_x"].iloc[i])  # still moving
        assert 0.1 < head.time < 0.3 and 1.5 < throw_distance(result, "car", person) < 3.0
    units = study.summary()["unit"]
    assert units["pedestrian.car.throw_distance"] == units["pedestrian.car.head_x"] == "m"
    assert units["pedestrian.car.head_time"] == "s"
    assert units["pedestrian.car.head_relative_speed"] == "m/s"
    again = cs.monte_carlo(scene, dists, n=3, seed=2, duration=0.3, dt=DT, progress=False)
    assert np.array_equal(again["pedestrian.car.throw_distance"],
                          study["pedestrian.car.throw_distance"])


def test_a_variant_the_pedestrian_refuses_fails_alone() -> None:
    study = cs.sweep(strike(), {"pedestrian.pose": [0.5, 1.0]}, duration=0.02, dt=DT,
                     progress=False)
    assert list(study.status) == ["failed", "ok"]
    (error,) = study.errors
    assert error.kind == "ParameterError"
    assert "variant 0 (pedestrian.pose = 0.5)" in error.message and "0 = standing" in error.message
    assert math.isnan(study["pedestrian.car.head_time"][1])  # no head strike in 20 ms
    assert study["pedestrian.car.first_contact_time"][1] < 0.02


def test_a_pedestrian_study_refuses_dask() -> None:
    scene = strike()
    with pytest.raises(StudyError, match='backend="local"'):
        cs.sweep(scene, {"pedestrian.height": [1.7]}, duration=0.1, backend="dask",
                 progress=False)


def test_a_pedestrian_study_runs_until_the_person_rests() -> None:
    """A man alone pushed over (0.5 and 1 m/s) lies still: each variant ends when every body
    rests (issue 22: since the joint limits stopped creating energy, such runs end), and its
    row is what that variant's own run until rest gives, bit for bit."""
    ped = cs.Pedestrian(pose="standing")
    scene = cs.Scene(ground=cs.Ground(friction=0.8), depth_of_penetration=0.0)
    scene.add(ped, (0.0, 0.0), heading=2.0, velocity=(0.5, 0.0, 0.0))
    study = cs.sweep(scene, {"pedestrian.speed": [0.5, 1.0]}, until="rest", duration=12.0,
                     dt=1e-3, progress=False)
    assert study.ok.all() and not study.errors
    for i in range(study.n):
        variant = scene.with_({"pedestrian.speed": float(study["pedestrian.speed"][i])})
        with warnings.catch_warnings():
            warnings.simplefilter("error", cs.RestNotReachedWarning)
            result = variant.run(dt=1e-3, until="rest", max_duration=12.0, record_interval=2e-3)
        end, speed = rest_of(result, variant.pedestrians["pedestrian"])
        assert result.trajectory(result.vehicles[0]).t[-1] < 12.0  # the rest test ended it
        assert speed < 0.1  # m/s, the study's REST_SPEED
        assert study["pedestrian.rest_x"][i] == end[0] and study["pedestrian.rest_y"][i] == end[1]
        assert study["pedestrian.final_speed"][i] == speed


def test_choice_draws_each_value_by_its_weight() -> None:
    c = choice([0, 1, 5], [1, 2, 1])
    c.check("p")
    assert list(c.ppf([0.0, 0.25, 0.2501, 0.75, 0.7501, 1.0])) == [0, 0, 1, 1, 5, 5]
    draws = c.sample(np.random.default_rng(3), 40_000)
    assert np.mean(draws == 1) == pytest.approx(0.5, abs=0.01)
    with pytest.raises(StudyError, match="one weight >= 0 per value"):
        choice([0, 1], [1]).check("p")
    with pytest.raises(StudyError, match="is not a number"):
        choice(["walking"]).check("p")


# -- a fit ------------------------------------------------------------------------------------


def test_evidence_of_a_pedestrian_is_checked() -> None:
    scene = strike()
    bounds = {"car.speed": (8.0, 16.0)}
    with pytest.raises(FitError, match="no pedestrian 'bob'"):
        cs.fit(scene, bounds, [PedestrianRest("bob", 1.0, 0.0, 0.2)], until=None, duration=0.1)
    with pytest.raises(FitError, match="is a segment of 'pedestrian'"):
        cs.fit(scene, bounds, [WrapAround("pedestrian", "pedestrian/head", 2.0, 0.1)],
               until=None, duration=0.1)
    # a run too short for the head to touch: the items say why they are absent
    result = run(scene, 0.05)
    assert HeadStrike("pedestrian", "car", 1.0, 0.0, 0.9, 0.05).absent(result) == (
        "the head of pedestrian never touched car in the fitted run")
    assert ThrowDistance("pedestrian", "car", 10.0, 0.5).absent(result) is None
    caveat = PedestrianRest("pedestrian", 1.0, 0.0, 0.2).caveat(result)
    assert caveat is not None and "still moves at" in caveat


def test_fit_recovers_the_impact_speed_from_the_rest_and_the_head_strike() -> None:
    """Evidence read off a run at 45 km/h (0.5 s): the person's centre of mass at the end
    (0.1 m) and the head-strike point on the car (0.05 m per coordinate); the car's speed
    fitted from 38 km/h within 30-60 km/h comes back within 0.5 km/h, the truth inside the
    95 % range. Least squares, no sampling or scan: 16 runs of 0.5 s."""
    truth = strike(45.0)
    result = run(truth, 0.5)
    person = truth.pedestrians["pedestrian"]
    end, _ = rest_of(result, person)
    head = segment_contacts(result, person, CAR)["head"]
    evidence = [PedestrianRest("pedestrian", end[0], end[1], 0.1),
                HeadStrike("pedestrian", "car", *head.point, 0.05)]
    fit = cs.fit(strike(38.0), {"car.speed": (cs.kmh(30.0), cs.kmh(60.0))}, evidence,
                 until=None, duration=0.5, dt=DT, samples=0, scan=False, progress=False)
    speed = fit.values["car.speed"]
    assert abs(speed - cs.kmh(45.0)) < cs.kmh(0.5)
    lo, hi = fit.ranges["car.speed"]
    assert lo < cs.kmh(45.0) < hi and hi - lo < cs.kmh(8.0)
    # measured 16 runs; 32 without the local solve's stop once a step gains under 0.001
    assert fit.n_runs <= 20 and fit.objective < 0.1
    # the person still slides at 0.5 s: the verdict says the "rest" is not one
    assert fit.verdict.status == "poor fit"
    assert any("still moves at" in r for r in fit.verdict.reasons)


def test_fit_of_a_pedestrians_own_path_rebuilds_it_per_candidate() -> None:
    """The person's place as the unknown (each candidate rebuilds the pedestrian): evidence
    of its centre of mass 0.05 s into a strike placed 0.1 m further from the car than the
    base scene; the fit recovers the place within 5 mm."""
    scene = strike()
    x0 = base_value(scene, "pedestrian.position_x")
    truth = scene.with_({"pedestrian.position_x": x0 + 0.1})
    end, _ = rest_of(run(truth, 0.05), truth.pedestrians["pedestrian"])
    fit = cs.fit(scene, {"pedestrian.position_x": (x0 - 0.02, x0 + 0.3)},
                 [PedestrianRest("pedestrian", end[0], end[1], 0.01)], until=None,
                 duration=0.05, dt=DT, samples=0, scan=False, progress=False)
    assert abs(fit.values["pedestrian.position_x"] - (x0 + 0.1)) < 0.005
    assert fit.scene.pedestrians["pedestrian"] is not scene.pedestrians["pedestrian"]


def test_an_override_key_no_study_makes_is_refused() -> None:
    """apply_overrides takes the study's keys ("pedestrian:pedestrian.height"), not paths: a
    path given as a key was ignored and its variant ran the base scene (how the study's
    stalled variant 63 once "ran in 4.7 s alone", docs/studies.md)."""
    from crashsim.studies.paths import apply_overrides

    scene = strike()
    with pytest.raises(cs.StudyError, match="'pedestrian.height' is none of a study's"):
        apply_overrides(scene, {"pedestrian.height": np.array([1.62])}, 0)
    height = scene.with_({"pedestrian.height": 1.62}).pedestrians["pedestrian"].height
    assert height == pytest.approx(1.62)
