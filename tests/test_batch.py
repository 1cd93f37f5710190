"""Batches (crashsim.batch, the core's batch.rs): the same bits whatever the thread count,
each variant equal to its own Scene.run (the report's PDOF and EDR delta-V included), failed
variants listed while the others finish, bad overrides refused naming the key, Ctrl-C keeping
what finished; the scene as a value (Scene.to_spec: JSON, pickle) and the contact parameters
checked once by the engine."""

from __future__ import annotations

import math
import pickle
import signal
from pathlib import Path

import crashsim as cs
import numpy as np
import pytest
from crashsim import _core
from crashsim.analysis.report import pdof
from crashsim.batch import BatchResult, VariantError, run_batch

EXAMPLES = Path(__file__).resolve().parents[1] / "examples"
MPH30 = 30.0 * 0.44704


def seed(red_position=(-3.65, 0.3, 0.7), red_velocity=(MPH30, 0.0, 0.0), **contact) -> cs.Scene:
    """The seed's 90 deg side impact (examples/seed-90deg.toml) with red's state given."""
    red = cs.Vehicle.box(4.5, 1.8, 1.4, mass=1450.0, name="red")
    blue = cs.Vehicle.box(4.6, 1.8, 1.45, mass=1500.0, name="blue")
    scene = cs.Scene(depth_of_penetration=0.030, **contact)
    scene.add(red, position=red_position, heading=0.0, velocity=red_velocity)
    scene.add(blue, position=(0.0, 0.0, 0.725), heading=math.pi / 2)
    return scene


def seed_overrides(n: int) -> dict[str, np.ndarray]:
    """Red's speed 9-17 m/s with a little sideways, its lateral offset 0.3 to -1.2 m."""
    f = np.linspace(0.0, 1.0, n)
    velocity = np.zeros((n, 2, 3))
    velocity[:, 0, 0] = 9.0 + 8.0 * f
    velocity[:, 0, 1] = 0.5 * f
    position = np.zeros((n, 2, 3))
    position[:, 0] = np.c_[np.full(n, -3.65), 0.3 - 1.5 * f, np.full(n, 0.7)]
    position[:, 1] = (0.0, 0.0, 0.725)
    return {"velocity": velocity, "position": position}


def same_bits(a: BatchResult, b: BatchResult) -> None:
    assert list(a.columns) == list(b.columns)
    for name in a.columns:
        assert a.columns[name].dtype == b.columns[name].dtype, name
        assert a.columns[name].tobytes() == b.columns[name].tobytes(), name
    assert a.errors == b.errors
    assert a.finished.tobytes() == b.finished.tobytes()


def magnitude(v) -> float:
    x, y, z = (float(c) for c in v)
    return math.sqrt(x * x + y * y + z * z)


def test_the_columns_are_the_same_bits_on_1_2_and_4_threads() -> None:
    scene = seed()
    o = seed_overrides(16)
    one = run_batch(scene, o, duration=1.0, dt=1e-3, threads=1)
    assert one.n == 16 and not one.errors and one.finished.all() and not one.interrupted
    for threads in (2, 4):
        same_bits(one, run_batch(scene, o, duration=1.0, dt=1e-3, threads=threads))
    assert list(one.columns)[:4] == [
        "n_impacts",
        "impact1.time",
        "impact1.energy",
        "impact1.red.delta_v",
    ]
    assert one.columns["n_impacts"].dtype == np.int64
    assert all(c.shape == (16,) for c in one.columns.values())
    assert (
        np.unique(
            one.columns["impact1.red.delta_v"][np.isfinite(one.columns["impact1.red.delta_v"])]
        ).size
        > 8
    )


def check_variant(batch: BatchResult, i: int, result: cs.Result) -> None:
    """Variant i's columns equal the same figures read from its own Result, bit for bit."""
    c = {k: v[i] for k, v in batch.columns.items()}
    report = cs.report(result)
    assert c["n_impacts"] == len(result.impacts)
    for k in (1, 2):
        if k > len(result.impacts):
            assert math.isnan(c[f"impact{k}.time"])
            continue
        imp = result.impacts[k - 1]
        assert c[f"impact{k}.time"] == imp.time
        assert c[f"impact{k}.energy"] == imp.energy_dissipated
        parties = {p.name: p for p in report.impacts[k - 1].parties}
        for name in result.vehicles:
            col = f"impact{k}.{name}"
            if name not in imp.moving:
                assert math.isnan(c[f"{col}.delta_v"])
                continue
            body = result.delta_v_body(imp, name)
            assert c[f"{col}.delta_v"] == imp.speed_change(name) == parties[name].delta_v_magnitude
            assert c[f"{col}.delta_v_x"] == imp.delta_v[name][0]
            assert c[f"{col}.delta_v_y"] == imp.delta_v[name][1]
            assert c[f"{col}.delta_v_long"] == body[0] == parties[name].longitudinal
            assert c[f"{col}.delta_v_lat"] == -body[1] == parties[name].lateral
            # the report's PDOF is the engine's, and report.pdof computes the same bits
            assert c[f"{col}.pdof_deg"] == parties[name].pdof_deg == pdof(body)
    for name in result.vehicles:
        tr = result.trajectory(name)
        total = 0.0
        for imp in result.impacts:
            if name in imp.moving:
                total += imp.speed_change(name)
        assert c[f"{name}.total_delta_v"] == total
        assert c[f"{name}.final_x"] == tr.position[-1][0]
        assert c[f"{name}.final_y"] == tr.position[-1][1]
        assert c[f"{name}.final_heading_deg"] == math.degrees(result.heading(name, tr.t[-1]))
        assert c[f"{name}.final_speed"] == magnitude(tr.velocity[-1])
        rest = result.rest(name)
        if rest is None:
            assert math.isnan(c[f"{name}.rest_time"]) and math.isnan(c[f"{name}.rest_x"])
        else:
            assert c[f"{name}.rest_time"] == rest.time
            assert c[f"{name}.rest_x"] == rest.position[0]
            assert c[f"{name}.rest_y"] == rest.position[1]
            assert c[f"{name}.rest_heading_deg"] == math.degrees(rest.heading)


def test_each_box_variant_equals_its_scene_run() -> None:
    n = 5
    o = seed_overrides(n)
    o["contact.restitution"] = np.linspace(0.0, 0.4, n)[:, None]
    batch = run_batch(seed(), o, duration=1.0, dt=1e-3, threads=2)
    assert not batch.errors
    assert batch.columns["n_impacts"].min() >= 1
    for i in range(n):
        scene = seed(
            red_position=o["position"][i, 0],
            red_velocity=o["velocity"][i, 0],
            restitution=float(o["contact.restitution"][i, 0]),
        )
        check_variant(batch, i, scene.run(1.0, 1e-3))


def test_a_mass_variant_equals_the_heavier_vehicle_run_alone() -> None:
    masses = np.array([[1450.0, 1500.0], [2000.0, 1100.0]])
    batch = run_batch(seed(), {"mass": masses}, duration=0.5, dt=1e-3, threads=1)
    assert not batch.errors
    red0 = cs.Vehicle.box(4.5, 1.8, 1.4, mass=1450.0, name="red")
    blue0 = cs.Vehicle.box(4.6, 1.8, 1.45, mass=1500.0, name="blue")
    for i, (m_red, m_blue) in enumerate(masses):
        scene = cs.Scene(depth_of_penetration=0.030)
        for v, m, pos, heading, vel in (
            (red0, m_red, (-3.65, 0.3, 0.7), 0.0, (MPH30, 0.0, 0.0)),
            (blue0, m_blue, (0.0, 0.0, 0.725), math.pi / 2, (0.0, 0.0, 0.0)),
        ):
            scaled = cs.Vehicle(v.mesh, m, v.cg, np.asarray(v.inertia) * (m / v.mass), name=v.name)
            scene.add(scaled, position=pos, heading=heading, velocity=vel)
        check_variant(batch, i, scene.run(0.5, 1e-3))


A, B = 1.1, 1.6
LOCKED = cs.DriverInputs(wheel_states=[("all", "locked", 0.0)])


def wheeled(name: str) -> cs.Vehicle:
    return cs.Vehicle.box(4.6, 1.8, 1.4, mass=1500.0, name=name, ground_clearance=0.15,
                          cg_height=0.55, wheelbase=A + B, track=1.55, wheel_radius=0.3,
                          cg_to_front_axle=A)  # fmt: skip


def ground_scene(speed: float = 12.0, tyre_friction: float | None = None) -> cs.Scene:
    """A car skidding (wheels locked) into the side of a parked, braked one, to rest."""
    scene = cs.Scene(ground=cs.Ground(friction=tyre_friction))
    scene.add(wheeled("a"), (-6.0, 0.4), heading=0.0, velocity=(speed, 0.0, 0.0), inputs=LOCKED)
    scene.add(wheeled("b"), (0.0, 0.0), heading=math.pi / 2, inputs=LOCKED)
    return scene


def test_ground_variants_run_to_rest_and_equal_their_scene_runs() -> None:
    speeds = np.array([11.0, 13.0, 15.0])
    mu = np.array([0.8, 0.6, 0.9])
    velocity = np.zeros((3, 2, 3))
    velocity[:, 0, 0] = speeds
    o = {"velocity": velocity, "ground.tyre_friction": mu}
    batch = run_batch(ground_scene(), o, duration=8.0, dt=1e-3, until="rest", threads=2)
    assert not batch.errors, batch.errors
    same_bits(batch, run_batch(ground_scene(), o, duration=8.0, dt=1e-3, until="rest", threads=1))
    assert np.isfinite(batch.columns["a.rest_time"]).all()
    assert np.isfinite(batch.columns["b.rest_x"]).all()
    for i in range(3):
        scene = ground_scene(float(speeds[i]), float(mu[i]))
        check_variant(batch, i, scene.run(until="rest", max_duration=8.0))


def test_failed_variants_are_listed_and_the_others_finish() -> None:
    o = seed_overrides(5)
    o["position"][1, 0] = (-1.0, 0.0, 0.7)  # red starts inside blue
    eps = np.full((5, 1), 0.1)
    eps[3, 0] = 1.5  # out of range
    o["contact.restitution"] = eps
    batch = run_batch(seed(), o, duration=0.3, dt=1e-3)
    assert batch.finished.all() and not batch.interrupted
    assert [(e.index, e.kind) for e in batch.errors] == [
        (1, "InitialOverlapError"),
        (3, "ParameterError"),
    ]
    assert batch.errors[0].message.startswith("variant 1: ")
    assert "red" in batch.errors[0].message and "blue" in batch.errors[0].message
    assert "restitution" in batch.errors[1].message
    for i in (1, 3):
        assert batch.columns["n_impacts"][i] == -1
        assert math.isnan(batch.columns["red.final_x"][i])
    for i in (0, 2, 4):
        assert batch.columns["n_impacts"][i] >= 0
        assert math.isfinite(batch.columns["red.final_x"][i])


def test_bad_overrides_are_refused_naming_the_key() -> None:
    scene = seed()
    with pytest.raises(cs.ParameterError, match="'speed'|\"speed\""):
        run_batch(scene, {"speed": np.ones(3)}, duration=0.1, dt=1e-3)
    with pytest.raises(cs.ParameterError, match="velocity"):
        run_batch(scene, {"velocity": np.zeros((3, 3))}, duration=0.1, dt=1e-3)
    with pytest.raises(cs.ParameterError, match="contact.friction"):
        run_batch(scene, {"contact.friction": np.zeros((3, 2))}, duration=0.1, dt=1e-3)
    with pytest.raises(cs.ParameterError, match="ground.body_friction"):
        run_batch(scene, {"ground.body_friction": np.ones(3)}, duration=0.1, dt=1e-3)
    with pytest.raises(cs.ParameterError, match="mass"):
        run_batch(scene, {"velocity": np.zeros((3, 2, 3)), "mass": np.ones((4, 2))},
                  duration=0.1, dt=1e-3)  # fmt: skip
    with pytest.raises(cs.ParameterError, match="give n"):
        run_batch(scene, duration=0.1, dt=1e-3)
    with pytest.raises(cs.ParameterError, match="threads"):
        run_batch(scene, n=2, duration=0.1, dt=1e-3, threads=0)
    with pytest.raises(cs.ParameterError, match="dt"):
        run_batch(scene, n=2, duration=0.1, dt=0.0)
    with pytest.raises(cs.ParameterError, match="duration"):
        run_batch(scene, n=2, duration="1 s", dt=1e-3)  # type: ignore[arg-type]
    empty = run_batch(scene, None, n=0, duration=0.1, dt=1e-3)
    assert empty.n == 0 and all(c.shape == (0,) for c in empty.columns.values())
    assert "impact1.red.pdof_deg" in empty.columns
    # no overrides: n copies of the scene
    same = run_batch(scene, n=3, duration=0.3, dt=1e-3)
    assert np.unique(same.columns["impact1.time"]).size == 1


def test_progress_is_called_from_the_caller_and_ctrl_c_keeps_what_finished() -> None:
    n = 400
    o = seed_overrides(n)
    calls: list[tuple[int, int]] = []
    whole = run_batch(
        seed(), o, duration=1.0, dt=1e-3, threads=1, progress=lambda d, k: calls.append((d, k))
    )
    assert calls[-1] == (n, n)
    assert [d for d, _ in calls] == sorted(d for d, _ in calls)

    def interrupt(done: int, total: int) -> None:
        if done >= 5:
            signal.raise_signal(signal.SIGINT)

    cut = run_batch(seed(), o, duration=1.0, dt=1e-3, threads=1, progress=interrupt)
    assert cut.interrupted
    done = int(cut.finished.sum())
    assert 5 <= done < n
    assert not cut.errors
    for name, column in cut.columns.items():
        kept = column[cut.finished]
        assert kept.tobytes() == whole.columns[name][cut.finished].tobytes(), name
        rest = column[~cut.finished]
        assert (rest == -1).all() if column.dtype == np.int64 else np.isnan(rest).all()


def test_an_exception_in_progress_stops_the_batch_and_propagates() -> None:
    def boom(done: int, total: int) -> None:
        raise RuntimeError("stop here")

    with pytest.raises(RuntimeError, match="stop here"):
        run_batch(seed(), seed_overrides(50), duration=1.0, dt=1e-3, progress=boom)


def test_a_batch_result_is_plain_picklable_data() -> None:
    batch = run_batch(seed(), seed_overrides(3), duration=0.3, dt=1e-3)
    back = pickle.loads(pickle.dumps(batch))
    same_bits(batch, back)
    assert back.n == 3 and back.interrupted is False
    assert VariantError(1, "ParameterError", "variant 1: x") == VariantError(
        1, "ParameterError", "variant 1: x"
    )


# -- the scene as a value ------------------------------------------------------------------


def test_the_scene_spec_round_trips_through_json_and_pickle_to_the_same_run() -> None:
    scene = ground_scene()
    scene.contact("a", "b", restitution=0.3, centroid=("a", (2.0, 0.0, 0.0)))
    spec = scene.to_spec(3.0, 1e-3)
    text = spec.to_json()
    back = _core.SceneSpec.from_json(text)
    assert back.to_json() == text
    assert pickle.loads(pickle.dumps(spec)).to_json() == text
    assert spec.names == ["a", "b"] and spec.run_options == (3.0, 1e-3, False)
    ran, again = spec.run(), back.run()
    for key in ("t", "position", "orientation", "velocity", "wheel_load"):
        assert np.asarray(ran[key]).tobytes() == np.asarray(again[key]).tobytes(), key
    with pytest.raises(cs.ParameterError, match="restitution"):
        _core.SceneSpec.from_json(text.replace('"restitution":0.3', '"restitution":7.0'))
    with pytest.raises(cs.ParameterError, match="invalid"):
        _core.SceneSpec.from_json("{}")


def test_contact_parameters_are_one_typed_value_checked_by_the_engine() -> None:
    d = _core.ContactParams()
    assert (d.depth_of_penetration, d.restitution, d.friction, d.pitch) == (0.03, 0.1, 0.6, 0.0)
    assert (d.restitution_mode, d.centroid, d.normal) == ("total", "auto", "horizontal")
    # the scene's defaults are the engine's
    assert cs.Scene().defaults["restitution"] == d.restitution
    p = _core.ContactParams(depth_of_penetration="auto", normal="vector", normal_vector=(1, 0, 0))
    assert p.needs_stiffness and p.depth_of_penetration == "auto"
    assert list(p.normal_vector) == [1.0, 0.0, 0.0]
    assert p == _core.ContactParams(
        depth_of_penetration="auto", normal="vector", normal_vector=(1.0, 0.0, 0.0)
    )
    for bad in ({"restitution": 1.5}, {"friction": -1.0}, {"depth_of_penetration": 0.07},
                {"pitch": 2.0}, {"normal": "sideways"}):  # fmt: skip
        with pytest.raises(cs.ParameterError):
            _core.ContactParams(**bad)
    with pytest.raises(cs.ParameterError, match="restitution"):
        cs.Scene(restitution=2.0)
