"""The ``crashsim`` command line on scene files: ``run`` end to end in a subprocess (every
output reopened by an independent reader), ``check``, the exit codes (0, 1, 2, 130), one-line
messages, the CSV against the run's own trajectories and a closed form."""

from __future__ import annotations

import csv
import json
import math
import os
import re
import signal
import subprocess
import sys
import time
from io import StringIO
from pathlib import Path

import crashsim as cs
import matplotlib.image
import numpy as np
import pytest
import trimesh
from conftest import REPO
from crashsim import cli
from crashsim.cli import main, write_csv
from crashsim.io.scenefile import load_scene, loads_scene

EXAMPLES = REPO / "examples"
SEED = EXAMPLES / "seed-90deg.toml"
PER_VEHICLE = 14  # CSV columns per vehicle: x y z, heading, 4 quaternion, 3 velocity, 3 spin


def crashsim(*args: str, cwd: Path, timeout: float = 300.0) -> subprocess.CompletedProcess[str]:
    return subprocess.run(
        [sys.executable, "-m", "crashsim", *args],
        cwd=cwd,
        capture_output=True,
        text=True,
        timeout=timeout,
        check=False,
    )


# -- run, end to end -------------------------------------------------------------------------


def test_run_writes_every_output_and_each_reopens(tmp_path: Path) -> None:
    out = tmp_path / "out"
    done = crashsim("run", str(SEED), "--out", str(out), cwd=tmp_path)
    assert done.returncode == 0, done.stderr
    assert "Traceback" not in done.stderr
    assert "Seed example 1" in done.stdout and "wrote:" in done.stdout
    want = load_scene(SEED).simulate()  # the same run in this process (deterministic)

    # the time histories: one row per sample, t and 15 columns per vehicle, SI
    csv_path = out / "time-histories.csv"
    header = csv_path.read_text(encoding="utf-8").splitlines()[0].split(",")
    assert header[:3] == ["t [s]", "red x [m]", "red y [m]"]
    assert len(header) == 1 + PER_VEHICLE * 2 and "blue wz (yaw rate) [rad/s]" in header
    table = np.loadtxt(csv_path, delimiter=",", skiprows=1)
    assert table.shape == (want.t.size, 1 + PER_VEHICLE * 2)
    # written with 15 significant digits
    assert np.allclose(table[:, 0], want.t, rtol=1e-14, atol=1e-17)
    for k, name in enumerate(want.vehicles):
        tr = want.trajectory(name)
        cols = table[:, 1 + PER_VEHICLE * k : 1 + PER_VEHICLE * (k + 1)]
        assert np.allclose(cols[:, 0:3], tr.position, rtol=1e-14, atol=1e-14)
        assert np.allclose(cols[:, 4:8], tr.orientation, rtol=1e-14, atol=1e-14)
        assert np.allclose(cols[:, 8:11], tr.velocity, rtol=1e-14, atol=1e-14)
        assert np.allclose(cols[:, 11:14], tr.angular_velocity, rtol=1e-14, atol=1e-14)
    assert table[0, 9] == pytest.approx(cs.mph(30.0), rel=1e-14)  # red's vx at t = 0
    assert table[0, 4 + PER_VEHICLE] == pytest.approx(math.pi / 2, rel=1e-14)  # blue's heading

    # the report
    report = json.loads((out / "report.json").read_text(encoding="utf-8"))
    assert report == json.loads(cs.build_report(want).to_json())
    # the impacts: one row per exchange, a column per number or word of the report's record
    with open(out / "impacts.csv", newline="", encoding="utf-8") as f:
        header, *rows = list(csv.reader(f))
    (imp,) = report["impacts"]
    (row,) = rows
    cell = dict(zip(header, row, strict=True))
    assert cell["number"] == "1" and (cell["vehicles.1"], cell["vehicles.2"]) == ("red", "blue")
    assert float(cell["closing_speed"]) == pytest.approx(imp["closing_speed"], rel=1e-14)
    assert float(cell["normal.y"]) == pytest.approx(imp["normal"][1], rel=1e-14, abs=1e-30)
    assert float(cell["contact_frame.t.y"]) == pytest.approx(imp["contact_frame"][1][1], rel=1e-14)
    for f in imp["figures"]:  # every figure by its name
        assert float(cell[f"figures.{f['name']}"]) == pytest.approx(f["value"], rel=1e-14)
    for p in imp["parties"]:  # per vehicle by role
        dv = float(cell[f"vehicle_{p['role']}.delta_v.magnitude"])
        assert dv == pytest.approx(p["delta_v"]["magnitude"], rel=1e-14)
    assert cell["depth_of_penetration.series_stiffness"] == ""  # None: no stiffness data
    # the pictures
    for name in ("trajectories.png", "impact-1.png"):
        img = matplotlib.image.imread(out / name)
        assert img.ndim == 3 and img.shape[0] > 200 and img.shape[1] > 200, name
        assert float(np.ptp(img[..., :3])) > 0.5  # not a blank picture
    assert not (out / "impact-2.png").exists()  # one impact, one picture
    # the 3-D motion
    glb = trimesh.load(out / "motion.glb")
    assert isinstance(glb, trimesh.Scene) and len(glb.geometry) >= 2


def test_run_default_folder_overrides_and_no_pictures(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch, capsys: pytest.CaptureFixture[str]
) -> None:
    monkeypatch.chdir(tmp_path)
    argv = ["run", str(SEED), "--duration", "0.1", "--dt", "2 ms", "--no-pictures"]
    assert main(argv) == 0
    out = tmp_path / "seed-90deg-out"  # <scene name>-out in the current folder
    assert sorted(p.name for p in out.iterdir()) == [
        "impacts.csv", "report.json", "time-histories.csv"
    ]  # fmt: skip
    t = np.loadtxt(out / "time-histories.csv", delimiter=",", skiprows=1)[:, 0]
    assert t[-1] == pytest.approx(0.1, abs=1e-15)  # --duration
    # --dt: the step ends are the multiples of 2 ms; the other samples are the first overlap
    # and the exchange (samples of their own)
    steps = np.round(t / 0.002)
    on_grid = np.abs(t - steps * 0.002) < 1e-12
    assert set(np.unique(steps[on_grid]).astype(int)) == set(range(51))
    assert int(np.count_nonzero(~on_grid)) == 2
    assert "crashsim: note" not in capsys.readouterr().err


def test_the_files_output_settings(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    text = SEED.read_text(encoding="utf-8") + (
        '\n[output]\ndir = "results"\ncsv = false\npictures = false\nglb = false\n'
    )
    path = tmp_path / "case.toml"
    path.write_text(text, encoding="utf-8")
    assert main(["run", str(path)]) == 0
    assert [p.name for p in (tmp_path / "results").iterdir()] == ["report.json"]


def test_csv_heading_is_the_closed_form_of_a_spin(tmp_path: Path) -> None:
    """A box spinning about its vertical principal axis keeps its angular velocity:
    heading(t) = h0 + w t, past +-pi (the column is unwrapped)."""
    case = loads_scene(
        """format_version = 1
[[vehicles]]
name = "spinner"
box = { length = "4.5 m", width = "1.8 m", height = "1.4 m" }
mass = "1450 kg"
position = [0, 0]
heading = "170 deg"
speed = "10 m/s"
direction = "-30 deg"
yaw_rate = "200 deg/s"
"""
    )
    result = case.simulate(duration=3.0, dt=0.01)
    header = write_csv(result, tmp_path / "h.csv")
    table = np.loadtxt(tmp_path / "h.csv", delimiter=",", skiprows=1)
    assert header[4] == "spinner heading [rad]"
    t, heading = table[:, 0], table[:, 4]
    want = cs.deg(170.0) + cs.deg(200.0) * t
    assert want[-1] > 4 * math.pi  # more than one and a half turns past +pi
    assert np.allclose(heading, want, rtol=0.0, atol=1e-9)
    v = cs.deg(-30.0)
    assert np.allclose(table[:, 1], 10.0 * math.cos(v) * t, rtol=0, atol=1e-9)
    assert np.allclose(table[:, 2], 10.0 * math.sin(v) * t, rtol=0, atol=1e-9)
    assert np.allclose(table[:, 14], cs.deg(200.0), rtol=0, atol=1e-12)  # yaw rate


def test_progress_bar() -> None:
    stream = StringIO()
    bar = cli.ProgressBar(0.5, stream, width=10)
    bar(0.25)
    assert stream.getvalue() == "\r  [#####.....]  50.0 %  t = 0.250 of 0.5 s"
    bar.close(done=True)
    assert stream.getvalue().endswith("[##########] 100.0 %  t = 0.500 of 0.5 s\n")
    quiet = StringIO()
    cli.ProgressBar(1.0, quiet).close(done=True)  # never drawn: nothing written
    assert quiet.getvalue() == ""


SPINNER = """format_version = 1
[run]
duration = "{duration}"
dt = "10 ms"
[[vehicles]]
name = "spinner"
box = {{ length = "4.5 m", width = "1.8 m", height = "1.4 m" }}
mass = "1450 kg"
position = [0, 0]
yaw_rate = "10 rad/s"
"""  # one box spinning fast: the rotation's sub-steps make each step slow, samples few


def test_progress_flag_draws_the_bar(tmp_path: Path) -> None:
    (tmp_path / "spin.toml").write_text(SPINNER.format(duration="1000 s"), encoding="utf-8")
    done = crashsim("run", "spin.toml", "--progress", "--no-pictures", "--out", "o", cwd=tmp_path)
    assert done.returncode == 0, done.stderr
    # (text mode reads each carriage return as a new line)
    assert done.stderr.count("%  t = ") >= 2 and done.stderr.startswith("\n  [")
    bar, _, outputs = done.stderr.partition("100.0 %  t = 1000.000 of 1000 s\n")
    assert bar and outputs
    # then a line per output as it is written, with its time
    lines = outputs.splitlines()
    assert [line.split(" ...")[0] for line in lines] == [
        "  writing report.json",
        "  writing time-histories.csv",
    ]
    assert all(re.fullmatch(r"  writing \S+ \.\.\. \d+\.\d s", line) for line in lines)


POLE = """format_version = 1
[run]
duration = "0.2 s"
dt = "1 ms"
[[vehicles]]
name = "red"
box = { length = "4.5 m", width = "1.8 m", height = "1.4 m" }
mass = "1450 kg"
position = ["-3 m", "0.4 m", "0.7 m"]
speed = "10 m/s"
[[obstacles]]
name = "pole"
pole = { diameter = "0.3 m", height = "6 m" }
position = [0, 0, 0]
"""  # a box car into a pole, no ground: one exchange, at 0.17 s


def test_run_draws_an_impact_with_a_fixed_obstacle(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    # Was: "impact 1 is with the fixed obstacle 'pole': no picture of it", no impact-1.png.
    (tmp_path / "pole.toml").write_text(POLE, encoding="utf-8")
    assert main(["run", str(tmp_path / "pole.toml"), "--out", str(tmp_path / "out")]) == 0
    out = capsys.readouterr().out
    assert "no picture" not in out and str(tmp_path / "out" / "impact-1.png") in out
    img = matplotlib.image.imread(tmp_path / "out" / "impact-1.png")
    assert img.shape[:2] == (984, 1800) and float(np.ptp(img[..., :3])) > 0.5


# -- check ---------------------------------------------------------------------------------


def test_check_passes_on_the_seed_example(capsys: pytest.CaptureFixture[str]) -> None:
    assert main(["check", str(SEED)]) == 0
    out = capsys.readouterr().out
    assert "first_overlap" in out and "pass" in out


def test_check_fails_with_exit_1_when_fcl_disagrees(
    monkeypatch: pytest.MonkeyPatch, capsys: pytest.CaptureFixture[str]
) -> None:
    class Disagrees:
        ok = False

        def __str__(self) -> str:
            return "first_overlap red - blue FAIL"

    monkeypatch.setattr(cli.scenes, "cross_check", lambda result: Disagrees())
    assert main(["check", str(SEED)]) == 1
    assert "FAIL" in capsys.readouterr().out


# -- exit codes and messages ---------------------------------------------------------------

BAD = {
    "a speed as a mass": ('"1450 kg"', '"30 mph"', "vehicles[0].mass"),
    "a typo": ("speed = ", "sped = ", "vehicles[0].sped"),
    "bad TOML": ('mass = "1500 kg"', 'mass = "1500 kg', "line {line}, column"),
    "an unknown preset": (
        'box = { length = "4.5 m", width = "1.8 m", height = "1.4 m" }',
        'generate = { preset = "tank" }',
        "vehicles[0].generate.preset",
    ),
    "a missing mesh": (
        'box = { length = "4.5 m", width = "1.8 m", height = "1.4 m" }',
        'mesh = "car.stl"',
        "vehicles[0].mesh",
    ),
}


@pytest.mark.parametrize("case", list(BAD))
def test_bad_scene_files_exit_2_with_one_line(
    case: str, tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    old, new, key = BAD[case]
    text = SEED.read_text(encoding="utf-8")
    assert old in text
    path = tmp_path / "bad.toml"
    text = text.replace(old, new, 1)
    path.write_text(text, encoding="utf-8")
    key = key.format(line=text.splitlines().index(new) + 1 if case == "bad TOML" else 0)
    assert main(["run", str(path), "--out", str(tmp_path / "o")]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and err.startswith(f"crashsim: error: {path}: ")
    assert key in err
    assert not (tmp_path / "o").exists()  # nothing ran, nothing was written


def test_bad_input_in_a_subprocess_has_no_traceback(tmp_path: Path) -> None:
    (tmp_path / "bad.toml").write_text("format_version = 1\nmass = 3\n", encoding="utf-8")
    done = crashsim("run", "bad.toml", cwd=tmp_path)
    assert done.returncode == 2 and done.stdout == ""
    assert done.stderr == (
        "crashsim: error: bad.toml: mass: unknown key: (the keys here: format_version, title, "
        "description, run, contact, pairs, vehicles, output, ground, obstacles, pedestrians, "
        "cyclists, joints, study, fit, evidence)\n"
    )
    done = crashsim("check", "missing.toml", cwd=tmp_path)
    assert (done.returncode, done.stderr) == (2, "crashsim: error: missing.toml: no such file\n")


def test_overlapping_vehicles_exit_2_naming_the_file(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    path = tmp_path / "overlap.toml"
    path.write_text(
        SEED.read_text(encoding="utf-8").replace('"-3.65 m"', '"-2.0 m"'), encoding="utf-8"
    )
    assert main(["run", str(path), "--out", str(tmp_path / "o")]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and f"{path}: vehicles 'red' and 'blue' already overlap" in err


def test_an_output_folder_that_is_a_file_exits_2_before_running(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch, capsys: pytest.CaptureFixture[str]
) -> None:
    (tmp_path / "taken").write_text("", encoding="utf-8")
    ran = []
    monkeypatch.setattr(cli.SceneFile, "simulate", lambda *a, **k: ran.append(1))
    assert main(["run", str(SEED), "--out", str(tmp_path / "taken")]) == 2
    assert ran == []
    err = capsys.readouterr().err
    assert (
        err == f"crashsim: error: the output folder {tmp_path / 'taken'} is a file: give "
        "another --out\n"
    )


def test_an_output_that_cannot_be_written_exits_1(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch, capsys: pytest.CaptureFixture[str]
) -> None:
    def full(*args: object, **kwargs: object) -> None:
        raise OSError(28, "No space left on device")

    monkeypatch.setattr(cli.output, "write_csv", full)
    assert main(["run", str(SEED), "--out", str(tmp_path), "--no-pictures"]) == 1
    assert capsys.readouterr().err == "crashsim: error: [Errno 28] No space left on device\n"


def test_a_simulation_error_exits_1(
    monkeypatch: pytest.MonkeyPatch, tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    def fail(*args: object, **kwargs: object) -> None:
        raise cs.SimulationError("the engine gave up (test)")

    monkeypatch.setattr(cli.SceneFile, "simulate", fail)
    assert main(["run", str(SEED), "--out", str(tmp_path)]) == 1
    assert capsys.readouterr().err == "crashsim: error: the engine gave up (test)\n"


@pytest.mark.parametrize(
    "argv, words",
    [
        (["run", str(SEED), "--dt", "3 mph"], '"3 mph" is a speed, not a time'),
        (["run", str(SEED), "--duration", "-1"], "the simulated time must be > 0"),
        (["run"], "the following arguments are required: scene"),
        (["frobnicate"], "invalid choice: 'frobnicate'"),
    ],
)
def test_bad_arguments_exit_2_with_one_line(
    argv: list[str], words: str, capsys: pytest.CaptureFixture[str]
) -> None:
    with pytest.raises(SystemExit) as done:
        main(argv)
    assert done.value.code == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and words in err and err.startswith("crashsim")


def test_out_on_unwritable_folder_exits_2(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch, capsys: pytest.CaptureFixture[str]
) -> None:
    # An output folder that cannot be made or written is bad input given on the command
    # line: exit 2 before the run (nothing simulated, nothing created). Run as root (as CI
    # is), a chmod does not stop a write: a folder under a file, and one under /proc (which
    # takes no new folders, even from root), cannot be made by anyone.
    (tmp_path / "a-file").write_text("", encoding="utf-8")
    ran = []
    monkeypatch.setattr(cli.SceneFile, "simulate", lambda *a, **k: ran.append(1))
    for out, words in [
        (tmp_path / "a-file" / "out", f"{tmp_path / 'a-file'} is a file, not a folder"),
        (Path("/proc/crashsim-test/out"), "cannot create the output folder /proc/crashsim-test"),
    ]:
        assert main(["run", str(SEED), "--out", str(out)]) == 2
        err = capsys.readouterr().err
        assert err.count("\n") == 1 and err.startswith("crashsim: error: ") and words in err
        assert "give" in err  # how to fix it
        assert not out.exists()
    assert ran == []


@pytest.mark.skipif(os.geteuid() == 0, reason="root writes into any folder whatever its mode")
def test_out_on_read_only_folder_exits_2(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch, capsys: pytest.CaptureFixture[str]
) -> None:
    locked = tmp_path / "locked"
    locked.mkdir(mode=0o555)
    monkeypatch.setattr(cli.SceneFile, "simulate", lambda *a, **k: pytest.fail("it ran"))
    assert main(["run", str(SEED), "--out", str(locked)]) == 2
    assert "cannot write into the output folder" in capsys.readouterr().err


def test_demo_runs_the_intersection_case_to_rest_and_writes_its_folder(tmp_path: Path) -> None:
    # Was: `crashsim demo` ran the seed's box-car impact without a ground and wrote nothing.
    # Now: generated cars on a ground, run to rest, a lamp post; the report's essentials
    # printed, the report, pictures and case page written to ./crashsim-demo-out.
    done = crashsim("demo", cwd=tmp_path)
    assert done.returncode == 0, done.stderr
    assert "Traceback" not in done.stderr
    out = tmp_path / "crashsim-demo-out"  # the default folder, in the current one
    report = json.loads((out / "report.json").read_text(encoding="utf-8"))
    text = done.stdout
    assert text.startswith("crashsim demo: red (generated sedan, ")
    # the case: a ground, two cars at rest, an impact between them and one with the lamp post
    assert report["run"]["on_ground"]
    pairs = [tuple(i["vehicles"]) for i in report["impacts"]]
    assert pairs[0] == ("red", "blue") and ("blue", "lamp post") in pairs
    assert all(r["at_rest"] for r in report["run_out"])
    # what it prints is the report's: every impact's delta-V, PDOF and energy, each rest
    for imp in report["impacts"]:
        a, b = imp["vehicles"]
        assert (f"impact {imp['number']}: {a} -> {b} at {imp['exchange_time']:.3f} s, closing "
                f"{imp['closing_speed']:.2f} m/s") in text  # fmt: skip
        assert f"energy dissipated {imp['energy']['dissipated'] / 1e3:.1f} kJ" in text
        for p in imp["parties"]:
            dv = p["delta_v"]["magnitude"]
            assert (f"{p['name']:<5} delta-V {dv:.2f} m/s ({dv * 3.6:.1f} km/h), PDOF "
                    f"{p['pdof_deg']:.0f} deg ({p['clock']} o'clock)") in text  # fmt: skip
    for r in report["run_out"]:
        x, y = r["end"]["position"][:2]
        rest = f"{r['vehicle']:<5} at rest at {r['rest_time']:.2f} s at ({x:.2f}, {y:.2f}) m"
        assert rest in text
    # the files it names
    names = ["report.json", "time-histories.csv", "impacts.csv", "trajectories.png", "motion.glb",
             "case.html"]  # fmt: skip
    names += [f"impact-{k}.png" for k in range(1, len(pairs) + 1)]
    assert sorted(p.name for p in out.iterdir()) == sorted(names)
    assert "wrote: " + ", ".join(str(Path("crashsim-demo-out") / n) for n in
                                 [*names[:4], *names[6:], names[4], names[5]]
                                 ) in text  # fmt: skip
    for name in names:
        if name.endswith(".png"):
            img = matplotlib.image.imread(out / name)
            assert img.shape[0] > 500 and float(np.ptp(img[..., :3])) > 0.5, name
    from crashsim.io.viewer.page import page_source

    assert page_source(out / "case.html") == "run"
    assert f"open {Path('crashsim-demo-out') / 'case.html'} in a browser" in text


def test_demo_out_and_speed(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    out = tmp_path / "demo"
    assert main(["demo", "--out", str(out), "--speed", "50 km/h", "--no-pictures"]) == 0
    text = capsys.readouterr().out
    assert "at 50 km/h into the left side of blue" in text
    assert sorted(p.name for p in out.iterdir()) == ["case.html", "impacts.csv", "report.json",
                                                     "time-histories.csv"]  # fmt: skip
    (tmp_path / "file").write_text("x", encoding="utf-8")
    assert main(["demo", "--out", str(tmp_path / "file")]) == 2  # checked before the run
    assert "is a file" in capsys.readouterr().err
    with pytest.raises(SystemExit) as done:
        main(["demo", "--speed", "3 kg"])
    assert done.value.code == 2
    assert "'3 kg': give a number of mph or a speed with its unit" in capsys.readouterr().err


def test_demo_speed_negative_exits_2_with_prefix(capsys: pytest.CaptureFixture[str]) -> None:
    # Was: exit 1 and "no impulse exchange happened within the run" without the prefix.
    for argv in (["demo", "--speed", "-5"], ["demo", "--speed=-5"], ["demo", "--speed", "0"]):
        with pytest.raises(SystemExit) as done:
            main(argv)
        assert done.value.code == 2
        err = capsys.readouterr().err
        assert err.count("\n") == 1 and err.startswith("crashsim: error: argument --speed: ")
        assert "speed > 0" in err


def test_demo_without_an_exchange_exits_1_with_prefix(capsys: pytest.CaptureFixture[str]) -> None:
    assert main(["demo", "--impact-only", "--duration", "10 ms"]) == 1
    out, err = capsys.readouterr()
    assert out == ""
    assert err.startswith("crashsim: error: no impulse exchange happened within the 0.01 s run")
    assert err.count("\n") == 1 and "--duration" in err and "a higher --speed" in err


def test_demo_too_fast_to_exchange_advises_a_lower_speed(
    capsys: pytest.CaptureFixture[str],
) -> None:
    # issue 24: at 1e9 mph red passed through blue in nanoseconds and was told "a higher
    # --speed"
    assert main(["demo", "--impact-only", "--speed", "1e9"]) == 1
    err = capsys.readouterr().err
    assert err == (
        "crashsim: error: no impulse exchange happened within the 0.5 s run: red at 1e+09 mph "
        "passed through blue without one (an overlap that brief is taken for a graze); give a "
        "lower --speed\n"
    )


@pytest.mark.parametrize(
    "argv, words",
    [
        (["run", str(SEED), "--dt", "-1ms"], "argument --dt: '-1ms' is -0.001 s: the time step"),
        (["run", str(SEED), "--dt=-1ms"], "argument --dt: '-1ms' is -0.001 s: the time step"),
        (["check", str(SEED), "--duration", "-2 s"], "the simulated time must be > 0"),
        (["demo", "--dt", "-1"], "argument --dt: '-1' is -1 s: the time step must be > 0"),
        (["dtp-montecarlo", "--seed", "-1"], "seed must be >= 0"),
    ],
)
def test_dt_negative_parses_and_gets_our_message(
    argv: list[str], words: str, capsys: pytest.CaptureFixture[str]
) -> None:
    # Was: argparse's "expected one argument" ("-1ms" looked like an option).
    try:
        code = main(argv)
    except SystemExit as e:
        code = e.code
    assert code == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and err.startswith("crashsim: error: ") and words in err
    assert "expected one argument" not in err


def test_an_option_after_a_value_option_is_still_an_option(
    capsys: pytest.CaptureFixture[str],
) -> None:
    # The "-x" joining must not swallow a real option: --dt is still missing its value.
    with pytest.raises(SystemExit) as done:
        main(["run", str(SEED), "--dt", "--progress"])
    assert done.value.code == 2
    assert "argument --dt: expected one argument" in capsys.readouterr().err
    args = cli._parser().parse_args(["run", str(SEED), "--dt", "2 ms"])
    assert args.dt == pytest.approx(0.002) and args.scene == SEED


def test_ctrl_c_exits_130(tmp_path: Path) -> None:
    # a long run (the engine honours Ctrl-C at its progress callbacks, about every 0.1 s)
    scene = tmp_path / "long.toml"
    scene.write_text(SPINNER.format(duration="1e4 s"), encoding="utf-8")  # 1e6 steps at most
    env = dict(os.environ, PYTHONUNBUFFERED="1")
    proc = subprocess.Popen(
        [sys.executable, "-m", "crashsim", "run", str(scene), "--progress", "--out", "o"],
        cwd=tmp_path,
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        env=env,
        bufsize=0,  # read(1) takes one byte: communicate() gets all the rest
        # A shell starting a job in the background (as a CI runner may) ignores SIGINT in it,
        # and Python leaves an ignored SIGINT ignored: restore the default for the child.
        preexec_fn=lambda: signal.signal(signal.SIGINT, signal.SIG_DFL),
    )
    try:
        assert proc.stderr is not None
        seen = b""
        deadline = time.monotonic() + 120.0
        while b"%" not in seen and time.monotonic() < deadline:  # the run has started
            byte = proc.stderr.read(1)
            if not byte:
                break
            seen += byte
        assert b"%" in seen, seen
        proc.send_signal(signal.SIGINT)
        _, err = proc.communicate(timeout=60.0)
    finally:
        if proc.poll() is None:
            proc.kill()
            proc.wait()
    assert proc.returncode == 130
    text = (seen + err).decode()
    assert text.endswith(" s\ncrashsim: interrupted\n") and "Traceback" not in text


def test_demo_and_montecarlo_still_run(capsys: pytest.CaptureFixture[str]) -> None:
    assert main(["demo", "--impact-only"]) == 0
    assert "red's travel past first overlap: 0.4023 m" in capsys.readouterr().out
    assert main(["dtp-montecarlo", "--samples", "2000", "--json"]) == 0
    assert json.loads(capsys.readouterr().out)["samples"] == 2000


def test_help_lists_the_commands_and_exit_codes(capsys: pytest.CaptureFixture[str]) -> None:
    with pytest.raises(SystemExit) as done:
        main(["--help"])
    assert done.value.code == 0
    out = capsys.readouterr().out
    for word in ("run", "check", "demo", "dtp-montecarlo", "Exit codes", "130"):
        assert word in out
