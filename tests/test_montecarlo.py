"""The vehicle-class Monte Carlo of the depth of penetration (crashsim.analysis.montecarlo) and its
command (``crashsim dtp-montecarlo``), on small stand-in classes with the shape of
crashsim.vehicles.vehicle_data (Figure(value, sd, source); classes with mass, width,
front/rear/side.B).
The stand-in numbers are invented test inputs, not vehicle data."""

from __future__ import annotations

import json
import math
import sys
import types
from dataclasses import dataclass
from pathlib import Path

import numpy as np
import pytest
from crashsim.analysis import penetration as pen
from crashsim.analysis.montecarlo import (
    CONFIGURATIONS,
    PERCENTILES,
    dtp_montecarlo,
    plot_dtp_histogram,
    summarize,
)
from crashsim.cli import main
from crashsim.errors import ParameterError
from scipy import stats


@dataclass(frozen=True)
class Figure:
    value: float
    sd: float | None
    source: str = "test stand-in"


@dataclass(frozen=True)
class Face:
    B: Figure | None


@dataclass(frozen=True)
class VehicleClass:
    mass: Figure
    width: Figure
    front: Face | None
    rear: Face | None
    side: Face | None


def _cls(
    m: float, w: float, bf: float, br: float | None, bs: float, rel_sd: float | None = 0.1
) -> VehicleClass:
    def fig(x: float) -> Figure:
        return Figure(x, None if rel_sd is None else rel_sd * x)

    return VehicleClass(
        fig(m),
        Figure(w, None if rel_sd is None else 0.03),
        Face(fig(bf)),
        None if br is None else Face(fig(br)),
        Face(fig(bs)),
    )


CLASSES = {
    "small": _cls(1100.0, 1.65, 0.9e6, 0.8e6, 0.45e6),
    "family": _cls(1500.0, 1.80, 1.1e6, 0.9e6, 0.55e6),
    "suv": _cls(2100.0, 1.90, 1.3e6, 1.0e6, 0.60e6),
}


# --- reproducibility and the sampled values --------------------------------------------------


def test_same_seed_same_bits_other_seed_other_bits() -> None:
    a = dtp_montecarlo(20_000, seed=7, classes=CLASSES)
    b = dtp_montecarlo(20_000, seed=7, classes=CLASSES)
    c = dtp_montecarlo(20_000, seed=8, classes=CLASSES)
    for name in ("dtp", "mass1", "mass2", "width", "B1", "B2", "class1", "class2"):
        assert getattr(a, name).tobytes() == getattr(b, name).tobytes(), name
    assert a.summary() == b.summary()
    assert not np.array_equal(a.dtp, c.dtp)


def test_each_sample_is_the_spring_model_of_its_draws() -> None:
    r = dtp_montecarlo(30_000, seed=1, classes=CLASSES)
    expected = pen.depth_of_penetration_from_b(r.mass1, r.mass2, r.B1, r.B2, r.width)
    np.testing.assert_allclose(r.dtp, expected, rtol=1e-14)
    assert not r.dtp.flags.writeable


def test_without_spread_every_pair_gives_its_closed_form() -> None:
    """sd None: no variation, so each sample is exactly the pair's dt_p with the faces of its
    configuration and the narrower width."""
    fixed = {
        "a": _cls(1000.0, 1.6, 1.0e6, 0.7e6, 0.4e6, rel_sd=None),
        "b": _cls(1800.0, 1.9, 1.4e6, 1.1e6, 0.6e6, rel_sd=None),
    }
    r = dtp_montecarlo(4 * 4 * 3, seed=0, classes=fixed)
    faces = {"front-front": ("front", "front"), "front-rear": ("front", "rear")}
    faces |= {"front-side": ("front", "side"), "rear-side": ("rear", "side")}
    names = r.class_names
    for k in range(len(r)):
        config = r.configurations[r.configuration[k]]
        c1, c2 = fixed[names[r.class1[k]]], fixed[names[r.class2[k]]]
        f1, f2 = faces[config]
        b1 = getattr(c1, f1).B.value
        b2 = getattr(c2, f2).B.value
        w = min(c1.width.value, c2.width.value)
        want = math.sqrt(
            (c1.mass.value * c2.mass.value / (c1.mass.value + c2.mass.value))
            / ((b1 * w) * (b2 * w) / (b1 * w + b2 * w))
        )
        assert r.dtp[k] == pytest.approx(want, rel=1e-14)


def test_draws_stay_within_one_sd_and_are_uniform() -> None:
    single = {"only": CLASSES["family"]}
    r = dtp_montecarlo(40_000, seed=3, classes=single, configurations=["front-side"])
    m, sm = single["only"].mass.value, single["only"].mass.sd
    assert r.mass1.min() >= m - sm and r.mass1.max() <= m + sm
    assert r.mass1.min() < m - 0.999 * sm and r.mass1.max() > m + 0.999 * sm
    # uniform on [m - sd, m + sd]: Kolmogorov-Smirnov on the seeded draws
    ks = stats.kstest(r.mass1, stats.uniform(loc=m - sm, scale=2 * sm).cdf)
    assert ks.pvalue > 1e-3
    # B1 is the front's, B2 the side's
    bf, bs = single["only"].front.B, single["only"].side.B
    assert np.all(np.abs(r.B1 - bf.value) <= bf.sd) and np.all(np.abs(r.B2 - bs.value) <= bs.sd)
    # the engagement width is the smaller of two independent uniform draws
    w, sw = single["only"].width.value, single["only"].width.sd
    assert np.all(r.width <= w + sw) and np.all(r.width >= w - sw)
    # E[min of two U(-1, 1)] = -1/3
    assert np.mean((r.width - w) / sw) == pytest.approx(-1.0 / 3.0, abs=0.01)


def test_pairing_ordered_with_self_pairs_and_equal_weights() -> None:
    n = 3 * 9 * 4 + 5  # not a multiple of the 36 pairs: counts differ by at most one
    r = dtp_montecarlo(n, seed=0, classes=CLASSES)
    assert r.configurations == CONFIGURATIONS
    counts = np.bincount(r.configuration, minlength=4)
    assert counts.sum() == n and counts.max() - counts.min() <= 1
    names = list(CLASSES)
    for k, c in enumerate(CONFIGURATIONS):
        want_pairs = {(a, b) for a in names for b in names}  # ordered, self-pairs included
        assert set(r.pairs[c]) == want_pairs and len(r.pairs[c]) == 9
        sel = r.configuration == k
        pair_counts = np.bincount(r.class1[sel] * 3 + r.class2[sel], minlength=9)
        assert pair_counts.max() - pair_counts.min() <= 1
        assert r.excluded[c] == ()


def test_a_class_without_a_face_is_left_out_only_where_that_face_is_needed() -> None:
    classes = dict(CLASSES, bus=_cls(12_000.0, 2.5, 2.0e6, None, 1.0e6))  # no rear data
    r = dtp_montecarlo(10_000, seed=0, classes=classes)
    assert r.excluded["front-rear"] == ("bus (vehicle 2: no rear B)",)
    assert r.excluded["rear-side"] == ("bus (vehicle 1: no rear B)",)
    assert r.excluded["front-front"] == () and r.excluded["front-side"] == ()
    assert len(r.pairs["front-front"]) == 16 and len(r.pairs["front-side"]) == 16
    assert len(r.pairs["front-rear"]) == 12 and len(r.pairs["rear-side"]) == 12
    bus = r.class_names.index("bus")
    fr = r.configuration == CONFIGURATIONS.index("front-rear")
    rs = r.configuration == CONFIGURATIONS.index("rear-side")
    assert np.any(r.class1[fr] == bus) and not np.any(r.class2[fr] == bus)
    assert np.any(r.class2[rs] == bus) and not np.any(r.class1[rs] == bus)


# --- the summary ----------------------------------------------------------------------------


def _linear_percentile(x: np.ndarray, p: float) -> float:
    """Independent linear interpolation between order statistics (rank (n-1) p/100)."""
    s = sorted(float(v) for v in x)
    h = (len(s) - 1) * p / 100.0
    lo = math.floor(h)
    hi = min(lo + 1, len(s) - 1)
    return s[lo] + (h - lo) * (s[hi] - s[lo])


def test_summary_matches_the_samples() -> None:
    r = dtp_montecarlo(8_001, seed=11, classes=CLASSES)
    summ = r.summary()
    assert summ["samples"] == 8_001 and summ["seed"] == 11 and summ["band"] == [0.010, 0.060]
    groups = {"overall": r.dtp} | {c: r.samples_of(c) for c in CONFIGURATIONS}
    for name, x in groups.items():
        s = summ["overall"] if name == "overall" else summ["by_configuration"][name]
        assert s["n"] == x.size
        assert s["mean"] == pytest.approx(math.fsum(x) / x.size, rel=1e-12)
        for p in PERCENTILES:
            assert s["percentiles"][f"{p:g}"] == pytest.approx(_linear_percentile(x, p), rel=1e-12)
        inside = sum(1 for v in x if 0.010 <= v <= 0.060)
        assert s["fraction_in_band"] == inside / x.size
    assert sum(s["n"] for s in summ["by_configuration"].values()) == summ["overall"]["n"]
    # a narrower band holds fewer samples
    assert r.summary(band=(0.030, 0.035))["overall"]["fraction_in_band"] < 1.0
    json.dumps(summ)  # plain JSON types


def test_summarize_refuses_empty() -> None:
    with pytest.raises(ParameterError):
        summarize([])


# --- bad inputs -----------------------------------------------------------------------------


@pytest.mark.parametrize(
    "kwargs",
    [
        {"samples": 0},
        {"samples": 35},  # fewer than the 36 pairs
        {"samples": 1000.0},
        {"samples": True},
        {"seed": -1},
        {"seed": 1.5},
        {"configurations": ["front-top"]},
        {"configurations": []},
        {"configurations": ["front-front", "front-front"]},
        {"classes": {}},
        {"classes": 42},
        {"classes": {"x": _cls(1000.0, 1.7, 1e6, 1e6, 1e6, rel_sd=1.0)}},  # value - sd = 0
        {"classes": {"x": _cls(float("nan"), 1.7, 1e6, 1e6, 1e6)}},
        {"classes": {"x": _cls(1000.0, 1.7, 1e6, None, 1e6)}, "configurations": ["rear-side"]},
    ],
)
def test_bad_inputs_raise_parameter_error(kwargs: dict[str, object]) -> None:
    args: dict[str, object] = {"samples": 1000, "seed": 0, "classes": CLASSES} | kwargs
    with pytest.raises(ParameterError):
        dtp_montecarlo(**args)  # type: ignore[arg-type]


# --- the picture ----------------------------------------------------------------------------


def test_histogram_picture(tmp_path: Path) -> None:
    from matplotlib.image import imread

    r = dtp_montecarlo(20_000, seed=0, classes=CLASSES)
    path = tmp_path / "dtp.png"
    fig = plot_dtp_histogram(r, path, source="test stand-ins")
    image = imread(path)
    assert image.ndim == 3 and image.shape[0] > 500 and image.shape[1] > 800
    assert image.std() > 0.05  # not blank
    hist_ax, box_ax = fig.axes[0], fig.axes[1]
    assert "(ms)" in box_ax.get_xlabel() and "%" in hist_ax.get_ylabel()
    assert "20,000" in fig.get_suptitle() and "test stand-ins" in fig.get_suptitle()
    legend_texts = [t.get_text() for t in fig.axes[2].get_legend().get_texts()]
    assert set(CONFIGURATIONS) <= set(legend_texts)
    assert any("10-60 ms" in t for t in legend_texts)
    assert hist_ax.patches  # the stacked histogram is drawn
    with pytest.raises(ParameterError):
        plot_dtp_histogram(r, None, bin_ms=0.0)


# --- the command line -----------------------------------------------------------------------


@pytest.fixture
def stand_in_data(monkeypatch: pytest.MonkeyPatch) -> None:
    """crashsim.vehicles.vehicle_data replaced by the stand-in classes for this test."""
    module = types.ModuleType("crashsim.vehicles.vehicle_data")
    module.vehicle_classes = lambda: dict(CLASSES)  # type: ignore[attr-defined]
    monkeypatch.setitem(sys.modules, "crashsim.vehicles.vehicle_data", module)


@pytest.mark.usefixtures("stand_in_data")
def test_cli_json_matches_the_api(capsys: pytest.CaptureFixture[str]) -> None:
    assert main(["dtp-montecarlo", "--samples", "3000", "--seed", "5", "--json"]) == 0
    out = json.loads(capsys.readouterr().out)
    want = dtp_montecarlo(3000, seed=5, classes=CLASSES).summary()
    for key in ("samples", "seed", "band", "overall", "by_configuration"):
        assert out[key] == want[key]
    assert out["classes"] == list(CLASSES) and out["plot"] is None
    assert out["pairs_per_configuration"] == dict.fromkeys(CONFIGURATIONS, 9)


@pytest.mark.usefixtures("stand_in_data")
def test_cli_table_and_plot(capsys: pytest.CaptureFixture[str], tmp_path: Path) -> None:
    path = tmp_path / "h.png"
    assert main(["dtp-montecarlo", "--samples", "3000", "--plot", str(path)]) == 0
    text = capsys.readouterr().out
    median = dtp_montecarlo(3000, seed=0, classes=CLASSES).summary()["overall"]["percentiles"]
    row = next(line for line in text.splitlines() if line.strip().startswith("all"))
    assert f"{1e3 * median['50']:.1f}" in row.split()
    for c in CONFIGURATIONS:
        assert any(line.strip().startswith(c) for line in text.splitlines())
    assert path.stat().st_size > 10_000 and str(path) in text


@pytest.mark.usefixtures("stand_in_data")
@pytest.mark.parametrize(
    "argv",
    [
        ["dtp-montecarlo", "--samples", "0"],
        ["dtp-montecarlo", "--samples", "10"],
        ["dtp-montecarlo", "--seed", "-3"],
        ["dtp-montecarlo", "--plot", "/nonexistent-folder/x/h.png"],
    ],
)
def test_cli_bad_values_exit_2(argv: list[str], capsys: pytest.CaptureFixture[str]) -> None:
    assert main(argv) == 2
    assert "crashsim: error:" in capsys.readouterr().err


@pytest.mark.parametrize(
    "argv", [["dtp-montecarlo", "--samples", "many"], ["dtp-montecarlo", "-x"]]
)
def test_cli_unparsable_arguments_exit_2(argv: list[str]) -> None:
    with pytest.raises(SystemExit) as e:
        main(argv)
    assert e.value.code == 2


# --- the real class data, once it exists ------------------------------------------------------


def test_real_vehicle_classes_run() -> None:
    from crashsim.vehicles import vehicle_data

    classes = vehicle_data.vehicle_classes()
    r = dtp_montecarlo(20_000, seed=0)
    assert r.class_names == tuple(classes)
    assert np.all(np.isfinite(r.dtp)) and np.all(r.dtp > 0)
    expected = pen.depth_of_penetration_from_b(r.mass1, r.mass2, r.B1, r.B2, r.width)
    np.testing.assert_allclose(r.dtp, expected, rtol=1e-14)
