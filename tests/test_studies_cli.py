"""``crashsim sweep`` and ``crashsim montecarlo`` on scene files, the ``[study]`` table, and
the text forms of values and distributions (crashsim.io.studyfile), with units."""

from __future__ import annotations

import math
import os
import re
import signal
import subprocess
import sys
import time
from pathlib import Path

import crashsim as cs
import numpy as np
import pandas as pd
import pytest
from conftest import REPO
from crashsim.cli import main
from crashsim.io.scenefile import SceneFileError, load_scene, loads_scene
from crashsim.io.studyfile import parse_distribution, parse_values
from crashsim.studies import Linspace, Normal, Triangular, Uniform, class_table

SEED = REPO / "examples" / "seed-90deg.toml"
STUDY = REPO / "examples" / "seed-90deg-study.toml"
MPH = 0.44704  # m/s


def test_values_and_distributions_from_text_with_units() -> None:
    assert parse_values("red.speed", "20:40:3 mph", "speed") == Linspace(20 * MPH, 40 * MPH, 3)
    assert parse_values("red.speed", "10 mph:20 m/s:2", "speed") == Linspace(10 * MPH, 20.0, 2)
    assert parse_values("red.speed", "10, 15, 20 mph", "speed") == [10 * MPH, 15 * MPH, 20 * MPH]
    assert parse_values("red.speed", "10, 15", "speed") == [10.0, 15.0]  # plain: SI
    assert parse_values("red.heading", ["5 deg", 0.1], "angle") == [math.radians(5), 0.1]
    assert parse_values("restitution", "0,0.1", None) == [0.0, 0.1]
    assert math.isnan(parse_values("depth_of_penetration", "auto", "time")[0])
    assert parse_distribution("red.speed", "normal(15 m/s, 1 m/s)", "speed") == Normal(15.0, 1.0)
    assert parse_distribution("red.speed", "normal(30, 2) mph", "speed") == Normal(
        30 * MPH, 2 * MPH)
    assert parse_distribution("red.heading", "uniform(-3 deg, 3 deg)", "angle") == Uniform(
        math.radians(-3), math.radians(3))
    assert parse_distribution("restitution", "triangular(0, 0.1, 0.3)", None) == Triangular(
        0.0, 0.1, 0.3)
    assert parse_distribution("red.mass", "class(sedan)", "mass") == class_table("sedan")
    for key, text, dim, why in (
        ("red.speed", "10:20", "speed", "start:stop:count"),
        ("red.speed", "10:20:x", "speed", "not a number"),
        ("red.speed", "10:20:2.5", "speed", "whole number"),
        ("red.speed", "30 kg", "speed", "is a mass, not a speed"),
        ("restitution", "0.1 mph", None, "plain number"),
        ("red.mass", "auto", "mass", "only a depth of penetration"),
    ):
        with pytest.raises(cs.StudyError, match=why):
            parse_values(key, text, dim)
    for text, why in (("gauss(1, 2)", "unknown distribution"), ("normal(1)", "takes 2 or 4"),
                      ("15 m/s", "not a distribution"), ("class(sedan, width)", "is a length")):
        with pytest.raises(cs.StudyError, match=why):
            parse_distribution("red.mass" if "class" in text else "red.speed", text,
                               "mass" if "class" in text else "speed")


def test_the_study_table_of_a_scene_file() -> None:
    case = load_scene(STUDY)
    spec = case.study
    assert spec.kind == "montecarlo" and spec.n == 500 and spec.seed == 1
    assert spec.distributions["red.speed"] == Normal(30 * MPH, 2 * MPH)
    assert list(spec.distributions) == ["red.speed", "red.heading", "red.position_y",
                                        "restitution"]
    text = SEED.read_text()
    swept = loads_scene(text + '\n[study]\nkind = "sweep"\n[study.vary]\n'
                        'red.speed = "20:30:3 mph"\nrestitution = [0, 0.2]\n')
    assert swept.study.vary == {"red.speed": Linspace(20 * MPH, 30 * MPH, 3),
                                "restitution": [0.0, 0.2]}
    for extra, key, why in (
        ('[study]\nkind = "sweep"\n[study.vary]\n"red.sped" = [1]\n', "study.vary.red.sped",
         "unknown parameter path"),
        ('[study]\nkind = "grid"\n', "study.kind", "sweep"),
        ('[study]\nkind = "montecarlo"\n[study.distributions]\n"red.speed" = "normal(1, 0)"\n',
         "study.distributions.red.speed", "standard deviation must be > 0"),
        ('[study]\nkind = "sweep"\nn = 3\n', "study.n", "n and seed are for"),
        ('[study]\nkind = "montecarlo"\nn = 0\n', "study.n", ">= 1"),
        ('[study]\nkind = "sweep"\nvaryy = 1\n', "study.varyy", "unknown key"),
    ):
        with pytest.raises(SceneFileError, match=why) as e:
            loads_scene(text + "\n" + extra, source="case.toml")
        assert e.value.key == key and str(e.value).startswith("case.toml: " + key)


def test_crashsim_sweep_prints_percentiles_and_writes_the_table(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    out = tmp_path / "sweep.csv"
    code = main(["sweep", str(SEED), "--vary", "red.speed=20:40:3 mph", "--vary",
                 "restitution=0,0.1,1.5", "--out", str(out), "--plots", str(tmp_path / "p"),
                 "--tornado"])
    text = capsys.readouterr().out
    assert code == 0
    assert "9 variants: 6 ran, 3 failed" in text
    assert "failed: ParameterError: variant 2 (red.speed = 8.9408 m/s, restitution = 1.5)" in text
    assert "impact1.red.delta_v" in text and "P95" in text
    assert "tornado of impact1.red.delta_v" in text
    frame = pd.read_csv(out, index_col="variant")
    assert frame.shape[0] == 9 and list(frame["status"]).count("failed") == 3
    assert np.allclose(frame["red.speed"].unique(), [20 * MPH, 30 * MPH, 40 * MPH])
    api = cs.sweep(load_scene(SEED).scene, {"red.speed": [20 * MPH, 30 * MPH, 40 * MPH],
                                            "restitution": [0.0, 0.1, 1.5]},
                   duration=0.3, dt=1e-3, progress=False)
    assert np.array_equal(frame["impact1.red.delta_v"].to_numpy(), api["impact1.red.delta_v"],
                          equal_nan=True)
    assert (tmp_path / "p" / "hist-impact1.red.delta_v.png").is_file()
    assert (tmp_path / "p" / "tornado-impact1.red.delta_v.png").is_file()


def test_crashsim_montecarlo_takes_the_file_study_and_the_command_line(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    out = tmp_path / "mc.parquet"
    code = main(["montecarlo", str(STUDY), "-n", "40", "--seed", "3", "--dist",
                 "red.speed=uniform(25 mph, 35 mph)", "--out", str(out)])
    text = capsys.readouterr().out
    assert code == 0 and "40 variants: 40 ran, 0 failed" in text
    frame = pd.read_parquet(out)
    assert frame["red.speed"].between(25 * MPH, 35 * MPH).all()  # the command line's
    assert frame["restitution"].between(0.05, 0.2).all()  # the file's
    case = load_scene(STUDY)
    dists = {**case.study.distributions, "red.speed": Uniform(25 * MPH, 35 * MPH)}
    api = cs.monte_carlo(case.scene, dists, 40, 3, duration=0.3, dt=1e-3, progress=False)
    assert np.array_equal(frame["impact1.blue.pdof_deg"].to_numpy(), api["impact1.blue.pdof_deg"])


def test_study_commands_fail_with_one_line_and_exit_2(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    for args, why in (
        (["sweep", str(SEED)], "nothing to vary: give --vary"),
        (["sweep", str(STUDY)], "its [study] is a montecarlo study"),
        (["sweep", str(SEED), "--vary", "red.sped=1,2"], 'unknown parameter path "red.sped"'),
        (["sweep", str(SEED), "--vary", "red.speed"], "write PATH=VALUE"),
        (["montecarlo", str(SEED), "--dist", "red.speed=normal(15, 0)"],
         "standard deviation must be > 0"),
        (["montecarlo", str(SEED), "--dist", "red.speed=normal(15, 1)"], "-n N"),
        (["sweep", str(SEED), "--vary", "restitution=0", "--out", str(tmp_path / "x.txt")],
         ".csv or .parquet"),
        (["sweep", str(SEED), "--vary", "restitution=0", "--scheduler", "tcp://127.0.0.1:9"],
         "--scheduler is for --backend dask"),
    ):
        assert main(args) == 2, args
        err = capsys.readouterr().err
        assert err.startswith("crashsim: error: ") and why in err, (args, err)
        assert err.count("\n") == 1


def test_missing_dask_and_huge_studies_exit_2_with_how_to_fix_it(
    monkeypatch: pytest.MonkeyPatch, capsys: pytest.CaptureFixture[str]
) -> None:
    # issue 24: without dask, --backend dask was a ModuleNotFoundError traceback (exit 1); a
    # 1e8-variant study a MemoryError traceback
    monkeypatch.setitem(sys.modules, "dask", None)  # as if not installed
    monkeypatch.setitem(sys.modules, "distributed", None)
    assert main(["montecarlo", str(STUDY), "-n", "4", "--backend", "dask"]) == 2
    err = capsys.readouterr().err
    assert err.startswith("crashsim: error: the Dask backend needs dask.distributed, which "
                          "cannot be imported") and err.count("\n") == 1  # fmt: skip
    assert "pip install 'dask[distributed]'" in err and 'backend "local"' in err
    monkeypatch.undo()
    from crashsim.studies import design

    def never(*args: object, **kwargs: object) -> None:
        raise AssertionError("the design of a refused study was made")

    monkeypatch.setattr(design, "grid", never)
    monkeypatch.setattr(design, "monte_carlo_sample", never)
    for args in (["montecarlo", str(STUDY), "-n", "100000000"],
                 ["sweep", str(SEED), "--vary", "red.speed=10:20:10000", "--vary",
                  "restitution=0:0.2:10000"]):  # fmt: skip
        assert main(args) == 2
        err = capsys.readouterr().err
        assert err.startswith("crashsim: error: the study's 100,000,000 variants would take ")
        assert "run at most" in err and err.count("\n") == 1


def test_every_variant_failing_exits_1(capsys: pytest.CaptureFixture[str]) -> None:
    assert main(["sweep", str(SEED), "--vary", "red.position_x=-2,-1.5"]) == 1
    captured = capsys.readouterr()
    assert "InitialOverlapError" in captured.out
    assert "every variant failed" in captured.err


def test_ctrl_c_writes_what_finished_and_exits_130(tmp_path: Path) -> None:
    out = tmp_path / "partial.csv"
    proc = subprocess.Popen(
        [sys.executable, "-m", "crashsim", "montecarlo", str(STUDY), "-n", "100000", "--out",
         str(out), "--threads", "1", "--progress"],
        stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True,
        env={**os.environ, "PYTHONUNBUFFERED": "1"},
    )
    assert proc.stderr is not None
    drawn = ""
    deadline = time.monotonic() + 60
    # the bar counts a finished variant (under load the first chunk may take over a second)
    while not re.search(r"\| *[1-9]\d*/100000", drawn) and time.monotonic() < deadline:
        drawn = drawn[-400:] + proc.stderr.read(200)
    proc.send_signal(signal.SIGINT)
    stdout, stderr = proc.communicate(timeout=60)
    assert proc.returncode == 130, stderr
    frame = pd.read_csv(out, index_col="variant")
    ok = frame["status"] == "ok"
    assert 0 < ok.sum() < 100000 and (frame.loc[~ok, "status"] == "not run").all()
    assert "not run (interrupted)" in stdout
