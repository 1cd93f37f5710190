"""Units, vehicles from boxes and from the shared real meshes, and their input checks."""

import math

import crashsim as cs
import numpy as np
import pytest
import trimesh

# L x W x H (m) from ../shared/meshes/README.md
PUBLISHED_EXTENTS = {
    "sedan_quaternius_normalcar1": (4.22, 1.81, 1.18),
    "suv_quaternius_suv": (4.21, 2.11, 1.53),
    "hatchback_gazebo": (4.00, 2.14, 1.57),
    "pickup_gazebo": (5.66, 2.47, 1.87),
    "van_gazebo_ambulance": (7.54, 2.97, 2.89),
    "bus_gazebo": (12.49, 2.71, 3.70),
}


def test_unit_factors_are_exact():
    assert cs.mph(30.0) == 30.0 * 0.44704
    assert cs.ft(1.32) == 1.32 * 0.3048
    assert cs.ft_s(44.0) == 44.0 * 0.3048
    assert cs.lb(1.0) == 0.45359237
    assert cs.kmh(36.0) == pytest.approx(10.0, rel=1e-15)
    assert cs.deg(180.0) == math.pi
    assert cs.units.to_mph(cs.mph(42.0)) == pytest.approx(42.0, rel=1e-15)
    # the seed: 30 mph is 44 ft/s
    assert cs.units.to_ft_s(cs.mph(30.0)) == pytest.approx(44.0, rel=1e-15)


def test_box_vehicle_has_the_analytic_inertia_and_a_closed_mesh():
    v = cs.Vehicle.box(length=4.5, width=1.8, height=1.4, mass=1500.0, name="b")
    m, length, w, h = 1500.0, 4.5, 1.8, 1.4
    expected = np.diag(
        [
            m / 12 * (w * w + h * h),
            m / 12 * (length * length + h * h),
            m / 12 * (length * length + w * w),
        ]
    )
    assert np.allclose(v.inertia, expected, rtol=1e-14, atol=0)
    assert v.mesh.is_watertight
    assert np.allclose(v.cg, [0, 0, 0.7])
    # trimesh's own mass properties of the same box agree
    tm = v.mesh.moment_inertia * (m / v.mesh.mass)
    assert np.allclose(tm, expected, rtol=1e-12, atol=1e-9)
    assert v.shape.n_triangles == 12


def test_shared_meshes_load_with_the_published_extents(mesh_paths):
    for path in mesh_paths:
        v = cs.Vehicle.from_mesh(path, mass=1500.0)
        expected = PUBLISHED_EXTENTS[path.stem]
        assert np.allclose(v.extents, expected, atol=0.01), (path.stem, v.extents)
        assert np.all(np.linalg.eigvalsh(v.inertia) > 0)
        assert v.sources["inertia"].startswith(("mesh volume", "convex hull"))
        assert v.shape.n_triangles == len(v.mesh.faces)


def test_inertia_from_mesh_is_scaled_to_the_mass_and_moved_to_a_given_cg():
    box = trimesh.creation.box(extents=(4.0, 2.0, 1.0))
    v = cs.Vehicle.from_mesh(box, mass=1000.0, name="m")
    assert np.allclose(v.inertia, np.diag([1000 / 12 * 5, 1000 / 12 * 17, 1000 / 12 * 20]))
    shifted = cs.Vehicle.from_mesh(box, mass=1000.0, name="m", cg=(0.0, 0.0, -0.2))
    # parallel axes: +m d^2 about x and y for a vertical shift d = 0.2 m
    assert shifted.inertia[0, 0] == pytest.approx(1000 / 12 * 5 + 1000 * 0.04, rel=1e-12)
    assert shifted.inertia[2, 2] == pytest.approx(1000 / 12 * 20, rel=1e-12)
    assert shifted.sources["cg"] == "user"


@pytest.mark.parametrize("mass", [0.0, -1.0, float("nan"), float("inf")])
def test_bad_mass_is_a_parameter_error(mass):
    with pytest.raises(cs.ParameterError, match="mass"):
        cs.Vehicle.box(4.0, 1.8, 1.4, mass=mass)


def test_bad_inertia_and_meshes_are_typed_errors():
    with pytest.raises(cs.ParameterError, match="positive definite"):
        cs.Vehicle.box(4.0, 1.8, 1.4, 1000.0).__class__.from_mesh(
            trimesh.creation.box(), mass=1.0, inertia=np.diag([1.0, 1.0, -1.0])
        )
    with pytest.raises(cs.ParameterError, match="symmetric"):
        cs.Vehicle.from_mesh(
            trimesh.creation.box(), mass=1.0, inertia=[[1, 0.5, 0], [0, 1, 0], [0, 0, 1]]
        )
    empty = trimesh.Trimesh(vertices=np.zeros((3, 3)), faces=np.zeros((0, 3), dtype=int))
    with pytest.raises(cs.MeshError, match="no triangles"):
        cs.Vehicle.from_mesh(empty, mass=1.0)
    nan = trimesh.creation.box()
    nan.vertices[0] = [np.nan, 0, 0]
    with pytest.raises(cs.MeshError, match="non-finite"):
        cs.Vehicle.from_mesh(nan, mass=1.0, inertia=np.eye(3))
    with pytest.raises(cs.MeshError, match="no mesh file"):
        cs.Vehicle.from_mesh("/nonexistent/car.ply", mass=1.0)
    # every input error is also a ValueError
    assert issubclass(cs.MeshError, ValueError) and issubclass(cs.ParameterError, ValueError)
    assert issubclass(cs.InputError, cs.CrashsimError)


def test_core_shape_refuses_broken_arrays():
    from crashsim import _core

    v = np.zeros((3, 3))
    with pytest.raises(cs.MeshError):
        _core.Shape(v, np.array([[0, 1, 5]]))
    with pytest.raises(cs.MeshError):
        _core.Shape(v, np.array([[0, 1, -1]]))
    with pytest.raises(cs.MeshError):
        _core.Shape(np.zeros((3, 2)), np.array([[0, 1, 2]]))
