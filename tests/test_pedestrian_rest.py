"""A pedestrian lying on the road comes to rest and gains no energy (issue 22; docs/human.md,
"Rest of a lying body"; docs/joints.md, "Limits").

The standing fall alone (1.75 m, 75 kg, no push, road friction 0.8, 1 ms steps) is
``scripts/pedestrian_rest.py``'s first run. Before the joint limits' velocity projection took
the limits left on their bound (and the resting limit's row its J' nu), a lying foot and shank
slid faster and faster from 12.4 s on and the run never passed the rest test in 20 s; the
segments' energy rose by up to 5.3 J after 1 s and by 2.2 J after 5 s.
"""

from __future__ import annotations

import warnings

import crashsim as cs
import numpy as np
from crashsim.human.pedestrian import ROAD_FRICTION
from crashsim.records import rotation_matrix

GRAVITY = 9.80665  # m/s^2, the engine's (vehicle/wheel.rs)


def segment_energy(result: cs.Result, ped: cs.Pedestrian) -> tuple[np.ndarray, np.ndarray]:
    """Sample times (s) and the segments' kinetic plus gravitational energy (J) summed: the
    contact springs' energy, at most a few tenths of a joule for a lying body, is left out."""
    total = None
    for seg in ped.segments:
        tr = result.trajectory(seg.name)
        w_body = np.einsum("kji,kj->ki", rotation_matrix(tr.orientation), tr.angular_velocity)
        e = (
            0.5 * seg.mass * (tr.velocity**2).sum(axis=1)
            + 0.5 * np.einsum("ki,ij,kj->k", w_body, np.asarray(seg.inertia), w_body)
            + seg.mass * GRAVITY * tr.position[:, 2]
        )
        total = e if total is None else total + e
        t = tr.t
    assert total is not None
    return t, total


def standing_fall(passive_moments: float, road_friction: float = ROAD_FRICTION
                  ) -> tuple[cs.Scene, np.ndarray, np.ndarray]:  # fmt: skip
    """A standing man (no push) falls on a road of friction 0.8 (his segments sliding on it
    at ``road_friction``) and lies there until the engine's rest test passes (a
    RestNotReachedWarning fails the test; 1 ms steps, at most 25 s): the scene, and the
    sample times (s) and segment energy (J) of segment_energy."""
    ped = cs.Pedestrian(pose="standing", passive_moments=passive_moments,
                        road_friction=road_friction)
    scene = cs.Scene(ground=cs.Ground(friction=0.8), depth_of_penetration=0.0)
    scene.add(ped, (0.0, 0.0), heading=0.0, velocity=(0.0, 0.0, 0.0))
    with warnings.catch_warnings():
        warnings.simplefilter("error", cs.RestNotReachedWarning)
        result = scene.run(until="rest", max_duration=25.0, dt=1e-3, record_interval=0.01)
    t, energy = segment_energy(result, ped)
    return scene, t, energy


def largest_rise(t: np.ndarray, energy: np.ndarray, after: float) -> float:
    """The most the energy (J) rises over its lowest so far from ``after`` (s) on."""
    late = energy[t >= after]
    return float(np.max(late - np.minimum.accumulate(late)))


def test_the_standing_fall_alone_comes_to_rest_and_gains_no_energy() -> None:
    # Without the leg's passive moments and with the segments sliding at the ground's body
    # friction 0.45 (the model before 2026-11-29, the same bits): the limits and the contacts
    # alone hold the lying body, which is what this test checks. (At the person's 0.66 it
    # rests at 21.57 s: the arm propped on the hand topples over more slowly still.)
    scene, t, energy = standing_fall(0.0, road_friction=0.45)
    assert not any(j.passive for j in scene.joints)
    # Measured: at rest at 18.50 s (scripts/pedestrian_rest.py); 10.20 s before the segments
    # had static friction: the right hand now holds where it slid, and the arm propped on it
    # topples over slowly (its energy falls 1.6 J from 3 s to 18 s, never rising).
    assert t[-1] < 20.0, f"came to rest only at {t[-1]:.2f} s"
    # Lying from about 3 s on: the energy only falls but for the contact springs' exchange
    # (measured: at most 0.9 mJ over its lowest so far from 4 s on; 2.2 J before the fix).
    rise = largest_rise(t, energy, 4.0)
    assert rise < 0.01, f"the lying body gained {rise:.4f} J"


def test_the_legs_passive_moments_bring_the_fall_to_rest_sooner() -> None:
    # The same fall with the pedestrian as Scene.add makes it, the leg's joints carrying
    # Riener and Edrich's passive moments: measured at rest at 2.71 s (18.50 s without) at
    # road friction 0.45; its
    # segments' energy then rises by at most 0.022 J over its lowest so far from 2 s on (the
    # moments' stored elastic energy is not counted in it).
    # Measured at the ground's body friction 0.45 (the segments' before 2026-11-29).
    scene, t, energy = standing_fall(1.0, road_friction=0.45)
    assert sum(1 for j in scene.joints if j.passive) == 6
    assert t[-1] < 4.0, f"came to rest only at {t[-1]:.2f} s"
    rise = largest_rise(t, energy, 2.0)
    assert rise < 0.05, f"the lying body gained {rise:.4f} J"
    # At the person's own 0.66 (the default): measured at rest at 2.81 s, the segments'
    # energy rising by at most 0.135 J over its lowest so far from 2 s on (at 2.16-2.30 s,
    # while the body still settles; 0.053 J from 2.3 s on): the static friction's springs and
    # the passive moments hold more, and what they store is not counted in it.
    scene, t, energy = standing_fall(1.0)
    assert t[-1] < 4.0, f"came to rest only at {t[-1]:.2f} s"
    rise = largest_rise(t, energy, 2.0)
    assert rise < 0.2, f"the lying body gained {rise:.4f} J"


def test_a_shoulder_flung_past_its_twist_range_does_not_blow_up() -> None:
    """A study's variant that stalled (docs/studies.md: the Monte Carlo's variant 63): a
    1.62 m walking man struck at 40 km/h (benches/pedestrian_studies.py's scene) lands at
    1.2866 s with his left arm flung to a swing of 179.99 deg at the shoulder, its twist past
    its bound. The twist limit's row, 1e5 times a unit one there, threw every segment to
    1e8 m/s in one Runge-Kutta step, and the first-contact search then crawled on for hours.
    Now the twist is not held past a swing of 150 deg (docs/joints.md, "Limits"): the run to
    1.4 s ends in seconds with every segment slower than 15 m/s from 1 s on. Since the leg's
    joints carry passive moments (2026-11-29) the variant no longer lands that way; its
    shoulders still swing past 150 deg (measured: the left 160.6 deg at 0.672 s, the right
    168.1 deg at 0.703 s), where the twist is let go, and the test asserts that they do."""
    import time

    car = cs.Vehicle.generate("sedan", name="car")
    person = cs.Pedestrian(height=1.75, mass=75.0, sex="male", pose="walking")
    scene = cs.Scene(ground=cs.Ground(friction=0.8))
    ahead = float(car.mesh.bounds[1, 0] - car.cg[0])
    scene.add(car, (0.0, 0.0), heading=0.0, velocity=(cs.kmh(40.0), 0.0, 0.0),
              inputs=cs.DriverInputs(brake=[(0.0, 1.0), (30.0, 1.0)]))  # fmt: skip
    left = float(person.vertices()[:, 1].max())
    scene.add(person, (ahead + 0.05 + left, 0.0), heading=np.pi / 2)
    for seg in person.segments:
        scene.contact(car, seg, depth_of_penetration=0.0, restitution=0.1, friction=0.3,
                      normal="volume")  # fmt: skip
    scene.soft_contact(car, person, stiffness=1e5, damping_ratio=0.5)
    variant = scene.with_({"ground.body_friction": 0.6299773458771732,
                           "pedestrian.pose": 1.0, "pedestrian.height": 1.6187641634677832})
    began = time.monotonic()

    def guard(t: float) -> None:  # fails in a minute rather than hanging for hours
        assert time.monotonic() - began < 60.0, f"stalled at t = {t:.5f} s"

    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        result = variant.run(1.4, dt=2e-4, record_interval=2e-3, progress=guard)
    # From 1 s on (flight, landing): measured at most 12.0 m/s (the left hand as the body
    # lands); 1e8 m/s in the blown-up step.
    fastest = 0.0
    for seg in variant.pedestrians["pedestrian"].segments:
        tr = result.trajectory(seg.name)
        speed = np.linalg.norm(tr.velocity[tr.t >= 1.0], axis=1)
        fastest = max(fastest, float(speed.max()))
    assert fastest < 15.0, f"a segment reached {fastest:.3g} m/s"
    swing = max(float(np.max(result.joints[f"pedestrian/shoulder_{side}"].angle("swing")))
                for side in ("left", "right"))  # fmt: skip
    assert swing > np.radians(150.0), f"the shoulders swung {np.degrees(swing):.1f} deg at most"
