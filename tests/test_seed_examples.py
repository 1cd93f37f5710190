"""The seed's worked examples (reference-cases.md section 1) through the Python API, with box
vehicles: with a 30 ms depth of penetration the bullet vehicle travels 1.32 ft (0.4023 m)
past first overlap at 30 mph and 2.64 ft (0.8047 m) at 60 mph before the impulse exchange,
whatever the time step."""

from __future__ import annotations

import crashsim as cs
import numpy as np
import pytest
from conftest import seed_side_impact

DEPTH_OF_PENETRATION = 0.030  # s


CASES = {
    # speed, heading of red (rad), red's start (x, y) m, travel published (m)
    "30 mph at 90 deg": (cs.mph(30.0), 0.0, (-3.65, 0.3), 0.4023),  # 1.32 ft
    # at 45 deg red's front-right corner leads; it reaches the side near y = -1.2 m
    "60 mph at 45 deg": (cs.mph(60.0), cs.deg(45.0), (-4.0, -3.0), 0.8047),  # 2.64 ft
}


@pytest.mark.parametrize("dt", [1e-3, 7e-3], ids=["dt=1ms", "dt=7ms"])
@pytest.mark.parametrize("case", list(CASES))
def test_travel_past_first_overlap(case: str, dt: float) -> None:
    speed, heading, start, published = CASES[case]
    result = seed_side_impact(speed, heading, start, dt)
    assert len(result.impacts) >= 1
    imp = result.impacts[0]
    assert imp.vehicles == ("red", "blue") and not imp.secondary
    # the exchange lands exactly depth_of_penetration after the first overlap
    assert imp.time - imp.first_contact_time == pytest.approx(DEPTH_OF_PENETRATION, abs=1e-9)
    assert imp.depth_of_penetration == pytest.approx(DEPTH_OF_PENETRATION, abs=1e-12)
    # the trajectory holds samples at both instants (the state at `time` is after the
    # exchange; the position is continuous through it)
    p0 = result.state_at("red", imp.first_contact_time)["position"]
    p1 = result.state_at("red", imp.time)["position"]
    travel = float(np.linalg.norm(p1 - p0))
    assert travel == pytest.approx(published, abs=1e-3)  # the seed's figure, to 1 mm
    assert travel == pytest.approx(speed * DEPTH_OF_PENETRATION, rel=1e-9)  # v dt_p
    assert cs.to_ft(travel) == pytest.approx(44.0 * speed / cs.mph(30.0) * 0.03, abs=1e-3)
    # it struck blue's left side: the normal is that face's inward normal, +x
    assert np.allclose(imp.normal, [1.0, 0.0, 0.0], rtol=0, atol=1e-9)


def test_first_overlap_instant_is_where_the_boxes_meet() -> None:
    # 90 deg: red's front (CG + 2.25 m) meets blue's side (x = -0.9 m) after 0.5 m of travel
    for dt in (1e-3, 7e-3):
        imp = seed_side_impact(cs.mph(30.0), 0.0, (-3.65, 0.3), dt).impacts[0]
        assert imp.first_contact_time == pytest.approx(0.5 / cs.mph(30.0), abs=1e-6)


def test_centroid_is_mid_crush_with_each_box_deformed_half_the_travel() -> None:
    # reference-cases.md: with boxes each bounding-box deformation is half of 0.4023 m
    result = seed_side_impact(cs.mph(30.0), 0.0, (-3.65, 0.3), 1e-3)
    imp = result.impacts[0]
    half = cs.mph(30.0) * DEPTH_OF_PENETRATION / 2.0
    # blue's side is at x = -0.9 m; red's front is 2 * half past it at the exchange. The
    # first overlap is bisected to 1e-9 s, i.e. 1.3e-8 m of red's travel: 1e-7 m tolerance.
    assert np.allclose(imp.centroid, [-0.9 + half, 0.3, 0.7], rtol=0, atol=1e-7)
    red_front = result.state_at("red", imp.time)["position"][0] + 2.25
    assert red_front - imp.centroid[0] == pytest.approx(half, abs=1e-7)  # red's crush
    assert imp.centroid[0] - (-0.9) == pytest.approx(half, abs=1e-7)  # blue's crush
    assert imp.region_max[0] == pytest.approx(red_front, abs=1e-9)  # region: n from -0.9 m
    assert imp.region_min[0] == pytest.approx(-0.9, abs=1e-9)
    assert half == pytest.approx(0.4023 / 2.0, abs=1e-3)
