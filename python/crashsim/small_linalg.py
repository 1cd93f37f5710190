"""Products of small vectors and matrices (3-vectors, 3 x 3 rotations, N x 3 points) in one
fixed order of operations, so that what crashsim builds and reports is the same bits whichever
BLAS kernel and SIMD level numpy runs on this CPU. (The C library's sin, atan2... may still
differ between CPUs with and without FMA: with glibc's FMA variants turned off
(GLIBC_TUNABLES), the two jointed-vehicle cases of scripts/result_fingerprint.py change.)

numpy's ``@``, ``dot`` and ``linalg.norm`` call OpenBLAS, which picks its kernels for the CPU
when it loads (``OPENBLAS_CORETYPE``: Prescott, Haswell, SkylakeX, ...), and the kernels
round differently (a fused multiply-add or not, another order of the sums). Measured on
crashsim 111d543: a walking pedestrian's joint frames differ in the 17th digit between the
three kernels, and a 0.3 s strike then ends with 44 or 50 impacts (the chain tumbles
differently). Here every product is an element-wise multiply (one rounding each, the same
everywhere) and a sum over the short axis in index order, which numpy does the same way
whatever SIMD it dispatches to. ``tests/test_small_linalg.py`` runs the scenes under several
kernels and compares the bits.
"""

from __future__ import annotations

from collections.abc import Callable

import numpy as np
from numpy.typing import ArrayLike, NDArray

Array = NDArray[np.float64]


def matmul(a: ArrayLike, b: ArrayLike) -> Array:
    """``a @ b`` (numpy's rules for 1-D and stacked operands), summed in index order."""
    x = np.asarray(a, dtype=np.float64)
    y = np.asarray(b, dtype=np.float64)
    if x.ndim == 0 or y.ndim == 0:
        raise ValueError("matmul: scalar operands are not allowed, use '*'")
    if y.ndim == 1:
        return dot(x, y)  # (..., m, n) @ (n,): each row with y
    if x.ndim == 1:
        return np.sum(x[:, None] * y, axis=-2)  # (n,) @ (..., n, k)
    return np.sum(x[..., :, :, None] * y[..., None, :, :], axis=-2)


def dot(a: ArrayLike, b: ArrayLike) -> Array:
    """The sum of the products over the last axis (a float array; 0-D for two vectors)."""
    return np.sum(np.asarray(a, dtype=np.float64) * np.asarray(b, dtype=np.float64), axis=-1)


def norm(v: ArrayLike) -> Array:
    """The Euclidean length over the last axis (0-D for a vector)."""
    x = np.asarray(v, dtype=np.float64)
    return np.sqrt(np.sum(x * x, axis=-1))



def rotation_about(axis: ArrayLike, sin: float, cos: float) -> Array:
    """The 3 x 3 rotation about the unit ``axis`` by the angle whose sine and cosine are
    given (Rodrigues: I + sin K + (1 - cos) K K, K the cross-product matrix of the axis)."""
    k = np.asarray(axis, dtype=np.float64)
    kx = np.array([[0.0, -k[2], k[1]], [k[2], 0.0, -k[0]], [-k[1], k[0], 0.0]])
    return np.eye(3) + sin * kx + (1.0 - cos) * matmul(kx, kx)

def transform_points(points: ArrayLike, transform: ArrayLike) -> Array:
    """Points (N, 3) moved by a 4 x 4 homogeneous transform: ``R p + t`` for each."""
    m = np.asarray(transform, dtype=np.float64)
    return matmul(np.asarray(points, dtype=np.float64), m[:3, :3].T) + m[:3, 3]


def by_libm(fn: Callable[[float], float], x: ArrayLike) -> Array:
    """``fn`` (one of Python's ``math`` functions: the C library's) applied to each element.
    numpy's own sin, cos, arccos, power... run its SIMD code for the CPU, which rounds
    differently from one CPU to the next (measured: a slerp's arccos and sin changed a
    Result's orientations between samples when numpy's AVX2 and AVX-512 code was turned
    off); the C library's are the ones the engine and Python's math use."""
    a = np.asarray(x, dtype=np.float64)
    return np.fromiter((fn(float(v)) for v in a.ravel()), np.float64, a.size).reshape(a.shape)
