"""A case page from a run's output folder: ``crashsim view report.json``.

The JSON report holds the numbers (impacts, the scene's inputs, masses and inertias) but
neither the motion nor, by default, the meshes. ``crashsim run --out DIR`` writes them beside
it, and the page takes them from there:

- the motion: ``time-histories.csv`` (every sample of every vehicle: CG position,
  orientation quaternion, velocity, angular velocity, 15 significant digits);
- the meshes: the report's own ``scene.vehicles[].mesh.vertex_positions`` and
  ``face_indices`` when it was written with ``include_meshes=True``, else ``motion.glb``
  (each vehicle's body-frame mesh, float32).

Fixed obstacles (reports of runs with them list their kind, pose and extents) are drawn as
their bounding boxes. The interpolation between samples is torque-free unless the report's
optional ``run.on_ground`` is true. What the report alone cannot give (the overlap region's
points, tyre marks, rest ghosts, friction zones) is left out; the overlap region is drawn as
its box. Anything missing or malformed is a :class:`ReportFileError` naming the file and
the key.
"""

from __future__ import annotations

import copy
import csv
import json
import math
import struct
from pathlib import Path
from typing import Any

import numpy as np
from numpy.typing import NDArray

from crashsim._core import __version__
from crashsim.errors import InputError
from crashsim.filekind import special_file
from crashsim.io.viewer.data import (
    FORMAT,
    FORMAT_VERSION,
    SAMPLE_KEYS,
    arrow_scales,
    body_entry,
    colour_of,
    dynamics,
    keep_samples,
    people_of,
    person_fields,
    vehicle_colours,
)
from crashsim.io.viewer.meshes import pack_array

__all__ = ["CSV_FILE", "GLB_FILE", "ReportFileError", "check_report_path", "report_page_data"]

Array = NDArray[np.float64]

# The names `crashsim run` gives its outputs (crashsim.cli; a test checks they agree).
CSV_FILE = "time-histories.csv"
GLB_FILE = "motion.glb"
_SCHEMA = "crashsim-report"

_GLB_MAGIC = 0x46546C67
_COMPONENTS = {5126: "<f4", 5125: "<u4", 5123: "<u2", 5121: "u1"}
_WIDTH = {"SCALAR": 1, "VEC3": 3, "VEC4": 4}


class ReportFileError(InputError):
    """A report.json (or a file beside it that a case page needs) is missing or malformed."""


def _get(doc: Any, path: str, kind: type | tuple[type, ...], where: Path) -> Any:
    """doc[a][b]... for path "a.b...", checked to be of ``kind``."""
    value = doc
    for key in path.split("."):
        if isinstance(value, list) and key.isdigit() and int(key) < len(value):
            value = value[int(key)]
        elif isinstance(value, dict) and key in value:
            value = value[key]
        else:
            raise ReportFileError(f"{where}: the report has no {path!r}")
    if not isinstance(value, kind):
        raise ReportFileError(f"{where}: {path!r} is not what a report holds there")
    return value


def _array(doc: Any, path: str, shape: tuple[int, ...], where: Path) -> Array:
    try:
        a = np.asarray(_get(doc, path, list, where), dtype=np.float64)
        ok = a.shape == shape and bool(np.all(np.isfinite(a)))
    except (TypeError, ValueError):
        ok = False
    if not ok:
        raise ReportFileError(f"{where}: {path!r} must be {shape} finite numbers")
    return a


def check_report_path(path: Path) -> None:
    """ReportFileError unless ``path`` is a file (a folder, a named pipe or a device is not
    opened)."""
    kind = special_file(path)
    if kind is not None:
        raise ReportFileError(f"{path}: is {kind}, not a report file")
    if not path.is_file():
        raise ReportFileError(f"{path}: no such file")


def _read_report(path: Path) -> dict[str, Any]:
    check_report_path(path)
    try:
        text = path.read_text(encoding="utf-8")
    except (OSError, UnicodeDecodeError) as e:
        raise ReportFileError(f"{path}: cannot read it ({e})") from e

    def finite(text: str) -> float:  # every number, also 1e999, Infinity, NaN
        value = float(text)
        if not math.isfinite(value):
            raise ReportFileError(
                f"{path}: the number {text[:24]} is not finite: a report holds finite numbers "
                "(null where there is none)"
            )
        return value

    def whole(text: str) -> int:  # within a float's range: counts and masses alike
        finite(text)
        return int(text)

    try:
        doc = json.loads(text, parse_float=finite, parse_int=whole, parse_constant=finite)
    except json.JSONDecodeError as e:
        raise ReportFileError(f"{path}: not JSON ({e})") from e
    except RecursionError:
        raise ReportFileError(f"{path}: nested too deeply to be a crashsim report") from None
    if not isinstance(doc, dict) or doc.get("schema") != _SCHEMA:
        raise ReportFileError(
            f'{path}: not a crashsim report (no "schema": "{_SCHEMA}"); give the '
            "report.json that `crashsim run --out` wrote"
        )
    if doc.get("schema_version") != 1:
        raise ReportFileError(
            f"{path}: report schema version {doc.get('schema_version')!r} is not one this "
            f"crashsim ({__version__}) reads (1)"
        )
    for key, kind in (
        ("scene.vehicles", list),
        ("impacts", list),
        ("contacts", list),
        ("run", dict),
    ):
        _get(doc, key, kind, path)
    return doc


def _read_csv(path: Path, names: list[str]) -> tuple[Array, dict[str, dict[str, Array]]]:
    """Sample times (k,) and per vehicle its position, orientation, velocity and angular
    velocity (k, 3 or 4) from the time histories written by ``crashsim run``."""
    if not path.is_file():
        raise ReportFileError(
            f"{path}: no such file; the report has no motion of its own: view the report.json "
            f"in the folder `crashsim run --out` wrote (with {CSV_FILE} beside it)"
        )
    try:
        with open(path, newline="", encoding="utf-8") as f:
            rows = list(csv.reader(f))
    except (OSError, UnicodeDecodeError, csv.Error) as e:
        raise ReportFileError(f"{path}: cannot read it ({e})") from e
    if len(rows) < 2:
        raise ReportFileError(f"{path}: no samples")
    header = rows[0]
    try:
        table = np.array(rows[1:], dtype=np.float64)
    except ValueError as e:
        raise ReportFileError(f"{path}: not a table of numbers ({e})") from e
    if table.ndim != 2 or table.shape[1] != len(header) or not np.all(np.isfinite(table)):
        raise ReportFileError(f"{path}: rows of unequal length or non-finite numbers")
    column = {h: i for i, h in enumerate(header)}
    parts = {
        "position": ("x [m]", "y [m]", "z [m]"),
        "orientation": ("qw [1]", "qx [1]", "qy [1]", "qz [1]"),
        "velocity": ("vx [m/s]", "vy [m/s]", "vz [m/s]"),
        "angular_velocity": ("wx [rad/s]", "wy [rad/s]", "wz (yaw rate) [rad/s]"),
    }
    if "t [s]" not in column:
        raise ReportFileError(f"{path}: no column 't [s]'")
    t = table[:, column["t [s]"]]
    if np.any(np.diff(t) < 0.0):
        raise ReportFileError(f"{path}: the times decrease")
    out: dict[str, dict[str, Array]] = {}
    for name in names:
        out[name] = {}
        for key, labels in parts.items():
            missing = [f"{name} {x}" for x in labels if f"{name} {x}" not in column]
            if missing:
                raise ReportFileError(f"{path}: no column {missing[0]!r} (vehicle {name!r})")
            out[name][key] = table[:, [column[f"{name} {x}"] for x in labels]]
    return t, out


def _read_glb(path: Path, names: list[str]) -> dict[str, tuple[Array, NDArray[np.int64]]]:
    """Each named vehicle's body-frame mesh from a GLB written by crashsim.io.export."""
    try:
        blob = path.read_bytes()
    except FileNotFoundError:
        raise ReportFileError(
            f"{path}: no such file; the report holds no meshes: write it with "
            f"include_meshes=True, or keep the {GLB_FILE} that `crashsim run` writes beside it "
            "(not with --no-pictures)"
        ) from None
    except OSError as e:
        raise ReportFileError(f"{path}: cannot read it ({e})") from e
    try:
        magic, _, _ = struct.unpack_from("<III", blob, 0)
        json_len, _ = struct.unpack_from("<II", blob, 12)
        doc = json.loads(blob[20 : 20 + json_len])
        bin_start = 20 + json_len + 8
        binary = blob[bin_start:]
        if magic != _GLB_MAGIC:
            raise ValueError("not a GLB file")

        def accessor(index: int) -> NDArray[Any]:
            acc = doc["accessors"][index]
            view = doc["bufferViews"][acc["bufferView"]]
            width = _WIDTH[acc["type"]]
            dtype = np.dtype(_COMPONENTS[acc["componentType"]])
            start = view.get("byteOffset", 0) + acc.get("byteOffset", 0)
            n = acc["count"] * width
            a = np.frombuffer(binary, dtype=dtype, count=n, offset=start)
            return a.reshape(-1, width) if width > 1 else a

        out: dict[str, tuple[Array, NDArray[np.int64]]] = {}
        for node in doc["nodes"]:
            name = node.get("name")
            if name in names and "mesh" in node and name not in out:
                prim = doc["meshes"][node["mesh"]]["primitives"][0]
                v = accessor(prim["attributes"]["POSITION"]).astype(np.float64)
                f = accessor(prim["indices"]).astype(np.int64).reshape(-1, 3)
                if len(f) and (f.min() < 0 or f.max() >= len(v)):
                    raise ValueError(f"the mesh of {name!r} has face indices out of range")
                out[name] = (v, f)
    except (struct.error, KeyError, IndexError, TypeError, ValueError) as e:
        raise ReportFileError(f"{path}: not a GLB that crashsim wrote ({e})") from e
    missing = [n for n in names if n not in out]
    if missing:
        raise ReportFileError(f"{path}: no mesh for vehicle {missing[0]!r}")
    return out


def _report_meshes(
    doc: dict[str, Any], folder: Path, names: list[str], where: Path
) -> dict[str, tuple[Array, NDArray[np.int64]]]:
    """Body-frame meshes: the report's own (model frame - CG) when it has them, else the
    GLB beside it."""
    vehicles = doc["scene"]["vehicles"]
    if all("vertex_positions" in v.get("mesh", {}) for v in vehicles):
        out = {}
        for j, v in enumerate(vehicles):
            try:
                verts = np.asarray(v["mesh"]["vertex_positions"], dtype=np.float64).reshape(-1, 3)
                faces = np.asarray(v["mesh"]["face_indices"], dtype=np.int64).reshape(-1, 3)
            except (KeyError, TypeError, ValueError) as e:
                raise ReportFileError(f"{where}: scene.vehicles.{j}.mesh is malformed") from e
            cg = _array(doc, f"scene.vehicles.{j}.cg_model", (3,), where)
            if len(faces) and (faces.min() < 0 or faces.max() >= len(verts)):
                raise ReportFileError(f"{where}: scene.vehicles.{j}.mesh: indices out of range")
            out[str(v["name"])] = (verts - cg, faces)
        return out
    return _read_glb(folder / GLB_FILE, names)


def _box(extents: Array) -> tuple[Array, NDArray[np.int64]]:
    """A box of the given extents (m) centred on its frame's origin."""
    h = np.asarray(extents, dtype=np.float64) / 2.0
    v = np.array([[x, y, z] for x in (-h[0], h[0]) for y in (-h[1], h[1]) for z in (-h[2], h[2])])
    f = [
        (0, 1, 3), (0, 3, 2), (4, 6, 7), (4, 7, 5), (0, 4, 5), (0, 5, 1),
        (2, 3, 7), (2, 7, 6), (0, 2, 6), (0, 6, 4), (1, 5, 7), (1, 7, 3),
    ]  # fmt: skip
    return v, np.array(f, dtype=np.int64)


def _impact(doc: dict[str, Any], j: int, where: Path) -> dict[str, Any]:
    """An exchange for the page from the report (no region points: its box is drawn)."""
    base = f"impacts.{j}"
    imp = _get(doc, base, dict, where)
    pair = [str(x) for x in _get(doc, base + ".vehicles", list, where)]
    delta_v = {}
    for k, party in enumerate(_get(doc, base + ".parties", list, where)):
        delta_v[str(party.get("name"))] = _array(
            doc, f"{base}.parties.{k}.delta_v.world", (3,), where
        ).tolist()
    obstacle = imp.get("obstacle")
    return {
        "number": int(_get(doc, base + ".number", int, where)),
        "vehicles": pair,
        "obstacle": obstacle.get("name") if isinstance(obstacle, dict) else None,
        "secondary": bool(_get(doc, base + ".secondary", bool, where)),
        "first_contact_time": float(_get(doc, base + ".first_contact_time", (int, float), where)),
        "time": float(_get(doc, base + ".exchange_time", (int, float), where)),
        "centroid": _array(doc, base + ".centroid.world", (3,), where).tolist(),
        "normal": _array(doc, base + ".normal", (3,), where).tolist(),
        "impulse": _array(doc, base + ".impulse.on_vehicle_2", (3,), where).tolist(),
        "delta_v": delta_v,
        "contact_frame": _array(doc, base + ".contact_frame", (3, 3), where).reshape(-1).tolist(),
        "region_min": _array(doc, base + ".overlap.region_min", (3,), where).tolist(),
        "region_max": _array(doc, base + ".overlap.region_max", (3,), where).tolist(),
        "region_points_total": 0,
        "region_points": pack_array(np.zeros(0), "f4"),
    }


def report_page_data(path: Path, *, max_triangles: int, max_samples: int) -> dict[str, Any]:
    """The page's data (as crashsim.io.viewer.data.page_data) from a report.json and the
    files beside it."""
    doc = _read_report(path)
    folder = path.parent
    vehicles = doc["scene"]["vehicles"]
    names = [str(_get(doc, f"scene.vehicles.{j}.name", str, path)) for j in range(len(vehicles))]
    t, motion = _read_csv(folder / CSV_FILE, names)
    meshes = _report_meshes(doc, folder, names, path)
    impacts = [_impact(doc, j, path) for j in range(len(doc["impacts"]))]
    contacts = doc["contacts"]
    events = [x for i in impacts for x in (i["first_contact_time"], i["time"])]
    events += [float(c["time"]) for c in contacts if isinstance(c, dict) and "time" in c]
    keep = keep_samples(t, events, max_samples)
    people = people_of(doc)
    colours = vehicle_colours(names, people)
    bodies = []
    lengths = []
    for j, name in enumerate(names):
        mass = float(_get(doc, f"scene.vehicles.{j}.mass", (int, float), path))
        inertia = _array(doc, f"scene.vehicles.{j}.inertia", (3, 3), path)
        mesh = meshes[name]
        lengths.append(float(np.max(np.ptp(mesh[0], axis=0))) if len(mesh[0]) else 0.0)
        body = body_entry(
            name,
            "vehicle",
            colours[j],
            mesh,
            {key: motion[name][key][keep] for key in SAMPLE_KEYS},
            max_triangles,
        )
        body.update(dynamics(mass, inertia))
        body["tyre_marks"] = []
        body["rest"] = None
        body.update(person_fields(name, people))
        bodies.append(body)
    for j, o in enumerate(doc["scene"].get("obstacles") or []):
        base = f"scene.obstacles.{j}"
        position = _array(doc, base + ".position", (3,), path)
        orientation = _array(doc, base + ".orientation", (4,), path)
        extents = _array(doc, base + ".extents", (3,), path)
        n = len(keep)
        bodies.append(
            body_entry(
                str(o.get("name", f"obstacle {j}")),
                "obstacle",
                colour_of(j, True),
                _box(extents),
                {
                    "position": np.tile(position, (n, 1)),
                    "orientation": np.tile(orientation, (n, 1)),
                    "velocity": np.zeros((n, 3)),
                    "angular_velocity": np.zeros((n, 3)),
                },
                max_triangles,
            )
        )
        lengths.append(float(np.max(extents)))
    run = doc["run"]
    on_ground = run.get("on_ground") is True
    return {
        "format": FORMAT,
        "version": FORMAT_VERSION,
        "crashsim_version": str(__version__),
        "title": "crashsim case: "
        + ", ".join(dict.fromkeys(people.get(n, (n, ""))[0] for n in names))
        + f" ({path.name})",
        "source": "report",
        "interpolation": "hermite" if on_ground else "torque-free",
        "samples": {"total": int(t.size), "kept": int(keep.size), "t": pack_array(t[keep], "f8")},
        "run": {
            "duration": run.get("duration"),
            "dt": run.get("dt"),
            "record_interval": None,
        },
        "bodies": bodies,
        "impacts": impacts,
        "contacts": contacts,
        "ground": {"modelled": on_ground, "height": 0.0, "zones": []},
        "scales": arrow_scales(
            [np.asarray(v) for i in impacts for v in i["delta_v"].values()],
            [np.asarray(i["impulse"]) for i in impacts],
            lengths,
        ),
        "report": _without_meshes(doc),
    }


def _without_meshes(doc: dict[str, Any]) -> dict[str, Any]:
    """The report as the page embeds it: the meshes' vertex and face lists (when the report
    has them) left out, the page has its own packed copies."""
    out = copy.deepcopy(doc)
    for v in out["scene"]["vehicles"]:
        mesh = v.get("mesh")
        if isinstance(mesh, dict):
            mesh.pop("vertex_positions", None)
            mesh.pop("face_indices", None)
    return out
