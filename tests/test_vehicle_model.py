"""The vehicle model (issue 19) against closed forms, each written out here:

- steady cornering in the linear range with load-sensitive tyres and a roll-stiffness split
  (Gillespie ch. 6 and 8; Milliken ch. 18): the lateral load transfer of each axle from its
  roll stiffness, each axle's cornering stiffness from its wheels' loads, the steer angle
  (hence the yaw rate) the single-track model then needs, and the roll angle. The engine's
  roll: the whole mass is sprung, the lateral forces act at the ground (arm h) and the
  contact points stay under the wheel centres, so gravity's overturning arm is the CG's
  height above the wheel centres (h - R): phi = m a_y h / (K - m g (h - R));
- the stopping distance of every braking input: locked wheels, a fraction of the friction, a
  deceleration demand (ideal distribution), a fixed front/rear split with ABS, and without
  ABS (the front wheels lock: their friction on their dynamic load), and rolling resistance;
  the Magic Formula tyre delivers the same braking as the linear one.

Tolerances are stated at each assertion (the issue's 1 % unless said).
"""

from __future__ import annotations

import math
from pathlib import Path

import crashsim as cs
import numpy as np
import pytest
from crashsim.result import rotation_matrix
from scipy.optimize import brentq

EXAMPLES = Path(__file__).resolve().parents[1] / "examples"
G = 9.80665
MU = 0.8  # the engine's default tyre friction (dry asphalt)
MASS = 1500.0
A, B = 1.1, 1.6  # CG to the front and rear axles (m)
L = A + B
TRACK = 1.55
H = 0.55  # CG height (m)
R = 0.3  # tyre radius (m)
C = 15.0  # the cornering coefficient (1/rad) of the cornering tests: a real tyre's, so the
# single-track model's small angles hold (the reconstruction tyre's 5.7 needs slip angles
# six times the steer at 0.4 g, and the two-track kinematics then move the yaw rate by 1 %)


def car(**wheels) -> cs.Vehicle:
    """A 4.6 x 1.8 x 1.4 m box car on its wheels (centre reference, parallel steer unless
    given, so the single-track model's steer angle is every front wheel's)."""
    wheels.setdefault("steering_reference", "centre")
    w = cs.Wheels(L, TRACK, A, H, R, **wheels)
    box = cs.Vehicle.box(4.6, 1.8, 1.4, mass=MASS, name="car", ground_clearance=0.15, cg_height=H)
    return box.with_wheels(w)


# -- steady cornering ---------------------------------------------------------------------------


def _axle_stiffness(static: float, transfer: float, e: float) -> float:
    """An axle's cornering stiffness (N/rad): two wheels of static load ``static`` (N) with
    ``transfer`` (N) moved from the inner to the outer, each C(F) = c F0 (F / F0)^(1 - e)."""
    x = transfer / static
    return C * static * ((1.0 + x) ** (1.0 - e) + (1.0 - x) ** (1.0 - e))


def _steady_state(v: float, delta: float, e: float, k_front: float, k_rear: float) -> dict:
    """The closed form: the yaw rate r (rad/s) at speed v with front steer delta on a flat
    road, by the single-track kinematics delta = L r / v + alpha_f - alpha_r, the axle forces
    from the yaw and lateral equilibrium (F_f = m a_y b / L, F_r = m a_y a / L, a_y = v r),
    the roll angle phi = m a_y h / (K - m g (h - R)) and each axle's transfer
    dF = K_axle phi / t."""
    w = MASS * G
    front, rear = w * B / L / 2.0, w * A / L / 2.0  # static wheel loads (N)
    k = k_front + k_rear

    def parts(r: float) -> dict:
        ay = v * r
        phi = MASS * ay * H / (k - MASS * G * (H - R))
        df, dr = k_front * phi / TRACK, k_rear * phi / TRACK
        cf, cr = _axle_stiffness(front, df, e), _axle_stiffness(rear, dr, e)
        alpha_f = MASS * ay * B / L / cf
        alpha_r = MASS * ay * A / L / cr
        residual = L * r / v + alpha_f - alpha_r - delta
        return {"ay": ay, "phi": phi, "df": df, "dr": dr, "residual": residual}

    r = brentq(lambda r: parts(r)["residual"], 1e-6, 2.0 * v * delta / L)
    return {"r": r, **parts(r)}


@pytest.mark.parametrize("e", [0.0, 0.3])
@pytest.mark.parametrize("front_share", [0.8, 0.3])
def test_steady_cornering_follows_the_closed_form_with_load_sensitivity_and_roll_split(
    front_share, e
) -> None:
    # 0.4 g at 30 m/s. With load-sensitive tyres (e = 0.3) the axle stiffer in roll takes
    # more of the load transfer and loses more cornering stiffness, so moving the roll
    # stiffness forward (0.8) understeers and rearward (0.3) oversteers (4.6 % of yaw rate
    # between the two); with e = 0 the split changes nothing. Measured: the yaw rate within
    # 0.4 %, the roll and each axle's transfer within 0.7 % of the closed form.
    v, delta = 30.0, 0.012
    bars = 900.0 * 180.0 / math.pi  # N m/rad in all, split
    vehicle = car(anti_roll=(front_share * bars, (1.0 - front_share) * bars),
                  ackermann=0.0, tyre=cs.Tyre(load_sensitivity=e, cornering=C))  # fmt: skip
    d = vehicle.wheels.describe(MASS)
    k_front, k_rear = d["roll_stiffness"]["front"], d["roll_stiffness"]["rear"]
    expected = _steady_state(v, delta, e, k_front, k_rear)
    scene = cs.Scene(ground=cs.Ground())
    scene.add(vehicle, (0.0, 0.0), velocity=(v, 0.0, 0.0),
              inputs=cs.DriverInputs(steer=[(0.0, 0.0), (0.3, delta)]))  # fmt: skip
    result = scene.run(4.0)
    tr = result.trajectory("car")
    # the state at 4 s, quasi-steady: the tyres' drag slows the car 1.2 % in 4 s, so the
    # closed form is taken at the speed then
    speed = float(np.linalg.norm(tr.velocity[-1, :2]))
    expected = _steady_state(speed, delta, e, k_front, k_rear)
    r = float(tr.angular_velocity[-1, 2])
    assert r == pytest.approx(expected["r"], rel=0.01)
    # the roll angle: in a turn to the left the body leans out, its left side up (+ about x)
    rot = rotation_matrix(tr.orientation[-1])
    roll = math.atan2(rot[2, 1], rot[2, 2])
    assert roll == pytest.approx(expected["phi"], rel=0.01)
    # the axles' load transfer: the outer (right) wheels carry more, front : rear as the roll
    # stiffnesses split it
    load = result.wheels("car").load[:, -1]
    assert (load[1] - load[0]) / 2.0 == pytest.approx(expected["df"], rel=0.01)
    assert (load[3] - load[2]) / 2.0 == pytest.approx(expected["dr"], rel=0.01)
    if e > 0.0:  # the split matters: the other split's closed form is more than 1.5 % away
        other = _steady_state(speed, delta, e, k_rear, k_front)
        assert abs(other["r"] / expected["r"] - 1.0) > 0.015


# -- stopping distances -------------------------------------------------------------------------

MAGIC = cs.Tyre("magic_formula", b=10.0, c=1.9, e=0.97)


def _stop(inputs: cs.DriverInputs, v: float = 20.0, **wheels) -> float:
    """The distance (m) the box car stops in from v (m/s) on the default ground (mu 0.8)."""
    scene = cs.Scene(ground=cs.Ground())
    scene.add(car(**wheels), (0.0, 0.0), velocity=(v, 0.0, 0.0), inputs=inputs)
    result = scene.run(until="rest", max_duration=120.0)
    rest = result.rest("car")
    assert rest is not None
    return float(rest.displacement)


@pytest.mark.parametrize("tyre", [None, MAGIC], ids=["linear", "magic_formula"])
@pytest.mark.parametrize(
    "brake, deceleration",
    [
        ("locked", MU * G),  # every wheel slides at mu Fz
        (0.5, 0.5 * MU * G),  # half the friction at every wheel
        (cs.Brake.deceleration(3.0), 3.0),  # the 3 m/s^2 (the MF gave 2.857)
        (cs.Brake.distributed(5.0, front_share=0.6), 5.0),  # fixed split, no wheel at its limit
    ],
    ids=["locked", "fraction", "deceleration", "distributed"],
)
def test_every_braking_input_stops_in_v_squared_over_two_a(brake, deceleration, tyre) -> None:
    # issue 19 item 6: the Magic Formula passed the brake force through its lateral curve
    # and under-delivered (2.857 m/s^2 for a demand of 3, 3.615 for half of 0.8 g); now every
    # input gives its deceleration on both laws. 1 %: the pitch and the tread's build-up at
    # the start (measured within 0.3 %).
    v = 20.0
    if brake == "locked":
        inputs = cs.DriverInputs(wheel_states=[("all", "locked", 0.0)])
    else:
        inputs = cs.DriverInputs(brake=brake)
    distance = _stop(inputs, v, tyre=tyre)
    assert distance == pytest.approx(v**2 / (2.0 * deceleration), rel=0.01)


def test_without_abs_the_front_wheels_lock_when_their_share_exceeds_their_friction() -> None:
    # 90 % of a 7 m/s^2 demand on the front axle asks it for 9.45 kN, more than its friction
    # can give, so without ABS the front wheels lock and slide at mu times their dynamic load,
    # m (g b + a h) / L, while the rear brake keeps its 10 %: the vehicle decelerates at
    # a = (mu g b / L + 0.1 x 7) / (1 - mu h / L). With ABS the front wheels brake at their
    # friction instead, rolling.
    v, demand, share = 20.0, 7.0, 0.9
    a = (MU * G * B / L + (1.0 - share) * demand) / (1.0 - MU * H / L)
    brake = cs.Brake.distributed(demand, front_share=share)
    locked = _stop(cs.DriverInputs(brake=brake), v, abs=False)
    assert locked == pytest.approx(v**2 / (2.0 * a), rel=0.01)
    scene = cs.Scene(ground=cs.Ground())
    inputs = cs.DriverInputs(brake=brake)
    scene.add(car(abs=False), (0.0, 0.0), velocity=(v, 0.0, 0.0), inputs=inputs)
    marks = scene.run(2.0).tyre_marks("car")
    assert marks["front_left"] and marks["front_right"]  # the locked fronts leave marks
    assert not marks["rear_left"] and not marks["rear_right"]


def test_rolling_resistance_coasts_to_a_stop_in_v_squared_over_two_f_g() -> None:
    # The default is 0 (the reconstruction programs' runs keep their speed); given, a free-
    # rolling car decelerates at f_r g.
    v, f = 10.0, 0.015
    distance = _stop(cs.DriverInputs(), v, tyre=cs.Tyre(rolling_resistance=f))
    assert distance == pytest.approx(v**2 / (2.0 * f * G), rel=0.01)


# -- what is linear between a steering table's points -------------------------------------------


def _ramp_run(interpolation: str | None) -> tuple[np.ndarray, np.ndarray]:
    """A 1 s steering-wheel ramp to 300 deg (left) at 10 m/s, outer-wheel reference, full
    Ackermann: the run's times and the two front wheels' recorded angles (rad)."""
    given = {} if interpolation is None else {"steering_interpolation": interpolation}
    v = car(steering_reference="outer", ackermann=1.0, steering_ratio=15.0, **given)
    ramp = [(0.2, 0.0), (1.2, math.radians(300.0))]
    scene = cs.Scene(ground=cs.Ground(friction=MU))
    scene.add(v, (0.0, 0.0), velocity=(10.0, 0.0, 0.0), inputs=cs.DriverInputs(steering_wheel=ramp))
    result = scene.run(1.5, dt=0.002)
    steer = result.wheel_steer("car")
    return result.wheels("car").t, steer[:2]


def test_wheels_linear_between_points_keep_the_ratio_of_the_ramps_end() -> None:
    """``steering_interpolation="wheels"`` moves each front wheel linearly between its
    Ackermann angles at the table's points (a reconstruction program's ramp): during the ramp
    the inner wheel keeps the end's ratio to the outer one, while the default linkage gives
    the geometric ratio of each instant (near 1 at small angles); at the points both agree."""
    t, by_wheel = _ramp_run("wheels")
    t_default, linkage = _ramp_run(None)
    assert np.array_equal(t, t_default)
    outer_end = math.radians(20.0)  # 300 deg over 15
    inner_end = math.atan(1.0 / (1.0 / math.tan(outer_end) - TRACK / L))  # cot o - cot i = t/L
    ramp = (t > 0.25) & (t < 1.15)
    # The left wheel is the inner one in a turn to the left.
    inner, outer = by_wheel[0], by_wheel[1]
    np.testing.assert_allclose(outer[ramp], outer_end * (t[ramp] - 0.2), rtol=0, atol=1e-12)
    np.testing.assert_allclose(inner[ramp] / outer[ramp], inner_end / outer_end, rtol=1e-10)
    # The default: the outer wheel the same, the inner at each instant's geometric angle.
    np.testing.assert_allclose(linkage[1][ramp], outer[ramp], rtol=0, atol=1e-12)
    geometric = np.arctan(1.0 / (1.0 / np.tan(outer[ramp]) - TRACK / L))
    np.testing.assert_allclose(linkage[0][ramp], geometric, rtol=1e-10)
    assert np.all(linkage[0][ramp] < inner[ramp])
    # Before and after the ramp the two are the same.
    still = (t < 0.2) | (t > 1.2)
    assert np.array_equal(by_wheel[:, still], linkage[:, still])
    end = by_wheel[:, t > 1.2]
    np.testing.assert_allclose(
        end, np.broadcast_to([[inner_end], [outer_end]], end.shape), atol=1e-12
    )


def test_an_unknown_steering_interpolation_is_refused_with_the_choices() -> None:
    with pytest.raises(cs.ParameterError, match="steering_interpolation.*'input'.*'wheels'"):
        car(steering_interpolation="spline")
    # The 15 mph reference example sets "wheels" (the reference program's steering ramp).
    from crashsim.io.scenefile import SceneFileError, loads_scene

    text = (EXAMPLES / "reference-sedan-steer-15mph.toml").read_text(encoding="utf-8")
    case = loads_scene(text)
    assert case.scene.vehicles[0].wheels.steering_interpolation == "wheels"
    with pytest.raises(SceneFileError, match="steering_interpolation"):
        loads_scene(
            text.replace('steering_interpolation = "wheels"', 'steering_interpolation = "spline"')
        )
