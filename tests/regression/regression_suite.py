"""The regression suite's machinery, shared by the runner (test_regression.py) and the re-minting
command (mint.py). README.md beside this file says how the suite works.

A case is a scene file ``scenes/<scene>.toml`` (the project's scene format) and an expected file
``expected/<name>.json`` that names the scene and lists checks. Running a case loads and runs
the scene, turns the run into *figures* (:func:`figures`: a nested dict of numbers, SI, world
frame unless a name says otherwise) and applies every check:

- ``values``: compare the figures given under ``expected`` (any subset of :func:`figures`) with
  the run's, each with the tolerance of its figure name in ``tolerances``. Published figures
  and the minted golden values (``"golden": true``, written by mint.py) are checks of this kind.
- ``collinear``: a central collinear impact against its closed form, from the inputs written in
  the check (masses, velocities, normal, restitution), which must also be the scene's.
- ``eccentric``: a planar eccentric impact with a user-given centroid and normal against its
  closed form (frictionless: Newton with the effective mass; sticking: planar Kudlich-Slibar
  or Newton with the 2 x 2 collision matrix), inputs written in the check as above.
- ``mirror``: the scene's mirror image in the world x-z plane (a committed scene file, or
  ``"auto"``: built here, meshes mirrored into a temporary folder) must give the mirrored
  figures (:func:`mirror_figures`).

Tolerances: a figure passes when ``|got - expected| <= abs + rel * |expected|`` (vectors: the
Euclidean norms of the difference and of the expected vector, or each component on its own
when the tolerance says ``"componentwise": true``; PDOF: the difference wrapped to
[-180, 180) deg). Integers (counts), booleans, names and kinds must be equal.
"""

from __future__ import annotations

import json
import math
import platform
import re
import tempfile
import tomllib
import warnings
from collections.abc import Callable, Iterator
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import crashsim as cs
import numpy as np
import trimesh
from crashsim.io.scenefile import SceneFile, load_scene, loads_scene, parse_quantity
from crashsim.vehicles.meshio import load_mesh

HERE = Path(__file__).resolve().parent
SCENES = HERE / "scenes"
EXPECTED = HERE / "expected"
REPO = HERE.parents[1]
SHARED_MESHES = REPO.parent / "shared" / "meshes"

# The golden tolerances mint.py writes into a new golden check (README.md, "Tolerances").
# Keys are figure names (the last part of a figure's path); rel is relative to the expected
# value's magnitude (vectors: its norm), abs in the figure's unit. 1e-9 relative everywhere:
# the engine is deterministic (bit-identical reruns, whatever the thread count), and inputs
# moved by a few units in their last place (what another libm's sin/cos does) move the
# figures by at most 6e-13 relative (measured on every golden scene); the abs floors only
# matter for figures near zero.
GOLDEN_TOLERANCES: dict[str, dict[str, float]] = {
    "first_contact_time": {"rel": 1e-9, "abs": 1e-12},  # s
    "exchange_time": {"rel": 1e-9, "abs": 1e-12},  # s
    "exchange_delay": {"rel": 1e-9, "abs": 1e-12},  # s
    "contact_time": {"rel": 1e-9, "abs": 1e-12},  # s
    "centroid": {"rel": 1e-9, "abs": 1e-12},  # m
    "normal": {"rel": 0.0, "abs": 1e-9},  # unit vector
    "impulse": {"rel": 1e-9, "abs": 1e-9},  # N s
    "closing_speed": {"rel": 1e-9, "abs": 1e-12},  # m/s
    "energy_dissipated": {"rel": 1e-9, "abs": 1e-6},  # J
    "overlap_depth": {"rel": 1e-9, "abs": 1e-12},  # m
    "delta_v": {"rel": 1e-9, "abs": 1e-12},  # m/s
    "delta_v_edr": {"rel": 1e-9, "abs": 1e-12},  # m/s
    "delta_omega": {"rel": 1e-9, "abs": 1e-12},  # rad/s
    "yaw_rate_change_deg_s": {"rel": 1e-9, "abs": 1e-10},  # deg/s
    "pdof_deg": {"rel": 0.0, "abs": 1e-7},  # deg (wrapped)
    "bounding_box_deformation": {"rel": 1e-9, "abs": 1e-12},  # m
    "mesh_deformation": {"rel": 1e-9, "abs": 1e-12},  # m
    "travel": {"rel": 1e-9, "abs": 1e-12},  # m
}

# The mirror checks' tolerances (README.md, "Mirror images"): the same 1e-9 relative. A mirror
# image is exact up to round-off (meshes are mirrored vertex by vertex, winding reversed);
# measured on every scene: at most 4e-13 relative, first contact times equal to the bit.
MIRROR_TOLERANCES: dict[str, dict[str, float]] = dict(GOLDEN_TOLERANCES)

# Closed forms: the engine against exact formulas of the same model (README.md).
CLOSED_FORM_TOLERANCES: dict[str, dict[str, float]] = {
    "delta_v": {"rel": 1e-9, "abs": 0.0},
    "delta_omega": {"rel": 1e-9, "abs": 1e-12},
    "yaw_rate_change_deg_s": {"rel": 1e-9, "abs": 1e-10},
    "impulse": {"rel": 1e-9, "abs": 0.0},
    "energy_dissipated": {"rel": 1e-9, "abs": 1e-6},
    "closing_speed": {"rel": 1e-12, "abs": 0.0},
    "normal": {"rel": 0.0, "abs": 1e-12},
    "centroid": {"rel": 0.0, "abs": 1e-12},
}

# Scene inputs a closed-form check reads back from the loaded scene (SI): relative tolerance.
INPUT_RTOL = 1e-12


# -- cases -----------------------------------------------------------------------------------


def case_names() -> list[str]:
    """The cases: the stems of expected/*.json, sorted."""
    return sorted(p.stem for p in EXPECTED.glob("*.json"))


def load_case(name: str) -> dict[str, Any]:
    """An expected file as a dict."""
    return json.loads((EXPECTED / f"{name}.json").read_text(encoding="utf-8"))


def write_case(name: str, case: dict[str, Any]) -> None:
    """Write an expected file: JSON, floats as Python's repr (they read back exactly), short
    lists and flat tables on one line so the files stay readable."""
    (EXPECTED / f"{name}.json").write_text(to_json(case) + "\n", encoding="utf-8")


def to_json(value: Any, indent: int = 0) -> str:
    """JSON text with 2-space indents; a list or table that fits in 96 columns and holds no
    table (nor a list of lists or tables) stays on one line."""
    one = json.dumps(value, ensure_ascii=False)
    if not isinstance(value, dict | list):
        return one
    children = list(value.values()) if isinstance(value, dict) else value
    flat = all(
        not isinstance(v, dict)
        and not (isinstance(v, list) and any(isinstance(x, dict | list) for x in v))
        for v in children
    )
    if flat and len(one) + indent <= 96:
        return one
    pad, inner = " " * indent, " " * (indent + 2)
    if isinstance(value, dict):
        items = [f"{inner}{json.dumps(k)}: {to_json(v, indent + 2)}" for k, v in value.items()]
        return "{\n" + ",\n".join(items) + "\n" + pad + "}"
    items = [f"{inner}{to_json(v, indent + 2)}" for v in value]
    return "[\n" + ",\n".join(items) + "\n" + pad + "]"


def missing_inputs(scene_path: Path) -> str | None:
    """Why a scene cannot run here (a skip reason), or None: the shared meshes are absent, or
    the scene uses generated bodies and this crashsim has no Vehicle.generate yet."""
    data = tomllib.loads(scene_path.read_text(encoding="utf-8"))
    for v in data.get("vehicles", []):
        if "generate" in v and not hasattr(cs.Vehicle, "generate"):
            return f"{scene_path.name}: this crashsim has no Vehicle.generate (generated bodies)"
        mesh = v.get("mesh")
        if mesh is None:
            continue
        file = Path(mesh if isinstance(mesh, str) else mesh.get("file", ""))
        if not file.is_absolute():
            file = scene_path.parent / file
        if not file.is_file() and not SHARED_MESHES.is_dir():
            return (
                f"{scene_path.name} needs the shared meshes, which are not at {SHARED_MESHES} "
                "(../shared/meshes beside the repository)"
            )
    return None


# -- running and figures ---------------------------------------------------------------------


@dataclass
class Run:
    """A scene file's run: the loaded scene, the result, the figures and the engine's warnings
    (e.g. an automatic depth of penetration outside 10-60 ms; they do not fail a case)."""

    scene_file: SceneFile
    result: cs.Result
    figures: dict[str, Any]
    warnings: list[str] = field(default_factory=list)


def run_scene(path: Path) -> Run:
    """Load and run a scene file with its own [run] settings."""
    scene_file = load_scene(path)
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        result = scene_file.simulate()
    return Run(scene_file, result, figures(result), [str(w.message) for w in caught])


def _vec(a: Any) -> list[float]:
    return [float(x) for x in np.asarray(a, dtype=np.float64)]


def figures(result: cs.Result) -> dict[str, Any]:
    """The figures of a run (SI; world frame unless said):

    - ``exchanges``: how many impulse exchanges; ``contacts``: the contact log, each
      {vehicles, kind, contact_time (s)};
    - ``impacts``: per exchange, in time order: vehicles (1, 2), secondary, sliding,
      first_contact_time (the timer's start, s), exchange_time (s), exchange_delay (exchange
      minus timer start = the depth of penetration used, s), centroid (m), normal (1 -> 2),
      impulse (on vehicle 2, N s), closing_speed (m/s), energy_dissipated (J), overlap_depth
      (along n, m) and ``parties``: per vehicle delta_v (m/s), delta_v_edr (longitudinal
      +forward, lateral +right, vertical +up at the exchange pose, m/s), delta_omega (rad/s),
      yaw_rate_change_deg_s (+ counter-clockwise), pdof_deg (SAE, [0, 360), None without a
      horizontal delta-V), bounding_box_deformation and mesh_deformation (the report's, m;
      mesh None when its ray misses) and travel (|CG displacement| from the timer's start to
      the exchange, m).
    """
    report = cs.report(result)
    impacts = []
    for imp, rep in zip(result.impacts, report.impacts, strict=True):
        parties = {}
        for p in rep.parties:
            start = result.state(p.name, imp.first_contact_time)["position"]
            end = result.state_at(p.name, imp.time)["position"]
            parties[p.name] = {
                "delta_v": _vec(p.delta_v),
                "delta_v_edr": [float(p.longitudinal), float(p.lateral), float(p.vertical)],
                "delta_omega": _vec(p.delta_omega),
                "yaw_rate_change_deg_s": float(p.yaw_rate_change),
                "pdof_deg": None if p.pdof_deg is None else float(p.pdof_deg),
                "bounding_box_deformation": float(p.deformation.bounding_box),
                "mesh_deformation": None
                if p.deformation.mesh is None
                else float(p.deformation.mesh),
                "travel": float(np.linalg.norm(end - start)),
            }
        impacts.append(
            {
                "vehicles": list(imp.vehicles),
                "secondary": bool(imp.secondary),
                "sliding": bool(imp.sliding),
                "first_contact_time": float(imp.first_contact_time),
                "exchange_time": float(imp.time),
                "exchange_delay": float(imp.time - imp.first_contact_time),
                "centroid": _vec(imp.centroid),
                "normal": _vec(imp.normal),
                "impulse": _vec(imp.impulse),
                "closing_speed": float(imp.closing_speed),
                "energy_dissipated": float(imp.energy_dissipated),
                "overlap_depth": float(rep.overlap_depth),
                "parties": parties,
            }
        )
    contacts = [
        {"vehicles": list(c.vehicles), "kind": c.kind, "contact_time": float(c.time)}
        for c in result.contacts
    ]
    return {"exchanges": len(impacts), "impacts": impacts, "contacts": contacts}


# -- comparing -------------------------------------------------------------------------------


def _leaves(tree: Any, path: str = "") -> Iterator[tuple[str, Any]]:
    """(path, value) of every figure in a figures tree; a list of numbers is one figure."""
    if isinstance(tree, dict):
        for k, v in tree.items():
            yield from _leaves(v, f"{path}.{k}" if path else k)
    elif isinstance(tree, list) and tree and all(isinstance(x, dict | list) for x in tree):
        for i, v in enumerate(tree):
            yield from _leaves(v, f"{path}[{i}]")
    else:
        yield path, tree


def _get(tree: Any, path: str) -> Any:
    """The value at a path written by :func:`_leaves` (KeyError/IndexError when absent)."""
    node = tree
    for part in re.findall(r"[^.\[\]]+|\[\d+\]", path):
        node = node[int(part[1:-1])] if part.startswith("[") else node[part]
    return node


def _name(path: str) -> str:
    """A figure's name: the last key of its path."""
    return re.sub(r"\[\d+\]$", "", path.rsplit(".", 1)[-1])


def _is_number(x: Any) -> bool:
    return isinstance(x, int | float) and not isinstance(x, bool)


def compare(
    expected: dict[str, Any], got: dict[str, Any], tolerances: dict[str, dict[str, float]]
) -> list[str]:
    """Every figure of ``expected`` against ``got``: a list of failures (empty when all pass).
    Numbers need a tolerance for their name in ``tolerances``; the rest must be equal."""
    return [message for _, ratio, message in deviations(expected, got, tolerances) if ratio > 1.0]


def deviations(
    expected: dict[str, Any], got: dict[str, Any], tolerances: dict[str, dict[str, float]]
) -> Iterator[tuple[str, float, str]]:
    """(path, difference / allowed difference, message) for every figure of ``expected``: a
    ratio above 1 fails (infinite for a missing figure, a missing tolerance or an exact figure
    that differs; 0 for an exact figure that agrees)."""
    for path, want in _leaves(expected):
        try:
            have = _get(got, path)
        except (KeyError, IndexError):
            yield path, math.inf, f"{path}: expected {want!r}, the run has no such figure"
            continue
        # floats and vectors carry tolerances; integers (counts), booleans and names are exact
        numeric = isinstance(want, float) or (
            isinstance(want, list) and want and all(_is_number(x) for x in want)
        )
        if not numeric or have is None:
            same = have == want
            yield path, 0.0 if same else math.inf, f"{path}: expected {want!r}, got {have!r}"
            continue
        name = _name(path)
        if name not in tolerances:
            yield path, math.inf, f"{path}: no tolerance given for the figure {name!r}"
            continue
        tol = tolerances[name]
        a, b = np.asarray(have, dtype=np.float64), np.asarray(want, dtype=np.float64)
        if a.shape != b.shape:
            yield path, math.inf, f"{path}: expected shape {b.shape}, got {a.shape}"
            continue
        diff = a - b
        if name == "pdof_deg":
            diff = (diff + 180.0) % 360.0 - 180.0
        rel, tol_abs = tol.get("rel", 0.0), tol.get("abs", 0.0)
        if tol.get("componentwise", False):
            allowed = tol_abs + rel * np.abs(b)
            ratios = np.abs(diff) / np.maximum(allowed, np.finfo(np.float64).tiny)
            worst = int(np.argmax(ratios)) if diff.ndim else 0
            err = float(np.abs(diff).reshape(-1)[worst])
            bound = float(np.asarray(allowed).reshape(-1)[worst])
        else:
            err = float(np.linalg.norm(diff))
            bound = tol_abs + rel * float(np.linalg.norm(b))
        ratio = err / bound if bound > 0.0 else (0.0 if err == 0.0 else math.inf)
        if not math.isfinite(err):
            ratio = math.inf
        yield (
            path,
            ratio,
            f"{path}: expected {want!r}, got {have!r} (difference {err:.3g}, allowed "
            f"{bound:.3g}: rel {rel:g}, abs {tol_abs:g}"
            + (", per component)" if tol.get("componentwise", False) else ")"),
        )


def differences(old: dict[str, Any], new: dict[str, Any]) -> list[str]:
    """What changed between two figure trees, one line per figure (mint.py prints this)."""
    lines = []
    old_leaves, new_leaves = dict(_leaves(old)), dict(_leaves(new))
    for path in old_leaves.keys() | new_leaves.keys():
        a, b = old_leaves.get(path, "(absent)"), new_leaves.get(path, "(absent)")
        if a == b:
            continue
        change = ""
        numeric = (_is_number(a) and _is_number(b)) or (
            isinstance(a, list) and isinstance(b, list) and len(a) == len(b)
        )
        if numeric:
            x, y = np.asarray(a, dtype=np.float64), np.asarray(b, dtype=np.float64)
            d = float(np.linalg.norm(y - x))
            scale = float(np.linalg.norm(x))
            change = f"  (|change| {d:.3g}" + (f", {d / scale:.3g} relative)" if scale else ")")
        lines.append(f"{path}: {a!r} -> {b!r}{change}")
    return sorted(lines, key=_natural)


def _natural(text: str) -> list[Any]:
    return [int(t) if t.isdigit() else t for t in re.split(r"(\d+)", text)]


# -- mirror images ---------------------------------------------------------------------------

_MIRROR = np.diag([1.0, -1.0, 1.0])


def mirror_figures(fig: dict[str, Any]) -> dict[str, Any]:
    """The figures the mirror image (in the world x-z plane) of a run must give: world vectors
    with y negated; angular velocities (axial vectors) with x and z negated; the EDR lateral
    delta-V and the yaw-rate change negated; PDOF 360 - x; times, energies, lengths and the
    rest unchanged."""

    def walk(node: Any, key: str = "") -> Any:
        if isinstance(node, dict):
            return {k: walk(v, k) for k, v in node.items()}
        if key in ("centroid", "normal", "impulse", "delta_v"):
            return [node[0], -node[1], node[2]]
        if key == "delta_omega":
            return [-node[0], node[1], -node[2]]
        if key == "delta_v_edr":
            return [node[0], -node[1], node[2]]
        if key == "yaw_rate_change_deg_s":
            return -node
        if key == "pdof_deg" and node is not None:
            return (360.0 - node) % 360.0
        if isinstance(node, list) and node and all(isinstance(x, dict) for x in node):
            return [walk(x) for x in node]
        return node

    return walk(fig)


def _vector_si(value: Any, dimension: str | None) -> list[float]:
    """A scene-file vector in SI: a list of quantities, or one string "(x, y, ...) unit"."""
    if isinstance(value, str):
        m = re.fullmatch(r"\s*\((.*)\)\s*(.*?)\s*", value, re.DOTALL)
        if m is None:
            raise ValueError(f"cannot read the vector {value!r}")
        unit = m.group(2)
        return [parse_quantity(f"{x.strip()} {unit}", dimension) for x in m.group(1).split(",")]
    if dimension is None:
        return [float(x) for x in value]
    return [parse_quantity(x, dimension) for x in value]


def _mirror_point(value: Any) -> list[float]:
    x = _vector_si(value, "length")
    return [x[0], -x[1], *x[2:]]


def mirror_scene_text(path: Path, folder: Path) -> str:
    """The mirror image in the world x-z plane of a scene file, as scene-file text whose
    relative paths are relative to ``folder``: y -> -y for positions, velocities, fixed
    normals and centroids; headings, directions and yaw rates negated (angular velocities:
    x and z negated; quaternions (w, x, y, z) -> (w, -x, y, -z); matrices M R M with
    M = diag(1, -1, 1)); each vehicle's left and right stiffness swapped; mesh files mirrored
    in the model frame (y -> -y, winding reversed so the faces still point out) and written to
    ``folder`` as PLY. A generated body becomes a mesh vehicle: its generated mesh mirrored, with
    its CG and inertia mirrored and given explicitly (the generator's surface is not exactly
    mirror-symmetric, so generating it again would not give the mirror image). Boxes are
    mirror-symmetric and stay as they are."""
    data = tomllib.loads(path.read_text(encoding="utf-8"))
    data.pop("output", None)
    data["title"] = data.get("title", "") + " (mirrored)"
    for section in [data.get("contact", {}), *data.get("pairs", [])]:
        _mirror_contact(section)
    generated = None
    for i, v in enumerate(data["vehicles"]):
        if "mesh" in v:
            v["mesh"] = _mirror_mesh(v["mesh"], path.parent, folder, i)
        if "generate" in v:
            if generated is None:
                generated = load_scene(path).scene.vehicles
            vehicle = generated[i]
            del v["generate"]
            v["mesh"] = {"file": _write_mirrored(vehicle.mesh, folder, f"mirrored-{i}-generated")}
            v["cg"] = _vec(vehicle.cg)  # as given; mirrored below with every explicit CG
            v["inertia"] = vehicle.inertia.tolist()
        if isinstance(v.get("cg"), list):
            v["cg"] = _mirror_point(v["cg"])
        if isinstance(v.get("inertia"), list):
            m = np.array([_vector_si(row, "moment of inertia") for row in v["inertia"]])
            v["inertia"] = (_MIRROR @ m @ _MIRROR).tolist()
        if isinstance(v.get("stiffness"), dict):
            s = v["stiffness"]
            left, right = s.pop("left", None), s.pop("right", None)
            if right is not None:
                s["left"] = right
            if left is not None:
                s["right"] = left
        v["position"] = _mirror_point(v["position"])
        for key in ("heading", "direction"):
            if key in v:
                v[key] = -parse_quantity(v[key], "angle")
        if "yaw_rate" in v:
            v["yaw_rate"] = -parse_quantity(v["yaw_rate"], "angular velocity")
        if "velocity" in v:
            vel = _vector_si(v["velocity"], "speed")
            v["velocity"] = [vel[0], -vel[1], *vel[2:]]
        if "angular_velocity" in v:
            w = _vector_si(v["angular_velocity"], "angular velocity")
            v["angular_velocity"] = [-w[0], w[1], -w[2]]
        if "orientation" in v:
            o = v["orientation"]
            if isinstance(o[0], list):
                v["orientation"] = (_MIRROR @ np.array(o, dtype=np.float64) @ _MIRROR).tolist()
            else:
                v["orientation"] = [o[0], -o[1], o[2], -o[3]]
    return to_toml(data)


def _mirror_contact(section: dict[str, Any]) -> None:
    normal = section.get("normal")
    if isinstance(normal, list):
        n = _vector_si(normal, None)
        section["normal"] = [n[0], -n[1], n[2]]
    centroid = section.get("centroid")
    if isinstance(centroid, dict):
        centroid["point"] = _mirror_point(centroid["point"])
    elif centroid is not None and not (
        isinstance(centroid, str) and centroid.strip() in ("auto", "stiffness")
    ):
        section["centroid"] = _mirror_point(centroid)


def _mirror_mesh(spec: Any, base: Path, folder: Path, index: int) -> dict[str, Any]:
    """Mirror a vehicle's mesh in its model frame into ``folder``; the new mesh entry."""
    options = {"file": spec} if isinstance(spec, str) else dict(spec)
    file = Path(options.pop("file"))
    if not file.is_absolute():
        file = base / file
    solid = options.pop("solid", None)
    mesh = load_mesh(file, **options)  # units, axes, ground, center applied: the model frame
    entry: dict[str, Any] = {"file": _write_mirrored(mesh, folder, f"mirrored-{index}-{file.stem}")}
    if solid is not None:
        entry["solid"] = solid
    return entry


def _write_mirrored(mesh: trimesh.Trimesh, folder: Path, stem: str) -> str:
    """Write a model-frame mesh's mirror image (y -> -y) as binary PLY; the file name."""
    vertices = np.asarray(mesh.vertices, dtype="<f8") * [1.0, -1.0, 1.0]
    faces = np.asarray(mesh.faces)[:, [0, 2, 1]]  # reversed winding: still pointing out
    # binary PLY with double vertices (trimesh's exporter writes floats: 1e-7 relative)
    header = (
        "ply\nformat binary_little_endian 1.0\n"
        f"element vertex {len(vertices)}\n"
        "property double x\nproperty double y\nproperty double z\n"
        f"element face {len(faces)}\n"
        "property list uchar int vertex_indices\nend_header\n"
    )
    rows = np.zeros(len(faces), dtype=[("n", "u1"), ("v", "<i4", (3,))])
    rows["n"], rows["v"] = 3, faces
    out = folder / f"{stem}.ply"
    out.write_bytes(header.encode("ascii") + vertices.tobytes() + rows.tobytes())
    return out.name


def _toml_key(key: str) -> str:
    return key if re.fullmatch(r"[A-Za-z0-9_-]+", key) else json.dumps(key)


def _toml_value(value: Any) -> str:
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, int | float):
        if isinstance(value, float) and not math.isfinite(value):
            raise ValueError(f"{value} cannot be written to a scene file")
        return repr(float(value)) if isinstance(value, float) else str(value)
    if isinstance(value, str):
        return json.dumps(value)  # a TOML basic string
    if isinstance(value, list):
        return "[" + ", ".join(_toml_value(x) for x in value) + "]"
    if isinstance(value, dict):
        items = ", ".join(f"{_toml_key(k)} = {_toml_value(v)}" for k, v in value.items())
        return "{ " + items + " }"
    raise TypeError(f"cannot write {type(value).__name__} to TOML")


def to_toml(data: dict[str, Any]) -> str:
    """TOML text of a scene-file dict (top-level keys, tables and arrays of tables; deeper
    tables inline)."""
    lines = []
    for k, v in data.items():
        if not isinstance(v, dict) and not (isinstance(v, list) and v and isinstance(v[0], dict)):
            lines.append(f"{_toml_key(k)} = {_toml_value(v)}")
    for k, v in data.items():
        tables = [v] if isinstance(v, dict) else v if isinstance(v, list) else []
        if not tables or not all(isinstance(t, dict) for t in tables):
            continue
        for t in tables:
            lines += ["", f"[{_toml_key(k)}]" if isinstance(v, dict) else f"[[{_toml_key(k)}]]"]
            lines += [f"{_toml_key(kk)} = {_toml_value(vv)}" for kk, vv in t.items()]
    return "\n".join(lines) + "\n"


def mirror_run(path: Path, folder: Path) -> Run:
    """Run the automatic mirror image of a scene file (scene and meshes written to folder)."""
    folder.mkdir(parents=True, exist_ok=True)
    text = mirror_scene_text(path, folder)
    mirrored = folder / f"{path.stem}-mirrored.toml"
    mirrored.write_text(text, encoding="utf-8")
    scene_file = loads_scene(text, base_dir=folder, source=str(mirrored), path=mirrored)
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        result = scene_file.simulate()
    return Run(scene_file, result, figures(result), [str(w.message) for w in caught])


# -- sensitivity to the last bits ------------------------------------------------------------

ULP = 2.0**-52


def perturbed_run(path: Path, rng: np.random.Generator, ulps: float = 4.0) -> Run:
    """Run a scene with every initial position, heading, direction, speed, velocity and yaw
    rate multiplied by 1 + k 2^-52, k uniform in [-ulps, ulps]: what another platform's libm
    (sin, cos, atan2 a few units in the last place off) can do to the inputs."""

    def nudge(x: float) -> float:
        return float(x * (1.0 + rng.uniform(-ulps, ulps) * ULP))

    data = tomllib.loads(path.read_text(encoding="utf-8"))
    for v in data["vehicles"]:
        v["position"] = [nudge(x) for x in _vector_si(v["position"], "length")]
        for key in ("heading", "direction"):
            if key in v:
                v[key] = nudge(parse_quantity(v[key], "angle"))
        if "speed" in v:
            v["speed"] = nudge(parse_quantity(v["speed"], "speed"))
        if "velocity" in v:
            v["velocity"] = [nudge(x) for x in _vector_si(v["velocity"], "speed")]
        if "yaw_rate" in v:
            v["yaw_rate"] = nudge(parse_quantity(v["yaw_rate"], "angular velocity"))
    scene_file = loads_scene(to_toml(data), base_dir=path.parent, source=str(path))
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        result = scene_file.simulate()
    return Run(scene_file, result, figures(result), [str(w.message) for w in caught])


def scaled(tolerances: dict[str, dict[str, Any]], factor: float) -> dict[str, dict[str, Any]]:
    """Tolerances with rel and abs multiplied by factor."""
    return {
        k: {**t, "rel": t.get("rel", 0.0) * factor, "abs": t.get("abs", 0.0) * factor}
        for k, t in tolerances.items()
    }


# -- closed forms ----------------------------------------------------------------------------


def _close(a: Any, b: Any, rtol: float = INPUT_RTOL) -> bool:
    a, b = np.asarray(a, dtype=np.float64), np.asarray(b, dtype=np.float64)
    return bool(np.linalg.norm(a - b) <= rtol * max(np.linalg.norm(b), 1.0))


def _initial(result: cs.Result, name: str) -> dict[str, np.ndarray]:
    tr = result.trajectory(name)
    return {
        "position": tr.position[0],
        "orientation": tr.orientation[0],
        "velocity": tr.velocity[0],
        "angular_velocity": tr.angular_velocity[0],
    }


def _check_inputs(run: Run, check: dict[str, Any], planar: bool) -> list[str]:
    """The closed form's inputs (written in the check) against the loaded scene."""
    scene, result = run.scene_file.scene, run.result
    v1, v2 = check["vehicle_1"], check["vehicle_2"]
    vehicles = {v.name: v for v in scene.vehicles}
    params = scene.contact_parameters(v1, v2)
    problems = []

    def need(ok: bool, what: str) -> None:
        if not ok:
            problems.append(f"the scene does not match the closed form's inputs: {what}")

    for key, name in (("m1", v1), ("m2", v2)):
        need(
            _close(vehicles[name].mass, check[key]),
            f"{key} = {check[key]} kg, the scene's {name} has {vehicles[name].mass} kg",
        )
    need(
        params["restitution"] == check["restitution"],
        f"restitution {check['restitution']}, the scene has {params['restitution']}",
    )
    need(
        params["restitution_mode"] == check.get("mode", "total"),
        f"mode {check.get('mode', 'total')}, the scene has {params['restitution_mode']}",
    )
    for key, name in (("v1", v1), ("v2", v2)):
        s = _initial(result, name)
        want = [*check[key], 0.0][:3]
        need(
            _close(s["velocity"], want),
            f"{key} = {want}, the scene's {name} has {s['velocity'].tolist()}",
        )
        need(not np.any(s["angular_velocity"]), f"{name} starts without spin")
    if planar:
        need(
            params["friction"] == check["friction"],
            f"friction {check['friction']}, the scene has {params['friction']}",
        )
        normal = params["normal"]
        need(
            normal is not None
            and not isinstance(normal, str)
            and _close(normal, [*check["normal"], 0.0]),
            f"normal {check['normal']}, the scene has {normal!r}",
        )
        owner, point = params["centroid"] if isinstance(params["centroid"], tuple) else (None, None)
        spec = check["centroid"]
        need(
            owner == spec["vehicle"] and _close(point, spec["point"]),
            f"centroid {spec}, the scene has {params['centroid']!r}",
        )
        for key, izz, name in (("x1", "izz1", v1), ("x2", "izz2", v2)):
            s = _initial(result, name)
            need(
                _close(s["position"][:2], check[key]),
                f"{key} = {check[key]}, the scene's {name} starts at {s['position'][:2].tolist()}",
            )
            inertia = vehicles[name].inertia
            need(
                _close(inertia[2, 2], check[izz]) and not np.any(inertia[2, :2]),
                f"{izz} = {check[izz]} kg m^2 about a principal vertical axis, the scene's "
                f"{name} has {inertia.tolist()}",
            )
            heading = check["headings"][name]
            q = s["orientation"]
            want_q = [
                math.cos(math.radians(heading) / 2),
                0,
                0,
                math.sin(math.radians(heading) / 2),
            ]
            need(_close(q, want_q), f"{name} heading {heading} deg")
        z = {n: _initial(result, n)["position"][2] for n in (v1, v2)}
        need(
            abs(z[v1] - z[v2]) <= 1e-12 and spec["point"][2] == 0.0,
            "both CGs and the centroid at one height (a planar problem)",
        )
    return problems


def collinear_expected(check: dict[str, Any]) -> dict[str, Any]:
    """A central collinear impact: delta-V1 = -(1 + eps) m2 / (m1 + m2) v_n n, delta-V2 =
    (1 + eps) m1 / (m1 + m2) v_n n, no rotation, energy (1 - eps^2) m1 m2 / (m1 + m2) v_n^2 / 2,
    v_n the closing speed along n."""
    m1, m2, eps = check["m1"], check["m2"], check["restitution"]
    n = np.array([*check["normal"], 0.0][:3], dtype=np.float64)
    vn = float((np.array([*check["v1"], 0.0][:3]) - np.array([*check["v2"], 0.0][:3])) @ n)
    reduced = m1 * m2 / (m1 + m2)
    jn = (1.0 + eps) * reduced * vn
    v1, v2 = check["vehicle_1"], check["vehicle_2"]
    return {
        "exchanges": 1,
        "impacts": [
            {
                "vehicles": [v1, v2],
                "secondary": False,
                "sliding": False,
                "normal": _vec(n),
                "closing_speed": vn,
                "impulse": _vec(jn * n),
                "energy_dissipated": 0.5 * (1.0 - eps * eps) * reduced * vn * vn,
                "parties": {
                    v1: {"delta_v": _vec(-jn / m1 * n), "delta_omega": [0.0, 0.0, 0.0]},
                    v2: {"delta_v": _vec(jn / m2 * n), "delta_omega": [0.0, 0.0, 0.0]},
                },
            }
        ],
    }


def _cross(a: np.ndarray, b: np.ndarray) -> float:
    return float(a[0] * b[1] - a[1] * b[0])


def eccentric_expected(check: dict[str, Any], exchange_time: float) -> dict[str, Any]:
    """A planar eccentric impact, both vehicles without spin, the centroid P fixed in one
    vehicle's body frame and a fixed horizontal normal n, everything at one height.

    At the exchange time te the CGs are at x_i + v_i te and P at the owner's CG plus its
    body point turned by its heading; r_i = P - x_i(te); u = v1 - v2. Frictionless (mu = 0):
    J = (1 + eps) m_eff (u.n) n with 1/m_eff = 1/m1 + 1/m2 + (r1 x n)^2 / Izz1 +
    (r2 x n)^2 / Izz2 (Newton and Kudlich-Slibar agree). With friction the impact must be full
    (the sticking impulse inside the cone; checked here): J = (1 + eps) K^-1 u
    (Kudlich-Slibar) or K^-1 (u + eps (u.n) n) (Newton), K = (1/m1 + 1/m2) E +
    sum_i [[ry^2, -rx ry], [-rx ry, rx^2]] / Izz_i. J acts on vehicle 2, -J on vehicle 1:
    delta-V_i = -/+ J / m_i, delta-omega_i = r_i x (-/+ J) / Izz_i; the energy lost is the
    kinetic energy before minus after."""
    v1n, v2n = check["vehicle_1"], check["vehicle_2"]
    m = np.array([check["m1"], check["m2"]], dtype=np.float64)
    izz = np.array([check["izz1"], check["izz2"]], dtype=np.float64)
    x = [np.array(check["x1"], dtype=np.float64), np.array(check["x2"], dtype=np.float64)]
    v = [np.array(check["v1"], dtype=np.float64), np.array(check["v2"], dtype=np.float64)]
    n = np.array(check["normal"], dtype=np.float64)
    eps, mu = check["restitution"], check["friction"]
    spec = check["centroid"]
    owner = 0 if spec["vehicle"] == v1n else 1
    h = math.radians(check["headings"][spec["vehicle"]])
    rot = np.array([[math.cos(h), -math.sin(h)], [math.sin(h), math.cos(h)]])
    at = [x[i] + v[i] * exchange_time for i in range(2)]
    p = at[owner] + rot @ np.array(spec["point"][:2], dtype=np.float64)
    r = [p - at[0], p - at[1]]
    u = v[0] - v[1]
    un = float(u @ n)
    k = (1.0 / m[0] + 1.0 / m[1]) * np.eye(2)
    for i in range(2):
        rx, ry = r[i]
        k += np.array([[ry * ry, -rx * ry], [-rx * ry, rx * rx]]) / izz[i]
    flags: dict[str, bool] = {}
    if mu == 0.0:
        inv_meff = 1.0 / m[0] + 1.0 / m[1] + sum(_cross(r[i], n) ** 2 / izz[i] for i in range(2))
        j = (1.0 + eps) * un / inv_meff * n
    else:
        jc = np.linalg.solve(k, u)
        jn = float(jc @ n)
        if not np.linalg.norm(jc - jn * n) <= mu * jn:
            raise ValueError("the closed form covers full impacts only: raise the friction")
        if check.get("mode", "total") == "total":
            j = (1.0 + eps) * jc
        else:
            j = np.linalg.solve(k, u + eps * un * n)
        flags["sliding"] = False
    dv = [-j / m[0], j / m[1]]
    dw = [_cross(r[0], -j) / izz[0], _cross(r[1], j) / izz[1]]
    before = 0.5 * sum(m[i] * v[i] @ v[i] for i in range(2))
    after = 0.5 * sum(
        m[i] * (v[i] + dv[i]) @ (v[i] + dv[i]) + izz[i] * dw[i] ** 2 for i in range(2)
    )
    z = check["height"]
    parties = {
        name: {
            "delta_v": [*_vec(dv[i]), 0.0],
            "delta_omega": [0.0, 0.0, dw[i]],
            "yaw_rate_change_deg_s": math.degrees(dw[i]),
        }
        for i, name in enumerate((v1n, v2n))
    }
    return {
        "exchanges": 1,
        "impacts": [
            {
                "vehicles": [v1n, v2n],
                "secondary": False,
                **flags,
                "centroid": [*_vec(p), z],
                "normal": [*_vec(n), 0.0],
                "closing_speed": un,
                "impulse": [*_vec(j), 0.0],
                "energy_dissipated": float(before - after),
                "parties": parties,
            }
        ],
    }


# -- checks ----------------------------------------------------------------------------------


def check_values(run: Run, check: dict[str, Any], _: Callable[[], Path]) -> list[str]:
    return compare(check["expected"], run.figures, check["tolerances"])


def check_collinear(run: Run, check: dict[str, Any], _: Callable[[], Path]) -> list[str]:
    problems = _check_inputs(run, check, planar=False)
    if problems:
        return problems
    return compare(collinear_expected(check), run.figures, check["tolerances"])


def check_eccentric(run: Run, check: dict[str, Any], _: Callable[[], Path]) -> list[str]:
    problems = _check_inputs(run, check, planar=True)
    if problems:
        return problems
    if not run.result.impacts:
        return ["no exchange: the closed form expects one"]
    expected = eccentric_expected(check, run.result.impacts[0].time)
    failures = compare(expected, run.figures, check["tolerances"])
    # the first overlap of the boxes, worked out by hand in the check
    t0 = run.figures["impacts"][0]["first_contact_time"]
    want = check["first_contact_time"]
    if not abs(t0 - want["value"]) <= want["abs"]:
        failures.append(
            f"impacts[0].first_contact_time: expected {want['value']!r} s "
            f"(+- {want['abs']:g} s), got {t0!r} s"
        )
    return failures


def check_mirror(run: Run, check: dict[str, Any], tmp: Callable[[], Path]) -> list[str]:
    scene = run.scene_file.path
    assert scene is not None
    if check["scene"] == "auto":
        other = mirror_run(scene, tmp())
    else:
        other = run_scene(SCENES / check["scene"])
    return compare(mirror_figures(run.figures), other.figures, check["tolerances"])


CHECKS: dict[str, Callable[[Run, dict[str, Any], Callable[[], Path]], list[str]]] = {
    "values": check_values,
    "collinear": check_collinear,
    "eccentric": check_eccentric,
    "mirror": check_mirror,
}


def run_case(name: str, tmp: Callable[[], Path] | None = None) -> list[str]:
    """Run one case and apply all its checks: the failures, each prefixed by its check's
    source (empty: the case passes). ``tmp`` makes a fresh folder for mirrored scenes."""
    case = load_case(name)
    run = run_scene(SCENES / case["scene"])
    if tmp is None:

        def tmp() -> Path:
            return Path(tempfile.mkdtemp(prefix=f"regression-{name}-"))

    failures = []
    for check in case["checks"]:
        kind = check["kind"]
        if kind not in CHECKS:
            failures.append(f"unknown check kind {kind!r} (known: {', '.join(CHECKS)})")
            continue
        for f in CHECKS[kind](run, check, tmp):
            failures.append(f"[{check.get('source', kind)}] {f}")
    return failures


def provenance() -> dict[str, str]:
    """Where golden values were minted (written into each golden check)."""
    return {
        "crashsim_version": cs.__version__,
        "python": platform.python_version(),
        "numpy": np.__version__,
        "machine": f"{platform.system()} {platform.machine()}",
    }
