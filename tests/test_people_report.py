"""A cyclist in the report, the picture from above and the case page's data (docs/report.md
"pedestrians[]", docs/human.md "The cyclist", docs/viewer.md "Pedestrians and cyclists"):
its rider gets the pedestrian section under the cyclist's name, with the bicycle's contacts,
throw and rest; the bicycle's bodies leave the run-out; the picture draws the rider and the
bicycle as one figure; the page marks every body with its person. One short side strike
(0.1 s at 0.2 ms: the legs, the frame and the front wheel touch the car; about 0.5 s)."""

from __future__ import annotations

import copy
import math

import crashsim as cs
import jsonschema
import numpy as np
import pytest
from crashsim.analysis.pedestrian import person_bodies, segment_contacts
from crashsim.analysis.report import report_schema
from crashsim.analysis.throw import first_contact_time, throw_distance, trajectory_type
from crashsim.io.viewer.data import page_data
from crashsim.plots.common import shade, vehicle_colour

BICYCLE_MASS = 13.75 + 3.96 + 3.545  # kg: frame and wheels (docs/human.md, "The bicycle")


@pytest.fixture(scope="module")
def strike() -> tuple[cs.Result, cs.Cyclist]:
    """A sedan at 40 km/h into a cyclist crossing at 15 km/h, its left side to the car."""
    car = cs.Vehicle.generate("sedan", name="car")
    cyclist = cs.Cyclist(height=1.75, mass=75.0)
    scene = cs.Scene(ground=cs.Ground(friction=0.8), normal="volume", friction=0.3)
    front = float(car.mesh.bounds[1, 0] - car.cg[0])
    scene.add(car, (0.0, 0.0), velocity=(cs.kmh(40.0), 0.0, 0.0))
    scene.add(cyclist, (front + 0.33, 0.0), heading=math.pi / 2, velocity=(0.0, cs.kmh(15), 0.0))
    scene.soft_contact(car, cyclist, stiffness=1e5, damping_ratio=0.5)
    return scene.run(0.1, dt=2e-4), cyclist


def _travel(result: cs.Result, names: list[str], masses: list[float], t0: float) -> float:
    """The horizontal travel (m) of the bodies' mass-weighted CG from the first sample at or
    after t0 to the last."""
    x = sum(m * result.trajectory(n).position for n, m in zip(names, masses, strict=True))
    x = x / sum(masses)
    k = int(np.flatnonzero(result.t >= t0)[0])
    return float(np.hypot(*(x[-1, :2] - x[k, :2])))


def test_the_cyclist_has_the_pedestrian_section(strike: tuple[cs.Result, cs.Cyclist]) -> None:
    result, cyclist = strike
    report = cs.report(result)
    data = report.to_dict()
    jsonschema.Draft202012Validator(report_schema()).validate(data)
    (entry,) = data["pedestrians"]
    rider, bike = cyclist.rider, cyclist.bicycle
    assert (entry["name"], entry["kind"]) == ("cyclist", "cyclist")
    assert entry["bodies"] == [s.name for s in rider.segments]
    assert entry["mass"] == pytest.approx(75.0, abs=1e-9)
    assert entry["height"] == pytest.approx(rider.height, abs=1e-12)
    (struck,) = entry["struck_by"]
    assert struck["vehicle"] == "car"
    # the rider's throw: crashsim.analysis.throw's, and the CG's travel computed here
    assert struck["first_contact_time"] == first_contact_time(result, "car", rider)
    assert struck["throw_distance"] == throw_distance(result, "car", rider)
    seg = [s.name for s in rider.segments]
    expect = _travel(result, seg, [s.mass for s in rider.segments], struck["first_contact_time"])
    assert struck["throw_distance"] == pytest.approx(expect, abs=1e-12)
    assert struck["segments"][0]["segment"] in ("shank_left", "thigh_left", "foot_left")
    # the rider's trajectory type: crashsim.analysis.throw's (0.1 s: on the bonnet still)
    assert struck["trajectory"] == trajectory_type(result, result.vehicle("car"), rider)
    assert struck["trajectory"] == "carried"
    # the bicycle: its own contacts, the frame's throw from its first contact, the frame's end
    b = entry["bicycle"]
    assert b["bodies"] == ["cyclist/frame", "cyclist/rear_wheel", "cyclist/front_wheel"]
    assert b["mass"] == pytest.approx(BICYCLE_MASS, abs=1e-9)
    (bs,) = b["struck_by"]
    touched = segment_contacts(result, bike, result.vehicle("car"))
    assert [c["segment"] for c in bs["segments"]] == list(touched)
    assert {"frame", "front_wheel"} <= set(touched)
    assert bs["first_contact_time"] == min(c.time for c in touched.values())
    frame = result.trajectory("cyclist/frame")
    assert bs["throw_distance"] == pytest.approx(
        _travel(result, ["cyclist/frame"], [1.0], bs["first_contact_time"]), abs=1e-12
    )
    assert bs["throw_distance"] > 0.5  # the bicycle was pushed ahead
    np.testing.assert_array_equal(b["rest"], frame.position[-1])
    assert b["rest_speed"] == pytest.approx(float(np.linalg.norm(frame.velocity[-1])), abs=1e-12)
    # one person: neither the rider's segments nor the bicycle's bodies are in the run-out
    assert [r["vehicle"] for r in data["run_out"]] == ["car"]
    assert set(person_bodies(result.scene)) == {*seg, *b["bodies"]}
    text = report.summary_table()
    assert "Cyclist 'cyclist' (the rider), sliding on the road at friction 0.66:" in text
    assert f"the bicycle 'cyclist' ({BICYCLE_MASS:.2f} kg):" in text
    assert f"throw distance from 'car': {struck['throw_distance']:.2f} m" in text
    assert "to the end of the run; trajectory: carried)" in text
    assert "trajectory" not in bs  # a bicycle's throw has none
    assert f"throw distance from 'car': {bs['throw_distance']:.2f} m (frame" in text


def test_the_added_fields_are_optional(strike: tuple[cs.Result, cs.Cyclist]) -> None:
    """A report written before them (no kind, bodies, height, mass, throws or bicycle) still
    meets the schema; a wrong kind or a bicycle without its bodies does not."""
    data = cs.report(strike[0]).to_dict()
    schema = report_schema()
    old = copy.deepcopy(data)
    for entry in old["pedestrians"]:
        for key in ("kind", "bodies", "height", "mass", "bicycle"):
            entry.pop(key)
        for s in entry["struck_by"]:
            s.pop("first_contact_time")
            s.pop("throw_distance")
            s.pop("trajectory")
    jsonschema.Draft202012Validator(schema).validate(old)
    for change in ("kind", "bicycle", "trajectory"):
        bad = copy.deepcopy(data)
        if change == "kind":
            bad["pedestrians"][0]["kind"] = "rider"
        elif change == "trajectory":
            bad["pedestrians"][0]["struck_by"][0]["trajectory"] = "somersault"
        else:
            bad["pedestrians"][0]["bicycle"].pop("bodies")
        with pytest.raises(jsonschema.ValidationError):
            jsonschema.Draft202012Validator(schema).validate(bad)


def test_the_picture_from_above_draws_a_cyclist_as_one(
    strike: tuple[cs.Result, cs.Cyclist],
) -> None:
    from crashsim.plots import plot_trajectories
    from matplotlib.colors import to_hex

    result, _ = strike
    fig = plot_trajectories(result)
    caption = fig._suptitle.get_text()
    assert "cyclist (its centre of mass) at (" in caption
    assert "; its bicycle's frame at (" in caption
    assert "cyclist/" not in caption  # no run-out line per body
    ax = fig.axes[0]
    texts = [t.get_text() for t in ax.texts]
    assert "cyclist (start)" in texts and not any("cyclist/" in t for t in texts)
    assert any(t.startswith("cyclist's bicycle at ") for t in texts)
    labels = [t.get_text() for t in fig.legends[0].get_texts()]
    assert labels[1].startswith("cyclist (a cyclist: the rider's segments")
    assert labels[2] == "cyclist's bicycle (frame and wheels from above)"
    # the rider's 16 segments in its colour, the bicycle's 3 bodies in the darker shade, at
    # the same times
    edges = [to_hex(p.get_edgecolor(), keep_alpha=False) for p in ax.patches]
    rider, bike = edges.count(vehicle_colour(1)), edges.count(to_hex(shade(vehicle_colour(1))))
    assert rider > 0 and rider % 16 == 0 and bike == 3 * rider // 16


def test_the_page_data_groups_the_bodies_by_person(
    strike: tuple[cs.Result, cs.Cyclist],
) -> None:
    from matplotlib.colors import to_hex

    result, cyclist = strike
    data = page_data(result)
    assert data["title"] == "crashsim case: car, cyclist"
    people = {b["name"]: (b["person"], b["role"], b["colour"]) for b in data["bodies"]}
    blue, darker = vehicle_colour(1), to_hex(shade(vehicle_colour(1)))
    assert people.pop("car") == (None, None, vehicle_colour(0))
    for s in cyclist.rider.segments:
        assert people.pop(s.name) == ("cyclist", "segment", blue)
    for b in cyclist.bicycle.segments:
        assert people.pop(b.name) == ("cyclist", "bicycle", darker)
    assert people == {}
