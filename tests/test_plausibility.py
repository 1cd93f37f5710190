"""Plausibility checks of vehicles (crashsim.vehicles.plausibility): impossible input is a
typed error, implausible input a PlausibilityWarning naming the likely mistake, and every
shared mesh and generator preset passes silently (pytest turns warnings into errors)."""

from __future__ import annotations

import warnings
from pathlib import Path

import crashsim as cs
import numpy as np
import pytest
import trimesh
from conftest import mesh_mass
from crashsim.vehicles import plausibility

CAR = (4.6, 1.8, 1.4)  # m: a car-sized closed box, 11.6 m^3


def car_box(scale: float = 1.0) -> trimesh.Trimesh:
    """A closed car-sized box standing on the ground, in units of 1/scale m."""
    mesh = trimesh.creation.box(extents=CAR)
    mesh.apply_translation([0.0, 0.0, CAR[2] / 2])
    mesh.apply_scale(scale)
    return mesh


def as_file(mesh: trimesh.Trimesh, tmp_path: Path, name: str = "car.ply") -> Path:
    path = tmp_path / name
    mesh.export(path)
    return path


# -- wrong units --------------------------------------------------------------------------------


def test_mesh_in_metres_read_as_cm_is_refused_naming_the_unit(tmp_path: Path) -> None:
    # Was: a 4.6 cm, 1450 kg car ran and reported 8 impacts.
    path = as_file(car_box(), tmp_path)
    with pytest.raises(cs.ParameterError) as error:
        cs.Vehicle.from_mesh(path, mass=1450.0, units="cm")
    text = str(error.value)
    assert "denser than any material" in text and "kg/m^3" in text
    assert "length 0.046 m outside 1-30 m" in text
    assert "if the file is not in cm, pass units='m' (4.6 x 1.8 x 1.4 m)" in text
    assert isinstance(error.value, ValueError)


def test_mesh_in_mm_read_as_metres_is_refused_naming_mm(tmp_path: Path) -> None:
    path = as_file(car_box(1000.0), tmp_path)  # 4600 x 1800 x 1400 mm
    with pytest.raises(cs.ParameterError, match="lighter than air") as error:
        cs.Vehicle.from_mesh(path, mass=1450.0)
    assert "pass units='mm' (4.6 x 1.8 x 1.4 m)" in str(error.value)
    v = cs.Vehicle.from_mesh(path, mass=1450.0, units="mm")
    assert np.allclose(v.extents, CAR)


def test_mesh_in_feet_read_as_metres_warns_naming_ft(tmp_path: Path) -> None:
    path = as_file(car_box(1.0 / 0.3048), tmp_path)  # 15.1 x 5.9 x 4.6 ft
    with pytest.warns(cs.PlausibilityWarning) as record:
        v = cs.Vehicle.from_mesh(path, mass=1450.0)
    assert len(record) == 1
    text = str(record[0].message)
    assert "width 5.91 m outside 0.3-5 m" in text and "pass units='ft' (4.6 x 1.8 x 1.4 m)" in text
    assert "1450 kg in 409.4 m^3 (the mesh volume) is 3.54 kg/m^3, below the 25 kg/m^3" in text
    assert 'filterwarnings("ignore", category=crashsim.PlausibilityWarning)' in text
    assert v.mass == 1450.0  # possible, so it is built


def test_absurd_scale_is_a_mesh_error_not_a_runtime_warning(tmp_path: Path) -> None:
    # Was: "encloses no volume" after a RuntimeWarning from trimesh's vertex merging.
    huge = car_box(1e12)
    with pytest.raises(cs.MeshError, match=r"coordinate of 2\.3e\+12, beyond the 1e\+09"):
        cs.Vehicle.from_mesh(huge, mass=1450.0)
    with pytest.raises(cs.MeshError, match="coordinate of 2.3e"):
        cs.Vehicle.from_mesh(as_file(huge, tmp_path), mass=1450.0)
    with pytest.raises(cs.MeshError, match="coordinate of 2.3e"):
        cs.load_mesh(huge)
    with pytest.raises(cs.MeshError, match="longer than 10 km"):  # 46 km: 0.1 mm read as m
        cs.Vehicle.from_mesh(car_box(1e4), mass=1450.0)
    with pytest.raises(cs.MeshError, match="no vehicle is shorter than 1 mm"):
        cs.Vehicle.from_mesh(car_box(1e-12), mass=1450.0)
    with pytest.raises(cs.MeshError, match="shorter than 1 mm"):  # before merging collapses it
        cs.load_mesh(car_box(1e-9))


# -- wrong axes -----------------------------------------------------------------------------------


def file_frame(mesh: trimesh.Trimesh, up: str, forward: str) -> trimesh.Trimesh:
    """The model-frame mesh written as a file with these up and forward axes would hold it."""
    out = mesh.copy()
    transform = np.eye(4)
    transform[:3, :3] = cs.meshio.axes_rotation(up, forward).T  # model -> file
    out.apply_transform(transform)
    return out


def test_y_up_truck_warns_naming_up_y() -> None:
    truck = trimesh.creation.box(extents=(5.66, 2.47, 1.87))
    y_up = file_frame(truck, up="y", forward="z")
    with pytest.warns(cs.PlausibilityWarning) as record:
        cs.Vehicle.from_mesh(y_up, mass=2200.0)  # read as z-up: 2.47 x 1.87 x 5.66 m
    text = str(record[0].message)
    assert "2.47 x 1.87 x 5.66 m" in text
    assert "the longest extent (5.66 m) is vertical (the file's z axis, read as up)" in text
    assert "is the mesh y-up? pass up='y' and forward='z' (or '-z')" in text
    v = cs.Vehicle.from_mesh(y_up, mass=2200.0, up="y", forward="z")  # the fix: silent
    assert np.allclose(v.extents, [5.66, 2.47, 1.87])


def test_sideways_mesh_warns_naming_forward() -> None:
    car = trimesh.creation.box(extents=CAR)
    sideways = file_frame(car, up="z", forward="-y")
    with pytest.warns(cs.PlausibilityWarning, match="is its front along y.*forward='y'"):
        cs.Vehicle.from_mesh(sideways, mass=1450.0)
    cs.Vehicle.from_mesh(sideways, mass=1450.0, forward="-y")


def test_size_findings_of_a_y_up_mesh_in_wrong_units_name_both() -> None:
    found = plausibility.size_findings([9.7, 7.3, 22.3], scale=1.0, units="m")
    assert len(found) == 2 and "is the mesh y-up?" in found[0]
    assert "fit no road vehicle in any orientation" in found[1] and "units='ft'" in found[1]


# -- density ------------------------------------------------------------------------------------


def test_density_below_road_vehicles_warns() -> None:
    bus = trimesh.creation.box(extents=(12.5, 2.55, 3.2))  # 102 m^3
    with pytest.warns(cs.PlausibilityWarning, match=r"1500 kg in 102 m\^3 .* is 14.7 kg/m\^3"):
        cs.Vehicle.from_mesh(bus, mass=1500.0)
    cs.Vehicle.from_mesh(bus, mass=12000.0)  # a real bus's mass: silent


def test_density_above_road_vehicles_warns() -> None:
    with pytest.warns(cs.PlausibilityWarning, match="above the 2000 kg/m"):
        cs.Vehicle.from_mesh(car_box(), mass=30_000.0)  # 2590 kg/m^3


def test_density_impossible_is_refused() -> None:
    with pytest.raises(cs.ParameterError, match=r"lighter than air.*1.45 t would be mass=1450"):
        cs.Vehicle.from_mesh(car_box(), mass=1.45)
    with pytest.raises(cs.ParameterError, match="denser than any material"):
        cs.Vehicle.from_mesh(car_box(), mass=1e6)


def test_density_of_an_open_mesh_with_given_cg_and_inertia_uses_its_convex_hull() -> None:
    car = car_box()
    open_car = trimesh.Trimesh(car.vertices, car.faces[2:])  # two triangles missing
    given = {"cg": (0.0, 0.0, 0.6), "inertia": np.diag([500.0, 2500.0, 2700.0])}
    with pytest.warns(cs.PlausibilityWarning, match=r"in 11.59 m\^3 \(its convex hull\)"):
        cs.Vehicle.from_mesh(open_car, mass=200.0, **given)
    cs.Vehicle.from_mesh(open_car, mass=1450.0, **given)


# -- possible but unusual: a warning that can be silenced ------------------------------------------


def test_road_train_and_toy_warn_but_build() -> None:
    train = trimesh.creation.box(extents=(40.0, 2.55, 4.0))
    with pytest.warns(cs.PlausibilityWarning, match="length 40 m outside 1-30 m"):
        v = cs.Vehicle.from_mesh(train, mass=60_000.0)
    assert v.mass == 60_000.0
    toy = trimesh.creation.box(extents=(0.3, 0.15, 0.1))
    with pytest.warns(cs.PlausibilityWarning, match="length 0.3 m outside"):
        cs.Vehicle.from_mesh(toy, mass=1.0)
    with warnings.catch_warnings():
        warnings.filterwarnings("ignore", category=cs.PlausibilityWarning)  # as the message says
        assert cs.Vehicle.from_mesh(toy, mass=1.0).mass == 1.0


def test_plausibility_warning_is_exported_and_a_user_warning() -> None:
    assert cs.PlausibilityWarning is cs.errors.PlausibilityWarning
    assert issubclass(cs.PlausibilityWarning, UserWarning)
    assert "PlausibilityWarning" in cs.__all__


# -- inertia -----------------------------------------------------------------------------------


def test_inertia_izz_above_ixx_plus_iyy_is_refused() -> None:
    impossible = np.diag([500.0, 2000.0, 3000.0])
    for build in (
        lambda: cs.Vehicle.box(*CAR, mass=1450.0, inertia=impossible),
        lambda: cs.Vehicle.from_mesh(car_box(), mass=1450.0, cg=(0, 0, 0.7), inertia=impossible),
        lambda: cs.Vehicle(car_box(), 1450.0, (0, 0, 0.7), impossible),
    ):
        with pytest.raises(cs.ParameterError) as error:
            build()
        text = str(error.value)
        assert "about body z (yaw, Izz), 3000 kg m^2, exceeds the sum of the other two" in text
        assert "500 + 2000 = 2500 kg m^2" in text and "Izz too large" in text


def test_inertia_triangle_inequality_in_principal_axes_and_at_the_limit() -> None:
    c, s = np.cos(0.4), np.sin(0.4)
    turn = np.array([[1.0, 0.0, 0.0], [0.0, c, -s], [0.0, s, c]])
    tilted = turn @ np.diag([400.0, 500.0, 1000.0]) @ turn.T  # Ixx 1000 > 900 about a tilt
    with pytest.raises(cs.ParameterError, match="about body x .roll, Ixx., 1000 kg m"):
        plausibility.check_inertia(np.diag([1000.0, 400.0, 500.0]))
    with pytest.raises(cs.ParameterError, match=r"about the principal axis \[0.0, -0.389"):
        plausibility.check_inertia(tilted)
    plausibility.check_inertia(np.diag([1.0, 2.0, 3.0]))  # a flat body: equality
    plausibility.check_inertia(np.diag([1.0, 2.0, 3.0 * (1 + 1e-7)]))  # within the tolerance
    with pytest.raises(cs.ParameterError):
        plausibility.check_inertia(np.diag([1.0, 2.0, 3.0 * (1 + 1e-5)]))


def test_empirical_rule_with_a_long_wheelbase_is_refused_with_a_hint() -> None:
    # 3 WB^2 = 27 > L^2 + W^2 + 2 H^2 = 21.8: the rule's Izz exceeds the box's Ixx + Iyy
    with pytest.raises(cs.ParameterError, match="'empirical' rule gave this tensor.*shorter"):
        cs.Vehicle.box(4.0, 1.7, 1.2, mass=1200.0, inertia="empirical", wheelbase=3.0)
    cs.Vehicle.box(4.0, 1.7, 1.2, mass=1200.0, inertia="empirical", wheelbase=2.5)


def test_generated_body_much_longer_than_its_wheelbase_is_refused_with_a_hint() -> None:
    # the class rule: Izz from the class at the wheelbase, Iyy from the 40 m long body
    with pytest.raises(cs.ParameterError, match="'class' rule.*wheelbase in proportion"):
        cs.Vehicle.generate("bus", length=40.0)


# -- what must stay silent ------------------------------------------------------------------------


def test_shared_meshes_are_plausible(mesh_path: Path) -> None:
    # warnings are errors: any PlausibilityWarning fails this
    v = cs.Vehicle.from_mesh(mesh_path, mass=mesh_mass(mesh_path))
    given = cs.Vehicle.from_mesh(mesh_path, mass=mesh_mass(mesh_path), cg=v.cg, inertia=v.inertia)
    assert given.sources == {"cg": "user", "inertia": "user"}


@pytest.mark.parametrize("preset", cs.generator.PRESETS)
def test_generator_presets_are_plausible(preset: str) -> None:
    v = cs.Vehicle.generate(preset)
    volume = float(v.mesh.volume)
    assert plausibility.DENSITY_PLAUSIBLE[0] < v.mass / volume < plausibility.DENSITY_PLAUSIBLE[1]
    for inertia in ("mesh", "empirical"):
        cs.Vehicle.generate(preset, inertia=inertia)
