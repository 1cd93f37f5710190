"""Issue 10 (reliability) through the Python API and the command line: a run that never
ended, a history without bound. Each test is named after the bug it pins."""

from __future__ import annotations

import math
from pathlib import Path

import crashsim as cs
import numpy as np
import pytest
from crashsim.cli import main
from crashsim.io.scenefile import load_scene, loads_scene

PLATE_INTO_WALL = """
format_version = 1
title = "1 mm plate edge-on into a 1 mm wall at 100 m/s"
[run]
duration = "0.1 s"
dt = "1 ms"
[contact]
depth_of_penetration = "0 ms"
[[vehicles]]
name = "plate"
box = { length = "0.5 m", width = "1 mm", height = "1 m" }
mass = "100 kg"
position = ["-5 m", 0, "1 m"]
heading = "90 deg"
velocity = ["100 m/s", 0]
[[vehicles]]
name = "wall"
box = { length = "1 mm", width = "10 m", height = "2 m" }
mass = "10000 kg"
position = [0, 0, "1 m"]
"""


def test_plate_edge_on_into_a_wall_with_zero_depth_of_penetration_ends() -> None:
    # It ran forever at 100 % CPU, growing memory by about 18 MB/s, deaf to Ctrl-C.
    result = loads_scene(PLATE_INTO_WALL).simulate()
    assert len(result.impacts) == 1
    imp = result.impacts[0]
    assert imp.time == imp.first_contact_time  # dt_p = 0
    # central collinear: delta-V = (1 + e) m2 / (m1 + m2) * closing speed, e = 0.1
    assert imp.speed_change("plate") == pytest.approx(1.1 * 10000 / 10100 * 100, rel=1e-12)


def seed_scene() -> cs.Scene:
    red = cs.Vehicle.box(4.5, 1.8, 1.4, mass=1450.0, name="red")
    blue = cs.Vehicle.box(4.6, 1.8, 1.45, mass=1500.0, name="blue")
    scene = cs.Scene()
    scene.add(red, position=(-3.65, 0.3, 0.7), velocity=(cs.mph(30), 0, 0))
    scene.add(blue, position=(0.0, 0.0, 0.725), heading=cs.deg(90))
    return scene


def test_record_interval_thins_the_samples_and_keeps_every_event() -> None:
    scene = seed_scene()
    full = scene.run(duration=1.0, dt=1e-3)
    thin = scene.run(duration=1.0, dt=1e-3, record_interval=0.05)
    assert (full.record_interval, thin.record_interval) == (1e-3, pytest.approx(0.05))
    assert full.t.size == 1003  # the start, 1000 step ends, the first overlap, the exchange
    assert thin.t.size == 23  # the start, 20 kept step ends (to 1 s), first overlap, exchange
    imp = thin.impacts[0]
    for t in (imp.first_contact_time, imp.time, 1.0):
        assert t in thin.t
    # The impacts are the same bits; a state between samples is the same free motion.
    assert imp.to_dict() == full.impacts[0].to_dict()
    for name in ("red", "blue"):
        a, b = full.state(name, 0.7375), thin.state(name, 0.7375)
        np.testing.assert_allclose(a["position"], b["position"], rtol=0, atol=1e-12)


def test_a_history_above_the_limit_is_refused_before_the_run() -> None:
    # `--duration "1e4 s"` under a 2.5 GB limit aborted ("memory allocation of 208 bytes
    # failed", exit 134): about 460 B of history per step, without bound.
    with pytest.raises(cs.ParameterError, match=r"record_interval = [0-9.e+-]+ s or more fits"):
        seed_scene().run(duration=100.0, dt=1e-3, record_interval=1e-3, max_history_bytes=2**20)
    for bad in (0, -1, 1.5, True, "1 GB"):
        with pytest.raises(cs.ParameterError, match="max_history_bytes"):
            seed_scene().run(duration=0.1, max_history_bytes=bad)  # type: ignore[arg-type]
    with pytest.raises(cs.ParameterError, match="record_interval"):
        seed_scene().run(duration=0.1, record_interval=0.0)


def test_a_long_run_keeps_about_a_hundred_thousand_samples_by_default() -> None:
    scene = cs.Scene()
    scene.add(cs.Vehicle.box(4.5, 1.8, 1.4, mass=1450.0, name="a"), position=(0, 0, 0.7))
    scene.add(cs.Vehicle.box(4.5, 1.8, 1.4, mass=1450.0, name="b"), position=(10, 0, 0.7))
    result = scene.run(duration=300.0, dt=1e-3)
    assert result.record_interval == pytest.approx(3e-3)
    assert result.t.size == 100_001 and result.t[-1] == 300.0


def test_record_interval_in_a_scene_file_and_on_the_command_line(tmp_path: Path) -> None:
    text = PLATE_INTO_WALL.replace('dt = "1 ms"', 'dt = "1 ms"\nrecord_interval = "10 ms"')
    case = loads_scene(text)
    assert case.run.record_interval == pytest.approx(0.01)
    assert case.simulate().record_interval == pytest.approx(0.01)
    with pytest.raises(cs.CrashsimError, match="record_interval"):
        loads_scene(text.replace('"10 ms"', '"-1 ms"'))
    path = tmp_path / "case.toml"
    path.write_text(PLATE_INTO_WALL)
    assert load_scene(path).run.record_interval is None
    # Refused before the run (in about a second), with the interval that fits: exit 2.
    code = main(
        ["run", str(path), "--duration", "1e4 s", "--record-interval", "1 ms", "--out", "x"]
    )
    assert code == 2 and not (tmp_path / "x").exists()


def test_a_refused_history_names_a_size_that_fits() -> None:
    scene = seed_scene()
    with pytest.raises(cs.ParameterError) as err:
        scene.run(duration=10.0, dt=1e-3, record_interval=1e-3, max_history_bytes=100_000)
    fits = float(str(err.value).split("record_interval = ")[1].split(" ")[0])
    result = scene.run(duration=10.0, dt=1e-3, record_interval=fits, max_history_bytes=100_000)
    assert math.isclose(result.record_interval, math.floor(fits / 1e-3) * 1e-3, rel_tol=1e-12)
