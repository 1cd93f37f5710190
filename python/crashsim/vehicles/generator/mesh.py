"""The generator's meshes: loft (a closed, outward-wound trimesh through cross-sections along
x, model frame in m) and ply_bytes (a mesh as byte-exact binary little-endian PLY).
"""

from __future__ import annotations

from collections.abc import Mapping
from typing import Any

import numpy as np
import trimesh
from numpy.typing import NDArray

from crashsim.errors import MeshError

Array = NDArray[np.float64]


# -- the loft ---------------------------------------------------------------------------------


def loft(x: Array, sections: Array) -> trimesh.Trimesh:
    """A closed, outward-wound mesh through cross-sections along x (model frame, m).

    x: (k,) strictly increasing, k >= 2. sections: (k, n, 2) points (y, z), n >= 3, each a
    simple polygon counter-clockwise seen from +x, point j of one section joined to point j of
    the next. Each end is closed by a fan from the centre of its section's bounding box, so
    the end sections must be star-shaped from there (a convex section is). Vertices: the
    sections in order, then the two fan centres (rear end, front end). Quads are split so
    that mirror-symmetric sections (about y = 0) give a mirror-symmetric mesh.
    """
    x = np.asarray(x, dtype=np.float64)
    sections = np.asarray(sections, dtype=np.float64)
    if x.ndim != 1 or len(x) < 2 or sections.shape[:1] != x.shape:
        raise MeshError("loft needs k >= 2 stations x and k sections (k, n, 2)")
    if sections.ndim != 3 or sections.shape[2] != 2 or sections.shape[1] < 3:
        raise MeshError(f"loft sections must be (k, n >= 3, 2), got {sections.shape}")
    if not (np.all(np.isfinite(x)) and np.all(np.isfinite(sections))):
        raise MeshError("loft stations and sections must be finite")
    if np.any(np.diff(x) <= 0.0):
        raise MeshError("loft stations x must be strictly increasing")
    k, n, _ = sections.shape
    ends = []
    for i in (0, k - 1):
        sec = sections[i]
        centre = (sec.min(axis=0) + sec.max(axis=0)) / 2.0
        a = sec - centre
        b = np.roll(sec, -1, axis=0) - centre
        if np.any(a[:, 0] * b[:, 1] - a[:, 1] * b[:, 0] <= 0.0):
            raise MeshError(
                f"loft end section {i} is not counter-clockwise and star-shaped about the "
                "centre of its bounding box: its end cap would fold"
            )
        ends.append(centre)
    xs = np.repeat(x, n)
    vertices = np.concatenate(
        [
            np.column_stack([xs, sections.reshape(-1, 2)]),
            [[x[0], ends[0][0], ends[0][1]], [x[-1], ends[1][0], ends[1][1]]],
        ]
    )
    i = np.arange(k - 1)[:, None] * n
    j = np.arange(n)[None, :]
    a = (i + j).ravel()
    b = (i + (j + 1) % n).ravel()
    c = a + n
    dd = b + n
    # Split each quad along the diagonal b-c where its mean y >= 0 and along a-dd where it is
    # below: mirrored quads get mirrored diagonals, so a left-right symmetric set of sections
    # gives a mirror-symmetric mesh (no spurious products of inertia or normal tilt).
    flat = sections.reshape(-1, 2)
    left = flat[a, 0] + flat[b, 0] + flat[c, 0] + flat[dd, 0] >= 0.0
    sides = np.concatenate(
        [
            np.column_stack([a, b, c])[left],
            np.column_stack([b, dd, c])[left],
            np.column_stack([a, b, dd])[~left],
            np.column_stack([a, dd, c])[~left],
        ]
    )
    rear_c, front_c = k * n, k * n + 1
    jj = np.arange(n)
    rear = np.column_stack([np.full(n, rear_c), (jj + 1) % n, jj])
    front = np.column_stack([np.full(n, front_c), (k - 1) * n + jj, (k - 1) * n + (jj + 1) % n])
    faces = np.concatenate([sides, rear, front]).astype(np.int64)
    return trimesh.Trimesh(vertices=vertices, faces=faces, process=False)


# -- binary PLY -------------------------------------------------------------------------------


def ply_bytes(mesh: trimesh.Trimesh, comments: Mapping[str, Any] | None = None) -> bytes:
    """The mesh as a binary little-endian PLY (float64 vertices, int32 indices), byte-exact
    for the same arrays; ``comments`` become "comment key=value" header lines."""
    vertices = np.ascontiguousarray(mesh.vertices, dtype="<f8")
    faces = np.asarray(mesh.faces)
    lines = ["ply", "format binary_little_endian 1.0"]
    for key, value in (comments or {}).items():
        text = f"{key}={value!r}" if isinstance(value, float) else f"{key}={value}"
        if "\n" in text:
            raise ValueError("a PLY comment must be one line")
        lines.append(f"comment {text}")
    lines += [
        f"element vertex {len(vertices)}",
        "property double x",
        "property double y",
        "property double z",
        f"element face {len(faces)}",
        "property list uchar int vertex_indices",
        "end_header",
    ]
    header = ("\n".join(lines) + "\n").encode("ascii")
    record = np.dtype([("n", "u1"), ("v", "<i4", (3,))])
    face_data = np.empty(len(faces), dtype=record)
    face_data["n"] = 3
    face_data["v"] = faces
    return header + vertices.tobytes() + face_data.tobytes()
