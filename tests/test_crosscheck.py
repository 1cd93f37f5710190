"""crashsim.analysis.crosscheck: the user-facing python-fcl cross-check of a run's contacts.

What is shown here:
- the seed's box scenes and random approaches of the shared real meshes (each against a box
  and each pair, with spin, several depths of penetration including 0 and 0.5 ms, shorter than
  the 1 ms bracket) pass every first-overlap bracket and every overlap-region check, and the
  engine's overlap box holds FCL's crossing points to round-off (ROUND_OFF), far inside the
  default tolerance;
- box runs with secondary exchanges, separations and second first overlaps pass as well;
- tampered results (a first-overlap instant moved 10 ms either way, the region box moved or
  shrunk) FAIL: the check can fail;
- a 1 cm cube wholly inside a box after 1 ms is "not checkable", not a disagreement;
- the crossing points (computed in numpy from the triangle pairs FCL reports) are right on a
  closed form, and agree with FCL's own triangle test on random triangle pairs.

Runs use dt = 10 ms; each real-mesh run stops 15 ms after its exchange (the first contact
time comes from an FCL sweep of the free motion, so the run length is known in advance).
"""

from __future__ import annotations

import dataclasses
import json
import math
import zlib
from typing import Any

import crashsim as cs
import numpy as np
import pytest
import trimesh
from conftest import mesh_mass, seed_side_impact
from crashsim import _core
from crashsim.analysis import crosscheck
from crashsim.analysis.crosscheck import CrossCheck, cross_check, crossing_points
from crashsim.result import rotation_matrix

fcl = pytest.importorskip("fcl", reason="python-fcl is not installed (pip install python-fcl)")

DT = 0.01  # s, the run's step (the engine resolves first overlaps to 1e-9 s whatever dt)
APPROACHES_VS_BOX = 5  # per shared mesh: 30 against the box
APPROACHES_VS_MESH = 2  # per pair of shared meshes: 30 mesh-mesh approaches
# Depths of penetration cycled through the approaches: the default, one shorter than the
# 1 ms bracket and zero (the exchange at the first overlap itself).
DEPTHS = (0.030, 0.0005, 0.0)
SWEEP_STEP = 0.002  # s, the FCL sweep that finds when the meshes first collide
GAP = 0.3  # m between the two vehicles' bounding circles (about the CG) at the start
# The engine's overlap box must hold every FCL crossing point to round-off: both compute the
# same segments from the same poses (measured worst 4.7e-14 m on these runs).
ROUND_OFF = 1e-9  # m

DEPTH_OF_PENETRATION = 0.030  # s, the seed's


# -- helpers ---------------------------------------------------------------------------------


def fcl_model(vehicle: cs.Vehicle) -> Any:
    """The vehicle's engine mesh (body frame, m) as an fcl BVH model (independent of the
    module under test)."""
    model = fcl.BVHModel()
    vertices = np.ascontiguousarray(vehicle.shape.vertices, dtype=np.float64)
    faces = np.ascontiguousarray(vehicle.shape.triangles, dtype=np.int64)
    model.beginModel(len(vertices), len(faces))
    model.addSubModel(vertices, faces)
    model.endModel()
    return model


def heading_quaternion(h: float) -> np.ndarray:
    return np.array([math.cos(h / 2.0), 0.0, 0.0, math.sin(h / 2.0)])


def horizontal_radius(v: cs.Vehicle) -> float:
    return float(np.max(np.linalg.norm(v.body_vertices[:, :2], axis=1)))


def first_fcl_hit(vehicles: tuple[cs.Vehicle, cs.Vehicle], states: list[tuple], t_max: float):
    """The first multiple of SWEEP_STEP (s) at which FCL finds the freely moving meshes
    colliding, or None before t_max."""
    objs = [fcl.CollisionObject(fcl_model(v), fcl.Transform()) for v in vehicles]
    for t in np.arange(0.0, t_max, SWEEP_STEP):
        for obj, v, s in zip(objs, vehicles, states, strict=True):
            p, q, _, _ = _core.free_motion(v.mass, v.inertia, *s, float(t))
            obj.setTransform(fcl.Transform(rotation_matrix(q), np.asarray(p)))
        if fcl.collide(objs[0], objs[1], fcl.CollisionRequest(), fcl.CollisionResult()):
            return float(t)
    return None


def approach(a: cs.Vehicle, b: cs.Vehicle, rng: np.random.Generator, depth: float):
    """One random approach of b towards a (headings, direction, lateral offset, closing speed
    5-30 m/s, yaw rates up to 2 rad/s, roll and pitch rates up to 0.3 rad/s): (result, time of
    FCL's first sampled collision), or None when the meshes miss."""
    ha, hb, theta = rng.uniform(0.0, 2.0 * math.pi, 3)
    closing = rng.uniform(5.0, 30.0)  # m/s
    share = rng.uniform(0.0, 1.0)  # of the closing speed carried by a
    ra, rb = horizontal_radius(a), horizontal_radius(b)
    lateral = rng.uniform(-0.6, 0.6) * min(ra, rb)
    d = np.array([math.cos(theta), math.sin(theta), 0.0])
    side = np.array([-d[1], d[0], 0.0])
    pa = np.array([0.0, 0.0, a.cg[2] + rng.uniform(0.001, 0.01)])
    pb = pa + d * (ra + rb + GAP) + side * lateral
    pb[2] = b.cg[2] + rng.uniform(0.001, 0.01)
    spin = [np.array([*rng.uniform(-0.3, 0.3, 2), rng.uniform(-2.0, 2.0)]) for _ in range(2)]
    states = [
        (pa, heading_quaternion(ha), d * closing * share, spin[0]),
        (pb, heading_quaternion(hb), -d * closing * (1.0 - share), spin[1]),
    ]
    hit = first_fcl_hit((a, b), states, (ra + rb + GAP) / closing)
    if hit is None:
        return None
    scene = cs.Scene(depth_of_penetration=depth)
    for v, (p, q, vel, w) in zip((a, b), states, strict=True):
        scene.add(v, position=p, orientation=q, velocity=vel, angular_velocity=w)
    return scene.run(duration=hit + depth + 0.015, dt=DT), hit


def assert_all_pass(cc: CrossCheck, case: Any) -> None:
    assert cc.ok, (case, str(cc))
    assert all(c.status == "pass" for c in cc.checks), (case, str(cc))
    assert cc.worst_outside <= ROUND_OFF, (case, cc.worst_outside)


def run_approaches(a: cs.Vehicle, b: cs.Vehicle, n: int) -> None:
    rng = np.random.default_rng(zlib.crc32(f"crosscheck|{a.name}|{b.name}".encode()))
    made = 0
    for k in range(n):
        depth = DEPTHS[k % len(DEPTHS)]
        out = approach(a, b, rng, depth)
        if out is None:
            continue
        result, hit = out
        made += 1
        cc = cross_check(result)
        case = (a.name, b.name, k, depth)
        # FCL saw a collision at `hit`: the engine's first overlap is at or before it, and
        # its exchange (hit + depth at the latest) is inside the run
        first = [c for c in cc.checks if c.kind == "first_overlap"]
        regions = [c for c in cc.checks if c.kind == "region"]
        assert first and regions, (case, str(cc))
        assert first[0].time <= hit + 1e-9, (case, first[0].time, hit)
        assert all(c.pairs and c.points for c in regions), (case, str(cc))
        assert_all_pass(cc, case)
    assert made >= 0.7 * n, f"only {made} of {n} approaches made contact"


SEED_CASES = {
    "30 mph at 90 deg": (cs.mph(30.0), 0.0, (-3.65, 0.3)),
    "60 mph at 45 deg": (cs.mph(60.0), cs.deg(45.0), (-4.0, -3.0)),
}


@pytest.fixture
def seed_result() -> cs.Result:
    return seed_side_impact(*SEED_CASES["30 mph at 90 deg"], dt=DT, duration=0.1)


# -- acceptance ------------------------------------------------------------------------------


@pytest.mark.parametrize("dt", [1e-3, 7e-3, DT], ids=["dt=1ms", "dt=7ms", "dt=10ms"])
@pytest.mark.parametrize("case", list(SEED_CASES))
def test_seed_box_scenes_pass(case: str, dt: float) -> None:
    result = seed_side_impact(*SEED_CASES[case], dt=dt, duration=0.1)
    cc = cross_check(result)
    assert [c.kind for c in cc.checks] == ["first_overlap", "region"]
    assert_all_pass(cc, case)
    first, region = cc.checks
    imp = result.impacts[0]
    assert first.time == imp.first_contact_time and region.time == imp.time
    assert first.before_pairs == 0 and first.after_pairs > 0
    assert first.after_time - first.time == pytest.approx(1e-3, abs=1e-12)
    assert first.time - first.before_time == pytest.approx(1e-3, abs=1e-12)


def test_real_mesh_against_a_box(mesh_path) -> None:
    box = cs.Vehicle.box(4.5, 1.8, 1.4, mass=1500.0, name="box")
    mesh = cs.Vehicle.from_mesh(mesh_path, mass=mesh_mass(mesh_path), name=mesh_path.stem)
    run_approaches(mesh, box, APPROACHES_VS_BOX)


def test_two_real_meshes(mesh_pair) -> None:
    a, b = (cs.Vehicle.from_mesh(p, mass=mesh_mass(p), name=p.stem) for p in mesh_pair)
    run_approaches(a, b, APPROACHES_VS_MESH)


def test_box_runs_with_secondary_exchanges_and_new_first_overlaps() -> None:
    rng = np.random.default_rng(3)  # a seed whose runs hold secondary exchanges
    a = cs.Vehicle.box(4.5, 1.8, 1.4, mass=1450.0, name="a")
    b = cs.Vehicle.box(4.2, 1.7, 1.5, mass=1200.0, name="b")
    kinds: dict[str, int] = {}
    secondary = 0
    for k in range(12):
        scene = cs.Scene(
            depth_of_penetration=0.030,
            restitution=rng.uniform(0.0, 0.3),
            friction=rng.uniform(0.2, 0.8),
        )
        scene.add(
            a,
            position=(0.0, 0.0, 0.7 + rng.uniform(0.0, 0.02)),
            heading=rng.uniform(0.0, 2.0 * math.pi),
            velocity=(rng.uniform(10.0, 20.0), 0.0, 0.0),
            angular_velocity=(0.0, 0.0, rng.uniform(-1.0, 1.0)),
        )
        scene.add(
            b,
            position=(6.0, rng.uniform(-1.5, 1.5), 0.75 + rng.uniform(0.0, 0.02)),
            heading=rng.uniform(0.0, 2.0 * math.pi),
            velocity=(rng.uniform(-5.0, 0.0), rng.uniform(-3.0, 3.0), 0.0),
            angular_velocity=(0.0, 0.0, rng.uniform(-1.0, 1.0)),
        )
        result = scene.run(duration=0.6, dt=DT)
        for c in result.contacts:
            kinds[c.kind] = kinds.get(c.kind, 0) + 1
        secondary += sum(i.secondary for i in result.impacts)
        cc = cross_check(result)
        n_first = sum(c.kind == "first_overlap" for c in result.contacts)
        assert sum(c.kind == "first_overlap" for c in cc.checks) == n_first
        assert sum(c.kind == "region" for c in cc.checks) == len(result.impacts)
        assert_all_pass(cc, k)
    # the runs exercise what follows a first exchange, not only first contacts
    assert secondary > 0 and kinds.get("closing_again", 0) > 0
    assert kinds.get("separation", 0) > 0 and kinds["first_overlap"] > 12


# -- the check can fail ----------------------------------------------------------------------


@pytest.mark.parametrize("shift", [0.010, -0.010], ids=["10ms-late", "10ms-early"])
def test_a_moved_first_overlap_fails(seed_result: cs.Result, shift: float) -> None:
    r = seed_result
    r.contacts[0] = dataclasses.replace(r.contacts[0], time=r.contacts[0].time + shift)
    imp = r.impacts[0]
    r.impacts[0] = dataclasses.replace(imp, first_contact_time=imp.first_contact_time + shift)
    cc = cross_check(r)
    assert not cc.ok
    (bad,) = cc.failures
    assert bad.kind == "first_overlap"
    if shift > 0:  # FCL already collides 9 ms after the true instant
        assert bad.before_pairs > 0
    else:  # and not yet 9 ms before it
        assert bad.after_pairs == 0


def test_a_moved_log_entry_alone_fails(seed_result: cs.Result) -> None:
    r = seed_result
    r.contacts[0] = dataclasses.replace(r.contacts[0], time=r.contacts[0].time - 0.010)
    cc = cross_check(r)
    assert [c.status for c in cc.checks if c.kind == "first_overlap"] == ["fail", "pass"]


@pytest.mark.parametrize("axis", [0, 1, 2], ids=["n", "t", "b"])
def test_a_moved_region_box_fails(seed_result: cs.Result, axis: int) -> None:
    r = seed_result
    imp = r.impacts[0]
    move = np.zeros(3)
    move[axis] = 0.05  # m along one contact-frame axis
    r.impacts[0] = dataclasses.replace(
        imp, region_min=imp.region_min + move, region_max=imp.region_max + move
    )
    cc = cross_check(r)
    (bad,) = cc.failures
    assert bad.kind == "region"
    # the box's low face moved 5 cm past points that were on it
    assert bad.worst_outside == pytest.approx(0.05, abs=1e-9)


def test_a_box_shrunk_beyond_the_tolerance_fails_and_within_it_passes(
    seed_result: cs.Result,
) -> None:
    r = seed_result
    imp = r.impacts[0]
    tol = crosscheck.ABS_TOL + crosscheck.REL_TOL * float(
        np.linalg.norm(imp.region_max - imp.region_min)
    )
    for shrink, ok in ((0.9 * tol, True), (1.1 * tol, False)):
        # the box's upper side along t pulled in: crossing points on it end up `shrink` out
        r.impacts[0] = dataclasses.replace(imp, region_max=imp.region_max - [0.0, shrink, 0.0])
        cc = cross_check(r)
        assert cc.ok is ok, (shrink, str(cc))
        assert cc.worst_outside == pytest.approx(shrink, rel=1e-9)


# -- not checkable ---------------------------------------------------------------------------


def test_a_mesh_wholly_inside_is_not_checkable() -> None:
    # a 1 cm cube at 30 m/s is wholly inside the box 1 ms after touching it: FCL (surfaces
    # only) sees nothing, the engine sees the cube inside. With delta = 0.1 ms (3 mm of
    # travel) the surfaces still cross and the bracket is checked.
    big = cs.Vehicle.box(4.5, 1.8, 1.4, mass=1500.0, name="big")
    cube = cs.Vehicle.box(0.01, 0.01, 0.01, mass=1.0, name="cube")
    scene = cs.Scene(depth_of_penetration=0.010)
    scene.add(big, position=(0.0, 0.0, 0.7))
    scene.add(cube, position=(2.5, 0.1, 0.7), velocity=(-30.0, 0.0, 0.0))
    # 2 cm after touching, the cube is wholly inside: its vector area has vanished, so the
    # engine reads the contact normal shallower and says so (docs/glancing.md).
    with pytest.warns(cs.DepthOfPenetrationWarning, match="vector area had collapsed"):
        result = scene.run(duration=0.03, dt=DT)
    cc = cross_check(result)
    assert cc.ok and not cc.failures
    assert [(c.kind, c.status) for c in cc.checks] == [
        ("first_overlap", "not checkable"),
        ("region", "not checkable"),
    ]
    assert cc.checks[0].after_pairs == 0 and cc.checks[1].pairs == 0
    fine = cross_check(result, delta=1e-4)
    assert [c.status for c in fine.checks] == ["pass", "not checkable"]


# -- output and misuse -----------------------------------------------------------------------


def test_output_table_and_json(seed_result: cs.Result) -> None:
    cc = cross_check(seed_result)
    text = str(cc)
    assert text.splitlines()[0].split()[:2] == ["check", "vehicles"]
    assert "first_overlap" in text and "region" in text and "2 passed, 0 failed" in text
    data = json.loads(json.dumps(cc.to_dict()))
    assert data["ok"] is True and data["delta"] == 1e-3
    assert [c["status"] for c in data["checks"]] == ["pass", "pass"]
    assert data["checks"][1]["vehicles"] == ["red", "blue"]


def test_fcl_models_are_built_once_per_vehicle(seed_result: cs.Result) -> None:
    cross_check(seed_result)
    red = seed_result.vehicle("red")
    model = crosscheck._MODELS[red]
    cross_check(seed_result)
    assert crosscheck._MODELS[red] is model


def test_misuse_raises_typed_errors(seed_result: cs.Result) -> None:
    for bad in (0.0, -1e-3, float("nan"), float("inf"), "1 ms"):
        with pytest.raises(cs.ParameterError, match="delta"):
            cross_check(seed_result, delta=bad)
    with pytest.raises(cs.ParameterError, match="abs_tol"):
        cross_check(seed_result, abs_tol=-1e-3)
    with pytest.raises(cs.ParameterError, match="rel_tol"):
        cross_check(seed_result, rel_tol=float("nan"))
    with pytest.raises(cs.ParameterError, match="max_pairs"):
        cross_check(seed_result, max_pairs=0)
    with pytest.raises(TypeError, match="Result"):
        cross_check(seed_result.to_dict())  # type: ignore[arg-type]
    seed_result.scene = None
    with pytest.raises(cs.SceneError, match="no scene"):
        cross_check(seed_result)


# -- the crossing points ---------------------------------------------------------------------


def test_crossing_points_closed_form() -> None:
    flat = np.array([[[0.0, 0.0, 0.0], [2.0, 0.0, 0.0], [0.0, 2.0, 0.0]]])
    # a triangle in the plane x = 0.5 meets z = 0 for y in [-1, 1]; flat spans y in [0, 1.5]
    upright = np.array([[[0.5, -1.0, -1.0], [0.5, 3.0, -1.0], [0.5, -1.0, 1.0]]])
    points, empty = crossing_points(flat, upright)
    assert empty == 0
    assert np.allclose(sorted(points.tolist()), [[0.5, 0.0, 0.0], [0.5, 1.0, 0.0]], atol=1e-15)
    # coplanar: x >= 0.5, y >= 0.5 inside x + y <= 2 is the triangle below
    shifted = np.array([[[0.5, 0.5, 0.0], [3.0, 0.5, 0.0], [0.5, 3.0, 0.0]]])
    points, empty = crossing_points(flat, shifted)
    corners = {tuple(np.round(p, 12)) for p in points}
    assert empty == 0 and corners == {(0.5, 0.5, 0.0), (1.5, 0.5, 0.0), (0.5, 1.5, 0.0)}
    # apart: parallel planes, and a triangle that misses
    points, empty = crossing_points(flat, flat + [0.0, 0.0, 1.0])
    assert points.shape == (0, 3) and empty == 1
    points, empty = crossing_points(flat, upright + [5.0, 0.0, 0.0])
    assert points.shape == (0, 3) and empty == 1
    # a zero-area triangle has no plane: no common point, counted
    needle = np.array([[[0.5, 0.5, -1.0], [0.5, 0.5, 1.0], [0.5, 0.5, 0.0]]])
    points, empty = crossing_points(flat, needle)
    assert points.shape == (0, 3) and empty == 1
    # several pairs at once: the crossing and the coplanar overlap, in that order
    points, empty = crossing_points(
        np.concatenate([flat, flat]), np.concatenate([upright, shifted])
    )
    assert empty == 0 and points.shape == (5, 3) and np.allclose(points[:, 2], 0.0)


def test_crossing_points_agree_with_fcl_on_random_triangle_pairs() -> None:
    rng = np.random.default_rng(11)
    n = 2000
    a = rng.uniform(0.0, 1.0, (n, 3, 3))
    b = rng.uniform(0.0, 1.0, (n, 3, 3))

    def model(tri: np.ndarray) -> Any:
        m = fcl.BVHModel()
        m.beginModel(3, 1)
        m.addSubModel(np.ascontiguousarray(tri), np.array([[0, 1, 2]], dtype=np.int64))
        m.endModel()
        return fcl.CollisionObject(m, fcl.Transform())

    by_fcl = np.array(
        [
            fcl.collide(model(a[k]), model(b[k]), fcl.CollisionRequest(), fcl.CollisionResult()) > 0
            for k in range(n)
        ]
    )
    ours = np.array([crossing_points(a[k : k + 1], b[k : k + 1])[0].shape[0] > 0 for k in range(n)])
    assert 0.1 * n < by_fcl.sum() < 0.9 * n  # both outcomes are well represented
    assert np.array_equal(by_fcl, ours)
    # every crossing point lies on both triangles (to round-off)
    hits = np.flatnonzero(ours)
    points, empty = crossing_points(a[hits], b[hits])
    assert empty == 0 and points.shape == (2 * hits.size, 3)
    for tri in (a[hits], b[hits]):
        owner = np.concatenate([tri, tri])  # start points, then end points
        closest = trimesh.triangles.closest_point(owner, points)
        assert np.max(np.linalg.norm(closest - points, axis=1)) < 1e-12
