"""Fitting (crashsim.studies.fit, evidence.py): synthetic truth recovered from starts off it,
residuals in their units, the uncertainty, Ctrl-C, bad input naming the item.

The full figures (10 random scenes, the 100-trial calibration):
``python benches/fit_synthetic.py recover`` and ``... calibrate`` (docs/fitting.md).
"""

from __future__ import annotations

import importlib.util
import math
from pathlib import Path

import crashsim as cs
import numpy as np
import pytest
from crashsim.studies.evidence import (
    EDRDeltaV,
    ImpactPoint,
    PostImpactSpeed,
    RestHeading,
    RestPosition,
    TyreMark,
)

_spec = importlib.util.spec_from_file_location(
    "fit_synthetic", Path(__file__).parents[1] / "benches" / "fit_synthetic.py"
)
assert _spec is not None and _spec.loader is not None
fs = importlib.util.module_from_spec(_spec)
_spec.loader.exec_module(fs)


@pytest.fixture(scope="module")
def truth0() -> tuple[cs.Scene, dict[str, float], dict[str, tuple[float, float]], cs.Result]:
    scene, truth, bounds = fs.case(0)
    return scene, truth, bounds, fs.truth_run(scene)


# -- evidence ---------------------------------------------------------------------------------


def test_evidence_residuals_are_zero_at_the_truth_and_in_their_units(truth0) -> None:
    scene, _, _, result = truth0
    rest = result.rest("red")
    imp = result.impacts[0]
    sep = [s for s in result.separations("red") if s.time >= imp.time][0]
    path = result.wheel_path("red", "FL")[::50, :2]
    items = [
        RestPosition("red", rest.position[0] + 0.3, rest.position[1], 0.2),
        RestHeading("red", rest.heading + 2 * math.pi + 0.01, 0.02),  # wrapped
        ImpactPoint(imp.centroid[0], imp.centroid[1] - 0.1, 0.5),
        PostImpactSpeed("red", sep.speed - 0.25, 0.5),
        TyreMark("red", "FL", path, 0.1),
        TyreMark("red", "FL", path + (0.0, 0.4), 0.1),
    ]
    got = [e.difference(e.from_result(result)) for e in items]
    np.testing.assert_allclose(got[0], [-0.3, 0.0], atol=1e-12)
    assert got[1][0] == pytest.approx(-0.01, abs=1e-9)
    np.testing.assert_allclose(got[2], [0.0, 0.1], atol=1e-12)
    assert got[3][0] == pytest.approx(0.25, abs=1e-12)
    assert got[4][0] == pytest.approx(0.0, abs=1e-9)
    assert 0.3 < got[5][0] <= 0.4  # the path runs mostly along x: about 0.4 m off
    assert items[0].normalised(got[0])[0] == pytest.approx(-1.5)


def test_column_and_result_readings_agree(truth0) -> None:
    scene, truth, _, result = truth0
    from crashsim.batch import run_batch

    items = fs.evidence_of(result)
    br = run_batch(scene, n=1, duration=fs.MAX_DURATION, dt=fs.DT, until="rest")
    for e in (e for e in items if not e.uses_result):
        np.testing.assert_allclose(e.measured(br.columns, 0), e.from_result(result), atol=1e-9)


# -- bad input --------------------------------------------------------------------------------


def test_bad_input_is_a_typed_error_naming_the_item(truth0) -> None:
    scene, truth, bounds, result = truth0
    ev = fs.evidence_of(result)
    with pytest.raises(cs.FitError, match="red.speed.*lo < hi") as e:
        cs.fit(scene, {"red.speed": (12.0, 12.0)}, ev, progress=False)
    assert e.value.key == "red.speed"
    with pytest.raises(cs.FitError, match="red.sped") as e:
        cs.fit(scene, {"red.sped": (1.0, 2.0)}, ev, progress=False)
    assert isinstance(e.value, cs.errors.StudyError)
    with pytest.raises(cs.FitError, match=r"evidence\[1\] RestPosition\(green\).*no vehicle"):
        cs.fit(scene, bounds, [ev[0], RestPosition("green", 0, 0, 0.2)], progress=False)
    with pytest.raises(cs.FitError, match=r"evidence\[0\] RestHeading\(red\).*tolerance"):
        cs.fit(scene, bounds, [RestHeading("red", 0.1, 0.0)], progress=False)
    with pytest.raises(cs.FitError, match=r"evidence\[0\] EDRDeltaV\(blue\).*tolerance"):
        cs.fit(scene, bounds, [EDRDeltaV("blue", 1.0, 0.0, -1.0)], progress=False)
    with pytest.raises(cs.FitError, match="outside its bounds"):
        cs.fit(scene, bounds, ev, start={"red.speed": 100.0}, progress=False)
    with pytest.raises(cs.FitError, match="method"):
        cs.fit(scene, bounds, ev, method="newton", progress=False)
    with pytest.raises(cs.FitError, match="at least one"):
        cs.fit(scene, bounds, [], progress=False)
    with pytest.raises(cs.FitError, match=r"evidence\[0\].*polyline"):
        cs.fit(scene, bounds, [TyreMark("red", "FL", [1.0, 2.0], 0.1)], progress=False)


# -- recovery ---------------------------------------------------------------------------------


def _skid(speed: float, heading: float) -> cs.Scene:
    scene = cs.Scene(ground=cs.Ground(friction=0.7))
    scene.add(fs._car("red", 1450.0), (0.0, 0.0), heading=heading,
              velocity=(speed * math.cos(heading), speed * math.sin(heading), 0.0),
              inputs=cs.DriverInputs(wheel_states=[("all", "locked", 0.0)]))  # fmt: skip
    return scene


@pytest.mark.parametrize("seed", [0, 1, 2])
def test_a_skid_to_rest_recovers_speed_and_heading_from_starts_20_percent_off(
    seed: int, tmp_path: Path
) -> None:
    rng = np.random.default_rng(seed)
    speed, heading = float(rng.uniform(10, 20)), float(rng.uniform(-0.5, 0.5))  # m/s, rad
    scene = _skid(speed, heading)
    rest = fs.truth_run(scene).rest("red")
    evidence = [RestPosition("red", rest.position[0], rest.position[1], 0.2),
                RestHeading("red", rest.heading, math.radians(2.0))]  # fmt: skip
    start = {"red.speed": 0.8 * speed if seed % 2 else 1.2 * speed,
             "red.heading": heading + math.radians(5.0)}  # fmt: skip
    bounds = {"red.speed": (0.6 * speed, 1.35 * speed),
              "red.heading": (heading - 0.3, heading + 0.25)}  # fmt: skip
    fit = cs.fit(scene, bounds, evidence, start=start, dt=fs.DT, max_duration=fs.MAX_DURATION,
                 progress=False, scan=seed == 0)  # fmt: skip
    assert abs(fit.values["red.speed"] / speed - 1) < 0.005
    assert abs(math.degrees(fit.values["red.heading"] - heading)) < 0.5
    assert fit.objective < 0.1 and not fit.interrupted
    assert len(fit.residuals) == 2 and fit.residuals[0].unit == "m"
    assert np.all(np.abs(fit.residuals[0].residual) < 0.05)  # m
    lo, hi = fit.ranges["red.speed"]
    assert lo < speed < hi and 0 < hi - lo < 0.3 * speed
    assert fit.result is not None and fit.result.rest("red") is not None
    if seed == 0:
        assert fit.scan_ranges is not None
        slo, shi = fit.scan_ranges["red.speed"]
        assert slo < fit.values["red.speed"] < shi
        out = tmp_path / "fit.png"
        fit.plot(out)
        assert out.stat().st_size > 10_000
        assert "red.speed" in fit.summary()


def test_ctrl_c_returns_the_best_so_far() -> None:
    scene = _skid(15.0, 0.0)
    rest = fs.truth_run(scene).rest("red")
    calls = []

    def progress(runs: int, best: float) -> None:
        calls.append(runs)
        if len(calls) == 3:
            raise KeyboardInterrupt

    fit = cs.fit(scene, {"red.speed": (10.0, 20.0)},
                 [RestPosition("red", rest.position[0], rest.position[1], 0.2)],
                 start={"red.speed": 12.0}, dt=fs.DT, progress=progress)  # fmt: skip
    assert fit.interrupted and "interrupted" in fit.message
    assert 10.0 <= fit.values["red.speed"] <= 20.0 and math.isfinite(fit.objective)
