"""3-D export (crashsim.io.export): the GLB's structure is what glTF 2.0 requires, trimesh reads
the vehicles back with their meshes, and the animation reproduces the run.

The files are parsed here with struct and json, independently of the writer: the 12-byte
header, the two chunks and their 4-byte alignment, every buffer view inside the buffer,
every accessor's min and max equal to its data. The CG moves in a straight line between
impacts (no force acts), so the animation's linear interpolation of the translation keys must
give the run's CG position at any time, to float32's resolution (1e-6 m here).
"""

from __future__ import annotations

import json
import math
import struct
from pathlib import Path
from typing import Any

import crashsim as cs
import numpy as np
import pytest
import trimesh
from conftest import seed_side_impact
from crashsim.io.export import GROUND_Z, Z_UP_TO_Y_UP, export_frames, export_glb, key_times

COMPONENTS = {5126: "<f4", 5125: "<u4", 5123: "<u2", 5121: "u1"}
WIDTH = {"SCALAR": 1, "VEC2": 2, "VEC3": 3, "VEC4": 4, "MAT4": 16}
POSITION_TOL = 1e-6  # m: float32 rounds by at most 4.8e-7 m at coordinates below 16 m


@pytest.fixture(scope="module")
def seed45() -> cs.Result:
    return seed_side_impact(cs.mph(60.0), cs.deg(45.0), (-4.0, -3.0))


@pytest.fixture(scope="module")
def sedan_pickup() -> cs.Result:
    """The shared sedan into the shared pickup's side; it rolls and pitches afterwards."""
    from conftest import shared_mesh_paths

    paths = {p.stem.split("_")[0]: p for p in shared_mesh_paths()}
    if not {"sedan", "pickup"} <= paths.keys():
        pytest.skip("the shared sedan and pickup meshes are absent")
    sedan = cs.Vehicle.from_mesh(paths["sedan"], mass=1450.0, name="sedan")
    pickup = cs.Vehicle.from_mesh(paths["pickup"], mass=2200.0, name="pickup")
    scene = cs.Scene(depth_of_penetration=0.030)
    scene.add(sedan, position=(-3.6, 0.4, sedan.cg[2] + 0.005), velocity=(cs.mph(30.0), 0, 0))
    scene.add(
        pickup,
        position=(0.0, 0.0, pickup.cg[2] + 0.005),
        heading=cs.deg(90.0),
        velocity=(0.0, 2.0, 0.0),
    )
    return scene.run(duration=0.4, dt=1e-3)


# -- an independent GLB reader -------------------------------------------------------------


def read_glb(path: Path) -> tuple[dict[str, Any], bytes]:
    """(JSON document, BIN chunk) of a GLB, checking the container as the spec words it."""
    data = path.read_bytes()
    magic, version, length = struct.unpack_from("<III", data, 0)
    assert magic == 0x46546C67 and version == 2  # "glTF", 2
    assert length == len(data) and length % 4 == 0
    json_len, json_type = struct.unpack_from("<II", data, 12)
    assert json_type == 0x4E4F534A and json_len % 4 == 0  # "JSON", padded
    text = data[20 : 20 + json_len]
    body = text.rstrip(b" ")  # padded with spaces, at most 3
    assert len(text) - len(body) < 4
    doc = json.loads(body.decode("utf-8"))
    offset = 20 + json_len
    bin_len, bin_type = struct.unpack_from("<II", data, offset)
    assert bin_type == 0x004E4942 and bin_len % 4 == 0  # "BIN\0", padded
    assert offset + 8 + bin_len == length  # nothing after the last chunk
    return doc, data[offset + 8 : offset + 8 + bin_len]


def accessor(doc: dict[str, Any], blob: bytes, index: int) -> np.ndarray:
    """An accessor's elements as (count, width) or (count,) numbers (tightly packed views)."""
    acc = doc["accessors"][index]
    view = doc["bufferViews"][acc["bufferView"]]
    dtype = np.dtype(COMPONENTS[acc["componentType"]])
    width = WIDTH[acc["type"]]
    start = view.get("byteOffset", 0) + acc.get("byteOffset", 0)
    n = acc["count"] * width
    assert "byteStride" not in view
    assert acc["count"] * width * dtype.itemsize <= view["byteLength"]
    a = np.frombuffer(blob, dtype=dtype, count=n, offset=start)
    return a.reshape(-1, width) if width > 1 else a


def check_structure(doc: dict[str, Any], blob: bytes) -> None:
    """The glTF rules the viewers rely on: references in range, views inside the buffer and
    aligned, accessor min/max present and equal to the data."""
    assert doc["asset"]["version"] == "2.0"
    (buffer,) = doc["buffers"]
    assert "uri" not in buffer and buffer["byteLength"] <= len(blob)
    for view in doc["bufferViews"]:
        assert view["buffer"] == 0
        assert view["byteOffset"] % 4 == 0
        assert view["byteOffset"] + view["byteLength"] <= buffer["byteLength"]
    for i, acc in enumerate(doc["accessors"]):
        data = accessor(doc, blob, i)
        rows = data.reshape(acc["count"], -1)
        assert acc["min"] == [float(v) if rows.dtype.kind == "f" else int(v) for v in rows.min(0)]
        assert acc["max"] == [float(v) if rows.dtype.kind == "f" else int(v) for v in rows.max(0)]
    nodes = doc["nodes"]
    for node in nodes:
        assert node.get("mesh", 0) < len(doc["meshes"])
        assert all(c < len(nodes) for c in node.get("children", []))
    for mesh in doc["meshes"]:
        for prim in mesh["primitives"]:
            positions = doc["accessors"][prim["attributes"]["POSITION"]]
            idx = accessor(doc, blob, prim["indices"])
            assert idx.size % 3 == 0 and int(idx.max()) < positions["count"]
            assert prim["material"] < len(doc["materials"])


def quaternion_matrix(q_xyzw: np.ndarray) -> np.ndarray:
    """The rotation of a glTF quaternion (x, y, z, w)."""
    x, y, z, w = np.asarray(q_xyzw, dtype=float) / np.linalg.norm(q_xyzw)
    return np.array(
        [
            [1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)],
            [2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)],
            [2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)],
        ]
    )


def sampled(times: np.ndarray, values: np.ndarray, t: float) -> np.ndarray:
    """glTF LINEAR sampling of a translation track at t (as a viewer computes it)."""
    k = int(np.clip(np.searchsorted(times, t, side="right") - 1, 0, len(times) - 2))
    s = (t - float(times[k])) / (float(times[k + 1]) - float(times[k]))
    return (1.0 - s) * values[k].astype(float) + s * values[k + 1].astype(float)


def tracks(doc: dict[str, Any], blob: bytes) -> dict[str, dict[str, np.ndarray]]:
    """{vehicle: {"t": times, "translation": (k, 3), "rotation": (k, 4)}} from the animation."""
    (anim,) = doc["animations"]
    out: dict[str, dict[str, np.ndarray]] = {}
    for ch in anim["channels"]:
        sampler = anim["samplers"][ch["sampler"]]
        assert sampler["interpolation"] == "LINEAR"
        name = doc["nodes"][ch["target"]["node"]]["name"]
        entry = out.setdefault(name, {})
        entry["t"] = accessor(doc, blob, sampler["input"])
        entry[ch["target"]["path"]] = accessor(doc, blob, sampler["output"])
        assert len(entry[ch["target"]["path"]]) == len(entry["t"])
    return out


# -- the animated file ----------------------------------------------------------------------


@pytest.mark.parametrize("case", ["seed45", "sedan_pickup"])
def test_glb_structure_and_trimesh_reads_the_vehicles(case: str, request, tmp_path: Path):
    result: cs.Result = request.getfixturevalue(case)
    path = export_glb(result, tmp_path / "run.glb")
    doc, blob = read_glb(path)
    check_structure(doc, blob)
    scene = trimesh.load(path)
    assert isinstance(scene, trimesh.Scene)
    for name in result.vehicles:
        v = result.vehicle(name)
        mesh = scene.geometry[name]
        assert len(mesh.vertices) == len(v.mesh.vertices)
        assert len(mesh.faces) == len(v.mesh.faces)
        # the mesh is written in the body frame: model vertices minus the CG (float32)
        assert np.allclose(mesh.vertices, v.body_vertices, rtol=0, atol=1e-6)
        assert np.array_equal(mesh.faces, v.mesh.faces)
    # root node: world z up -> glTF y up
    root = doc["nodes"][doc["scenes"][doc["scene"]]["nodes"][0]]
    assert root["rotation"] == list(Z_UP_TO_Y_UP)
    turn = quaternion_matrix(np.array(root["rotation"]))
    assert np.allclose(turn @ [0, 0, 1], [0, 1, 0], atol=1e-15)
    assert np.allclose(turn @ [1, 0, 0], [1, 0, 0], atol=1e-15)
    # the ground lies at GROUND_Z under every CG path
    ground = [n for n in doc["nodes"] if n.get("name") == "ground"]
    assert len(ground) == 1
    g_lo = np.min(
        [
            doc["accessors"][p["attributes"]["POSITION"]]["min"]
            for p in doc["meshes"][ground[0]["mesh"]]["primitives"]
        ],
        axis=0,
    )
    g_hi = np.max(
        [
            doc["accessors"][p["attributes"]["POSITION"]]["max"]
            for p in doc["meshes"][ground[0]["mesh"]]["primitives"]
        ],
        axis=0,
    )
    assert g_lo[2] == g_hi[2] == pytest.approx(GROUND_Z, abs=1e-9)
    for name in result.vehicles:
        xy = result.trajectory(name).position[:, :2]
        assert np.all(xy >= g_lo[:2]) and np.all(xy <= g_hi[:2])


@pytest.mark.parametrize("case", ["seed45", "sedan_pickup"])
def test_animation_reproduces_the_run(case: str, request, tmp_path: Path) -> None:
    result: cs.Result = request.getfixturevalue(case)
    fps = 30.0
    doc, blob = read_glb(export_glb(result, tmp_path / "run.glb", fps=fps))
    got = tracks(doc, blob)
    assert set(got) == set(result.vehicles)
    imp = result.impacts[0]
    t_end = float(result.t[-1])
    for name in result.vehicles:
        t = got[name]["t"]
        assert t.dtype == np.float32 and np.all(np.diff(t) > 0) and t[0] == 0.0
        assert float(t[-1]) == pytest.approx(t_end, abs=1e-7)
        # fps frames plus the impact instants (30 ms apart, so both are keys)
        assert len(t) >= math.floor(t_end * fps) + 1
        for when in (imp.first_contact_time, imp.time):
            assert np.min(np.abs(t.astype(float) - when)) < 1e-8
        # translation sampled as a viewer does = the CG, at the impacts and between keys
        rng = np.random.default_rng(7)
        probes = [imp.first_contact_time, imp.time, *rng.uniform(0.0, t_end, 40)]
        for when in probes:
            expected = result.state(name, float(when))["position"]
            got_p = sampled(t.astype(float), got[name]["translation"], float(when))
            assert np.allclose(got_p, expected, rtol=0, atol=POSITION_TOL), (name, when)
        # rotations: unit quaternions (x, y, z, w), the body -> world rotation at each key
        q = got[name]["rotation"].astype(float)
        assert np.allclose(np.linalg.norm(q, axis=1), 1.0, rtol=0, atol=1e-6)
        assert np.all(np.sum(q[1:] * q[:-1], axis=1) > 0.0)  # no sign flips between keys
        for k in range(0, len(t), 3):
            r = result.pose(name, float(t[k]))[1]
            assert np.allclose(quaternion_matrix(q[k]), r, rtol=0, atol=2e-6), (name, t[k])
        # the node's static transform is the pose at the start
        node = next(n for n in doc["nodes"] if n.get("name") == name)
        p0, r0 = result.pose(name, 0.0)
        assert np.allclose(node["translation"], p0, rtol=0, atol=1e-12)
        assert np.allclose(quaternion_matrix(np.array(node["rotation"])), r0, atol=1e-12)


def test_quaternions_are_in_gltf_order(seed45: cs.Result, tmp_path: Path) -> None:
    # blue stands at heading 90 deg until it is struck; red drives at heading 45 deg
    doc, blob = read_glb(export_glb(seed45, tmp_path / "run.glb"))
    got = tracks(doc, blob)
    s45, c45 = math.sin(math.radians(45.0)), math.cos(math.radians(45.0))
    s22, c22 = math.sin(math.radians(22.5)), math.cos(math.radians(22.5))
    assert np.allclose(got["blue"]["rotation"][0], [0.0, 0.0, s45, c45], rtol=0, atol=1e-7)
    assert np.allclose(got["red"]["rotation"][0], [0.0, 0.0, s22, c22], rtol=0, atol=1e-7)
    node = next(n for n in doc["nodes"] if n.get("name") == "blue")
    assert np.allclose(node["rotation"], [0.0, 0.0, s45, c45], rtol=0, atol=1e-15)


def test_key_times() -> None:
    result = seed_side_impact(cs.mph(30.0), 0.0, (-3.65, 0.3))
    imp = result.impacts[0]
    t = key_times(result, 10.0)
    frames = [0.0, 0.1, 0.2, 0.3]
    assert np.allclose(t, sorted([*frames, imp.first_contact_time, imp.time]), atol=1e-12)
    with pytest.raises(cs.ParameterError, match="fps"):
        export_glb(result, "unused.glb", fps=0.0)


# -- static frames --------------------------------------------------------------------------


def test_frames_pose_the_vehicles(seed45: cs.Result, tmp_path: Path) -> None:
    imp = seed45.impacts[0]
    times = [0.0, imp.first_contact_time, imp.time, 0.3]
    paths = export_frames(seed45, tmp_path / "frames", times)
    assert [p.name for p in paths] == [
        "frame_0000_t0.0000s.glb",
        "frame_0001_t0.0460s.glb",
        "frame_0002_t0.0760s.glb",
        "frame_0003_t0.3000s.glb",
    ]
    turn = np.eye(4)
    turn[:3, :3] = quaternion_matrix(np.array(Z_UP_TO_Y_UP))
    for path, t in zip(paths, times, strict=True):
        doc, blob = read_glb(path)
        check_structure(doc, blob)
        assert "animations" not in doc
        scene = trimesh.load(path)
        for name in seed45.vehicles:
            transform, geometry = scene.graph.get(name)
            assert geometry == name
            p, r = seed45.pose(name, t)
            pose = np.eye(4)
            pose[:3, :3], pose[:3, 3] = r, p
            # trimesh's world transform of the node: the root's turn times the pose
            assert np.allclose(transform, turn @ pose, rtol=0, atol=1e-9)
    with pytest.raises(cs.ParameterError, match="outside the run"):
        export_frames(seed45, tmp_path / "bad", [0.5])
    bare = seed_side_impact(cs.mph(30.0), 0.0, (-3.65, 0.3))
    bare.scene = None
    with pytest.raises(cs.SceneError, match="no scene"):
        export_glb(bare, tmp_path / "x.glb")


# -- long runs: the keys follow what moves ----------------------------------------------------


@pytest.fixture(scope="module")
def long_rest() -> cs.Result:
    """A car braked to rest in about 2 s on the ground, the run going on to 60 s."""
    car = cs.Vehicle.generate("sedan")
    scene = cs.Scene(ground=cs.Ground())
    locked = cs.DriverInputs(wheel_states=[(w, "locked", 0.0) for w in car.wheels])
    scene.add(car, (0.0, 0.0), heading=0.3, velocity=(12.0, 4.0, 0.0), inputs=locked)
    return scene.run(60.0, 1e-3)


def test_states_at_many_times_are_the_states_at_each(long_rest: cs.Result) -> None:
    rng = np.random.default_rng(3)
    times = np.r_[long_rest.t[[0, 17, 2500, -1]], rng.uniform(0.0, 60.0, 30)]
    many = long_rest.states("sedan", times)
    assert many["position"].shape == (len(times), 3)
    assert many["orientation"].shape == (len(times), 4)
    for k, t in enumerate(times):
        one = long_rest.state("sedan", float(t))
        for key, value in one.items():
            assert np.array_equal(many[key][k], value), (key, t)
    # a sample time gives the sample itself
    tr = long_rest.trajectory("sedan")
    assert np.array_equal(many["position"][1], tr.position[17])
    with pytest.raises(cs.SceneError, match="outside the run"):
        long_rest.states("sedan", [1.0, 61.0])


def test_a_vehicle_at_rest_costs_two_keys_and_the_animation_still_follows_the_run(
    long_rest: cs.Result, tmp_path: Path
) -> None:
    rest = long_rest.rest("sedan")
    assert rest is not None and rest.time < 3.0
    doc, blob = read_glb(export_glb(long_rest, tmp_path / "run.glb", fps=30.0))
    got = tracks(doc, blob)
    t = got["sedan"]["t"].astype(float)
    # every frame while it moves and settles; a handful once nothing moves (not 30 per s)
    assert len(t) < 30 * 6 + 10, len(t)
    assert t[0] == 0.0 and t[-1] == pytest.approx(60.0, abs=1e-5)
    # between frames while it brakes: the chord of the path, within a (1 / 30 s)^2 / 8 of
    # the braking's 8 m/s^2 (1.1 mm); at rest within the still keys' drift (1 mm)
    rng = np.random.default_rng(5)
    for when, tol in [*((w, 1.5e-3) for w in rng.uniform(0.0, 4.0, 20)),
                      *((w, 1e-3) for w in rng.uniform(4.0, 60.0, 20))]:  # fmt: skip
        expected = long_rest.state("sedan", float(when))["position"]
        position = sampled(t, got["sedan"]["translation"], float(when))
        assert np.allclose(position, expected, rtol=0, atol=tol), when
    # the wheels' tracks share the keys
    for name, track in got.items():
        assert np.array_equal(track["t"], got["sedan"]["t"]), name


def test_a_run_longer_than_the_key_budget_is_keyed_at_a_lower_rate(
    long_rest: cs.Result, tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    import crashsim.io.export as export

    monkeypatch.setattr(export, "MAX_KEYS", 600)  # 10 per s over the 60 s run
    with pytest.warns(UserWarning, match="keyed at 10 per second"):
        path = export_glb(long_rest, tmp_path / "run.glb", fps=30.0)
    t = tracks(*read_glb(path))["sedan"]["t"].astype(float)
    assert len(t) <= 600 + 2
    moving = t[t < 2.0]
    assert np.allclose(np.diff(moving), 0.1, atol=1e-6)
