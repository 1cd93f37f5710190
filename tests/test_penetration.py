"""The depth-of-penetration toolkit (crashsim.analysis.penetration) against closed forms, a
numerical
integration of the two-mass spring equations of motion, direct quadrature of the CRASH3
energy density, and the collision matrix of docs/model.md.

Tolerances: algebraic identities 1e-12 relative; the ODE (DOP853, rtol 1e-12, atol 1e-15 m)
1e-6 relative to the maximum crush; quadrature (scipy quad, epsrel 1e-13) 1e-9 relative."""

from __future__ import annotations

import math

import numpy as np
import pytest
from crashsim.analysis import penetration as pen
from crashsim.errors import ParameterError
from crashsim.units import deg, ft, mph
from scipy.integrate import quad, solve_ivp

RTOL_ID = 1e-12


def _cases(n: int, seed: int) -> tuple[np.ndarray, ...]:
    """n random (m1, m2 kg; k1, k2 N/m; v m/s) spanning realistic and lopsided pairs."""
    rng = np.random.default_rng(seed)
    m1 = rng.uniform(200.0, 40_000.0, n)
    m2 = rng.uniform(200.0, 40_000.0, n)
    k1 = 10.0 ** rng.uniform(4.5, 7.5, n)
    k2 = 10.0 ** rng.uniform(4.5, 7.5, n)
    v = rng.uniform(0.5, 40.0, n)
    return m1, m2, k1, k2, v


# --- closed forms and identities ------------------------------------------------------------


def test_building_blocks_closed_forms() -> None:
    assert pen.reduced_mass(1000.0, 1500.0) == pytest.approx(600.0, rel=1e-15)
    assert pen.series_stiffness(2.0e6, 3.0e6) == pytest.approx(1.2e6, rel=1e-15)
    assert pen.spring_stiffness(1.1e6, 1.7) == pytest.approx(1.87e6, rel=1e-15)
    # m' = 600 kg, k' = 1.2e6 N/m: dt_p = sqrt(5e-4) s, omega = 1/dt_p
    dtp = pen.depth_of_penetration(1000.0, 1500.0, 2.0e6, 3.0e6)
    assert dtp == pytest.approx(math.sqrt(5e-4), rel=1e-15)
    assert pen.angular_frequency(1000.0, 1500.0, 2.0e6, 3.0e6) == pytest.approx(1 / dtp, rel=1e-15)
    assert pen.contact_duration(1000.0, 1500.0, 2.0e6, 3.0e6) == pytest.approx(math.pi * dtp)
    # the same pair from B coefficients over a 2 m engagement width
    assert pen.depth_of_penetration_from_b(1000.0, 1500.0, 1.0e6, 1.5e6, 2.0) == pytest.approx(
        dtp, rel=1e-15
    )
    assert isinstance(dtp, float)


def test_seed_worked_examples_crush_is_closing_speed_times_dtp() -> None:
    """Seed: at 30 mph (44 ft/s) and dt_p = 30 ms the total crush is 1.32 ft; at 60 mph 2.64 ft."""
    m = 750.0  # kg, reduced mass of two 1500 kg cars
    k_series = m / 0.030**2  # N/m, so that dt_p = 30 ms
    k = 2.0 * k_series  # two equal springs in series
    assert pen.depth_of_penetration(1500.0, 1500.0, k, k) == pytest.approx(0.030, rel=1e-14)
    for speed, crush_ft in ((30.0, 1.32), (60.0, 2.64)):
        c = pen.max_total_crush(mph(speed), 1500.0, 1500.0, k, k)
        assert c == pytest.approx(ft(crush_ft), rel=1e-12)
        # equal stiffness: each car takes half (eq. 36)
        c1, c2 = pen.max_vehicle_crush(mph(speed), 1500.0, 1500.0, k, k)
        assert c1 == pytest.approx(0.5 * ft(crush_ft), rel=1e-12)
        assert c2 == pytest.approx(0.5 * ft(crush_ft), rel=1e-12)
        assert pen.depth_of_penetration_from_crush(mph(speed), c) == pytest.approx(0.030, rel=1e-12)


def test_identities_to_1e12() -> None:
    m1, m2, k1, k2, v = _cases(500, seed=1)
    dtp = pen.depth_of_penetration(m1, m2, k1, k2)
    t_max = pen.time_of_max_engagement(m1, m2, k1, k2)
    np.testing.assert_allclose(t_max, 0.5 * np.pi * dtp, rtol=RTOL_ID, atol=0)
    # C_T(t_max) = v dt_p (eq. 29) through the time function and the direct one
    np.testing.assert_allclose(pen.total_crush(t_max, v, m1, m2, k1, k2), v * dtp, rtol=RTOL_ID)
    np.testing.assert_allclose(pen.max_total_crush(v, m1, m2, k1, k2), v * dtp, rtol=RTOL_ID)
    # the split at random times inside the contact
    t = np.random.default_rng(2).uniform(0.0, 1.0, m1.size) * np.pi * dtp
    ct = pen.total_crush(t, v, m1, m2, k1, k2)
    c1, c2 = pen.crush_split(ct, k1, k2)
    np.testing.assert_allclose(c1 + c2, ct, rtol=RTOL_ID)
    np.testing.assert_allclose(k1 * c1, k2 * c2, rtol=RTOL_ID)
    # eqs. 30-31 (own formula) agree with the split of eq. 24 (eqs. 14-15)
    e1, e2 = pen.vehicle_crush(t, v, m1, m2, k1, k2)
    np.testing.assert_allclose(e1, c1, rtol=RTOL_ID)
    np.testing.assert_allclose(e2, c2, rtol=RTOL_ID)
    # eqs. 32-33 equal eqs. 34-35
    x1, x2 = pen.max_vehicle_crush(v, m1, m2, k1, k2)
    s1, s2 = pen.crush_split(v * dtp, k1, k2)
    np.testing.assert_allclose(x1, s1, rtol=RTOL_ID)
    np.testing.assert_allclose(x2, s2, rtol=RTOL_ID)
    np.testing.assert_allclose(x1 + x2, v * dtp, rtol=RTOL_ID)
    # the split depends only on the stiffness ratio: B over a common width splits alike
    b1, b2 = pen.crush_split(ct, k1 / 1.7, k2 / 1.7)
    np.testing.assert_allclose(b1, c1, rtol=RTOL_ID)


def test_crush_is_zero_after_the_contact_and_at_the_start() -> None:
    args = (12.0, 1400.0, 1700.0, 1.5e6, 0.9e6)
    dtp = pen.depth_of_penetration(*args[1:])
    assert pen.total_crush(0.0, *args) == 0.0
    assert pen.total_crush(np.pi * dtp * 1.0001, *args) == 0.0
    assert pen.total_crush(5.0, *args) == 0.0
    assert pen.vehicle_crush(5.0, *args) == (0.0, 0.0)
    # just before the end the crush is small and positive
    assert 0.0 < pen.total_crush(np.pi * dtp * 0.999, *args) < 1e-2 * 12.0 * dtp


def test_broadcasting_matches_scalar_calls() -> None:
    m1, m2, k1, k2, v = _cases(7, seed=3)
    t = np.linspace(0.0, 0.05, 5)[:, None]  # (5, 1) against (7,) -> (5, 7)
    grid = pen.total_crush(t, v, m1, m2, k1, k2)
    c1, c2 = pen.vehicle_crush(t, v, m1, m2, k1, k2)
    assert grid.shape == (5, 7)
    for i in range(5):
        for j in range(7):
            args = (float(t[i, 0]), float(v[j]), float(m1[j]), float(m2[j]))
            one = pen.total_crush(*args, float(k1[j]), float(k2[j]))
            assert isinstance(one, float)
            assert grid[i, j] == pytest.approx(one, rel=1e-14, abs=0)
            s1, s2 = pen.vehicle_crush(*args, float(k1[j]), float(k2[j]))
            assert c1[i, j] == pytest.approx(s1, rel=1e-14, abs=0)
            assert c2[i, j] == pytest.approx(s2, rel=1e-14, abs=0)
    funcs = [
        (pen.depth_of_penetration, (m1, m2, k1, k2)),
        (pen.time_of_max_engagement, (m1, m2, k1, k2)),
        (pen.angular_frequency, (m1, m2, k1, k2)),
        (pen.max_total_crush, (v, m1, m2, k1, k2)),
        (pen.reduced_mass, (m1, m2)),
        (pen.series_stiffness, (k1, k2)),
        (pen.depth_of_penetration_from_b, (m1, m2, k1, k2, 1.8)),
        (pen.effective_mass_factor, (m1, m1 * 1.5, v / 10.0)),
        (pen.effective_mass, (m1, m1 * 1.5, v / 10.0)),
        (pen.max_crush_from_residual, (v / 40.0,)),
        (pen.residual_crush_from_max, (v / 40.0,)),
        (pen.pdof_correction, (v / 40.0,)),
    ]
    for f, args in funcs:
        arr = f(*args)
        for j in range(7):
            one = f(*(a[j] if isinstance(a, np.ndarray) else a for a in args))
            assert isinstance(one, float), f.__name__
            assert arr[j] == pytest.approx(one, rel=1e-14, abs=0), f.__name__


# --- the equations of motion, integrated -----------------------------------------------------


@pytest.mark.parametrize(
    ("m1", "m2", "k1", "k2", "v"),
    [
        (1500.0, 1500.0, 1.8e6, 1.8e6, 13.4112),  # equal cars, 30 mph
        (1200.0, 2400.0, 2.2e6, 0.8e6, 20.0),  # small stiff front into a soft side
        (900.0, 30_000.0, 0.6e6, 6.0e6, 8.0),  # lopsided: car into a truck's rear
    ],
)
def test_two_mass_spring_integration_reproduces_the_model(
    m1: float, m2: float, k1: float, k2: float, v: float
) -> None:
    """x1, x2 of the centres of gravity, contact at x' = 0 at t = 0 with D1i, D2i the distances
    to the contact; m1 x1'' = -k1 C1, m2 x2'' = +k2 C2 with C1 = k2/(k1+k2) C_T,
    C2 = k1/(k1+k2) C_T and C_T = (D1i + D2i) - (x2 - x1) (springs push, never pull)."""
    d1, d2 = 2.1, 1.7  # m
    ks = k1 + k2

    def rhs(_t: float, y: np.ndarray) -> np.ndarray:
        x1, x2, v1, v2 = y
        ct = max((d1 + d2) - (x2 - x1), 0.0)
        c1, c2 = k2 / ks * ct, k1 / ks * ct
        return np.array([v1, v2, -k1 * c1 / m1, k2 * c2 / m2])

    def common_velocity(_t: float, y: np.ndarray) -> float:
        return y[2] - y[3]  # relative velocity v1 - v2

    common_velocity.direction = -1.0  # type: ignore[attr-defined]

    dtp = pen.depth_of_penetration(m1, m2, k1, k2)
    t_end = 1.3 * np.pi * dtp
    sol = solve_ivp(
        rhs,
        (0.0, t_end),
        [-d1, d2, v, 0.0],
        method="DOP853",
        rtol=1e-12,
        atol=1e-15,
        dense_output=True,
        events=common_velocity,
    )
    assert sol.success
    c_max = v * dtp
    # t_max from the integration: the first instant of common velocity
    t_event = sol.t_events[0]
    assert t_event.size == 1
    assert t_event[0] == pytest.approx(pen.time_of_max_engagement(m1, m2, k1, k2), rel=1e-6)
    y_event = sol.y_events[0][0]
    assert (d1 + d2) - (y_event[1] - y_event[0]) == pytest.approx(c_max, rel=1e-6)

    t = np.linspace(0.0, t_end, 401)
    x1, x2, _, _ = sol.sol(t)
    ct_num = np.maximum((d1 + d2) - (x2 - x1), 0.0)
    ct_model = pen.total_crush(t, v, m1, m2, k1, k2)
    np.testing.assert_allclose(ct_num, ct_model, rtol=0, atol=1e-6 * c_max)
    # each vehicle's crush from the contact point of eq. 13 (force balance at x')
    xp = (k1 * d1 - k2 * d2 + k1 * x1 + k2 * x2) / ks
    c1_num = np.where(ct_num > 0, d1 - (xp - x1), 0.0)
    c2_num = np.where(ct_num > 0, d2 - (x2 - xp), 0.0)
    c1_model, c2_model = pen.vehicle_crush(t, v, m1, m2, k1, k2)
    m1_max, m2_max = pen.max_vehicle_crush(v, m1, m2, k1, k2)
    np.testing.assert_allclose(c1_num, c1_model, rtol=0, atol=1e-6 * m1_max)
    np.testing.assert_allclose(c2_num, c2_model, rtol=0, atol=1e-6 * m2_max)
    c1e, c2e = pen.crush_split((d1 + d2) - (y_event[1] - y_event[0]), k1, k2)
    assert c1e == pytest.approx(m1_max, rel=1e-6)
    assert c2e == pytest.approx(m2_max, rel=1e-6)


# --- effective mass -----------------------------------------------------------------------


def test_gamma_limits_and_effective_mass() -> None:
    m, inertia = 1500.0, 2500.0  # kg, kg m^2: k_g^2 = 5/3 m^2
    kg2 = inertia / m
    assert pen.effective_mass_factor(m, inertia, 0.0) == 1.0
    assert pen.effective_mass(m, inertia, 0.0) == pytest.approx(m, rel=1e-15)
    h = np.array([1e2, 1e4, 1e6])
    gamma = pen.effective_mass_factor(m, inertia, h)
    # h -> inf: gamma -> k_g^2 / h^2 -> 0
    np.testing.assert_allclose(gamma * h**2 / kg2, 1.0, rtol=2e-4)
    assert gamma[-1] < 2e-12
    hs = np.linspace(0.0, 5.0, 51)
    g = pen.effective_mass_factor(m, inertia, hs)
    assert np.all(np.diff(g) < 0) and np.all(g > 0) and g[0] == 1.0
    # the sign of the lever arm does not matter; gamma m is the effective mass
    np.testing.assert_array_equal(g, pen.effective_mass_factor(m, inertia, -hs))
    np.testing.assert_allclose(pen.effective_mass(m, inertia, hs), g * m, rtol=1e-14)
    # h = k_g halves the mass
    assert pen.effective_mass_factor(m, inertia, math.sqrt(kg2)) == pytest.approx(0.5, rel=1e-15)


def _cross_matrix(r: np.ndarray) -> np.ndarray:
    return np.array([[0.0, -r[2], r[1]], [r[2], 0.0, -r[0]], [-r[1], r[0], 0.0]])


def test_effective_mass_along_matches_collision_matrix_and_planar_gamma() -> None:
    rng = np.random.default_rng(4)
    for _ in range(50):
        m = rng.uniform(800.0, 3000.0)
        q, _ = np.linalg.qr(rng.normal(size=(3, 3)))
        inertia = q @ np.diag(rng.uniform(300.0, 4000.0, 3)) @ q.T
        inertia = 0.5 * (inertia + inertia.T)
        r = rng.normal(size=3) * 1.5
        n = rng.normal(size=3)
        n_unit = n / np.linalg.norm(n)
        # one body's part of K (docs/model.md): (1/m) E - [r]x I^-1 [r]x; m_eff = 1 / (n.K n)
        rx = _cross_matrix(r)
        k_mat = np.eye(3) / m - rx @ np.linalg.inv(inertia) @ rx
        expected = 1.0 / (n_unit @ k_mat @ n_unit)
        assert pen.effective_mass_along(m, inertia, r, n) == pytest.approx(expected, rel=1e-12)
    # planar: horizontal r and n, vertical principal axis -> gamma m with h = |(r x n)_z|
    izz = 2700.0
    inertia = np.diag([600.0, 2500.0, izz])
    for _ in range(20):
        r = np.array([*rng.normal(size=2) * 2.0, 0.0])
        a = rng.uniform(0, 2 * np.pi)
        n = np.array([np.cos(a), np.sin(a), 0.0])
        h = abs(r[0] * n[1] - r[1] * n[0])
        got = pen.effective_mass_along(1600.0, inertia, r, n)
        assert got == pytest.approx(pen.effective_mass(1600.0, izz, h), rel=1e-12)
    # r along n: no turning, the full mass
    assert pen.effective_mass_along(1600.0, inertia, [2.0, 0, 0], [1.0, 0, 0]) == 1600.0
    # stacked input broadcasts
    rs = rng.normal(size=(5, 3))
    stacked = pen.effective_mass_along(1600.0, inertia, rs, [1.0, 0.0, 0.0])
    assert stacked.shape == (5,)
    for j in range(5):
        one = pen.effective_mass_along(1600.0, inertia, rs[j], [1.0, 0.0, 0.0])
        assert stacked[j] == pytest.approx(one, rel=1e-14)


def test_non_central_impact_shortens_dtp() -> None:
    """Seed: effective masses can only be smaller, so dt_p can only get shorter."""
    central = pen.depth_of_penetration(1500.0, 1600.0, 1.9e6, 0.9e6)
    m1 = pen.effective_mass(1500.0, 2400.0, 0.8)
    m2 = pen.effective_mass(1600.0, 2700.0, 1.1)
    assert pen.depth_of_penetration(m1, m2, 1.9e6, 0.9e6) < central


# --- SAE 880223 ---------------------------------------------------------------------------


def test_sae_880223_round_trip() -> None:
    assert pen.max_crush_from_residual(0.0) == pytest.approx(0.0889, rel=1e-15)
    inch = 0.0254
    assert pen.max_crush_from_residual(1.0 * inch) == pytest.approx(4.64 * inch, rel=1e-14)
    residual = np.random.default_rng(5).uniform(0.0, 1.2, 200)
    back = pen.residual_crush_from_max(pen.max_crush_from_residual(residual))
    np.testing.assert_allclose(back, residual, rtol=1e-12, atol=1e-15)
    maximum = np.random.default_rng(6).uniform(0.0889, 1.5, 200)
    np.testing.assert_allclose(
        pen.max_crush_from_residual(pen.residual_crush_from_max(maximum)), maximum, rtol=1e-12
    )
    # below 3.5 in of maximum crush the relation predicts no permanent crush
    assert pen.residual_crush_from_max(0.05) == 0.0


# --- CRASH3 crush energy ------------------------------------------------------------------


def _energy_by_quadrature(a: float, b: float, profile: np.ndarray, width: float) -> float:
    xs = np.linspace(0.0, width, profile.size)

    def density(w: float) -> float:
        c = float(np.interp(w, xs, profile))
        return a * c + 0.5 * b * c * c + a * a / (2.0 * b)

    total = 0.0
    for lo, hi in zip(xs[:-1], xs[1:], strict=True):  # smooth on each segment
        value, _ = quad(density, lo, hi, epsabs=0.0, epsrel=1e-13, limit=200)
        total += value
    return total


@pytest.mark.parametrize("points", [2, 4, 6])
def test_crush_energy_matches_quadrature(points: int) -> None:
    rng = np.random.default_rng(10 + points)
    for _ in range(20):
        a = rng.uniform(0.0, 8e4)  # N/m
        b = rng.uniform(2e5, 2e6)  # N/m^2
        width = rng.uniform(0.3, 2.0)  # m
        profile = rng.uniform(0.0, 0.8, points)  # m
        e = pen.crush_energy(a, b, profile, width)
        assert e == pytest.approx(_energy_by_quadrature(a, b, profile, width), rel=1e-9)


def test_crush_energy_closed_forms() -> None:
    a, b, width = 5.0e4, 1.2e6, 1.6
    g = a * a / (2 * b)
    # uniform crush: width * density
    for n in (2, 4, 6):
        e = pen.crush_energy(a, b, np.full(n, 0.3), width)
        assert e == pytest.approx(width * (a * 0.3 + 0.5 * b * 0.09 + g), rel=1e-14)
    # zero crush: only the threshold term
    assert pen.crush_energy(a, b, [0.0, 0.0], width) == pytest.approx(width * g, rel=1e-15)
    # the classic six-point CRASH3 expression
    c = np.array([0.10, 0.25, 0.40, 0.38, 0.22, 0.05])
    classic = (width / 5.0) * (
        a / 2.0 * (c[0] + 2 * c[1:5].sum() + c[5])
        + b / 6.0 * (c[0] ** 2 + 2 * (c[1:5] ** 2).sum() + c[5] ** 2 + (c[:-1] * c[1:]).sum())
        + 5.0 * g
    )
    assert pen.crush_energy(a, b, c, width) == pytest.approx(classic, rel=1e-14)


def test_crush_energy_pdof_correction_and_broadcasting() -> None:
    a, b, width = 4.0e4, 9.0e5, 1.5
    c = np.array([0.2, 0.35, 0.3, 0.1])
    e0 = pen.crush_energy(a, b, c, width)
    e30 = pen.crush_energy(a, b, c, width, angle=deg(30.0))
    assert e30 == pytest.approx(e0 * (1.0 + math.tan(deg(30.0)) ** 2), rel=1e-14)
    assert pen.crush_energy(a, b, c, width, angle=-deg(30.0)) == e30
    # CRASH3 cap: beyond 45 deg the factor stays 2 (default); uncapped on request
    assert pen.crush_energy(a, b, c, width, angle=deg(60.0)) == pytest.approx(2 * e0, rel=1e-14)
    uncapped = pen.crush_energy(a, b, c, width, angle=deg(60.0), angle_limit=None)
    assert uncapped == pytest.approx(4.0 * e0, rel=1e-13)
    assert pen.pdof_correction(deg(45.0)) == pytest.approx(2.0, rel=1e-15)
    # a stack of profiles (3, 4) with per-profile widths and angles
    stack = np.stack([c, 0.5 * c, 2.0 * c])
    widths = np.array([1.5, 1.0, 2.0])
    angles = np.array([0.0, deg(10.0), deg(20.0)])
    got = pen.crush_energy(a, b, stack, widths, angle=angles)
    assert got.shape == (3,)
    for j in range(3):
        one = pen.crush_energy(a, b, stack[j], widths[j], angle=angles[j])
        assert got[j] == pytest.approx(one, rel=1e-14)


# --- bad inputs -----------------------------------------------------------------------------


@pytest.mark.parametrize(
    ("func", "args"),
    [
        (pen.reduced_mass, (0.0, 1000.0)),
        (pen.reduced_mass, (-5.0, 1000.0)),
        (pen.reduced_mass, (float("nan"), 1000.0)),
        (pen.reduced_mass, ("heavy", 1000.0)),
        (pen.reduced_mass, (True, 1000.0)),
        (pen.series_stiffness, (1e6, float("inf"))),
        (pen.series_stiffness, (1e6, -1e6)),
        (pen.spring_stiffness, (1e6, 0.0)),
        (pen.depth_of_penetration, (1000.0, 1000.0, 1e6, 0.0)),
        (pen.depth_of_penetration, (np.array([1000.0, -1.0]), 1000.0, 1e6, 1e6)),
        (pen.depth_of_penetration_from_b, (1000.0, 1000.0, 1e6, 1e6, -1.7)),
        (pen.depth_of_penetration_from_crush, (0.0, 0.4)),
        (pen.depth_of_penetration_from_crush, (10.0, -0.4)),
        (pen.total_crush, (-0.01, 10.0, 1000.0, 1000.0, 1e6, 1e6)),
        (pen.total_crush, (0.01, -10.0, 1000.0, 1000.0, 1e6, 1e6)),
        (pen.crush_split, (-0.1, 1e6, 1e6)),
        (pen.crush_split, (0.1, 1e6, float("nan"))),
        (pen.effective_mass_factor, (1000.0, 0.0, 1.0)),
        (pen.effective_mass_factor, (1000.0, 2000.0, float("inf"))),
        (pen.effective_mass_along, (1000.0, np.eye(3) * 1e3, [1.0, 0, 0], [0.0, 0, 0])),
        (pen.effective_mass_along, (1000.0, np.diag([1e3, -1e3, 1e3]), [1.0, 0, 0], [0, 1.0, 0])),
        (pen.effective_mass_along, (1000.0, np.eye(2), [1.0, 0], [0, 1.0])),
        (pen.max_crush_from_residual, (-0.01,)),
        (pen.residual_crush_from_max, (float("nan"),)),
        (pen.pdof_correction, (math.pi / 2,)),
        (pen.pdof_correction, (0.1, math.pi / 2)),
        (pen.crush_energy, (4e4, 1e6, [0.1, 0.2, 0.3], 1.5)),
        (pen.crush_energy, (4e4, 1e6, [0.1] * 8, 1.5)),
        (pen.crush_energy, (4e4, 1e6, 0.3, 1.5)),
        (pen.crush_energy, (4e4, 1e6, [0.1, -0.2], 1.5)),
        (pen.crush_energy, (-4e4, 1e6, [0.1, 0.2], 1.5)),
        (pen.crush_energy, (4e4, 0.0, [0.1, 0.2], 1.5)),
        (pen.crush_energy, (4e4, 1e6, [0.1, 0.2], 0.0)),
        (pen.crush_energy, (4e4, 1e6, [0.1, 0.2], 1.5, deg(95.0))),
    ],
)
def test_bad_inputs_raise_parameter_error(func: object, args: tuple[object, ...]) -> None:
    with pytest.raises(ParameterError):
        func(*args)  # type: ignore[operator]


def test_error_message_names_the_parameter_and_unit() -> None:
    with pytest.raises(ParameterError, match=r"m2 must be > 0 kg, got -3"):
        pen.reduced_mass(1000.0, -3.0)
    with pytest.raises(ParameterError, match="2, 4 or 6"):
        pen.crush_energy(4e4, 1e6, [0.1, 0.2, 0.3], 1.5)
