"""The mesh-impact regression suite: one test per expected file in expected/, each running its
scene file from scenes/ and applying every check listed there (published figures, closed forms,
mirror images, minted golden values). How it works, what each figure's change means, and how
to add a case or re-mint the golden values: README.md beside this file.

Cases whose scene needs the shared meshes (../shared/meshes beside the repository) skip with
a message when that folder is absent; so do cases with generated bodies while this crashsim
has no Vehicle.generate.
"""

from __future__ import annotations

import json
from pathlib import Path

import pytest
import regression_suite as suite

CASES = suite.case_names()


def scene_text(name: str) -> str:
    return (suite.SCENES / suite.load_case(name)["scene"]).read_text(encoding="utf-8")


def test_there_are_cases_and_every_scene_has_one() -> None:
    """Every scene file is run by a case (directly, or as the mirror image of another's), and
    at least 10 cases run pairs of the shared real meshes."""
    real_mesh = [n for n in CASES if "shared/meshes" in scene_text(n)]
    assert len(real_mesh) >= 10, real_mesh
    used = set()
    for name in CASES:
        case = suite.load_case(name)
        used.add(case["scene"])
        used.update(c["scene"] for c in case["checks"] if c["kind"] == "mirror")
    scenes = {p.name for p in suite.SCENES.glob("*.toml")}
    assert scenes <= used, f"scene files no case runs: {sorted(scenes - used)}"
    assert {s for s in used if s != "auto"} <= scenes, "a case names a missing scene file"


@pytest.mark.parametrize("name", CASES)
def test_case(name: str, tmp_path: Path) -> None:
    case = suite.load_case(name)
    reason = suite.missing_inputs(suite.SCENES / case["scene"])
    if reason is not None:
        pytest.skip(reason)
    counter = iter(range(1_000_000))
    failures = suite.run_case(name, tmp=lambda: tmp_path / f"mirror-{next(counter)}")
    assert not failures, f"{name} ({case['scene']}):\n" + "\n".join(failures)


# -- the comparison itself (so a check that cannot fail is caught here) -----------------------


def test_compare_catches_a_perturbed_figure() -> None:
    figures = {
        "exchanges": 1,
        "impacts": [
            {
                "vehicles": ["a", "b"],
                "secondary": False,
                "first_contact_time": 0.0123456789,
                "parties": {"a": {"delta_v": [-3.0, 4.0, 0.0], "pdof_deg": 359.9999}},
            }
        ],
    }
    tol = {
        "first_contact_time": {"abs": 1e-9},
        "delta_v": {"rel": 1e-6},
        "pdof_deg": {"abs": 1e-3},
    }
    assert suite.compare(figures, figures, tol) == []
    moved = json.loads(json.dumps(figures))
    moved["impacts"][0]["parties"]["a"]["delta_v"][1] += 5.0 * 1e-6 * 1.01  # just past rel 1e-6
    moved["impacts"][0]["first_contact_time"] += 2e-9
    moved["impacts"][0]["secondary"] = True
    failures = suite.compare(figures, moved, tol)
    assert len(failures) == 3
    assert any("delta_v" in f for f in failures) and any("secondary" in f for f in failures)
    # PDOF wraps: 359.9999 and 0.0001 deg are 0.0002 deg apart
    wrapped = json.loads(json.dumps(figures))
    wrapped["impacts"][0]["parties"]["a"]["pdof_deg"] = 0.0001
    assert suite.compare(figures, wrapped, tol) == []
    # a missing figure, a missing tolerance and a count that differs all fail
    assert suite.compare({"exchanges": 2}, figures, tol) != []
    assert suite.compare({"impacts": [{"parties": {"c": {"delta_v": [0, 0, 0]}}}]}, figures, tol)
    assert (
        "no tolerance" in suite.compare({"impacts": [{"first_contact_time": 0.0}]}, figures, {})[0]
    )


def test_mirror_figures() -> None:
    figures = {
        "impacts": [
            {
                "centroid": [1.0, 2.0, 3.0],
                "exchange_time": 0.1,
                "parties": {
                    "a": {
                        "delta_v": [1.0, -2.0, 0.5],
                        "delta_omega": [0.1, 0.2, 0.3],
                        "delta_v_edr": [-1.0, 2.0, 0.0],
                        "yaw_rate_change_deg_s": 12.0,
                        "pdof_deg": 30.0,
                    }
                },
            }
        ]
    }
    m = suite.mirror_figures(figures)["impacts"][0]
    assert m["centroid"] == [1.0, -2.0, 3.0] and m["exchange_time"] == 0.1
    a = m["parties"]["a"]
    assert a["delta_v"] == [1.0, 2.0, 0.5] and a["delta_omega"] == [-0.1, 0.2, -0.3]
    assert a["delta_v_edr"] == [-1.0, -2.0, 0.0] and a["yaw_rate_change_deg_s"] == -12.0
    assert a["pdof_deg"] == 330.0
    assert suite.mirror_figures(suite.mirror_figures(figures)) == figures


def test_missing_shared_meshes_skip_with_a_reason(tmp_path: Path, monkeypatch) -> None:
    scene = tmp_path / "case.toml"
    scene.write_text(
        'format_version = 1\n[[vehicles]]\nname = "a"\nmesh = "../meshes/car.ply"\n'
        "mass = 1000\nposition = [0, 0]\n",
        encoding="utf-8",
    )
    monkeypatch.setattr(suite, "SHARED_MESHES", tmp_path / "absent")
    reason = suite.missing_inputs(scene)
    assert reason is not None and "shared meshes" in reason and "absent" in reason
    monkeypatch.setattr(suite, "SHARED_MESHES", tmp_path)  # present: a wrong path is an error
    assert suite.missing_inputs(scene) is None


MIRROR_SCENE = """
format_version = 1
title = "every mirrored key"
[run]
duration = "0.3 s"
[contact]
restitution = 0.2
friction = 0.5
normal = "volume"
[[pairs]]
vehicles = ["b", "a"]
normal = [-0.9, 0.3, 0.1]
centroid = { vehicle = "a", point = ["2.2 m", "0.4 m", "0.1 m"] }
[[pairs]]
vehicles = ["a", "c"]
centroid = "(-5.6, 0.45, 0.6) m"
[[vehicles]]
name = "a"
box = { length = "4.4 m", width = "1.8 m", height = "1.4 m" }
mass = 1400
inertia = [[500, 20, -10], [20, 2100, 15], [-10, 15, 2300]]
position = ["-3.1 m", "0.35 m", "0.72 m"]
orientation = [0.9961946980917455, 0.0, 0.0, 0.08715574274765817]
velocity = ["14 m/s", "1.5 m/s", 0]
angular_velocity = ["0.02 rad/s", "-0.03 rad/s", "0.2 rad/s"]
[vehicles.stiffness]
front = { A = "60 kN/m", B = "800 kN/m^2" }
left = { A = "20 kN/m", B = "250 kN/m^2" }
right = { A = "30 kN/m", B = "400 kN/m^2" }
[[vehicles]]
name = "b"
box = { length = "4.6 m", width = "1.9 m", height = "1.5 m" }
mass = 1600
position = [0.2, -0.3]
heading = "80 deg"
speed = "5 m/s"
direction = "70 deg"
yaw_rate = "-5 deg/s"
[[vehicles]]
name = "c"
box = { length = "4.0 m", width = "1.7 m", height = "1.4 m" }
mass = 1200
position = ["-8.3 m", "0.5 m"]
heading = "5 deg"
speed = "25 m/s"
"""


def test_the_automatic_mirror_image_mirrors_every_key(tmp_path: Path) -> None:
    """A box scene using every key the mirror rewrites (3-D position, quaternion, velocity and
    angular velocity vectors, a full inertia matrix, left/right stiffness, [[pairs]] with a
    fixed normal, a body-fixed and a world centroid) runs into mirrored answers."""
    scene = tmp_path / "scene.toml"
    scene.write_text(MIRROR_SCENE, encoding="utf-8")
    original = suite.run_scene(scene)
    mirrored = suite.mirror_run(scene, tmp_path / "mirror")
    assert original.figures["exchanges"] >= 2  # a-b and a-c at least
    text = (tmp_path / "mirror" / "scene-mirrored.toml").read_text(encoding="utf-8")
    assert "orientation = [0.9961946980917455, -0.0, 0.0, -0.08715574274765817]" in text
    assert "position = [-3.1, -0.35, 0.72]" in text and 'centroid = "' not in text
    failures = suite.compare(
        suite.mirror_figures(original.figures), mirrored.figures, suite.MIRROR_TOLERANCES
    )
    assert not failures, "\n".join(failures)
    a, b = (s.scene_file.scene.vehicles[0] for s in (original, mirrored))
    assert b.stiffness.face("left") == a.stiffness.face("right")
    assert b.inertia[0, 1] == -a.inertia[0, 1] and b.inertia[0, 2] == a.inertia[0, 2]
