"""The Nicolas-Comstock combined-slip law (issue 19 item 7; Brach and Brach's modification,
SAE 2000-01-0357, 2009-01-0102, 2011-01-0094) from the Python side: named by the engine, the
scene file and the report, and its pure-slip limits in a run (the closed forms of the force
itself are tested in crates/crashsim-core/src/vehicle/combined_slip.rs):

- pure braking (no slip angle): Fx(s), the brake demand, so a straight stop is the one the
  default law gives, bit for bit, and v^2 / (2 a) within 1 %;
- pure cornering (no braking): Fy(alpha), so a steady turn is the default law's, bit for bit.
"""

from __future__ import annotations

from pathlib import Path

import crashsim as cs
import pytest
from crashsim.analysis.report import build_report
from crashsim.io.scenefile import SceneFileError, loads_scene
from test_runout import SCENE

G = 9.80665
MU = 0.8  # the default ground's tyre friction


def test_the_engine_names_the_law_and_its_stiffness_and_rejects_bad_ones() -> None:
    nc = cs.Tyre(combined="nicolas_comstock").resolved()
    assert nc["combined"] == "nicolas_comstock" and nc["longitudinal_stiffness"] is None
    given = cs.Tyre(combined="nicolas_comstock", longitudinal_stiffness=20.0).resolved()
    assert given["longitudinal_stiffness"] == 20.0
    # the other laws do not list it (their reports are unchanged)
    assert "longitudinal_stiffness" not in cs.Tyre().resolved()
    cases = [
        ({"longitudinal_stiffness": 20.0}, "used by the nicolas_comstock combined-slip law only"),
        ({"combined": "nicolas_comstock", "longitudinal_stiffness": 0.0}, r"\(0, 100\]"),
        ({"combined": "nicolas_comstock", "longitudinal_stiffness": 150.0}, r"\(0, 100\]"),
        ({"combined": "nicolas-comstock"}, '"nicolas_comstock"'),
    ]
    for kwargs, match in cases:
        with pytest.raises(cs.ParameterError, match=match):
            cs.Tyre(**kwargs)


def test_a_scene_file_and_its_report_carry_the_law(tmp_path: Path) -> None:
    text = SCENE.replace(
        'relaxation_length = "0.1 m"\n',
        'relaxation_length = "0.1 m"\ncombined = "nicolas_comstock"\nlongitudinal_stiffness = 20\n',
    )
    case = loads_scene(text, base_dir=tmp_path)
    tyre = case.scene.vehicles[0].wheels.tyre
    assert tyre.combined == "nicolas_comstock" and tyre.longitudinal_stiffness == 20.0
    report = build_report(case.scene.run(0.2))
    assert "combined slip nicolas_comstock (longitudinal stiffness 20 Fz per unit slip)" in (
        report.summary_table()
    )
    with pytest.raises(SceneFileError, match="tyre: longitudinal_stiffness = -1"):
        loads_scene(
            SCENE.replace('relaxation_length = "0.1 m"\n', "longitudinal_stiffness = -1\n"),
            base_dir=tmp_path,
        )


def _car(combined: str) -> cs.Vehicle:
    box = cs.Vehicle.box(4.6, 1.8, 1.4, mass=1500.0, name="car", ground_clearance=0.15,
                         cg_height=0.55)  # fmt: skip
    wheels = cs.Wheels(2.7, 1.55, 1.1, 0.55, 0.3, tyre=cs.Tyre(combined=combined))
    return box.with_wheels(wheels)


def _run(combined: str, inputs: cs.DriverInputs, duration: float) -> cs.Result:
    scene = cs.Scene(ground=cs.Ground())
    scene.add(_car(combined), (0.0, 0.0), velocity=(20.0, 0.0, 0.0), inputs=inputs)
    return scene.run(until="rest", max_duration=duration) if duration > 10 else scene.run(duration)


@pytest.mark.parametrize(
    "brake, deceleration",
    [(0.5, 0.5 * MU * G), (cs.Brake.deceleration(3.0), 3.0)],
    ids=["fraction", "deceleration"],
)
def test_pure_braking_gives_the_brake_demand(brake, deceleration) -> None:
    # No slip angle: Fx(s, 0) = Fx(s), the demand; the stop is the default law's to the bit
    # and v^2 / (2 a) within 1 % (the pitch and the tread's build-up, as for the default).
    inputs = cs.DriverInputs(brake=brake)
    stops = [
        _run(law, inputs, 60.0).rest("car") for law in ("nicolas_comstock", "braking_priority")
    ]
    assert stops[0] is not None and stops[1] is not None
    assert stops[0].displacement == stops[1].displacement
    assert stops[0].displacement == pytest.approx(20.0**2 / (2.0 * deceleration), rel=0.01)


def test_pure_cornering_gives_the_lateral_law() -> None:
    # No braking, drive or rolling resistance: s = 0 and Fy(0, alpha) = Fy(alpha), so a 2 s
    # steer ramp into a turn is the default law's run, bit for bit.
    steer = cs.DriverInputs(steer=[(0.0, 0.0), (0.5, 0.05)])
    runs = [_run(law, steer, 2.0) for law in ("nicolas_comstock", "braking_priority")]
    a, b = (r.trajectory("car") for r in runs)
    assert (a.position == b.position).all() and (a.velocity == b.velocity).all()
    assert abs(a.position[-1][1]) > 1.0  # it did turn
