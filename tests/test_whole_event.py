"""The whole event in what a run gives back: the report's run-out section, the top-down picture
of a ground run, the GLB's wheels, obstacles and ground, and the whole-event examples
(examples/runout-*.toml) run to rest without sinking through the ground.

Closed forms written out here: a locked skid from v on friction mu stops after
t = v / (mu g) and d = v^2 / (2 mu g); the distance along a path is the integral of the speed.
Frames: world, z up, SI (angles in the report in degrees, counter-clockwise from world x).
"""

from __future__ import annotations

import json
import math
import subprocess
import sys
from pathlib import Path
from typing import Any

import crashsim as cs
import jsonschema
import numpy as np
import pytest
import shapely
import trimesh
from conftest import MISSING, REPO, SHARED_MESHES, seed_side_impact
from crashsim.analysis.report import report_schema
from crashsim.analysis.runout import run_out
from crashsim.io.export import (
    GROUND_Z,
    WHEEL_WIDTH,
    Z_UP_TO_Y_UP,
    ZONE_Z,
    export_frames,
    export_glb,
    wheel_node_name,
)
from crashsim.io.scenefile import load_scene
from crashsim.plots import plot_trajectories, silhouette
from crashsim.result import rotation_matrix

G = 9.80665
MU = 0.8  # the engine's default tyre friction (dry asphalt)
A, B = 1.1, 1.6
EXAMPLES = REPO / "examples"


def wheeled(name: str = "car", **kwargs) -> cs.Vehicle:
    return cs.Vehicle.box(4.6, 1.8, 1.4, mass=1500.0, name=name, ground_clearance=0.15,
                          cg_height=0.55, wheelbase=A + B, track=1.55, wheel_radius=0.3,
                          cg_to_front_axle=A, **kwargs)  # fmt: skip


LOCKED = cs.DriverInputs(wheel_states=[("all", "locked", 0.0)])
LOCKED_AFTER = cs.DriverInputs(wheel_states=[("all", "locked", "exchange")])


def speed_integral(result: cs.Result, name: str, t0: float) -> float:
    """The integral of the CG's speed from t0 to the end (m), trapezoids over the samples
    (the first from t0's interpolated state): the distance travelled, computed apart from the
    polyline the report measures."""
    tr = result.trajectory(name)
    k = int(np.searchsorted(tr.t, t0, side="right"))
    t = np.r_[t0, tr.t[k:]]
    v = np.r_[
        np.linalg.norm(result.state(name, t0)["velocity"]),
        np.linalg.norm(tr.velocity[k:], axis=1),
    ]
    return float(np.trapezoid(v, t))


@pytest.fixture(scope="module")
def skid() -> cs.Result:
    """A car locked from 20 m/s along world x, run to rest (no impact)."""
    scene = cs.Scene(ground=cs.Ground())
    scene.add(wheeled(), (0.0, 0.0), heading=0.0, velocity=(20.0, 0.0, 0.0), inputs=LOCKED)
    return scene.run(until="rest")


@pytest.fixture(scope="module")
def collision() -> cs.Result:
    """Red at 15 m/s into the rear of blue (at rest), both locked from the exchange on."""
    scene = cs.Scene(ground=cs.Ground())
    scene.add(wheeled("red"), (0.0, 0.0), heading=0.0, velocity=(15.0, 0.0, 0.0),
              inputs=LOCKED_AFTER)  # fmt: skip
    scene.add(wheeled("blue"), (7.0, 0.3), heading=0.2, inputs=LOCKED_AFTER)
    return scene.run(until="rest", max_duration=15.0)


@pytest.fixture(scope="module")
def into_wall() -> cs.Result:
    """A car locked at 14 m/s through a grass zone into a wall, on a ground with a zone."""
    ground = cs.Ground(
        friction="dry asphalt",
        zones=[cs.FrictionZone([(4, -3), (9, -3), (9, 3), (4, 3)], "grass", name="verge")],
    )
    scene = cs.Scene(ground=ground)
    scene.add(wheeled(), (0.0, 0.0), heading=0.0, velocity=(14.0, 0.0, 0.0), inputs=LOCKED)
    scene.add_obstacle(cs.Obstacle.wall(6.0, name="wall"), (14.0, 0.5), heading=0.0)
    return scene.run(until="rest", max_duration=15.0)


# -- the report's run-out ---------------------------------------------------------------------


def test_a_locked_skid_reports_v_over_mu_g_and_v_squared_over_two_mu_g(skid) -> None:
    report = cs.report(skid)
    r = report.vehicle_run_out("car")
    rest = skid.rest("car")
    assert r.start == "start" and r.start_time == 0.0 and r.other is None
    assert r.speed == pytest.approx(20.0, abs=1e-9) and r.direction == pytest.approx(0.0)
    assert r.heading == pytest.approx(0.0, abs=1e-9) and r.yaw_rate == pytest.approx(0.0)
    assert r.at_rest and r.rest_time == rest.time
    np.testing.assert_array_equal(r.position, rest.position)  # the rest position, exactly
    assert r.end_heading == pytest.approx(math.degrees(rest.heading), abs=1e-9)
    # closed forms of the locked skid, within 1 %
    assert r.time_to_rest == pytest.approx(20.0 / (MU * G), rel=0.01)  # 2.549 s
    assert r.distance == pytest.approx(20.0**2 / (2 * MU * G), rel=0.01)  # 25.49 m
    assert r.displacement == pytest.approx(20.0**2 / (2 * MU * G), rel=0.01)
    # the distance is the integral of the speed along the path
    assert r.distance == pytest.approx(speed_integral(skid, "car", 0.0), rel=2e-3)
    assert r.displacement <= r.distance
    assert abs(r.heading_change) < 0.01
    # every wheel leaves one skid mark the length of the skid
    assert set(r.tyre_marks) == set(skid.wheels("car").names)
    for marks in r.tyre_marks.values():
        assert marks.count == 1 and marks.longest == marks.length
        assert marks.length == pytest.approx(r.displacement, rel=0.02)
    assert r.obstacle_impacts == ()


def test_the_run_out_starts_at_separation_with_its_speeds(collision) -> None:
    report = cs.report(collision)
    assert [r.vehicle for r in report.run_out] == ["red", "blue"]
    for name in ("red", "blue"):
        r = report.vehicle_run_out(name)
        sep = collision.separations(name)[0]
        other = "blue" if name == "red" else "red"
        assert r.start == "separation" and r.other == other
        assert r.start_time == sep.time > collision.impacts[-1].time
        assert r.speed == pytest.approx(sep.speed, abs=1e-12)
        np.testing.assert_allclose(r.velocity, sep.velocity, atol=1e-12)
        assert r.yaw_rate == pytest.approx(math.degrees(sep.angular_velocity[2]), abs=1e-9)
        v = sep.velocity
        assert r.direction == pytest.approx(math.degrees(math.atan2(v[1], v[0])), abs=1e-9)
        assert r.heading == pytest.approx(math.degrees(sep.heading), abs=1e-9)
        rest = collision.rest(name)
        assert r.at_rest and r.rest_time == rest.time
        assert r.time_to_rest == pytest.approx(rest.time - sep.time, abs=1e-12)
        np.testing.assert_array_equal(r.position, rest.position)
        start = collision.state(name, sep.time)["position"]
        assert r.displacement == pytest.approx(float(np.linalg.norm(rest.position - start)))
        assert r.distance == pytest.approx(speed_integral(collision, name, sep.time), rel=5e-3)
        # from separation, less than from the exchange
        assert r.distance < rest.distance_from_exchange
    # the text: the section, its units and the numbers
    text = str(report)
    section = text[text.index("Run-out") :]
    for unit in ("t (s)", "speed (m/s)", "speed (km/h)", "yaw rate (deg/s)", "travel dir. (deg)",
                 "rest x (m)", "rest y (m)", "distance (m)", "displacement (m)"):  # fmt: skip
        assert unit in section
    red = report.vehicle_run_out("red")
    assert f"{red.distance:.3f}" in section and f"{red.rest_time:.3f}" in section
    assert "separation from blue" in section and "NOT AT REST" not in section


def test_the_json_run_out_matches_and_validates(collision) -> None:
    report = cs.report(collision)
    data = json.loads(report.to_json())
    jsonschema.validate(data, report_schema())
    (red,) = [r for r in data["run_out"] if r["vehicle"] == "red"]
    rest = collision.rest("red")
    assert red["at_rest"] is True and red["rest_time"] == rest.time
    assert red["end"]["position"] == rest.position.tolist()
    assert red["start"]["kind"] == "separation" and red["start"]["other"] == "blue"
    assert red["distance"] == report.vehicle_run_out("red").distance
    assert set(red["tyre_marks"]) == set(collision.wheels("red").names)
    # a corrupted run-out fails the schema
    red["start"]["kind"] = "somewhere"
    with pytest.raises(jsonschema.ValidationError):
        jsonschema.validate(data, report_schema())


def test_a_run_without_ground_has_no_run_out() -> None:
    result = seed_side_impact(cs.mph(30.0), 0.0, (-3.65, 0.3))
    report = cs.report(result)
    assert report.run_out == [] and "run_out" not in report.to_dict()
    assert "Run-out" not in str(report)
    with pytest.raises(cs.SceneError, match="no ground"):
        report.vehicle_run_out("red")
    with pytest.raises(cs.SceneError, match="no ground"):
        run_out(result, "red")


def test_a_vehicle_still_moving_is_said_so() -> None:
    scene = cs.Scene(ground=cs.Ground())
    scene.add(wheeled(), (0.0, 0.0), velocity=(20.0, 0.0, 0.0))
    with pytest.warns(cs.RestNotReachedWarning):
        result = scene.run(until="rest", max_duration=0.2)
    report = cs.report(result)
    r = report.vehicle_run_out("car")
    end_speed = float(np.linalg.norm(result.trajectory("car").velocity[-1]))
    assert not r.at_rest and r.rest_time is None and r.time_to_rest is None
    assert r.end_time == pytest.approx(0.2) and r.end_speed == pytest.approx(end_speed)
    text = str(report)
    assert "NOT AT REST" in text
    assert f"car did NOT reach rest: still moving at t = 0.200 s, speed {end_speed:.3f} m/s" in text
    data = report.to_dict()
    jsonschema.validate(json.loads(json.dumps(data)), report_schema())
    assert data["run_out"][0]["at_rest"] is False and data["run_out"][0]["rest_time"] is None


def test_obstacle_impacts_in_the_run_out(into_wall) -> None:
    (imp,) = into_wall.impacts
    assert imp.obstacle == "wall"
    r = cs.report(into_wall).vehicle_run_out("car")
    (hit,) = r.obstacle_impacts
    assert hit.impact == 1 and hit.obstacle == "wall" and hit.time == imp.time
    assert hit.closing_speed == imp.closing_speed
    assert hit.delta_v == pytest.approx(imp.speed_change("car"), abs=1e-12)
    assert hit.speed_before == pytest.approx(float(np.linalg.norm(imp.velocity_before["car"])))
    assert hit.speed_after < hit.speed_before
    assert r.start in ("separation", "exchange") and r.other == "wall"
    text = str(cs.report(into_wall))
    assert f"car: impact 1 with wall at t = {imp.time:.3f} s" in text


# -- wheel centres and steering -----------------------------------------------------------------


def test_wheel_centres_follow_the_ground_and_the_steering() -> None:
    scene = cs.Scene(ground=cs.Ground())
    steer = cs.DriverInputs(steer=[(0.0, 0.0), (0.5, 0.1)], wheel_states=[("all", "locked", 1.0)])
    scene.add(wheeled(), (0.0, 0.0), heading=0.3,
              velocity=(15 * math.cos(0.3), 15 * math.sin(0.3), 0.0), inputs=steer)  # fmt: skip
    result = scene.run(until="rest")
    car = result.vehicle("car")
    centres = result.wheel_centres("car")
    tr = result.trajectory("car")
    # at static ride height the centres are the body-frame ones posed with the body
    posed = tr.position[0] + car.wheels.centers @ rotation_matrix(tr.orientation[0]).T
    np.testing.assert_allclose(centres[:, 0], posed, atol=1e-9)
    # on the plane the tyres stay on the ground: every centre one radius above it, while the
    # body pitches under braking (the hubs it carries dip and rise by cm)
    np.testing.assert_allclose(centres[..., 2], 0.3, atol=1e-9)
    poses = zip(tr.position, tr.orientation, strict=True)
    hubs = np.array([p + car.wheels.centers @ rotation_matrix(q).T for p, q in poses])
    assert np.ptp(hubs[:, 0, 2]) > 0.02
    # the steering: the steerable (front) wheels turn through the linkage, the rear ones do
    # not. The table is the outer wheel's angle (the right one in a turn to the left); the
    # inner one is full Ackermann's, cot(inner) = cot(outer) - track / wheelbase.
    angles = result.wheel_steer("car")
    outer = np.interp(result.t, [0.0, 0.5], [0.0, 0.1])
    np.testing.assert_allclose(angles[1], outer, rtol=1e-12)
    turning = outer > 0.0
    inner = np.arctan(1.0 / (1.0 / np.tan(outer[turning]) - 1.55 / (A + B)))
    np.testing.assert_allclose(angles[0][turning], inner, rtol=1e-12)
    assert not np.any(angles[2:])


# -- the picture ------------------------------------------------------------------------------


def test_the_run_out_picture_draws_marks_under_the_wheels(into_wall, tmp_path: Path) -> None:
    fig = plot_trajectories(into_wall, tmp_path / "run.png")
    (ax,) = fig.axes
    marks = into_wall.tyre_marks("car")
    drawn: dict[str, list[Any]] = {}
    for line in ax.lines:
        if (line.get_gid() or "").startswith("tyre"):
            drawn.setdefault(line.get_gid(), []).append(line)
    assert set(drawn) == {f"tyre-mark:car:{w}" for w, lines in marks.items() if lines}
    for wheel, lines in marks.items():
        if not lines:
            continue
        # every mark of the wheel, in time order (a wheel may leave several)
        got = drawn[f"tyre-mark:car:{wheel}"]
        assert len(got) == len(lines)
        for line, mark in zip(got, lines, strict=True):
            np.testing.assert_allclose(np.asarray(line.get_xydata()), mark[:, :2])
    # every mark point lies under the car's outline at that instant (the tyre is under the body)
    record = into_wall.wheels("car")
    for w in range(len(record.names)):
        for k in np.flatnonzero(record.sliding[w])[::25]:
            p, r = into_wall.pose("car", float(into_wall.t[k]))
            outline = silhouette(into_wall.vehicle("car"), p, r)
            point = record.contact[w, k, :2]
            assert outline.buffer(1e-6).contains(shapely.Point(*point))
    # the obstacle, the zone (with its friction in the legend) and the rest outline's label
    assert any(t.get_gid() == "obstacle:wall" for t in ax.texts)
    zone = [p for p in ax.patches if p.get_gid() == "zone:0"]
    assert len(zone) == 1
    np.testing.assert_allclose(zone[0].get_xy()[:4], [(4, -3), (9, -3), (9, 3), (4, 3)])
    legend = [t.get_text() for t in fig.legends[0].get_texts()]
    assert "zone 'verge': tyre friction 0.35" in legend
    rest = into_wall.rest("car")
    assert any(t.get_text() == f"car at rest, t = {rest.time:.2f} s" for t in ax.texts)
    assert f"car at rest at {rest.time:.2f} s" in fig.get_suptitle()
    assert "tyre-road friction 0.8 (dry asphalt)" in fig.get_suptitle()
    # the whole picture is inside the figure: the title and the legend below the axes
    renderer = fig.canvas.get_renderer()
    page = fig.bbox
    for artist in (fig._suptitle, fig.legends[0]):
        box = artist.get_window_extent(renderer)
        assert page.x0 <= box.x0 and box.x1 <= page.x1 and page.y0 <= box.y0 <= box.y1 <= page.y1
    # equal axes in metres
    assert ax.get_aspect() == 1.0


def test_a_picture_of_a_vehicle_still_moving_says_so(tmp_path: Path) -> None:
    scene = cs.Scene(ground=cs.Ground())
    scene.add(wheeled(), (0.0, 0.0), velocity=(20.0, 0.0, 0.0))
    with pytest.warns(cs.RestNotReachedWarning):
        result = scene.run(until="rest", max_duration=0.5)
    fig = plot_trajectories(result)
    (ax,) = fig.axes
    assert any(t.get_text() == "car still moving at t = 0.50 s" for t in ax.texts)
    assert "car STILL MOVING at 0.50 s" in fig.get_suptitle()


# -- the GLB ----------------------------------------------------------------------------------


def _turn() -> np.ndarray:
    """The GLB root's rotation (world z up -> glTF y up) as a 4 x 4 transform."""
    x, y, z, w = Z_UP_TO_Y_UP
    out = np.eye(4)
    out[:3, :3] = rotation_matrix(np.array([w, x, y, z]))
    return out


def _parts(scene: trimesh.Scene, node: str) -> list[trimesh.Trimesh]:
    """The meshes of a GLB node: its own, or (a mesh of several primitives, which trimesh
    splits) its children's."""
    names = [
        n
        for n in scene.graph.nodes_geometry
        if n == node or scene.graph.transforms.parents.get(n) == node
    ]
    return [scene.geometry[scene.graph[n][1]] for n in names]


def _world(transform: np.ndarray) -> np.ndarray:
    """A node's trimesh world transform back in crashsim's world (z up)."""
    return np.linalg.inv(_turn()) @ transform


def test_the_glb_holds_wheels_obstacles_zones_and_ground(into_wall, tmp_path: Path) -> None:
    path = export_glb(into_wall, tmp_path / "run.glb")
    scene = trimesh.load(path)
    car = into_wall.vehicle("car")
    centres = into_wall.wheel_centres("car")
    nodes = set(scene.graph.nodes_geometry)
    wheels = {wheel_node_name("car", w) for w in car.wheels.names}
    assert wheels | {"car", "wall", "friction zones"} <= nodes
    # each wheel: a cylinder of the tyre's radius and width, at its centre at the start
    for k, w in enumerate(car.wheels.names):
        transform, geometry = scene.graph.get(wheel_node_name("car", w))
        mesh = scene.geometry[geometry]
        assert np.ptp(mesh.vertices[:, 1]) == pytest.approx(WHEEL_WIDTH * 0.3, abs=1e-6)
        assert np.max(np.hypot(mesh.vertices[:, 0], mesh.vertices[:, 2])) == pytest.approx(0.3)
        np.testing.assert_allclose(_world(transform)[:3, 3], centres[k, 0], atol=1e-9)
    # the wall where the result has it, its mesh in its own frame
    transform, geometry = scene.graph.get("wall")
    p, r = into_wall.pose("wall", 0.0)
    np.testing.assert_allclose(_world(transform)[:3, 3], p, atol=1e-9)
    np.testing.assert_allclose(_world(transform)[:3, :3], r, atol=1e-9)
    wall = into_wall.obstacle("wall")
    np.testing.assert_allclose(scene.geometry[geometry].vertices, wall.mesh.vertices, atol=1e-6)
    # the zone: its polygon, ZONE_Z above the plane, its area
    (zone,) = _parts(scene, "friction zones")
    assert zone.area == pytest.approx(5.0 * 6.0, rel=1e-6)
    np.testing.assert_allclose(zone.vertices[:, 2], ZONE_Z, atol=1e-7)
    # the checkerboard under the plane z = 0, under the wall too
    tiles = _parts(scene, "ground")
    assert len(tiles) == 2  # the checkerboard's two colours
    ground = trimesh.util.concatenate(tiles)
    np.testing.assert_allclose(ground.vertices[:, 2], GROUND_Z, atol=1e-7)
    assert ground.vertices[:, 0].max() >= 14.15 + 3.0


def test_the_glb_wheels_follow_the_run(tmp_path: Path) -> None:
    """On a terrain, a steering car's wheel nodes at each frame: where Result.wheel_centres
    puts them (at sample times), turned with the body and the road-wheel angle."""
    h = 40.0
    v = [[-h, -h, -0.05 * h], [h, -h, 0.05 * h], [h, h, 0.05 * h], [-h, h, -0.05 * h]]
    sheet = trimesh.Trimesh(v, [[0, 1, 2], [0, 2, 3]], process=False)
    scene = cs.Scene(ground=cs.Ground(terrain=sheet))
    steer = cs.DriverInputs(steer=[(0.0, 0.0), (0.4, 0.08)])
    scene.add(wheeled(), (-10.0, 0.0), heading=0.0, velocity=(10.0, 0.0, 0.0), inputs=steer)
    result = scene.run(1.0)
    times = [float(result.t[0]), float(result.t[400]), float(result.t[-1])]
    samples = [0, 400, len(result.t) - 1]
    paths = export_frames(result, tmp_path / "frames", times)
    centres = result.wheel_centres("car")
    steer_angles = result.wheel_steer("car")
    car = result.vehicle("car")
    for path, t, k in zip(paths, times, samples, strict=True):
        glb = trimesh.load(path)
        # the terrain is the ground
        (terrain,) = _parts(glb, "ground")
        np.testing.assert_allclose(terrain.vertices, sheet.vertices, atol=1e-6)
        body = result.pose("car", t)[1]
        for i, w in enumerate(car.wheels.names):
            transform = _world(glb.graph.get(wheel_node_name("car", w))[0])
            np.testing.assert_allclose(transform[:3, 3], centres[i, k], atol=1e-6)
            a = steer_angles[i, k]
            yaw = np.array(
                [[math.cos(a), -math.sin(a), 0], [math.sin(a), math.cos(a), 0], [0, 0, 1]]
            )
            np.testing.assert_allclose(transform[:3, :3], body @ yaw, atol=1e-6)
    # the outer (right) front wheel at the table's 0.08, the inner more, the rear ones not
    assert steer_angles[1, -1] == pytest.approx(0.08) and steer_angles[2, -1] == 0.0
    assert steer_angles[0, -1] > steer_angles[1, -1]
    # the car climbs the terrain: the front wheels sit one radius above it, along its normal
    n = np.array([-0.05, 0.0, 1.0]) / math.hypot(0.05, 1.0)
    for i in range(4):
        x, y, z = centres[i, -1]
        assert (np.array([x, y, z]) - [x, y, 0.05 * x]) @ n == pytest.approx(0.3, abs=1e-6)


def test_without_ground_the_wheels_ride_with_the_body(tmp_path: Path) -> None:
    scene = cs.Scene()
    scene.add(wheeled(), (0.0, 0.0, 0.55), velocity=(5.0, 0.0, 0.0))
    result = scene.run(0.2)
    (frame,) = export_frames(result, tmp_path, [0.1])
    glb = trimesh.load(frame)
    car = result.vehicle("car")
    p, r = result.pose("car", 0.1)
    for i, w in enumerate(car.wheels.names):
        transform = _world(glb.graph.get(wheel_node_name("car", w))[0])
        np.testing.assert_allclose(transform[:3, 3], p + r @ car.wheels.centers[i], atol=1e-9)
    for tiles in _parts(glb, "ground"):
        np.testing.assert_allclose(tiles.vertices[:, 2], GROUND_Z, atol=1e-9)


# -- the examples -----------------------------------------------------------------------------

RUN_OUT_EXAMPLES = [
    "runout-sedan-into-suv",
    "runout-small-overlap-barrier",
    "runout-sedan-into-pole",
    "runout-rollover-kerb",
]
SINK = 0.02  # m: nothing goes further below the ground than this
# The engine's points of a mesh left to its wheels (WHEEL_HALF_WIDTH and WHEEL_CLEARANCE in
# crates/crashsim-core/src/motion/ground_contact.rs): a mesh's own wheels are part of its
# rigid body, so they dip when the suspension compresses; they are checked against the tyre
# instead.
WHEEL_HALF_WIDTH, WHEEL_CLEARANCE = 0.15, 0.05


def sinking(result: cs.Result, name: str) -> tuple[np.ndarray, np.ndarray]:
    """Per sample: the lowest vertex of the body outside its wheels (m, world z over the
    plane z = 0), and the smallest margin of the mesh's own wheels (m) over the depth the
    engine's tyre allows them: its compression beyond static (R - h, h the hub's height above
    the ground) plus half the wheel's width times the sine of the body's tilt."""
    v = result.vehicle(name)
    body = v.body_vertices
    owner = np.full(len(body), -1)
    if v.wheels is not None:
        for k, (c, radius) in enumerate(zip(v.wheels.centers, v.wheels.radii, strict=True)):
            d = body - c
            inside = (np.abs(d[:, 1]) <= WHEEL_HALF_WIDTH) & (
                np.hypot(d[:, 0], d[:, 2]) <= radius + WHEEL_CLEARANCE
            )
            owner[inside & (owner < 0)] = k
    tr = result.trajectory(name)
    record = result.wheels(name) if v.wheels is not None else None
    lowest, margin = [], []
    for i, (p, q) in enumerate(zip(tr.position, tr.orientation, strict=True)):
        r = rotation_matrix(q)
        z = body @ r[2] + p[2]
        lowest.append(z[owner < 0].min())
        tilt = math.sqrt(max(0.0, 1.0 - r[2, 2] ** 2))
        worst = np.inf
        for k in range(len(v.wheels.names) if v.wheels is not None else 0):
            if not np.any(owner == k):
                continue
            hub = p + r @ v.wheels.centers[k]
            contact = record.contact[k, i]
            h = float(np.linalg.norm(hub - contact)) * (1.0 if hub[2] >= contact[2] else -1.0)
            allowed = -max(0.0, float(v.wheels.radii[k]) - h) - WHEEL_HALF_WIDTH * tilt
            worst = min(worst, float(z[owner == k].min()) - allowed)
        margin.append(worst)
    return np.array(lowest), np.array(margin)


@pytest.fixture(scope="module")
def examples() -> dict[str, cs.Result]:
    if not SHARED_MESHES.is_dir():
        pytest.skip(MISSING)
    return {name: load_scene(EXAMPLES / f"{name}.toml").simulate() for name in RUN_OUT_EXAMPLES}


@pytest.mark.filterwarnings("ignore::crashsim.DepthOfPenetrationWarning")
@pytest.mark.parametrize("name", RUN_OUT_EXAMPLES)
def test_each_example_runs_to_rest_and_nothing_sinks(name: str, examples) -> None:
    result = examples[name]
    assert result.impacts, "an impact"
    report = cs.report(result)
    for vehicle in result.vehicles:
        r = report.vehicle_run_out(vehicle)
        assert r.at_rest, f"{vehicle} did not reach rest by {result.t[-1]} s"
        assert r.end_speed < 0.05
        lowest, margin = sinking(result, vehicle)
        if name != "runout-rollover-kerb":  # the rollover: the next test
            assert lowest.min() >= -SINK, (vehicle, float(lowest.min()))
        assert lowest[-1] >= -0.005, "at rest the body sinks at most 5 mm"
        assert margin.min() >= -0.01, (vehicle, float(margin.min()))


@pytest.mark.filterwarnings("ignore::crashsim.DepthOfPenetrationWarning")
def test_the_examples_figures(examples) -> None:
    """The run-outs are what the scenes describe (figures of the current engine, with room)."""
    reports = {n: cs.report(r) for n, r in examples.items()}
    a = reports["runout-sedan-into-suv"]
    for vehicle in ("sedan", "suv"):
        r = a.vehicle_run_out(vehicle)
        assert r.start == "separation" and r.other in ("sedan", "suv")
        assert 3.0 < r.speed < 10.0 and 2.0 < r.distance < 8.0
    # the sedan, locked and turning slowly, stops after about v^2 / (2 mu g) from separation
    # (the SUV spins at 220 deg/s: its tyres stop the spin too, and it slides farther)
    sedan = a.vehicle_run_out("sedan")
    assert abs(sedan.yaw_rate) < 90.0
    assert sedan.distance == pytest.approx(sedan.speed**2 / (2 * MU * G), rel=0.15)
    b = reports["runout-small-overlap-barrier"].vehicle_run_out("sedan")
    (hit,) = b.obstacle_impacts
    assert hit.obstacle == "barrier" and 15.0 < hit.closing_speed < 18.0
    assert abs(b.heading_change) > 10.0  # the small overlap spins it
    c = reports["runout-sedan-into-pole"].vehicle_run_out("sedan")
    assert c.obstacle_impacts[0].obstacle == "pole" and c.displacement < 3.0
    d_result = examples["runout-rollover-kerb"]
    end = rotation_matrix(d_result.trajectory("suv").orientation[-1])
    assert end[2, 2] < 0.0, "the SUV rests on its roof"
    rolled = reports["runout-rollover-kerb"].vehicle_run_out("suv")
    assert rolled.attitude == "on its roof"
    assert rolled.tilt == pytest.approx(math.degrees(math.acos(end[2, 2])), abs=1e-9)
    assert "suv ends on its roof" in str(reports["runout-rollover-kerb"])
    assert a.vehicle_run_out("suv").attitude == "upright"
    assert (
        reports["runout-rollover-kerb"].vehicle_run_out("suv").obstacle_impacts[0].obstacle
        == "kerb"
    )


def test_the_rollover_lands_within_2_cm(examples) -> None:
    """Landing on its roof the SUV's hull points are slowed by inelastic impulses (the
    engine's landing, crates/crashsim-core/src/motion/ground_contact.rs): 1.8 cm into the
    road for a moment (4.6 cm with the body-ground spring alone), a few mm at rest on the spring."""
    lowest, _ = sinking(examples["runout-rollover-kerb"], "suv")
    assert lowest.min() >= -SINK
    assert lowest[-1] >= -0.005


def test_an_example_through_the_command_line(tmp_path: Path) -> None:
    out = subprocess.run(
        [
            sys.executable,
            "-m",
            "crashsim",
            "run",
            str(EXAMPLES / "runout-sedan-into-pole.toml"),
            "--out",
            str(tmp_path / "o"),
        ],  # fmt: skip
        capture_output=True,
        text=True,
        check=False,
    )
    assert out.returncode == 0, out.stderr
    assert "Run-out" in out.stdout and "sedan: impact 1 with pole" in out.stdout
    report = json.loads((tmp_path / "o" / "report.json").read_text(encoding="utf-8"))
    jsonschema.validate(report, report_schema())
    (sedan,) = report["run_out"]
    assert sedan["at_rest"] and sedan["obstacle_impacts"][0]["obstacle"] == "pole"
    for name in ("trajectories.png", "motion.glb"):
        assert (tmp_path / "o" / name).stat().st_size > 10_000
