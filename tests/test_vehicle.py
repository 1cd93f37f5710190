"""Vehicles: boxes (analytic mass properties), the shared real meshes (published extents and
triangle counts), mass properties from trimesh, scene flattening, and the input checks."""

from __future__ import annotations

import math
from pathlib import Path

import crashsim as cs
import numpy as np
import pytest
import trimesh
from conftest import mesh_mass
from crashsim.vehicles.stiffness import FaceStiffness, Stiffness

# From ../shared/meshes/README.md: triangles and L x W x H (m), published to 1 cm.
PUBLISHED = {
    "sedan_quaternius_normalcar1": (2954, (4.22, 1.81, 1.18)),
    "suv_quaternius_suv": (3294, (4.21, 2.11, 1.53)),
    "hatchback_gazebo": (788, (4.00, 2.14, 1.57)),
    "pickup_gazebo": (1084, (5.66, 2.47, 1.87)),
    "van_gazebo_ambulance": (1080, (7.54, 2.97, 2.89)),
    "bus_gazebo": (1040, (12.49, 2.71, 3.70)),
}


def uniform_box_inertia(m: float, length: float, w: float, h: float) -> np.ndarray:
    return np.diag(
        [m / 12 * (w * w + h * h), m / 12 * (length**2 + h * h), m / 12 * (length**2 + w * w)]
    )


# -- boxes -----------------------------------------------------------------------------------


def test_box_has_the_analytic_inertia_and_a_closed_mesh() -> None:
    v = cs.Vehicle.box(length=4.5, width=1.8, height=1.4, mass=1500.0, name="b")
    assert np.allclose(v.inertia, uniform_box_inertia(1500.0, 4.5, 1.8, 1.4), rtol=1e-14, atol=0)
    assert v.inertia[0, 0] == pytest.approx(1500.0 / 12 * (1.8**2 + 1.4**2), rel=1e-15)
    assert v.mesh.is_watertight and v.mesh.is_volume
    assert np.array_equal(v.cg, [0.0, 0.0, 0.7])
    assert np.allclose(v.mesh.bounds, [[-2.25, -0.9, 0.0], [2.25, 0.9, 1.4]], rtol=0, atol=1e-15)
    assert v.sources == {"cg": "uniform box", "inertia": "uniform box"}
    assert (v.name, v.mass) == ("b", 1500.0)
    # trimesh's own mass properties of the same mesh: moment_inertia is about the centre of
    # mass for density 1, so scaling by mass / volume gives the same tensor
    trimesh_inertia = v.mesh.moment_inertia * (1500.0 / v.mesh.mass)
    assert np.allclose(trimesh_inertia, v.inertia, rtol=1e-12, atol=1e-9)
    assert v.shape.n_triangles == 12 and v.shape.n_vertices == 8
    mins, maxs = v.shape.aabb()  # body frame: origin at the CG
    assert np.allclose(mins, [-2.25, -0.9, -0.7]) and np.allclose(maxs, [2.25, 0.9, 0.7])


def test_box_ground_clearance_and_cg_height() -> None:
    v = cs.Vehicle.box(4.0, 1.8, 1.2, mass=1000.0, ground_clearance=0.15, cg_height=0.55)
    assert np.allclose(v.mesh.bounds, [[-2.0, -0.9, 0.15], [2.0, 0.9, 1.35]], atol=1e-15)
    assert np.array_equal(v.cg, [0.0, 0.0, 0.55])
    # parallel axes: the uniform box about a point 0.2 m below its centre
    expected = uniform_box_inertia(1000.0, 4.0, 1.8, 1.2) + 1000.0 * 0.2**2 * np.diag([1, 1, 0])
    assert np.allclose(v.inertia, expected, rtol=1e-14, atol=1e-12)
    assert v.sources == {"cg": "user", "inertia": "uniform box"}
    assert v.name == "box"


def test_box_with_a_user_inertia() -> None:
    v = cs.Vehicle.box(4.8, 1.8, 1.45, mass=1621.2, inertia=np.diag([600.0, 2900.0, 3167.5]))
    assert np.array_equal(v.inertia, np.diag([600.0, 2900.0, 3167.5]))
    assert v.sources == {"cg": "uniform box", "inertia": "user"}


def test_body_frame_is_the_model_frame_shifted_to_the_cg() -> None:
    v = cs.Vehicle.box(4.0, 2.0, 1.0, mass=1.0, cg_height=0.3)
    assert np.array_equal(v.body_vertices, v.mesh.vertices - [0.0, 0.0, 0.3])
    assert np.array_equal(v.shape.vertices, v.body_vertices)
    assert v.shape is v.shape  # built once, cached


def test_arrays_are_read_only_and_renamed_shares_the_shape() -> None:
    v = cs.Vehicle.box(4.0, 2.0, 1.0, mass=1.0, name="a")
    with pytest.raises(ValueError):
        v.cg[0] = 1.0
    with pytest.raises(ValueError):
        v.inertia[0, 0] = 1.0
    w = v.renamed("b")
    assert (w.name, v.name) == ("b", "a") and w.shape is v.shape and w.mass == v.mass


# -- mass properties from meshes ---------------------------------------------------------------


def test_from_mesh_of_a_closed_mesh_uses_its_volume() -> None:
    mesh = trimesh.creation.box(extents=(4.0, 2.0, 1.0))
    mesh.apply_translation([0.3, -0.2, 0.5])
    v = cs.Vehicle.from_mesh(mesh, mass=1000.0)
    assert v.name == "vehicle"
    assert np.allclose(v.cg, [0.3, -0.2, 0.5], atol=1e-12)
    assert np.allclose(v.inertia, uniform_box_inertia(1000.0, 4.0, 2.0, 1.0), rtol=1e-12)
    assert v.sources == {"cg": "mesh volume", "inertia": "mesh volume"}
    # the vehicle owns a copy: editing the input later changes nothing
    mesh.apply_translation([5.0, 0.0, 0.0])
    assert np.allclose(v.mesh.bounds[0], [-1.7, -1.2, 0.0], atol=1e-12)


def test_from_mesh_quality_report_is_kept_not_printed(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    # The README said from_mesh prints a quality report: a library function prints nothing;
    # vehicle.quality holds the report and print(vehicle.quality) shows it.
    path = tmp_path / "car.ply"
    trimesh.creation.box(extents=(4.0, 2.0, 1.0)).export(path)
    v = cs.Vehicle.from_mesh(path, mass=1000.0)
    assert capsys.readouterr() == ("", "")
    assert isinstance(v.quality, cs.MeshQuality) and v.quality.watertight
    print(v.quality)
    out = capsys.readouterr().out
    assert out.startswith("12 triangles, 8 vertices, 4.000 x 2.000 x 1.000 m\n")
    assert "watertight: yes" in out and "volume: 8 m^3" in out
    readme = (Path(__file__).resolve().parents[1] / "README.md").read_text(encoding="utf-8")
    assert "print(vehicle.quality)" in readme and "prints a mesh-quality report" not in readme


def test_from_mesh_of_an_open_mesh_uses_its_winding_solid_or_its_convex_hull() -> None:
    mesh = trimesh.creation.box(extents=(4.0, 2.0, 1.0))
    open_mesh = trimesh.Trimesh(mesh.vertices, mesh.faces[:-2])  # one side left open
    assert not open_mesh.is_volume
    v = cs.Vehicle.from_mesh(open_mesh, mass=1000.0)  # the default: the winding-number solid
    assert v.sources == {"cg": "winding-number solid", "inertia": "winding-number solid"}
    # one face of six missing: the winding number is still above 1/2 in all but a thin
    # wedge near the hole; the grid (50k cells) resolves the box to a few cm
    assert np.allclose(v.cg, 0.0, atol=0.05)
    box = uniform_box_inertia(1000.0, 4.0, 2.0, 1.0)
    assert np.allclose(v.inertia, box, rtol=0.05, atol=5.0)
    hull = cs.Vehicle.from_mesh(open_mesh, mass=1000.0, solid="convex hull")
    assert hull.sources == {"cg": "convex hull", "inertia": "convex hull"}
    assert np.allclose(hull.cg, 0.0, atol=1e-12)
    assert np.allclose(hull.inertia, box, rtol=1e-12)
    assert len(v.mesh.faces) == 10  # the solid is for mass properties only


def test_user_cg_moves_the_mesh_inertia_by_parallel_axes() -> None:
    mesh = trimesh.creation.box(extents=(4.0, 2.0, 1.0))
    v = cs.Vehicle.from_mesh(mesh, mass=1000.0, cg=(0.1, 0.0, -0.2))
    d = np.array([0.1, 0.0, -0.2])
    expected = uniform_box_inertia(1000.0, 4.0, 2.0, 1.0) + 1000.0 * (
        d @ d * np.eye(3) - np.outer(d, d)
    )
    assert np.allclose(v.inertia, expected, rtol=1e-12, atol=1e-9)
    assert v.inertia[0, 2] == pytest.approx(1000.0 * 0.02, rel=1e-12)  # -m dx dz
    assert v.sources == {"cg": "user", "inertia": "mesh volume"}
    given = cs.Vehicle.from_mesh(mesh, mass=1000.0, cg=(0, 0, 0), inertia=np.eye(3) * 7.0)
    assert given.sources == {"cg": "user", "inertia": "user"}
    assert np.array_equal(given.inertia, np.eye(3) * 7.0)


def test_a_scene_file_is_flattened_with_its_transforms(tmp_path: Path) -> None:
    scene = trimesh.Scene()
    scene.add_geometry(trimesh.creation.box(extents=(2.0, 1.0, 1.0)))
    moved = trimesh.transformations.translation_matrix([3.0, 0.0, 0.0])
    scene.add_geometry(trimesh.creation.box(extents=(2.0, 1.0, 1.0)), transform=moved)
    path = tmp_path / "two_boxes.glb"
    scene.export(path)
    v = cs.Vehicle.from_mesh(path, mass=100.0)
    assert v.name == "two_boxes"
    assert len(v.mesh.faces) == 24
    assert np.allclose(v.mesh.bounds, [[-1.0, -0.5, -0.5], [4.0, 0.5, 0.5]], atol=1e-6)
    # an in-memory scene too
    assert len(cs.Vehicle.from_mesh(scene, mass=100.0).mesh.faces) == 24


def test_an_stl_soup_is_merged_as_trimesh_would(tmp_path: Path) -> None:
    path = tmp_path / "box.stl"
    trimesh.creation.box(extents=(4.0, 2.0, 1.0)).export(path)
    v = cs.Vehicle.from_mesh(path, mass=1000.0, name="stl")
    assert len(v.mesh.vertices) == 8 and v.mesh.is_volume
    assert v.sources["inertia"] == "mesh volume"
    assert np.allclose(v.inertia, uniform_box_inertia(1000.0, 4.0, 2.0, 1.0), rtol=1e-12)


# -- the shared real meshes ---------------------------------------------------------------------


def test_shared_mesh_loads_with_the_published_size(mesh_path: Path) -> None:
    triangles, extents = PUBLISHED[mesh_path.stem]
    v = cs.Vehicle.from_mesh(mesh_path, mass=mesh_mass(mesh_path))
    assert v.name == mesh_path.stem
    assert len(v.mesh.faces) == triangles
    assert np.allclose(v.extents, extents, rtol=0, atol=0.01), v.extents
    # front +x, centred in x and y, ground at z = 0 (README)
    assert v.mesh.bounds[0, 2] == pytest.approx(0.0, abs=1e-6)
    assert np.allclose(v.mesh.bounds.sum(axis=0)[:2], 0.0, atol=0.02)
    moments = np.linalg.eigvalsh(v.inertia)
    assert np.all(moments > 0)
    assert v.sources["cg"] in ("mesh volume", "winding-number solid")
    # yaw radius of gyration between 0.2 and 0.35 of the length (a solid box: 0.3)
    k_yaw = math.sqrt(v.inertia[2, 2] / v.mass) / extents[0]
    assert 0.2 < k_yaw < 0.35
    assert v.shape.n_triangles == triangles


# -- input checks ---------------------------------------------------------------------------------


@pytest.mark.parametrize("mass", [0.0, -1.0, float("nan"), float("inf"), "heavy"])
def test_bad_mass_is_a_parameter_error(mass) -> None:
    with pytest.raises(cs.ParameterError, match="mass") as box_error:
        cs.Vehicle.box(4.0, 1.8, 1.4, mass=mass)
    assert isinstance(box_error.value, ValueError)
    with pytest.raises(cs.ParameterError, match="mass"):
        cs.Vehicle.from_mesh(trimesh.creation.box(), mass=mass)


@pytest.mark.parametrize(
    "inertia, match",
    [
        (np.diag([1.0, 1.0, -1.0]), "not positive definite"),
        (np.zeros((3, 3)), "not positive definite"),
        ([[1.0, 0.5, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]], "not symmetric"),
        (np.eye(2), "3x3"),
        (np.diag([1.0, np.nan, 1.0]), "non-finite"),
    ],
)
def test_bad_inertia_is_a_parameter_error(inertia, match) -> None:
    with pytest.raises(cs.ParameterError, match=match) as error:
        cs.Vehicle.from_mesh(trimesh.creation.box(), mass=1.0, inertia=inertia)
    assert isinstance(error.value, ValueError)
    with pytest.raises(cs.ParameterError, match=match):
        cs.Vehicle.box(1.0, 1.0, 1.0, mass=1.0, inertia=inertia)


def test_bad_box_dimensions_are_parameter_errors() -> None:
    with pytest.raises(cs.ParameterError, match="dimensions"):
        cs.Vehicle.box(4.0, -1.8, 1.4, mass=1.0)
    with pytest.raises(cs.ParameterError, match="ground_clearance"):
        cs.Vehicle.box(4.0, 1.8, 1.4, mass=1.0, ground_clearance=-0.1)
    with pytest.raises(cs.ParameterError, match="cg"):
        cs.Vehicle.box(4.0, 1.8, 1.4, mass=1.0, cg_height=float("nan"))


def test_an_empty_mesh_is_a_mesh_error() -> None:
    empty = trimesh.Trimesh(vertices=np.zeros((3, 3)), faces=np.zeros((0, 3), dtype=np.int64))
    with pytest.raises(cs.MeshError, match="no triangles") as error:
        cs.Vehicle.from_mesh(empty, mass=1.0)
    assert isinstance(error.value, ValueError)


def test_a_nan_vertex_is_a_mesh_error() -> None:
    mesh = trimesh.creation.box()
    mesh.vertices[3] = [np.nan, 0.0, 0.0]
    with pytest.raises(cs.MeshError, match=r"non-finite.*vertex 3") as error:
        cs.Vehicle.from_mesh(mesh, mass=1.0, cg=(0, 0, 0), inertia=np.eye(3))
    assert isinstance(error.value, ValueError)


def test_unreadable_files_are_mesh_errors_naming_the_path(tmp_path: Path) -> None:
    missing = tmp_path / "nowhere" / "car.ply"
    with pytest.raises(cs.MeshError, match="car.ply") as error:
        cs.Vehicle.from_mesh(missing, mass=1.0)
    assert "check the path" in str(error.value)
    junk = tmp_path / "junk.ply"
    junk.write_text("not a ply file\n")
    with pytest.raises(cs.MeshError, match="junk.ply"):
        cs.Vehicle.from_mesh(junk, mass=1.0)
    unknown = tmp_path / "car.unknownformat"
    unknown.write_text("hello\n")
    with pytest.raises(cs.MeshError, match="car.unknownformat"):
        cs.Vehicle.from_mesh(unknown, mass=1.0)
    cloud = tmp_path / "cloud.ply"
    trimesh.PointCloud(np.random.default_rng(0).random((10, 3))).export(cloud)
    with pytest.raises(cs.MeshError, match="no triangles"):
        cs.Vehicle.from_mesh(cloud, mass=1.0)


def test_the_engine_refuses_broken_index_arrays() -> None:
    mesh = trimesh.Trimesh(np.eye(3), [[0, 1, 5]], process=False, validate=False)
    # the vehicle's mesh check refuses it first (its message names the face) ...
    with pytest.raises(cs.MeshError, match=r"face 0 = \[0, 1, 5\]"):
        cs.Vehicle(mesh, mass=1.0, cg=(0, 0, 0), inertia=np.eye(3), name="broken")
    # ... and the engine on its own still does
    with pytest.raises(cs.MeshError, match="only 3 vertices"):
        cs._core.Shape(np.eye(3), np.array([[0, 1, 5]]))


# -- mass: kg or lb ---------------------------------------------------------------------------


def test_weight_in_pounds_is_converted_exactly_and_reported() -> None:
    v = cs.Vehicle.box(4.8, 1.8, 1.45, weight_lb=3574.2)
    assert v.mass == 3574.2 * 0.45359237  # the pound-mass is exact
    assert v.mass == pytest.approx(1621.2, abs=0.05)  # reference-cases.md section 2
    assert v.mass_source == "weight in lb (3574.2 lb)"
    assert "[weight in lb (3574.2 lb)]" in v.summary()
    mesh = cs.Vehicle.from_mesh(trimesh.creation.box(extents=(4, 2, 1)), weight_lb=2000.0)
    assert mesh.mass == 2000.0 * 0.45359237
    assert cs.Vehicle.box(4.0, 1.8, 1.4, mass=1500.0).mass_source == "user"


def test_mass_and_weight_must_be_exactly_one() -> None:
    with pytest.raises(cs.ParameterError, match="conflict"):
        cs.Vehicle.box(4.0, 1.8, 1.4, mass=1500.0, weight_lb=3300.0)
    with pytest.raises(cs.ParameterError, match="conflict"):
        cs.Vehicle.from_mesh(trimesh.creation.box(), mass=1.0, weight_lb=2.2)
    with pytest.raises(cs.ParameterError, match="mass .kg. or weight_lb"):
        cs.Vehicle.from_mesh(trimesh.creation.box())
    with pytest.raises(cs.ParameterError, match="weight_lb"):
        cs.Vehicle.box(4.0, 1.8, 1.4, weight_lb="heavy")
    with pytest.raises(cs.ParameterError, match="mass"):
        cs.Vehicle.box(4.0, 1.8, 1.4, weight_lb=-3300.0)


# -- inertia: the empirical rule ----------------------------------------------------------------


def test_empirical_inertia_is_half_the_wheelbase_in_yaw_and_the_box_in_roll_and_pitch() -> None:
    mesh = trimesh.creation.box(extents=(4.5, 1.8, 1.4))
    mesh.apply_translation([0.0, 0.0, 0.7])
    v = cs.Vehicle.from_mesh(mesh, mass=1500.0, inertia="empirical", wheelbase=2.7)
    assert v.inertia[2, 2] == pytest.approx(1500.0 * 1.35**2, rel=1e-15)
    box = uniform_box_inertia(1500.0, 4.5, 1.8, 1.4)
    assert v.inertia[0, 0] == pytest.approx(box[0, 0], rel=1e-15)
    assert v.inertia[1, 1] == pytest.approx(box[1, 1], rel=1e-15)
    assert np.count_nonzero(v.inertia - np.diag(np.diag(v.inertia))) == 0
    assert v.sources == {"cg": "mesh volume", "inertia": "empirical"}
    assert "Izz = m (0.5 WB)^2 with WB = 2.700 m" in v.summary()
    b = cs.Vehicle.box(4.5, 1.8, 1.4, mass=1500.0, inertia="empirical", wheelbase=2.7)
    assert np.array_equal(b.inertia, v.inertia)
    assert b.sources == {"cg": "uniform box", "inertia": "empirical"}


def test_the_yaw_rule_on_the_measured_reference_cars() -> None:
    # reference-cases.md section 3: (mass kg, wheelbase m, measured yaw inertia kg m^2), whose
    # yaw radii of gyration are 0.47, 0.50, 0.52 WB; the rule (0.5 WB) is off by the factor
    # (0.5 / k)^2, i.e. between -9 % and +14 % on these cars
    cars = {"Escort": (1225.9, 2.393, 1538.9), "320i": (1093.3, 2.579, 1791.6)}
    cars["Vanagon"] = (1478.9, 2.472, 2473.1)
    ratios = []
    for mass, wb, measured in cars.values():
        k = math.sqrt(measured / mass) / wb
        rule = cs.vehicles.mass_properties.empirical_inertia(mass, wb, 4.5, 1.7, 1.4)[2, 2]
        assert rule == pytest.approx(mass * (0.5 * wb) ** 2, rel=1e-15)
        assert rule / measured == pytest.approx((0.5 / k) ** 2, rel=1e-12)
        ratios.append(rule / measured)
    assert np.round(ratios, 3).tolist() == [1.14, 1.015, 0.914]


def test_empirical_inertia_needs_a_sensible_wheelbase() -> None:
    box = trimesh.creation.box(extents=(4.5, 1.8, 1.4))
    with pytest.raises(cs.ParameterError, match="needs the wheelbase"):
        cs.Vehicle.from_mesh(box, mass=1.0, inertia="empirical")
    with pytest.raises(cs.ParameterError, match="needs the wheelbase"):
        cs.Vehicle.box(4.5, 1.8, 1.4, mass=1.0, inertia="empirical")
    with pytest.raises(cs.ParameterError, match="only used by"):
        cs.Vehicle.from_mesh(box, mass=1.0, wheelbase=2.7)
    with pytest.raises(cs.ParameterError, match="only used by"):
        cs.Vehicle.box(4.5, 1.8, 1.4, mass=1.0, wheelbase=2.7)
    for bad in (2700.0, -2.7, 0.0, float("nan")):  # 2700: a wheelbase in mm
        with pytest.raises(cs.ParameterError, match="wheelbase"):
            cs.Vehicle.from_mesh(box, mass=1.0, inertia="empirical", wheelbase=bad)
    with pytest.raises(cs.ParameterError, match="inertia = 'guess' is unknown"):
        cs.Vehicle.from_mesh(box, mass=1.0, inertia="guess")
    with pytest.raises(cs.ParameterError, match="cg = 'empirical' is unknown"):
        cs.Vehicle.from_mesh(box, mass=1.0, cg="empirical")


# -- mass properties of open meshes: the solid that stands for them -------------------------------


def test_cg_and_inertia_mesh_mean_the_default() -> None:
    mesh = trimesh.creation.box(extents=(4.0, 2.0, 1.0))
    v = cs.Vehicle.from_mesh(mesh, mass=1000.0, cg="mesh", inertia="mesh")
    w = cs.Vehicle.from_mesh(mesh, mass=1000.0)
    assert np.array_equal(v.cg, w.cg) and np.array_equal(v.inertia, w.inertia)
    assert v.sources == w.sources == {"cg": "mesh volume", "inertia": "mesh volume"}


def boxes_and_a_sheet() -> trimesh.Trimesh:
    """Two disjoint closed boxes and an open sheet (a box without its top)."""
    a = trimesh.creation.box(extents=(2.0, 1.0, 1.0))
    b = trimesh.creation.box(extents=(1.0, 1.0, 1.0))
    b.apply_translation([3.0, 0.0, 0.5])
    sheet = trimesh.creation.box(extents=(1.0, 1.0, 1.0))
    sheet = trimesh.Trimesh(sheet.vertices, sheet.faces[sheet.face_normals[:, 2] < 0.5])
    sheet.apply_translation([0.0, 5.0, 0.0])
    return trimesh.util.concatenate([a, b, sheet])


def test_the_union_of_closed_shells_ignores_the_open_ones() -> None:
    mesh = boxes_and_a_sheet()  # 4.5 m long (x), 6 m wide (y): no vehicle, it warns
    with pytest.warns(cs.PlausibilityWarning, match="longest extent .* is across"):
        v = cs.Vehicle.from_mesh(mesh, mass=300.0, solid="closed shells")
    assert v.sources == {"cg": "closed shells", "inertia": "closed shells"}
    # volumes 2 and 1 m^3, centroids (0, 0, 0) and (3, 0, 0.5): mass 200 and 100 kg
    cg = np.array([1.0, 0.0, 1.0 / 6.0])
    assert np.allclose(v.cg, cg, rtol=0, atol=1e-12)
    expected = uniform_box_inertia(200.0, 2.0, 1.0, 1.0) + uniform_box_inertia(100.0, 1, 1, 1)
    for m, c in ((200.0, [0.0, 0.0, 0.0]), (100.0, [3.0, 0.0, 0.5])):
        d = np.array(c) - cg
        expected += m * (d @ d * np.eye(3) - np.outer(d, d))
    assert np.allclose(v.inertia, expected, rtol=1e-12, atol=1e-9)
    assert "closed shells: 2 of 3" in v.summary()
    # the convex hull takes the sheet in
    with pytest.warns(cs.PlausibilityWarning, match="longest extent .* is across"):
        hull = cs.Vehicle.from_mesh(mesh, mass=300.0, solid="convex hull")
    assert hull.sources["inertia"] == "convex hull" and hull.cg[1] > 1.0


def test_the_winding_number_solid_of_a_box_is_exact_on_its_grid() -> None:
    # the grid's cells tile the box exactly, so volume, centroid and inertia are exact
    mesh = trimesh.creation.box(extents=(4.0, 2.0, 1.0))
    mesh.apply_translation([0.5, 0.25, 0.5])
    volume, centroid, inertia = cs.vehicles.mass_properties._winding_solid(mesh, "box")
    assert volume == pytest.approx(8.0, rel=1e-12)
    assert np.allclose(centroid, [0.5, 0.25, 0.5], rtol=0, atol=1e-12)
    assert np.allclose(inertia, uniform_box_inertia(8.0, 4.0, 2.0, 1.0), rtol=1e-9)


def test_the_winding_number_solid_closes_a_small_hole() -> None:
    mesh = trimesh.creation.box(extents=(4.0, 2.0, 1.0)).subdivide().subdivide()
    mesh.apply_translation([0.0, 0.0, 0.5])
    holed = trimesh.Trimesh(mesh.vertices, mesh.faces[1:])  # one of 192 triangles missing
    assert not holed.is_watertight
    v = cs.Vehicle.from_mesh(holed, mass=800.0, solid="winding number")
    assert v.sources == {"cg": "winding-number solid", "inertia": "winding-number solid"}
    # the grid (about 50,000 cells) resolves the box to a fraction of a cell
    assert np.allclose(v.cg, [0.0, 0.0, 0.5], rtol=0, atol=0.01)
    assert np.allclose(v.inertia, uniform_box_inertia(800.0, 4.0, 2.0, 1.0), rtol=0.02, atol=2)
    # a closed mesh is always its own solid, whatever solid= says
    closed = cs.Vehicle.from_mesh(mesh, mass=800.0, solid="winding number")
    assert closed.sources["inertia"] == "mesh volume"
    with pytest.raises(cs.ParameterError, match="solid = 'voxels' is unknown"):
        cs.Vehicle.from_mesh(mesh, mass=800.0, solid="voxels")


def flat_sheet() -> trimesh.Trimesh:
    """A flat, open 2 x 1 m sheet of 4 triangles at z = 0.5."""
    v = [[0, 0, 0.5], [1, 0, 0.5], [2, 0, 0.5], [0, 1, 0.5], [1, 1, 0.5], [2, 1, 0.5]]
    return trimesh.Trimesh(v, [[0, 1, 4], [0, 4, 3], [1, 2, 5], [1, 5, 4]])


@pytest.mark.parametrize("solid", ["auto", "convex hull", "closed shells", "winding number"])
def test_mass_properties_of_a_mesh_without_volume_are_a_mesh_error(solid: str) -> None:
    sheet = flat_sheet()
    with pytest.raises(cs.MeshError, match="volume") as error:
        cs.Vehicle.from_mesh(sheet, mass=1.0, solid=solid, cg=(0, 0, 0))  # inertia "mesh"
    assert isinstance(error.value, ValueError)
    with pytest.raises(cs.MeshError, match="volume"):
        cs.Vehicle.from_mesh(sheet, mass=1.0, solid=solid, inertia=np.eye(3))  # cg "mesh"
    # the user's numbers or the empirical rule need no volume (a flat sheet is no vehicle:
    # it warns; a wheelbase of 1.2 m keeps the rule's tensor possible on this 2 x 1 m sheet)
    with pytest.warns(cs.PlausibilityWarning, match="height 0 m outside"):
        v = cs.Vehicle.from_mesh(
            sheet, mass=1.0, solid=solid, cg=(1, 0.5, 0.5), inertia="empirical", wheelbase=1.2
        )
    assert v.sources == {"cg": "user", "inertia": "empirical"}


def test_a_single_open_curved_sheet_has_no_closed_shell_but_a_winding_solid() -> None:
    # a spherical cap (less than a hemisphere): no closed shell. Its winding number is above
    # 1/2 near the cap and below it near the flat opening (0.35 at the sphere's centre), so
    # the solid is most of the cap's convex hull (the opening closed off)
    sphere = trimesh.creation.icosphere(subdivisions=3)
    cap = trimesh.Trimesh(sphere.vertices, sphere.faces[sphere.triangles_center[:, 2] > 0.3])
    with pytest.raises(cs.MeshError, match="no closed shell"):
        cs.Vehicle.from_mesh(cap, mass=1.0, solid="closed shells")
    lens = cs.vehicles.mass_properties._winding_solid(cap, "cap")[0]
    assert 0.85 < lens / cap.convex_hull.volume < 1.0


def test_a_closed_mesh_with_inward_faces_is_refused() -> None:
    box = trimesh.creation.box(extents=(4.0, 2.0, 1.0))
    inverted = trimesh.Trimesh(box.vertices, box.faces[:, ::-1])
    with pytest.raises(cs.MeshError, match="point inwards"):
        cs.Vehicle.from_mesh(inverted, mass=1000.0)


# -- geometry options through from_mesh ---------------------------------------------------------


def test_from_mesh_converts_units_and_axes(tmp_path: Path) -> None:
    mesh = trimesh.creation.box(extents=(180.0, 400.0, 140.0))  # cm, z up, -y forward
    path = tmp_path / "car_cm.obj"
    mesh.export(path)
    v = cs.Vehicle.from_mesh(path, mass=1500.0, units="cm", forward="-y", ground=True)
    assert np.allclose(v.extents, [4.0, 1.8, 1.4], atol=1e-9)  # the file's x is 1.8 m wide
    assert v.mesh.bounds[0, 2] == pytest.approx(0.0, abs=1e-12)
    assert np.allclose(v.cg, [0.0, 0.0, 0.7], atol=1e-9)
    with pytest.raises(cs.ParameterError, match="same axis"):
        cs.Vehicle.from_mesh(path, mass=1500.0, up="y", forward="y")
    with pytest.raises(cs.ParameterError, match="units"):
        cs.Vehicle.from_mesh(path, mass=1500.0, units="furlong")


# -- stiffness and the report ---------------------------------------------------------------------


def test_stiffness_is_kept_shown_and_checked() -> None:
    faces = {"front": (50_000.0, 1.2e6), "side": {"A": 20_000.0, "B": 5e5}}
    v = cs.Vehicle.box(4.5, 1.8, 1.4, mass=1500.0, stiffness=faces)
    assert v.stiffness.front == FaceStiffness(50_000.0, 1.2e6)
    assert v.stiffness.left == v.stiffness.right == FaceStiffness(20_000.0, 5e5)
    assert v.stiffness.rear is None
    assert "front A = 5e+04 N/m, B = 1.2e+06 N/m^2" in v.summary()
    assert v.renamed("b").stiffness is v.stiffness
    m = cs.Vehicle.from_mesh(trimesh.creation.box(), mass=500.0, stiffness=v.stiffness)
    assert m.stiffness is v.stiffness
    assert cs.Vehicle.box(1, 1, 1, mass=1.0).stiffness == Stiffness()
    assert "stiffness: no data" in cs.Vehicle.box(1, 1, 1, mass=1.0).summary()
    own = cs.Vehicle(trimesh.creation.box(), 1.0, (0, 0, 0), np.eye(3), stiffness=faces)
    assert own.stiffness == v.stiffness
    with pytest.raises(cs.ParameterError, match="unknown face 'roof'"):
        cs.Vehicle.box(1, 1, 1, mass=1.0, stiffness={"roof": (1.0, 1.0)})
    with pytest.raises(cs.ParameterError, match="stiffness B"):
        cs.Vehicle.from_mesh(trimesh.creation.box(), mass=1.0, stiffness={"rear": (1.0, -1.0)})


def test_renamed_keeps_every_source_and_the_quality() -> None:
    v = cs.Vehicle.box(4.8, 1.8, 1.45, weight_lb=3574.2, inertia="empirical", wheelbase=2.7)
    w = v.renamed("other")
    assert w.quality == v.quality and w.mass_source == v.mass_source
    assert w.summary().split("\n", 1)[1] == v.summary().split("\n", 1)[1]


def test_the_summary_names_every_source(mesh_path: Path) -> None:
    v = cs.Vehicle.from_mesh(mesh_path, mass=mesh_mass(mesh_path))
    text = v.summary()
    q = v.quality
    assert f"{q.shells} shells ({q.closed_shells} closed)" in text
    kind = "mesh volume" if q.watertight else "winding-number solid"
    assert text.count(f"[{kind} ") == 2 and "[user]" in text


def test_with_mass_scales_the_inertia_and_keeps_the_wheels_frequencies() -> None:
    """Vehicle.with_mass (a study's ``<vehicle>.mass`` path): the inertia scales with the
    mass (radii of gyration kept), explicit spring rates and damping scale with it (natural
    frequencies kept), wheels given by frequency are shared, the mesh and engine shape are
    shared, the original is untouched; a mass the engine refuses is a ParameterError."""
    car = cs.Vehicle.box(4.5, 1.8, 1.4, mass=1500.0, name="car").with_wheels(
        wheelbase=2.7, track=1.5, radius=0.3, cg_to_front_axle=1.2,
        spring_rates=30e3, damping=2.5e3)  # fmt: skip
    heavy = car.with_mass(1800.0)
    assert heavy.mass == 1800.0 and car.mass == 1500.0
    np.testing.assert_array_equal(heavy.inertia, np.asarray(car.inertia) * (1800.0 / 1500.0))
    assert heavy.shape is car.shape and heavy.name == "car"
    spec, base = heavy.wheels.spec(1800.0), car.wheels.spec(1500.0)
    np.testing.assert_allclose(spec["spring_rates"], base["spring_rates"] * 1.2, rtol=1e-15)
    np.testing.assert_allclose(spec["damping"], base["damping"] * 1.2, rtol=1e-15)
    by_frequency = cs.Vehicle.box(4.5, 1.8, 1.4, mass=1500.0).with_wheels(
        wheelbase=2.7, track=1.5, radius=0.3, cg_to_front_axle=1.2)  # fmt: skip
    assert by_frequency.with_mass(1600.0).wheels is by_frequency.wheels
    with pytest.raises(cs.ParameterError, match="mass"):
        car.with_mass(-5.0)
