"""Tests of the built-in vehicle-class table (crashsim.vehicles.vehicle_data).

Unit factors are written here from their exact definitions, independently of the module:
1 lb (mass) = 0.45359237 kg, 1 lbf = 4.4482216152605 N, 1 in = 0.0254 m, 1 ft = 0.3048 m.
"""

from __future__ import annotations

import math
import tomllib
from importlib import resources

import crashsim.vehicles.vehicle_data as vd
import pytest
from crashsim.errors import ParameterError
from crashsim.vehicles.stiffness import FaceStiffness, Stiffness

LBF = 4.4482216152605
LBM = 0.45359237
IN = 0.0254
FACTOR = {
    "m": 1.0,
    "kg": 1.0,
    "lb": LBM,
    "in": IN,
    "ft": 0.3048,
    "kg m^2": 1.0,
    "lb/in": LBF / IN,
    "lb/in^2": LBF / IN**2,
    "kN/m": 1e3,
    "kN/m^2": 1e3,
    "deg/g": math.pi / 180.0,  # roll per g of lateral acceleration: rad per g
}
REL = 1e-12  # conversions are exact products: only round-off may differ

# Plausible ranges per class, SI: (mass kg, length m, width m, height m, wheelbase m)
PLAUSIBLE = {
    "small_car": ((700, 1400), (3.4, 4.6), (1.5, 1.8), (1.2, 1.6), (2.2, 2.7)),
    "sedan": ((1100, 2000), (4.3, 5.2), (1.65, 1.95), (1.25, 1.6), (2.5, 3.0)),
    "large_car": ((1400, 2300), (4.8, 5.6), (1.75, 2.05), (1.25, 1.6), (2.7, 3.2)),
    "van": ((1400, 2600), (4.3, 5.6), (1.7, 2.1), (1.5, 2.2), (2.7, 3.5)),
    "suv": ((1300, 2800), (4.0, 5.8), (1.65, 2.1), (1.5, 2.1), (2.3, 3.3)),
    "pickup": ((1200, 3000), (4.4, 6.3), (1.6, 2.1), (1.5, 2.1), (2.6, 4.1)),
    "bus": ((8000, 20000), (10.0, 14.0), (2.4, 2.6), (2.8, 3.6), (5.0, 8.0)),
}
DIMS = ("mass", "length", "width", "height", "wheelbase")


def _raw() -> dict:
    path = resources.files("crashsim.vehicles").joinpath("data", "vehicle_classes.toml")
    return tomllib.loads(path.read_text(encoding="utf-8"))


def _all_figures():
    for name, vc in vd.vehicle_classes().items():
        for key, fig in vc.figures().items():
            yield name, key, fig


# --- interface ---------------------------------------------------------------------------------


def test_classes_in_stable_order_and_required_presets_present():
    names = list(vd.vehicle_classes())
    assert names == ["small_car", "sedan", "large_car", "van", "suv", "pickup", "bus"]
    assert names == list(vd.vehicle_classes())  # same order on every call
    for preset in ("sedan", "suv", "pickup", "van", "bus"):
        assert vd.vehicle_class(preset).name == preset


def test_aliases_and_case_resolve_to_the_same_class():
    assert vd.vehicle_class("mid_car") is vd.vehicle_class("sedan")
    assert vd.vehicle_class(" SUV ") is vd.vehicle_class("suv")
    assert vd.ALIASES["mid_car"] == "sedan"


def test_unknown_name_raises_parameter_error_listing_the_known_ones():
    with pytest.raises(ParameterError) as e:
        vd.vehicle_class("tank")
    msg = str(e.value)
    assert "tank" in msg
    for name in vd.vehicle_classes():
        assert name in msg
    assert isinstance(e.value, ValueError)
    with pytest.raises(ParameterError):
        vd.vehicle_class(3)  # type: ignore[arg-type]


def test_stiffness_property_maps_side_to_left_and_right():
    for vc in vd.vehicle_classes().values():
        s = vc.stiffness
        assert isinstance(s, Stiffness) and s.complete
        assert s.front == FaceStiffness(vc.front.A.value, vc.front.B.value)
        assert s.rear == FaceStiffness(vc.rear.A.value, vc.rear.B.value)
        assert s.left == s.right == FaceStiffness(vc.side.A.value, vc.side.B.value)


def test_figures_are_frozen_and_bounds_are_one_sd():
    f = vd.vehicle_class("sedan").mass
    with pytest.raises(AttributeError):
        f.value = 1.0  # type: ignore[misc]
    lo, hi = f.bounds()
    assert f.sd is not None
    assert lo == pytest.approx(f.value - f.sd, rel=REL)
    assert hi == pytest.approx(f.value + f.sd, rel=REL)
    g = vd.vehicle_class("pickup").width  # a single named vehicle: no sd
    assert g.sd is None and g.bounds() == (g.value, g.value)


# --- numbers -------------------------------------------------------------------------------------


def test_every_number_finite_positive_with_finite_positive_sd():
    n = 0
    for name, key, fig in _all_figures():
        assert math.isfinite(fig.value) and fig.value > 0.0, (name, key)
        if fig.sd is not None:
            assert math.isfinite(fig.sd) and fig.sd > 0.0, (name, key)
        n += 1
    assert n == 7 * 18


@pytest.mark.parametrize("name", list(PLAUSIBLE))
def test_plausible_ranges_and_geometric_consistency(name):
    vc = vd.vehicle_class(name)
    for key, (lo, hi) in zip(DIMS, PLAUSIBLE[name], strict=True):
        v = getattr(vc, key).value
        assert lo <= v <= hi, (name, key, v)
    assert vc.wheelbase.value < vc.length.value
    assert vc.width.value < vc.length.value
    assert 0.0 < vc.cg_to_front_axle.value < vc.wheelbase.value
    assert 0.25 * vc.height.value < vc.cg_height.value < 0.5 * vc.height.value
    # crush coefficients: A tens of kN/m, B hundreds of kN/m^2 (CRASH3 and NHTSA test ranges)
    for face in (vc.front, vc.rear, vc.side):
        assert 1e4 < face.A.value < 2e5
        assert 1e5 < face.B.value < 3e6


def test_yaw_radius_of_gyration_is_half_the_wheelbase_within_ten_percent():
    for vc in vd.vehicle_classes().values():
        ratio = vc.radius_of_gyration / vc.wheelbase.value
        assert 0.45 <= ratio <= 0.55, (vc.name, ratio)


def test_yaw_inertia_derived_by_the_rule_follows_it_exactly():
    raw = _raw()["classes"]
    derived = 0
    for name, vc in vd.vehicle_classes().items():
        rule = raw[name]["yaw_inertia"].get("gyration_ratio")
        if rule is None:  # measured (NHTSA database): must not claim to be derived by the rule
            assert vc.yaw_inertia.published["unit"] == "kg m^2"
            continue
        derived += 1
        expect = vc.mass.value * (rule * vc.wheelbase.value) ** 2
        assert vc.yaw_inertia.value == pytest.approx(expect, rel=REL)
        assert vc.yaw_inertia.derived
    assert derived == 5  # small_car, sedan, large_car, van, bus


def test_derived_cg_position_and_height_follow_their_stated_formulas():
    raw = _raw()["classes"]
    for name, vc in vd.vehicle_classes().items():
        frac = raw[name]["cg_to_front_axle"]["fraction"]
        assert vc.cg_to_front_axle.value == pytest.approx(frac * vc.wheelbase.value, rel=REL)
        h = raw[name]["cg_height"]
        if "fit" in h:
            slope, icpt = h["fit"]
            assert vc.cg_height.value == pytest.approx(slope * vc.mass.value + icpt, rel=REL)
        else:
            assert vc.cg_height.value == pytest.approx(h["height_ratio"] * vc.height.value, rel=REL)
    # the car fraction is the mean of the two measured CommonRoad cars (reference-cases.md 3)
    car = (0.884 / 2.393 + 1.156 / 2.579) / 2
    assert raw["sedan"]["cg_to_front_axle"]["fraction"] == pytest.approx(car, rel=REL)


# --- sources -------------------------------------------------------------------------------------


def test_every_source_is_a_key_or_a_derivation_and_every_ref_is_a_key():
    assert vd.SOURCES and all(v.strip() for v in vd.SOURCES.values())
    for name, key, fig in _all_figures():
        if fig.derived:
            assert len(fig.source) > len("derived: ") + 20, (name, key)
        else:
            assert fig.source in vd.SOURCES, (name, key, fig.source)
            assert fig.source in fig.refs
        for ref in fig.refs:
            assert ref in vd.SOURCES, (name, key, ref)
        # a derivation that names a source key must list it in refs
        for src in vd.SOURCES:
            if f" {src}" in fig.source or f"({src})" in fig.source:
                assert src in fig.refs, (name, key, src)


# --- conversions ---------------------------------------------------------------------------------


def test_si_values_reproduce_the_published_values():
    checked = 0
    for name, key, fig in _all_figures():
        pub = fig.published
        if not pub:
            continue
        f = FACTOR[pub["unit"]]
        if "value" in pub and "p5" not in pub:
            assert fig.value == pytest.approx(pub["value"] * f, rel=REL), (name, key)
            if "sd" in pub:
                assert fig.sd == pytest.approx(pub["sd"] * f, rel=REL), (name, key)
            else:
                assert fig.sd is None, (name, key)
            checked += 1
        elif "p5" in pub:  # median with its 5-95 % range: normal sd from the percentiles
            z95 = 1.6448536269514722
            assert fig.value == pytest.approx(pub["value"] * f, rel=REL)
            assert fig.sd == pytest.approx((pub["p95"] - pub["p5"]) * f / (2 * z95), rel=REL)
            checked += 1
        else:  # a published range: midpoint, sd of the uniform distribution over it
            lo, hi = pub["low"] * f, pub["high"] * f
            assert fig.value == pytest.approx((lo + hi) / 2, rel=REL)
            assert fig.sd == pytest.approx((hi - lo) / math.sqrt(12.0), rel=REL)
            checked += 1
    assert checked >= 60


def test_hand_worked_conversions():
    # CRASH3 Table 8-2 category 4 side: 143 lb/in, 50 lb/in^2
    sedan = vd.vehicle_class("sedan")
    assert sedan.side.A.value == pytest.approx(25043.13744, rel=1e-9)
    assert sedan.side.B.value == pytest.approx(344737.8647, rel=1e-9)
    # the pooled NHTSA frontal medians: 64 kN/m, 769 kN/m^2, on every class's front
    for vc in vd.vehicle_classes().values():
        assert (vc.front.A.value, vc.front.B.value) == (64000.0, 769000.0)
    # 40-foot bus: 41 ft = 12.4968 m, 102 in = 2.5908 m, 283.75 in = 7.20725 m
    bus = vd.vehicle_class("bus")
    assert bus.length.value == pytest.approx(12.4968, rel=REL)
    assert bus.width.value == pytest.approx(2.5908, rel=REL)
    assert bus.wheelbase.value == pytest.approx(7.20725, rel=REL)
    # 28,250 lb = 12,813.9844525 kg
    assert bus.mass.value == pytest.approx(12813.9844525, rel=REL)


def test_track_and_tyre_radius_follow_their_stated_derivations():
    """Track = width x the mean track/width ratio of the three CommonRoad vehicles
    (shared/data/reference-cases.md section 3, written out here); tyre radius = half the
    published overall diameter where one is given."""
    raw = _raw()["classes"]
    front = (1.390 / 1.674 + 1.387 / 1.610 + 1.574 / 1.844) / 3
    rear = (1.423 / 1.674 + 1.364 / 1.610 + 1.544 / 1.844) / 3
    for name, vc in vd.vehicle_classes().items():
        for key, ratio in (("track_front", front), ("track_rear", rear)):
            assert raw[name][key]["width_ratio"] == pytest.approx(ratio, rel=REL)
            assert getattr(vc, key).value == pytest.approx(ratio * vc.width.value, rel=REL)
            assert getattr(vc, key).derived
        assert 0.75 * vc.width.value < vc.track_front.value < vc.width.value
        radius = vc.tyre_radius
        assert 0.25 < radius.value < 0.6, name
        diameter = raw[name]["tyre_radius"].get("diameter")
        if diameter is not None:
            assert radius.value == pytest.approx(diameter["value"] * IN / 2, rel=REL)
    # the suv's Explorer tyre: 235/75R15, 28.9 in overall -> 0.36703 m
    assert vd.vehicle_class("suv").tyre_radius.value == pytest.approx(0.36703, rel=1e-12)
