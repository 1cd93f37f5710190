"""The JSON report's own records (crashsim.analysis.report): the schema's name and version,
units and conventions, the scene (vehicles with their meshes, obstacles, contact pairs) and
the engagements; report_schema() loads the JSON Schema."""

from __future__ import annotations

import hashlib
import json
from importlib import resources
from typing import TYPE_CHECKING, Any

import numpy as np

from crashsim.analysis.engagements import WHY_SECONDARY
from crashsim.analysis.report_common import _mat, _opt, _plain, _vec
from crashsim.small_linalg import norm

if TYPE_CHECKING:
    from crashsim.analysis.engagements import Engagement
    from crashsim.result import Result
    from crashsim.scene import Scene
    from crashsim.vehicles.vehicle import Vehicle

SCHEMA_NAME = "crashsim-report"
SCHEMA_VERSION = 1
_SCHEMA_FILE = ("schema", "report-1.schema.json")

UNITS = {
    "length": "m",
    "time": "s",
    "mass": "kg",
    "velocity": "m/s",
    "angular_velocity": "rad/s",
    "yaw_rate_change": "deg/s",
    "angle": "deg",
    "impulse": "N s",
    "energy": "J",
    "inertia": "kg m^2",
    "spring_rate": "N/m",
    "stiffness_A": "N/m",
    "stiffness_B": "N/m^2",
    "orientation": "unit quaternion (w, x, y, z), body -> world",
}

CONVENTIONS = {
    "world_frame": "right-handed, z up, ground at z = 0",
    "body_frame": (
        "ISO 8855: origin at the vehicle's CG, x forward, y left, z up; posed at the exchange"
    ),
    "model_frame": "the vehicle's mesh frame (x forward, y left, z up); body = model - cg",
    "normal": "unit, world, from vehicle 1 into vehicle 2",
    "impulse": "world, N s; acts on vehicle 2, its negative on vehicle 1",
    "delta_v_edr": "longitudinal +forward (body x), lateral +right (-body y), vertical +up",
    "pdof": (
        "SAE: direction FROM which the force acts on the vehicle, in its body x-y plane, "
        "degrees clockwise seen from above from straight ahead (0 ahead, 90 right, 180 "
        "behind, 270 left), in [0, 360)"
    ),
    "clock": "PDOF to the nearest hour: 12 = 0 deg, 3 = 90, 6 = 180, 9 = 270 (x.5 rounds up)",
    "yaw_rate_change": "world z component of the angular velocity change, + counter-clockwise "
    "seen from above",
    "deformation": (
        "vehicle 1 measured along +n, vehicle 2 along -n, from the impulse centroid to the "
        "undeformed (body-frame) bounding box or mesh surface"
    ),
    "engagements": (
        "a pair's contact from its first overlap to its separation: its exchanges grouped "
        "(the primary, then the secondary ones) with their delta-V summed (world); " + WHY_SECONDARY
    ),
}


def _mesh_record(vehicle: Vehicle, include_mesh: bool) -> dict[str, Any]:
    """What the report knows of a vehicle's mesh: size, model-frame bounds, a SHA-256 of its
    vertices (float64, model frame, m) and faces (int64), the scalar entries of trimesh's
    metadata (a file name, a box's extents, ...) and, when asked, the mesh itself."""
    mesh = vehicle.mesh
    vertices = np.ascontiguousarray(mesh.vertices, dtype=np.float64)
    faces = np.ascontiguousarray(mesh.faces, dtype=np.int64)
    digest = hashlib.sha256(vertices.tobytes() + faces.tobytes()).hexdigest()
    metadata: dict[str, Any] = {}
    for key, value in mesh.metadata.items():
        if str(key).startswith("_"):
            continue
        if isinstance(value, str | bool | int | float):
            metadata[str(key)] = value
        elif isinstance(value, np.ndarray) and value.size <= 16 and value.dtype.kind in "fiu":
            metadata[str(key)] = value.tolist()
    out: dict[str, Any] = {
        "triangles": len(faces),
        "vertices": len(vertices),
        "bounds_model": _mat(mesh.bounds),
        "sha256": digest,
        "metadata": metadata,
    }
    if include_mesh:
        out["vertex_positions"] = _mat(vertices)
        out["face_indices"] = [[int(i) for i in f] for f in faces]
    return out


def _contact_pairs(scene: Scene) -> list[dict[str, Any]]:
    """Every pair's parameters as the engine gets them, vehicle 1 first (the normal and a
    fixed centroid are given as seen from vehicle 1)."""
    return [{"vehicles": [a, b], "parameters": _plain(params)} for a, b, params in scene.pairs()]


def _scene_record(result: Result, include_meshes: bool) -> dict[str, Any]:
    scene = result.scene
    assert scene is not None
    vehicles = []
    for name in result.vehicles:
        v = result.vehicle(name)
        tr = result.trajectory(name)
        vehicles.append(
            {
                "name": name,
                "mass": float(v.mass),
                "mass_source": str(v.mass_source),
                "cg_model": _vec(v.cg),
                "inertia": _mat(v.inertia),
                "sources": {str(a): str(b) for a, b in v.sources.items()},
                "stiffness": _plain(v.stiffness.to_dict()),
                "summary": v.summary(),
                "mesh": _mesh_record(v, include_meshes),
                "generator": None
                if v.generator_params is None
                else _plain(v.generator_params.as_dict()),
                "initial_state": {
                    "time": float(tr.t[0]),
                    "position": _vec(tr.position[0]),
                    "orientation": _vec(tr.orientation[0]),
                    "velocity": _vec(tr.velocity[0]),
                    "angular_velocity": _vec(tr.angular_velocity[0]),
                },
                # optional: a vehicle on its wheels in a run on the ground
                **(
                    {"wheels": _plain(v.wheels.describe(v.mass))}
                    if v.wheels is not None and getattr(result, "on_ground", False)
                    else {}
                ),
            }
        )
    out: dict[str, Any] = {
        "vehicles": vehicles,
        "contact": {
            "defaults": _plain(scene.defaults),
            "pairs": _contact_pairs(scene),
        },
    }
    if result.obstacles:
        out["obstacles"] = []
        for name in result.obstacles:
            o = result.obstacle(name)
            tr = result.trajectory(name)
            out["obstacles"].append(
                {
                    "name": name,
                    "kind": o.kind,
                    "stiffness": _plain(o.stiffness.to_dict()),
                    "position": _vec(tr.position[0]),
                    "orientation": _vec(tr.orientation[0]),
                    "extents": _vec(o.extents),
                }
            )
    return out


def _engagement_record(e: Engagement) -> dict[str, Any]:
    """An engagement as JSON (impact numbers 1-based, as in ``impacts[].number``)."""
    return {
        "vehicles": list(e.vehicles),
        "first_overlap_time": float(e.first_overlap_time),
        "separation_time": _opt(e.separation_time),
        "exchanged": e.exchanged,
        "primary": None if e.primary is None else e.primary + 1,
        "secondary": [i + 1 for i in e.secondary],
        "secondary_causes": [
            {"impact": i + 1, "cause": cause} for i, cause in sorted(e.causes.items())
        ],
        "no_exchange": [{"time": float(t), "reason": reason} for t, reason in e.no_exchange],
        "delta_v": {
            "summed": {n: _vec(v) for n, v in e.delta_v.items()},
            "magnitude": {n: float(norm(v)) for n, v in e.delta_v.items()},
        },
        "energy_dissipated": float(e.energy_dissipated),
    }


def report_schema() -> dict[str, Any]:
    """The JSON Schema (draft 2020-12) of the report, version SCHEMA_VERSION."""
    text = resources.files("crashsim.analysis").joinpath(*_SCHEMA_FILE).read_text(encoding="utf-8")
    return dict(json.loads(text))


def impact_table(report: dict[str, Any]) -> tuple[list[str], list[list[Any]]]:
    """The impacts of a JSON report (``Report.to_dict()``) as a table: one row per impact,
    one column per number or word of its record, named by its JSON path in the record
    (units: docs/report.md, the same paths). A vector's components are ``.x``, ``.y``,
    ``.z`` (the contact frame's rows ``.n``, ``.t``, ``.b`` then those), ``parties`` become
    ``vehicle_1`` and ``vehicle_2`` by role, ``figures`` ``figures.<name>``, ``vehicles``
    ``vehicles.1`` and ``.2``, ``notes`` one column joined by "; "; None stays None. Every
    field of the record, a new one too, has its column; the columns are the union over the
    impacts in the order first met. Returns (header, rows)."""
    flat = [_flat_impact(imp) for imp in report["impacts"]]
    header: list[str] = []
    for row in flat:
        header += [k for k in row if k not in header]
    return header, [[row.get(k) for k in header] for row in flat]


def _flat_impact(impact: dict[str, Any]) -> dict[str, Any]:
    out: dict[str, Any] = {}
    _flatten(impact, "", out)
    return out


_AXES = ("x", "y", "z")
_FRAME_ROWS = ("n", "t", "b")  # the contact frame's rows


def _flatten(value: Any, path: str, out: dict[str, Any]) -> None:
    """``value`` under ``path`` into ``out`` as the columns of ``impact_table``."""
    name = path.rsplit(".", 1)[-1]
    if isinstance(value, dict):
        for key, v in value.items():
            _flatten(v, f"{path}.{key}" if path else key, out)
    elif isinstance(value, list) and name == "parties":
        for party in value:
            _flatten(party, f"vehicle_{party['role']}", out)
    elif isinstance(value, list) and name == "figures":
        for f in value:
            out[f"figures.{f['name']}"] = f["value"]
    elif isinstance(value, list) and name == "notes":
        out[path] = "; ".join(value)
    elif isinstance(value, list) and name == "contact_frame":
        for row, v in zip(_FRAME_ROWS, value, strict=True):
            _flatten(v, f"{path}.{row}", out)
    elif isinstance(value, list) and len(value) == 3:
        for axis, v in zip(_AXES, value, strict=True):
            out[f"{path}.{axis}"] = v
    elif isinstance(value, list):
        for k, v in enumerate(value, start=1):
            _flatten(v, f"{path}.{k}", out)
    else:
        out[path] = value
