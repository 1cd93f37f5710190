"""crashsim side by side with its peers, in one process, on the same meshes and poses.

Prints ratios engine time / peer time (below 1: the engine is faster), each a ratio of
medians over repeats, with the machine it ran on. Four comparisons (crashsim issue 6):

1. **Overlap query**: ``crashsim._core.shapes_overlap`` (surfaces crossing, or one mesh
   inside the other) against python-fcl ``collide`` (OBBRSS ``BVHModel``s built once,
   ``CollisionRequest(num_max_contacts=1, enable_contact=False)``), in four poses: a near
   miss whose bounding boxes overlap (1 cm gap), touching (1 mm past the first contact),
   shallow (2 cm) and deep (0.5 m). FCL tests surface crossings only; the engine's query
   also answers "one inside the other", so it does more per call.
2. **Overlap region**: ``crashsim._core.overlap_region`` against the manifold3d boolean
   intersection through trimesh (``trimesh.boolean.intersection([a, b],
   engine="manifold")``) at the shallow and deep poses. The posed trimesh meshes are built
   once, outside the timing (the peer's best case: trimesh caches its volume check).
3. **Whole scene**: two generated sedans subdivided to 21,440 triangles each, the seed's
   90 deg side impact (30 mph into the stationary car's left side, 0.3 m offset, depth of
   penetration 30 ms), 1 s at 1 ms steps: ``Scene.run`` against the same scene driven from
   Python with python-fcl: each step the engine's poses are replayed (quaternion to matrix
   in numpy, ``fcl.Transform``, ``collide``), and at the exchange (first colliding step +
   30 steps) the two posed meshes are intersected with the manifold boolean and its volume
   centroid taken. The Python loop does less than the engine (first contact to the step,
   not to 1e-9 s; no normal, impulse or separation search): a lower bound of a user's cost.
4. **pycrash** (GPL; only ever imported here, guarded): its time-stepped planar impact
   simulation (``pycrash.Impact``, impulse-momentum "IMPC") of the same collision: same
   masses, yaw inertias, dimensions, positions, headings, speeds, friction and restitution;
   the striking point at the engine's impulse centroid (in the striking car's frame), the
   impact plane along the engine's normal, the struck edge the left side. Run in this
   process when ``import pycrash`` works, else in the venv given by ``--pycrash-python``
   (default /tmp/pycrash-venv/bin/python) through a subprocess that times itself. pycrash
   0.0.18 needs pandas < 3, so it cannot share an environment with pandas 3; set it up with
   ``python3 -m venv /tmp/pycrash-venv && /tmp/pycrash-venv/bin/pip install pycrash==0.0.18``.

Meshes (ours, no third-party data): the sedan preset's body (``crashsim.vehicles.generator``,
``body_params("sedan", **default_dims("sedan"))``), closed and single-shell, at a
resolution, then trimesh ``subdivide()`` (x4 triangles per call): "2.5k" = resolution 0.5
(the generator's smallest, 2,464 triangles), "20k" = resolution 1.0 (= meshes/sedan.ply,
5,360) subdivided once: 21,440; "200k" = resolution 3.5 (48,800) subdivided once: 195,200.
Body frame at the class CG of ``Vehicle.generate("sedan")``.

Poses for 1 and 2 (world: x east, y north, z up; m): the struck sedan's CG at (0, 0, h_cg)
heading 100 deg (10 deg off square, so that the bounding boxes overlap before the surfaces
meet); the striking sedan heading 0, CG at (x, 0.3, h_cg), x the first contact (bisection
with the engine's query to 1e-9 m, checked with FCL) plus the case's offset.

Timing: every repeat times a batch of calls of each side (engine first in even repeats,
the peer first in odd ones) lasting at least ``min_time``; the figure is the median over
the repeats of the time per call; the ratio's range is that of the per-repeat ratios.

    python3 benches/compare_peers.py                  # 20k and 200k; 3-6 min (pycrash: most)
    python3 benches/compare_peers.py --quick          # 20k, fewer repeats; about 1 min
    python3 benches/compare_peers.py --sizes 2.5k,20k,200k --only query,region
    # run one engine call in a loop, for a profiler (perf record -g -- python3 ...):
    python3 benches/compare_peers.py --engine-loop region-shallow --sizes 20k --seconds 10

Results and profiles: benches/COMPARISON.md.
"""

from __future__ import annotations

import argparse
import contextlib
import datetime
import functools
import gc
import io
import json
import math
import os
import platform
import shutil
import statistics
import subprocess
import sys
import time
import warnings
from collections.abc import Callable
from dataclasses import dataclass, field
from importlib import metadata
from pathlib import Path
from typing import Any

import numpy as np

# -- configuration ---------------------------------------------------------------------------

# size label -> (generator resolution, number of trimesh subdivide() calls)
SIZES: dict[str, tuple[float, int]] = {
    "2.5k": (0.5, 0),
    "20k": (1.0, 1),
    "200k": (3.5, 1),
}
PRESET = "sedan"
STRUCK_HEADING_DEG = 100.0  # query/region poses: the struck car's heading (deg)
LATERAL_OFFSET = 0.3  # m, the striking car's CG north of the struck car's
# case -> offset (m) of the striking car along x from the first contact
CASES: dict[str, float] = {"miss": -0.01, "touching": 0.001, "shallow": 0.02, "deep": 0.5}
REGION_CASES = ("shallow", "deep")

# whole scene (the seed's 90 deg side impact)
SCENE_SIZE = "20k"
SPEED = 30.0 * 0.44704  # 30 mph in m/s
SCENE_GAP = 0.30  # m between the bullet car's nose and the struck side at t = 0
DTP = 0.030  # s, depth of penetration
RESTITUTION = 0.1
FRICTION = 0.6
DURATION = 1.0  # s
DT = 1e-3  # s

TARGETS = {"query": 0.5, "region": 0.2, "scene": 0.1, "pycrash": 1e-3}
DEFAULT_PYCRASH_PYTHON = "/tmp/pycrash-venv/bin/python"
PYCRASH_VERSION = "0.0.18"

# pycrash units
M_PER_FT = 0.3048
KG_PER_SLUG = 14.593902937206364
NMS2_PER_SLUGFT2 = 1.3558179483314004  # kg m^2 per slug ft^2 (= lb ft s^2)
MPH_PER_MS = 1.0 / 0.44704
G_PYCRASH = 32.2  # ft/s^2: pycrash takes weight (lb) and divides by 32.2 for the mass


# -- timing ----------------------------------------------------------------------------------


@dataclass
class Timing:
    """Per-call times (s) of the engine and the peer, one per repeat."""

    engine: list[float]
    peer: list[float]

    @property
    def engine_median(self) -> float:
        return statistics.median(self.engine)

    @property
    def peer_median(self) -> float:
        return statistics.median(self.peer)

    @property
    def ratio(self) -> float:
        return self.engine_median / self.peer_median

    @property
    def ratio_range(self) -> tuple[float, float]:
        r = [e / p for e, p in zip(self.engine, self.peer, strict=True)]
        return min(r), max(r)


def _calls_for(f: Callable[[], Any], min_time: float) -> int:
    """Calls per batch so that a batch lasts about min_time (s)."""
    t0 = time.perf_counter()
    f()
    one = time.perf_counter() - t0
    return max(1, math.ceil(min_time / max(one, 1e-7)))


def _batch(f: Callable[[], Any], n: int) -> float:
    t0 = time.perf_counter()
    for _ in range(n):
        f()
    return (time.perf_counter() - t0) / n


def compare(
    engine: Callable[[], Any], peer: Callable[[], Any], repeats: int, min_time: float
) -> Timing:
    """Interleaved batches of both callables; garbage collection off while timing."""
    engine()
    peer()  # warm-up (caches, page faults)
    n_e, n_p = _calls_for(engine, min_time), _calls_for(peer, min_time)
    te: list[float] = []
    tp: list[float] = []
    was_enabled = gc.isenabled()
    gc.collect()
    gc.disable()
    try:
        for r in range(repeats):
            if r % 2 == 0:
                te.append(_batch(engine, n_e))
                tp.append(_batch(peer, n_p))
            else:
                tp.append(_batch(peer, n_p))
                te.append(_batch(engine, n_e))
    finally:
        if was_enabled:
            gc.enable()
    return Timing(te, tp)


def _fmt_time(s: float) -> str:
    if s < 1e-3:
        return f"{s * 1e6:8.1f} us"
    if s < 1.0:
        return f"{s * 1e3:8.2f} ms"
    return f"{s:8.3f} s "


def _fmt_ratio(t: Timing) -> str:
    lo, hi = t.ratio_range
    return f"{t.ratio:7.3f} [{lo:.3f}-{hi:.3f}]"


def _verdict(ratio: float, target: float) -> str:
    return "met" if ratio <= target else "MISSED"


# -- machine ---------------------------------------------------------------------------------


def _version(dist: str) -> str:
    try:
        return metadata.version(dist)
    except metadata.PackageNotFoundError:
        return "not installed"


def _cpu_model() -> str:
    try:
        for line in Path("/proc/cpuinfo").read_text().splitlines():
            if line.startswith("model name"):
                return line.split(":", 1)[1].strip()
    except OSError:
        pass
    return platform.processor() or "unknown"


def machine_lines(pycrash_info: str) -> list[str]:
    from crashsim import _core

    load = os.getloadavg()
    try:
        repo = Path(__file__).resolve().parent.parent
        rev = subprocess.run(
            ["git", "-C", str(repo), "describe", "--always", "--dirty"],
            capture_output=True,
            text=True,
            check=False,
        ).stdout.strip()
    except OSError:
        rev = ""
    return [
        f"date: {datetime.datetime.now().isoformat(timespec='seconds')}",
        f"machine: {_cpu_model()}, {os.cpu_count()} logical cores, {platform.system()} "
        f"{platform.release()}; load average (1/5/15 min) at start {load[0]:.2f} / "
        f"{load[1]:.2f} / {load[2]:.2f}",
        f"python {platform.python_version()}, numpy {np.__version__}, "
        f"trimesh {_version('trimesh')}, python-fcl {_version('python-fcl')}, "
        f"manifold3d {_version('manifold3d')}, pycrash {pycrash_info}",
        f"crashsim {_core.__version__} (git {rev or 'unknown'}), extension "
        f"{Path(_core.__file__).name}",
    ]


# -- meshes and poses ------------------------------------------------------------------------


@dataclass
class Body:
    """A generated body: model-frame mesh, body-frame (CG origin) vertices, engine and FCL
    models."""

    label: str
    mesh: Any  # trimesh.Trimesh, model frame
    vertices: np.ndarray  # body frame (m), float64 (n, 3)
    faces: np.ndarray  # int64 (m, 3)
    shape: Any  # crashsim._core.Shape
    fcl_model: Any  # fcl.BVHModel (OBBRSS)
    build_engine: float  # s to build the engine's shape (BVH, dipoles)
    build_fcl: float  # s to build the FCL model

    @property
    def n_triangles(self) -> int:
        return len(self.faces)


@functools.cache
def _class_vehicle() -> Any:
    import crashsim as cs

    return cs.Vehicle.generate(PRESET)


def make_mesh(label: str) -> Any:
    """The sedan body of a size label (model frame), see SIZES."""
    from crashsim.vehicles.generator import body_params, default_dims, generate_body

    resolution, subdivisions = SIZES[label]
    mesh = generate_body(body_params(PRESET, **default_dims(PRESET)), resolution)
    for _ in range(subdivisions):
        mesh = mesh.subdivide()
    return mesh


def fcl_model(vertices: np.ndarray, faces: np.ndarray) -> Any:
    import fcl

    model = fcl.BVHModel()
    model.beginModel(len(vertices), len(faces))
    model.addSubModel(vertices, faces.astype(np.int32))
    model.endModel()
    return model


def make_body(label: str) -> Body:
    from crashsim import _core

    mesh = make_mesh(label)
    cg = _class_vehicle().cg
    vertices = np.ascontiguousarray(np.asarray(mesh.vertices, dtype=np.float64) - cg)
    faces = np.ascontiguousarray(np.asarray(mesh.faces, dtype=np.int64))
    t0 = time.perf_counter()
    shape = _core.Shape(vertices, faces)
    t1 = time.perf_counter()
    model = fcl_model(vertices, faces)
    t2 = time.perf_counter()
    return Body(label, mesh, vertices, faces, shape, model, t1 - t0, t2 - t1)


def quat_z(heading: float) -> np.ndarray:
    """(w, x, y, z) of a yaw of heading rad about world z."""
    return np.array([math.cos(heading / 2), 0.0, 0.0, math.sin(heading / 2)])


def quat_matrix(q: np.ndarray) -> np.ndarray:
    """Rotation matrix (body -> world) of a unit quaternion (w, x, y, z)."""
    w, x, y, z = q
    return np.array(
        [
            [1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)],
            [2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)],
            [2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)],
        ]
    )


@dataclass
class Pose:
    position: np.ndarray  # CG, world (m)
    quaternion: np.ndarray  # (w, x, y, z)

    @property
    def matrix(self) -> np.ndarray:
        return quat_matrix(self.quaternion)


@dataclass
class Poses:
    """The query/region poses of one size: the struck body and the striker per case."""

    struck: Pose
    strikers: dict[str, Pose]
    first_contact_x: float  # m, the striker's CG x at the first contact
    boxes_overlap_at_miss: tuple[bool, bool]  # (world AABBs, posed body-frame boxes)


def make_poses(body: Body) -> Poses:
    import fcl
    from crashsim import _core

    h = _class_vehicle().cg[2]
    struck = Pose(np.array([0.0, 0.0, h]), quat_z(math.radians(STRUCK_HEADING_DEG)))
    q1 = quat_z(0.0)

    def striker(x: float) -> Pose:
        return Pose(np.array([x, LATERAL_OFFSET, h]), q1)

    def overlaps(x: float) -> bool:
        s = striker(x)
        return bool(
            _core.shapes_overlap(
                body.shape, s.position, s.quaternion, body.shape, struck.position, struck.quaternion
            )
        )

    lo, hi = -10.0, 0.0
    if overlaps(lo) or not overlaps(hi):
        raise RuntimeError("the first-contact bracket [-10, 0] m is wrong for these meshes")
    while hi - lo > 1e-9:
        mid = 0.5 * (lo + hi)
        if overlaps(mid):
            hi = mid
        else:
            lo = mid
    strikers = {case: striker(hi + d) for case, d in CASES.items()}
    # Do the bounding boxes overlap at the near miss? World AABBs, and the body-frame boxes
    # as posed (the root boxes of both engines' trees).
    miss = strikers["miss"]
    w1 = body.vertices @ miss.matrix.T + miss.position
    w2 = body.vertices @ struck.matrix.T + struck.position
    aabb = bool(np.all(w1.max(0) > w2.min(0)) and np.all(w2.max(0) > w1.min(0)))
    lo_b, hi_b = body.vertices.min(0), body.vertices.max(0)
    centre = 0.5 * (lo_b + hi_b)

    def box(p: Pose) -> Any:
        r = p.matrix
        shape = fcl.Box(*(hi_b - lo_b))
        return fcl.CollisionObject(shape, fcl.Transform(r, p.position + r @ centre))

    obb = fcl.collide(box(miss), box(struck), fcl.CollisionRequest()) > 0
    return Poses(struck, strikers, hi, (aabb, bool(obb)))


# -- 1. overlap query ------------------------------------------------------------------------


@dataclass
class Row:
    size: str
    case: str
    triangles: int
    timing: Timing
    answer: str = ""  # query: the engine's and FCL's answers
    note: str = ""
    extra: dict[str, Any] = field(default_factory=dict)


def run_query(body: Body, poses: Poses, repeats: int, min_time: float) -> list[Row]:
    import fcl
    from crashsim import _core

    rows = []
    st = poses.struck
    o2 = fcl.CollisionObject(body.fcl_model, fcl.Transform(st.matrix, st.position))
    request = fcl.CollisionRequest(num_max_contacts=1, enable_contact=False)
    for case, p in poses.strikers.items():
        o1 = fcl.CollisionObject(body.fcl_model, fcl.Transform(p.matrix, p.position))
        engine = functools.partial(
            _core.shapes_overlap,
            body.shape,
            p.position,
            p.quaternion,
            body.shape,
            st.position,
            st.quaternion,
        )
        peer = functools.partial(fcl.collide, o1, o2, request)
        a_e, a_p = bool(engine()), peer() > 0
        t = compare(engine, peer, repeats, min_time)
        answer = f"{a_e}/{a_p}" + ("" if a_e == a_p else " (DISAGREE)")
        rows.append(Row(body.label, case, body.n_triangles, t, answer=answer))
    return rows


# -- 2. overlap region -----------------------------------------------------------------------


def posed_trimesh(body: Body, pose: Pose) -> Any:
    import trimesh

    return trimesh.Trimesh(body.vertices @ pose.matrix.T + pose.position, body.faces, process=False)


def run_region(body: Body, poses: Poses, repeats: int, min_time: float) -> list[Row]:
    import trimesh
    from crashsim import _core

    rows = []
    st = poses.struck
    b = posed_trimesh(body, st)
    for case in REGION_CASES:
        p = poses.strikers[case]
        a = posed_trimesh(body, p)
        engine = functools.partial(
            _core.overlap_region,
            body.shape,
            p.position,
            p.quaternion,
            body.shape,
            st.position,
            st.quaternion,
        )
        peer = functools.partial(trimesh.boolean.intersection, [a, b], engine="manifold")
        region = engine()
        inter = peer()
        t = compare(engine, peer, repeats, min_time)
        pts = np.asarray(region["points"])
        extent_e = pts.max(0) - pts.min(0) if len(pts) else np.zeros(3)
        extent_m = inter.extents if len(inter.faces) else np.zeros(3)
        note = (
            f"region box {_vec(extent_e)} m ({region['segment_count']} segments, "
            f"{region['inside_vertices']} inside vertices); boolean box {_vec(extent_m)} m, "
            f"{inter.volume * 1e3:.3g} L, {len(inter.faces)} triangles"
        )
        rows.append(Row(body.label, case, body.n_triangles, t, note=note))
    return rows


def _vec(v: Any, digits: int = 3) -> str:
    return "(" + ", ".join(f"{float(x):.{digits}f}" for x in v) + ")"


# -- 3. whole scene --------------------------------------------------------------------------


@dataclass
class SceneSetup:
    scene: Any  # crashsim.Scene
    body: Body
    red: Any
    blue: Any
    positions: dict[str, np.ndarray]  # initial CG positions


def make_scene(body: Body) -> SceneSetup:
    """The seed's 90 deg side impact with two sedans on ``body``'s mesh."""
    import crashsim as cs

    v = _class_vehicle()

    def vehicle(name: str) -> Any:
        return cs.Vehicle(body.mesh, v.mass, v.cg, v.inertia, name=name, stiffness=v.stiffness)

    red, blue = vehicle("red"), vehicle("blue")
    length, width = float(body.mesh.extents[0]), float(body.mesh.extents[1])
    nose = length / 2.0 - float(v.cg[0])  # CG to front face (m)
    h = float(v.cg[2])
    p_red = np.array([-width / 2.0 - nose - SCENE_GAP, LATERAL_OFFSET, h])
    p_blue = np.array([0.0, 0.0, h])
    scene = cs.Scene(depth_of_penetration=DTP, restitution=RESTITUTION, friction=FRICTION)
    scene.add(red, p_red, heading=0.0, velocity=(SPEED, 0.0, 0.0))
    scene.add(blue, p_blue, heading=math.pi / 2.0)
    red.shape, blue.shape  # noqa: B018 - build the engine's shapes outside the timing
    return SceneSetup(scene, body, red, blue, {"red": p_red, "blue": p_blue})


@dataclass
class Replay:
    """The engine's poses at the step ends t_k = k DT, k = 0..n, for the Python loop."""

    positions: np.ndarray  # (2, n + 1, 3)
    quaternions: np.ndarray  # (2, n + 1, 4)


def replay_of(result: Any) -> Replay:
    n = round(DURATION / DT)
    pos = np.empty((2, n + 1, 3))
    quat = np.empty((2, n + 1, 4))
    for i, name in enumerate(("red", "blue")):
        for k in range(n + 1):
            s = result.state(name, min(k * DT, DURATION))
            pos[i, k] = s["position"]
            quat[i, k] = s["orientation"]
    return Replay(pos, quat)


def python_fcl_scene(body: Body, replay: Replay, dtp_steps: int) -> dict[str, Any]:
    """The scene as a user would drive it from Python: poses per step, FCL collide every
    step, the manifold boolean at the exchange (first colliding step + dtp_steps)."""
    import fcl
    import trimesh

    o1 = fcl.CollisionObject(body.fcl_model, fcl.Transform())
    o2 = fcl.CollisionObject(body.fcl_model, fcl.Transform())
    request = fcl.CollisionRequest(num_max_contacts=1, enable_contact=False)
    first = last = None
    exchange: dict[str, Any] = {}
    n = replay.positions.shape[1] - 1
    for k in range(1, n + 1):
        p1, p2 = replay.positions[0, k], replay.positions[1, k]
        r1, r2 = quat_matrix(replay.quaternions[0, k]), quat_matrix(replay.quaternions[1, k])
        o1.setTransform(fcl.Transform(r1, p1))
        o2.setTransform(fcl.Transform(r2, p2))
        hit = fcl.collide(o1, o2, request) > 0
        if hit:
            if first is None:
                first = k
            last = k
        if first is not None and k == first + dtp_steps:
            a = trimesh.Trimesh(body.vertices @ r1.T + p1, body.faces, process=False)
            b = trimesh.Trimesh(body.vertices @ r2.T + p2, body.faces, process=False)
            inter = trimesh.boolean.intersection([a, b], engine="manifold")
            exchange = {"step": k, "volume": inter.volume, "centroid": inter.center_mass}
    return {"first": first, "last": last, "exchange": exchange}


def run_scene(setup: SceneSetup, repeats: int) -> tuple[Row, Any]:
    result = setup.scene.run(DURATION, DT)
    replay = replay_of(result)
    dtp_steps = round(DTP / DT)
    engine = functools.partial(setup.scene.run, DURATION, DT)
    peer = functools.partial(python_fcl_scene, setup.body, replay, dtp_steps)
    check = peer()
    t = compare(engine, peer, repeats, 0.0)
    imp = result.impacts[0]
    sep = [c.time for c in result.contacts if c.kind == "separation"]
    ex = check["exchange"]
    note = (
        f"engine: first contact {imp.first_contact_time:.6f} s, exchange {imp.time:.6f} s, "
        f"separation {sep[0] if sep else float('nan'):.6f} s, centroid {_vec(imp.centroid)} m, "
        f"{len(result.impacts)} exchange(s); python+fcl: first colliding step "
        f"{(check['first'] or 0) * DT:.3f} s, last {(check['last'] or 0) * DT:.3f} s, "
        f"boolean at {ex.get('step', 0) * DT:.3f} s: {ex.get('volume', float('nan')) * 1e3:.3g} L, "
        f"centroid {_vec(ex.get('centroid', (math.nan,) * 3))} m"
    )
    return Row(setup.body.label, "1 s @ 1 ms", setup.body.n_triangles, t, note=note), result


def scene_phases(setup: SceneSetup, result: Any) -> list[tuple[str, float, float, float]]:
    """The engine's wall time per phase of the scene: one fresh world run in pieces cut at
    step boundaries around the first contact, the exchange and the separation. Returns
    (phase, start s, end s, wall s)."""
    imp = result.impacts[0]
    sep = [c.time for c in result.contacts if c.kind == "separation"]

    def step_floor(t: float) -> float:
        return math.floor(t / DT) * DT

    marks = [
        ("approach", step_floor(imp.first_contact_time)),
        ("step with the first contact", step_floor(imp.first_contact_time) + DT),
        ("timer (depth of penetration)", step_floor(imp.time)),
        ("step with the exchange", step_floor(imp.time) + DT),
    ]
    if sep:
        marks += [
            ("engaged (overlap, not closing)", step_floor(sep[0])),
            ("step with the separation", step_floor(sep[0]) + DT),
            ("apart again (after separation)", DURATION),
        ]
    else:
        marks.append(("engaged (overlap, not closing)", DURATION))
    world = setup.scene.build_world()
    out = []
    start = 0.0
    for name, end in marks:
        t0 = time.perf_counter()
        world.run(round(end - start, 12), DT)
        out.append((name, start, end, time.perf_counter() - t0))
        start = end
    return out


# -- 4. pycrash ------------------------------------------------------------------------------


def make_box_scene(setup: SceneSetup) -> Any:
    """The same planar scene with the vehicles as pycrash models them: rectangles, i.e. box
    meshes (12 triangles) of the body's length, width and height with the same mass, CG and
    inertia, at the same CG positions and headings."""
    import crashsim as cs
    import trimesh

    v = _class_vehicle()
    lo, hi = setup.body.mesh.bounds
    box = trimesh.creation.box(extents=hi - lo)
    box.apply_translation((lo + hi) / 2.0)
    scene = cs.Scene(depth_of_penetration=DTP, restitution=RESTITUTION, friction=FRICTION)
    for name, heading, speed in (("red", 0.0, SPEED), ("blue", math.pi / 2.0, 0.0)):
        vehicle = cs.Vehicle(box, v.mass, v.cg, v.inertia, name=name)
        scene.add(vehicle, setup.positions[name], heading=heading, velocity=(speed, 0.0, 0.0))
        vehicle.shape  # noqa: B018 - built outside the timing
    return scene


def pycrash_spec(setup: SceneSetup, result: Any, repeats: int, dts: list[float]) -> dict[str, Any]:
    """The engine's scene in pycrash's terms (ft, lb, mph, deg; its frames: vehicle x forward,
    y right; global X east, Y south, headings clockwise seen from above)."""
    v = _class_vehicle()
    params = v.generator_params
    length, width = (float(e) for e in setup.body.mesh.extents[:2])
    cgx, cgz = float(v.cg[0]), float(v.cg[2])
    front_axle = length / 2.0 - params.front_overhang  # model-frame x (m)
    lcgf = front_axle - cgx
    imp = result.impacts[0]
    red = result.state_at("red", imp.time)
    r = quat_matrix(np.asarray(red["orientation"]))
    c_body = r.T @ (np.asarray(imp.centroid) - np.asarray(red["position"]))
    n_body = r.T @ np.asarray(imp.normal)

    def vehicle(name: str, pos: np.ndarray, heading_deg: float, speed: float) -> dict[str, Any]:
        ft = 1.0 / M_PER_FT
        return {
            "name": name,
            "inputs": {
                "year": 2020,
                "vehmake": "crashsim",
                "vehmodel": f"generated {PRESET}",
                "weight": v.mass / KG_PER_SLUG * G_PYCRASH,  # lb, so that weight/32.2 = mass
                "vin": "none",
                "brake": 0.0,
                "steer_ratio": 16.0,
                "init_x_pos": float(pos[0]) * ft,
                "init_y_pos": -float(pos[1]) * ft,
                "head_angle": -heading_deg,
                "width": width * ft,
                "length": length * ft,
                "hcg": cgz * ft,
                "lcgf": lcgf * ft,
                "lcgr": (params.wheelbase - lcgf) * ft,
                "wb": params.wheelbase * ft,
                "track": 0.85 * width * ft,  # assumed: pycrash's tire model needs a track
                "f_hang": params.front_overhang * ft,
                "r_hang": (length - params.wheelbase - params.front_overhang) * ft,
                "tire_d": 2.0 * params.wheel_radius * ft,
                "tire_w": 0.2 * ft,
                "izz": float(v.inertia[2, 2]) / NMS2_PER_SLUGFT2,
                "fwd": 1,
                "rwd": 0,
                "awd": 0,
                "A": 0.0,
                "B": 0.0,
                "k": 0.0,
                "L": 0.0,
                "c": 0.0,
                "vx_initial": speed * MPH_PER_MS,
                "vy_initial": 0.0,
                "omega_z": 0.0,
            },
        }

    ft = 1.0 / M_PER_FT
    front, rear, half = (length / 2 - cgx) * ft, (length / 2 + cgx) * ft, width / 2 * ft
    return {
        "duration": DURATION,
        "dts": dts,
        "repeats": repeats,
        "mu": FRICTION,
        "cor": RESTITUTION,
        "vehicles": [
            vehicle("red", setup.positions["red"], 0.0, SPEED),
            vehicle("blue", setup.positions["blue"], 90.0, 0.0),
        ],
        # striking point (ft, x forward, y right) and the impact plane's normal angle (deg)
        "impact_point": [
            float(c_body[0]) * ft,
            -float(c_body[1]) * ft,
            math.degrees(math.atan2(-float(n_body[1]), float(n_body[0]))),
        ],
        # the struck car's left side, front to rear in its frame: pycrash edge 3
        "edge": [3, [-rear, -half, front, -half]],
    }


def pycrash_worker(spec: dict[str, Any]) -> dict[str, Any]:
    """Build and time pycrash's scene (runs wherever pycrash imports). pycrash's own output
    (it prints a lot) is swallowed; its warnings are silenced."""
    buf = io.StringIO()
    with warnings.catch_warnings(), contextlib.redirect_stdout(buf):
        warnings.simplefilter("ignore")
        import pandas as pd
        import pycrash
        from pycrash import Impact, Vehicle

        out: dict[str, Any] = {
            "pycrash": _version("pycrash"),
            "pandas": pd.__version__,
            "numpy": np.__version__,
            "python": platform.python_version(),
            "executable": sys.executable,
            "module": getattr(pycrash, "__file__", ""),
            "runs": [],
        }
        duration = spec["duration"]
        for dt in spec["dts"]:
            times = []
            for _ in range(spec["repeats"]):
                t_in = np.round(np.arange(0.0, duration + dt / 2, dt), 6)
                zero = np.zeros_like(t_in)
                vehicles = []
                for vs in spec["vehicles"]:
                    veh = Vehicle(vs["name"], vs["inputs"])
                    veh.driver_input = pd.DataFrame(
                        {"t": t_in, "throttle": zero, "brake": zero, "steer": zero}
                    )
                    veh.isTrailer = False  # 0.0.18's Vehicle never sets it; Impact reads it
                    vehicles.append(veh)
                vehicles[0].striking = True
                vehicles[0].impact_points = [tuple(spec["impact_point"])]
                vehicles[1].striking = False
                vehicles[1].edgeimpact = [spec["edge"][0]]
                vehicles[1].edgeimpact_points = [tuple(spec["edge"][1])]
                t0 = time.perf_counter()
                sim = Impact(
                    "crashsim comparison",
                    duration,
                    "IMPC",
                    vehicles,
                    impact_order=[[0, 1]],
                    impc_inputs={0: {"vehicle_mu": spec["mu"], "cor": spec["cor"]}},
                    user_sim_defaults={"dt_motion": dt, "mu_max": 0.76, "alpha_max": 0.174533},
                )
                sim.simulate(show_results=False)
                times.append(time.perf_counter() - t0)
            steps = sorted(sim._impactIndex)
            run: dict[str, Any] = {"dt": dt, "times": times}
            if steps:
                i = int(steps[0])
                run["impact_time"] = float(sim.vehicles[0].model.t[i])
                for k, veh in enumerate(sim.vehicles):
                    m = veh.model
                    before = np.array([m.Vx[i - 1], m.Vy[i - 1]]) * M_PER_FT
                    after = np.array([m.Vx[i], m.Vy[i]]) * M_PER_FT
                    run[f"delta_v_{k}"] = float(np.linalg.norm(after - before))
            out["runs"].append(run)
    return out


def run_pycrash(spec: dict[str, Any], python: str | None) -> tuple[dict[str, Any] | None, str, str]:
    """(worker output or None, where it ran, what failed)."""
    try:
        with contextlib.redirect_stdout(io.StringIO()), warnings.catch_warnings():
            warnings.simplefilter("ignore")
            import pycrash  # noqa: F401 - GPL: only ever imported here, never in the package
        in_process = True
    except ImportError:
        in_process = False
    if in_process:
        return pycrash_worker(spec), "this process", ""
    exe = python or DEFAULT_PYCRASH_PYTHON
    if not (Path(exe).exists() or shutil.which(exe)):
        return (
            None,
            "",
            f"pycrash not installed (not importable here, and no interpreter at {exe}); "
            f"set up: python3 -m venv /tmp/pycrash-venv && /tmp/pycrash-venv/bin/pip "
            f"install pycrash=={PYCRASH_VERSION}",
        )
    proc = subprocess.run(
        [exe, str(Path(__file__).resolve()), "--pycrash-worker"],
        input=json.dumps(spec),
        capture_output=True,
        text=True,
        check=False,
    )
    if proc.returncode != 0:
        tail = "\n".join(proc.stderr.strip().splitlines()[-5:])
        return None, exe, f"pycrash worker failed in {exe} (exit {proc.returncode}):\n{tail}"
    return json.loads(proc.stdout), f"subprocess {exe}", ""


def _worker_main() -> None:
    spec = json.loads(sys.stdin.read())
    out = pycrash_worker(spec)
    sys.stdout.write(json.dumps(out))


# -- engine loops for profilers --------------------------------------------------------------


def engine_loop(what: str, label: str, seconds: float) -> None:
    """Call one engine operation in a loop for ``seconds`` (for perf / py-spy)."""
    from crashsim import _core

    body = make_body(label)
    if what == "scene":
        setup = make_scene(make_body(SCENE_SIZE) if label != SCENE_SIZE else body)
        f: Callable[[], Any] = functools.partial(setup.scene.run, DURATION, DT)
    else:
        kind, case = what.split("-", 1)
        poses = make_poses(body)
        p, st = poses.strikers[case], poses.struck
        fn = _core.shapes_overlap if kind == "query" else _core.overlap_region
        f = functools.partial(
            fn, body.shape, p.position, p.quaternion, body.shape, st.position, st.quaternion
        )
    n = 0
    t0 = time.perf_counter()
    while time.perf_counter() - t0 < seconds:
        f()
        n += 1
    el = time.perf_counter() - t0
    print(f"{what} at {label}: {n} calls, {_fmt_time(el / n).strip()} per call")


# -- main ------------------------------------------------------------------------------------


def _print_rows(title: str, rows: list[Row], peer: str, target: float) -> None:
    print(title)
    head = f"  {'size':>5} {'triangles':>9}  {'case':<11} {'engine':>11}  {peer:>11}"
    print(head + f"  {'ratio [range]':<22} target <= {target:g}")
    for r in rows:
        t = r.timing
        print(
            f"  {r.size:>5} {r.triangles:>9,}  {r.case:<11} {_fmt_time(t.engine_median)}  "
            f"{_fmt_time(t.peer_median)}  {_fmt_ratio(t):<22} {_verdict(t.ratio, target):<6}"
            + (f"   overlap engine/fcl: {r.answer}" if r.answer else "")
        )
    for r in rows:
        if r.note:
            print(f"    {r.size} {r.case}: {r.note}")


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--quick", action="store_true", help="a short run (20k, fewer repeats)")
    ap.add_argument("--sizes", help=f"comma-separated, of {', '.join(SIZES)} (default 20k,200k)")
    ap.add_argument(
        "--only",
        default="query,region,scene,pycrash",
        help="comma-separated comparisons: query, region, scene, pycrash",
    )
    ap.add_argument("--repeats", type=int, help="repeats per figure (default 7; quick 3)")
    ap.add_argument("--pycrash-python", help=f"interpreter with pycrash ({DEFAULT_PYCRASH_PYTHON})")
    ap.add_argument("--pycrash-repeats", type=int, help="pycrash runs per dt (default 3; quick 1)")
    ap.add_argument("--engine-loop", help="profile helper: query-<case>, region-<case> or scene")
    ap.add_argument("--seconds", type=float, default=10.0, help="duration of --engine-loop (s)")
    ap.add_argument("--pycrash-worker", action="store_true", help=argparse.SUPPRESS)
    args = ap.parse_args(argv)
    if args.pycrash_worker:
        _worker_main()
        return 0

    sizes = (args.sizes or ("20k" if args.quick else "20k,200k")).split(",")
    for s in sizes:
        if s not in SIZES:
            ap.error(
                f"size {s!r} is unknown: use {', '.join(SIZES)} (the generator's smallest body "
                "has 2,464 triangles, so there is no 1k)"
            )
    if args.engine_loop:
        engine_loop(args.engine_loop, sizes[0], args.seconds)
        return 0
    only = set(args.only.split(","))
    unknown = only - {"query", "region", "scene", "pycrash"}
    if unknown:
        ap.error(f"--only: unknown comparison(s) {sorted(unknown)}")
    repeats = args.repeats or (3 if args.quick else 7)
    min_time = 0.05 if args.quick else 0.2
    scene_repeats = args.repeats or (2 if args.quick else 5)
    pycrash_repeats = args.pycrash_repeats or (1 if args.quick else 3)

    print("crashsim vs peers: benches/compare_peers.py " + " ".join(sys.argv[1:]))
    pycrash_note = "(see 4.)" if "pycrash" in only else "(not run)"
    for line in machine_lines(pycrash_note):
        print(line)
    print(
        f"timing: median of {repeats} repeats (scene: {scene_repeats}), each a batch of calls "
        f">= {min_time} s, engine and peer interleaved; ratio = engine / peer (< 1: engine "
        "faster) [range of the per-repeat ratios]"
    )
    print()

    bodies = {s: make_body(s) for s in sizes}
    print("meshes: generated sedan body (crashsim.vehicles.generator), closed single shell")
    for s, b in bodies.items():
        res, sub = SIZES[s]
        print(
            f"  {s:>5}: resolution {res}, "
            f"{f'subdivided x{4**sub}' if sub else 'not subdivided'}: {b.n_triangles:,} triangles, "
            f"{len(b.vertices):,} vertices; build: engine {_fmt_time(b.build_engine).strip()}, "
            f"fcl {_fmt_time(b.build_fcl).strip()} (outside the timing)"
        )
    poses = {s: make_poses(b) for s, b in bodies.items()} if only & {"query", "region"} else {}
    if poses:
        print(
            f"poses: struck CG (0, 0, h_cg) heading {STRUCK_HEADING_DEG:g} deg; striker heading "
            f"0, CG (x_c + offset, {LATERAL_OFFSET}, h_cg), x_c the first contact; offsets "
            + ", ".join(f"{c} {d * 1e3:+g} mm" for c, d in CASES.items())
        )
        for s, p in poses.items():
            aabb, obb = p.boxes_overlap_at_miss
            print(
                f"  {s:>5}: x_c = {p.first_contact_x:.6f} m; near miss: world AABBs overlap "
                f"{aabb}, posed body boxes overlap {obb}"
            )
    print()

    summary: list[tuple[str, float, float]] = []
    if "query" in only:
        rows = [r for s in sizes for r in run_query(bodies[s], poses[s], repeats, min_time)]
        _print_rows(
            "1. overlap query: crashsim shapes_overlap vs python-fcl collide (OBBRSS, 1 contact)",
            rows,
            "fcl",
            TARGETS["query"],
        )
        print(
            '  note: FCL detects surface crossings only; shapes_overlap also answers "one '
            'inside the other" (a winding number per shell when no surfaces cross)'
        )
        print()
        summary += [(f"query {r.size} {r.case}", r.timing.ratio, TARGETS["query"]) for r in rows]
    if "region" in only:
        rows = [r for s in sizes for r in run_region(bodies[s], poses[s], repeats, min_time)]
        _print_rows(
            "2. overlap region: crashsim overlap_region vs trimesh.boolean.intersection "
            "(manifold3d)",
            rows,
            "manifold",
            TARGETS["region"],
        )
        print()
        summary += [(f"region {r.size} {r.case}", r.timing.ratio, TARGETS["region"]) for r in rows]
    scene_times: list[float] = []  # the engine's Scene.run wall times (s)
    if only & {"scene", "pycrash"}:
        body = bodies.get(SCENE_SIZE) or make_body(SCENE_SIZE)
        setup = make_scene(body)
        if "scene" in only:
            row, result = run_scene(setup, scene_repeats)
            scene_times = list(row.timing.engine)
            _print_rows(
                "3. whole scene: Scene.run vs Python + python-fcl per step + manifold boolean "
                f"at the exchange (seed 90 deg side impact, two sedans, {body.n_triangles:,} "
                "triangles each)",
                [row],
                "python",
                TARGETS["scene"],
            )
            print("  engine wall time by phase (one run cut at step boundaries):")
            for name, t_a, t_b, wall in scene_phases(setup, result):
                print(f"    {t_a:6.3f}-{t_b:6.3f} s  {name:<32} {_fmt_time(wall)}")
            print()
            summary.append((f"scene {SCENE_SIZE}", row.timing.ratio, TARGETS["scene"]))
        else:
            result = setup.scene.run(DURATION, DT)
        if "pycrash" in only:
            if not scene_times:
                for _ in range(scene_repeats):
                    t0 = time.perf_counter()
                    setup.scene.run(DURATION, DT)
                    scene_times.append(time.perf_counter() - t0)
            dts = [DT, 0.01]
            spec = pycrash_spec(setup, result, pycrash_repeats, dts)
            out, where, error = run_pycrash(spec, args.pycrash_python)
            # The load changes over minutes: time the engine again right after pycrash and
            # take the median of all the engine's runs.
            engine_times = list(scene_times)
            for _ in range(scene_repeats if out is not None else 0):
                t0 = time.perf_counter()
                setup.scene.run(DURATION, DT)
                engine_times.append(time.perf_counter() - t0)
            engine_scene = statistics.median(engine_times)
            # The planar scene as pycrash sees it: rectangles (box meshes).
            box_scene = make_box_scene(setup)
            box_result = box_scene.run(DURATION, DT)
            box_times = []
            for _ in range(max(scene_repeats, 5)):
                t0 = time.perf_counter()
                box_scene.run(DURATION, DT)
                box_times.append(time.perf_counter() - t0)
            engine_boxes = statistics.median(box_times)
            print(
                "4. pycrash: Impact (IMPC) time-stepped planar simulation of the same scene, "
                f"{DURATION:g} s (construction + simulate)"
            )
            if out is None:
                print(f"  {error}")
            else:
                print(
                    f"  pycrash {out['pycrash']} in {where} (python {out['python']}, numpy "
                    f"{out['numpy']}, pandas {out['pandas']}); striking point "
                    f"{_vec(np.array(spec['impact_point'][:2]) * M_PER_FT)} m (x fwd, y right), "
                    f"plane {spec['impact_point'][2]:.2f} deg"
                )
                imp = result.impacts[0]
                dv = [float(np.linalg.norm(imp.delta_v[n])) for n in ("red", "blue")]
                print(
                    f"  engine Scene.run {_fmt_time(engine_scene).strip()} (median of "
                    f"{len(engine_times)}: before and right after pycrash); "
                    f"exchange at {imp.time:.4f} s, delta-V red {dv[0]:.2f}, blue {dv[1]:.2f} m/s"
                )
                box_imp = box_result.impacts[0]
                box_dv = [float(np.linalg.norm(box_imp.delta_v[n])) for n in ("red", "blue")]
                print(
                    f"  engine Scene.run with rectangles (box meshes, as pycrash models them) "
                    f"{_fmt_time(engine_boxes).strip()} (median of {len(box_times)}); exchange "
                    f"at {box_imp.time:.4f} s, delta-V red {box_dv[0]:.2f}, blue "
                    f"{box_dv[1]:.2f} m/s"
                )
                for run in out["runs"]:
                    med = statistics.median(run["times"])
                    ratio_boxes = engine_boxes / med
                    if run["dt"] == DT:
                        print(
                            f"  dt {run['dt'] * 1e3:g} ms, rectangles: ratio {ratio_boxes:.6f} = "
                            f"engine {1 / ratio_boxes:,.0f}x faster; target <= "
                            f"{TARGETS['pycrash']:g}: {_verdict(ratio_boxes, TARGETS['pycrash'])}"
                        )
                        summary.append(("pycrash (same dt, rect)", ratio_boxes, TARGETS["pycrash"]))
                    ratio = engine_scene / med
                    tag = "same step" if run["dt"] == DT else "pycrash's default step"
                    print(
                        f"  dt {run['dt'] * 1e3:g} ms ({tag}): pycrash {_fmt_time(med).strip()} "
                        f"(median of {len(run['times'])}); ratio {ratio:.5f} = engine "
                        f"{1 / ratio:,.0f}x faster; target <= {TARGETS['pycrash']:g}: "
                        f"{_verdict(ratio, TARGETS['pycrash'])}; impact at "
                        f"{run.get('impact_time', float('nan')):.3f} s, delta-V red "
                        f"{run.get('delta_v_0', float('nan')):.2f}, blue "
                        f"{run.get('delta_v_1', float('nan')):.2f} m/s"
                    )
                    if run["dt"] == DT:
                        summary.append(("pycrash (same dt, 20k)", ratio, TARGETS["pycrash"]))
            print()
    load = os.getloadavg()
    print(f"load average at end {load[0]:.2f} / {load[1]:.2f} / {load[2]:.2f}")
    print("summary (ratio = engine / peer, median):")
    for name, ratio, target in summary:
        print(f"  {name:<22} {ratio:9.4f}  target <= {target:g}: {_verdict(ratio, target)}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
