"""Fuzzing the scene-file loader (crashsim.io.scenefile.loads_scene) with hypothesis.

Documents are the examples' (box, generated and three-vehicle scenes) mutated: leaves replaced
by wrong types, wrong or unknown units, NaN, infinities, huge and negative numbers; keys
deleted or added; vehicles duplicated; and the TOML text itself truncated or edited. The
loader must either return a scene whose every number is finite or raise a crashsim error
(a CrashsimError subclass, with a message) - never another exception, a NumPy or trimesh
warning, or a hang (hypothesis' deadline). Profiles: conftest.py ("ci" by default, "long").
"""

from __future__ import annotations

import json
import math
import re
import tomllib
from typing import Any

import crashsim as cs
import numpy as np
import pytest
from conftest import REPO
from crashsim.io.scenefile import SceneFile, loads_scene
from hypothesis import example, given
from hypothesis import strategies as st

EXAMPLES = ("seed-90deg", "three-vehicles", "generated-offset-frontal")
TEXTS = {
    name: (REPO / "examples" / f"{name}.toml").read_text(encoding="utf-8") for name in EXAMPLES
}
DOCS = {name: tomllib.loads(text) for name, text in TEXTS.items()}

# The loader's own warnings are documented behaviour; any other warning is an error.
pytestmark = [
    pytest.mark.filterwarnings("ignore::crashsim.PlausibilityWarning"),
    pytest.mark.filterwarnings("ignore::crashsim.DepthOfPenetrationWarning"),
]

# -- a TOML writer for the documents (everything inline: one key per line) --------------------

_BARE = re.compile(r"^[A-Za-z0-9_-]+$")


def _key(k: str) -> str:
    return k if _BARE.match(k) else json.dumps(k, ensure_ascii=False)


def _value(v: Any) -> str:
    if isinstance(v, bool):
        return "true" if v else "false"
    if isinstance(v, int):
        return str(v)
    if isinstance(v, float):
        if math.isnan(v):
            return "nan"
        if math.isinf(v):
            return "inf" if v > 0 else "-inf"
        return repr(v)
    if isinstance(v, str):
        return json.dumps(v, ensure_ascii=False)
    if isinstance(v, list):
        return "[" + ", ".join(_value(x) for x in v) + "]"
    if isinstance(v, dict):
        return "{ " + ", ".join(f"{_key(k)} = {_value(x)}" for k, x in v.items()) + " }"
    raise TypeError(type(v))


def dumps(doc: dict[str, Any]) -> str:
    return "".join(f"{_key(k)} = {_value(v)}\n" for k, v in doc.items())


def test_the_writer_round_trips_the_examples() -> None:
    for doc in DOCS.values():
        assert tomllib.loads(dumps(doc)) == doc


# -- mutations -----------------------------------------------------------------------------------

QUANTITIES = [
    "30 mph", "-1 m", "1e308 kg", "nan kg", "inf s", "-inf m", "1450 kg", "90 deg", "-5 ms",
    "0 ms", "1e-300 m", "3 m/s", "1 lb", "4.5 m", "-0 m", "10 furlong", " 2 m ", "1,5 m",
    "2 m m", "m", "", "auto", "mesh", "sedan", "empirical", "1e400 m", "0x10 m", "1_000 kg",
    "50 %", "2 deg/s", "1 lb ft s^2", "34 lb/in^2", "NaN", "infinity",
]  # fmt: skip
KEYS = [
    "name", "box", "mesh", "generate", "mass", "weight", "position", "heading", "speed",
    "velocity", "direction", "yaw_rate", "angular_velocity", "cg", "cg_height", "inertia",
    "wheelbase", "stiffness", "length", "width", "height", "ground_clearance", "preset",
    "depth_of_penetration", "restitution", "friction", "normal", "pitch", "centroid",
    "duration", "dt", "vehicles", "format_version", "junk", "Ixx", "front", "A", "B",
]  # fmt: skip

numbers = st.one_of(
    st.floats(allow_nan=True, allow_infinity=True),
    st.integers(min_value=-(10**18), max_value=10**18),
    st.sampled_from([0, -1, 1e-320, 1e308, -1e308, 2**63, 0.030, 0.06, 1e9]),
)
leaves = st.one_of(
    numbers,
    st.booleans(),
    st.sampled_from(QUANTITIES),
    st.text(max_size=6),
)
values = st.one_of(
    leaves,
    st.lists(st.one_of(numbers, st.sampled_from(QUANTITIES)), max_size=4),
    st.dictionaries(st.sampled_from(KEYS), leaves, max_size=3),
)


def _paths(node: Any, path: tuple[Any, ...] = ()) -> list[tuple[Any, ...]]:
    """Every path (keys and indices) to a value inside the document."""
    out = [path] if path else []
    if isinstance(node, dict):
        for k, v in node.items():
            out += _paths(v, (*path, k))
    elif isinstance(node, list):
        for i, v in enumerate(node):
            out += _paths(v, (*path, i))
    return out


def _at(doc: Any, path: tuple[Any, ...]) -> Any:
    for k in path:
        doc = doc[k]
    return doc


@st.composite
def mutated(draw: st.DrawFn) -> str:
    name = draw(st.sampled_from(EXAMPLES))
    doc = json.loads(json.dumps(DOCS[name]))  # a deep copy
    for _ in range(draw(st.integers(1, 4))):
        paths = _paths(doc)
        if not paths:
            break
        path = draw(st.sampled_from(paths))
        parent, last = _at(doc, path[:-1]), path[-1]
        op = draw(st.sampled_from(["replace", "replace", "delete", "add", "duplicate"]))
        if op == "replace":
            parent[last] = draw(values)
        elif op == "delete":
            del parent[last]
        elif op == "add" and isinstance(parent, dict):
            parent[draw(st.sampled_from(KEYS))] = draw(values)
        elif op == "duplicate" and isinstance(parent, list):
            parent.append(json.loads(json.dumps(parent[last])))
    return dumps(doc)


@st.composite
def edited_text(draw: st.DrawFn) -> str:
    """An example's text truncated, or with a stretch replaced by random characters."""
    text = TEXTS[draw(st.sampled_from(EXAMPLES))]
    i = draw(st.integers(0, len(text)))
    if draw(st.booleans()):
        return text[:i]
    j = draw(st.integers(i, min(len(text), i + 12)))
    return text[:i] + draw(st.text(max_size=12)) + text[j:]


# -- the property --------------------------------------------------------------------------------


def _finite(a: Any) -> bool:
    return bool(np.all(np.isfinite(np.asarray(a, dtype=np.float64))))


def check_loads(text: str) -> SceneFile | None:
    """The property: a scene with finite numbers, or a crashsim error with a message."""
    try:
        case = loads_scene(text)
    except cs.CrashsimError as e:
        assert str(e).strip(), "an error without a message"
        return None
    assert math.isfinite(case.run.duration) and case.run.duration > 0.0
    assert math.isfinite(case.run.dt) and case.run.dt > 0.0
    for p in case.scene.placements:
        v = p.vehicle
        assert math.isfinite(v.mass) and v.mass > 0.0
        assert _finite(v.cg) and _finite(v.inertia) and _finite(v.mesh.vertices)
        for state in (p.position, p.orientation, p.velocity, p.angular_velocity):
            assert _finite(state)
    return case


@given(mutated())
def test_mutated_scene_files_load_or_raise_a_crashsim_error(text: str) -> None:
    check_loads(text)


@given(edited_text())
@example("")
@example("format_version = 1\n")
@example("\x00")
def test_edited_scene_text_loads_or_raises_a_crashsim_error(text: str) -> None:
    check_loads(text)


def test_the_unmutated_examples_load() -> None:
    for text in TEXTS.values():
        assert check_loads(text) is not None


def test_a_box_longer_than_any_vehicle_is_a_scene_error_not_an_overflow() -> None:
    # Found by test_mutated_scene_files_load_or_raise_a_crashsim_error: box length 1e153 m
    # (or 9.99e307) overflowed the box inertia m L^2 / 12 with a RuntimeWarning.
    doc = json.loads(json.dumps(DOCS["seed-90deg"]))
    for length in (1.1992307984244954e153, 9.987184082568422e307, 2e4):
        doc["vehicles"][1]["box"]["length"] = length
        with pytest.raises(cs.SceneError, match=r"vehicles\[1\].*no vehicle is longer than 10 km"):
            loads_scene(dumps(doc))
    with pytest.raises(cs.ParameterError, match="shorter than 1 mm"):
        cs.Vehicle.box(1e-4, 1e-4, 1e-4, mass=1.0)


def test_absurd_dimensions_elsewhere_are_errors_not_overflows() -> None:
    # Found by the same test: a box's ground_clearance of 2.8e152 m overflowed the parallel
    # axis term of its inertia, and a generated sedan 8.1e14 m high divided 0 by 0 in the
    # generator (RuntimeWarnings, then NaN).
    doc = json.loads(json.dumps(DOCS["three-vehicles"]))
    doc["vehicles"][2]["box"]["ground_clearance"] = 2.795721214301781e152
    with pytest.raises(cs.SceneError, match=r"vehicles\[2\].*the inertia about it is not finite"):
        loads_scene(dumps(doc))
    doc = json.loads(json.dumps(DOCS["generated-offset-frontal"]))
    doc["vehicles"][1]["generate"]["height"] = 811250576211876.0
    with pytest.raises(cs.SceneError, match=r"height = 8.1\d+e\+14 m: no vehicle is longer"):
        loads_scene(dumps(doc))


def test_an_absurd_mass_is_a_scene_error_not_an_overflow() -> None:
    # Found by the same test: mass = 9.18e307 kg overflowed the box inertia (m L^2 / 12)
    # and, at 4.59e307 kg, the sum of two principal moments in the inertia check.
    doc = json.loads(json.dumps(DOCS["seed-90deg"]))
    doc["vehicles"][1]["mass"] = 9.183617547189352e307
    with pytest.raises(cs.SceneError, match=r"vehicles\[1\].*the inertia of a 9.18\d*e\+307 kg"):
        loads_scene(dumps(doc))
    doc["vehicles"][1]["mass"] = 4.591808773594676e307
    check_loads(dumps(doc))  # possible in floating point: no warning, every number finite
