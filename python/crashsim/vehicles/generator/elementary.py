"""Deterministic elementary functions of the generator: cos and sin by a fixed polynomial,
piecewise-linear interpolation and the side view's filleted polylines (d, z in m), written
with +, -, *, / and sqrt only in a fixed order, so the same parameters give the same bits on
any IEEE-754 machine.
"""

from __future__ import annotations

import math

import numpy as np
from numpy.typing import NDArray

Array = NDArray[np.float64]

_FILLET = 0.25  # side-view fillets use up to this share of each adjacent profile segment
_FILLET_MAX = 0.35  # ... and at most this path length (m)

# -- deterministic elementary functions -------------------------------------------------------


def _cos_sin(theta: Array) -> tuple[Array, Array]:
    """cos and sin of angles in [0, pi] (rad) by fixed Taylor polynomials (error < 1e-16).

    Only + - * / in a fixed order, so the bits do not depend on the platform's libm or on
    numpy's SIMD paths."""
    theta = np.asarray(theta, dtype=np.float64)
    flip = theta > math.pi / 2.0
    x = np.where(flip, math.pi - theta, theta)  # in [0, pi/2]
    x2 = x * x
    s = np.ones_like(x)
    c = np.ones_like(x)
    for k in range(13, 0, -1):
        s = 1.0 - x2 * s / float((2 * k) * (2 * k + 1))
        c = 1.0 - x2 * c / float((2 * k - 1) * (2 * k))
    return np.where(flip, -c, c), x * s


def _interp(xq: Array, xp: Array, fp: Array) -> Array:
    """Piecewise-linear interpolation of (xp, fp) at xq (xp strictly increasing, xq inside).
    Written out (not np.interp) so the arithmetic is fixed; flat pieces give exact values."""
    i = np.clip(np.searchsorted(xp, xq, side="right") - 1, 0, len(xp) - 2)
    x0, x1, f0, f1 = xp[i], xp[i + 1], fp[i], fp[i + 1]
    return f0 + (xq - x0) / (x1 - x0) * (f1 - f0)


def _filleted(points: list[tuple[float, float]], per_corner: int) -> tuple[Array, Array]:
    """A polyline (d, z) with strictly increasing d whose interior corners are replaced by
    quadratic Bezier fillets sampled at per_corner points (the ends are kept)."""
    pts = np.array(points, dtype=np.float64)
    out = [pts[0]]
    for k in range(1, len(pts) - 1):
        a, b, c = pts[k - 1], pts[k], pts[k + 1]
        # lengths written out: a BLAS dot product may fuse multiply-adds on some machines
        ux, uz, vx, vz = (float(t) for t in (b[0] - a[0], b[1] - a[1], c[0] - b[0], c[1] - b[1]))
        la = math.sqrt(ux * ux + uz * uz)
        lc = math.sqrt(vx * vx + vz * vz)
        f = min(_FILLET * la, _FILLET * lc, _FILLET_MAX)
        p0 = b + (a - b) * (f / la)
        p2 = b + (c - b) * (f / lc)
        t = np.arange(per_corner + 1, dtype=np.float64) / per_corner
        u = 1.0 - t
        curve = (u * u)[:, None] * p0 + (2.0 * u * t)[:, None] * b + (t * t)[:, None] * p2
        out.extend(curve)
    out.append(pts[-1])
    poly = np.array(out)
    return poly[:, 0], poly[:, 1]
