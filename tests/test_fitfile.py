"""Fits in scene files (crashsim.io.fitfile: ``[fit]``, ``[[evidence]]``) and ``crashsim fit``:
the tables read into what the Python API takes (units converted), every mistake a typed
error naming the file, the key and the item, the command end to end (values recovered,
fit.json and fit.png that reopen, exit codes 0, 2 and 130 with the best so far written)."""

from __future__ import annotations

import dataclasses
import json
import math
import os
import pickle
import signal
import subprocess
import sys
import time
from pathlib import Path

import crashsim as cs
import numpy as np
import pytest
from conftest import REPO
from crashsim.cli import main
from crashsim.io.fitfile import FitFileError, FitSpec, format_fit
from crashsim.io.scenefile import SceneFileError, load_scene, loads_scene
from crashsim.studies.evidence import (
    EDRDeltaV,
    ImpactPoint,
    PostImpactSpeed,
    RestHeading,
    RestPosition,
    TyreMark,
)

EXAMPLE = REPO / "examples" / "fit-skid.toml"
SEED = REPO / "examples" / "seed-90deg.toml"
MPH = 0.44704  # m/s
KMH = 1 / 3.6  # m/s
DEG = math.pi / 180  # rad
TRUTH = {"red.speed": 60 * KMH, "red.heading": 8 * DEG}  # the run the example's evidence is of

_TEXT = EXAMPLE.read_text(encoding="utf-8")
BASE = _TEXT[: _TEXT.index("\n[fit]\n") + 1]  # the example's scene without its fit
FIT = '[fit]\n[fit.unknowns]\n"red.speed" = ["30 km/h", "90 km/h"]\n'
EV = ('[[evidence]]\ntype = "rest_position"\nvehicle = "red"\nposition = ["31 m", "5 m"]\n'
      'tolerance = "0.2 m"\n')  # fmt: skip


def _load(extra: str) -> FitSpec:
    case = loads_scene(BASE + extra, source="case.toml")
    assert case.fit is not None
    return case.fit


# -- the tables -------------------------------------------------------------------------------


def test_the_tables_read_to_what_the_python_api_takes_with_units_converted() -> None:
    spec = _load("""
[fit]
method = "global"
seed = 3
popsize = 6
maxiter = 4
scan_points = 5
[fit.unknowns]
"red.speed" = ["30 mph", "50 mph"]
red.heading = "(-10, 10) deg"            # a dotted key and a vector string
"ground.friction" = [0.5, 0.9]           # a plain number
[fit.start]
"red.speed" = "40 mph"

[[evidence]]
type = "rest_position"
vehicle = "red"
position = ["82 ft", "1.5 m"]
tolerance = "20 cm"

[[evidence]]
type = "rest_heading"
vehicle = "red"
heading = "9.3 deg"
tolerance = "2 deg"

[[evidence]]
type = "edr_delta_v"
vehicle = "red"
longitudinal = "-12 mph"
lateral = "3 km/h"
tolerance = "3 mph"
impact = 2

[[evidence]]
type = "impact_point"
position = "(1.5, -0.25) m"
tolerance = 0.3

[[evidence]]
type = "tyre_mark"
vehicle = "red"
wheel = "front_left"
polyline = [["1 m", "0.9 m"], "(12, 2.4) m", [30, 5.8]]
tolerance = "10 cm"

[[evidence]]
type = "post_impact_speed"
vehicle = "red"
speed = "30 km/h"
tolerance = "1 m/s"
""")
    want = {"red.speed": (30 * MPH, 50 * MPH), "red.heading": (-10 * DEG, 10 * DEG),
            "ground.friction": (0.5, 0.9)}  # fmt: skip
    assert list(spec.unknowns) == list(want)
    for n, bounds in want.items():
        assert spec.unknowns[n] == pytest.approx(bounds, rel=1e-12), n
    assert spec.unknowns["red.speed"][0] == pytest.approx(13.4112, abs=1e-12)  # "30 mph"
    assert spec.start == pytest.approx({"red.speed": 40 * MPH})
    assert spec.kwargs() == {"method": "global", "start": spec.start, "seed": 3, "popsize": 6,
                             "maxiter": 4, "scan_points": 5}  # fmt: skip
    assert spec.units == {"red.speed": "mph", "red.heading": "deg"}  # as written, for display
    assert spec.types == ["rest_position", "rest_heading", "edr_delta_v", "impact_point",
                          "tyre_mark", "post_impact_speed"]  # fmt: skip
    assert spec.evidence_units == ["cm", "deg", "mph", None, "cm", "m/s"]
    api = [
        RestPosition("red", 82 * 0.3048, 1.5, 0.2),
        RestHeading("red", 9.3 * DEG, 2 * DEG),
        EDRDeltaV("red", -12 * MPH, 3 * KMH, 3 * MPH, impact=2),
        ImpactPoint(1.5, -0.25, 0.3),
        TyreMark("red", "front_left", np.array([[1, 0.9], [12, 2.4], [30, 5.8]]), 0.1),
        PostImpactSpeed("red", 30 * KMH, 1.0),
    ]
    for got, want in zip(spec.evidence, api, strict=True):
        assert type(got) is type(want)
        for f in dataclasses.fields(want):
            a, b = getattr(got, f.name), getattr(want, f.name)
            if isinstance(b, str | int):
                assert a == b, f.name
            else:
                np.testing.assert_allclose(a, b, rtol=1e-12, err_msg=f.name)


def test_evidence_alone_is_kept_and_checked() -> None:
    spec = _load(EV)
    assert spec.unknowns == {} and spec.method == "least_squares"
    assert spec.evidence == [RestPosition("red", 31.0, 5.0, 0.2)]
    assert loads_scene(BASE).fit is None


BAD = [
    # (the fit's text, the key path, what the message says)
    (FIT.replace('["30 km/h", "90 km/h"]', '["90 km/h", "30 km/h"]') + EV,
     "fit.unknowns.red.speed", "the bounds (90, 30) km/h need lo < hi"),
    (FIT.replace('["30 km/h", "90 km/h"]', '["30 km/h", "30 km/h"]') + EV,
     "fit.unknowns.red.speed", "need lo < hi"),
    (FIT.replace("red.speed", "red.sped") + EV,
     "fit.unknowns.red.sped", 'unknown parameter path "red.sped"'),
    (FIT.replace("red.speed", "green.speed") + EV,
     "fit.unknowns.green.speed", 'unknown parameter path "green.speed"'),
    (FIT.replace('"90 km/h"', '"90 deg"') + EV,
     "fit.unknowns.red.speed[1]", "is a angle, not a speed"),
    (FIT.replace('["30 km/h", "90 km/h"]', '"30 km/h"') + EV,
     "fit.unknowns.red.speed", "expected the bounds [lo, hi]"),
    (FIT + '"red.velocity_x" = [1, 2]\n' + EV, "fit.unknowns", "set the same velocity"),
    (FIT + "[fit.start]\n\"red.speed\" = \"100 km/h\"\n" + EV,
     "fit.start.red.speed", "outside the bounds (30, 90) km/h"),
    (FIT.replace("[fit]\n", '[fit]\nmethod = "newton"\n') + EV, "fit.method", "not one of"),
    (FIT.replace("[fit]\n", "[fit]\nseed = 1\n") + EV, "fit.seed", 'for method = "global"'),
    (FIT.replace("[fit]\n", "[fit]\nmethd = 1\n") + EV, "fit.methd", 'did you mean "method"'),
    ("[fit]\n" + EV, "fit.unknowns", "required and missing"),
    (FIT, "evidence", "a fit needs evidence"),
    (FIT + EV.replace('"red"', '"green"'),
     "evidence[0].vehicle", 'rest_position of green: the scene has no vehicle "green"'),
    (FIT + EV.replace('"0.2 m"', '"0 m"'),
     "evidence[0].tolerance", 'rest_position of red: "0 m" must be positive'),
    (FIT + EV.replace('"0.2 m"', "-0.2"), "evidence[0].tolerance", "-0.2 must be positive"),
    (FIT + EV.replace('"0.2 m"', '"2 deg"'),
     "evidence[0].tolerance", '"2 deg" is a angle, not a length'),
    (FIT + EV.replace('"5 m"', '"5 mph"'),
     "evidence[0].position[1]", "rest_position of red: \"5 mph\" is a speed, not a length"),
    (FIT + EV.replace("rest_position", "rest_place"),
     "evidence[0].type", '"rest_place" is not one of "rest_position", "rest_heading"'),
    (FIT + EV.replace('type = "rest_position"\n', ""), "evidence[0].type", "required"),
    (FIT + EV.replace('position = ["31 m", "5 m"]\n', ""),
     "evidence[0].position", "rest_position of red: this key is required and missing"),
    (FIT + EV.replace("position =", "positon ="),
     "evidence[0].positon", 'unknown key: did you mean "position"'),
    (FIT + EV + EV.replace('"0.2 m"', '"0 ft"'),  # the second item
     "evidence[1].tolerance", "rest_position of red"),
    (FIT + '[[evidence]]\ntype = "impact_point"\nvehicle = "red"\nposition = [0, 0]\n'
     "tolerance = 1\n", "evidence[0].vehicle", "impact_point: unknown key"),
    (FIT + '[[evidence]]\ntype = "edr_delta_v"\nvehicle = "red"\nlongitudinal = "-3 mph"\n'
     'lateral = 0\ntolerance = "1 mph"\nimpact = 0\n',
     "evidence[0].impact", "edr_delta_v of red: 0: give a whole number >= 1"),
    (FIT + '[[evidence]]\ntype = "tyre_mark"\nvehicle = "red"\nwheel = "XX"\n'
     'polyline = [[0, 0]]\ntolerance = "1 m"\n', "evidence[0].wheel", "unknown wheel 'XX'"),
    (FIT + '[[evidence]]\ntype = "tyre_mark"\nvehicle = "red"\nwheel = "FL"\n'
     'polyline = [[0, 0], ["1 m", "2 s"]]\ntolerance = "1 m"\n',
     "evidence[0].polyline[1][1]", "tyre_mark of red: \"2 s\" is a time, not a length"),
    (FIT + '[[evidence]]\ntype = "post_impact_speed"\nvehicle = "red"\nspeed = "3 mph"\n'
     'tolerance = "0 mph"\n', "evidence[0].tolerance", "post_impact_speed of red"),
]


@pytest.mark.parametrize(("extra", "key", "why"), BAD, ids=[b[1] for b in BAD])
def test_every_mistake_is_a_typed_error_naming_the_file_key_and_item(
    extra: str, key: str, why: str
) -> None:
    with pytest.raises(FitFileError) as e:
        loads_scene(BASE + extra, source="case.toml")
    err = e.value
    assert isinstance(err, SceneFileError) and isinstance(err, cs.FitError)
    assert err.key == key and err.file == "case.toml"
    assert str(err).startswith(f"case.toml: {key}: "), str(err)
    assert why in str(err) and "\n" not in str(err)
    back = pickle.loads(pickle.dumps(err))
    assert type(back) is FitFileError and back.key == key and str(back) == str(err)


def test_evidence_that_is_not_an_array_of_tables() -> None:
    for text in ("evidence = 3\n" + BASE, BASE + '[evidence]\ntype = "rest_position"\n'):
        with pytest.raises(FitFileError, match=r"case.toml: evidence: expected \[\[evidence\]\]"):
            loads_scene(text, source="case.toml")
    seed = SEED.read_text(encoding="utf-8")  # box vehicles without wheels
    with pytest.raises(FitFileError, match=r"evidence\[0\].vehicle: tyre_mark of red: vehicle "
                       '"red" has no wheels'):  # fmt: skip
        loads_scene(seed + '[[evidence]]\ntype = "tyre_mark"\nvehicle = "red"\nwheel = "FL"\n'
                    'polyline = [[0, 0]]\ntolerance = "1 m"\n', source="case.toml")  # fmt: skip


def test_the_answer_in_the_files_units() -> None:
    case = load_scene(EXAMPLE)
    spec = case.fit
    fit = cs.fit(case.scene, spec.unknowns, spec.evidence[:2], dt=case.run.dt,
                 max_duration=case.run.longest, progress=False, scan=False,
                 **spec.kwargs())  # fmt: skip
    spec2 = dataclasses.replace(spec, evidence=spec.evidence[:2], types=spec.types[:2],
                                evidence_units=spec.evidence_units[:2])  # fmt: skip
    text = format_fit(fit, spec2)
    row = next(line for line in text.splitlines() if line.startswith("red.speed"))
    best = float(row.split()[1])
    assert best == pytest.approx(60.0, rel=5e-3) and "km/h" in row and "m/s)" in row
    heading = next(line for line in text.splitlines() if "rest_heading (red)" in line)
    assert heading.split()[-1] == "deg" and float(heading.split()[4]) == pytest.approx(8.0)
    data = json.loads(json.dumps(fit.to_dict(), allow_nan=False))
    assert data["values"]["red.speed"] == pytest.approx(fit.values["red.speed"])
    assert data["scan"] is None and len(data["residuals"]) == 2
    assert "red.speed" in format_fit(fit)  # without a spec: SI


def test_the_picture_in_the_files_units() -> None:
    # Was: fit.png's scans along red.speed in m/s while the table gave the file's km/h.
    case = load_scene(EXAMPLE)
    spec = case.fit
    options = dict(spec.kwargs(), scan_points=3, samples=0)
    fit = cs.fit(case.scene, spec.unknowns, spec.evidence[:2], dt=case.run.dt,
                 max_duration=case.run.longest, progress=False, **options)  # fmt: skip
    assert spec.display_units() == {"red.speed": ("km/h", KMH), "red.heading": ("deg", DEG)}
    fig = fit.plot(units=spec.display_units())
    panels = {a.get_xlabel(): a for a in fig.axes[1:]}
    assert set(panels) == {"red.speed (km/h)", "red.heading (deg)"}
    for name, label, unit in (("red.speed", "red.speed (km/h)", KMH),
                              ("red.heading", "red.heading (deg)", DEG)):  # fmt: skip
        xs, _ = fit.scan[name]
        (scan,) = [line for line in panels[label].lines if line.get_label() == "scan"]
        assert np.allclose(scan.get_xdata(), xs / unit, rtol=1e-12, atol=0)
        best = [line for line in panels[label].lines if line.get_color() == "k"]
        assert best[0].get_xdata()[0] == pytest.approx(fit.values[name] / unit, rel=1e-12)
    assert fit.values["red.speed"] / KMH == pytest.approx(60.0, rel=5e-3)  # the table's 60
    # without units: SI, angles in degrees
    plain = {a.get_xlabel() for a in fit.plot().axes[1:]}
    assert plain == {"red.speed (m/s)", "red.heading (deg)"}


def test_crashsim_fit_draws_fit_png_in_the_files_units(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    drawn: list[object] = []
    plot = cs.FitResult.plot

    def spy(self, path=None, units=None):  # type: ignore[no-untyped-def]
        drawn.append(units)
        return plot(self, path, units)

    monkeypatch.setattr(cs.FitResult, "plot", spy)
    assert main(["fit", str(EXAMPLE), "--out", str(tmp_path / "fit"), "--no-scan"]) == 0
    assert drawn == [{"red.speed": ("km/h", KMH), "red.heading": ("deg", DEG)}]
    assert (tmp_path / "fit" / "fit.png").stat().st_size > 10_000


# -- crashsim fit -------------------------------------------------------------------------------


def test_crashsim_fit_recovers_the_example_and_writes_json_and_png(tmp_path: Path) -> None:
    out = tmp_path / "fit"
    proc = subprocess.run(
        [sys.executable, "-m", "crashsim", "fit", str(EXAMPLE), "--out", str(out)],
        capture_output=True, text=True, timeout=300,
    )  # fmt: skip
    assert proc.returncode == 0, proc.stderr
    data = json.loads((out / "fit.json").read_text(encoding="utf-8"))
    assert not data["interrupted"] and data["objective"] < 0.1
    # the example's evidence was made from a run at 60 km/h and 8 deg (rounded to 1 cm, 0.1 deg)
    assert data["values"]["red.speed"] == pytest.approx(TRUTH["red.speed"], rel=5e-3)
    assert abs(data["values"]["red.heading"] - TRUTH["red.heading"]) < 0.5 * DEG
    for n, (lo, hi) in data["ranges"].items():
        assert lo < TRUTH[n] < hi
    assert [r["unit"] for r in data["residuals"]] == ["m", "rad", "m"]
    assert data["evidence_types"] == ["rest_position", "rest_heading", "tyre_mark"]
    assert data["units_written"] == {"red.speed": "km/h", "red.heading": "deg"}
    assert all(abs(x) < 1 for r in data["residuals"] for x in r["normalised"])
    import matplotlib.image

    picture = matplotlib.image.imread(out / "fit.png")
    assert picture.ndim == 3 and picture.shape[0] > 300 and picture.shape[1] > 600
    report = json.loads((out / "fitted-report.json").read_text(encoding="utf-8"))
    assert report["run_out"] and report["scene"]
    text = proc.stdout
    assert "km/h  (= 16.6" in text and "rest_heading (red)" in text and "wrote: " in text


def test_crashsim_fit_bad_input_exits_2_with_one_line(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    bad = tmp_path / "bad.toml"
    bad.write_text(BASE + FIT + EV.replace('"0.2 m"', '"0 m"'), encoding="utf-8")
    for args, why in (
        ([str(SEED)], "nothing to fit to: add [[evidence]]"),
        ([str(bad)], "bad.toml: evidence[0].tolerance: rest_position of red"),
        ([str(EXAMPLE), "--unknown", "red.speed=1"], "give the two bounds"),
        ([str(EXAMPLE), "--unknown", "red.speed=30,20 mph"], "need lo < hi"),
        ([str(EXAMPLE), "--unknown", "red.sped=1,2"], 'unknown parameter path "red.sped"'),
        ([str(EXAMPLE), "--start", "red.speed=100 mph"], "lies outside the bounds"),
        ([str(EXAMPLE), "--seed", "1"], "--seed is for --method global"),
        ([str(EXAMPLE), "--out", str(bad / "x")], "output folder"),
    ):
        assert main(["fit", *args]) == 2, args
        err = capsys.readouterr().err
        assert err.startswith("crashsim: error: ") and why in err, (args, err)
        assert err.count("\n") == 1
    with pytest.raises(SystemExit) as e:  # argparse's own check
        main(["fit", str(EXAMPLE), "--method", "newton"])
    assert e.value.code == 2 and "invalid choice" in capsys.readouterr().err


def test_crashsim_fit_takes_the_unknowns_from_the_command_line(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    # evidence alone in the file (rest position and heading: candidates run as batches)
    case = tmp_path / "skid.toml"
    first = _TEXT.index("\n[[evidence]]\n")
    mark = _TEXT.index('\n[[evidence]]\ntype = "tyre_mark"')
    case.write_text(BASE + _TEXT[first:mark], encoding="utf-8")
    out = tmp_path / "out"
    assert main(["fit", str(case), "--unknown", "red.speed=30,90 km/h", "--unknown",
                 "red.heading=-5,20deg", "--start", "red.speed=45 km/h", "--no-scan",
                 "--no-pictures", "--out", str(out), "--threads", "2"]) == 0  # fmt: skip
    text = capsys.readouterr().out
    data = json.loads((out / "fit.json").read_text(encoding="utf-8"))
    assert data["start"]["red.speed"] == pytest.approx(45 * KMH)
    assert data["values"]["red.speed"] == pytest.approx(TRUTH["red.speed"], rel=5e-3)
    assert data["scan"] is None and not (out / "fit.png").exists()
    assert data["units_written"] == {}  # the command line's bounds: shown in SI
    assert "m/s" in next(line for line in text.splitlines() if line.startswith("red.speed"))


def test_crashsim_check_checks_the_fit(capsys: pytest.CaptureFixture[str]) -> None:
    assert main(["check", str(EXAMPLE)]) == 0
    out = capsys.readouterr().out
    assert "fit: unknowns red.speed, red.heading; 3 evidence items" in out


def test_ctrl_c_prints_and_writes_the_best_so_far_and_exits_130(tmp_path: Path) -> None:
    out = tmp_path / "fit"
    proc = subprocess.Popen(
        [sys.executable, "-m", "crashsim", "fit", str(EXAMPLE), "--method", "global", "--out",
         str(out), "--progress"],
        stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True,
        env={**os.environ, "PYTHONUNBUFFERED": "1"},
    )  # fmt: skip
    assert proc.stderr is not None
    seen = ""
    deadline = time.monotonic() + 60
    while "fit: " not in seen and time.monotonic() < deadline:  # the progress line: running
        seen += proc.stderr.read(1)
    time.sleep(0.5)
    proc.send_signal(signal.SIGINT)
    stdout, stderr = proc.communicate(timeout=60)
    assert proc.returncode == 130, stderr
    assert "INTERRUPTED (Ctrl-C): the best so far" in stdout and "crashsim: interrupted" in stderr
    data = json.loads((out / "fit.json").read_text(encoding="utf-8"))
    assert data["interrupted"] and data["n_runs"] > 0 and math.isfinite(data["objective"])
    lo, hi = data["bounds"]["red.speed"]
    assert lo <= data["values"]["red.speed"] <= hi
    assert (out / "fit.png").stat().st_size > 10_000


def test_the_format_document_names_every_fit_key_and_evidence_type() -> None:
    from crashsim.io.fitfile import EVIDENCE_KEYS, FIT_KEYS

    doc = (REPO / "docs" / "scene-format.md").read_text(encoding="utf-8")
    words = {*FIT_KEYS, *EVIDENCE_KEYS, *(k for _, keys, _ in EVIDENCE_KEYS.values() for k in keys)}
    missing = sorted(k for k in words if f"`{k}`" not in doc)
    assert not missing, f"docs/scene-format.md does not describe {missing}"


def test_the_docs_give_the_fit_defaults_the_code_has() -> None:
    # Was: scene-format.md gave step 0.001 and seed "fresh entropy", fitting.md step 1e-2 and
    # seed 0; the code's are cs.fit's keyword defaults (the file's [fit] leaves them to it).
    import inspect
    import re

    defaults = {k: p.default for k, p in inspect.signature(cs.fit).parameters.items()}
    table = (REPO / "docs" / "scene-format.md").read_text(encoding="utf-8")
    section = table[table.index("`[fit]`:\n") : table.index("`[[evidence]]`, one section")]
    rows = [r.split("|") for r in section.splitlines() if r.startswith("| `")]
    for key in ("seed", "popsize", "maxiter", "max_nfev", "step", "scan", "scan_points"):
        # | `key`, `key2` | type | default, default2 | meaning |
        cells = next(c for c in rows if f"`{key}`" in c[1])
        names = re.findall(r"`(\w+)`", cells[1])
        value = [w.strip().strip("`") for w in cells[3].split(",")][names.index(key)]
        expected = defaults[key]
        if isinstance(expected, bool):
            assert value == str(expected).lower(), (key, value)
        else:
            assert float(value) == expected, (key, value, expected)
    fitting = (REPO / "docs" / "fitting.md").read_text(encoding="utf-8")
    assert float(re.search(r"a step of `step` = ([0-9.e-]+)", fitting).group(1)) == defaults["step"]
    assert int(re.search(r"`seed` \(default (\d+)\)", fitting).group(1)) == defaults["seed"]
    with pytest.raises(FitFileError, match=r"\(default 0\.01\)"):
        _load(FIT.replace("[fit]\n", "[fit]\nstep = 0.7\n") + EV)
