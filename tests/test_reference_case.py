"""Reference case 2 of reference-cases.md: the IIHS small-overlap test CF11002 as modelled
with the planar impulse-momentum method of Carpenter et al. (SAE 2019-01-0422): a 2008 Ford
Fusion into a rigid barrier, a user-given impulse centroid and contact plane, restitution 0,
friction 0.82 (a full impact). Published: delta-V -15.972 m/s longitudinal, 3.397 m/s to the
right, yaw-rate change +176.43 deg/s (counter-clockwise), 231.06 kJ dissipated."""

from __future__ import annotations

import math

import crashsim as cs
import numpy as np
import pytest

MASS = 1621.2  # kg (3574.2 lb)
IZZ = 3167.5  # kg m^2 (2336.3 lb ft s^2)
SPEED = 17.8613  # m/s (39.9545 mph)
POINT = np.array([1.1037, 0.6118, 0.0])  # m from the CG, ISO body frame (+y left)
NORMAL_ANGLE = cs.deg(15.4)  # left of the vehicle's x axis
FRICTION = 0.82
BARRIER_MASS = cs.lb(1e7)  # kg

PUBLISHED = {
    "longitudinal": -15.972,  # m/s (-35.7275 mph)
    "lateral_iso_y": -3.397,  # m/s: 3.397 to the RIGHT (+7.5998 mph SAE)
    "yaw_rate_deg_s": 176.43,  # CCW seen from above (SAE -176.43)
    "energy": 231.06e3,  # J (170,421.5 ft lb)
}


def closed_form(barrier_mass: float) -> dict[str, float]:
    """The planar full impact in the vehicle frame: J = K^-1 u on the barrier (-J on the
    car), with K = (1/m + 1/M) E + [[ry^2, -rx ry], [-rx ry, rx^2]] / Izz (the barrier's
    rotation neglected), u = (v, 0), restitution 0; energy lost = u.J / 2."""
    rx, ry = POINT[:2]
    k = (1.0 / MASS + 1.0 / barrier_mass) * np.eye(2)
    k += np.array([[ry * ry, -rx * ry], [-rx * ry, rx * rx]]) / IZZ
    u = np.array([SPEED, 0.0])
    j = np.linalg.solve(k, u)
    n = np.array([math.cos(NORMAL_ANGLE), math.sin(NORMAL_ANGLE)])
    t = np.array([-n[1], n[0]])
    return {
        "longitudinal": -j[0] / MASS,
        "lateral_iso_y": -j[1] / MASS,
        "yaw_rate_deg_s": math.degrees((rx * -j[1] - ry * -j[0]) / IZZ),
        "energy": 0.5 * float(u @ j),
        "impulse_ratio": abs(float(j @ t)) / float(j @ n),
    }


@pytest.fixture(scope="module")
def impact_and_result() -> tuple[cs.Impact, cs.Result]:
    # a Fusion-sized box; only Izz matters (the centroid is at CG height), Ixx and Iyy are
    # plausible values for a mid-size sedan
    car = cs.Vehicle.box(
        4.8, 1.8, 1.45, mass=MASS, name="fusion", ground_clearance=0.15,
        inertia=np.diag([600.0, 2900.0, IZZ]),
    )  # fmt: skip
    barrier = cs.Vehicle.box(
        1.0, 6.0, 2.0, mass=BARRIER_MASS, name="barrier", inertia=np.eye(3) * 1e12
    )
    scene = cs.Scene()
    scene.add(car, position=(0.0, 0.0, car.cg[2]), heading=0.0, velocity=(SPEED, 0.0, 0.0))
    # the barrier's face 2 cm ahead of the car's front (2.4 m ahead of its CG): contact
    # after about 1 ms
    scene.add(barrier, position=(2.42 + 0.5, 0.0, barrier.cg[2]))
    scene.contact(
        car,
        barrier,
        restitution=0.0,
        friction=FRICTION,
        centroid=(car, POINT),
        normal=(math.cos(NORMAL_ANGLE), math.sin(NORMAL_ANGLE), 0.0),
    )
    result = scene.run(duration=0.05, dt=1e-3)
    return result.impacts[0], result


def test_the_closed_form_reproduces_the_published_figures() -> None:
    immovable = closed_form(math.inf)
    heavy = closed_form(BARRIER_MASS)
    for key, published in PUBLISHED.items():
        # the spreadsheet's own rounding (g = 32.2 ft/s^2, 1.46667 ft/s per mph): ~0.1 %
        assert heavy[key] == pytest.approx(published, rel=2e-3), key
        assert immovable[key] == pytest.approx(published, rel=2e-3), key
    assert heavy["impulse_ratio"] == pytest.approx(0.06, abs=0.005)  # below 0.82: full


def test_the_engine_matches_the_published_figures(impact_and_result) -> None:
    imp, result = impact_and_result
    assert imp.vehicles == ("fusion", "barrier")
    assert not imp.sliding
    assert 0.0 < imp.first_contact_time < 0.002
    dv = result.delta_v_body(imp, "fusion")  # ISO body frame; the car still heads along +x
    assert dv[0] == pytest.approx(PUBLISHED["longitudinal"], rel=2e-3)
    assert dv[1] == pytest.approx(PUBLISHED["lateral_iso_y"], rel=2e-3)
    yaw_rate = math.degrees(imp.delta_omega["fusion"][2])
    assert yaw_rate == pytest.approx(PUBLISHED["yaw_rate_deg_s"], rel=2e-3)
    assert imp.energy_dissipated == pytest.approx(PUBLISHED["energy"], rel=2e-3)


def test_the_engine_matches_the_closed_form(impact_and_result) -> None:
    imp, result = impact_and_result
    expected = closed_form(BARRIER_MASS)
    # 1e-8: the closed form neglects the barrier's rotation (r^2 / 1e12 kg m^2 against
    # 1 / 1621 kg: about 2e-9 relative)
    dv = result.delta_v_body(imp, "fusion")
    assert dv[0] == pytest.approx(expected["longitudinal"], rel=1e-8)
    assert dv[1] == pytest.approx(expected["lateral_iso_y"], rel=1e-8)
    assert abs(dv[2]) < 1e-8 * SPEED
    yaw_rate = math.degrees(imp.delta_omega["fusion"][2])
    assert yaw_rate == pytest.approx(expected["yaw_rate_deg_s"], rel=1e-8)
    assert imp.energy_dissipated == pytest.approx(expected["energy"], rel=1e-8)
    # the user's centroid, carried by the car to the exchange, and the user's normal
    car = result.state_at("fusion", imp.time)["position"]
    assert np.allclose(imp.centroid, car + POINT, rtol=0, atol=1e-12)
    assert np.allclose(imp.normal, [math.cos(NORMAL_ANGLE), math.sin(NORMAL_ANGLE), 0.0])
    # restitution 0, full impact: the relative velocity at the centroid ends at zero
    assert np.linalg.norm(imp.relative_velocity_after) < 1e-9 * SPEED
