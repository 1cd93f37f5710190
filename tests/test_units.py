"""Unit helpers: the exact definitions (1 ft = 0.3048 m, 1 mph = 0.44704 m/s,
1 lb = 0.45359237 kg, 1 km/h = 1/3.6 m/s) and their inverses."""

import math

import crashsim as cs
import numpy as np
import pytest
from crashsim import units


def test_the_factors_are_the_exact_definitions() -> None:
    assert units.FOOT == 0.3048
    assert units.MILE_PER_HOUR == 0.44704
    assert units.POUND == 0.45359237
    assert cs.ft(1.0) == 0.3048
    assert cs.ft_s(1.0) == 0.3048
    assert cs.mph(1.0) == 0.44704
    assert cs.lb(1.0) == 0.45359237
    assert cs.kmh(3.6) == 1.0
    assert cs.kmh(36.0) == 10.0
    assert cs.deg(180.0) == math.pi
    # 1 mph is exactly 5280 ft per 3600 s
    assert cs.mph(1.0) == pytest.approx(5280.0 * 0.3048 / 3600.0, rel=1e-15)


def test_the_seed_figures() -> None:
    # 30 mph = 44 ft/s = 13.4112 m/s; 60 mph = 88 ft/s; 0.4023 m = 1.32 ft
    assert cs.mph(30.0) == pytest.approx(13.4112, rel=1e-15)
    assert cs.ft_s(44.0) == pytest.approx(cs.mph(30.0), rel=1e-15)
    assert cs.ft_s(88.0) == pytest.approx(cs.mph(60.0), rel=1e-15)
    assert cs.ft(1.32) == pytest.approx(0.402336, rel=1e-15)
    # the barrier of reference case 2: 1e7 lb
    assert cs.lb(1e7) == pytest.approx(4535923.7, rel=1e-15)


@pytest.mark.parametrize(
    "forward, inverse, x",
    [
        (cs.mph, cs.to_mph, 39.9545),
        (cs.kmh, cs.to_kmh, 50.0),
        (cs.ft, cs.to_ft, 3.6209),
        (cs.ft_s, cs.to_ft_s, 44.0),
        (cs.lb, cs.to_lb, 3574.2),
        (cs.deg, cs.to_deg, 15.4),
    ],
)
def test_inverses_round_trip(forward, inverse, x) -> None:
    assert inverse(forward(x)) == pytest.approx(x, rel=2e-16)
    assert forward(inverse(x)) == pytest.approx(x, rel=2e-16)


def test_inverse_factors() -> None:
    assert cs.to_mph(13.4112) == pytest.approx(30.0, rel=1e-15)
    assert cs.to_kmh(10.0) == 36.0
    assert cs.to_ft(0.3048) == 1.0
    assert cs.to_lb(0.45359237) == 1.0
    assert cs.to_deg(math.pi) == 180.0


def test_helpers_work_elementwise_on_arrays() -> None:
    v = np.array([0.0, 30.0, 60.0])
    assert np.array_equal(cs.mph(v), v * 0.44704)
    assert np.array_equal(cs.units.to_ft(cs.ft(v)), v)
    assert cs.deg(np.array([90.0]))[0] == math.pi / 2
