"""The same scene run twice gives the same bits: every trajectory array, every field of every
impact and the contact log (np.array_equal, no tolerance)."""

from __future__ import annotations

import dataclasses
import math
from pathlib import Path

import crashsim as cs
import numpy as np
import pytest
from conftest import MISSING, SHARED_MESHES


def assert_identical(r1: cs.Result, r2: cs.Result) -> None:
    assert r1.vehicles == r2.vehicles
    assert np.array_equal(r1.t, r2.t)
    for name in r1.vehicles:
        for a, b in zip(r1.trajectory(name), r2.trajectory(name), strict=True):
            assert a.dtype == b.dtype and np.array_equal(a, b)
    assert len(r1.impacts) == len(r2.impacts)
    for i1, i2 in zip(r1.impacts, r2.impacts, strict=True):
        for f in dataclasses.fields(cs.Impact):
            a, b = getattr(i1, f.name), getattr(i2, f.name)
            if isinstance(a, dict):
                assert a.keys() == b.keys(), f.name
                assert all(np.array_equal(a[k], b[k]) for k in a), f.name
            elif isinstance(a, np.ndarray):
                assert np.array_equal(a, b), f.name
            else:
                assert a == b, f.name
    assert r1.contacts == r2.contacts


def oblique_boxes() -> cs.Scene:
    """Three boxes: an oblique, eccentric 60 mph impact that sets both cars spinning, and a
    third car hit afterwards."""
    red = cs.Vehicle.box(4.5, 1.8, 1.4, mass=1450.0, name="red")
    blue = cs.Vehicle.box(4.6, 1.8, 1.45, mass=1500.0, name="blue", ground_clearance=0.02)
    green = cs.Vehicle.box(4.2, 1.7, 1.5, mass=1300.0, name="green")
    scene = cs.Scene(restitution=0.2, friction=0.4)
    a = cs.deg(40.0)
    speed = cs.mph(60.0)
    scene.add(red, position=(-4.0, -2.5, 0.7), heading=a,
              velocity=(speed * math.cos(a), speed * math.sin(a), 0.0),
              angular_velocity=(0.0, 0.0, 0.3))  # fmt: skip
    scene.add(blue, position=(0.0, 0.0, 0.745), heading=cs.deg(90.0))
    scene.add(green, position=(4.0, 2.5, 0.75), heading=cs.deg(10.0))
    return scene


def test_boxes_run_twice_give_the_same_bits() -> None:
    r1 = oblique_boxes().run(duration=0.5, dt=1e-3)
    r2 = oblique_boxes().run(duration=0.5, dt=1e-3)
    assert len(r1.impacts) >= 1
    assert_identical(r1, r2)
    # the same Scene object twice too (a fresh engine world per run)
    scene = oblique_boxes()
    assert_identical(scene.run(0.5, 1e-3), scene.run(0.5, 1e-3))


def test_real_meshes_run_twice_give_the_same_bits() -> None:
    sedan_path = SHARED_MESHES / "sedan_quaternius_normalcar1.ply"
    pickup_path = SHARED_MESHES / "pickup_gazebo.ply"
    if not (sedan_path.is_file() and pickup_path.is_file()):
        pytest.skip(MISSING)

    def scene(sedan_path: Path = sedan_path, pickup_path: Path = pickup_path) -> cs.Scene:
        sedan = cs.Vehicle.from_mesh(sedan_path, mass=1400.0, name="sedan")
        pickup = cs.Vehicle.from_mesh(pickup_path, mass=2200.0, name="pickup")
        s = cs.Scene()
        # the sedan square into the pickup's left side, 0.5 m off its CG
        s.add(sedan, position=(-4.0, 0.5, sedan.cg[2] + 0.005), velocity=(15.0, 0.0, 0.0))
        s.add(pickup, position=(0.0, 0.0, pickup.cg[2] + 0.005), heading=cs.deg(90.0))
        return s

    r1 = scene().run(duration=0.25, dt=1e-3)
    r2 = scene().run(duration=0.25, dt=1e-3)
    assert len(r1.impacts) >= 1
    assert_identical(r1, r2)
