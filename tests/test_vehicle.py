"""Vehicles: boxes (analytic mass properties), the shared real meshes (published extents and
triangle counts), mass properties from trimesh, scene flattening, and the input checks."""

from __future__ import annotations

import math
from pathlib import Path

import crashsim as cs
import numpy as np
import pytest
import trimesh

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


def test_from_mesh_of_an_open_mesh_uses_its_convex_hull() -> None:
    mesh = trimesh.creation.box(extents=(4.0, 2.0, 1.0))
    open_mesh = trimesh.Trimesh(mesh.vertices, mesh.faces[:-2])  # one side left open
    assert not open_mesh.is_volume
    v = cs.Vehicle.from_mesh(open_mesh, mass=1000.0)
    assert v.sources == {"cg": "convex hull", "inertia": "convex hull"}
    assert np.allclose(v.cg, 0.0, atol=1e-12)
    assert np.allclose(v.inertia, uniform_box_inertia(1000.0, 4.0, 2.0, 1.0), rtol=1e-12)
    assert len(v.mesh.faces) == 10  # the hull is for mass properties only


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
    v = cs.Vehicle.from_mesh(mesh_path, mass=1500.0)
    assert v.name == mesh_path.stem
    assert len(v.mesh.faces) == triangles
    assert np.allclose(v.extents, extents, rtol=0, atol=0.01), v.extents
    # front +x, centred in x and y, ground at z = 0 (README)
    assert v.mesh.bounds[0, 2] == pytest.approx(0.0, abs=1e-6)
    assert np.allclose(v.mesh.bounds.sum(axis=0)[:2], 0.0, atol=0.02)
    moments = np.linalg.eigvalsh(v.inertia)
    assert np.all(moments > 0)
    assert v.sources["cg"] in ("mesh volume", "convex hull")
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
    v = cs.Vehicle(mesh, mass=1.0, cg=(0, 0, 0), inertia=np.eye(3), name="broken")
    with pytest.raises(cs.MeshError, match="only 3 vertices"):
        _ = v.shape
