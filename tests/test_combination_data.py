"""Tests of the built-in combination-class table (crashsim.vehicles.combination_data).

Unit factors are written here from their exact definitions, independently of the module:
1 in = 0.0254 m, 1 ft = 0.3048 m, 1 lb = 0.45359237 kg, 1 t = 1000 kg. Every bound below names
the rule it comes from (the source keys are those of docs/vehicle-data.md, "Combination classes").
"""

from __future__ import annotations

import math
import tomllib
from importlib import resources

import crashsim.vehicles.combination_data as cd
import pytest
from crashsim.errors import ParameterError

IN = 0.0254
FT = 0.3048
LB = 0.45359237
FACTOR = {
    "m": 1.0,
    "kg": 1.0,
    "kg m^2": 1.0,
    "t": 1000.0,
    "cm": 0.01,
    "mm": 0.001,
    "in": IN,
    "ft": FT,
    "lb": LB,
    "%": 0.01,
}
REL = 1e-12  # conversions and rules are exact products: only round-off may differ

# Regulatory maxima, SI (eu_96_53: Directive 96/53/EC Annex I; transportxxl_dims: its B1 rule)
EU_MOTOR_VEHICLE_LENGTH = 12.00  # 1.1
EU_WIDTH, EU_WIDTH_CONDITIONED = 2.55, 2.60  # 1.2
EU_HEIGHT = 4.00  # 1.3
EU_KINGPIN_TO_REAR = 12.00  # 1.6
EU_ROAD_TRAIN_BODIES = 15.65  # 1.7: load length less the gap between the bodies
EU_KINGPIN_TO_FRONT = 2.04  # B1: kingpin axis to any point at the front of the semitrailer
EU_ARTICULATED_MASS = 40000.0  # transportxxl_weights: five or more axles, 40 t
EU_TWO_AXLE_MASS = 18000.0  # transportxxl_weights: two-axle lorry or trailer, 18 t
UNBRAKED_TRAILER_MASS = 750.0  # mersea_trailers
LIGHT_TRAILER_WIDTH = 2.55  # mersea_trailers
US_WIDTH, US_HEIGHT = 8.5 * FT, 13.5 * FT  # aashto_2018_us: WB-67
US_SEMITRAILER_LENGTH = 53.0 * FT  # aashto_2018_us: the WB-67's 53.0-ft trailer
CENTRE_AXLE_MAX_SHARE = 0.10  # iss_centre_axle: a centre-axle trailer's static vertical load
BOUND_SOURCES = {
    "eu_96_53",
    "transportxxl_dims",
    "transportxxl_weights",
    "mersea_trailers",
    "aashto_2018_us",
    "iss_centre_axle",
}


def _raw() -> dict:
    path = resources.files("crashsim.vehicles").joinpath("data", "combination_classes.toml")
    return tomllib.loads(path.read_text(encoding="utf-8"))


def _all_figures():
    for name, cls in cd.combination_classes().items():
        for key, fig in cls.figures.items():
            yield name, key, fig


def _v(name: str, quantity: str) -> float:
    return cd.combination_class(name)[quantity].value


# --- interface ---------------------------------------------------------------------------------


def test_classes_in_table_order_each_listing_its_quantities_in_table_order():
    names = list(cd.combination_classes())
    assert names == [
        "tractor_6x4",
        "rigid_truck",
        "box_van",
        "flatbed",
        "tanker",
        "caravan",
        "centre_axle_trailer",
        "drawbar_trailer",
    ]
    order = list(cd.QUANTITIES)
    for cls in cd.combination_classes().values():
        assert cls.quantities, cls.name
        positions = [order.index(q) for q in cls.quantities]  # every one a known quantity
        assert positions == sorted(positions), cls.name
    assert cd.combination_class(" Tractor_6x4 ") is cd.combination_class("tractor_6x4")


def test_unknown_name_raises_parameter_error_listing_the_known_ones():
    with pytest.raises(ParameterError) as e:
        cd.combination_class("road_train")
    msg = str(e.value)
    assert "road_train" in msg
    for name in cd.combination_classes():
        assert name in msg
    with pytest.raises(ParameterError):
        cd.combination_class(7)  # type: ignore[arg-type]


def test_a_quantity_not_sourced_raises_parameter_error_naming_those_carried():
    rigid = cd.combination_class("rigid_truck")
    assert "yaw_inertia" not in rigid and "wheelbase" in rigid
    with pytest.raises(ParameterError) as e:
        rigid["yaw_inertia"]
    msg = str(e.value)
    assert "rigid_truck" in msg and "yaw_inertia" in msg
    for q in rigid.quantities:
        assert q in msg


def test_classes_and_figures_are_frozen():
    cls = cd.combination_class("caravan")
    with pytest.raises(AttributeError):
        cls.name = "x"  # type: ignore[misc]
    with pytest.raises(TypeError):
        cls.figures["mass"] = cls.figures["mass_max"]  # type: ignore[index]
    lo, hi = cls["mass_max"].bounds()
    assert (lo, hi) == pytest.approx((1250.0 - 57.735026919, 1250.0 + 57.735026919), rel=1e-10)


def test_a_class_with_an_unknown_quantity_is_refused():
    with pytest.raises(ParameterError, match="unknown quantities"):
        cd._class("x", {"kind": "k", "description": "d", "speed": {}}, _raw()["quantities"])


# --- numbers and sources -----------------------------------------------------------------------


def test_every_number_finite_positive_with_finite_positive_sd():
    n = 0
    for name, key, fig in _all_figures():
        assert math.isfinite(fig.value) and fig.value > 0.0, (name, key)
        if fig.sd is not None:
            assert math.isfinite(fig.sd) and 0.0 < fig.sd < fig.value, (name, key)
        n += 1
    assert n == 15 + 11 + 12 + 10 + 6 + 10 + 6 + 2


def test_every_source_is_a_key_or_a_derivation_every_ref_a_key_every_key_used():
    assert cd.SOURCES and all(v.strip() for v in cd.SOURCES.values())
    used: set[str] = set()
    for name, key, fig in _all_figures():
        assert fig.refs, (name, key)
        if fig.derived:
            assert len(fig.source) > len("derived: ") + 20, (name, key)
        else:
            assert fig.source in cd.SOURCES, (name, key, fig.source)
            assert fig.source in fig.refs, (name, key)
        for ref in fig.refs:
            assert ref in cd.SOURCES, (name, key, ref)
        # a derivation that names a source key lists it in refs
        for src in cd.SOURCES:
            if f" {src}" in fig.source or f"({src})" in fig.source:
                assert src in fig.refs, (name, key, src)
        used.update(fig.refs)
    # no citation without a number or a bound of these tests resting on it
    assert BOUND_SOURCES <= set(cd.SOURCES)
    assert used | BOUND_SOURCES == set(cd.SOURCES)


def test_si_values_reproduce_the_published_values():
    checked = 0
    for name, key, fig in _all_figures():
        pub = fig.published
        if not pub:
            continue
        f = FACTOR[pub["unit"]]
        if "value" in pub:
            assert fig.value == pytest.approx(pub["value"] * f, rel=REL), (name, key)
            assert fig.sd is None, (name, key)
        else:  # a published range: midpoint, sd of the uniform distribution over it
            lo, hi = pub["low"] * f, pub["high"] * f
            assert fig.value == pytest.approx((lo + hi) / 2, rel=REL), (name, key)
            assert fig.sd == pytest.approx((hi - lo) / math.sqrt(12.0), rel=REL), (name, key)
        checked += 1
    assert checked == 60  # every figure but the 12 derived by a rule alone


def test_derived_figures_follow_their_stated_rules():
    raw = _raw()["classes"]
    rules = 0
    for name, key, fig in _all_figures():
        r = raw[name][key]
        if "axle_spacings" in r and key == "wheelbase":  # front axle to the tandem centre
            s = r["axle_spacings"]
            expect = s[0] + s[1] / 2
        elif "axle_spacings" in r:  # first to last axle of a group
            expect = sum(r["axle_spacings"])
        elif "fraction" in r:
            expect = r["fraction"] * _v(name, "wheelbase")
        elif "gyration_sq" in r:
            expect = r["gyration_sq"] * _v(name, "mass")
        elif "tyre_size" in r:  # tyre_rule: rim/2 + width x aspect
            width_mm, aspect, rim_in = r["tyre_size"]
            expect = rim_in * IN / 2 + width_mm / 1000 * aspect / 100
        elif "hitch_length" in r:
            expect = _v(name, "length") - r["hitch_length"]
        elif "axle_loads" in r:  # the rear axle's share of the axle loads, times the wheelbase
            front, rear = r["axle_loads"]
            expect = _v(name, "wheelbase") * rear / (front + rear)
        elif "payload_lb" in r:
            expect = _v(name, "mass") + r["payload_lb"] * LB
        elif "gross_lb" in r:  # the gross less the tractor class's mass
            expect = r["gross_lb"] * LB - _v("tractor_6x4", "mass")
        else:
            continue
        assert fig.derived, (name, key)
        assert fig.value == pytest.approx(expect, rel=REL), (name, key)
        rules += 1
    assert rules == 12
    # the published numbers behind them, written out (ghandriz2020, openpbs_registry)
    tractor = raw["tractor_6x4"]
    assert tractor["cg_to_front_axle"]["fraction"] == pytest.approx(1.4992 / 4.085, rel=REL)
    assert tractor["yaw_inertia"]["gyration_sq"] == pytest.approx(46711.6 / 10250.0, rel=REL)
    assert _v("tractor_6x4", "wheelbase") == pytest.approx(3.685, rel=REL)
    assert _v("tractor_6x4", "tyre_radius_front") == pytest.approx(0.536, rel=REL)
    assert _v("box_van", "kingpin_setback") == pytest.approx(1.6, rel=REL)
    # cm1995's 7.5 t + 10.5 t, hdt_flatbeds_2011's 48,000 lb payload, the 80,000 lb gross
    assert raw["rigid_truck"]["cg_to_front_axle_laden"]["axle_loads"] == [7.5, 10.5]
    assert _v("rigid_truck", "cg_to_front_axle_laden") == pytest.approx(6.1 * 10.5 / 18.0)
    assert _v("flatbed", "mass_laden") == pytest.approx((10250.0 + 48000.0) * LB, rel=REL)
    assert _v("tanker", "mass_laden") == pytest.approx(80000.0 * LB - 9875.0, rel=REL)


# --- physical and regulatory bounds ------------------------------------------------------------


def test_every_track_within_the_width_and_every_radius_of_gyration_within_the_unit():
    """A track between wheel centres is narrower than the unit; a radius of gyration about the
    centre of mass cannot exceed the farthest point of the unit, sqrt(L^2 + W^2) (a bound for
    any mass distribution within the footprint)."""
    for cls in cd.combination_classes().values():
        for t in ("track", "track_front", "track_rear"):
            if t in cls and "width" in cls:
                assert 0.5 * cls["width"].value < cls[t].value < cls["width"].value, cls.name
        for inertia, mass in (("yaw_inertia", "mass"), ("yaw_inertia_laden", "mass_laden")):
            if inertia in cls:
                k = math.sqrt(cls[inertia].value / cls[mass].value)
                assert k < math.hypot(cls["length"].value, cls["width"].value), cls.name
        if "cg_height" in cls:
            assert cls["cg_height"].value < cls["height"].value
        if "cg_height_laden" in cls:
            assert cls["cg_height_laden"].value < cls["height"].value
        for r in ("tyre_radius", "tyre_radius_front", "tyre_radius_rear"):
            if r in cls:  # a 22.5 in rim: above its 0.286 m, below a 1.2 m tyre's 0.6 m
                assert 22.5 * IN / 2 < cls[r].value < 0.6, cls.name


def test_tractor_within_eu_limits_and_its_fifth_wheel_over_the_tandem():
    t = cd.combination_class("tractor_6x4")
    assert t["length"].value <= EU_MOTOR_VEHICLE_LENGTH
    assert t["width"].value <= EU_WIDTH and t["height"].value <= EU_HEIGHT
    wb = t["wheelbase"].value
    assert 0.0 < t["cg_to_front_axle"].value < wb
    assert wb + t["tandem_spread"].value / 2 < t["length"].value  # last axle within the body
    # the fifth wheel ahead of the tandem centre, behind the front axle
    assert 0.0 <= t["fifth_wheel_offset"].value < wb
    # axleload_eu: low-deck 95-100 cm, standard 100-120 cm
    lo, hi = t["fifth_wheel_height"].bounds(math.sqrt(3.0))  # uniform: mean +- sqrt(3) sd
    assert lo == pytest.approx(1.00, rel=1e-12) and hi == pytest.approx(1.20, rel=1e-12)
    assert 0.95 <= lo  # above a low-deck tractor's lowest plate
    # with the laden box van: within the 40 t of an articulated vehicle
    assert t["mass"].value + _v("box_van", "mass_laden") <= EU_ARTICULATED_MASS


def test_rigid_truck_within_its_limits_and_its_axles_within_its_length():
    r = cd.combination_class("rigid_truck")
    assert r["length"].value <= EU_MOTOR_VEHICLE_LENGTH
    assert r["mass_max"].value <= EU_TWO_AXLE_MASS  # two axles
    parts = r["front_overhang"].value + r["wheelbase"].value + r["rear_overhang"].value
    assert parts == pytest.approx(r["length"].value, abs=3 * 0.05)  # three figures to 0.1 m
    # laden to 18 t: the centre of mass between the axles, the rear axle within cm1995's
    # UK limit of 10.5 t and under 96/53/EC's 11.5 t driving axle
    cg = r["cg_to_front_axle_laden"].value
    assert 0.0 < cg < r["wheelbase"].value
    rear_t = r["mass_max"].value * cg / r["wheelbase"].value / 1000.0
    assert rear_t == pytest.approx(10.5, rel=1e-12)


def test_eu_box_van_within_the_kingpin_rules_of_96_53():
    b = cd.combination_class("box_van")
    length, setback = b["length"].value, b["kingpin_setback"].value
    assert length - setback <= EU_KINGPIN_TO_REAR + 1e-12  # 1.6
    assert 0.0 < setback <= EU_KINGPIN_TO_FRONT  # B1, along the centreline
    assert length <= EU_KINGPIN_TO_REAR + EU_KINGPIN_TO_FRONT  # both rules together: 14.04 m
    assert b["width"].value <= EU_WIDTH_CONDITIONED and b["height"].value <= EU_HEIGHT
    # the axle group within the trailer behind the kingpin
    group_end = b["kingpin_to_axle_group"].value + b["axle_group_spread"].value / 2
    assert group_end < length - setback
    assert b["mass"].value < b["mass_laden"].value


def test_north_american_semitrailers_within_the_wb67_envelope():
    f = cd.combination_class("flatbed")
    assert f["length"].value == pytest.approx(US_SEMITRAILER_LENGTH, rel=REL)
    assert f["width"].value <= US_WIDTH and f["deck_height"].value < US_HEIGHT
    # the spread axles behind the kingpin, ahead of the rear end
    group_end = f["kingpin_to_axle_group"].value + f["axle_group_spread"].value / 2
    assert group_end < f["length"].value - f["kingpin_setback"].value
    # each spread axle a single axle (more than 96 in apart, truckingtruth_kingpin's tandem
    # bound): laden and coupled, the two carry the trailer's share, under 2 x 20,000 lb
    assert f["axle_group_spread"].value > 96 * IN
    assert f["mass"].value < f["mass_laden"].value
    tanker = cd.combination_class("tanker")
    assert tanker["width"].value <= US_WIDTH
    assert tanker["length"].value <= US_SEMITRAILER_LENGTH
    # the laden tanker and flatbed with the tractor class: at the 80,000 lb gross
    gross = 80000.0 * LB
    tractor = _v("tractor_6x4", "mass")
    assert tractor + tanker["mass_laden"].value == pytest.approx(gross, rel=REL)
    assert tractor + f["mass_laden"].value == pytest.approx(gross, rel=1e-3)


def test_light_trailers_nose_loads_and_coupling_heights():
    for name in ("caravan", "centre_axle_trailer"):
        cls = cd.combination_class(name)
        # legal minimum 4 % (practical_caravan_2020) up to the 10 % of a centre-axle trailer
        # (iss_centre_axle)
        lo, hi = cls["nose_load_share"].bounds(math.sqrt(3.0))
        assert cls["nose_load_share_min"].value == 0.04
        assert 0.04 <= lo and hi <= CENTRE_AXLE_MAX_SHARE, name
        assert cls["nose_load_min"].value == 25.0
        # 94/20/EC: the coupling range sits 35 mm above the tow-ball range (nose down)
        ball, coupling = cls["tow_ball_height"], cls["coupling_height"]
        assert coupling.value - ball.value == pytest.approx(0.035, rel=1e-9)
        assert ball.bounds(math.sqrt(3.0)) == pytest.approx((0.350, 0.420), rel=1e-12)
    caravan = cd.combination_class("caravan")
    assert caravan["mass"].value < caravan["mass_max"].bounds(math.sqrt(3.0))[0]
    assert caravan["width"].value <= LIGHT_TRAILER_WIDTH
    assert cd.combination_class("centre_axle_trailer")["mass_max"].value <= UNBRAKED_TRAILER_MASS


def test_drawbar_trailer_body_fits_the_road_train_rule():
    d = cd.combination_class("drawbar_trailer")
    assert 2 * d["body_length"].value <= EU_ROAD_TRAIN_BODIES  # 96/53 1.7, two bodies
    assert d["mass_max"].value <= EU_TWO_AXLE_MASS
