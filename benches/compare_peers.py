"""crashsim side by side with its peers, in one process, on the same meshes and poses.

Prints ratios engine time / peer time (below 1: the engine is faster), each a ratio of
medians over repeats, with the machine it ran on. Five comparisons (crashsim issues 6 and
11):

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
5. **Whole event, run to rest** (crashsim issue 11): the same scene on a level ground, both
   sedans on the class's wheels and tyres (``Vehicle.generate("sedan").wheels``), every wheel
   of both locked at the vehicle's first exchange, run until both are at rest:
   ``Scene.run(until="rest")`` against a Python loop that does the same in plain Python:
   both vehicles' motion on the ground (``PeerVehicles``: the engine's wheels, suspension,
   reconstruction tyre, body-ground contact and RK4 sub-steps, written anew in scalar
   Python), python-fcl ``collide`` every 1 ms step, a timer of 30 steps from the first
   colliding step, the manifold boolean at the exchange, the exchange's velocity changes
   taken from the engine (the peer does not solve the impulse), every wheel locked from then
   on, and the engine's rest criterion. The two runs' rest poses are printed side by side
   (they agree to the millimetre but for the peer's exchange at a step end), and the
   engine's time is split into the impact phase (to the step after the first separation)
   and the run-out.

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

    python3 benches/compare_peers.py                  # 20k and 200k; about 5 min (pycrash: most)
    python3 benches/compare_peers.py --quick          # 20k, fewer repeats; about 2 min
    python3 benches/compare_peers.py --only runout    # 5. alone; under a minute
    python3 benches/compare_peers.py --only runout --check-peer  # and the peer's motion checked
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
import statistics
import sys
import time
import warnings
from collections.abc import Callable
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np
from pycrash_peer import (  # benches/pycrash_peer.py (this folder is on sys.path)
    DEFAULT_PYCRASH_PYTHON,
    dist_version,
    git_revision,
    pycrash_imports,
    run_worker,
    worker_environment,
)

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

# Goals (engine / peer ratio, median): issue 23's for the near-miss query (0.3 at 20k and
# 200k), the seed's scene (0.1) and the run to rest (0.03); the earlier issues' (6 and 11) for
# the query's other poses (0.5), the overlap region and pycrash.
TARGETS = {"query": 0.5, "region": 0.2, "scene": 0.1, "runout": 0.03, "pycrash": 1e-3}
QUERY_MISS_TARGET = 0.3  # the near miss ("miss") of the query


def _query_target(case: str) -> float:
    return QUERY_MISS_TARGET if case == "miss" else TARGETS["query"]


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
    rev = git_revision()
    return [
        f"date: {datetime.datetime.now().isoformat(timespec='seconds')}",
        f"machine: {_cpu_model()}, {os.cpu_count()} logical cores, {platform.system()} "
        f"{platform.release()}; load average (1/5/15 min) at start {load[0]:.2f} / "
        f"{load[1]:.2f} / {load[2]:.2f}",
        f"python {platform.python_version()}, numpy {np.__version__}, "
        f"trimesh {dist_version('trimesh')}, python-fcl {dist_version('python-fcl')}, "
        f"manifold3d {dist_version('manifold3d')}, pycrash {pycrash_info}",
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


# -- 5. the whole event: the same scene on the ground, run to rest ---------------------------

RUNOUT_MAX_DURATION = 20.0  # s, the longest a run to rest may take (either side)
# The engine's constants the peer re-uses (crates/crashsim-core/src/motion/, vehicle/tyre.rs,
# world/stepper.rs); the others come from crashsim.vehicles.wheels.dynamics_defaults().
MAX_SUBSTEP = 1e-3  # s
MAX_SUBSTEP_ANGLE = 0.02  # rad
MAX_SUBSTEP_RELAXATION = 1.0  # h |v_x| / sigma per sub-step
MAX_SUBSTEP_SUSPENSION = 2.0  # h |lambda| per sub-step of the suspension's fastest mode
AIRBORNE_RELAXATION = 0.02  # s
YIELD_RELAXATION = 0.005  # s
ROLLING_RESISTANCE_SPEED = 0.1  # m/s
BODY_CONTACT_FREQUENCY = 20.0  # Hz
BODY_CONTACT_DAMPING = 0.5
BODY_SLIP_SPEED = 0.05  # m/s
WHEEL_CLEARANCE = 0.05  # m
WHEEL_HALF_WIDTH = 0.15  # m
MOVING_SPEED_FACTOR = 10.0  # MOVING_SPEED = 10 REST_SPEED; 10 REST_YAW_RATE counts as yawing
SETTLED_ANGULAR_SPEED = math.radians(2.0)  # rad/s
SETTLED_SPEED = 0.01  # m/s: every velocity component, as the engine's SETTLED_SPEED


@dataclass
class RunoutSetup:
    """The seed's scene on a level ground, both sedans on the class's wheels, every wheel of
    both locked at the vehicle's first exchange."""

    scene: Any  # crashsim.Scene with a ground
    body: Body
    vehicles: list[Any]  # crashsim.Vehicle, red then blue


def make_runout_scene(body: Body) -> RunoutSetup:
    import crashsim as cs

    v = _class_vehicle()

    def vehicle(name: str) -> Any:
        plain = cs.Vehicle(body.mesh, v.mass, v.cg, v.inertia, name=name, stiffness=v.stiffness)
        return plain.with_wheels(v.wheels)

    red, blue = vehicle("red"), vehicle("blue")
    length, width = float(body.mesh.extents[0]), float(body.mesh.extents[1])
    nose = length / 2.0 - float(v.cg[0])
    scene = cs.Scene(
        depth_of_penetration=DTP, restitution=RESTITUTION, friction=FRICTION, ground=cs.Ground()
    )
    for veh, xy, heading, speed in (
        (red, (-width / 2.0 - nose - SCENE_GAP, LATERAL_OFFSET), 0.0, SPEED),
        (blue, (0.0, 0.0), math.pi / 2.0, 0.0),
    ):
        lock = cs.DriverInputs(wheel_states=[(w, "locked", "exchange 1") for w in veh.wheels])
        scene.add(veh, xy, heading=heading, velocity=(speed, 0.0, 0.0), inputs=lock)
        veh.shape  # noqa: B018 - build the engine's shapes outside the timing
    return RunoutSetup(scene, body, [red, blue])


STRIDE = 21  # floats per vehicle in the peer's state: x 3, q 4, v 3, l 3, u 4 x 2


def _rotation(qw: float, qx: float, qy: float, qz: float) -> tuple[float, ...]:
    """Row-major rotation matrix (body -> world) of a quaternion, normalised first."""
    n = math.sqrt(qw * qw + qx * qx + qy * qy + qz * qz)
    w, x, y, z = qw / n, qx / n, qy / n, qz / n
    return (
        1 - 2 * (y * y + z * z),
        2 * (x * y - w * z),
        2 * (x * z + w * y),
        2 * (x * y + w * z),
        1 - 2 * (x * x + z * z),
        2 * (y * z - w * x),
        2 * (x * z - w * y),
        2 * (y * z + w * x),
        1 - 2 * (x * x + y * y),
    )


def _world_inverse(r: tuple[float, ...], inv: tuple[float, ...], lx: float, ly: float, lz: float):
    """w = R I^-1 R^T l (rad/s) from the world angular momentum l."""
    r00, r01, r02, r10, r11, r12, r20, r21, r22 = r
    bx = r00 * lx + r10 * ly + r20 * lz
    by = r01 * lx + r11 * ly + r21 * lz
    bz = r02 * lx + r12 * ly + r22 * lz
    i00, i01, i02, i10, i11, i12, i20, i21, i22 = inv
    cx = i00 * bx + i01 * by + i02 * bz
    cy = i10 * bx + i11 * by + i12 * bz
    cz = i20 * bx + i21 * by + i22 * bz
    return (
        r00 * cx + r01 * cy + r02 * cz,
        r10 * cx + r11 * cy + r12 * cz,
        r20 * cx + r21 * cy + r22 * cz,
    )


class PeerVehicles:
    """The engine's vehicles-on-the-ground model re-written in plain Python (scalar floats
    and the math module; numpy only where a body touches the ground): gravity; each wheel a
    vertical spring-damper whose load is max(0, F0 + k (R - h) - c dh/dt + the anti-roll
    bar's k_bar (c_l - c_r), each travel held at its droop -F0 / k); the linear tyre (tread
    deflection u with du/dt = -slip - |vx| / sigma u, force k_t u + c_t du/dt with
    k_t = C / sigma, C = c Fz the cornering coefficient times the load, c_t = 2 sqrt(k_t Fz /
    g); friction circle; elasto-plastic yield at mu sigma / c; a locked wheel slides against
    its patch velocity; rolling resistance on a rolling wheel); the body's hull points as a
    stiff spring-damper with friction where they reach the ground; classical Runge-Kutta in
    sub-steps of at most 1 ms and 0.02 rad. The same equations as
    crates/crashsim-core/src/motion/ and vehicle/ (read there, written anew here) for what
    the scene uses: the level ground z = 0 with one friction, the linear tyre, no steering,
    brakes or drive (each wheel free or locked).

    The state is a flat list of floats, ``STRIDE`` per vehicle: CG position x, orientation q
    (w, x, y, z), velocity v, world angular momentum about the CG l, tread deflections u
    (x forward, y left, per wheel). Scalar Python, because the arrays are tiny: the same
    equations as numpy arrays over the vehicles and wheels (the first version) gave the same
    states to 1e-15 m and took ten times as long per step (2.65 ms against 0.26 ms)."""

    def __init__(self, vehicles: list[Any]) -> None:
        import trimesh
        from crashsim.vehicles.wheels import dynamics_defaults

        d = dynamics_defaults()
        self.g = d["gravity"]
        self.mu = d["tyre_friction"]
        self.body_mu = d["body_friction"]
        self.cornering = d["cornering"]
        self.sigma = d["relaxation_length"]
        self.rolling = d["rolling_resistance"]
        self.rest_speed = d["rest_speed"]
        self.rest_yaw = d["rest_yaw_rate"]
        self.rest_time = d["rest_time"]
        omega = 2.0 * math.pi * BODY_CONTACT_FREQUENCY
        self.bodies: list[dict[str, Any]] = []
        for v in vehicles:
            spec = v.wheels.spec(v.mass)
            if spec["tyre"] != type(spec["tyre"])("linear"):
                raise ValueError(f"the peer has the default linear tyre only, not {spec['tyre']}")
            centers = np.asarray(spec["centers"], dtype=np.float64)
            bars = [
                (left, right, float(k) / float(centers[left, 1] - centers[right, 1]) ** 2)
                for left, right, k in spec["anti_roll"]
            ]
            inertia = np.asarray(v.inertia, dtype=np.float64)
            # the bound on the suspension's fastest mode (the engine's suspension_rate)
            inv_i_max = float(np.linalg.eigvalsh(np.linalg.inv(inertia)).max())
            reach = np.linalg.norm(centers, axis=1) + np.asarray(spec["radii"], dtype=np.float64)
            inv_m = 1.0 / v.mass + reach * reach * inv_i_max
            stiffness = float(np.sum(np.asarray(spec["spring_rates"]) * inv_m)) + sum(
                k_bar * (inv_m[left] + inv_m[right]) for left, right, k_bar in bars
            )
            suspension_rate = float(np.sum(np.asarray(spec["damping"]) * inv_m)) + math.sqrt(
                stiffness
            )
            wheels = [
                (
                    *(float(c) for c in spec["centers"][k]),
                    float(spec["radii"][k]),
                    float(spec["static_loads"][k]),
                    float(spec["spring_rates"][k]),
                    float(spec["damping"][k]),
                )
                for k in range(len(spec["radii"]))
            ]
            # the body's contact with the ground: hull vertices outside the wheels, each with
            # the stiffness and damping of its share of the hull area
            verts = np.asarray(v.shape.vertices, dtype=np.float64)
            hull = trimesh.convex.convex_hull(verts)
            hv, hf = np.asarray(hull.vertices), np.asarray(hull.faces)
            tri = hv[hf]
            third = np.linalg.norm(np.cross(tri[:, 1] - tri[:, 0], tri[:, 2] - tri[:, 0]), axis=1)
            area = np.zeros(len(hv))
            for j in range(3):
                np.add.at(area, hf[:, j], third / 6.0)
            rel = hv[:, None, :] - spec["centers"][None, :, :]
            in_wheel = (
                (np.abs(rel[..., 1]) <= WHEEL_HALF_WIDTH)
                & (np.hypot(rel[..., 0], rel[..., 2]) <= spec["radii"][None, :] + WHEEL_CLEARANCE)
            ).any(axis=1)
            keep = (area > 0.0) & ~in_wheel
            lo, hi = verts.min(0), verts.max(0)
            footprint = max(float((hi[0] - lo[0]) * (hi[1] - lo[1])), 1e-6)
            pts = hv[keep]
            self.bodies.append(
                {
                    "mass": float(v.mass),
                    "inertia": inertia,
                    "inv": tuple(float(a) for a in np.linalg.inv(inertia).ravel()),
                    "wheels": wheels,
                    "bars": bars,
                    "reach": float(reach.max()),
                    "suspension_rate": suspension_rate,
                    "hull": pts,
                    "hull_lo": tuple(float(a) for a in pts.min(0)),
                    "hull_hi": tuple(float(a) for a in pts.max(0)),
                    "stiffness": v.mass * omega * omega / footprint * area[keep],
                    "damping": 2.0 * BODY_CONTACT_DAMPING * v.mass * omega / footprint * area[keep],
                }
            )

    def rates(self, b: int, s: list[float], lk: bool) -> list[float]:
        """d/dt of vehicle b's state ``s`` (``STRIDE`` floats); ``lk``: every wheel locked."""
        mu, sigma, g = self.mu, self.sigma, self.g
        u_sat = mu * sigma / self.cornering  # the tread's deflection at the friction limit
        k_per_load = self.cornering / sigma  # tread stiffness per unit load C / (sigma Fz)
        rolling = self.rolling
        out: list[float] = []
        body = self.bodies[b]
        x0, x1, x2, qw, qx, qy, qz, v0, v1, v2, lx, ly, lz = s[:13]
        r = _rotation(qw, qx, qy, qz)
        r00, r01, r02, r10, r11, r12, r20, r21, r22 = r
        wx, wy, wz = _world_inverse(r, body["inv"], lx, ly, lz)
        # wheel axes in the ground plane: the body x axis (no steering), flattened
        hn = math.hypot(r00, r10)
        exx, exy = r00 / hn, r10 / hn
        pz = -x2  # the contact patch is on z = 0
        fx_t = fy_t = fz_t = tx = ty = tz = 0.0
        du: list[float] = []
        # the anti-roll bars' loads: each travel R - h, held at the spring's droop
        bar = [0.0] * len(body["wheels"])
        for left, right, k_bar in body["bars"]:
            travel = []
            for cx, cy, cz, radius, f0, rate, _ in (body["wheels"][left], body["wheels"][right]):
                h = x2 + r20 * cx + r21 * cy + r22 * cz
                travel.append(max(radius - h, -f0 / rate))
            f = k_bar * (travel[0] - travel[1])
            bar[left] += f
            bar[right] -= f
        for k, (cx, cy, cz, radius, f0, rate, cdamp) in enumerate(body["wheels"]):
            rcx = r00 * cx + r01 * cy + r02 * cz
            rcy = r10 * cx + r11 * cy + r12 * cz
            rcz = r20 * cx + r21 * cy + r22 * cz
            # the spring-damper: compression R - h, compression rate -(centre velocity).z
            fz = f0 + rate * (radius - x2 - rcz) - cdamp * (v2 + wx * rcy - wy * rcx) + bar[k]
            u0, u1 = s[13 + 2 * k], s[14 + 2 * k]
            if fz <= 0.0:  # off the ground: no force, the tread springs back
                du += (-u0 / AIRBORNE_RELAXATION, -u1 / AIRBORNE_RELAXATION)
                continue
            vpx = v0 + wy * pz - wz * rcy
            vpy = v1 + wz * rcx - wx * pz
            vx = vpx * exx + vpy * exy
            vy = vpy * exx - vpx * exy
            kt = k_per_load * fz
            relax = abs(vx) / sigma
            # critical damping of the wheel's share of the mass, less the rolling's renewal
            share = fz / g
            damp = max(2.0 * math.sqrt(kt * share) - share * relax, 0.0)
            friction = mu * fz
            el1 = -vy - relax * u1
            if lk:
                # both ways dragged by the slip, the resultant at most mu Fz; at the
                # limit the tread slides (its deflection held at u_sat)
                el0 = -vx - relax * u0
                fx, fy = kt * u0 + damp * el0, kt * u1 + damp * el1
                f_lin = math.hypot(fx, fy)
                if f_lin >= friction:
                    fx, fy = fx * friction / f_lin, fy * friction / f_lin
                un = math.hypot(u0, u1)
                if un >= u_sat and un > 0.0:
                    d0, d1 = u0 / un, u1 / un
                    radial = el0 * d0 + el1 * d1
                    cut = radial - (min(radial, 0.0) - (un - u_sat) / YIELD_RELAXATION)
                    el0, el1 = el0 - cut * d0, el1 - cut * d1
            else:
                # rolling free: no x deflection, rolling resistance along x, the lateral
                # force at most what the friction leaves (braking priority)
                el0 = -u0 / AIRBORNE_RELAXATION
                fx = -rolling * fz * vx / max(abs(vx), ROLLING_RESISTANCE_SPEED)
                if abs(fx) >= friction:
                    fx = math.copysign(friction, fx)
                available = math.sqrt(max(friction * friction - fx * fx, 0.0))
                fy_lin = kt * u1 + damp * el1
                fy = math.copysign(min(abs(fy_lin), available), fy_lin)
                if kt * abs(u1) >= available and u1 * el1 >= 0.0:
                    el1 = -(u1 - math.copysign(available / kt, u1)) / YIELD_RELAXATION
            du += (el0, el1)
            fwx = fx * exx - fy * exy
            fwy = fx * exy + fy * exx
            fx_t += fwx
            fy_t += fwy
            fz_t += fz
            tx += rcy * fz - pz * fwy
            ty += pz * fwx - rcx * fz
            tz += rcx * fwy - rcy * fwx
        # the body's hull: the lowest corner of its points' box first
        lo, hi = body["hull_lo"], body["hull_hi"]
        lowest = (
            min(r20 * lo[0], r20 * hi[0])
            + min(r21 * lo[1], r21 * hi[1])
            + min(r22 * lo[2], r22 * hi[2])
        )
        if x2 + lowest <= 0.0:
            f, t = self._body_contact(body, r, (x0, x1, x2), (v0, v1, v2), (wx, wy, wz))
            fx_t, fy_t, fz_t = fx_t + f[0], fy_t + f[1], fz_t + f[2]
            tx, ty, tz = tx + t[0], ty + t[1], tz + t[2]
        m = body["mass"]
        out += (
            v0,
            v1,
            v2,
            0.5 * (-wx * qx - wy * qy - wz * qz),
            0.5 * (qw * wx + wy * qz - wz * qy),
            0.5 * (qw * wy + wz * qx - wx * qz),
            0.5 * (qw * wz + wx * qy - wy * qx),
            fx_t / m,
            fy_t / m,
            fz_t / m - g,
            tx,
            ty,
            tz,
        )
        out += du
        return out

    def _body_contact(
        self,
        body: dict[str, Any],
        r: tuple[float, ...],
        x: tuple[float, float, float],
        v: tuple[float, float, float],
        w: tuple[float, float, float],
    ) -> tuple[np.ndarray, np.ndarray]:
        """Force and torque (about the CG) of the ground on the hull points below z = 0."""
        p = body["hull"] @ np.asarray(r).reshape(3, 3).T
        depth = -(x[2] + p[:, 2])
        touch = depth > 0.0
        if not touch.any():
            return np.zeros(3), np.zeros(3)
        p, depth = p[touch], depth[touch]
        vp = np.asarray(v) + np.cross(np.asarray(w), p)
        fn = np.maximum(body["stiffness"][touch] * depth - body["damping"][touch] * vp[:, 2], 0.0)
        scale = self.body_mu * fn / np.maximum(np.hypot(vp[:, 0], vp[:, 1]), BODY_SLIP_SPEED)
        f = np.column_stack([-vp[:, 0] * scale, -vp[:, 1] * scale, fn])
        return f.sum(0), np.cross(p, f).sum(0)

    def angular_velocities(self, s: list[float]) -> list[tuple[float, float, float]]:
        out = []
        for b, body in enumerate(self.bodies):
            o = b * STRIDE
            r = _rotation(*s[o + 3 : o + 7])
            out.append(_world_inverse(r, body["inv"], *s[o + 10 : o + 13]))
        return out

    def advance(self, s: list[float], dt: float, locked: list[bool]) -> list[float]:
        """The state after dt s: each vehicle by RK4 in its own n equal sub-steps, as the
        engine's: at most 1 ms, 0.02 rad, a tread renewal of 1 (from twice the fastest patch
        speed) and 2 / the suspension's fastest rate each."""
        out: list[float] = []
        for b, (wx, wy, wz) in enumerate(self.angular_velocities(s)):
            body = self.bodies[b]
            sb = s[b * STRIDE : (b + 1) * STRIDE]
            w = math.sqrt(wx * wx + wy * wy + wz * wz)
            patch_speed = 2.0 * (
                math.sqrt(sb[7] ** 2 + sb[8] ** 2 + sb[9] ** 2) + w * body["reach"]
            )
            n = max(
                1,
                math.ceil(dt / MAX_SUBSTEP),
                math.ceil(w * dt / MAX_SUBSTEP_ANGLE),
                math.ceil(dt * patch_speed / self.sigma / MAX_SUBSTEP_RELAXATION),
                math.ceil(dt * body["suspension_rate"] / MAX_SUBSTEP_SUSPENSION),
            )
            h = dt / n
            h2, h6 = 0.5 * h, h / 6.0
            lk = locked[b]
            for _ in range(n):
                k1 = self.rates(b, sb, lk)
                k2 = self.rates(b, [a + h2 * d for a, d in zip(sb, k1, strict=True)], lk)
                k3 = self.rates(b, [a + h2 * d for a, d in zip(sb, k2, strict=True)], lk)
                k4 = self.rates(b, [a + h * d for a, d in zip(sb, k3, strict=True)], lk)
                sb = [
                    a + h6 * (d1 + 2.0 * (d2 + d3) + d4)
                    for a, d1, d2, d3, d4 in zip(sb, k1, k2, k3, k4, strict=True)
                ]
                qw, qx, qy, qz = sb[3:7]
                nq = math.sqrt(qw * qw + qx * qx + qy * qy + qz * qz)
                sb[3:7] = [qw / nq, qx / nq, qy / nq, qz / nq]
            out += sb
        return out

    def pose(self, s: list[float], b: int) -> tuple[np.ndarray, np.ndarray]:
        """Vehicle b's rotation matrix (body -> world) and CG position."""
        o = b * STRIDE
        return np.array(_rotation(*s[o + 3 : o + 7])).reshape(3, 3), np.array(s[o : o + 3])

    def state_of(self, positions, orientations, velocities, angular_velocities) -> list[float]:
        """The flat state from per-vehicle arrays (treads undeflected)."""
        s: list[float] = []
        for b, body in enumerate(self.bodies):
            q = np.asarray(orientations[b], dtype=np.float64)
            r = np.array(_rotation(*q)).reshape(3, 3)
            ang = r @ body["inertia"] @ r.T @ np.asarray(angular_velocities[b], dtype=np.float64)
            s += [float(a) for a in positions[b]] + [float(a) for a in q]
            s += [float(a) for a in velocities[b]] + [float(a) for a in ang]
            s += [0.0] * (2 * len(body["wheels"]))
        return s

    def apply(self, s: list[float], delta_v: np.ndarray, delta_omega: np.ndarray) -> list[float]:
        """The state after an exchange that changes the velocities by delta_v (B, 3) and the
        angular velocities by delta_omega (B, 3): l += R I R^T delta_omega."""
        s = list(s)
        for b, body in enumerate(self.bodies):
            o = b * STRIDE
            r, _ = self.pose(s, b)
            dl = r @ body["inertia"] @ r.T @ delta_omega[b]
            for j in range(3):
                s[o + 7 + j] += float(delta_v[b][j])
                s[o + 10 + j] += float(dl[j])
        return s


@dataclass
class PeerExchange:
    """What the peer applies at its n-th exchange: the engine's velocity changes (the peer
    does not solve the impulse; see ``python_fcl_runout``)."""

    delta_v: np.ndarray  # (B, 3) m/s
    delta_omega: np.ndarray  # (B, 3) rad/s


def peer_start(model: PeerVehicles, result: Any, names: list[str]) -> list[float]:
    """The peer's state at t = 0: the scene's initial states (as the scene placed them on the
    ground), treads undeflected."""
    states = [result.state(n, 0.0) for n in names]
    return model.state_of(
        [s["position"] for s in states],
        [s["orientation"] for s in states],
        [s["velocity"] for s in states],
        [s["angular_velocity"] for s in states],
    )


def python_fcl_runout(
    model: PeerVehicles,
    body: Body,
    start: list[float],
    exchanges: list[PeerExchange],
    dtp_steps: int,
) -> dict[str, Any]:
    """The scene run to rest as a user would write it in Python: per 1 ms step, both vehicles
    advanced by ``model``, posed in FCL and tested with ``collide``; the first colliding step
    after being apart starts a timer of ``dtp_steps`` steps, at whose end the two posed meshes
    are intersected with the manifold boolean (volume and centroid), the exchange's velocity
    changes are applied (the engine's n-th exchange: the peer does not solve the impulse) and
    every wheel locks; the pair is then engaged until a step without a collision (a
    separation). The engine's rest criterion ends the run."""
    import fcl
    import trimesh

    t_begin = time.perf_counter()
    nb = len(model.bodies)
    objects = [fcl.CollisionObject(body.fcl_model, fcl.Transform()) for _ in range(nb)]
    request = fcl.CollisionRequest(num_max_contacts=1, enable_contact=False)
    s = list(start)
    locked = [False] * nb
    phase, exchange_step, n_exchanges = "apart", -1, 0
    events: list[tuple[str, float]] = []
    exchange_info: list[dict[str, Any]] = []
    slow_since: list[float | None] = [None] * nb
    settled_since: list[float | None] = [None] * nb
    stopped_at: list[float | None] = [None] * nb
    wall_separation = None
    n_max = round(RUNOUT_MAX_DURATION / DT)
    moving_speed = MOVING_SPEED_FACTOR * model.rest_speed
    moving_yaw = MOVING_SPEED_FACTOR * model.rest_yaw
    k = 0
    while k < n_max:
        s = model.advance(s, DT, locked)
        k += 1
        t = k * DT
        poses = [model.pose(s, b) for b in range(nb)]
        for obj, (r, x) in zip(objects, poses, strict=True):
            obj.setTransform(fcl.Transform(r, x))
        hit = fcl.collide(objects[0], objects[1], request) > 0
        if phase == "apart" and hit:
            phase, exchange_step = "timer", k + dtp_steps
            events.append(("first contact", t))
        elif phase == "timer" and k == exchange_step:
            meshes = [
                trimesh.Trimesh(body.vertices @ r.T + x, body.faces, process=False)
                for r, x in poses
            ]
            inter = trimesh.boolean.intersection(meshes, engine="manifold")
            exchange_info.append({"t": t, "volume": inter.volume, "centroid": inter.center_mass})
            if n_exchanges < len(exchanges):
                ex = exchanges[n_exchanges]
                s = model.apply(s, ex.delta_v, ex.delta_omega)
            n_exchanges += 1
            locked = [True] * nb
            phase = "engaged"
            events.append(("exchange", t))
        elif phase == "engaged" and not hit:
            phase = "apart"
            events.append(("separation", t))
            if wall_separation is None:
                wall_separation = time.perf_counter() - t_begin
        # rest: the engine's criterion (travel and yaw slow for rest_time; the time reported
        # is the first slow instant since the vehicle last moved; the run stops once every
        # vehicle has also been settled for rest_time: every velocity component below
        # SETTLED_SPEED, every angular one below SETTLED_ANGULAR_SPEED; the cars never leave
        # the plane here, so "on the ground" always holds)
        done = True
        for b, (wx, wy, wz) in enumerate(model.angular_velocities(s)):
            o = b * STRIDE
            v0, v1, v2 = s[o + 7 : o + 10]
            speed = math.hypot(v0, v1)
            slow = speed < model.rest_speed and abs(wz) < model.rest_yaw
            if not slow:
                slow_since[b] = None
            elif slow_since[b] is None:
                slow_since[b] = t
            if speed > moving_speed or abs(v2) > moving_speed or abs(wz) > moving_yaw:
                stopped_at[b] = None
            elif slow and stopped_at[b] is None:
                stopped_at[b] = t
            settled = (
                slow
                and math.sqrt(v0 * v0 + v1 * v1 + v2 * v2) < SETTLED_SPEED
                and math.sqrt(wx * wx + wy * wy + wz * wz) < SETTLED_ANGULAR_SPEED
            )
            if not settled:
                settled_since[b] = None
            elif settled_since[b] is None:
                settled_since[b] = t
            since, calm = slow_since[b], settled_since[b]
            done = done and (
                since is not None
                and t - since >= model.rest_time - 1e-12
                and calm is not None
                and t - calm >= model.rest_time - 1e-12
            )
        if done:
            break
    wall = time.perf_counter() - t_begin
    # at rest: the time as the engine reports it, the pose at the end of the run (as
    # crashsim.Result.rest gives it)
    rests: list[dict[str, Any] | None] = []
    for b in range(nb):
        if slow_since[b] is None:
            rests.append(None)
            continue
        r, x = model.pose(s, b)
        rests.append(
            {
                "time": stopped_at[b] if stopped_at[b] is not None else slow_since[b],
                "position": x,
                "heading": math.atan2(r[1, 0], r[0, 0]),
            }
        )
    return {
        "end": k * DT,
        "events": events,
        "exchanges": exchange_info,
        "exchanges_applied": min(n_exchanges, len(exchanges)),
        "exchanges_found": n_exchanges,
        "rest": rests,
        "wall": wall,
        "wall_impact": wall_separation if wall_separation is not None else wall,
    }


def engine_exchanges(result: Any, names: list[str]) -> list[PeerExchange]:
    """The engine's exchanges as the velocity changes of every vehicle."""
    out = []
    for imp in result.impacts:
        dv = np.zeros((len(names), 3))
        dw = np.zeros((len(names), 3))
        for i, n in enumerate(names):
            if n in imp.delta_v:
                dv[i] = imp.delta_v[n]
                dw[i] = imp.delta_omega[n]
        out.append(PeerExchange(dv, dw))
    return out


def check_peer(body: Body) -> list[str]:
    """The peer's vehicle motion against the engine's for one sedan on the ground: spinning
    at 2.5 rad/s while sliding on wheels locked from t = 0, and rolling free, each run to
    rest; the largest distance between the two CG positions every 0.1 s."""
    import crashsim as cs

    red = make_runout_scene(body).vehicles[0]
    lines = []
    for label, states in (
        ("locked from 0 s", [(w, "locked", 0.0) for w in red.wheels]),
        ("free", []),
    ):
        scene = cs.Scene(ground=cs.Ground())
        scene.add(
            red,
            (0.0, 0.0),
            heading=0.3,
            velocity=(8.0, 2.0, 0.0),
            angular_velocity=(0.0, 0.0, 2.5),
            inputs=cs.DriverInputs(wheel_states=states),
        )
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            result = scene.run(dt=DT, until="rest", max_duration=RUNOUT_MAX_DURATION)
        model = PeerVehicles([red])
        s = peer_start(model, result, ["red"])
        locked = [bool(states)]
        worst = 0.0
        n = round(float(result.t[-1]) / DT)
        for k in range(1, n + 1):
            s = model.advance(s, DT, locked)
            if k % 100 == 0 or k == n:
                ref = result.state("red", k * DT)["position"]
                worst = max(worst, float(np.linalg.norm(np.array(s[0:3]) - ref)))
        lines.append(
            f"peer check, one sedan {label}, {n * DT:.3f} s to rest: CG positions apart by "
            f"at most {worst * 1e6:.1f} um (every 0.1 s)"
        )
    return lines


def runout_phases(setup: RunoutSetup, result: Any) -> list[tuple[str, float, float, float]]:
    """The engine's wall time per phase of the run to rest: one fresh world run in pieces cut
    at the step boundaries around each first overlap, exchange and separation of ``result``,
    the last piece until rest. Returns (phase, start s, end s, wall s)."""
    events = sorted(
        [(c.time, c.kind.replace("_", " ")) for c in result.contacts]
        + [(imp.time, "exchange") for imp in result.impacts]
    )
    after = {
        "first overlap": "timer (depth of penetration)",
        "no exchange": "resting contact (no exchange)",
        "exchange": "engaged (overlap, not closing)",
        "separation": "apart",
    }
    marks = []
    phase = "approach"
    for te, kind in events:
        k0 = math.floor(te / DT + 1e-9) * DT
        marks += [(phase, k0), (f"step with the {kind}", k0 + DT)]
        phase = after.get(kind, phase)
    world = setup.scene.build_world()
    out = []
    start = 0.0
    for name, end in marks:
        if end - start > 1e-9:
            t0 = time.perf_counter()
            world.run(round(end - start, 12), DT)
            out.append((name, start, end, time.perf_counter() - t0))
            start = end
    t0 = time.perf_counter()
    last = world.run(round(RUNOUT_MAX_DURATION - start, 12), DT, until_rest=True)
    out.append((f"{phase}, to rest", start, float(last["t"][-1]), time.perf_counter() - t0))
    return out


def run_runout(setup: RunoutSetup, repeats: int) -> tuple[Row, Any, dict[str, Any]]:
    """The engine's run to rest against the Python + fcl loop, interleaved (one run per
    batch), and the engine's phase split (median over the repeats)."""
    names = [v.name for v in setup.vehicles]
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        result = setup.scene.run(dt=DT, until="rest", max_duration=RUNOUT_MAX_DURATION)
    model = PeerVehicles(setup.vehicles)
    start = peer_start(model, result, names)
    exchanges = engine_exchanges(result, names)
    dtp_steps = round(DTP / DT)

    def engine() -> Any:
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            return setup.scene.run(dt=DT, until="rest", max_duration=RUNOUT_MAX_DURATION)

    peer = functools.partial(python_fcl_runout, model, setup.body, start, exchanges, dtp_steps)
    check = peer()
    t = compare(engine, peer, repeats, 0.0)
    splits = [runout_phases(setup, result) for _ in range(repeats)]
    peer_runs = [peer() for _ in range(max(1, repeats // 2))] + [check]
    info: dict[str, Any] = {"check": check, "names": names}
    # the phases' medians; the impact phase ends with the step of the first separation
    phases = [
        (name, a, b, statistics.median(s[k][3] for s in splits))
        for k, (name, a, b, _) in enumerate(splits[0])
    ]
    info["phases"] = phases
    sep = next((k for k, p in enumerate(phases) if p[0] == "step with the separation"), None)
    if sep is not None:
        info["split"] = phases[sep][2]
        info["engine_impact"] = sum(p[3] for p in phases[: sep + 1])
        info["engine_runout"] = sum(p[3] for p in phases[sep + 1 :])
    info["peer_split"] = next((t for k, t in check["events"] if k == "separation"), None)
    info["peer_impact"] = statistics.median(p["wall_impact"] for p in peer_runs)
    info["peer_runout"] = statistics.median(p["wall"] - p["wall_impact"] for p in peer_runs)
    return Row(setup.body.label, "to rest @ 1 ms", setup.body.n_triangles, t), result, info


def runout_lines(setup: RunoutSetup, result: Any, info: dict[str, Any]) -> list[str]:
    """The cross-check of the two runs and the time split, as printed lines."""
    check = info["check"]
    names = info["names"]
    ev = [f"{c.kind.replace('_', ' ')} {c.time:.4f}" for c in result.contacts]
    ex = [f"{imp.time:.4f}" for imp in result.impacts]
    end = float(result.t[-1])
    lines = [
        f"engine: {', '.join(ev)} s; exchanges at {', '.join(ex)} s; run ends {end:.3f} s",
        "python+fcl: "
        + ", ".join(f"{k} {t:.3f}" for k, t in check["events"])
        + f" s (steps); {check['exchanges_found']} exchange(s), "
        f"{check['exchanges_applied']} with the engine's velocity changes; run ends "
        f"{check['end']:.3f} s",
    ]
    for e in check["exchanges"]:
        lines.append(
            f"python+fcl boolean at {e['t']:.3f} s: {e['volume'] * 1e3:.3g} L, centroid "
            f"{_vec(e['centroid'])} m"
        )
    for i, n in enumerate(names):
        rs = result.rest(n)
        rp = check["rest"][i]
        if rs is None or rp is None:
            lines.append(f"{n}: rest engine {rs}, python+fcl {rp}")
            continue
        gap = float(np.hypot(*(np.asarray(rs.position[:2]) - rp["position"][:2])))
        dh = math.degrees((rs.heading - rp["heading"] + math.pi) % (2 * math.pi) - math.pi)
        lines.append(
            f"{n}: rest engine {rs.time:.3f} s at {_vec(rs.position[:2])} m heading "
            f"{math.degrees(rs.heading):.2f} deg; python+fcl {rp['time']:.3f} s at "
            f"{_vec(rp['position'][:2])} m heading {math.degrees(rp['heading']):.2f} deg "
            f"({gap * 1e3:.1f} mm, {dh:+.2f} deg apart)"
        )
    lines.append("engine wall time by phase (one run cut at step boundaries; median):")
    for name, t_a, t_b, wall in info["phases"]:
        lines.append(f"  {t_a:6.3f}-{t_b:6.3f} s  {name:<34} {_fmt_time(wall)}")
    if "engine_impact" in info:
        lines.append(
            f"impact phase (to the step with the first separation, {info['split']:.3f} s) and "
            f"run-out, median: engine {_fmt_time(info['engine_impact']).strip()} + "
            f"{_fmt_time(info['engine_runout']).strip()}; python+fcl (split at its own first "
            f"separation, {info['peer_split'] or float('nan'):.3f} s) "
            f"{_fmt_time(info['peer_impact']).strip()} + {_fmt_time(info['peer_runout']).strip()}"
        )
    return lines


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

        out: dict[str, Any] = {**worker_environment(pycrash, pd, np), "runs": []}
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
    if pycrash_imports():
        return pycrash_worker(spec), "this process", ""
    try:
        out, where = run_worker(__file__, spec, python)
    except RuntimeError as e:
        return None, python or DEFAULT_PYCRASH_PYTHON, str(e)
    return out, where, ""


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


def _print_rows(
    title: str,
    rows: list[Row],
    peer: str,
    target: float,
    of_case: Callable[[str], float] | None = None,
) -> None:
    """The rows with their verdicts against ``target``, or per case ``of_case(case)``."""
    print(title)
    head = f"  {'size':>5} {'triangles':>9}  {'case':<11} {'engine':>11}  {peer:>11}"
    if of_case is None:
        goal = f"target <= {target:g}"
    else:
        cases = dict.fromkeys(r.case for r in rows)
        goal = "targets: " + ", ".join(f"{c} <= {of_case(c):g}" for c in cases)
    print(head + f"  {'ratio [range]':<22} {goal}")
    for r in rows:
        t = r.timing
        limit = of_case(r.case) if of_case else target
        print(
            f"  {r.size:>5} {r.triangles:>9,}  {r.case:<11} {_fmt_time(t.engine_median)}  "
            f"{_fmt_time(t.peer_median)}  {_fmt_ratio(t):<22} {_verdict(t.ratio, limit):<6}"
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
        default="query,region,scene,runout,pycrash",
        help="comma-separated comparisons: query, region, scene, runout, pycrash",
    )
    ap.add_argument("--repeats", type=int, help="repeats per figure (default 7; quick 3)")
    ap.add_argument("--pycrash-python", help=f"interpreter with pycrash ({DEFAULT_PYCRASH_PYTHON})")
    ap.add_argument("--pycrash-repeats", type=int, help="pycrash runs per dt (default 3; quick 1)")
    ap.add_argument("--engine-loop", help="profile helper: query-<case>, region-<case> or scene")
    ap.add_argument("--seconds", type=float, default=10.0, help="duration of --engine-loop (s)")
    ap.add_argument(
        "--check-peer",
        action="store_true",
        help="5.: also check the Python peer's vehicle motion against the engine's (one car)",
    )
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
    unknown = only - {"query", "region", "scene", "runout", "pycrash"}
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

    # the sizes are for 1. and 2.; 3. to 5. use the 20k scene only
    sizes_built = sizes if only & {"query", "region"} else [SCENE_SIZE]
    bodies = {s: make_body(s) for s in sizes_built}
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
            _query_target,
        )
        print(
            '  note: FCL detects surface crossings only; shapes_overlap also answers "one '
            'inside the other" (a winding number per shell when no surfaces cross)'
        )
        print()
        summary += [(f"query {r.size} {r.case}", r.timing.ratio, _query_target(r.case))
                    for r in rows]  # fmt: skip
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
    if "runout" in only:
        body = bodies.get(SCENE_SIZE) or make_body(SCENE_SIZE)
        bodies.setdefault(SCENE_SIZE, body)
        run_setup = make_runout_scene(body)
        row, run_result, info = run_runout(run_setup, scene_repeats)
        _print_rows(
            '5. whole event, run to rest: Scene.run(until="rest") on a ground vs Python '
            "vehicle motion (the engine's wheels, tyres and ground, re-written) + python-fcl "
            "per step + manifold boolean at each exchange (the seed's scene, "
            f"{body.n_triangles:,} triangles each, every wheel locked at the exchange)",
            [row],
            "python",
            TARGETS["runout"],
        )
        for line in runout_lines(run_setup, run_result, info):
            print(f"    {line}")
        if args.check_peer:
            for line in check_peer(body):
                print(f"    {line}")
        print()
        summary.append((f"runout {SCENE_SIZE}", row.timing.ratio, TARGETS["runout"]))
    load = os.getloadavg()
    print(f"load average at end {load[0]:.2f} / {load[1]:.2f} / {load[2]:.2f}")
    print("summary (ratio = engine / peer, median):")
    for name, ratio, target in summary:
        print(f"  {name:<22} {ratio:9.4f}  target <= {target:g}: {_verdict(ratio, target)}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
