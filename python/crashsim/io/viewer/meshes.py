"""Meshes and arrays for the case viewer: decimation for display, quantization and packing.

The page draws meshes, it does not compute with them: every figure on it comes from the run
(poses, impacts) or the report. So a mesh is reduced for display only:

- **Decimation by vertex clustering** (:func:`decimate`): the vertices are binned in a cubic
  grid, each occupied cell becomes one vertex (the mean of its members), triangles whose
  corners fall into fewer than three cells vanish, and repeated triangles are dropped. The
  cell is the smallest (found by bisection on its size) that leaves at most
  ``max_triangles``. Deterministic and numpy only. A mesh within the budget is kept whole.
- **Quantization** (:func:`pack_mesh`): positions become unsigned 16-bit integers over the
  mesh's bounding box (a step of extent / 65535 per axis: 76 um for a 5 m car), indices
  16-bit when there are at most 65536 vertices, else 32-bit.
- **Packing** (:func:`pack_array`): raw little-endian bytes, deflated (zlib) and base64
  encoded; the page inflates them with the browser's own DecompressionStream.
"""

from __future__ import annotations

import base64
import math
import zlib
from typing import Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

__all__ = ["DEFAULT_MAX_TRIANGLES", "decimate", "pack_array", "pack_mesh"]

Array = NDArray[np.float64]

# Triangles kept per body on the page (docs/viewer.md: page size and time to first draw).
DEFAULT_MAX_TRIANGLES = 60_000

_DTYPES = {"f8": "<f8", "f4": "<f4", "u2": "<u2", "u4": "<u4", "u1": "u1"}
_BISECTIONS = 24  # halvings of the cell-size bracket (relative 2^-24 of its width)


def pack_array(values: ArrayLike, dtype: str) -> dict[str, Any]:
    """An array as the page reads it: {"dtype", "count", "b64"} with the raw little-endian
    bytes of ``values`` (flattened, cast to ``dtype``: "f8", "f4", "u2", "u4" or "u1")
    deflated (zlib) and base64-encoded."""
    a = np.ascontiguousarray(np.asarray(values).reshape(-1), dtype=_DTYPES[dtype])
    data = zlib.compress(a.tobytes(), 9)
    return {"dtype": dtype, "count": int(a.size), "b64": base64.b64encode(data).decode("ascii")}


def unpack_array(packed: dict[str, Any]) -> NDArray[Any]:
    """The inverse of :func:`pack_array` (for tests and tools)."""
    data = zlib.decompress(base64.b64decode(packed["b64"]))
    return np.frombuffer(data, dtype=_DTYPES[packed["dtype"]]).copy()


def _cluster(
    vertices: Array, faces: NDArray[np.int64], cell: float
) -> tuple[Array, NDArray[np.int64]]:
    """Vertex clustering on a grid of ``cell`` m: (vertices, faces) with every vertex moved to
    the mean of its cell, degenerate and repeated triangles dropped, unused vertices gone."""
    lo = vertices.min(axis=0)
    ijk = np.floor((vertices - lo) / cell).astype(np.int64)
    dims = ijk.max(axis=0) + 1
    key = (ijk[:, 0] * dims[1] + ijk[:, 1]) * dims[2] + ijk[:, 2]
    _, cluster = np.unique(key, return_inverse=True)
    cluster = cluster.reshape(-1)
    f = cluster[faces]
    keep = (f[:, 0] != f[:, 1]) & (f[:, 1] != f[:, 2]) & (f[:, 0] != f[:, 2])
    f = f[keep]
    # a triangle repeated (in any order of its corners) is drawn once
    _, first = np.unique(np.sort(f, axis=1), axis=0, return_index=True)
    f = f[np.sort(first)]
    used, f = np.unique(f, return_inverse=True)
    f = f.reshape(-1, 3)
    counts = np.bincount(cluster, minlength=int(cluster.max()) + 1).astype(np.float64)
    sums = np.stack(
        [np.bincount(cluster, weights=vertices[:, k], minlength=counts.size) for k in range(3)],
        axis=1,
    )
    mean = sums / counts[:, None]
    return mean[used], f.astype(np.int64)


def decimate(
    vertices: ArrayLike, faces: ArrayLike, max_triangles: int
) -> tuple[Array, NDArray[np.int64]]:
    """A display copy of a triangle mesh with at most ``max_triangles`` triangles (vertices
    (n, 3) m, faces (m, 3)): the mesh itself (unused vertices dropped) when it is within
    the budget, else the vertex clustering on the finest grid that meets it."""
    v = np.asarray(vertices, dtype=np.float64).reshape(-1, 3)
    f = np.asarray(faces, dtype=np.int64).reshape(-1, 3)
    if max_triangles < 1:
        raise ValueError("max_triangles must be at least 1")  # internal misuse
    if len(f) <= max_triangles:
        used, inverse = np.unique(f, return_inverse=True)
        return v[used], inverse.reshape(-1, 3).astype(np.int64)
    extent = float(np.max(np.ptp(v, axis=0)))
    if extent == 0.0:
        return v[:1], np.zeros((0, 3), dtype=np.int64)
    # bracket: a cell as large as the mesh leaves nothing; a tiny one keeps nearly all
    hi = extent
    lo = extent * 1e-6
    best = _cluster(v, f, hi)
    for _ in range(_BISECTIONS):
        mid = math.sqrt(lo * hi)  # bisect the size's logarithm
        out = _cluster(v, f, mid)
        if len(out[1]) <= max_triangles:
            hi, best = mid, out
        else:
            lo = mid
        if hi / lo < 1.0 + 1e-3:
            break
    return best


def pack_mesh(
    vertices: ArrayLike, faces: ArrayLike, max_triangles: int = DEFAULT_MAX_TRIANGLES
) -> dict[str, Any]:
    """A mesh (body frame, m) for the page: decimated to ``max_triangles``, positions
    quantized to 16 bits over its bounding box, packed. Keys: ``triangles_source``,
    ``triangles``, ``vertices``, ``lo`` and ``step`` (m; position = lo + step * q),
    ``positions`` (u2, 3 per vertex), ``indices`` (u2 or u4, 3 per triangle)."""
    source = np.asarray(faces).reshape(-1, 3)
    v, f = decimate(vertices, source, max_triangles)
    lo = v.min(axis=0) if len(v) else np.zeros(3)
    span = (v.max(axis=0) - lo) if len(v) else np.zeros(3)
    step = np.where(span > 0.0, span / 65535.0, 1.0)
    q = np.rint((v - lo) / step).clip(0, 65535)
    return {
        "triangles_source": int(len(source)),
        "triangles": int(len(f)),
        "vertices": int(len(v)),
        "lo": [float(x) for x in lo],
        "step": [float(x) for x in step],
        "positions": pack_array(q, "u2"),
        "indices": pack_array(f, "u2" if len(v) <= 65536 else "u4"),
    }
