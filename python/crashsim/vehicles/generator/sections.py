"""The generator's cross-sections: at each station along the body a simple polygon in the
y-z plane (m, model frame: y left, z up), all with the same number of points and structure
(underside, wheel-arch notch, sill rounding, side wall, greenhouse leaning in by the
tumblehome, rounded roof or hood, mirrored in y), and the resolution that sets their counts.
"""

from __future__ import annotations

import math

import numpy as np
from numpy.typing import NDArray

from crashsim.errors import ParameterError
from crashsim.vehicles.generator.elementary import _cos_sin
from crashsim.vehicles.generator.params import (
    _SILL_RADIUS,
    _STEP,
    BodyParams,
    _profiles,
    _stations,
)

Array = NDArray[np.float64]

_CROWN = 0.012  # roof crown as a fraction of the width (limited by the local top height)


# -- cross-sections ---------------------------------------------------------------------------


def _counts(resolution: float) -> dict[str, int]:
    """Points per part of a half cross-section."""

    def n(base: float, least: int) -> int:
        return max(least, round(base * resolution))

    return {
        "bottom": n(2, 1),
        "notch": n(1, 1),
        "corner": n(3, 2),
        "wall": n(3, 2),
        "side": n(2, 1),
        "fillet": n(3, 2),
        "roof": n(3, 2),
    }


def body_sections(p: BodyParams, resolution: float = 1.0) -> tuple[Array, Array]:
    """The loft of the body: x (k,) strictly increasing (m, model frame) and the sections
    (k, n, 2) as (y, z) points (m), each a simple polygon, counter-clockwise seen from +x."""
    res = _resolution(resolution)
    d = _stations(p, res)
    prof = _profiles(p, d)
    half = p.width / 2.0
    s = prof["scale"][:, None]
    zb = prof["z_bottom"][:, None]
    zn = prof["z_notch"][:, None]
    zs = prof["z_shoulder"][:, None]
    zt = prof["z_top"][:, None]
    cnt = _counts(res)
    parts_y: list[Array] = []
    parts_z: list[Array] = []

    def add(y: Array, z: Array) -> None:
        y, z = np.broadcast_arrays(y, z)
        parts_y.append(y)
        parts_z.append(z)

    def frac(n: int, first: int = 1) -> Array:
        """j / n for j = first..n as a (1, n - first + 1) row."""
        return (np.arange(first, n + 1, dtype=np.float64) / n)[None, :]

    y_inner = (half - p.arch_depth) * s  # inner wall of the arch notch at the underside
    # 1. underside from the centre line (excluded) to the arch's inner wall
    add(y_inner * frac(cnt["bottom"]), zb)
    # 2. the arch's inner wall, bevelled by _STEP
    y_step = y_inner + _STEP * s
    add(y_step, zn)
    # 3. underside of the notch (points strictly between the wall and the sill rounding)
    y_corner = (half - _SILL_RADIUS) * s
    t = frac(cnt["notch"] + 1)[:, :-1]
    add(y_step + (y_corner - y_step) * t, zn)
    # 4. sill rounding: a quarter ellipse (half axes _SILL_RADIUS * scale, _SILL_RADIUS)
    phi = np.arange(cnt["corner"] + 1, dtype=np.float64) * (math.pi / 2.0 / cnt["corner"])
    c, sn = _cos_sin(phi)  # phi = 0: bottom of the rounding, pi/2: foot of the wall
    add(y_corner + (_SILL_RADIUS * s) * sn[None, :], zn + _SILL_RADIUS * (1.0 - c[None, :]))
    # 5. vertical side wall up to the shoulder
    w = half * s
    z_foot = zn + _SILL_RADIUS
    add(w, z_foot + (zs - z_foot) * frac(cnt["wall"]))
    # 6. greenhouse side (leaning in by the tumblehome) up to the start of the roof fillet
    green = np.minimum((zt - zs) / (p.height - p.beltline), 1.0)
    w_top = (half - p.tumblehome * green) * s
    crown = np.minimum(_CROWN * p.width, 0.3 * (zt - zs))
    kz = zt - crown  # roof edge corner K = (w_top, kz)
    ay, az = w, zs
    side = np.sqrt((ay - w_top) ** 2 + (az - kz) ** 2)
    f_side = np.minimum(p.shoulder_radius, 0.45 * side)
    psy = w_top + (ay - w_top) * (f_side / side)
    psz = kz + (az - kz) * (f_side / side)
    add(ay + (psy - ay) * frac(cnt["side"]), az + (psz - az) * frac(cnt["side"]))
    # 7. shoulder fillet: quadratic Bezier from Ps over K to Pe on the roof
    f_roof = np.minimum(p.shoulder_radius, 0.45 * w_top)
    pey = w_top - f_roof
    pez = zt - crown * (pey / w_top) ** 2
    tb = frac(cnt["fillet"])
    ub = 1.0 - tb
    add(
        ub * ub * psy + 2.0 * ub * tb * w_top + tb * tb * pey,
        ub * ub * psz + 2.0 * ub * tb * kz + tb * tb * pez,
    )
    # 8. crowned roof (or hood, deck) towards the centre line (excluded)
    t = frac(cnt["roof"] + 1)[:, :-1]
    ry = pey - pey * t
    add(ry, zt - crown * (ry / w_top) ** 2)
    hy = np.concatenate(parts_y, axis=1)
    hz = np.concatenate(parts_z, axis=1)
    k = len(d)
    zeros = np.zeros((k, 1))
    y = np.concatenate([zeros, hy, zeros, -hy[:, ::-1]], axis=1)
    z = np.concatenate([zb, hz, zt, hz[:, ::-1]], axis=1)
    x = p.length / 2.0 - d[::-1]  # x increases; d = 0 is the front face at x = length / 2
    sections = np.stack([y[::-1], z[::-1]], axis=2)
    _check_sections(sections, p)
    return x, sections


def _check_sections(sections: Array, p: BodyParams) -> None:
    """Internal guard of what makes each section a simple polygon: its y > 0 half climbs from
    the underside to the roof (z never decreases, and where it stays level y grows) with every
    point but the two on the centre line at y > 0; the other half is its mirror image."""
    n = sections.shape[1]
    half = sections[:, : n // 2 + 1, :]  # bottom centre ... top centre, y >= 0
    dy = np.diff(half[..., 0], axis=1)
    dz = np.diff(half[..., 1], axis=1)
    climbs = (dz > 1e-9) | ((dz >= 0.0) & (dy > 1e-9))
    if not np.all(climbs) or np.any(half[:, 1:-1, 0] <= 0.0):
        raise ParameterError(
            f"the {p.preset} parameters give a degenerate cross-section: {p.as_dict()} "
            "(please report this with the parameters)"
        )


def _resolution(resolution: float) -> float:
    if isinstance(resolution, bool) or not isinstance(resolution, int | float):
        raise ParameterError(f"resolution must be a number, got {resolution!r}")
    res = float(resolution)
    if not math.isfinite(res) or not 0.25 <= res <= 8.0:
        raise ParameterError(
            f"resolution = {resolution} is invalid: give a number in [0.25, 8] (1 = default, "
            "a few thousand triangles; the count grows about as resolution squared)"
        )
    return res
