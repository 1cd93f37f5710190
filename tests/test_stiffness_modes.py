"""Face stiffness in the engine: depth_of_penetration="auto" (dt_p = sqrt(m'/k')) and
centroid="stiffness" (C1 : C2 = k2 : k1), against the seed's spring model computed here
independently (crashsim.analysis.penetration), and their errors and warnings."""

from __future__ import annotations

import crashsim as cs
import pytest
from crashsim.analysis import penetration
from crashsim.scene import DepthOfPenetrationWarning

A = 35_000.0  # N/m, any pre-load: dt_p depends on B only


def stiff(front: float, rear: float, side: float) -> dict[str, tuple[float, float]]:
    return {"front": (A, front), "rear": (A, rear), "side": (A, side)}


def rear_end(b_front1: float, b_rear2: float, v: float = 15.0, **contact) -> cs.Result:
    """A 1500 kg 4.5 x 1.8 x 1.4 m box at v m/s into the rear of a 1200 kg 4.2 x 1.7 x 1.2 m
    box at rest (0.1 m off the ground so the CGs are level at 0.7 m) and in line: a central
    impact 1.7 m wide."""
    bullet = cs.Vehicle.box(
        4.5, 1.8, 1.4, mass=1500.0, name="bullet", stiffness=stiff(b_front1, 8e5, 5e5)
    )
    target = cs.Vehicle.box(
        4.2,
        1.7,
        1.2,
        mass=1200.0,
        name="target",
        ground_clearance=0.1,
        stiffness=stiff(1.1e6, b_rear2, 5e5),
    )
    scene = cs.Scene(**contact)
    scene.add(bullet, position=(-4.5, 0.0, 0.7), velocity=(v, 0.0, 0.0))
    scene.add(target, position=(0.0, 0.0, 0.7))
    return scene.run(duration=0.3, dt=1e-3)


@pytest.mark.parametrize(("b1", "b2"), [(1.0e6, 0.6e6), (0.5e6, 0.5e6), (0.4e6, 1.5e6)])
def test_auto_exchanges_sqrt_of_reduced_mass_over_series_stiffness(b1: float, b2: float) -> None:
    v, width = 15.0, 1.7
    result = rear_end(b1, b2, v, depth_of_penetration="auto")
    imp = result.impacts[0]
    expected = penetration.depth_of_penetration_from_b(1500.0, 1200.0, b1, b2, width)
    # The engine bisects the fixed point dt = sqrt(m'/k')(dt) to 1e-9 s.
    assert imp.depth_of_penetration == pytest.approx(expected, abs=2e-9)
    assert imp.depth_of_penetration_mode == "auto"
    assert imp.struck_faces == {"bullet": "front", "target": "rear"}
    assert imp.overlap_width == pytest.approx(width, abs=1e-12)
    assert imp.spring_rates == pytest.approx({"bullet": b1 * width, "target": b2 * width})
    assert imp.effective_mass == pytest.approx({"bullet": 1500.0, "target": 1200.0}, rel=1e-12)
    travel = (
        result.state_at("bullet", imp.time)["position"][0]
        - result.state_at("bullet", imp.first_contact_time)["position"][0]
    )
    assert travel == pytest.approx(v * expected, abs=1e-6)  # m


def test_auto_outside_10_to_60_ms_warns_and_says_so_in_the_impact() -> None:
    # Stiff faces: sqrt(m'/k') about 7 ms, below the typical range.
    with pytest.warns(DepthOfPenetrationWarning, match="outside the typical 10-60 ms"):
        result = rear_end(2e7, 2e7, depth_of_penetration="auto")
    imp = result.impacts[0]
    assert imp.depth_of_penetration < 0.010
    assert any("outside the typical" in n for n in imp.notes)
    # Soft faces: clamped to the accepted 60 ms.
    with pytest.warns(DepthOfPenetrationWarning, match="clamped to 60 ms"):
        result = rear_end(1e4, 1e4, depth_of_penetration="auto")
    assert result.impacts[0].depth_of_penetration == pytest.approx(0.060, abs=1e-12)


@pytest.mark.parametrize(("b1", "b2"), [(1.0e6, 0.6e6), (0.7e6, 0.7e6), (0.3e6, 1.2e6)])
def test_stiffness_centroid_splits_the_crush_as_k2_to_k1(b1: float, b2: float) -> None:
    v, dtp = 15.0, 0.030
    result = rear_end(b1, b2, v, depth_of_penetration=dtp, centroid="stiffness")
    imp = result.impacts[0]
    front1 = result.state_at("bullet", imp.time)["position"][0] + 2.25  # m, bullet's front
    rear2 = -2.1  # m, the target's undeformed rear face
    total = front1 - rear2  # the overlap depth along n
    assert total == pytest.approx(v * dtp, abs=1e-6)  # t0 is resolved to 1e-9 s
    c1, c2 = front1 - imp.centroid[0], imp.centroid[0] - rear2
    e1, e2 = penetration.crush_split(total, b1, b2)  # k = B W, W common
    assert c1 == pytest.approx(e1, abs=1e-9) and c2 == pytest.approx(e2, abs=1e-9)
    assert c1 * b1 == pytest.approx(c2 * b2, rel=1e-9)  # Newton's third law, k1 C1 = k2 C2
    assert imp.centroid[1:] == pytest.approx([0.0, 0.7], abs=1e-12)


def test_effective_masses_of_an_eccentric_impact() -> None:
    # The target (4.2 x 2.0 x 1.5 m) rides 0.5 m off the ground, so the overlap spans
    # z = 0.5-1.4 m and its centre (0.95 m) lies 0.25 m above the bullet's CG and 0.3 m below
    # the target's: both are struck off their CG. The normal is along x, so only pitch acts and
    # the seed's planar gamma = k_g^2 / (k_g^2 + h^2) with k_g^2 = Iyy/m is exact.
    s = stiff(1e6, 1e6, 1e6)
    bullet = cs.Vehicle.box(4.5, 1.8, 1.4, mass=1500.0, name="bullet", stiffness=s)
    target = cs.Vehicle.box(
        4.2, 2.0, 1.5, mass=1200.0, name="target", ground_clearance=0.5, stiffness=s
    )
    scene = cs.Scene(depth_of_penetration="auto")
    scene.add(bullet, position=(-4.5, 0.0, 0.7), velocity=(15.0, 0.0, 0.0))
    scene.add(target, position=(0.0, 0.0, 1.25))
    result = scene.run(duration=0.3, dt=1e-3)
    imp = result.impacts[0]
    assert imp.normal == pytest.approx([1.0, 0.0, 0.0], abs=1e-12)
    assert imp.overlap_width == pytest.approx(1.8, abs=1e-12)
    for vehicle, lever in ((bullet, 0.25), (target, -0.3)):
        cg = result.state_at(vehicle.name, imp.time)["position"]  # same pose as before it
        r = imp.centroid - cg
        assert r[1:] == pytest.approx([0.0, lever], abs=1e-12)
        gamma = penetration.effective_mass_factor(vehicle.mass, vehicle.inertia[1, 1], lever)
        assert gamma < 0.97  # really eccentric (0.967 and 0.953)
        assert imp.effective_mass[vehicle.name] == pytest.approx(gamma * vehicle.mass, rel=1e-9)
        # and the independent 3-D form
        expected = penetration.effective_mass_along(vehicle.mass, vehicle.inertia, r, imp.normal)
        assert imp.effective_mass[vehicle.name] == pytest.approx(expected, rel=1e-9)
    m1, m2 = imp.effective_mass["bullet"], imp.effective_mass["target"]
    k1, k2 = imp.spring_rates["bullet"], imp.spring_rates["target"]
    assert imp.depth_of_penetration == pytest.approx(
        penetration.depth_of_penetration(m1, m2, k1, k2), abs=2e-9
    )


def test_stiffness_modes_need_stiffness_on_both_vehicles() -> None:
    bare = cs.Vehicle.box(4.5, 1.8, 1.4, mass=1500.0, name="bare")
    full = cs.Vehicle.box(4.5, 1.8, 1.4, mass=1500.0, name="full", stiffness=stiff(1, 1, 1))
    for kwargs in ({"depth_of_penetration": "auto"}, {"centroid": "stiffness"}):
        scene = cs.Scene()
        scene.add(full, position=(-5.0, 0.0, 0.7))
        scene.add(bare, position=(0.0, 0.0, 0.7))
        with pytest.raises(cs.ParameterError, match="vehicle 'bare': it has no stiffness"):
            scene.contact(full, bare, **kwargs)
        defaults = cs.Scene(**kwargs)
        defaults.add(full, position=(-5.0, 0.0, 0.7)).add(bare, position=(0.0, 0.0, 0.7))
        with pytest.raises(cs.ParameterError, match="vehicle 'bare': it has no stiffness"):
            defaults.run(duration=0.1)
    with pytest.raises(cs.ParameterError, match="depth_of_penetration"):
        cs.Scene(depth_of_penetration="automatic")
