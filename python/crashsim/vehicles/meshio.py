"""Loading vehicle meshes and reporting their quality.

Real vehicle meshes come from 3-D stores, CAD exports and scans in any unit and axis
convention, made of many shells, mostly open, sometimes with non-manifold edges. This module
brings such a file into the *model frame* (m; x forward, y left, z up, right-handed) and
counts what is wrong with it, without repairing anything silently.

    mesh = load_mesh("car.glb", units="cm", up="y", forward="-z", ground=True)
    print(mesh_quality(mesh))

Definitions used by :class:`MeshQuality` (all counts exact, on the mesh after coincident
vertices are merged):

- an *edge* is an unordered pair of vertices joined by at least one face;
- an *open* (boundary) edge belongs to exactly one face, a *non-manifold* edge to three or
  more; the mesh is *watertight* when every edge belongs to exactly two faces;
- a *shell* is a connected component of faces, two faces being connected when they share an
  edge that belongs to exactly two faces (trimesh's ``face_adjacency``; a non-manifold edge
  does not join shells);
- a shell is *closed* when each of its edges belongs to exactly two of its faces;
  ``closed_shells_filled`` also counts shells that become closed once their holes of three
  or four edges are filled (trimesh's ``split`` with its default repair);
- a face is *degenerate* when its area is zero to round-off: twice its area is at most
  1e-10 times the square of its longest edge (a repeated vertex, or three collinear ones);
- a face is a *duplicate* when an earlier face has the same three vertices, in any order
  or winding;
- the winding is *consistent* when every edge shared by exactly two faces is traversed in
  opposite directions by them.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from os import PathLike
from pathlib import Path
from typing import Any

import numpy as np
import trimesh
from numpy.typing import NDArray

from crashsim.errors import MeshError, ParameterError
from crashsim.filekind import special_file
from crashsim.small_linalg import transform_points
from crashsim.units import FOOT
from crashsim.vehicles.plausibility import check_size

__all__ = [
    "UNITS",
    "MeshQuality",
    "MeshSource",
    "axes_rotation",
    "check_mesh",
    "closed_shells",
    "describe",
    "load_mesh",
    "mesh_quality",
    "shell_labels",
    "unit_scale",
]

Array = NDArray[np.float64]
MeshSource = str | PathLike[str] | trimesh.Trimesh | trimesh.Scene

# Metres per file unit.
UNITS: dict[str, float] = {"m": 1.0, "cm": 0.01, "mm": 0.001, "in": 0.0254, "ft": FOOT}

_AXES = {"x": 0, "y": 1, "z": 2}

# Twice a face's area at most this times its longest edge squared: zero to round-off.
DEGENERATE_RATIO = 1e-10

# Largest accepted |coordinate|, in file units and in metres. No vehicle mesh comes near it
# in any unit (a bus in mm reaches 1.3e4, one placed in UTM coordinates in mm 1e10 would
# not pass: move it near the origin); beyond about 9e10 trimesh's vertex merging, which
# rounds to 1e-8 of a unit in 64-bit integers, overflows (a RuntimeWarning and garbage).
MAX_COORDINATE = 1e9

# Bytes of a mesh file read to check its header before trimesh reads the file (a PLY header
# must end within them).
HEADER_BYTES = 1 << 20


# -- units and axes ----------------------------------------------------------------------------


def unit_scale(units: str | float) -> float:
    """Metres per file unit: one of "m", "cm", "mm", "in", "ft", or a finite positive
    number (e.g. 0.001 for a file in millimetres)."""
    if isinstance(units, str):
        try:
            return UNITS[units.strip().lower()]
        except KeyError:
            raise ParameterError(
                f"units = {units!r} is unknown: use one of {', '.join(UNITS)} or a number "
                "of metres per file unit"
            ) from None
    if isinstance(units, bool) or not isinstance(units, int | float | np.floating):
        raise ParameterError(
            f"units must be a unit name ({', '.join(UNITS)}) or metres per file unit, got {units!r}"
        )
    scale = float(units)
    if not math.isfinite(scale) or scale <= 0.0:
        raise ParameterError(
            f"units = {scale} is invalid: metres per file unit must be finite and positive"
        )
    return scale


def _axis(value: str, name: str) -> Array:
    """The file-frame unit vector named by "x", "+y", "-z", ..."""
    if not isinstance(value, str):
        raise ParameterError(f"{name} must be an axis name such as 'z', 'y' or '-x', got {value!r}")
    text = value.strip().lower()
    sign = -1.0 if text.startswith("-") else 1.0
    letter = text.lstrip("+-")
    if letter not in _AXES or len(text) - len(letter) > 1:
        raise ParameterError(
            f"{name} = {value!r} is not an axis: use x, y or z with an optional sign "
            "('z', '-y', '+x')"
        )
    out = np.zeros(3)
    out[_AXES[letter]] = sign
    return out


def axes_rotation(up: str = "z", forward: str = "x") -> Array:
    """The rotation R (3, 3) taking file coordinates to model coordinates, p_model = R p_file.

    up: the file axis that points up (model +z); forward: the file axis that points to the
    vehicle's front (model +x). Model +y (left) is up x forward, so R is always a proper
    rotation; up and forward on the same axis (e.g. "z" and "-z") are refused.
    """
    z = _axis(up, "up")
    x = _axis(forward, "forward")
    if abs(float(x @ z)) > 0.0:
        raise ParameterError(
            f"up = {up!r} and forward = {forward!r} are on the same axis: they must be two "
            "different axes (e.g. up='y', forward='-z')"
        )
    y = np.cross(z, x)
    return np.vstack([x, y, z])


# -- loading -------------------------------------------------------------------------------------


def _flatten(loaded: Any, what: str) -> trimesh.Trimesh:
    """One Trimesh from what trimesh returned: a Scene is flattened with its node
    transforms applied; anything else without triangles (a point cloud, a path) is refused."""
    if isinstance(loaded, trimesh.Scene):
        meshes = [g for g in loaded.geometry.values() if isinstance(g, trimesh.Trimesh)]
        if not meshes or not any(len(g.faces) for g in meshes):
            raise MeshError(f"{what} has no triangles: a vehicle needs a surface mesh")
        if hasattr(loaded, "to_mesh"):  # trimesh >= 4.6
            loaded = loaded.to_mesh()
        else:  # pragma: no cover - older trimesh
            loaded = loaded.dump(concatenate=True)
    if not isinstance(loaded, trimesh.Trimesh):
        raise MeshError(
            f"{what} holds a {type(loaded).__name__}, not a triangle mesh: "
            "give a surface mesh (PLY, STL, OBJ, OFF, GLB, ...)"
        )
    return loaded


def check_mesh(mesh: trimesh.Trimesh, what: str) -> None:
    """MeshError unless the mesh has triangles whose indices name its vertices, and finite
    vertices no farther than MAX_COORDINATE from the origin."""
    if len(mesh.faces) == 0:
        raise MeshError(f"{what} has no triangles: a vehicle needs a surface mesh")
    vertices = np.asarray(mesh.vertices, dtype=np.float64)
    if vertices.ndim != 2 or vertices.shape[1] != 3:
        raise MeshError(
            f"{what} has vertices of {vertices.shape[1] if vertices.ndim == 2 else '?'} "
            "coordinates: a vehicle mesh needs x, y, z (the file is damaged or not 3-D)"
        )
    faces = np.asarray(mesh.faces)
    if faces.ndim != 2 or faces.shape[1] != 3:
        raise MeshError(f"{what} has faces of shape {faces.shape}: a vehicle needs triangles")
    outside = (faces < 0) | (faces >= len(vertices))
    if np.any(outside):
        k = int(np.flatnonzero(np.any(outside, axis=1))[0])
        raise MeshError(
            f"{what} has {int(np.any(outside, axis=1).sum())} faces naming vertices it does not "
            f"have (it has {len(vertices)}), the first is face {k} = {faces[k].tolist()}: the "
            "file is damaged or truncated"
        )
    bad = ~np.all(np.isfinite(vertices), axis=1)
    if np.any(bad):
        i = int(np.flatnonzero(bad)[0])
        raise MeshError(
            f"{what} has {int(bad.sum())} non-finite (NaN or inf) vertices, the first is "
            f"vertex {i} = {vertices[i].tolist()}: repair or remove them"
        )
    largest = float(np.max(np.abs(vertices))) if vertices.size else 0.0
    if largest > MAX_COORDINATE:
        raise MeshError(
            f"{what} has a coordinate of {largest:.3g}, beyond the {MAX_COORDINATE:.0e} that "
            "any vehicle mesh stays within in any unit (a bus in mm reaches 1.3e4): the "
            "file's units or scale are wrong, or the mesh sits far from the origin (move it "
            "there)"
        )


def _ply_header(head: bytes, size: int) -> str | None:
    lines = head.split(b"\n", 2)
    if lines[0].rstrip(b"\r") != b"ply":
        return 'it does not start with the line "ply"'
    words = lines[1].split() if len(lines) > 1 else []
    if len(words) != 3 or words[0] != b"format" or words[1] not in PLY_ENCODINGS:
        return (
            'its second line is not "format ascii 1.0" (or binary_little_endian, '
            "binary_big_endian)"
        )
    if not any(line.strip() == b"end_header" for line in head.split(b"\n")[:-1]):
        return f"its header does not end (end_header) within its first {HEADER_BYTES:,} bytes"
    return None


def _stl_header(head: bytes, size: int) -> str | None:
    if head.lstrip()[:5].lower() == b"solid":  # ASCII
        return None
    count = int.from_bytes(head[80:84], "little") if size >= 84 else 0
    if size == 84 + 50 * count:  # binary: an 80-byte header, the count, 50 bytes a triangle
        return None
    return (
        'it is neither ASCII (starting with "solid") nor binary (84 bytes and 50 a triangle: '
        f"{84 + 50 * count:,} bytes for the {count:,} triangles its header gives, not {size:,})"
    )


def _text_header(head: bytes, size: int) -> str | None:
    return "it holds NUL bytes, and the format is text" if b"\0" in head else None


def _off_header(head: bytes, size: int) -> str | None:
    lines = (line.split(b"#", 1)[0].strip() for line in head.split(b"\n"))
    first = next((line for line in lines if line), b"")
    if not (first.split() or [b""])[0].upper().endswith(b"OFF") or b"\0" in head:
        return 'it does not start with "OFF" (or COFF, NOFF, ...)'
    return None


def _glb_header(head: bytes, size: int) -> str | None:
    if head[:4] != b"glTF" or int.from_bytes(head[4:8], "little") != 2:
        return 'it does not start with "glTF" and version 2'
    return None


PLY_ENCODINGS = (b"ascii", b"binary_little_endian", b"binary_big_endian")
# A cheap check per suffix of the file's first HEADER_BYTES (and its size), before trimesh,
# whose loaders read the whole file first: a 1 GB file of zeros named .ply took 24 s and
# 8.5 GB to be refused.
_HEADERS = {
    "ply": _ply_header,
    "stl": _stl_header,
    "obj": _text_header,
    "off": _off_header,
    "glb": _glb_header,
}


def _check_header(path: Path, what: str) -> None:
    """MeshError when the start of the file cannot be its format's (by its suffix)."""
    suffix = path.suffix.lower().lstrip(".")
    check = _HEADERS.get(suffix)
    if check is None:
        return
    try:
        with open(path, "rb") as f:
            head = f.read(HEADER_BYTES)
        size = path.stat().st_size
    except OSError as e:
        raise MeshError(f"cannot read {what}: {e.strerror or e}") from e
    why = check(head, size)
    if why is not None:
        raise MeshError(f"{what} is not a .{suffix} file: {why}")


def describe(source: MeshSource) -> str:
    """How error messages name a mesh source."""
    if isinstance(source, trimesh.Trimesh | trimesh.Scene):
        return f"the given {type(source).__name__}"
    return f"the mesh file {str(Path(source))!r}"


def load_mesh(
    source: MeshSource,
    *,
    units: str | float = "m",
    up: str = "z",
    forward: str = "x",
    ground: bool = False,
    center: bool = False,
) -> trimesh.Trimesh:
    """A mesh in the model frame (m; x forward, y left, z up), from a file in any format
    trimesh reads (PLY, STL, OBJ, OFF, GLB/glTF, ...) or from a trimesh.Trimesh/Scene.

    A scene is flattened with its node transforms. The vertices are checked as written (no
    triangles, a NaN/inf vertex, a coordinate beyond MAX_COORDINATE or a largest extent in
    metres under 1 mm or over 10 km, which no vehicle has, is a MeshError naming the units
    that would fit), then coincident vertices are merged (files
    split corners at texture and normal seams; the engine needs the shared corners) and
    nothing else is repaired. The input object is never modified.

    units: metres per file unit, a name ("m", "cm", "mm", "in", "ft") or a number.
    up, forward: the file axes that are the vehicle's up and front ("z", "-y", ...); the
    defaults ("z", "x") keep the file's axes.
    ground: default False; True shifts the mesh so its lowest point is at z = 0.
    center: default False; True centres its bounding box at x = y = 0.
    Order: scale, rotate, then ground and center.
    """
    scale = unit_scale(units)
    rotation = axes_rotation(up, forward)
    what = describe(source)
    if isinstance(source, trimesh.Trimesh | trimesh.Scene):
        mesh = _flatten(source, what).copy()  # the caller's object is left as it was
    else:
        path = Path(source)
        kind = special_file(path)
        if kind is not None:
            raise MeshError(f"{what} is {kind}, not a file: give the mesh file itself")
        if not path.is_file():
            raise MeshError(f"no mesh file at {str(path)!r}: check the path")
        _check_header(path, what)
        try:
            # process=False: check the vertices as written before trimesh repairs anything.
            loaded: Any = trimesh.load_scene(path, process=False)
        except Exception as e:  # trimesh raises many kinds; name the file that failed
            raise MeshError(
                f"trimesh could not read {what} ({type(e).__name__}: {e}): "
                "give a mesh in a format trimesh reads (PLY, STL, OBJ, OFF, GLB, ...)"
            ) from e
        mesh = _flatten(loaded, what)
    check_mesh(mesh, what)
    # Before merging (which joins vertices within 1e-8 of a unit: a tiny mesh would become
    # one point): no vehicle is under 1 mm or over 10 km, whatever the file's units.
    used = units.strip().lower() if isinstance(units, str) else f"{scale:g} m per unit"
    raw = np.asarray(mesh.vertices, dtype=np.float64)
    check_size(np.ptp(raw, axis=0) * scale, what, scale, used)
    # Geometry only: corners split for texture coordinates or normals are joined.
    mesh.merge_vertices(merge_tex=True, merge_norm=True)
    transform = np.eye(4)
    transform[:3, :3] = rotation * scale
    if not np.array_equal(transform, np.eye(4)):
        mesh.vertices = transform_points(mesh.vertices, transform)
        check_mesh(mesh, what + f" scaled to metres ({scale:g} m per unit)")
    shift = np.zeros(3)
    lo, hi = mesh.bounds
    if ground:
        shift[2] = -lo[2]
    if center:
        shift[:2] = -(lo[:2] + hi[:2]) / 2.0
    if np.any(shift != 0.0):
        mesh.apply_translation(shift)
    return mesh


# -- the quality report -------------------------------------------------------------------------


@dataclass(frozen=True)
class MeshQuality:
    """What is wrong (or right) with a mesh; see the module docstring for the definitions.

    Counts are exact. ``volume`` (m^3) is the enclosed volume when the mesh is watertight
    with a consistent winding (negative when the faces point inwards), else None.
    ``extents``: length, width, height of the axis-aligned bounding box (m).
    """

    triangles: int
    vertices: int
    edges: int
    shells: int
    closed_shells: int
    closed_shells_filled: int
    watertight: bool
    open_edges: int
    nonmanifold_edges: int
    degenerate_faces: int
    duplicate_faces: int
    winding_consistent: bool
    volume: float | None
    extents: tuple[float, float, float]

    @property
    def is_volume(self) -> bool:
        """Watertight, consistently wound and enclosing a positive volume."""
        return self.volume is not None and self.volume > 0.0

    def __str__(self) -> str:
        def yes(flag: bool) -> str:
            return "yes" if flag else "no"

        length, width, height = self.extents
        filled = ""
        if self.closed_shells_filled != self.closed_shells:
            filled = f", {self.closed_shells_filled} after filling 3- and 4-edge holes"
        volume = "-" if self.volume is None else f"{self.volume:.4g} m^3"
        return "\n".join(
            [
                f"{self.triangles} triangles, {self.vertices} vertices, "
                f"{length:.3f} x {width:.3f} x {height:.3f} m",
                f"  shells: {self.shells}, closed {self.closed_shells}{filled}",
                f"  watertight: {yes(self.watertight)}  (open edges {self.open_edges}, "
                f"non-manifold edges {self.nonmanifold_edges})",
                f"  winding consistent: {yes(self.winding_consistent)}  "
                f"(degenerate faces {self.degenerate_faces}, "
                f"duplicate faces {self.duplicate_faces})",
                f"  volume: {volume}",
            ]
        )


def _edge_index(faces: NDArray[np.int64]) -> tuple[NDArray[np.int64], NDArray[np.int64]]:
    """(the unique edge of each face side, face order (3 n,)); faces per unique edge)."""
    n = int(faces.max()) + 1 if faces.size else 1
    a = faces.reshape(-1)
    b = faces[:, [1, 2, 0]].reshape(-1)
    keys = np.minimum(a, b) * n + np.maximum(a, b)  # one int64 per unordered vertex pair
    _, inverse, counts = np.unique(keys, return_inverse=True, return_counts=True)
    return inverse.reshape(-1), counts


def _closed_per_shell(
    faces: NDArray[np.int64], labels: NDArray[np.int64], n_shells: int
) -> NDArray[np.bool_]:
    """For each shell: True when each of its edges belongs to exactly two of its faces."""
    edge, _ = _edge_index(faces)
    side_shell = np.repeat(labels, 3)
    pairs, counts = np.unique(edge * n_shells + side_shell, return_counts=True)
    closed = np.ones(n_shells, dtype=bool)
    closed[pairs[counts != 2] % n_shells] = False
    return closed


def _closed(faces: NDArray[np.int64]) -> bool:
    """True when every edge of these faces belongs to exactly two of them."""
    return bool(np.all(_edge_index(faces)[1] == 2))


def shell_labels(mesh: trimesh.Trimesh) -> NDArray[np.int64]:
    """The shell of each face, 0 .. shells - 1 (faces joined by two-face edges)."""
    return np.asarray(
        trimesh.graph.connected_component_labels(mesh.face_adjacency, node_count=len(mesh.faces)),
        dtype=np.int64,
    )


def _duplicates(faces: NDArray[np.int64]) -> int:
    """Faces whose three vertices (in any order) repeat an earlier face's."""
    rows = np.sort(faces, axis=1)
    rows = rows[np.lexsort(rows.T[::-1])]
    return int(np.count_nonzero(np.all(rows[1:] == rows[:-1], axis=1)))


def mesh_quality(mesh: trimesh.Trimesh) -> MeshQuality:
    """The quality report of a mesh as it is (no merging or repair here)."""
    faces = np.asarray(mesh.faces, dtype=np.int64)
    vertices = np.asarray(mesh.vertices, dtype=np.float64)
    if len(faces) == 0:
        raise MeshError("the mesh has no triangles: there is nothing to report on")
    _, counts = _edge_index(faces)
    labels = shell_labels(mesh)
    n_shells = int(labels.max()) + 1
    closed = _closed_per_shell(faces, labels, n_shells)
    filled = int(closed.sum())
    for k in np.flatnonzero(~closed):
        filled += bool(mesh.submesh([np.flatnonzero(labels == k)], repair=True)[0].is_watertight)
    tri = vertices[faces]
    double_area = np.linalg.norm(np.cross(tri[:, 1] - tri[:, 0], tri[:, 2] - tri[:, 0]), axis=1)
    longest = np.max(
        [np.sum((tri[:, i] - tri[:, (i + 1) % 3]) ** 2, axis=1) for i in range(3)], axis=0
    )
    degenerate = int(np.count_nonzero(double_area <= DEGENERATE_RATIO * longest))
    duplicates = _duplicates(faces)
    watertight = bool(np.all(counts == 2))
    winding = bool(mesh.is_winding_consistent)
    volume = None
    if watertight and winding:
        with np.errstate(invalid="ignore", divide="ignore"):  # trimesh's centroid of volume 0
            volume = float(mesh.volume)
    extents = vertices.max(axis=0) - vertices.min(axis=0)
    return MeshQuality(
        triangles=len(faces),
        vertices=len(vertices),
        edges=len(counts),
        shells=n_shells,
        closed_shells=int(closed.sum()),
        closed_shells_filled=int(filled),
        watertight=watertight,
        open_edges=int(np.count_nonzero(counts == 1)),
        nonmanifold_edges=int(np.count_nonzero(counts > 2)),
        degenerate_faces=degenerate,
        duplicate_faces=int(duplicates),
        winding_consistent=winding,
        volume=volume,
        extents=(float(extents[0]), float(extents[1]), float(extents[2])),
    )


def closed_shells(mesh: trimesh.Trimesh) -> list[trimesh.Trimesh]:
    """The closed shells of a mesh (each edge in exactly two of the shell's faces), each
    as its own Trimesh and oriented outwards (a shell enclosing a negative volume is
    flipped; one wound inconsistently is re-wound by trimesh's fix_winding). Open shells
    are left out; no hole is filled."""
    faces = np.asarray(mesh.faces, dtype=np.int64)
    if len(faces) == 0:
        return []
    labels = shell_labels(mesh)
    closed = _closed_per_shell(faces, labels, int(labels.max()) + 1)
    out = []
    for k in np.flatnonzero(closed):
        shell = mesh.submesh([np.flatnonzero(labels == k)], append=True, repair=False)
        if not shell.is_winding_consistent:
            trimesh.repair.fix_winding(shell)  # a copy: the caller's mesh is left alone
        with np.errstate(invalid="ignore", divide="ignore"):  # a zero-volume shell's centroid
            inverted = shell.volume < 0.0
        if inverted:
            shell.invert()
        out.append(shell)
    return out
