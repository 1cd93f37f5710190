"""The standard manoeuvres of docs/vehicle-model.md as runnable examples, and the driver who
follows a path (pure pursuit): each example runs and does what its page says, against figures
computed here (the linear single-track model, the cones of ISO 3888-1, the linkage's angles).
"""

from __future__ import annotations

import math
from pathlib import Path

import crashsim as cs
import numpy as np
import pytest
from crashsim.io.scenefile import load_scene
from crashsim.result import rotation_matrix

EXAMPLES = Path(__file__).resolve().parents[1] / "examples"
IN = 0.0254
WHEELBASE, TRACK, RATIO, WIDTH, LENGTH = 106 * IN, 60 * IN, 15.9, 70 * IN, 187 * IN


def test_the_reference_steer_ramp_turns_the_outer_wheel_by_the_ratio() -> None:
    # 360 deg of steering wheel over 15.9: the outer (left, in this turn to the right) front
    # wheel at 22.64 deg, the inner at full Ackermann's cot(o) - cot(i) = track / wheelbase
    result = load_scene(EXAMPLES / "reference-sedan-steer-15mph.toml").simulate()
    steer = result.wheel_steer("sedan")[:, -1]
    outer = -math.radians(360.0) / RATIO
    assert steer[0] == pytest.approx(outer, rel=1e-12)
    inner = -math.atan(1.0 / (1.0 / math.tan(-outer) - TRACK / WHEELBASE))
    assert steer[1] == pytest.approx(inner, rel=1e-12)
    assert steer[1] / steer[0] == pytest.approx(1.265, abs=0.001)  # "26 % more" of issue 19
    # it loops on a circle of about 6 m: more than a full turn in the run, 12 m across
    tr = result.trajectory("sedan")
    heading = np.unwrap([math.atan2(rotation_matrix(q)[1, 0], rotation_matrix(q)[0, 0])
                         for q in tr.orientation])  # fmt: skip
    assert heading[-1] < -2.0 * math.pi
    assert np.ptp(tr.position[:, 1]) == pytest.approx(12.0, abs=1.0)


def test_the_step_steer_follows_the_linear_single_track_model() -> None:
    # ISO 7401: 80 km/h, 21.3 deg at 400 deg/s. The steady yaw rate of the single-track model
    # with the linear tyre (load-proportional stiffness: neutral steer) is u delta / L, delta
    # the outer-reference linkage's mean angle; within 3 % (the roll, the tyres' drag slowing
    # the car 1 %, the two tracks: the model has none of them; measured 1.4 %).
    result = load_scene(EXAMPLES / "manoeuvre-step-steer.toml").simulate()
    tr = result.trajectory("sedan")
    steer = result.wheel_steer("sedan")[:, -1]
    delta = 0.5 * (steer[0] + steer[1])
    speed = float(np.linalg.norm(tr.velocity[-1, :2]))
    kinematic = speed * math.tan(delta) / WHEELBASE
    assert tr.angular_velocity[-1, 2] == pytest.approx(kinematic, rel=0.03)
    # 4 m/s^2 of steady lateral acceleration, as the input was chosen for (5 %)
    assert speed * tr.angular_velocity[-1, 2] == pytest.approx(4.0, rel=0.05)


def _lanes(width: float) -> list[tuple[float, float, float, float]]:
    """ISO 3888-1: (start x m, length m, lane centre y m, lane width m) of its three lanes for a
    vehicle `width` m wide (lane widths 1.1 w + 0.25, 1.2 w + 0.25, 1.3 w + 0.25 m; the side
    lane offset 3.5 m; the exit lane's right edge in line with the entry's)."""
    w1, w2, w3 = 1.1 * width + 0.25, 1.2 * width + 0.25, 1.3 * width + 0.25
    return [
        (0.0, 15.0, 0.0, w1),
        (45.0, 25.0, w2 / 2 - w1 / 2 + 3.5, w2),
        (95.0, 15.0, (w3 - w1) / 2, w3),
    ]


def test_the_lane_change_driver_keeps_the_car_inside_the_cones() -> None:
    result = load_scene(EXAMPLES / "manoeuvre-lane-change.toml").simulate()
    tr = result.trajectory("sedan")
    x, y = tr.position[:, 0], tr.position[:, 1]
    heading = np.unwrap([math.atan2(rotation_matrix(q)[1, 0], rotation_matrix(q)[0, 0])
                         for q in tr.orientation])  # fmt: skip
    for start, length, centre, lane in _lanes(WIDTH):
        on = (x >= start) & (x <= start + length)
        assert on.any()
        half = 0.5 * (WIDTH * np.cos(heading[on]) + LENGTH * np.abs(np.sin(heading[on])))
        assert np.all(np.abs(y[on] - centre) + half <= lane / 2 + 1e-9), (start, centre)


def test_the_fishhook_lifts_no_wheel_of_the_sedan() -> None:
    result = load_scene(EXAMPLES / "manoeuvre-fishhook.toml").simulate()
    loads = result.wheels("sedan").load
    assert loads.min() > 0.0  # no wheel leaves the ground
    rot = [rotation_matrix(q) for q in result.trajectory("sedan").orientation]
    roll = np.degrees([math.atan2(r[2, 1], r[2, 2]) for r in rot])
    # the roll gradient of 6 deg/g at up to mu g: at most 6 x 0.8 plus the overshoot of the
    # countersteer (measured 5.5 deg)
    assert 4.0 < np.abs(roll).max() < 6.5


@pytest.mark.parametrize("radius, speed", [(40.0, 15.0), (150.0, 25.0)])
def test_a_driver_follows_a_circle_within_a_metre(radius, speed) -> None:
    # pure pursuit around a circle (0.57 and 0.42 g at the entry): after the entry's step of
    # curvature the CG keeps to the circle's radius within 1 m (measured 0.48 and 0.94 m)
    th = np.linspace(0.0, 2.0 * math.pi, 361)
    points = np.c_[radius * np.sin(th), radius * (1.0 - np.cos(th))]
    car = cs.Vehicle.generate("sedan", name="car")
    scene = cs.Scene(ground=cs.Ground())
    scene.add(car, (0.0, 0.0), velocity=(speed, 0.0, 0.0),
              inputs=cs.DriverInputs(path=points, preview=0.6))  # fmt: skip
    duration = 2.0 * math.pi * radius / speed * 0.8
    result = scene.run(duration)
    tr = result.trajectory("car")
    d = np.hypot(tr.position[:, 0], tr.position[:, 1] - radius)
    settled = result.t > 0.3 * duration
    assert np.abs(d[settled] - radius).max() < 1.0


def test_a_driver_steers_back_onto_a_straight_line_and_stays_there() -> None:
    car = cs.Vehicle.generate("sedan", name="car")
    scene = cs.Scene(ground=cs.Ground())
    line = [(-10.0, 2.0), (500.0, 2.0)]  # the car starts 2 m right of it
    scene.add(car, (0.0, 0.0), velocity=(20.0, 0.0, 0.0), inputs=cs.DriverInputs(path=line))
    result = scene.run(12.0)
    tr = result.trajectory("car")
    assert abs(tr.position[-1, 1] - 2.0) < 0.05  # measured 2.6 cm, closing
    assert abs(tr.angular_velocity[-1, 2]) < 0.01  # rad/s: settled on the line
    with pytest.raises(cs.ParameterError, match="path points 0 and 1 are the same point"):
        inputs = cs.DriverInputs(path=[(0, 0), (0, 0), (5, 0)])
        cs.Scene(ground=cs.Ground()).add(car, (0.0, 0.0), inputs=inputs)
    with pytest.raises(cs.ParameterError, match="path preview"):
        inputs = cs.DriverInputs(path=line, preview=20.0)
        cs.Scene(ground=cs.Ground()).add(car, (0.0, 0.0), inputs=inputs)
