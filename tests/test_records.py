"""records.py's Impact against the engine's record of an exchange (a dict keyed by the core
``Impact``'s field names, serialized by the binding without naming any): every field the
engine records is one the model reads, each value the engine's bits, per-body pairs keyed by
vehicle name."""

from __future__ import annotations

import math

import crashsim as cs
import numpy as np
from crashsim import records
from crashsim.records import Impact

MPH30 = 30.0 * 0.44704


def side_impact() -> cs.Scene:
    """The seed's 90 deg side impact (examples/seed-90deg.toml)."""
    red = cs.Vehicle.box(4.5, 1.8, 1.4, mass=1450.0, name="red")
    blue = cs.Vehicle.box(4.6, 1.8, 1.45, mass=1500.0, name="blue")
    scene = cs.Scene(depth_of_penetration=0.030)
    scene.add(red, position=(-3.65, 0.3, 0.7), heading=0.0, velocity=(MPH30, 0.0, 0.0))
    scene.add(blue, position=(0.0, 0.0, 0.725), heading=math.pi / 2)
    return scene


def car_into_wall() -> cs.Scene:
    car = cs.Vehicle.box(4.5, 1.8, 1.4, mass=1500.0, name="car")
    scene = cs.Scene()
    scene.add(car, (0.0, 0.0, 0.7), velocity=(10.0, 0.0, 0.0))
    scene.add_obstacle(cs.Obstacle.wall(5.0, 0.5, 2.0), (3.0, 0.0))
    return scene


def same(a: object, b: object) -> bool:
    """The same shape and the same float64 bits (the engine's values are nested sequences)."""
    x, y = np.asarray(a, dtype=np.float64), np.asarray(b, dtype=np.float64)
    return x.shape == y.shape and x.tobytes() == y.tobytes()


def engine_impacts(scene: cs.Scene) -> list[dict]:
    return scene.to_spec(0.3, 1e-3).run()["impacts"]


def test_the_model_reads_every_field_the_engine_records_and_no_other() -> None:
    (raw,) = engine_impacts(side_impact())
    read = {f.name for f, _ in records._engine_fields(Impact)}
    assert set(raw) - {"body1", "body2"} == read  # body1, body2: the derived names
    assert {"vehicles", "bodies", "delta_v", "delta_omega", "obstacle"}.isdisjoint(read)


def test_each_value_is_the_engines_with_per_body_pairs_keyed_by_name() -> None:
    (raw,) = engine_impacts(side_impact())
    (imp,) = side_impact().run(0.3, 1e-3).impacts
    assert imp.vehicles == ("red", "blue") and imp.bodies == (raw["body1"], raw["body2"])
    assert imp.time == raw["time"] and imp.sliding is raw["sliding"]
    assert imp.depth_of_penetration_mode == raw["depth_of_penetration_mode"] == "fixed"
    assert imp.contact_frame.shape == (3, 3) and same(imp.contact_frame, raw["contact_frame"])
    assert np.allclose(imp.contact_frame @ imp.contact_frame.T, np.eye(3), atol=1e-12)
    assert same(imp.contact_frame[0], raw["normal"])  # row n: the normal
    assert imp.region_points.shape == (len(raw["region_points"]), 3)
    for k, name in enumerate(imp.vehicles):
        assert same(imp.velocity_before[name], raw["velocity_before"][k])
        assert same(imp.delta_v_body[name], raw["delta_v_body"][k])
        assert imp.pdof_deg[name] == raw["pdof_deg"][k]
        assert imp.struck_faces[name] == raw["struck_faces"][k]
        assert imp.effective_mass[name] == raw["effective_mass"][k]
        after, before = raw["velocity_after"][k], raw["velocity_before"][k]
        assert same(imp.delta_v[name], [a - b for a, b in zip(after, before, strict=True)])
        assert not imp.velocity_before[name].flags.writeable
    assert imp.struck_faces == {"red": "front", "blue": "left"}
    assert imp.spring_rates is None is raw["spring_rates"]  # no stiffness data


def test_a_fixed_obstacle_keeps_only_its_face_and_infinite_effective_mass() -> None:
    (imp,) = car_into_wall().run(0.3).impacts
    assert imp.obstacle == "wall" and imp.moving == ("car",)
    assert set(imp.velocity_before) == set(imp.delta_v) == set(imp.pdof_deg) == {"car"}
    assert set(imp.struck_faces) == set(imp.effective_mass) == {"car", "wall"}
    assert imp.effective_mass["wall"] == math.inf and imp.struck_faces["car"] == "front"


def test_an_empty_region_reads_as_zero_points_of_three_coordinates() -> None:
    (raw,) = engine_impacts(side_impact())
    imp = Impact.from_core({**raw, "region_points": []}, ["red", "blue"])
    assert imp.region_points.shape == (0, 3)


def graze() -> cs.Scene:
    """Red slides sideways past blue's rear 1 cm deep (tests/test_report.py's graze): a first
    overlap, a timer's end without an exchange (with its reason) and a separation."""
    red = cs.Vehicle.box(4.5, 1.8, 1.4, mass=1450.0, name="red")
    blue = cs.Vehicle.box(4.6, 1.8, 1.45, mass=1500.0, name="blue")
    scene = cs.Scene(depth_of_penetration=0.060)
    scene.add(red, position=(-2.3 - 2.25 + 0.01, -3.0, 0.7), velocity=(0.0, 40.0, 0.0))
    scene.add(blue, position=(0.0, 0.0, 0.725))
    return scene


def test_the_contact_log_is_the_engines_with_the_reason_only_where_one_was_given() -> None:
    raw = graze().to_spec(0.3, 1e-3).run()["contacts"]
    assert [c["kind"] for c in raw] == ["first_overlap", "no_exchange", "separation"]
    assert [set(c) for c in raw] == [
        {"body1", "body2", "time", "kind"},
        {"body1", "body2", "time", "kind", "reason"},
        {"body1", "body2", "time", "kind"},
    ]
    events = graze().run(0.3, 1e-3).contacts
    for event, c in zip(events, raw, strict=True):
        assert event.vehicles == ("red", "blue") and event.time == c["time"]
        assert event.kind == c["kind"] and event.reason == c.get("reason")
    assert events[1].reason.startswith("the vehicles are not approaching")
    assert events[0].reason is None
