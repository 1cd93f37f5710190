"""python-fcl, an independent collision library, agrees with every first-overlap instant the
engine reports: no collision 1 ms before impacts[0].first_contact_time, a collision 1 ms after.

Each shared real mesh meets a box in APPROACHES_VS_BOX random approaches and every pair of
real meshes meets in APPROACHES_VS_MESH (seeded, so the cases are the same on every run).
Motion is pure translation at constant velocity, so the pose at time t is the initial pose
moved by velocity * t, orientation fixed; the exchange at t0 + 30 ms is after the bracket.
Vehicles start about START_GAP apart along the approach, so runs are short (at most 0.24 s).
"""

from __future__ import annotations

import math
import zlib
from pathlib import Path
from typing import Any

import crashsim as cs
import numpy as np
import pytest
from conftest import mesh_mass

fcl = pytest.importorskip("fcl", reason="python-fcl is not installed (pip install python-fcl)")

APPROACHES_VS_BOX = 50  # per real mesh: 300 against the box in all
APPROACHES_VS_MESH = 50  # per pair of real meshes: 750 mesh-mesh approaches in all
BRACKET = 1e-3  # s either side of the engine's first-overlap instant
MIN_CONTACT_SHARE = 0.7  # of the approaches must make contact (the rest are near misses)
START_GAP = 1.0  # m of travel along the approach direction before the meshes touch
SWEEP_STEP = 0.02  # m, resolution of the placement sweep (placement only, not the check)


def fcl_object(vehicle: cs.Vehicle) -> Any:  # an fcl.CollisionObject
    """The vehicle's body-frame mesh (m, origin at the CG) as an fcl BVH model."""
    model = fcl.BVHModel()
    vertices = np.ascontiguousarray(vehicle.body_vertices, dtype=np.float64)
    faces = np.ascontiguousarray(vehicle.mesh.faces, dtype=np.int64)
    model.beginModel(len(vertices), len(faces))
    model.addSubModel(vertices, faces)
    model.endModel()
    return fcl.CollisionObject(model, fcl.Transform())


def yaw(h: float) -> np.ndarray:
    """Rotation about world z by h rad (body -> world)."""
    c, s = math.cos(h), math.sin(h)
    return np.array([[c, -s, 0.0], [s, c, 0.0], [0.0, 0.0, 1.0]])


def collide(objs: list[Any], rotations: list[np.ndarray], positions: list[np.ndarray]) -> bool:
    for obj, r, p in zip(objs, rotations, positions, strict=True):
        obj.setTransform(fcl.Transform(r, np.asarray(p, dtype=np.float64)))
    return fcl.collide(objs[0], objs[1], fcl.CollisionRequest(), fcl.CollisionResult()) > 0


def horizontal_radius(v: cs.Vehicle) -> float:
    return float(np.max(np.linalg.norm(v.body_vertices[:, :2], axis=1)))


def approach(a: cs.Vehicle, b: cs.Vehicle, objs: list[Any], rng: np.random.Generator) -> bool:
    """One random approach: returns False when the meshes miss each other, else checks the
    engine's first overlap against fcl (asserting) and returns True."""
    ha, hb, theta = rng.uniform(0.0, 2.0 * math.pi, 3)
    closing = rng.uniform(5.0, 30.0)  # m/s
    share = rng.uniform(0.0, 1.0)  # of the closing speed carried by a
    ra, rb = horizontal_radius(a), horizontal_radius(b)
    lateral = rng.uniform(-0.6, 0.6) * min(ra, rb)
    d = np.array([math.cos(theta), math.sin(theta), 0.0])
    side = np.array([-d[1], d[0], 0.0])
    # A few mm off the ground: coplanar bottom faces only touch, and a touch is not an overlap.
    pa = np.array([0.0, 0.0, a.cg[2] + rng.uniform(0.001, 0.01)])
    far = pa + d * (ra + rb + 0.5) + side * lateral
    far[2] = b.cg[2] + rng.uniform(0.001, 0.01)
    rot = [yaw(ha), yaw(hb)]
    # Placement: slide b towards a until fcl sees a collision, then back off START_GAP.
    hits = [
        s
        for s in np.arange(0.0, ra + rb + 0.5, SWEEP_STEP)
        if collide(objs, rot, [pa, far - d * s])
    ]
    if not hits:
        return False
    pb = far - d * max(hits[0] - START_GAP, 0.0)
    va, vb = d * closing * share, -d * closing * (1.0 - share)
    scene = cs.Scene(depth_of_penetration=0.030)
    scene.add(a, position=pa, heading=ha, velocity=va)
    scene.add(b, position=pb, heading=hb, velocity=vb)
    # b's first collision in the sweep came within START_GAP of travel: the first overlap is
    # by START_GAP / closing; stop one step after that (the timer and the exchange that
    # follow are not checked here).
    result = scene.run(duration=START_GAP / closing + 1e-3, dt=1e-3)
    if not result.contacts:
        return False
    assert result.contacts[0].kind == "first_overlap"
    t0 = result.contacts[0].time
    case = (a.name, b.name, float(ha), float(hb), float(theta), float(closing), float(t0))
    before = [pa + va * (t0 - BRACKET), pb + vb * (t0 - BRACKET)]
    after = [pa + va * (t0 + BRACKET), pb + vb * (t0 + BRACKET)]
    assert not collide(objs, rot, before), ("fcl collides 1 ms before the first overlap", case)
    assert collide(objs, rot, after), ("fcl sees no collision 1 ms after the first overlap", case)
    return True


def run_approaches(a: cs.Vehicle, b: cs.Vehicle, n: int) -> None:
    rng = np.random.default_rng(zlib.crc32(f"{a.name}|{b.name}".encode()))
    objs = [fcl_object(a), fcl_object(b)]
    made = sum(approach(a, b, objs, rng) for _ in range(n))
    assert made >= MIN_CONTACT_SHARE * n, f"only {made} of {n} approaches made contact"


def vehicle(path: Path) -> cs.Vehicle:
    return cs.Vehicle.from_mesh(path, mass=mesh_mass(path), name=path.stem)


def test_fcl_agrees_on_first_overlap_of_a_real_mesh_and_a_box(mesh_path: Path) -> None:
    box = cs.Vehicle.box(4.5, 1.8, 1.4, mass=1500.0, name="box")
    run_approaches(vehicle(mesh_path), box, APPROACHES_VS_BOX)


def test_fcl_agrees_on_first_overlap_of_two_real_meshes(mesh_pair: tuple[Path, Path]) -> None:
    run_approaches(vehicle(mesh_pair[0]), vehicle(mesh_pair[1]), APPROACHES_VS_MESH)
