"""The flatbed, tanker and rigid-truck presets (docs/joints.md, "Articulated vehicles";
docs/vehicle-data.md, "Combination classes"): each built from its class's numbers, parked with
the axle loads statics gives (and, for the rigid truck, the axle loads its source publishes),
and driven straight coupled and upright."""

from __future__ import annotations

import math

import crashsim as cs
import numpy as np
import pytest
from crashsim.errors import ParameterError
from crashsim.vehicles.combination_data import combination_class

G = 9.80665
EXACT = 1e-12  # positions and masses are the class's numbers: only round-off may differ


def _v(name: str, quantity: str) -> float:
    return combination_class(name)[quantity].value


def _axle_x(vehicle: cs.Vehicle) -> np.ndarray:
    """Each axle's x in the model frame (its left and right wheels share it)."""
    return np.unique(np.round(vehicle.wheels.centers[:, 0] + vehicle.cg[0], 9))[::-1]


def _front(vehicle: cs.Vehicle) -> float:
    return float(vehicle.mesh.bounds[1][0])


@pytest.mark.parametrize("laden", [True, False])
def test_the_flatbed_is_its_class(laden: bool) -> None:
    f = cs.Trailer.generate("flatbed", laden=laden)
    mass = _v("flatbed", "mass_laden" if laden else "mass")
    assert f.mass == pytest.approx(mass, rel=EXACT)
    front = _front(f)
    assert front == pytest.approx(_v("flatbed", "length") / 2, rel=EXACT)
    kingpin = f.cg + f.coupler.point
    assert front - kingpin[0] == pytest.approx(_v("flatbed", "kingpin_setback"), rel=EXACT)
    assert kingpin[2] == pytest.approx(1.1, rel=EXACT)  # the tractor class's fifth wheel
    x = _axle_x(f)
    group = _v("flatbed", "kingpin_setback") + _v("flatbed", "kingpin_to_axle_group")
    assert front - x.mean() == pytest.approx(group, rel=EXACT)
    assert x[0] - x[1] == pytest.approx(_v("flatbed", "axle_group_spread"), rel=EXACT)
    assert len(f.wheels.load_groups) == 0  # spread axles: two single axles, no equaliser
    # the CG mid-deck; its height the deck's and load's uniform solids': the deck from the
    # kingpin's 1.1 m to the deck height, the load 1.0 m (FLATBED_LOAD_HEIGHT) on it
    deck = _v("flatbed", "deck_height")
    empty = _v("flatbed", "mass")
    z = ((1.1 + deck) / 2 * empty + (deck + 0.5) * (mass - empty)) / mass
    assert f.cg == pytest.approx([0.0, 0.0, z], abs=1e-9)
    widths = f.wheels.centers[::2, 1] - f.wheels.centers[1::2, 1]
    assert widths == pytest.approx(_v("flatbed", "track"), rel=EXACT)


def test_the_tanker_is_its_class_and_needs_a_mass_empty() -> None:
    t = cs.Trailer.generate("tanker")
    assert t.mass == pytest.approx(_v("tanker", "mass_laden"), rel=EXACT)
    front = _front(t)
    assert 2 * front == pytest.approx(_v("tanker", "length"), rel=1e-9)
    assert front - (t.cg + t.coupler.point)[0] == pytest.approx(
        _v("tanker", "kingpin_setback"), rel=1e-9
    )
    # the barrel's axis: its width across, resting on the kingpin's 1.1 m
    assert t.cg == pytest.approx([0.0, 0.0, 1.1 + _v("tanker", "width") / 2], abs=1e-9)
    x = _axle_x(t)
    assert x[0] - x[1] == pytest.approx(_v("tractor_6x4", "tandem_spread"), rel=1e-9)
    assert len(t.wheels.load_groups) == 2  # a tandem sharing its load, each side
    widths = t.wheels.centers[::2, 1] - t.wheels.centers[1::2, 1]
    assert widths == pytest.approx(_v("tanker", "track"), rel=EXACT)
    with pytest.raises(ParameterError, match="no empty mass"):
        cs.Trailer.generate("tanker", laden=False)
    assert cs.Trailer.generate("tanker", laden=False, mass=7000.0).mass == 7000.0
    with pytest.raises(ParameterError, match="got height"):
        cs.Trailer.generate("tanker", height=3.0)


def test_the_rigid_truck_is_its_class_laden_to_18_t() -> None:
    r = cs.Vehicle.generate("rigid_truck")
    assert r.mass == _v("rigid_truck", "mass_max")
    front = _front(r)
    assert 2 * front == pytest.approx(_v("rigid_truck", "length"), rel=EXACT)
    x = _axle_x(r)
    assert front - x[0] == pytest.approx(_v("rigid_truck", "front_overhang"), rel=EXACT)
    assert x[0] - x[1] == pytest.approx(_v("rigid_truck", "wheelbase"), rel=EXACT)
    cg_behind = x[0] - r.cg[0]
    assert cg_behind == pytest.approx(_v("rigid_truck", "cg_to_front_axle_laden"), rel=1e-9)
    assert r.hitch is not None and r.hitch.kind == "ball"
    assert (r.cg + r.hitch.point)[0] == pytest.approx(-front + 0.05, rel=EXACT)
    assert list(r.wheels.steerable) == [True, True, False, False]
    assert cs.Vehicle.generate("rigid_truck", mass=9000.0).mass == 9000.0
    with pytest.raises(ParameterError, match="give width to crashsim.rigid_truck"):
        cs.Vehicle.generate("rigid_truck", width=2.5)


def test_a_parked_rigid_truck_carries_the_axle_loads_of_its_source() -> None:
    # cm1995: an 18 t two-axle rigid on a 7.5 t front and a 10.5 t drive axle; statics with
    # the class's CG gives the same (1 %).
    r = cs.Vehicle.generate("rigid_truck")
    scene = cs.Scene(ground=cs.Ground())
    scene.add(r, (0, 0), heading=0.0)
    loads = scene.run(1.0).wheels("rigid_truck").load[:, -1]
    front, rear = loads[:2].sum() / G, loads[2:].sum() / G
    wb = _v("rigid_truck", "wheelbase")
    cg = _v("rigid_truck", "cg_to_front_axle_laden")
    assert rear == pytest.approx(r.mass * cg / wb, rel=1e-2)
    assert front == pytest.approx(7500.0, rel=1e-2) and rear == pytest.approx(10500.0, rel=1e-2)


@pytest.mark.parametrize("preset", ["flatbed", "tanker"])
def test_a_parked_tractor_carries_the_semitrailers_kingpin_load_statics_gives(preset: str) -> None:
    tractor = cs.Vehicle.generate("tractor")
    trailer = cs.Trailer.generate(preset)
    scene = cs.Scene(ground=cs.Ground())
    scene.add(tractor, (0, 0), heading=0.0, trailers=[trailer])
    result = scene.run(1.0)
    kingpin = result.joints[f"tractor-{preset}"].force[-1, 2]
    assert kingpin == pytest.approx(trailer.wheels.coupling_load(trailer.mass), rel=1e-2)
    # statics of the trailer: its weight on the kingpin and its wheels, no moment about its CG
    # (the spread axles, each on its own springs, need both equations: 1 % of W and of W x L)
    loads = result.wheels(preset).load[:, -1]
    x = trailer.wheels.centers[:, 0]  # from the CG
    k = float(trailer.coupler.point[0])
    weight = trailer.mass * G
    assert loads.sum() + kingpin == pytest.approx(weight, rel=1e-2)
    assert abs(kingpin * k + (loads * x).sum()) < 1e-2 * weight * k
    if preset == "tanker":  # a tandem sharing its load: determinate, the group's middle
        span = k - x.mean()
        assert kingpin == pytest.approx(weight * -x.mean() / span, rel=1e-2)
    tractor_wheels = result.wheels("tractor").load[:, -1].sum()
    assert tractor_wheels == pytest.approx(tractor.mass * G + kingpin, rel=1e-2)


def _upright_and_coupled(result: cs.Result, names: list[str], joint: str) -> None:
    from crashsim.result import rotation_matrix

    for name in names:
        up = rotation_matrix(result.trajectory(name).orientation)[:, :, 2]
        assert np.degrees(np.arccos(np.clip(up[:, 2], -1, 1))).max() < 2.0, name
    gap = result.joints[joint]
    assert np.abs(gap.force[:, 2]).max() < 1e7  # finite, joined throughout
    assert result.impacts == [] and result.contacts == []


def test_the_rigid_truck_tows_a_centre_axle_trailer_straight_at_20_m_s() -> None:
    truck = cs.Vehicle.generate("rigid_truck", name="truck")
    hz = float((truck.cg + truck.hitch.point)[2])
    trailer = cs.Trailer.box(
        "centre_axle", length=6.0, width=2.4, height=2.0, mass=6000.0, ground_clearance=1.0,
        coupler=2.0, coupler_height=hz, axles=[2.6, 3.9], track=1.8, radius=0.45,
        cg_from_front=3.0, name="trailer",
    )
    scene = cs.Scene(ground=cs.Ground(friction=0.8))
    scene.add(truck, (0, 0), heading=0.0, velocity=(20, 0, 0), trailers=[trailer])
    result = scene.run(2.0)
    _upright_and_coupled(result, ["truck", "trailer"], "truck-trailer")
    # coupled: the trailer's coupler stays on the truck's ball (within 1 cm)
    from crashsim.result import rotation_matrix

    def world(name: str, point: np.ndarray) -> np.ndarray:
        tr = result.trajectory(name)
        return tr.position + rotation_matrix(tr.orientation) @ point

    gap = world("truck", truck.hitch.point) - world("trailer", trailer.coupler.point)
    assert np.linalg.norm(gap, axis=1).max() < 0.01
    assert result.trajectory("trailer").position[-1, 0] > 30.0  # it moved with the truck
    assert result.joints["truck-trailer"].force[-1, 2] == pytest.approx(
        trailer.wheels.coupling_load(trailer.mass), rel=5e-2
    )


def test_the_tractor_draws_the_laden_tanker_straight_at_20_m_s() -> None:
    tractor = cs.Vehicle.generate("tractor")
    tanker = cs.Trailer.generate("tanker")
    scene = cs.Scene(ground=cs.Ground(friction=0.8))
    scene.add(tractor, (0, 0), heading=0.0, velocity=(20, 0, 0), trailers=[tanker])
    result = scene.run(2.0)
    _upright_and_coupled(result, ["tractor", "tanker"], "tractor-tanker")
    assert math.isclose(
        result.trajectory("tanker").position[-1, 0] - result.trajectory("tanker").position[0, 0],
        40.0,
        rel_tol=2e-2,
    )
