"""The ground (plane, terrain, friction zones), the table of road surfaces and fixed obstacles
(crashsim.environment), and obstacles in runs and reports.

Closed forms written out here: a full central impact of a body on an immovable one with
restitution e changes its velocity by -(1 + e) v; a locked skid from v on friction mu stops
after v^2 / (2 mu g).
"""

from __future__ import annotations

import json
import math
import pickle
import tomllib
from importlib import resources

import crashsim as cs
import jsonschema
import numpy as np
import pytest
import trimesh
from crashsim.analysis.report import report_schema
from crashsim.environment import surfaces as sf

G = 9.80665


# -- the surface table -------------------------------------------------------------------------


def test_surface_table_has_the_design_defaults_and_sourced_ranges() -> None:
    table = sf.surfaces()
    assert list(table)[:2] == ["dry_asphalt", "wet_asphalt"]
    for name, expected in (("dry_asphalt", 0.8), ("wet_asphalt", 0.5), ("gravel", 0.55),
                           ("grass", 0.35), ("ice", 0.1)):  # fmt: skip
        assert table[name].value == expected
    for s in table.values():
        assert 0.0 < s.low <= s.value <= s.high <= 1.0, s.name
        if s.derived:
            assert len(s.source) > 40, s.name
        else:
            assert s.source in sf.SOURCES and s.source in s.refs, s.name
        for ref in s.refs:
            assert ref in sf.SOURCES, (s.name, ref)
    # the engine's default tyre friction is the dry asphalt figure
    assert cs.vehicles.wheels.dynamics_defaults()["tyre_friction"] == table["dry_asphalt"].value


def test_surface_names_are_forgiving_and_unknown_ones_listed() -> None:
    assert sf.surface("Wet asphalt") is sf.surface("wet_asphalt")
    assert sf.surface("asphalt") is sf.surface("dry_asphalt")
    assert sf.friction("packed-snow") == 0.3
    assert sf.friction(0.42) == 0.42
    with pytest.raises(cs.ParameterError, match="unknown surface 'lava'.*dry_asphalt.*ice"):
        sf.surface("lava")
    # finiteness is the engine's rule, checked once where the ground is made, in its place
    with pytest.raises(cs.ParameterError, match="ground: tyre-road friction = NaN") as raised:
        cs.Ground(friction=float("nan"))
    assert raised.value.loc[-1] == ("parameter", None, "tyre-road friction")


def test_every_surface_row_has_its_keys() -> None:
    path = resources.files("crashsim.environment").joinpath("data", "ground_surfaces.toml")
    raw = tomllib.loads(path.read_text(encoding="utf-8"))
    assert set(raw["order"]) == set(raw["surfaces"])
    for row in raw["surfaces"].values():
        assert {"description", "value", "low", "high", "source", "refs"} <= set(row)


# -- the ground --------------------------------------------------------------------------------


def square(x0: float, y0: float, s: float) -> list[tuple[float, float]]:
    return [(x0, y0), (x0 + s, y0), (x0 + s, y0 + s), (x0, y0 + s)]


def test_ground_frictions_zones_and_heights() -> None:
    g = cs.Ground(height=0.5, friction="wet asphalt", zones=[(square(0, 0, 10), "grass")])
    assert g.height_at(3.0, 4.0) == 0.5
    assert g.friction_at(5.0, 5.0) == 0.35 and g.friction_at(20.0, 5.0) == 0.5
    assert g.core.tyre_friction == 0.5 and g.core.friction_at(5.0, 5.0) == 0.35
    default = cs.Ground()
    d = cs.vehicles.wheels.dynamics_defaults()
    assert default.tyre_friction == d["tyre_friction"]
    assert default.core.body_friction == d["body_friction"]
    # a study's variant: another friction, checked by the engine, the zones kept
    wet = g.with_friction(0.3, body_friction=0.4)
    assert wet.friction_at(20.0, 5.0) == 0.3 and wet.friction_at(5.0, 5.0) == 0.35
    assert wet.core.body_friction == 0.4 and g.friction_at(20.0, 5.0) == 0.5
    with pytest.raises(cs.ParameterError, match="friction"):
        g.with_friction(-1.0)
    # the engine's value is rebuilt when a ground is unpickled
    back = pickle.loads(pickle.dumps(g))
    assert back.friction_at(5.0, 5.0) == 0.35 and back.core.tyre_friction == 0.5


@pytest.mark.parametrize("height", [1e30, -2e6])
def test_a_ground_height_past_the_world_is_refused(height) -> None:
    # issue 24: at 1e30 m a locked skid reported rest at 1.478 s while still at 4.2 m/s
    # (the springs' travel was below the height's rounding)
    with pytest.raises(cs.ParameterError, match=r"ground height = .* within \+-1e6 m"):
        cs.Ground(height=height)
    assert cs.Ground(height=-4.5e5).height == -4.5e5  # the Dead Sea to far above Everest


def test_a_terrain_or_a_vehicle_past_the_world_is_refused() -> None:
    far = trimesh.creation.box(extents=(100.0, 100.0, 1.0))
    far.apply_translation((5.0e6, 0.0, 0.0))  # a national grid's easting
    with pytest.raises(cs.ParameterError, match="a terrain vertex coordinate = .* within"):
        cs.Ground(terrain=far)
    scene = cs.Scene()
    car = cs.Vehicle.box(4.6, 1.8, 1.4, mass=1500.0, name="car")
    with pytest.raises(cs.ParameterError, match=r"position x = 2000000 m .* within \+-1e6 m"):
        scene.add(car, (2.0e6, 0.0, 0.7))


def test_overlapping_zones_are_an_error_naming_them() -> None:
    zones = [
        cs.FrictionZone(square(0, 0, 10), "wet asphalt", name="puddle"),
        cs.FrictionZone(square(5, 5, 10), 0.3),
    ]
    with pytest.raises(cs.ParameterError, match="friction zones 'puddle' and 1: they overlap"):
        cs.Ground(zones=zones)
    # sharing an edge is fine
    cs.Ground(zones=[(square(0, 0, 10), 0.5), (square(10, 0, 10), 0.35)])


@pytest.mark.parametrize(
    "zone, match",
    [
        (([(0, 0), (1, 0)], 0.5), "zone 0: it has 2 corners"),
        (([(0, 0), (2, 2), (2, 0), (0, 1)], 0.5), "zone 0: it crosses itself"),
        ((square(0, 0, 1), 3.0), "must lie in \\(0, 2\\]"),
        ((square(0, 0, 1), "lava"), "unknown surface 'lava'"),
        (([(0, 0, 0), (1, 0, 0), (1, 1, 0)], 0.5), "shape \\(k, 2\\)"),
    ],
)
def test_bad_zones_are_parameter_errors(zone, match) -> None:
    with pytest.raises(cs.ParameterError, match=match) as raised:
        cs.Ground(zones=[zone])
    # a pair given to the ground is placed at its index in the ground, as the engine does
    assert raised.value.loc[:2] == (("part", None, "ground"), ("zone", 0, None))
    assert str(raised.value).startswith("ground: friction zone 0: ")


@pytest.mark.parametrize(
    "polygon, friction, loc, message",
    [
        ([(0, 0), (1, 0)], 0.5, (), "it has 2 corners: a polygon needs at least 3"),
        (square(0, 0, 1), 3.0, (("parameter", None, "friction"),),
         "friction = 3 is invalid: a friction coefficient must lie in (0, 2] (dry asphalt about "
         "0.8)"),
        (square(0, 0, 1), float("nan"), (("parameter", None, "friction"),),
         "friction = NaN is invalid: it must be a finite number"),
        ([(0, 0), (2, 2), (2, 0), (0, 1)], 0.5, (),
         "it crosses itself (edges 0 and 2): give its corners in order around it"),
    ],
)  # fmt: skip
def test_a_zone_is_checked_by_the_engines_rules_when_made(polygon, friction, loc, message) -> None:
    """FrictionZone is a value checked once, when made, by the core's rules of a zone (the
    ground applies the same function to its zones), in the zone's place."""
    for name, part in ((None, "friction zone"), ("wet", "friction zone 'wet'")):
        with pytest.raises(cs.ParameterError) as raised:
            cs.FrictionZone(polygon, friction, name=name)
        e = raised.value
        assert e.loc == (("part", None, part), *loc)
        assert e.message == message and str(e) == f"{part}: {message}"


def test_a_bow_tie_zone_is_said_to_cross_itself() -> None:
    # a bow-tie's two lobes cancel: its signed area is 0, and the core says "its corners are
    # in a line", which they are not
    with pytest.raises(cs.ParameterError, match="zone 'bow': it crosses itself"):
        cs.Ground(zones=[cs.FrictionZone([(0, 0), (1, 1), (1, 0), (0, 1)], 0.5, name="bow")])
    with pytest.raises(cs.ParameterError, match="in a line"):  # collinear corners still are
        cs.Ground(zones=[cs.FrictionZone([(0, 0), (1, 1), (2, 2)], 0.5)])


def terrain(size: float = 40.0, slope: float = 0.0) -> trimesh.Trimesh:
    """A square sheet z = slope x centred on the origin (two triangles)."""
    h = size / 2
    v = np.array([[-h, -h, -slope * h], [h, -h, slope * h], [h, h, slope * h], [-h, h, -slope * h]])
    return trimesh.Trimesh(v, [[0, 1, 2], [0, 2, 3]], process=False)


def test_a_terrain_gives_its_height_and_none_off_its_edge(tmp_path) -> None:
    path = tmp_path / "ramp.ply"
    terrain(slope=0.1).export(path)
    g = cs.Ground(terrain=path)
    assert g.height_at(4.0, 3.0) == pytest.approx(0.4, abs=1e-12)
    assert g.height_at(30.0, 0.0) is None
    assert g.holes([(0.0, 0.0), (25.0, 0.0)]) == [1]
    with pytest.raises(cs.ParameterError, match="height or a terrain, not both"):
        cs.Ground(height=1.0, terrain=path)
    flat = trimesh.Trimesh([[0, 0, 0], [1, 0, 0], [0, 0, 1]], [[0, 1, 2]], process=False)
    with pytest.raises(cs.MeshError, match="no extent seen from above"):
        cs.Ground(terrain=flat)


def wheeled(name: str = "car") -> cs.Vehicle:
    return cs.Vehicle.box(4.6, 1.8, 1.4, mass=1500.0, name=name, ground_clearance=0.15,
                          cg_height=0.55, wheelbase=2.7, track=1.55, wheel_radius=0.3,
                          cg_to_front_axle=1.1)  # fmt: skip


def test_a_wheel_over_a_hole_in_the_terrain_is_named_before_the_run() -> None:
    scene = cs.Scene(ground=cs.Ground(terrain=terrain(size=40.0)))
    # placed by (x, y): the front axle at x = 20.1 is off the sheet
    with pytest.raises(cs.SceneError, match=r"'car' wheel 'front_left' at \(20.10, 0.78\) m"):
        scene.add(wheeled(), (19.0, 0.0), heading=0.0)
    # placed with its z: found when the world is built
    scene.add(wheeled(), (19.0, 0.0, 0.55), heading=0.0)
    with pytest.raises(cs.SceneError, match=r"'car' wheel 'front_left' starts at \(20.10, 0.78\)"):
        scene.run(0.1)


def test_a_wheel_leaving_the_terrain_names_the_vehicle_and_wheel() -> None:
    scene = cs.Scene(ground=cs.Ground(terrain=terrain(size=40.0)))
    scene.add(wheeled(), (10.0, 0.0), heading=0.0, velocity=(10.0, 0.0, 0.0))
    left = r"vehicle 'car': wheel 'front_left': t = 0\.\d{6} s: it left the terrain"
    with pytest.raises(cs.SimulationError, match=left) as raised:
        scene.run(2.0)
    # the time is a place: the simulated time (s) as its index
    ((kind, t, name),) = [p for p in raised.value.loc if p[0] == "time"]
    assert name is None and 0.5 < t < 2.0 and f"t = {t:.6f} s" in str(raised.value)


def test_a_vehicle_placed_by_x_y_stands_on_the_terrain_at_its_static_height() -> None:
    slope = 0.05
    scene = cs.Scene(ground=cs.Ground(terrain=terrain(slope=slope)))
    car = wheeled()
    scene.add(car, (4.0, 0.0), heading=0.0)
    placed = scene._placements[0]
    n = np.array([-slope, 0.0, 1.0]) / math.hypot(slope, 1.0)  # the terrain's normal
    np.testing.assert_allclose(placed.position, [4.0, 0.0, 4.0 * slope] + 0.55 * n, atol=1e-12)
    # tilted to the slope (nose up), heading kept: every tyre touches the terrain
    r = cs.result.rotation_matrix(placed.orientation)
    np.testing.assert_allclose(r[:, 2], n, atol=1e-12)
    feet = placed.position + car.wheels.contact_points() @ r.T
    np.testing.assert_allclose(feet[:, 2], slope * feet[:, 0], atol=1e-12)
    # it stands still there (a braked car, the slope well below atan(mu))
    scene.ground = cs.Ground(terrain=terrain(slope=slope))  # re-read: the same pose
    np.testing.assert_allclose(scene._placements[0].position, placed.position, atol=1e-15)
    with pytest.raises(cs.SceneError, match="has no ground under it"):
        scene.add(wheeled("far"), (100.0, 0.0))


def test_a_zone_sets_the_skid_distance() -> None:
    """A locked skid from 15 m/s inside a wet zone (mu 0.5) stops after v^2/(2 mu g)."""
    v = 15.0
    zone = cs.FrictionZone([(-10, -10), (200, -10), (200, 10), (-10, 10)], "wet asphalt")
    scene = cs.Scene(ground=cs.Ground(zones=[zone]))
    locked = cs.DriverInputs(wheel_states=[("all", "locked", 0.0)])
    scene.add(wheeled(), (0.0, 0.0), heading=0.0, velocity=(v, 0.0, 0.0), inputs=locked)
    rest = scene.run(until="rest").rest("car")
    assert rest is not None
    expected = v * v / (2 * 0.5 * G)
    assert rest.displacement == pytest.approx(expected, rel=0.01)


# -- obstacles ---------------------------------------------------------------------------------


def test_primitives_are_closed_solids_of_their_dimensions() -> None:
    wall = cs.Obstacle.wall(5.0, 0.5, 2.0)
    assert wall.mesh.volume == pytest.approx(5.0 * 0.5 * 2.0)
    assert np.allclose(wall.mesh.bounds, [[-0.25, -2.5, 0.0], [0.25, 2.5, 2.0]])
    barrier = cs.Obstacle.barrier(10.0)
    assert barrier.mesh.is_watertight and barrier.mesh.volume > 0
    assert barrier.mesh.volume == pytest.approx((0.61 + 0.15) / 2 * 0.81 * 10.0)
    kerb = cs.Obstacle.kerb(3.0)
    assert kerb.kind == "kerb" and kerb.mesh.volume == pytest.approx(3.0 * 0.3 * 0.15)
    for o in (cs.Obstacle.pole(0.3), cs.Obstacle.tree(0.5, stiffness=(1e4, 2e5))):
        assert o.mesh.is_watertight and o.mesh.bounds[0][2] == pytest.approx(0.0)
    tree = cs.Obstacle.tree(0.5, stiffness=(1e4, 2e5))
    assert tree.kind == "tree" and all(
        tree.stiffness.face(f) is not None for f in cs.vehicles.stiffness.FACES
    )
    with pytest.raises(cs.ParameterError, match="diameter = -0.3 m is invalid"):
        cs.Obstacle.pole(-0.3)
    with pytest.raises(cs.ParameterError, match="narrows upwards"):
        cs.Obstacle.barrier(5.0, top_width=1.0)


def test_an_obstacle_from_a_mesh_file(tmp_path) -> None:
    path = tmp_path / "block.stl"
    trimesh.creation.box(extents=(200.0, 100.0, 50.0)).export(path)
    o = cs.Obstacle.from_mesh(path, units="cm", ground=True)
    assert o.name == "block" and np.allclose(o.extents, [2.0, 1.0, 0.5])


def car_into_wall(restitution: float | None = None) -> tuple[cs.Scene, float]:
    v = 10.0
    car = cs.Vehicle.box(4.5, 1.8, 1.4, mass=1500.0, name="car")
    scene = cs.Scene()
    scene.add(car, (0.0, 0.0, 0.7), velocity=(v, 0.0, 0.0))
    scene.add_obstacle(cs.Obstacle.wall(5.0, 0.5, 2.0), (3.0, 0.0))
    if restitution is not None:
        scene.contact("car", "wall", restitution=restitution)
    return scene, v


@pytest.mark.parametrize("e", [None, 0.0, 0.4])
def test_a_box_car_into_a_wall_changes_its_velocity_by_one_plus_e_times_v(e) -> None:
    scene, v = car_into_wall(e)
    result = scene.run(0.3)
    assert result.vehicles == ["car"] and result.obstacles == ["wall"]
    assert result.is_obstacle("wall") and not result.is_obstacle("car")
    (imp,) = result.impacts
    assert imp.obstacle == "wall" and imp.moving == ("car",)
    restitution = scene.defaults["restitution"] if e is None else e
    dv = imp.delta_v["car"]
    assert dv[0] == pytest.approx(-(1.0 + restitution) * v, rel=1e-9)
    assert abs(dv[1]) < 1e-9 * v and abs(dv[2]) < 1e-9 * v
    assert "wall" not in imp.delta_v and math.isinf(imp.effective_mass["wall"])
    with pytest.raises(cs.SceneError, match="'wall' is a fixed obstacle: it has no delta-V"):
        imp.speed_change("wall")
    wall_track = result.trajectory("wall")
    assert np.all(wall_track.position == wall_track.position[0])


def test_obstacle_reports_are_valid_json_with_the_vehicle_taking_all_the_energy() -> None:
    scene, v = car_into_wall()
    result = scene.run(0.3)
    report = cs.report(result)
    text = report.to_json()
    assert "Infinity" not in text and "NaN" not in text
    data = json.loads(text)
    jsonschema.validate(data, report_schema())
    (imp,) = data["impacts"]
    assert imp["obstacle"]["name"] == "wall" and imp["obstacle"]["effective_mass"] is None
    assert [p["name"] for p in imp["parties"]] == ["car"]
    assert imp["energy"]["split_basis"] == "rigid obstacle"
    (party,) = imp["parties"]
    e = result.impacts[0].energy_dissipated
    # E = m v^2 (1 - e^2) / 2 for a full impact on a rigid wall; EES = sqrt(2 E / m)
    assert e == pytest.approx(0.5 * 1500.0 * v * v * (1 - 0.1**2), rel=1e-9)
    assert party["energy"]["ees"] == pytest.approx(math.sqrt(2 * e / 1500.0), rel=1e-12)
    assert data["scene"]["obstacles"][0]["kind"] == "wall"
    assert json.loads(json.dumps(result.to_dict()))["obstacles"] == ["wall"]
    assert "wall is a fixed obstacle" in str(report)


@pytest.mark.parametrize("heading_deg, side, face", [(0.0, "-x", "rear"), (90.0, "+y", "left")])
def test_a_poles_struck_side_is_named_in_its_frame(heading_deg, side, face) -> None:
    # Was: "pole is a fixed obstacle ...; struck face: rear": the engine names the face of the
    # obstacle's frame turned to the car with a vehicle's words (stiffness.rs Face::facing;
    # world/geometry.rs); the report now says which side of its frame that is.
    scene = cs.Scene()
    scene.add(cs.Vehicle.box(4.5, 1.8, 1.4, mass=1500.0, name="car"), (0.0, 0.0, 0.7),
              velocity=(10.0, 0.0, 0.0))  # fmt: skip
    scene.add_obstacle(cs.Obstacle.pole(0.3), (3.0, 0.2), heading=math.radians(heading_deg))
    report = cs.report(scene.run(0.3))
    (imp,) = report.impacts
    assert imp.obstacle.struck_face == face and imp.obstacle.struck_side == side
    text = str(report)
    assert "pole is a fixed obstacle" in text and f"struck on its {side} side" in text
    assert "struck face: rear" not in text and "struck face: left" not in text
    data = json.loads(report.to_json())
    jsonschema.validate(data, report_schema())
    assert data["impacts"][0]["obstacle"]["struck_side"] == side


def test_an_obstacle_with_stiffness_gives_an_automatic_depth_of_penetration() -> None:
    car = cs.Vehicle.box(
        4.5, 1.8, 1.4, mass=1500.0, name="car", stiffness=cs.vehicle_class("sedan").stiffness
    )
    # some faces only: refused, saying how to fix it
    scene = cs.Scene(depth_of_penetration="auto")
    scene.add(car, (0.0, 0.0, 0.7), velocity=(10.0, 0.0, 0.0))
    front_only = cs.Obstacle.wall(5.0, stiffness={"front": (1e5, 5e6)})
    with pytest.raises(cs.ParameterError, match="obstacle 'wall': it has no stiffness on its rear"):
        scene.add_obstacle(front_only, (3.0, 0.0)).run(0.3)
    stiff = cs.Scene(depth_of_penetration="auto")
    stiff.add(car, (0.0, 0.0, 0.7), velocity=(10.0, 0.0, 0.0))
    stiff.add_obstacle(cs.Obstacle.wall(5.0, stiffness=(1e5, 5e6)), (3.0, 0.0))
    (imp,) = stiff.run(0.3).impacts
    assert imp.depth_of_penetration_mode == "auto" and 0.0 < imp.depth_of_penetration <= 0.06


def test_an_obstacle_without_stiffness_is_rigid_in_the_spring_model() -> None:
    # issue 19.8: auto dt_p and the stiffness centroid against an obstacle without stiffness
    # (before: a ParameterError). dt_p = sqrt(m / (B W)) from the car's front alone (central:
    # m' = m; W = the car's 1.8 m), P on the wall's face; the report's k' is the car's.
    b = cs.vehicle_class("sedan").stiffness.front.B
    car = cs.Vehicle.box(
        4.5, 1.8, 1.4, mass=1500.0, name="car", stiffness=cs.vehicle_class("sedan").stiffness
    )
    scene = cs.Scene(depth_of_penetration="auto", centroid="stiffness")
    scene.add(car, (0.0, 0.0, 0.7), velocity=(10.0, 0.0, 0.0))
    scene.add_obstacle(cs.Obstacle.wall(5.0), (3.0, 0.0))  # its face at x = 2.85 m
    result = scene.run(0.3)
    (imp,) = result.impacts
    assert imp.spring_rates == {"car": pytest.approx(b * 1.8, rel=1e-12), "wall": math.inf}
    assert imp.depth_of_penetration == pytest.approx(math.sqrt(1500.0 / (b * 1.8)), abs=2e-9)
    assert imp.centroid[0] == pytest.approx(2.85, abs=1e-9)
    report = cs.report(result)
    (ir,) = report.impacts
    assert ir.energy_split_basis == "rigid obstacle"
    assert ir.series_stiffness == pytest.approx(b * 1.8, rel=1e-12)
    assert ir.implied_depth_of_penetration == pytest.approx(imp.depth_of_penetration, abs=2e-9)
    assert ir.obstacle is not None and ir.obstacle.spring_rate is None
    text = report.to_json()
    assert "Infinity" not in text and "NaN" not in text
    jsonschema.validate(json.loads(text), report_schema())


def test_obstacle_names_pairs_and_overlaps() -> None:
    scene = cs.Scene()
    scene.add(cs.Vehicle.box(4.5, 1.8, 1.4, mass=1500.0, name="car"), (0.0, 0.0, 0.7))
    pole = cs.Obstacle.pole(0.3)
    scene.add_obstacle(pole, (10.0, 0.0)).add_obstacle(pole.renamed("pole2"), (12.0, 0.0))
    with pytest.raises(cs.SceneError, match="named 'car' is already in the scene"):
        scene.add_obstacle(pole.renamed("car"), (20.0, 0.0))
    with pytest.raises(cs.SceneError, match="two obstacles never meet"):
        scene.contact("pole", "pole2")
    assert [p[:2] for p in scene.pairs()] == [("car", "pole"), ("car", "pole2")]
    scene.add_obstacle(cs.Obstacle.wall(3.0).renamed("inside"), (0.0, 0.0))
    with pytest.raises(cs.InitialOverlapError, match="'car' and 'inside' already overlap"):
        scene.run(0.1)


def test_the_fcl_cross_check_re_tests_contacts_with_obstacles() -> None:
    pytest.importorskip("fcl")
    scene, _ = car_into_wall()
    check = cs.cross_check(scene.run(0.3))
    assert check.ok and len(check.checks) == 2


def test_a_vehicle_placed_into_the_ground_is_refused_by_name() -> None:
    """A box car whose CG height puts its body 0.15 m into the road (the ground's contact
    would throw it up) is an InitialOverlapError naming the vehicle and the depth."""
    car = cs.Vehicle.box(4.5, 1.8, 1.4, mass=1450.0, name="red").with_wheels(
        wheelbase=2.7, track=1.5, radius=0.3, cg_to_front_axle=1.2, cg_height=0.55,
    )  # the body reaches 0.7 m below the CG, which is 0.55 m up
    scene = cs.Scene(ground=cs.Ground())
    scene.add(car, (0.0, 0.0), heading=0.0)
    into = r"vehicle 'red': it starts 0\.150 m into the ground"
    with pytest.raises(cs.InitialOverlapError, match=into):
        scene.run(0.1)
