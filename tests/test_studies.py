"""Studies (crashsim.studies): parameter paths and Scene.with_, distributions and designs,
sweeps and Monte Carlo into a Study, failed and interrupted variants, outputs (frame, CSV,
Parquet, percentiles, pictures), the tornado and Sobol indices."""

from __future__ import annotations

import dataclasses
import math
import os
import signal
from pathlib import Path

import crashsim as cs
import numpy as np
import pytest
from crashsim.batch import run_batch
from crashsim.studies import (
    class_table,
    grid,
    linspace,
    monte_carlo_sample,
    normal,
    paths,
    triangular,
    uniform,
)

DURATION, DT = 0.3, 1e-3  # s


def _scene() -> cs.Scene:
    red = cs.Vehicle.box(4.5, 1.8, 1.4, mass=1450.0, name="red")
    blue = cs.Vehicle.box(4.6, 1.8, 1.45, mass=1500.0, name="blue")
    scene = cs.Scene(depth_of_penetration=0.03, restitution=0.1, friction=0.6)
    scene.add(red, (-3.65, 0.3, 0.7), heading=0.0, velocity=(13.4112, 0.0, 0.0))
    scene.add(blue, (0.0, 0.0, 0.725), heading=np.pi / 2)
    return scene


def _ground_scene() -> cs.Scene:
    car = cs.Vehicle.box(4.5, 1.8, 1.25, mass=1450.0, name="red", cg_height=0.55,
                         ground_clearance=0.15).with_wheels(
        wheelbase=2.7, track=1.5, radius=0.3, cg_to_front_axle=1.2,
        spring_rates=30e3, damping=2.5e3,
    )  # fmt: skip
    scene = cs.Scene(ground=cs.Ground(friction=0.7))
    scene.add(car, (0.0, 0.0), heading=0.0, velocity=(10.0, 0.0, 0.0),
              inputs=cs.DriverInputs(wheel_states=[("all", "locked", 0.0)]))
    return scene


def _equal_runs(a: cs.Result, b: cs.Result) -> None:
    assert len(a.impacts) == len(b.impacts)
    for name in a.vehicles:
        ta, tb = a.trajectory(name), b.trajectory(name)
        assert np.array_equal(ta.position, tb.position)
        assert np.array_equal(ta.velocity, tb.velocity)
    for ia, ib in zip(a.impacts, b.impacts, strict=True):
        assert np.array_equal(ia.impulse, ib.impulse)


# -- parameter paths and Scene.with_ ----------------------------------------------------------


def test_an_unknown_path_names_the_key_and_lists_the_valid_ones() -> None:
    scene = _scene()
    with pytest.raises(cs.StudyError, match='"red.sped".*did you mean "red.speed"') as e:
        scene.with_({"red.sped": 10.0})
    assert e.value.key == "red.sped"
    assert "red/blue.{restitution" in str(e.value) and "blue.{speed" in str(e.value)
    for bad, why in (("green.speed", "no vehicle named 'green'"),
                     ("red/green.friction", "no pair"),
                     ("ground.friction", "needs a ground"),
                     ("speed", "a path is")):
        with pytest.raises(cs.StudyError, match=why):
            paths.parse_path(scene, bad)
    with pytest.raises(cs.StudyError, match="same velocity"):
        paths.overrides(scene, {"red.speed": [1.0], "red.velocity_y": [1.0]})
    with pytest.raises(cs.StudyError, match="set the same input"):
        paths.overrides(scene, {"red/blue.friction": [1.0], "blue/red.friction": [1.0]})
    assert isinstance(e.value, cs.CrashsimError) and isinstance(e.value, ValueError)


def test_placements_are_the_vehicles_initial_states_read_only() -> None:
    scene = _scene()
    placements = scene.placements
    assert isinstance(placements, tuple) and all(isinstance(p, cs.Placement) for p in placements)
    assert [p.vehicle.name for p in placements] == [v.name for v in scene.vehicles]
    assert np.array_equal(placements[0].velocity, [13.4112, 0.0, 0.0])
    with pytest.raises(ValueError, match="read-only"):
        placements[0].velocity[0] = 1.0
    with pytest.raises(dataclasses.FrozenInstanceError):
        placements[0].velocity = np.zeros(3)  # type: ignore[misc]


def test_with_leaves_the_scene_unchanged_and_follows_the_rules() -> None:
    scene = _scene()
    turned = scene.with_({"red.heading": math.radians(10.0), "red.speed": 20.0})
    again = scene.with_({"red.heading": math.radians(10.0)})
    p0 = scene.placements[0]
    assert np.array_equal(p0.velocity, [13.4112, 0.0, 0.0])  # the base is untouched
    p = turned.placements[0]
    # turned about the CG: position kept, velocity turned with the body, then scaled to 20 m/s
    assert np.array_equal(p.position, p0.position)
    assert np.allclose(p.velocity, 20.0 * np.array([math.cos(0.17453292519943295),
                                                    math.sin(0.17453292519943295), 0.0]))
    assert math.isclose(float(np.linalg.norm(again.placements[0].velocity)), 13.4112)
    # a level vehicle's heading is exactly what Scene.add(heading=h) gives
    h = math.radians(10.0)
    assert np.array_equal(p.orientation, [math.cos(h / 2), 0.0, 0.0, math.sin(h / 2)])
    # a vehicle at rest takes its speed along its heading
    moving = scene.with_({"blue.speed": 2.0}).placements[1]
    assert np.allclose(moving.velocity, [0.0, 2.0, 0.0], atol=1e-15)
    assert scene.with_(restitution=0.3).contact_parameters("red", "blue")["restitution"] == 0.3
    assert scene.contact_parameters("red", "blue")["restitution"] == 0.1


@pytest.mark.parametrize(
    "changes",
    [
        {"red.speed": 17.5, "red.heading": 0.05},
        {"red.position_x": -3.9, "red.position_y": 0.8, "red.yaw_rate": 0.4},
        {"red.velocity_x": 12.0, "red.velocity_y": 1.5, "red/blue.friction": 0.3},
        {"restitution": 0.25, "pitch": 0.02, "depth_of_penetration": 0.02},
        {"red.mass": 1800.0, "blue.mass": 1100.0, "red.direction": 0.1},
    ],
)
def test_scene_with_runs_as_that_variant_of_the_batch(changes: dict[str, float]) -> None:
    scene = _scene()
    ov = paths.overrides(scene, {k: [v, v] for k, v in changes.items()})
    b = run_batch(scene, ov, duration=DURATION, dt=DT)
    r = scene.with_(changes).run(duration=DURATION, dt=DT)
    assert b.errors == []
    assert b.columns["impact1.red.delta_v"][1] == r.impacts[0].speed_change("red")
    assert b.columns["red.final_x"][1] == r.trajectory("red").position[-1, 0]
    assert b.columns["blue.final_speed"][1] == np.linalg.norm(r.trajectory("blue").velocity[-1])


def test_ground_paths_and_mass_on_wheels() -> None:
    scene = _ground_scene()
    study = cs.sweep(scene, {"ground.friction": [0.4, 0.8], "red.mass": [1450.0, 2000.0]},
                     until="rest", duration=6.0, dt=2e-3, progress=False)
    assert study.ok.all()
    rest_x = study["red.rest_x"]
    assert rest_x[0] > rest_x[2]  # less friction: further
    assert math.isclose(rest_x[0], rest_x[1], rel_tol=0.05)  # a locked skid barely minds mass
    variant = scene.with_({"ground.friction": 0.4, "red.mass": 2000.0})
    assert variant.vehicles[0].wheels._rates[0] == pytest.approx(30e3 * 2000.0 / 1450.0)
    r = variant.run(until="rest", max_duration=6.0, dt=2e-3)
    assert study["red.rest_x"][1] == r.rest("red").position[0]
    assert study["red.rest_time"][1] == r.rest("red").time
    assert scene.ground.friction == 0.7


# -- distributions and designs ----------------------------------------------------------------


def test_invalid_distribution_parameters_name_the_key() -> None:
    for dist, why in ((normal(15.0, 0.0), "standard deviation must be > 0"),
                      (normal(15.0, -1.0), "standard deviation must be > 0"),
                      (uniform(2.0, 1.0), "lo must be below hi"),
                      (triangular(0.0, 2.0, 1.0), "mode 2 lies outside"),
                      (normal(0.0, 1.0, 50.0, 60.0), "too far in the tail"),
                      (class_table("sedna"), "unknown vehicle class"),
                      (class_table("sedan", "length", k=0), "must be > 0"),
                      (class_table("suv", "width"), "no published standard deviation")):
        with pytest.raises(cs.StudyError, match=why) as e:
            cs.monte_carlo(_scene(), {"red.speed": dist}, n=4, seed=1, progress=False)
        assert e.value.key == "red.speed" and '"red.speed"' in str(e.value)
    with pytest.raises(cs.StudyError, match="is not a distribution"):
        monte_carlo_sample({"red.speed": 15.0}, 4, 1)  # type: ignore[dict-item]
    with pytest.raises(cs.StudyError, match="seed"):
        monte_carlo_sample({"red.speed": normal(1, 1)}, 4, -1)


def test_samples_are_seeded_and_have_their_shape() -> None:
    d = {"a": normal(15.0, 2.0), "b": uniform(0.0, 0.3), "c": triangular(0.2, 0.3, 0.8),
         "d": normal(10.0, 5.0, 8.0, 11.0), "e": class_table("sedan")}
    x = monte_carlo_sample(d, 20_000, 3)
    y = monte_carlo_sample(d, 20_000, 3)
    assert all(np.array_equal(x[k], y[k]) for k in d)
    assert not np.array_equal(x["a"], monte_carlo_sample(d, 20_000, 4)["a"])
    assert abs(np.mean(x["a"]) - 15.0) < 0.05 and abs(np.std(x["a"]) - 2.0) < 0.05
    assert 0.0 <= x["b"].min() and x["b"].max() < 0.3
    assert 0.2 <= x["c"].min() and x["c"].max() <= 0.8
    assert abs(np.mean(x["c"]) - (0.2 + 0.3 + 0.8) / 3) < 0.005  # the triangle's mean
    assert 8.0 <= x["d"].min() and x["d"].max() <= 11.0
    sedan = cs.vehicle_class("sedan").mass
    assert abs(np.mean(x["e"]) - sedan.value) < 5.0
    assert sedan.value - 3 * sedan.sd <= x["e"].min() and x["e"].max() <= sedan.value + 3 * sedan.sd
    assert math.isclose(normal(15.0, 2.0).percentile(95.0), 15.0 + 2.0 * 1.6448536269514722)


def test_grids_are_full_factorial_first_path_slowest() -> None:
    g = grid({"red.speed": linspace(10.0, 20.0, 3), "restitution": [0.0, 0.2]})
    assert list(g["red.speed"]) == [10.0, 10.0, 15.0, 15.0, 20.0, 20.0]
    assert list(g["restitution"]) == [0.0, 0.2] * 3
    assert np.isnan(grid({"depth_of_penetration": ["auto", 0.02]})["depth_of_penetration"][0])
    for spec, why in (({"red.speed": []}, "no values"), ({"red.speed": ["fast"]}, "not a number"),
                      ({"red.speed": linspace(1, 2, 0)}, "count = 0"), ({}, "at least one")):
        with pytest.raises(cs.StudyError, match=why):
            grid(spec)


def test_a_grid_is_made_column_by_column_in_product_order() -> None:
    import itertools

    spec = {"red.speed": [10.0, 11.0, 12.0], "restitution": linspace(0.0, 0.2, 5),
            "friction": [0.5, 0.7], "red.heading": 0.1}  # fmt: skip
    g = grid(spec)
    rows = list(itertools.product([10.0, 11.0, 12.0], np.linspace(0.0, 0.2, 5), [0.5, 0.7],
                                  [0.1]))  # fmt: skip
    assert np.array_equal(np.column_stack(list(g.values())), np.array(rows))
    assert cs.studies.design.grid_size(spec) == 30 == len(rows)
    assert cs.studies.design.grid_size({"red.speed": linspace(0, 1, 10**9)}) == 10**9  # not made


def test_a_study_too_big_for_memory_is_refused_before_its_design_is_made(
    monkeypatch: pytest.MonkeyPatch,
) -> None:
    # issue 24: montecarlo -n 1e8 and a 1e8-variant grid (a list of 1e8 tuples) ended in
    # MemoryError tracebacks
    from crashsim.studies import design, run

    scene = _scene()
    # the estimate is what a study holds: inputs, the engine's overrides, outputs, status
    study = cs.monte_carlo(scene, {"red.speed": normal(13.0, 1.0), "red.heading": uniform(0, 0.1)},
                           n=5, seed=1, duration=DURATION, dt=DT, progress=False)  # fmt: skip
    held = sum(a.nbytes for a in (*study.inputs.values(), *study.outputs.values()))
    held += sum(a.nbytes for a in paths.overrides(scene, study.inputs).values())
    status = 8 + 4 * len("not run")  # per variant: the object array, then "<U7"
    per = held // 5 + status
    assert held % 5 == 0
    keys = ["red.speed", "red.heading"]
    run.check_size(scene, keys, 1000, 2, max_bytes=1000 * per)  # fits exactly
    with pytest.raises(cs.StudyError, match=rf"1,000 variants would take .*\({per:,} bytes each: "
                       r"2 inputs, the engine's overrides, 47 outputs, the status\).*run at most "
                       r"999 variants at a time"):  # fmt: skip
        run.check_size(scene, keys, 1000, 2, max_bytes=1000 * per - 1)

    def never(*args: object, **kwargs: object) -> None:
        raise AssertionError("the design of a refused study was made")

    monkeypatch.setattr(design, "grid", never)
    monkeypatch.setattr(design, "monte_carlo_sample", never)
    with pytest.raises(cs.StudyError, match=r"100,000,000 variants would take 4[0-9.]+ GiB.*"
                       r"study limit of 1\.00 GiB.*max_study_bytes"):  # fmt: skip
        cs.sweep(scene, {"red.speed": linspace(10, 20, 10_000), "restitution":
                         linspace(0, 0.2, 10_000)}, progress=False)  # fmt: skip
    with pytest.raises(cs.StudyError, match=r"100,000,000 variants would take"):
        cs.monte_carlo(scene, {"red.speed": normal(13.0, 1.0)}, n=10**8, seed=1, progress=False)
    with pytest.raises(cs.StudyError, match=r"402,653,184 variants would take"):
        cs.sobol(scene, {"red.speed": uniform(10.0, 16.0)}, n=2**27, progress=False)
    with pytest.raises(cs.StudyError, match="max_study_bytes = 0 is invalid"):
        cs.monte_carlo(scene, {"red.speed": normal(13.0, 1.0)}, n=2, max_study_bytes=0)
    monkeypatch.undo()  # a study under the limit runs as before
    small = cs.monte_carlo(scene, {"red.speed": normal(13.0, 1.0)}, n=3, seed=1,
                           duration=DURATION, dt=DT, progress=False, max_study_bytes=3 * per)
    assert small.ok.all()


def test_an_unknown_column_is_a_study_error_naming_it() -> None:
    # issue 24: tornado(...).table("x") raised a bare KeyError
    t = cs.tornado(_scene(), {"red.speed": (12.0, 14.0)}, duration=DURATION, dt=DT,
                   progress=False)
    with pytest.raises(cs.StudyError, match=r"no column 'x': the inputs are red.speed; outputs "
                       r"such as n_impacts") as e:  # fmt: skip
        t.table("x")
    assert isinstance(e.value, KeyError)  # still what a lookup by name raises
    assert str(e.value).startswith("no column 'x'")  # not KeyError's quoted form
    with pytest.raises(cs.StudyError, match="no column 'x'"):
        t.plot(output="x")


# -- running: a Study -------------------------------------------------------------------------


def test_a_sweep_lists_failed_variants_and_the_rest_finish(tmp_path: Path) -> None:
    scene = _scene()
    study = cs.sweep(scene, {"red.position_x": [-3.65, -2.0], "restitution": [0.1, 1.5]},
                     duration=DURATION, dt=DT, progress=False)
    assert study.n == 4 and list(study.status) == ["ok", "failed", "failed", "failed"]
    kinds = {e.index: e.kind for e in study.errors}
    assert kinds[1] == "ParameterError" and kinds[2] == "InitialOverlapError"
    assert kinds[3] in ("ParameterError", "InitialOverlapError")  # both wrong: either is fair
    first = study.errors[0]
    assert first.message.startswith("variant 1 (red.position_x = -3.65 m, restitution = 1.5): ")
    assert "restitution" in first.message and first.inputs == {"red.position_x": -3.65,
                                                                "restitution": 1.5}
    assert '("red") and 1 ("blue"): they already overlap' in study.errors[1].message
    assert np.isfinite(study["impact1.red.delta_v"][0])
    frame = study.frame
    assert list(frame.columns[:2]) == ["red.position_x", "restitution"]
    assert frame.index.name == "variant" and frame["status"].tolist() == list(study.status)
    # CSV and Parquet hold the same numbers
    import pandas as pd

    study.write(tmp_path / "s.csv")
    study.write(tmp_path / "s.parquet")
    back_csv = pd.read_csv(tmp_path / "s.csv", index_col="variant")
    back_pq = pd.read_parquet(tmp_path / "s.parquet")
    for k in study.outputs:
        assert np.array_equal(back_pq[k].to_numpy(), study[k], equal_nan=True), k
        assert np.array_equal(back_csv[k].to_numpy(), study[k], equal_nan=True), k
    with pytest.raises(cs.StudyError, match=r"\.csv or a \.parquet"):
        study.write(tmp_path / "s.xlsx")


def test_a_study_equals_its_batch_and_one_chunk_or_many() -> None:
    scene = _scene()
    d = {"red.speed": normal(13.0, 1.0), "red.heading": uniform(-0.1, 0.1)}
    a = cs.monte_carlo(scene, d, n=30, seed=5, duration=DURATION, dt=DT, progress=False)
    b = cs.monte_carlo(scene, d, n=30, seed=5, duration=DURATION, dt=DT, progress=False,
                       chunk_size=7, threads=1)
    ov = paths.overrides(scene, monte_carlo_sample(d, 30, 5))
    ref = run_batch(scene, ov, duration=DURATION, dt=DT)
    for k, col in ref.columns.items():
        assert np.array_equal(a[k], col, equal_nan=True), k
        assert np.array_equal(b[k], col, equal_nan=True), k
    assert a.seed == 5 and a.kind == "montecarlo" and a.units["red.heading"] == "rad"


def test_ctrl_c_stops_the_study_and_keeps_what_finished() -> None:
    scene = _scene()
    g = {"red.speed": linspace(10.0, 20.0, 40)}
    full = cs.sweep(scene, g, duration=DURATION, dt=DT, progress=False)
    calls = []

    def progress(done: int, n: int) -> None:
        calls.append(done)
        if done >= 10 and len(calls) < 100:
            os.kill(os.getpid(), signal.SIGINT)  # as Ctrl-C does

    study = cs.sweep(scene, g, duration=DURATION, dt=DT, progress=progress, chunk_size=5,
                     threads=1)
    assert study.interrupted
    ran = study.status == "ok"
    assert 10 <= ran.sum() < 40 and (study.status[~ran] == "not run").all()
    assert np.array_equal(study["impact1.red.delta_v"][ran], full["impact1.red.delta_v"][ran])
    assert np.isnan(study["impact1.red.delta_v"][~ran]).all()
    assert (study["n_impacts"][~ran] == -1).all()


def test_ctrl_c_while_a_chunk_is_taken_keeps_that_chunk_whole(monkeypatch) -> None:
    # Ctrl-C after a chunk returned, while its columns are placed into the study's: the study
    # ends interrupted with that chunk in it, whole (before, the interrupt left the study's
    # loop and the whole study was lost).
    from crashsim.studies import chunks

    place = chunks.place_chunk
    placed = []

    def place_then_ctrl_c(columns, chunk, start, n) -> None:
        placed.append(start)
        if start == 10:
            os.kill(os.getpid(), signal.SIGINT)  # as Ctrl-C does, between two columns
        place(columns, chunk, start, n)

    monkeypatch.setattr(chunks, "place_chunk", place_then_ctrl_c)
    scene = _scene()
    g = {"red.speed": linspace(10.0, 20.0, 40)}
    study = cs.sweep(scene, g, duration=DURATION, dt=DT, progress=False, chunk_size=5,
                     threads=1)
    assert study.interrupted and placed == [0, 5, 10]
    ran = study.status == "ok"
    assert ran[:15].all() and (study.status[15:] == "not run").all()
    assert np.isfinite(study["impact1.red.delta_v"][:15]).all()


def test_an_interrupt_deferred_is_raised_when_the_block_ends() -> None:
    from crashsim.studies.chunks import interrupt_deferred

    done = []
    with pytest.raises(KeyboardInterrupt):
        with interrupt_deferred():
            os.kill(os.getpid(), signal.SIGINT)
            done.append("after the signal")
    assert done == ["after the signal"]
    assert signal.getsignal(signal.SIGINT) is signal.default_int_handler
    with interrupt_deferred():  # no signal: nothing raised
        done.append("quiet")
    assert done[-1] == "quiet"


def test_percentiles_of_every_column() -> None:
    study = cs.monte_carlo(_scene(), {"red.speed": uniform(10.0, 16.0)}, n=40, seed=2,
                           duration=DURATION, dt=DT, progress=False)
    table = study.summary()
    x = study["impact1.red.delta_v"]
    row = table.loc["impact1.red.delta_v"]
    assert row["unit"] == "m/s" and row["n"] == 40
    assert row["P5"] == np.percentile(x, 5) and row["P95"] == np.percentile(x, 95)
    assert row["P50"] == np.median(x) and row["max"] == x.max()
    assert table.loc["red.speed", "unit"] == "m/s"
    assert table.loc["impact1.red.pdof_deg", "unit"] == "deg"
    assert table.loc["impact2.time", "n"] == 0  # no second impact
    assert list(study.summary([10, 90]).columns) == ["unit", "n", "mean", "sd", "min", "P10",
                                                     "P90", "max"]
    with pytest.raises(cs.StudyError, match="outside"):
        study.summary([120])


def test_histograms_are_written(tmp_path: Path) -> None:
    from crashsim.studies.plots import plot_histograms

    study = cs.monte_carlo(_scene(), {"red.speed": uniform(10.0, 16.0)}, n=20, seed=2,
                           duration=DURATION, dt=DT, progress=False)
    written = plot_histograms(study, tmp_path / "h", ["impact1.red.delta_v", "red.speed"])
    names = [p.name for p in written]
    assert names == ["hist-impact1.red.delta_v.png", "hist-red.speed.png"]
    assert all(p.stat().st_size > 5000 for p in written)
    with pytest.raises(cs.StudyError, match="no finite value"):
        plot_histograms(study, tmp_path / "h", ["impact2.time"])


# -- sensitivity -------------------------------------------------------------------------------


def test_the_tornado_runs_each_input_low_and_high_around_the_base(tmp_path: Path) -> None:
    scene = _scene()
    t = cs.tornado(scene, {"red.speed": (10.0, 18.0), "friction": (0.3, 0.9),
                           "restitution": uniform(0.0, 0.4)},
                   duration=DURATION, dt=DT, progress=False)
    assert t.study.n == 7 and t.ranges["restitution"] == pytest.approx((0.02, 0.38))
    assert t.base == {"red.speed": 13.4112, "friction": 0.6, "restitution": 0.1}
    table = t.table("impact1.red.delta_v")
    assert list(table.index) == ["red.speed", "restitution", "friction"]  # largest swing first
    low = scene.with_({"red.speed": 10.0, "friction": 0.6, "restitution": 0.1}).run(
        duration=DURATION, dt=DT)
    assert table.loc["red.speed", "output_low"] == low.impacts[0].speed_change("red")
    assert table.loc["friction", "swing"] < 1e-6  # a full (not sliding) impact
    t.plot(tmp_path / "t.png")
    assert (tmp_path / "t.png").stat().st_size > 5000


def test_sobol_indices_find_the_input_that_matters(tmp_path: Path) -> None:
    s = cs.sobol(_scene(), {"red.speed": uniform(10.0, 16.0), "friction": uniform(0.4, 0.8)},
                 n=32, seed=3, duration=DURATION, dt=DT, progress=False)
    assert s.study.n == 32 * 4
    dv = s.of("impact1.red.delta_v")
    assert dv.loc["red.speed", "S1"] > 0.9 and dv.loc["red.speed", "ST"] > 0.9
    assert abs(dv.loc["friction", "ST"]) < 0.05
    assert "impact2.time" in s.skipped
    with pytest.raises(cs.StudyError, match="no column 'x'"):
        s.of("x")
    s.plot(tmp_path / "s.png")
    assert (tmp_path / "s.png").stat().st_size > 5000
    with pytest.raises(cs.StudyError, match="power of 2"):
        cs.sobol(_scene(), {"red.speed": uniform(10.0, 16.0)}, n=30, progress=False)
