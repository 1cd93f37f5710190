"""crashsim.batch.run_batch against the batch contract (docs/batch-contract.md): written
against the contract only, so they hold for the provisional pure-Python batch and for the
batch engine that replaces it."""

from __future__ import annotations

import math
import pickle

import crashsim as cs
import numpy as np
import pytest
from crashsim.analysis.report import pdof
from crashsim.batch import BatchResult, VariantError, run_batch

DURATION, DT = 0.3, 1e-3  # s


def _scene() -> cs.Scene:
    red = cs.Vehicle.box(4.5, 1.8, 1.4, mass=1450.0, name="red")
    blue = cs.Vehicle.box(4.6, 1.8, 1.45, mass=1500.0, name="blue")
    scene = cs.Scene(depth_of_penetration=0.03, restitution=0.1, friction=0.6)
    scene.add(red, (-3.65, 0.3, 0.7), heading=0.0, velocity=(13.4112, 0.0, 0.0))
    scene.add(blue, (0.0, 0.0, 0.725), heading=np.pi / 2)
    return scene


def _overrides(n: int) -> dict[str, np.ndarray]:
    vel = np.zeros((n, 2, 3))
    vel[:, 0, 0] = np.linspace(8.0, 20.0, n)
    rest = np.linspace(0.0, 0.3, n)[:, None]
    return {"velocity": vel, "contact.restitution": rest}


def _columns(names: list[str], k: int) -> list[str]:
    out = ["n_impacts"]
    for i in range(1, k + 1):
        out += [f"impact{i}.time", f"impact{i}.energy"]
        for n in names:
            out += [f"impact{i}.{n}.{c}" for c in
                    ("delta_v", "delta_v_x", "delta_v_y", "delta_v_long", "delta_v_lat",
                     "pdof_deg")]
    for n in names:
        out += [f"{n}.{c}" for c in ("total_delta_v", "final_x", "final_y", "final_heading_deg",
                                     "final_speed", "rest_time", "rest_x", "rest_y",
                                     "rest_heading_deg")]
    return out


def test_columns_are_the_contracts_in_order_and_shape() -> None:
    b = run_batch(_scene(), _overrides(5), duration=DURATION, dt=DT)
    assert isinstance(b, BatchResult) and b.n == 5
    assert list(b.columns) == _columns(["red", "blue"], 2)
    assert all(v.shape == (5,) for v in b.columns.values())
    assert b.columns["n_impacts"].dtype == np.int64
    assert all(v.dtype == np.float64 for k, v in b.columns.items() if k != "n_impacts")
    assert b.finished.all() and not b.interrupted and b.errors == []
    assert np.all(b.columns["n_impacts"] >= 1)
    assert np.all(np.isnan(b.columns["red.rest_time"]))  # no ground: no rest
    three = run_batch(_scene(), None, n=2, duration=DURATION, dt=DT, max_impacts=3)
    assert list(three.columns) == _columns(["red", "blue"], 3)


def test_each_variant_equals_its_own_scene_run_bit_for_bit() -> None:
    scene = _scene()
    ov = _overrides(4)
    b = run_batch(scene, ov, duration=DURATION, dt=DT)
    for i in range(4):
        variant = scene.with_({"red.velocity_x": ov["velocity"][i, 0, 0],
                               "restitution": ov["contact.restitution"][i, 0]})
        r = variant.run(duration=DURATION, dt=DT)
        imp = r.impacts[0]
        assert b.columns["impact1.time"][i] == imp.time
        assert b.columns["impact1.energy"][i] == imp.energy_dissipated
        for name in ("red", "blue"):
            dv = imp.delta_v[name]
            body = r.delta_v_body(imp, name)
            assert b.columns[f"impact1.{name}.delta_v"][i] == np.linalg.norm(dv)
            assert b.columns[f"impact1.{name}.delta_v_x"][i] == dv[0]
            assert b.columns[f"impact1.{name}.delta_v_y"][i] == dv[1]
            assert b.columns[f"impact1.{name}.delta_v_long"][i] == body[0]
            assert b.columns[f"impact1.{name}.delta_v_lat"][i] == -body[1]  # EDR: + right
            assert b.columns[f"impact1.{name}.pdof_deg"][i] == pdof(body)
            tr = r.trajectory(name)
            assert b.columns[f"{name}.final_x"][i] == tr.position[-1, 0]
            assert b.columns[f"{name}.final_speed"][i] == np.linalg.norm(tr.velocity[-1])
            assert math.isclose(b.columns[f"{name}.final_heading_deg"][i],
                                math.degrees(r.heading(name, float(r.t[-1]))), abs_tol=1e-9)


def test_results_do_not_depend_on_the_thread_count() -> None:
    one = run_batch(_scene(), _overrides(6), duration=DURATION, dt=DT, threads=1)
    two = run_batch(_scene(), _overrides(6), duration=DURATION, dt=DT, threads=2)
    for k in one.columns:
        assert np.array_equal(one.columns[k], two.columns[k], equal_nan=True), k


def test_unknown_keys_and_wrong_shapes_are_parameter_errors_naming_the_key() -> None:
    with pytest.raises(cs.ParameterError, match="contact.restitutoin"):
        run_batch(_scene(), {"contact.restitutoin": np.zeros((2, 1))}, duration=DURATION, dt=DT)
    with pytest.raises(cs.ParameterError, match="velocity"):
        run_batch(_scene(), {"velocity": np.zeros((2, 3))}, duration=DURATION, dt=DT)
    with pytest.raises(cs.ParameterError, match="mass|velocity"):  # n differs between keys
        run_batch(_scene(), {"mass": np.ones((2, 2)), "velocity": np.zeros((3, 2, 3))},
                  duration=DURATION, dt=DT)


def test_a_value_out_of_range_fails_only_its_variant() -> None:
    ov = _overrides(3)
    ov["contact.restitution"][1, 0] = 1.5
    b = run_batch(_scene(), ov, duration=DURATION, dt=DT)
    assert [(e.index, e.kind) for e in b.errors] == [(1, "ParameterError")]
    assert isinstance(b.errors[0], VariantError)
    assert b.errors[0].message.startswith("variant 1: ") and "restitution" in b.errors[0].message
    assert b.columns["n_impacts"][1] == -1
    assert all(np.isnan(v[1]) for k, v in b.columns.items() if k != "n_impacts")
    assert np.isfinite(b.columns["impact1.red.delta_v"][[0, 2]]).all()


def test_a_variant_overlapping_at_the_start_is_listed() -> None:
    pos = np.repeat(np.array([[[-3.65, 0.3, 0.7], [0.0, 0.0, 0.725]]]), 2, axis=0)
    pos[1, 0, 0] = -2.0  # red's nose inside blue
    b = run_batch(_scene(), {"position": pos}, duration=DURATION, dt=DT)
    assert [(e.index, e.kind) for e in b.errors] == [(1, "InitialOverlapError")]
    assert "red" in b.errors[0].message and "blue" in b.errors[0].message


def test_mass_scales_the_inertia_and_auto_depth_of_penetration_is_nan() -> None:
    scene = _scene()
    b = run_batch(scene, {"mass": np.array([[1450.0, 1500.0], [2900.0, 1500.0]]),
                          "contact.depth_of_penetration": np.array([[0.03], [0.03]])},
                  duration=DURATION, dt=DT)
    assert b.columns["impact1.red.delta_v"][1] < b.columns["impact1.red.delta_v"][0]
    heavy = scene.with_({"red.mass": 2900.0}).run(duration=DURATION, dt=DT)
    assert b.columns["impact1.red.delta_v"][1] == heavy.impacts[0].speed_change("red")
    assert np.allclose(heavy.vehicle("red").inertia, 2.0 * scene.vehicles[0].inertia, rtol=0,
                       atol=1e-9)


def test_batch_results_pickle() -> None:
    b = run_batch(_scene(), _overrides(2), duration=DURATION, dt=DT)
    back = pickle.loads(pickle.dumps(b))
    assert back.n == 2 and back.errors == b.errors
    assert np.array_equal(back.columns["impact1.red.delta_v"], b.columns["impact1.red.delta_v"])


def test_progress_reaches_n() -> None:
    seen: list[tuple[int, int]] = []
    run_batch(_scene(), _overrides(4), duration=DURATION, dt=DT,
              progress=lambda d, n: seen.append((d, n)))
    assert seen and seen[-1] == (4, 4)
    assert all(n == 4 for _, n in seen)
    assert [d for d, _ in seen] == sorted(d for d, _ in seen)
