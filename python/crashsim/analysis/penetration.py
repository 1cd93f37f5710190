"""The depth-of-penetration toolkit: the two-mass spring model of a collinear impact.

Two bodies (masses m1, m2, kg) each carry a linear crush spring (k1, k2, N/m) and meet at a
closing speed v_rel (m/s). While the springs are compressed the total crush C_T = C1 + C2 (m)
obeys a simple harmonic oscillator with the reduced mass m' and the series stiffness k'; the
"depth of penetration" dt_p = sqrt(m'/k') (s) is the time for which two rigid shapes would
pass through each other at the closing speed to produce the same maximum total crush.
Equation numbers (eq. N) refer to the seed note on the depth-of-penetration parameter
(/work/shared/seed/000_005cd8f78e215b1b.txt); docs/model.md ("What a user gets back") lists
the toolkit.

Every function takes floats or numpy arrays, broadcasts them against each other, and returns
a float when all inputs are scalars, else a float64 array. SI units throughout: kg, m, s, N,
rad; stiffness k in N/m, CRASH3 coefficients A in N/m and B in N/m^2, energies in J. Bad
numbers (non-finite, non-positive masses, stiffnesses or widths, negative crush, ...) raise
``crashsim.errors.ParameterError``.
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

from crashsim.errors import ParameterError

__all__ = [
    "SAE_880223_INTERCEPT",
    "SAE_880223_SLOPE",
    "angular_frequency",
    "contact_duration",
    "crush_energy",
    "crush_split",
    "depth_of_penetration",
    "depth_of_penetration_from_b",
    "depth_of_penetration_from_crush",
    "effective_mass",
    "effective_mass_along",
    "effective_mass_factor",
    "max_crush_from_residual",
    "max_total_crush",
    "max_vehicle_crush",
    "pdof_correction",
    "reduced_mass",
    "residual_crush_from_max",
    "series_stiffness",
    "spring_stiffness",
    "time_of_max_engagement",
    "total_crush",
    "vehicle_crush",
]

Array = NDArray[np.float64]
Real = float | Array

# SAE 880223 (frontal barrier tests, as quoted by the seed): C_max = 3.5 in + 1.14 C_residual.
SAE_880223_INTERCEPT = 0.0889  # m: 3.5 in (1 in = 0.0254 m exactly)
SAE_880223_SLOPE = 1.14  # dimensionless

# CRASH3 practice caps the PDOF energy correction 1 + tan^2(alpha) at 2, i.e. |alpha| <= 45 deg.
DEFAULT_ANGLE_LIMIT = math.pi / 4.0  # rad


# --- input checks -------------------------------------------------------------------------


def _num(name: str, value: Any, unit: str) -> Array:
    """``value`` as a finite float64 array; ParameterError otherwise."""
    if isinstance(value, bool | np.bool_) or (
        isinstance(value, np.ndarray) and value.dtype == np.bool_
    ):
        raise ParameterError(f"{name} must be a number ({unit}), got a boolean {value!r}")
    try:
        a = np.asarray(value, dtype=np.float64)
    except (TypeError, ValueError) as e:
        raise ParameterError(
            f"{name} must be a number or an array of numbers ({unit}), got {value!r}"
        ) from e
    bad = ~np.isfinite(a)
    if bad.any():
        raise ParameterError(f"{name} must be finite ({unit}), got {a[bad].flat[0]}")
    return a


def _positive(name: str, value: Any, unit: str) -> Array:
    a = _num(name, value, unit)
    bad = a <= 0.0
    if bad.any():
        raise ParameterError(f"{name} must be > 0 {unit}, got {a[bad].flat[0]}")
    return a


def _nonnegative(name: str, value: Any, unit: str) -> Array:
    a = _num(name, value, unit)
    bad = a < 0.0
    if bad.any():
        raise ParameterError(f"{name} must be >= 0 {unit}, got {a[bad].flat[0]}")
    return a


def _out(a: Array) -> Real:
    """A Python float for a 0-d result, the array otherwise."""
    return float(a) if np.ndim(a) == 0 else a


# --- the spring model (seed eqs. 14-36) ----------------------------------------------------


def reduced_mass(m1: ArrayLike, m2: ArrayLike) -> Real:
    """Reduced mass m' = m1 m2 / (m1 + m2), kg (eq. 21). Masses in kg, > 0."""
    a = _positive("m1", m1, "kg")
    b = _positive("m2", m2, "kg")
    return _out(a * b / (a + b))


def series_stiffness(k1: ArrayLike, k2: ArrayLike) -> Real:
    """Series stiffness k' = k1 k2 / (k1 + k2), N/m (eq. 20): two crush springs in series.
    Stiffnesses in N/m, > 0."""
    a = _positive("k1", k1, "N/m")
    b = _positive("k2", k2, "N/m")
    return _out(a * b / (a + b))


def spring_stiffness(B: ArrayLike, width: ArrayLike) -> Real:
    """Spring stiffness k = B W, N/m, of a face with CRASH3 coefficient B (N/m^2, > 0) over a
    width W (m, > 0) of direct contact (seed, "From k to B")."""
    b = _positive("B", B, "N/m^2")
    w = _positive("width", width, "m")
    return _out(b * w)


def _mk(m1: ArrayLike, m2: ArrayLike, k1: ArrayLike, k2: ArrayLike) -> tuple[Array, Array]:
    """(m', k') as arrays after checking all four."""
    a1 = _positive("m1", m1, "kg")
    a2 = _positive("m2", m2, "kg")
    s1 = _positive("k1", k1, "N/m")
    s2 = _positive("k2", k2, "N/m")
    return a1 * a2 / (a1 + a2), s1 * s2 / (s1 + s2)


def angular_frequency(m1: ArrayLike, m2: ArrayLike, k1: ArrayLike, k2: ArrayLike) -> Real:
    """omega = sqrt(k'/m'), rad/s (eq. 19): the angular frequency of the total crush's
    oscillation (eq. 18). Masses kg, stiffnesses N/m."""
    m, k = _mk(m1, m2, k1, k2)
    return _out(np.sqrt(k / m))


def depth_of_penetration(m1: ArrayLike, m2: ArrayLike, k1: ArrayLike, k2: ArrayLike) -> Real:
    """Depth-of-penetration time dt_p = sqrt(m'/k'), s (eq. 28) = (2/pi) t_max (eq. 27).
    Masses kg (use effective masses for non-central impacts), stiffnesses N/m."""
    m, k = _mk(m1, m2, k1, k2)
    return _out(np.sqrt(m / k))


def depth_of_penetration_from_b(
    m1: ArrayLike, m2: ArrayLike, B1: ArrayLike, B2: ArrayLike, width: ArrayLike
) -> Real:
    """dt_p = sqrt(m'/k'), s (eq. 28) with k_i = B_i W: masses m1, m2 (kg), the struck faces'
    CRASH3 B coefficients B1, B2 (N/m^2) and the common engagement width W (m)."""
    w = _positive("width", width, "m")
    b1 = _positive("B1", B1, "N/m^2")
    b2 = _positive("B2", B2, "N/m^2")
    m, k = _mk(m1, m2, b1 * w, b2 * w)
    return _out(np.sqrt(m / k))


def depth_of_penetration_from_crush(closing_speed: ArrayLike, total_max_crush: ArrayLike) -> Real:
    """dt_p = C_T(t_max) / v_rel, s (eq. 29 solved for dt_p): the depth of penetration that
    reproduces a total maximum crush C_T (m, >= 0; the sum of both vehicles' maximum crush,
    see ``max_crush_from_residual``) at closing speed v_rel (m/s, > 0)."""
    v = _positive("closing_speed", closing_speed, "m/s")
    c = _nonnegative("total_max_crush", total_max_crush, "m")
    return _out(c / v)


def time_of_max_engagement(m1: ArrayLike, m2: ArrayLike, k1: ArrayLike, k2: ArrayLike) -> Real:
    """t_max = (pi/2) sqrt(m'/k'), s (eq. 25): the time from first contact to maximum crush,
    where the bodies reach a common velocity. Masses kg, stiffnesses N/m."""
    m, k = _mk(m1, m2, k1, k2)
    return _out(0.5 * math.pi * np.sqrt(m / k))


def contact_duration(m1: ArrayLike, m2: ArrayLike, k1: ArrayLike, k2: ArrayLike) -> Real:
    """pi sqrt(m'/k') = 2 t_max, s: the time the (perfectly elastic) springs stay in contact,
    half a period of eq. 24. Masses kg, stiffnesses N/m."""
    m, k = _mk(m1, m2, k1, k2)
    return _out(math.pi * np.sqrt(m / k))


def _sine(t: ArrayLike, omega: Array) -> Array:
    """sin(omega t) during contact (0 <= omega t <= pi), 0 after it; t in s, >= 0."""
    tt = _nonnegative("t", t, "s")
    phase = omega * tt
    return np.where(phase <= math.pi, np.sin(np.minimum(phase, math.pi)), 0.0)


def total_crush(
    t: ArrayLike,
    closing_speed: ArrayLike,
    m1: ArrayLike,
    m2: ArrayLike,
    k1: ArrayLike,
    k2: ArrayLike,
) -> Real:
    """Total crush C_T(t) = v_rel sqrt(m'/k') sin(sqrt(k'/m') t), m (eq. 24).

    t: time since first contact, s (>= 0); closing_speed v_rel: m/s (>= 0); masses kg;
    stiffnesses N/m. The springs are linear and elastic, so after the contact ends at
    t = pi sqrt(m'/k') (``contact_duration``) they are apart and the crush is 0."""
    v = _nonnegative("closing_speed", closing_speed, "m/s")
    m, k = _mk(m1, m2, k1, k2)
    return _out(v * np.sqrt(m / k) * _sine(t, np.sqrt(k / m)))


def max_total_crush(
    closing_speed: ArrayLike, m1: ArrayLike, m2: ArrayLike, k1: ArrayLike, k2: ArrayLike
) -> Real:
    """Maximum total crush C_T(t_max) = v_rel dt_p, m (eqs. 26, 29). closing_speed m/s (>= 0),
    masses kg, stiffnesses N/m."""
    v = _nonnegative("closing_speed", closing_speed, "m/s")
    m, k = _mk(m1, m2, k1, k2)
    return _out(v * np.sqrt(m / k))


def crush_split(total: ArrayLike, k1: ArrayLike, k2: ArrayLike) -> tuple[Real, Real]:
    """Each vehicle's share (C1, C2), m, of a total crush C_T (m, >= 0):
    C1 = k2/(k1+k2) C_T, C2 = k1/(k1+k2) C_T (eqs. 14-15; at t_max eqs. 34-35), so that
    k1 C1 = k2 C2 (equal and opposite forces). The softer vehicle takes more crush.

    k1, k2 in N/m; only their ratio matters, so B coefficients (N/m^2) over a common width
    give the same split."""
    c = _nonnegative("total crush", total, "m")
    a = _positive("k1", k1, "N/m")
    b = _positive("k2", k2, "N/m")
    s = a + b
    return _out(b / s * c), _out(a / s * c)


def vehicle_crush(
    t: ArrayLike,
    closing_speed: ArrayLike,
    m1: ArrayLike,
    m2: ArrayLike,
    k1: ArrayLike,
    k2: ArrayLike,
) -> tuple[Real, Real]:
    """Each vehicle's crush against time (C1(t), C2(t)), m (eqs. 30-31):
    C_i(t) = v_rel sqrt(k' m') / k_i sin(sqrt(k'/m') t). Arguments as ``total_crush``;
    0 after the contact ends."""
    v = _nonnegative("closing_speed", closing_speed, "m/s")
    s1 = _positive("k1", k1, "N/m")
    s2 = _positive("k2", k2, "N/m")
    m, k = _mk(m1, m2, s1, s2)
    amplitude = v * np.sqrt(k * m)
    sine = _sine(t, np.sqrt(k / m))
    return _out(amplitude / s1 * sine), _out(amplitude / s2 * sine)


def max_vehicle_crush(
    closing_speed: ArrayLike, m1: ArrayLike, m2: ArrayLike, k1: ArrayLike, k2: ArrayLike
) -> tuple[Real, Real]:
    """Each vehicle's maximum crush (C1(t_max), C2(t_max)) = v_rel sqrt(k' m') / k_i, m
    (eqs. 32-33), equal to the split of v_rel dt_p (eqs. 34-35). closing_speed m/s, masses kg,
    stiffnesses N/m."""
    v = _nonnegative("closing_speed", closing_speed, "m/s")
    s1 = _positive("k1", k1, "N/m")
    s2 = _positive("k2", k2, "N/m")
    m, k = _mk(m1, m2, s1, s2)
    amplitude = v * np.sqrt(k * m)
    return _out(amplitude / s1), _out(amplitude / s2)


# --- effective mass (non-central impacts) --------------------------------------------------


def effective_mass_factor(mass: ArrayLike, inertia: ArrayLike, lever_arm: ArrayLike) -> Real:
    """gamma = k_g^2 / (k_g^2 + h^2) (dimensionless, in (0, 1]) with k_g^2 = I/m (seed,
    "Non-central collisions"; no equation number there).

    mass m: kg (> 0); inertia I: yaw moment of inertia about the vertical axis through the CG,
    kg m^2 (> 0); lever_arm h: the perpendicular distance from the CG to the line of action
    of the impulse in the ground plane, m (finite; its sign does not matter). gamma = 1 for a
    central impact (h = 0) and tends to 0 as h grows: the effective mass gamma m is what the
    impulse "sees" along its line of action when the body can also turn."""
    m = _positive("mass", mass, "kg")
    i = _positive("inertia", inertia, "kg m^2")
    h = _num("lever_arm", lever_arm, "m")
    kg2 = i / m
    return _out(kg2 / (kg2 + h * h))


def effective_mass(mass: ArrayLike, inertia: ArrayLike, lever_arm: ArrayLike) -> Real:
    """Planar effective mass gamma m = m k_g^2 / (k_g^2 + h^2), kg (seed, "Non-central
    collisions"), for use as m1 or m2 in the spring model of a non-central impact. Arguments
    as ``effective_mass_factor``."""
    m = _positive("mass", mass, "kg")
    i = _positive("inertia", inertia, "kg m^2")
    h = _num("lever_arm", lever_arm, "m")
    return _out(m * i / (i + m * h * h))


def effective_mass_along(mass: ArrayLike, inertia: ArrayLike, r: ArrayLike, n: ArrayLike) -> Real:
    """Three-dimensional effective mass along a direction, kg:
    m_eff = 1 / (1/m + (r x n) . I^-1 (r x n)).

    mass m: kg (> 0), shape (...); inertia I: the 3x3 inertia tensor about the CG (kg m^2,
    symmetric positive definite), shape (..., 3, 3); r: from the CG to the impulse centroid,
    m, shape (..., 3); n: the impulse direction (normalised here; non-zero), shape (..., 3).
    I, r and n in one frame (world or body). This is 1 / (n . K n) for one body's part of
    the collision matrix K (docs/model.md); for a horizontal r and n and a principal vertical
    axis it equals ``effective_mass(m, I_zz, h)`` with h = |(r x n)_z|. The reduced
    effective mass of a pair along n is ``reduced_mass(m1_eff, m2_eff)``."""
    m = _positive("mass", mass, "kg")
    tensor = _num("inertia", inertia, "kg m^2")
    rr = _num("r", r, "m")
    nn = _num("n", n, "1")
    if tensor.ndim < 2 or tensor.shape[-2:] != (3, 3):
        raise ParameterError(f"inertia must be a 3x3 tensor (..., 3, 3), got shape {tensor.shape}")
    for name, vec in (("r", rr), ("n", nn)):
        if vec.ndim < 1 or vec.shape[-1] != 3:
            raise ParameterError(f"{name} must be a 3-vector (..., 3), got shape {vec.shape}")
    if not np.allclose(tensor, np.swapaxes(tensor, -1, -2), rtol=1e-9, atol=0.0):
        raise ParameterError("inertia must be a symmetric tensor (kg m^2)")
    try:
        np.linalg.cholesky(tensor)
    except np.linalg.LinAlgError as e:
        raise ParameterError("inertia must be positive definite (kg m^2)") from e
    length = np.linalg.norm(nn, axis=-1, keepdims=True)
    if (length == 0.0).any():
        raise ParameterError("n must be a non-zero direction")
    rn = np.cross(rr, nn / length)
    lead = np.broadcast_shapes(tensor.shape[:-2], rn.shape[:-1])
    tensor = np.broadcast_to(tensor, (*lead, 3, 3))
    rn = np.broadcast_to(rn, (*lead, 3))
    x = np.linalg.solve(tensor, rn[..., None])[..., 0]
    return _out(1.0 / (1.0 / m + np.sum(rn * x, axis=-1)))


# --- maximum and residual crush (SAE 880223) ------------------------------------------------


def max_crush_from_residual(residual: ArrayLike) -> Real:
    """Maximum (dynamic) crush from residual crush, m: C_max = 0.0889 m + 1.14 C_residual
    (SAE 880223, a fit to frontal barrier tests: 3.5 in + 1.14 C_residual). residual in m,
    >= 0."""
    c = _nonnegative("residual crush", residual, "m")
    return _out(SAE_880223_INTERCEPT + SAE_880223_SLOPE * c)


def residual_crush_from_max(maximum: ArrayLike) -> Real:
    """Residual crush from maximum crush, m: C_residual = (C_max - 0.0889 m) / 1.14, the
    inverse of ``max_crush_from_residual`` (SAE 880223). maximum in m, >= 0. Below 0.0889 m
    (3.5 in) the relation predicts no permanent crush and this returns 0."""
    c = _nonnegative("maximum crush", maximum, "m")
    return _out(np.maximum(c - SAE_880223_INTERCEPT, 0.0) / SAE_880223_SLOPE)


# --- CRASH3 crush energy --------------------------------------------------------------------


def pdof_correction(angle: ArrayLike, angle_limit: float | None = DEFAULT_ANGLE_LIMIT) -> Real:
    """CRASH3 energy correction factor 1 + tan^2(alpha) (dimensionless, >= 1).

    angle alpha: rad, between the principal direction of force and the normal of the
    damaged face (|alpha| < pi/2; for a side face this is the PDOF minus 90 deg). CRASH3
    practice caps the factor at 2, i.e. |alpha| is limited to 45 deg: with the default
    angle_limit = pi/4 a larger |alpha| is treated as 45 deg. angle_limit=None applies the
    factor uncapped; any other limit must lie in [0, pi/2)."""
    a = np.abs(_num("angle", angle, "rad"))
    bad = a >= 0.5 * math.pi
    if bad.any():
        raise ParameterError(
            f"angle = {a[bad].flat[0]} rad: the force must make less than 90 deg with the face "
            "normal (|alpha| < pi/2); a force along the face crushes nothing"
        )
    if angle_limit is not None:
        lim = float(_nonnegative("angle_limit", angle_limit, "rad"))
        if lim >= 0.5 * math.pi:
            raise ParameterError(f"angle_limit = {lim} rad must be < pi/2 (or None: no limit)")
        a = np.minimum(a, lim)
    t = np.tan(a)
    return _out(1.0 + t * t)


def crush_energy(
    A: ArrayLike,
    B: ArrayLike,
    profile: ArrayLike,
    width: ArrayLike,
    angle: ArrayLike = 0.0,
    angle_limit: float | None = DEFAULT_ANGLE_LIMIT,
) -> Real:
    """CRASH3 crush energy, J, of one vehicle's damage.

    A: N/m (>= 0), B: N/m^2 (> 0), the damaged face's CRASH3 coefficients. profile: 2, 4 or 6
    crush depths C1..Cn (m, >= 0) measured at equal spacing across the damage width L
    (width, m, > 0), C1 and Cn at its ends; the last axis of an array holds the points, the
    leading axes broadcast against A, B, width and angle. The profile is taken as
    piecewise linear between the points and the energy is the integral over the width of
    the energy per unit width A C + B C^2 / 2 + A^2 / (2 B); each of the n - 1 segments of
    length d = L / (n - 1) between depths a and b contributes, in closed form,
        d [A (a + b) / 2 + B (a^2 + a b + b^2) / 6 + A^2 / (2 B)].
    This is the seed's E_max = (1/2) integral of B (A/B + C)^2 over the width (section "From
    k to B"). The A^2/(2B) term (energy absorbed without permanent crush) is counted over the
    whole width, so a zero profile gives L A^2 / (2 B). The result is multiplied by
    ``pdof_correction(angle, angle_limit)`` (angle in rad; see there)."""
    a_coef = _nonnegative("A", A, "N/m")
    b_coef = _positive("B", B, "N/m^2")
    c = _nonnegative("crush profile", profile, "m")
    w = _positive("width", width, "m")
    if c.ndim == 0 or c.shape[-1] not in (2, 4, 6):
        got = "a single number" if c.ndim == 0 else f"{c.shape[-1]} points"
        raise ParameterError(
            f"a CRASH3 crush profile has 2, 4 or 6 equally spaced points (m), got {got}"
        )
    factor = np.asarray(pdof_correction(angle, angle_limit))
    n = c.shape[-1]
    lo, hi = c[..., :-1], c[..., 1:]
    first = np.sum(lo + hi, axis=-1) / 2.0  # integral of C over the segments / d
    second = np.sum(lo * lo + lo * hi + hi * hi, axis=-1) / 3.0  # integral of C^2 / d
    d = w / (n - 1)
    energy = d * (a_coef * first + 0.5 * b_coef * second) + w * a_coef * a_coef / (2.0 * b_coef)
    return _out(energy * factor)
