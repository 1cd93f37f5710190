"""A struck pedestrian's figures (crashsim.analysis.pedestrian, docs/human.md "Head impact"):
the wrap-around distance on a box's outline against its closed form, and each segment's first
contact with a car read from a soft strike."""

from __future__ import annotations

import math

import crashsim as cs
import pytest
from crashsim.analysis.pedestrian import rest_of, segment_contacts, wrap_around_distance
from crashsim.errors import ParameterError


def _box_car() -> cs.Vehicle:
    # front face x = 2 m from z = 0.3 to 1.3 m, the top at z = 1.3 m (model frame)
    return cs.Vehicle.box(length=4.0, width=1.7, height=1.0, mass=1200.0, name="car",
                          ground_clearance=0.3, cg_height=0.8)


@pytest.mark.parametrize(
    ("point", "expected"),
    [
        ((2.0, 0.2, 0.8), 0.3 + 0.5),  # on the front face: the gap under it, then up
        ((1.5, -0.4, 1.3), 0.3 + 1.0 + 0.5),  # on the top, 0.5 m behind the front edge
        ((-1.0, 0.0, 1.3), 0.3 + 1.0 + 3.0),
        ((-2.0, 0.2, 0.5), None),  # on the rear face
        ((0.0, 0.2, 0.3), None),  # underneath
    ],
)
def test_the_wrap_around_distance_on_a_box(
    point: tuple[float, float, float], expected: float | None
) -> None:
    got = wrap_around_distance(_box_car(), point)
    if expected is None:
        assert got is None
    else:
        assert got == pytest.approx(expected, abs=1e-9)


def test_a_point_beside_the_vehicle_is_refused() -> None:
    with pytest.raises(ParameterError, match="beside vehicle 'car'"):
        wrap_around_distance(_box_car(), (0.0, 2.0, 1.0))


def test_each_segments_first_contact_is_read_from_the_run() -> None:
    car = _box_car()
    person = cs.Pedestrian(height=1.75, mass=75.0)
    scene = cs.Scene(ground=cs.Ground(), normal="volume", friction=0.3)
    scene.add(car, (0.0, 0.0), velocity=(10.0, 0.0, 0.0))
    scene.add(person, (2.4, 0.0), heading=math.pi / 2)
    scene.soft_contact(car, person, stiffness=1e5, damping_ratio=0.5)
    result = scene.run(0.12, dt=2e-4)
    contacts = segment_contacts(result, person, car)
    log = [c for c in result.contacts if c.kind == "first_overlap"]
    first = next(iter(contacts.values()))
    # the log's first overlap, its segment and time
    assert f"pedestrian/{first.segment}" == log[0].vehicles[1]
    assert first.time == log[0].time
    assert list(contacts) == list(dict.fromkeys(c.vehicles[1].split("/")[1] for c in log))
    # struck by the front face (model x = 2 m, between its 0.3 and 1.3 m edges) of a car
    # closing at 10 m/s on a person standing still
    assert first.point[0] == pytest.approx(2.0, abs=1e-9)
    assert 0.3 <= first.point[2] <= 1.3
    assert first.wrap_around == pytest.approx(first.point[2], abs=1e-9)
    assert first.relative_speed == pytest.approx(10.0, rel=0.02)
    assert first.peak_relative_speed >= first.relative_speed
    # the person's centre of mass, pushed ahead of the car's front
    x, speed = rest_of(result, person)
    assert x[0] > 2.4 and speed > 1.0
    assert x[2] > 0.5


def test_the_report_has_the_pedestrian_as_one() -> None:
    import json
    from importlib import resources

    import jsonschema
    from crashsim.analysis.report import build_report
    from crashsim.analysis.throw import first_contact_time, throw_distance

    car = _box_car()
    person = cs.Pedestrian(height=1.75, mass=75.0)
    scene = cs.Scene(ground=cs.Ground(), normal="volume", friction=0.3)
    scene.add(car, (0.0, 0.0), velocity=(10.0, 0.0, 0.0))
    scene.add(person, (2.4, 0.0), heading=math.pi / 2)
    scene.soft_contact(car, person, stiffness=1e5, damping_ratio=0.5)
    result = scene.run(0.05, dt=2e-4)
    report = build_report(result)
    data = report.to_dict()
    schema = json.loads(
        resources.files("crashsim.analysis").joinpath("schema/report-1.schema.json").read_text()
    )
    jsonschema.validate(data, schema)
    (ped,) = data["pedestrians"]
    assert ped["name"] == "pedestrian" and ped["struck_by"][0]["vehicle"] == "car"
    first = ped["struck_by"][0]["segments"][0]
    read = next(iter(segment_contacts(result, person, car).values()))
    assert (first["segment"], first["time"], first["relative_speed"]) == (
        read.segment, read.time, read.relative_speed
    )
    assert [r["vehicle"] for r in data["run_out"]] == ["car"]  # the segments are the person
    # one person: its kind, its segments' names, its throw by the car (crashsim.analysis.throw)
    assert (ped["kind"], ped["bodies"]) == ("pedestrian", [s.name for s in person.segments])
    assert ped["mass"] == pytest.approx(75.0, abs=1e-9) and "bicycle" not in ped
    struck = ped["struck_by"][0]
    assert struck["first_contact_time"] == first_contact_time(result, "car", person)
    assert struck["first_contact_time"] == first["time"]
    assert struck["throw_distance"] == throw_distance(result, "car", person)
    text = report.summary_table()
    assert "Pedestrian 'pedestrian', sliding on the road at friction 0.66:" in text
    assert "first contacts with 'car': " in text
    assert f"throw distance from 'car': {struck['throw_distance']:.2f} m" in text
    # the case page's data: every segment marked as the person's, in one colour
    from crashsim.io.viewer.data import page_data

    bodies = page_data(result)["bodies"]
    roles = [(b["person"], b["role"]) for b in bodies]
    assert roles == [(None, None)] + [("pedestrian", "segment")] * 16
    colours = [b["colour"] for b in bodies]
    assert len(set(colours[1:])) == 1 and colours[1] != colours[0]
