"""3-D export of a run as glTF 2.0 binary (.glb) files that any glTF viewer opens.

``export_glb`` writes one file holding each vehicle's mesh, a ground plane and the motion as a
glTF animation; ``export_frames`` writes one static file per time, for viewers that do not
play animations.

Frames and units. crashsim's world is z up; glTF's is y up. Everything is written in
crashsim's world frame (m) under one root node whose rotation (-90 deg about x) turns z up
into glTF's y up (world x stays glTF x, world y becomes glTF -z). Each vehicle's mesh is its
body-frame mesh (model vertices minus the CG), so a vehicle node's translation is the CG in
the world and its rotation is the body -> world rotation. The ground is a checkerboard of
square tiles at z = GROUND_Z (just below z = 0, so that the bottoms of meshes standing on
z = 0 do not flicker against it).

A run on a ground (``Result.on_ground``) writes that ground instead: the plane z = h as the
checkerboard (GROUND_Z below it) with each friction zone as a tinted polygon just above it
(ZONE_Z), or the terrain mesh itself (its triangles, world frame; zones are not draped on a
terrain). Fixed obstacles are nodes with their meshes (their own frame) at their places.
Vehicles with wheels get one node per wheel, a cylinder of the tyre's radius (axis along the
body y): on the ground its centre follows ``Result.wheel_centres`` (the tyre on the ground,
so the suspension's travel shows) and it turns with the body and the steering
(``Result.wheel_steer``); without wheel records (no ground) the wheels are children of the
vehicle's node at their static body-frame centres. The wheels do not spin (a plain
cylinder looks the same turned).

Animation: one animation "motion" with, per vehicle, a translation and a rotation sampler,
LINEAR, quaternions in glTF's (x, y, z, w) order (crashsim's are (w, x, y, z)), times in s
from the start of the run. Keys are at ``fps`` frames per second plus every impact's first
contact and exchange instant (the velocity jumps there, so the pose between keys is exact at
the impacts and linear in between); keys inside a stretch where nothing moves are left out
(a vehicle at rest costs two keys), and a run longer than MAX_KEYS frames is keyed at a lower
rate, with a warning. The poses are taken at all keys at once (``Result.states``), so the
export's time grows with the keys and the run's samples, not their product. glTF stores
float32: positions are rounded by at most 0.5 um within 16 m of the origin (relative 6e-8),
times by a relative 6e-8.

The files are written with numpy, struct and json only (no glTF library): the format is
small, and writing it here keeps the accessor bounds and alignment under our control.
"""

from __future__ import annotations

import json
import math
import struct
import warnings
from pathlib import Path
from typing import TYPE_CHECKING, Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

from crashsim._core import __version__
from crashsim.errors import ParameterError, SceneError
from crashsim.plots import VEHICLE_COLOURS, ZONE_COLOURS
from crashsim.records import rotation_matrix

if TYPE_CHECKING:
    from crashsim.result import Result

__all__ = [
    "GROUND_Z",
    "ZONE_Z",
    "Z_UP_TO_Y_UP",
    "export_frames",
    "export_glb",
    "key_times",
    "wheel_node_name",
]

Array = NDArray[np.float64]

# The root node's rotation, glTF (x, y, z, w): -90 deg about x, world z -> glTF y.
Z_UP_TO_Y_UP = (-math.sqrt(0.5), 0.0, 0.0, math.sqrt(0.5))
GROUND_Z = -0.005  # m: the checkerboard's height in the world (below the ground's plane)
ZONE_Z = -0.002  # m: friction zones, relative to the ground's plane (above the checkerboard)
WHEEL_WIDTH = 0.65  # a drawn wheel's width per tyre radius (a 205/55 R16 tyre: 0.66)
WHEEL_SECTIONS = 24  # sides of a drawn wheel's cylinder
WHEEL_COLOUR = "#2b2b2b"
OBSTACLE_COLOUR = "#8c8c8c"
GROUND_MARGIN = 3.0  # m of ground beyond the vehicles' reach on every side
MAX_TILES = 60  # per side of the ground: the tile grows (1, 2, 5, 10 ... m) to keep under it
MIN_KEY_GAP = 1e-4  # s: a frame closer than this to an impact instant is dropped for it
# Keys of the animation at most: a frame rate that would give more is lowered to fit (55 min
# of run at 30 fps); the file and the memory taken to write it grow with the keys (7 floats
# per animated node and key).
MAX_KEYS = 100_000
# A node whose translation changes less than this (m) and whose rotation's components change
# less than STILL_ROTATION between neighbouring keys is still there; keys inside a stretch
# where every node is still are left out (linear interpolation redraws them) until the
# change summed since the stretch began passes STILL_DRIFT times the tolerance.
STILL_TRANSLATION = 1e-4
STILL_ROTATION = 1e-5  # about 2e-5 rad
STILL_DRIFT = 10.0

_GLB_MAGIC = 0x46546C67  # "glTF"
_CHUNK_JSON = 0x4E4F534A  # "JSON"
_CHUNK_BIN = 0x004E4942  # "BIN\0"
_FLOAT = 5126
_UINT = 5125
_ARRAY_BUFFER = 34962
_ELEMENT_ARRAY_BUFFER = 34963
_TRIANGLES = 4
_TYPES = {1: "SCALAR", 3: "VEC3", 4: "VEC4"}

_GROUND_COLOURS = ((0.62, 0.62, 0.60), (0.50, 0.50, 0.48))  # linear RGB, two tiles
_TERRAIN_COLOUR = (0.55, 0.52, 0.44)  # linear RGB


def wheel_node_name(vehicle: str, wheel: str) -> str:
    """The name of a wheel's node: "<vehicle> wheel <wheel>"."""
    return f"{vehicle} wheel {wheel}"


def _linear_rgba(hex_colour: str, alpha: float = 1.0) -> list[float]:
    """glTF's baseColorFactor (linear RGB) of an sRGB hex colour."""
    srgb = np.array([int(hex_colour[i : i + 2], 16) / 255.0 for i in (1, 3, 5)])
    lin = np.where(srgb <= 0.04045, srgb / 12.92, ((srgb + 0.055) / 1.055) ** 2.4)
    return [*(round(float(c), 6) for c in lin), alpha]


def _gltf_quaternion(q_wxyz: ArrayLike) -> Array:
    """crashsim's (w, x, y, z) as glTF's (x, y, z, w), normalised; (..., 4) row by row."""
    q = np.asarray(q_wxyz, dtype=np.float64)
    q = q / np.linalg.norm(q, axis=-1, keepdims=True)
    return q[..., [1, 2, 3, 0]]


class _Gltf:
    """A glTF 2.0 document being built: JSON objects plus one binary buffer."""

    def __init__(self) -> None:
        self.bin = bytearray()
        self.doc: dict[str, Any] = {
            "asset": {"version": "2.0", "generator": f"crashsim {__version__}"},
            "scene": 0,
            "scenes": [{"name": "crashsim", "nodes": [0]}],
            "nodes": [
                {
                    "name": "world (crashsim z-up, turned to glTF y-up)",
                    "rotation": list(Z_UP_TO_Y_UP),
                    "children": [],
                }
            ],
            "meshes": [],
            "materials": [],
            "accessors": [],
            "bufferViews": [],
            "buffers": [],
        }

    def accessor(self, data: ArrayLike, *, target: int | None = None) -> int:
        """Appends data (float -> float32, int -> uint32; rows are elements) as a buffer view
        and an accessor with min and max (of the stored values); returns the accessor."""
        a = np.asarray(data)
        if a.dtype.kind == "f":
            stored, ctype = np.ascontiguousarray(a, dtype="<f4"), _FLOAT
        else:
            stored, ctype = np.ascontiguousarray(a, dtype="<u4"), _UINT
        if stored.ndim == 1:
            width = 1
        else:
            width = stored.shape[1]
        if width not in _TYPES or stored.size == 0:
            raise ValueError(f"cannot store an array of shape {a.shape}")  # internal misuse
        while len(self.bin) % 4:
            self.bin.append(0)
        view: dict[str, Any] = {
            "buffer": 0,
            "byteOffset": len(self.bin),
            "byteLength": stored.nbytes,
        }
        if target is not None:
            view["target"] = target
        self.bin.extend(stored.tobytes())
        self.doc["bufferViews"].append(view)
        rows = stored.reshape(-1, width)
        cast = float if ctype == _FLOAT else int
        self.doc["accessors"].append(
            {
                "bufferView": len(self.doc["bufferViews"]) - 1,
                "componentType": ctype,
                "count": int(rows.shape[0]),
                "type": _TYPES[width],
                "min": [cast(v) for v in rows.min(axis=0)],
                "max": [cast(v) for v in rows.max(axis=0)],
            }
        )
        return len(self.doc["accessors"]) - 1

    def material(self, name: str, rgba: list[float], roughness: float = 0.7) -> int:
        self.doc["materials"].append(
            {
                "name": name,
                "pbrMetallicRoughness": {
                    "baseColorFactor": rgba,
                    "metallicFactor": 0.0,
                    "roughnessFactor": roughness,
                },
                # vehicle meshes are often open or inconsistently wound: show both sides
                "doubleSided": True,
            }
        )
        return len(self.doc["materials"]) - 1

    def mesh(self, name: str, parts: list[tuple[Array, NDArray[np.int64], int]]) -> int:
        """A mesh of triangle primitives, each (vertices (n, 3) m, faces (m, 3), material).
        No normals: glTF viewers then shade flat, which suits low-poly vehicles."""
        primitives = []
        for vertices, faces, material in parts:
            primitives.append(
                {
                    "attributes": {"POSITION": self.accessor(vertices, target=_ARRAY_BUFFER)},
                    "indices": self.accessor(
                        np.asarray(faces).reshape(-1), target=_ELEMENT_ARRAY_BUFFER
                    ),
                    "material": material,
                    "mode": _TRIANGLES,
                }
            )
        self.doc["meshes"].append({"name": name, "primitives": primitives})
        return len(self.doc["meshes"]) - 1

    def node(self, node: dict[str, Any], parent: int = 0) -> int:
        """A child of ``parent`` (default the root, world node); returns the node's index."""
        self.doc["nodes"].append(node)
        index = len(self.doc["nodes"]) - 1
        self.doc["nodes"][parent].setdefault("children", []).append(index)
        return index

    def glb(self) -> bytes:
        """The binary glTF: 12-byte header, JSON chunk (space-padded), BIN chunk
        (zero-padded), every length a multiple of 4."""
        while len(self.bin) % 4:
            self.bin.append(0)
        doc = dict(self.doc)
        doc["buffers"] = [{"byteLength": len(self.bin)}]
        for key in ("meshes", "materials", "accessors", "bufferViews"):
            if not doc[key]:
                del doc[key]
        text = json.dumps(doc, separators=(",", ":"), allow_nan=False).encode("utf-8")
        text += b" " * (-len(text) % 4)
        total = 12 + 8 + len(text) + 8 + len(self.bin)
        return b"".join(
            [
                struct.pack("<III", _GLB_MAGIC, 2, total),
                struct.pack("<II", len(text), _CHUNK_JSON),
                text,
                struct.pack("<II", len(self.bin), _CHUNK_BIN),
                bytes(self.bin),
            ]
        )


def _check_result(result: Result) -> None:
    if result.scene is None:
        raise SceneError(
            "this result has no scene, so no vehicle meshes to export: export the Result "
            "that Scene.run returned"
        )


def _vehicle_meshes(doc: _Gltf, result: Result) -> list[int]:
    """One mesh per vehicle (body frame: model vertices - CG, m); returns their indices."""
    out = []
    for k, name in enumerate(result.vehicles):
        v = result.vehicle(name)
        colour = VEHICLE_COLOURS[k % len(VEHICLE_COLOURS)]  # as in the plots
        material = doc.material(name, _linear_rgba(colour))
        faces = np.asarray(v.mesh.faces, dtype=np.int64)
        out.append(doc.mesh(name, [(v.body_vertices, faces, material)]))
    return out


def _nice_tile(span: float) -> float:
    """The smallest of 1, 2, 5, 10, 20 ... m that covers ``span`` in MAX_TILES tiles."""
    tile = 1.0
    while span / tile > MAX_TILES:
        for m in (2.0, 2.5, 2.0):  # 1 -> 2 -> 5 -> 10 -> 20 ...
            tile *= m
            if span / tile <= MAX_TILES:
                break
    return tile


def _scene_ground(result: Result) -> Any:
    """The Ground of a run on the ground, else None."""
    if not getattr(result, "on_ground", False) or result.scene is None:
        return None
    return result.scene.ground


def _ground(doc: _Gltf, result: Result) -> int:
    """The ground: a run's terrain mesh, or a checkerboard GROUND_Z below the plane (z = 0
    without a ground) under everything the vehicles and obstacles reach (m), with the
    friction zones tinted on it."""
    ground = _scene_ground(result)
    if ground is not None and ground.terrain is not None:
        material = doc.material("terrain", [*_TERRAIN_COLOUR, 1.0], roughness=0.95)
        terrain = ground.terrain
        mesh = doc.mesh(
            "ground (terrain)",
            [(np.asarray(terrain.vertices), np.asarray(terrain.faces, dtype=np.int64), material)],
        )
        return doc.node({"name": "ground", "mesh": mesh})
    base = 0.0 if ground is None else float(ground.height)
    lo = np.array([np.inf, np.inf])
    hi = -lo
    for name in result.vehicles:
        xy = result.trajectory(name).position[:, :2]
        reach = float(np.max(np.linalg.norm(result.vehicle(name).body_vertices, axis=1)))
        lo = np.minimum(lo, xy.min(axis=0) - reach)
        hi = np.maximum(hi, xy.max(axis=0) + reach)
    for name in result.obstacles:  # under the obstacles too
        p, _ = _pose(result, name, float(result.t[0]))
        reach = float(np.max(np.linalg.norm(result.obstacle(name).mesh.vertices, axis=1)))
        lo, hi = np.minimum(lo, p[:2] - reach), np.maximum(hi, p[:2] + reach)
    lo, hi = lo - GROUND_MARGIN, hi + GROUND_MARGIN
    tile = _nice_tile(float(np.max(hi - lo)))
    i0, j0 = np.floor(lo / tile).astype(int)
    i1, j1 = np.ceil(hi / tile).astype(int)
    z = base + GROUND_Z
    parts: list[tuple[Array, NDArray[np.int64], int]] = []
    for parity, rgb in enumerate(_GROUND_COLOURS):
        verts: list[tuple[float, float, float]] = []
        faces: list[tuple[int, int, int]] = []
        for i in range(i0, i1):
            for j in range(j0, j1):
                if (i + j) % 2 != parity:
                    continue
                x0, y0, x1, y1 = i * tile, j * tile, (i + 1) * tile, (j + 1) * tile
                b = len(verts)
                verts += [(x0, y0, z), (x1, y0, z), (x1, y1, z), (x0, y1, z)]
                faces += [(b, b + 1, b + 2), (b, b + 2, b + 3)]  # up
        if faces:
            material = doc.material(f"ground {parity}", [*rgb, 1.0], roughness=0.95)
            parts.append((np.array(verts), np.array(faces, dtype=np.int64), material))
    mesh = doc.mesh(f"ground ({tile:g} m tiles)", parts)
    node = doc.node({"name": "ground", "mesh": mesh})
    if ground is not None and ground.zones:
        zones: list[tuple[Array, NDArray[np.int64], int]] = []
        for k, zone in enumerate(ground.zones):
            poly = np.asarray(zone.polygon, dtype=np.float64)
            tri = _triangulate(poly)
            corners = np.column_stack([poly, np.full(len(poly), base + ZONE_Z)])
            colour = ZONE_COLOURS[k % len(ZONE_COLOURS)]
            material = doc.material(
                f"{zone.label(k)}, tyre friction {zone.friction:g}", _linear_rgba(colour)
            )
            zones.append((corners, tri, material))
        doc.node({"name": "friction zones", "mesh": doc.mesh("friction zones", zones)})
    return node


def _triangulate(polygon: Array) -> NDArray[np.int64]:
    """Triangles (m, 3) of a simple polygon's corners (n, 2), by ear clipping, each wound
    counter-clockwise seen from above (facing +z)."""
    pts = np.asarray(polygon, dtype=np.float64)
    area = 0.5 * float(
        np.sum(pts[:, 0] * np.roll(pts[:, 1], -1) - np.roll(pts[:, 0], -1) * pts[:, 1])
    )
    order = list(range(len(pts))) if area >= 0.0 else list(range(len(pts)))[::-1]

    def cross(o: int, a: int, b: int) -> float:
        return float(
            (pts[a, 0] - pts[o, 0]) * (pts[b, 1] - pts[o, 1])
            - (pts[a, 1] - pts[o, 1]) * (pts[b, 0] - pts[o, 0])
        )

    def inside(p: int, a: int, b: int, c: int) -> bool:
        return cross(a, b, p) >= 0.0 and cross(b, c, p) >= 0.0 and cross(c, a, p) >= 0.0

    out: list[tuple[int, int, int]] = []
    guard = 0
    while len(order) > 3 and guard < 10 * len(pts) ** 2:
        guard += 1
        n = len(order)
        for k in range(n):
            a, b, c = order[k - 1], order[k], order[(k + 1) % n]
            if cross(a, b, c) <= 0.0:
                continue  # a reflex (or flat) corner is no ear
            if any(inside(p, a, b, c) for p in order if p not in (a, b, c)):
                continue
            out.append((a, b, c))
            del order[k]
            break
        else:  # no ear: degenerate left-overs (collinear corners); fan them
            break
    for k in range(1, len(order) - 1):
        out.append((order[0], order[k], order[k + 1]))
    return np.asarray(out, dtype=np.int64).reshape(-1, 3)


def _cylinder(radius: float, width: float) -> tuple[Array, NDArray[np.int64]]:
    """A closed cylinder (m) centred on its frame's origin, its axis along y."""
    a = np.linspace(0.0, 2.0 * math.pi, WHEEL_SECTIONS, endpoint=False)
    ring = np.column_stack([radius * np.cos(a), np.zeros_like(a), radius * np.sin(a)])
    left, right = ring + (0.0, width / 2.0, 0.0), ring + (0.0, -width / 2.0, 0.0)
    verts = np.vstack([left, right, [(0.0, width / 2.0, 0.0), (0.0, -width / 2.0, 0.0)]])
    n = WHEEL_SECTIONS
    faces = []
    for k in range(n):
        j = (k + 1) % n
        faces += [(k, j, n + j), (k, n + j, n + k)]  # the tread
        faces += [(2 * n, j, k), (2 * n + 1, n + k, n + j)]  # the two sides
    return verts, np.asarray(faces, dtype=np.int64)


def _obstacles(doc: _Gltf, result: Result) -> None:
    """One node per fixed obstacle: its mesh (its own frame) at its place."""
    if not result.obstacles:
        return
    material = doc.material("obstacle", _linear_rgba(OBSTACLE_COLOUR))
    t0 = float(result.t[0])
    for name in result.obstacles:
        obstacle = result.obstacle(name)
        mesh = doc.mesh(
            name,
            [(np.asarray(obstacle.mesh.vertices), np.asarray(obstacle.mesh.faces), material)],
        )
        p, q = _pose(result, name, t0)
        doc.node(
            {
                "name": name,
                "mesh": mesh,
                "translation": [float(c) for c in p],
                "rotation": [float(c) for c in q],
            }
        )


class _Wheels:
    """A vehicle's drawn wheels: their meshes, and their poses at any time of the run."""

    def __init__(self, doc: _Gltf, result: Result, name: str, material: int) -> None:
        self.name = name
        v = result.vehicle(name)
        assert v.wheels is not None
        self.names = tuple(v.wheels.names)
        self.body = np.asarray(v.wheels.centers, dtype=np.float64)  # static, body frame (m)
        self.meshes = [
            doc.mesh(
                wheel_node_name(name, w),
                [(*_cylinder(float(r), WHEEL_WIDTH * float(r)), material)],
            )
            for w, r in zip(self.names, v.wheels.radii, strict=True)
        ]
        self.result = result
        self.moving = bool(getattr(result, "on_ground", False))
        if self.moving:
            # the wheels' centres in the body frame at the samples (m), one sample per time
            # (at an exchange the last one; the centres do not jump there)
            t = result.t
            last = np.r_[np.diff(t) > 0.0, True]
            tr = result.trajectory(name)
            rot = rotation_matrix(tr.orientation[last])
            centres = result.wheel_centres(name)[:, last, :]  # (n, k, 3) world
            rel = centres - tr.position[last][None, :, :]
            self.t = t[last]
            self.offsets = np.einsum("kji,nkj->nki", rot, rel)  # R^T (c - p), (n, k, 3)
            # each wheel's road-wheel angle as the engine ran it (rad, body z)
            self.steer = result.wheel_steer(name)[:, last]

    def poses(self, times: Array) -> tuple[Array, Array]:
        """Each wheel's centre (n, m, 3) (m, world) and glTF quaternion (x, y, z, w)
        (n, m, 4) at the m ``times`` (s)."""
        s = self.result.states(self.name, times)
        p, q = s["position"], s["orientation"]
        r = rotation_matrix(q)  # (m, 3, 3)
        centres, quaternions = [], []
        for k in range(len(self.names)):
            b = np.stack([np.interp(times, self.t, self.offsets[k, :, i]) for i in range(3)], 1)
            half = 0.5 * np.interp(times, self.t, self.steer[k])
            zero = np.zeros_like(half)
            turn = np.stack([np.cos(half), zero, zero, np.sin(half)], axis=1)
            centres.append(p + np.einsum("mij,mj->mi", r, b))
            quaternions.append(_gltf_quaternion(_multiply(q, turn)))
        return np.array(centres), np.array(quaternions)


def _multiply(a: ArrayLike, b: ArrayLike) -> Array:
    """The quaternion product a b, both (w, x, y, z); (..., 4) row by row."""
    w1, x1, y1, z1 = np.moveaxis(np.asarray(a, dtype=np.float64), -1, 0)
    w2, x2, y2, z2 = np.moveaxis(np.asarray(b, dtype=np.float64), -1, 0)
    return np.stack(
        [
            w1 * w2 - x1 * x2 - y1 * y2 - z1 * z2,
            w1 * x2 + x1 * w2 + y1 * z2 - z1 * y2,
            w1 * y2 - x1 * z2 + y1 * w2 + z1 * x2,
            w1 * z2 + x1 * y2 - y1 * x2 + z1 * w2,
        ],
        axis=-1,
    )


def _wheels(doc: _Gltf, result: Result) -> list[_Wheels]:
    """The drawn wheels of every vehicle that has wheels."""
    out = []
    material: int | None = None
    for name in result.vehicles:
        if result.vehicle(name).wheels is None:
            continue
        if material is None:
            material = doc.material("tyre", _linear_rgba(WHEEL_COLOUR), roughness=0.9)
        out.append(_Wheels(doc, result, name, material))
    return out


def _static_wheels(doc: _Gltf, wheels: _Wheels, vehicle_node: int) -> None:
    """Wheels at their static body-frame centres, children of the vehicle's node."""
    for w, mesh, centre in zip(wheels.names, wheels.meshes, wheels.body, strict=True):
        doc.node(
            {
                "name": wheel_node_name(wheels.name, w),
                "mesh": mesh,
                "translation": [float(c) for c in centre],
            },
            parent=vehicle_node,
        )


def _pose(result: Result, name: str, t: float) -> tuple[Array, Array]:
    """(CG position m, glTF quaternion (x, y, z, w)) of a vehicle at time t."""
    positions, quaternions = _poses(result, name, np.array([t]))
    return positions[0], quaternions[0]


def _poses(result: Result, name: str, times: Array) -> tuple[Array, Array]:
    """(CG positions (m, 3) m, glTF quaternions (m, 4)) of a vehicle at the m ``times``."""
    s = result.states(name, times)
    return np.asarray(s["position"], dtype=np.float64), _gltf_quaternion(s["orientation"])


def _extras(result: Result) -> dict[str, Any]:
    return {
        "crashsim": {
            "units": "m, s; world frame z up (turned to glTF y up by the root node)",
            "vehicles": list(result.vehicles),
            "impacts": [
                {
                    "vehicles": list(i.vehicles),
                    "first_contact_time": i.first_contact_time,
                    "time": i.time,
                    "centroid": [float(c) for c in i.centroid],
                }
                for i in result.impacts
            ],
        }
    }


def key_times(result: Result, fps: float) -> Array:
    """The animation's key times (s): every 1/fps from the run's start, its end, and every
    impact's first contact and exchange; a frame closer than MIN_KEY_GAP to an impact
    instant gives way to it."""
    t0, t1 = float(result.t[0]), float(result.t[-1])
    frames = t0 + np.arange(int(math.floor((t1 - t0) * fps + 1e-9)) + 1) / fps
    frames = frames[frames <= t1]
    keys = [t for i in result.impacts for t in (i.first_contact_time, i.time)] + [t0, t1]
    keys_a = np.unique(np.asarray(keys, dtype=np.float64))
    near = np.min(np.abs(frames[:, None] - keys_a[None, :]), axis=1) < MIN_KEY_GAP
    times = np.unique(np.concatenate([frames[~near], keys_a]))
    # float32 must keep them strictly increasing (glTF); drop any that would merge
    stored = times.astype(np.float32)
    keep = np.concatenate([[True], np.diff(stored) > 0])
    return times[keep]


def _moving_keys(tracks: list[tuple[Array, Array]], always: NDArray[np.bool_]) -> NDArray[np.bool_]:
    """Which of the keys to write, given each node's (translation (m, 3), rotation (m, 4)) at
    the m keys: the first, the last, those marked in ``always``, and every key where a node
    moves. A key between two steps in which every node is still (translations within
    STILL_TRANSLATION, rotation components within STILL_ROTATION) is left out, except one
    whenever the change summed since the stretch began passes STILL_DRIFT of those
    tolerances (a slow creep stays drawn): a vehicle at rest costs two keys, not one per
    frame."""
    m = len(always)
    if m <= 2:
        return np.ones(m, dtype=bool)
    change = np.zeros(m - 1)
    for translation, rotation in tracks:
        change = np.maximum(change, np.abs(np.diff(translation, axis=0)).max(1) / STILL_TRANSLATION)
        change = np.maximum(change, np.abs(np.diff(rotation, axis=0)).max(1) / STILL_ROTATION)
    still = change < 1.0
    drift = np.floor(np.r_[0.0, np.cumsum(change)] / STILL_DRIFT)
    droppable = np.zeros(m, dtype=bool)
    droppable[1:-1] = still[:-1] & still[1:] & (drift[1:-1] == drift[:-2])
    return ~droppable | always


def export_glb(result: Result, path: str | Path, fps: float = 30.0, *, ground: bool = True) -> Path:
    """Writes the run as one animated GLB (glTF 2.0 binary) at ``path``; returns the path.

    The file holds one node and mesh per vehicle (named as in the scene; the mesh in the
    body frame, so the node's translation is the CG), its wheels (nodes named by
    ``wheel_node_name``), the fixed obstacles, the ground (unless ``ground=False``: a
    checkerboard, with a ground run's friction zones, or its terrain mesh) and the animation
    "motion": per vehicle, and per wheel on the ground, a translation and a rotation (x, y,
    z, w) sampler, LINEAR, keyed at ``fps`` per second plus the impacts' instants (times in
    s). The world's z up is turned to glTF's y up by the root node. The nodes' static
    transforms are the poses at the start of the run."""
    _check_result(result)
    try:
        if isinstance(fps, str):
            raise TypeError(fps)
        rate = float(fps)
    except (TypeError, ValueError) as e:
        raise ParameterError(f"fps must be a number of frames per second, got {fps!r}") from e
    if not math.isfinite(rate) or rate <= 0.0 or rate > 10_000.0:
        raise ParameterError(f"fps = {fps!r} is invalid: give frames per second in (0, 10000]")
    span = float(result.t[-1] - result.t[0])
    if span * rate > MAX_KEYS:
        lowered = MAX_KEYS / span
        warnings.warn(
            f"{span:.0f} s of run at {rate:g} frames per second is more than {MAX_KEYS} keys: "
            f"the animation is keyed at {lowered:.3g} per second instead (pass a lower fps, or "
            "export a part of the run with export_frames)",
            stacklevel=2,
        )
        rate = lowered
    doc = _Gltf()
    doc.doc["asset"]["extras"] = _extras(result)
    meshes = _vehicle_meshes(doc, result)
    times = key_times(result, rate)
    # every animated node's track at every key: (name, mesh, translation, rotation)
    tracks: list[tuple[str, int, Array, Array]] = []
    for name, mesh in zip(result.vehicles, meshes, strict=True):
        tracks.append((name, mesh, *_poses(result, name, times)))
    all_wheels = _wheels(doc, result)
    for wheels in all_wheels:
        if wheels.moving:
            centres, rotations = wheels.poses(times)
            for k, (w, mesh) in enumerate(zip(wheels.names, wheels.meshes, strict=True)):
                tracks.append((wheel_node_name(wheels.name, w), mesh, centres[k], rotations[k]))
    for _, _, _, rotation in tracks:  # q and -q are one rotation: keep the short way
        flips = np.einsum("ij,ij->i", rotation[1:], rotation[:-1]) < 0.0
        rotation *= np.r_[1.0, np.where(np.cumsum(flips) % 2 == 1, -1.0, 1.0)][:, None]
    impacts = np.isin(times, [t for i in result.impacts for t in (i.first_contact_time, i.time)])
    keep = _moving_keys([(tr[2], tr[3]) for tr in tracks], impacts)
    times = times[keep]
    time_accessor = doc.accessor(times)
    samplers: list[dict[str, Any]] = []
    channels: list[dict[str, Any]] = []
    nodes = {}
    for name, mesh, translation, rotation in tracks:
        node = doc.node(
            {
                "name": name,
                "mesh": mesh,
                "translation": [float(c) for c in translation[0]],
                "rotation": [float(c) for c in rotation[0]],
            }
        )
        nodes[name] = node
        for path_name, values in (("translation", translation), ("rotation", rotation)):
            samplers.append(
                {
                    "input": time_accessor,
                    "output": doc.accessor(values[keep]),
                    "interpolation": "LINEAR",
                }
            )
            channels.append(
                {"sampler": len(samplers) - 1, "target": {"node": node, "path": path_name}}
            )
    for wheels in all_wheels:
        if not wheels.moving:
            _static_wheels(doc, wheels, nodes[wheels.name])
    _obstacles(doc, result)
    if ground:
        _ground(doc, result)
    doc.doc["animations"] = [{"name": "motion", "samplers": samplers, "channels": channels}]
    out = Path(path)
    out.write_bytes(doc.glb())
    return out


def export_frames(
    result: Result, folder: str | Path, times: ArrayLike, *, ground: bool = True
) -> list[Path]:
    """Writes one static GLB per time (s) into ``folder`` (created if missing), named
    ``frame_0000_t0.0673s.glb`` etc. in the order given: the vehicles posed at that time on
    the ground with their wheels and the obstacles, no animation, for viewers that cannot
    play one. Returns the paths."""
    _check_result(result)
    try:
        ts = np.asarray(times, dtype=np.float64).reshape(-1)
    except (TypeError, ValueError) as e:
        raise ParameterError(f"times must be numbers (s), got {times!r}") from e
    if ts.size == 0:
        raise ParameterError("times is empty: give at least one time (s) within the run")
    t0, t1 = float(result.t[0]), float(result.t[-1])
    bad = ts[~((ts >= t0) & (ts <= t1))]
    if bad.size:
        raise ParameterError(
            f"times {bad.tolist()} are outside the run [{t0}, {t1}] s: give times within it"
        )
    folder = Path(folder)
    folder.mkdir(parents=True, exist_ok=True)
    paths = []
    for k, t in enumerate(ts):
        doc = _Gltf()
        extras = _extras(result)
        extras["crashsim"]["time"] = float(t)
        doc.doc["asset"]["extras"] = extras
        nodes = {}
        for name, mesh in zip(result.vehicles, _vehicle_meshes(doc, result), strict=True):
            p, q = _pose(result, name, float(t))
            nodes[name] = doc.node(
                {
                    "name": name,
                    "mesh": mesh,
                    "translation": [float(c) for c in p],
                    "rotation": [float(c) for c in q],
                }
            )
        for wheels in _wheels(doc, result):
            if not wheels.moving:
                _static_wheels(doc, wheels, nodes[wheels.name])
                continue
            centres, rotations = wheels.poses(np.array([t]))
            for w, mesh, p, q in zip(
                wheels.names, wheels.meshes, centres[:, 0], rotations[:, 0], strict=True
            ):
                doc.node(
                    {
                        "name": wheel_node_name(wheels.name, w),
                        "mesh": mesh,
                        "translation": [float(c) for c in p],
                        "rotation": [float(c) for c in q],
                    }
                )
        _obstacles(doc, result)
        if ground:
            _ground(doc, result)
        out = folder / f"frame_{k:04d}_t{t:.4f}s.glb"
        out.write_bytes(doc.glb())
        paths.append(out)
    return paths
