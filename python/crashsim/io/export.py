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

Animation: one animation "motion" with, per vehicle, a translation and a rotation sampler,
LINEAR, quaternions in glTF's (x, y, z, w) order (crashsim's are (w, x, y, z)), times in s
from the start of the run. Keys are at ``fps`` frames per second plus every impact's first
contact and exchange instant (the velocity jumps there, so the pose between keys is exact at
the impacts and linear in between). glTF stores float32: positions are rounded by at most
0.5 um within 16 m of the origin (relative 6e-8), times by a relative 6e-8.

The files are written with numpy, struct and json only (no glTF library): the format is
small, and writing it here keeps the accessor bounds and alignment under our control.
"""

from __future__ import annotations

import json
import math
import struct
from pathlib import Path
from typing import TYPE_CHECKING, Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

from crashsim._core import __version__
from crashsim.errors import ParameterError, SceneError
from crashsim.plots import VEHICLE_COLOURS

if TYPE_CHECKING:
    from crashsim.result import Result

__all__ = ["GROUND_Z", "Z_UP_TO_Y_UP", "export_frames", "export_glb", "key_times"]

Array = NDArray[np.float64]

# The root node's rotation, glTF (x, y, z, w): -90 deg about x, world z -> glTF y.
Z_UP_TO_Y_UP = (-math.sqrt(0.5), 0.0, 0.0, math.sqrt(0.5))
GROUND_Z = -0.005  # m: the ground plane's height in the world
GROUND_MARGIN = 3.0  # m of ground beyond the vehicles' reach on every side
MAX_TILES = 60  # per side of the ground: the tile grows (1, 2, 5, 10 ... m) to keep under it
MIN_KEY_GAP = 1e-4  # s: a frame closer than this to an impact instant is dropped for it

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


def _linear_rgba(hex_colour: str, alpha: float = 1.0) -> list[float]:
    """glTF's baseColorFactor (linear RGB) of an sRGB hex colour."""
    srgb = np.array([int(hex_colour[i : i + 2], 16) / 255.0 for i in (1, 3, 5)])
    lin = np.where(srgb <= 0.04045, srgb / 12.92, ((srgb + 0.055) / 1.055) ** 2.4)
    return [*(round(float(c), 6) for c in lin), alpha]


def _gltf_quaternion(q_wxyz: ArrayLike) -> Array:
    """crashsim's (w, x, y, z) as glTF's (x, y, z, w), normalised."""
    q = np.asarray(q_wxyz, dtype=np.float64).reshape(4)
    q = q / np.linalg.norm(q)
    return np.array([q[1], q[2], q[3], q[0]])


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

    def node(self, node: dict[str, Any]) -> int:
        """A child of the root (world) node; returns the node's index."""
        self.doc["nodes"].append(node)
        index = len(self.doc["nodes"]) - 1
        self.doc["nodes"][0]["children"].append(index)
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


def _ground(doc: _Gltf, result: Result) -> int:
    """A checkerboard at z = GROUND_Z under everything the vehicles reach (m)."""
    lo = np.array([np.inf, np.inf])
    hi = -lo
    for name in result.vehicles:
        xy = result.trajectory(name).position[:, :2]
        reach = float(np.max(np.linalg.norm(result.vehicle(name).body_vertices, axis=1)))
        lo = np.minimum(lo, xy.min(axis=0) - reach)
        hi = np.maximum(hi, xy.max(axis=0) + reach)
    lo, hi = lo - GROUND_MARGIN, hi + GROUND_MARGIN
    tile = _nice_tile(float(np.max(hi - lo)))
    i0, j0 = np.floor(lo / tile).astype(int)
    i1, j1 = np.ceil(hi / tile).astype(int)
    parts = []
    for parity, rgb in enumerate(_GROUND_COLOURS):
        verts, faces = [], []
        for i in range(i0, i1):
            for j in range(j0, j1):
                if (i + j) % 2 != parity:
                    continue
                x0, y0, x1, y1 = i * tile, j * tile, (i + 1) * tile, (j + 1) * tile
                base = len(verts)
                verts += [
                    (x0, y0, GROUND_Z),
                    (x1, y0, GROUND_Z),
                    (x1, y1, GROUND_Z),
                    (x0, y1, GROUND_Z),
                ]
                faces += [(base, base + 1, base + 2), (base, base + 2, base + 3)]  # up
        if faces:
            material = doc.material(f"ground {parity}", [*rgb, 1.0], roughness=0.95)
            parts.append((np.array(verts), np.array(faces), material))
    mesh = doc.mesh(f"ground ({tile:g} m tiles)", parts)
    return doc.node({"name": "ground", "mesh": mesh})


def _pose(result: Result, name: str, t: float) -> tuple[Array, Array]:
    """(CG position m, glTF quaternion (x, y, z, w)) of a vehicle at time t."""
    s = result.state(name, t)
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


def export_glb(result: Result, path: str | Path, fps: float = 30.0, *, ground: bool = True) -> Path:
    """Writes the run as one animated GLB (glTF 2.0 binary) at ``path``; returns the path.

    The file holds one node and mesh per vehicle (named as in the scene; the mesh in the
    body frame, so the node's translation is the CG), a ground checkerboard (unless
    ``ground=False``) and the animation "motion": per vehicle a translation and a rotation
    (x, y, z, w) sampler, LINEAR, keyed at ``fps`` per second plus the impacts' instants
    (times in s). The world's z up is turned to glTF's y up by the root node. The nodes'
    static transforms are the poses at the start of the run."""
    _check_result(result)
    try:
        if isinstance(fps, str):
            raise TypeError(fps)
        rate = float(fps)
    except (TypeError, ValueError) as e:
        raise ParameterError(f"fps must be a number of frames per second, got {fps!r}") from e
    if not math.isfinite(rate) or rate <= 0.0 or rate > 10_000.0:
        raise ParameterError(f"fps = {fps!r} is invalid: give frames per second in (0, 10000]")
    doc = _Gltf()
    doc.doc["asset"]["extras"] = _extras(result)
    meshes = _vehicle_meshes(doc, result)
    times = key_times(result, rate)
    time_accessor = doc.accessor(times)
    samplers: list[dict[str, Any]] = []
    channels: list[dict[str, Any]] = []
    for name, mesh in zip(result.vehicles, meshes, strict=True):
        poses = [_pose(result, name, float(t)) for t in times]
        translation = np.array([p for p, _ in poses])
        rotation = np.array([q for _, q in poses])
        for k in range(1, len(rotation)):  # q and -q are one rotation: keep the short way
            if float(rotation[k] @ rotation[k - 1]) < 0.0:
                rotation[k] = -rotation[k]
        node = doc.node(
            {
                "name": name,
                "mesh": mesh,
                "translation": [float(c) for c in translation[0]],
                "rotation": [float(c) for c in rotation[0]],
            }
        )
        for path_name, values in (("translation", translation), ("rotation", rotation)):
            samplers.append(
                {
                    "input": time_accessor,
                    "output": doc.accessor(values),
                    "interpolation": "LINEAR",
                }
            )
            channels.append(
                {"sampler": len(samplers) - 1, "target": {"node": node, "path": path_name}}
            )
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
    the ground, no animation, for viewers that cannot play one. Returns the paths."""
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
        for name, mesh in zip(result.vehicles, _vehicle_meshes(doc, result), strict=True):
            p, q = _pose(result, name, float(t))
            doc.node(
                {
                    "name": name,
                    "mesh": mesh,
                    "translation": [float(c) for c in p],
                    "rotation": [float(c) for c in q],
                }
            )
        if ground:
            _ground(doc, result)
        out = folder / f"frame_{k:04d}_t{t:.4f}s.glb"
        out.write_bytes(doc.glb())
        paths.append(out)
    return paths
