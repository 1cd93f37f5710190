"""The parametric vehicle body generator (crashsim.vehicles.generator).

Every preset and 60 random valid parameter sets (all 200 in the long run,
CRASHSIM_LONG_TESTS=1) give closed, watertight, single-shell, outward-wound bodies with the
asked extents, no degenerate faces and no self-intersections. Self-intersections are looked
for by two independent checks, each shown to catch a deliberately folded mesh: an exact search
for crossing triangle pairs, and the exact generalized winding number (closed-form solid
angles) of probe points just inside and just outside every face, which must be 1 and 0 (a fold
gives 2, 0 or -1 there). Mass properties: trimesh's against closed forms for lofts that are
boxes and rectangular frustums, and against the engine's own computation when it has one. Bad
input gives ParameterErrors that name the parameter. The reference meshes in meshes/
regenerate bit for bit.
"""

from __future__ import annotations

import dataclasses
import functools
import hashlib
import importlib.util
import itertools
import math
import os
import subprocess
import sys
from pathlib import Path
from types import ModuleType

import numpy as np
import pytest
import trimesh
from crashsim import _core
from crashsim.errors import MeshError, ParameterError
from crashsim.vehicles.generator import (
    PRESETS,
    SHAPE_PARAMETERS,
    BodyParams,
    body_params,
    body_sections,
    default_dims,
    generate_body,
    loft,
    ply_bytes,
)
from crashsim.vehicles.generator.adaptive import _ARCH_BUMPER, _ARCH_CLEARANCE, _CORNER_SHARE
from crashsim.vehicles.generator.params import _profiles
from crashsim.vehicles.vehicle_data import vehicle_class
from numpy.polynomial import Polynomial

REPO = Path(__file__).resolve().parents[1]
MESHES = REPO / "meshes"

# -- independent checks ------------------------------------------------------------------------


def winding_numbers(mesh: trimesh.Trimesh, points: np.ndarray, chunk: int = 128) -> np.ndarray:
    """Exact generalized winding numbers: the sum of the triangles' signed solid angles seen from
    each point over 4 pi (Van Oosterom and Strackee's closed form), integers (to round-off)
    for a closed mesh at any point off its surface."""
    tri = np.asarray(mesh.triangles, dtype=np.float64)
    corner = [np.ascontiguousarray(tri[:, k, i]) for k in range(3) for i in range(3)]
    points = np.asarray(points, dtype=np.float64).reshape(-1, 3)
    out = np.empty(len(points))
    for start in range(0, len(points), chunk):
        px, py, pz = (points[start : start + chunk, i, None] for i in range(3))
        ax, ay, az = corner[0] - px, corner[1] - py, corner[2] - pz
        bx, by, bz = corner[3] - px, corner[4] - py, corner[5] - pz
        cx, cy, cz = corner[6] - px, corner[7] - py, corner[8] - pz
        la = np.sqrt(ax * ax + ay * ay + az * az)
        lb = np.sqrt(bx * bx + by * by + bz * bz)
        lc = np.sqrt(cx * cx + cy * cy + cz * cz)
        det = ax * (by * cz - bz * cy) - ay * (bx * cz - bz * cx) + az * (bx * cy - by * cx)
        den = (
            la * lb * lc
            + (ax * bx + ay * by + az * bz) * lc
            + (ax * cx + ay * cy + az * cz) * lb
            + (bx * cx + by * cy + bz * cz) * la
        )
        # each triangle subtends 2 atan2(det, den); the winding number is the sum over 4 pi
        out[start : start + chunk] = np.arctan2(det, den).sum(axis=1) / (2.0 * np.pi)
    return out


def winding_failures(
    mesh: trimesh.Trimesh,
    rng: np.random.Generator,
    n_probes: int | None = None,
    n_box: int = 400,
) -> dict[str, int]:
    """Counts of probe points whose exact winding number is off. Probes: eps = 0.2 mm inside
    and outside each vertex along its normal (a fold moves vertices to where the winding is 2,
    0 or -1) and each face's centroid (n_probes of each, chosen at random, or all), and n_box
    random points in and around the box (which must be within 1e-6 of 0 or 1)."""
    eps = 2e-4  # m; every part of a valid body is far thicker
    v_idx = np.arange(len(mesh.vertices))
    f_idx = np.arange(len(mesh.faces))
    if n_probes is not None:
        v_idx = np.sort(rng.choice(v_idx, min(n_probes, len(v_idx)), replace=False))
        f_idx = np.sort(rng.choice(f_idx, min(n_probes, len(f_idx)), replace=False))
    points = np.concatenate([mesh.vertices[v_idx], mesh.triangles_center[f_idx]])
    normals = np.concatenate([mesh.vertex_normals[v_idx], mesh.face_normals[f_idx]])
    lo, hi = mesh.bounds
    box = rng.uniform(lo - 0.05 * (hi - lo), hi + 0.05 * (hi - lo), size=(n_box, 3))
    w = winding_numbers(mesh, np.concatenate([points - eps * normals, points + eps * normals, box]))
    n = len(points)
    w_in, w_out, w_box = w[:n], w[n : 2 * n], w[2 * n :]
    return {
        "inside probes not 1": int(np.sum(np.abs(w_in - 1.0) > 1e-6)),
        "outside probes not 0": int(np.sum(np.abs(w_out) > 1e-6)),
        "box points not 0 or 1": int(np.sum(np.minimum(np.abs(w_box), np.abs(w_box - 1.0)) > 1e-6)),
    }


def _orient(p: np.ndarray, q: np.ndarray, r: np.ndarray, s: np.ndarray) -> np.ndarray:
    """Six times the signed volume of the tetrahedra (p, q, r, s), row by row."""
    (ax, ay, az), (bx, by, bz), (cx, cy, cz) = ((v - p).T for v in (q, r, s))
    return ax * (by * cz - bz * cy) - ay * (bx * cz - bz * cx) + az * (bx * cy - by * cx)


def _segments_cross(p0, p1, a, b, c) -> np.ndarray:
    """Does segment p0-p1 pass through the interior of triangle abc, row by row? By signs of
    volumes: the ends strictly on opposite sides of the triangle's plane, and the segment's
    line strictly on the same side of the three edges. A sign only counts when the volume is
    larger than 1e-12 of the cube of the pair's longest edge, so touching and coplanar pairs
    (a flat floor, a shared line) are not crossings."""
    pts = (p0, p1, a, b, c)
    edges = [pts[i] - pts[j] for i, j in ((1, 0), (3, 2), (4, 3), (2, 4))]
    scale = np.max([np.einsum("ij,ij->i", e, e) for e in edges], axis=0) ** 1.5
    tol = 1e-12 * scale
    s0, s1 = _orient(a, b, c, p0), _orient(a, b, c, p1)
    apart = ((s0 > tol) & (s1 < -tol)) | ((s0 < -tol) & (s1 > tol))
    e1, e2, e3 = _orient(p0, p1, a, b), _orient(p0, p1, b, c), _orient(p0, p1, c, a)
    same = ((e1 > tol) & (e2 > tol) & (e3 > tol)) | ((e1 < -tol) & (e2 < -tol) & (e3 < -tol))
    return apart & same


def crossing_pairs(mesh: trimesh.Trimesh) -> int:
    """The number of triangle pairs that cross each other: candidate pairs from overlapping
    bounding boxes (sweep along x); a pair without a shared vertex crosses when an edge of
    one passes through the other's interior; a pair sharing one vertex when the edge opposite
    that vertex does; a pair sharing an edge when it is folded flat onto itself (normals
    opposite)."""
    v = np.asarray(mesh.vertices, dtype=np.float64)
    f = np.asarray(mesh.faces, dtype=np.int64)
    tri = v[f]
    lo, hi = tri.min(axis=1), tri.max(axis=1)
    order = np.argsort(lo[:, 0], kind="stable")
    lo_sorted = lo[order, 0]
    stop = np.searchsorted(lo_sorted, hi[order, 0], side="right")
    start = np.arange(len(order)) + 1
    count = np.maximum(stop - start, 0)
    first = np.repeat(np.arange(len(order)), count)
    offset = np.arange(count.sum()) - np.repeat(np.cumsum(count) - count, count)
    i = order[first]
    j = order[np.repeat(start, count) + offset]
    tol = 1e-12
    boxes = np.all((lo[i] <= hi[j] + tol) & (lo[j] <= hi[i] + tol), axis=1)
    i, j = i[boxes], j[boxes]
    shared = (f[i][:, :, None] == f[j][:, None, :]).sum(axis=(1, 2))
    crossing = 0
    # no shared vertex: any of the six edges through the other triangle
    k = shared == 0
    ti, tj = tri[i[k]], tri[j[k]]
    hit = np.zeros(int(k.sum()), dtype=bool)
    for s_tri, o_tri in ((ti, tj), (tj, ti)):
        for e in range(3):
            p0, p1 = s_tri[:, e], s_tri[:, (e + 1) % 3]
            hit |= _segments_cross(p0, p1, o_tri[:, 0], o_tri[:, 1], o_tri[:, 2])
    crossing += int(hit.sum())
    # one shared vertex: the edge opposite it, in each triangle, through the other
    k = shared == 1
    fi, fj = f[i[k]], f[j[k]]
    ti, tj = tri[i[k]], tri[j[k]]
    hit = np.zeros(int(k.sum()), dtype=bool)
    rows = np.arange(int(k.sum()))
    for fa, ta, fb, tb in ((fi, ti, fj, tj), (fj, tj, fi, ti)):
        at = np.argmax((fa[:, :, None] == fb[:, None, :]).any(axis=2), axis=1)
        p0 = ta[rows, (at + 1) % 3]
        p1 = ta[rows, (at + 2) % 3]
        hit |= _segments_cross(p0, p1, tb[:, 0], tb[:, 1], tb[:, 2])
    crossing += int(hit.sum())
    # a shared edge: folded flat
    k = shared == 2
    n = mesh.face_normals
    crossing += int(np.sum(np.einsum("ij,ij->i", n[i[k]], n[j[k]]) < -1.0 + 1e-9))
    return crossing


def assert_valid_body(mesh: trimesh.Trimesh, p: BodyParams) -> None:
    """Closed, one shell, outward, the asked box (1e-9 m), no zero-area face."""
    assert mesh.is_watertight
    assert mesh.is_winding_consistent
    assert mesh.body_count == 1
    assert len(trimesh.graph.connected_components(mesh.face_adjacency)) == 1
    assert mesh.is_volume and mesh.volume > 0.0
    expected = [
        [-p.length / 2, -p.width / 2, p.ground_clearance],
        [p.length / 2, p.width / 2, p.height],
    ]
    assert np.allclose(mesh.bounds, expected, rtol=0.0, atol=1e-9), (mesh.bounds, expected)
    # zero-area faces: the smallest face is far from round-off (and trimesh agrees)
    assert mesh.area_faces.min() > 1e-7
    assert mesh.nondegenerate_faces().all()
    assert len(np.unique(np.sort(mesh.faces, axis=1), axis=0)) == len(mesh.faces)


# -- the checks themselves catch what they are for ---------------------------------------------


def folded_sedan() -> trimesh.Trimesh:
    """The default sedan with the roof's centre-line point of one mid-cabin section pulled
    down through the floor: a spike of roof surface that pierces the underside."""
    p = body_params("sedan", **default_dims("sedan"))
    x, sections = body_sections(p, 0.5)
    i = int(np.argmin(np.abs(x - 0.0)))
    top = sections.shape[1] // 2
    sections = sections.copy()
    sections[i, top, 1] = p.ground_clearance - 0.3
    return loft(x, sections)


def test_the_checks_find_a_deliberate_fold() -> None:
    mesh = folded_sedan()
    assert mesh.is_watertight and mesh.body_count == 1  # the topology alone does not see it
    assert crossing_pairs(mesh) > 0
    failures = winding_failures(mesh, np.random.default_rng(1))
    assert failures["inside probes not 1"] + failures["outside probes not 0"] > 0
    # inside the spike but below the floor, the roof surface is wound once around the point
    # the wrong way: the winding number is -1 there
    i = int(np.argmin(np.abs(mesh.vertices[:, 0])))
    x0 = mesh.vertices[i, 0]
    below = np.array([[x0, 0.0, mesh.vertices[:, 2].min() + 0.02]])
    assert winding_numbers(mesh, below)[0] == pytest.approx(-1.0, abs=1e-9)


def test_the_crossing_search_sees_two_crossing_boxes_and_not_two_apart() -> None:
    a = trimesh.creation.box(extents=[1.0, 1.0, 1.0])
    b = trimesh.creation.box(extents=[1.0, 1.0, 1.0])
    b.apply_translation([0.5, 0.3, 0.2])
    assert crossing_pairs(trimesh.util.concatenate([a, b])) > 0
    b.apply_translation([1.0, 0.0, 0.0])  # now 0.5 m apart in x
    assert crossing_pairs(trimesh.util.concatenate([a, b])) == 0
    assert crossing_pairs(a) == 0


def test_exact_winding_numbers_of_a_box() -> None:
    box = trimesh.creation.box(extents=[2.0, 1.0, 0.5])
    points = np.array([[0.0, 0.0, 0.0], [0.99, 0.49, 0.24], [1.01, 0.0, 0.0], [5.0, 5.0, 5.0]])
    assert np.allclose(winding_numbers(box, points), [1.0, 1.0, 0.0, 0.0], rtol=0, atol=1e-12)
    flipped = box.copy()
    flipped.invert()
    assert winding_numbers(flipped, points[:1])[0] == pytest.approx(-1.0, abs=1e-12)


# -- presets -----------------------------------------------------------------------------------


@pytest.fixture(scope="module", params=PRESETS)
def preset_body(request: pytest.FixtureRequest) -> tuple[BodyParams, trimesh.Trimesh]:
    p = body_params(request.param, **default_dims(request.param))
    return p, generate_body(p)


def test_preset_body_is_a_valid_closed_shell(preset_body) -> None:
    p, mesh = preset_body
    assert_valid_body(mesh, p)
    assert 3000 <= len(mesh.faces) <= 8000  # "a few thousand triangles" by default


def test_preset_body_has_no_self_intersection(preset_body) -> None:
    p, mesh = preset_body
    assert crossing_pairs(mesh) == 0
    failures = winding_failures(mesh, np.random.default_rng(7), n_probes=800)
    assert failures == {
        "inside probes not 1": 0,
        "outside probes not 0": 0,
        "box points not 0 or 1": 0,
    }


def test_preset_body_inside_agrees_with_engine_and_ray_tests(preset_body) -> None:
    """The engine's fast winding number (a far-field approximation: measured errors up to
    about 0.02) and trimesh's ray test give the same inside/outside as the exact count."""
    p, mesh = preset_body
    rng = np.random.default_rng(3)
    lo, hi = mesh.bounds
    points = rng.uniform(lo - 0.1, hi + 0.1, size=(1500, 3))
    exact = winding_numbers(mesh, points)
    assert np.all(np.minimum(np.abs(exact), np.abs(exact - 1.0)) < 1e-6)
    inside = exact > 0.5
    assert 0.2 < inside.mean() < 0.9  # the sample probes both
    engine = _core.Shape(mesh.vertices, mesh.faces).winding_numbers(points)
    assert np.max(np.abs(engine - exact)) < 0.1
    pytest.importorskip("rtree", reason="trimesh's ray test needs rtree")
    assert np.array_equal(mesh.contains(points), inside)


def test_preset_body_keeps_the_asked_shape(preset_body) -> None:
    """Spot checks of the parameters in the mesh: the roof height at the cabin, the ground
    clearance between the axles, the wheel arches open at the axles, the rounded corners."""
    p, mesh = preset_body
    v = mesh.vertices
    x_front_axle = p.length / 2 - p.front_overhang
    x_rear_axle = x_front_axle - p.wheelbase
    # below each wheel centre, at the body side, there is no body (the arch is open) ...
    for x in (x_front_axle, x_rear_axle):
        side = np.array([[x, p.width / 2 - 0.02, p.wheel_radius], [x, -p.width / 2 + 0.02, 0.3]])
        assert np.all(np.abs(winding_numbers(mesh, side)) < 1e-9)
        # ... while the same point is inside the body ahead of and behind the arch
        for dx in (-1.0, 1.0):
            away = np.array(
                [
                    [
                        x + dx * (p.arch_radius + 0.05),
                        p.width / 2 - 0.02,
                        0.5 * (p.wheel_radius + p.arch_radius + p.wheel_radius),
                    ]
                ]
            )
            if abs(away[0, 0]) < p.length / 2 - p.bumper_radius:
                assert winding_numbers(mesh, away)[0] == pytest.approx(1.0, abs=1e-9)
    # the underside between the axles is at the ground clearance
    mid = (np.abs(v[:, 0]) < 0.2) & (np.abs(v[:, 1]) < p.width / 2 - p.arch_depth)
    assert v[mid, 2].min() == pytest.approx(p.ground_clearance, abs=1e-12)
    # the front corners are rounded: no vertex near the box corner (+L/2, +W/2)
    corner = np.hypot(v[:, 0] - p.length / 2, v[:, 1] - p.width / 2)
    assert corner.min() > 0.9 * (math.sqrt(2) - 1) * p.bumper_radius


# -- the adaptive defaults over the dimensions a vehicle of the class can have ------------------

# Each preset's nominal wheel radius (m): the adapted default never exceeds it.
NOMINAL_WHEEL = {"sedan": 0.31, "suv": 0.37, "pickup": 0.40, "van": 0.32, "bus": 0.50}


def class_dimension_box(preset: str) -> dict[str, tuple[float, float]]:
    """(low, high) of each dimension (m) a user of the class could give: the class value
    scaled by the property test's DIM_RANGES, widened to +-2 sd where the table has an sd."""
    vc = vehicle_class(preset)
    box = {}
    for name, (lo, hi) in DIM_RANGES.items():
        fig = getattr(vc, name)
        low, high = fig.value * lo, fig.value * hi
        if fig.sd is not None:
            low, high = min(low, fig.value - 2.0 * fig.sd), max(high, fig.value + 2.0 * fig.sd)
        box[name] = (low, high)
    return box


def wheel_rule_margin(p: BodyParams) -> float:
    """The least margin (m) of the rule of the wheel_radius default, measured on the profile
    the sections are built from (_profiles, at 4001 stations over each arch): the top of the
    body side over each arch less (arch top + _ARCH_CLEARANCE), the body kept ahead of and
    behind the arches less _ARCH_BUMPER, and the room between the arches less 0.1 m."""
    ra = p.arch_radius
    margins = [
        min(p.front_overhang, p.rear_overhang) - ra - _ARCH_BUMPER,
        p.wheelbase - 2.0 * ra - 0.1,
    ]
    for da in (p.front_overhang, p.front_overhang + p.wheelbase):
        d = da + ra * np.linspace(-1.0, 1.0, 4001)
        side = _profiles(p, d)["z_shoulder"]
        margins.append(float(side.min()) - (p.wheel_radius + ra + _ARCH_CLEARANCE))
    return min(margins)


@pytest.mark.parametrize("preset", PRESETS)
def test_class_dimensions_keep_the_nominal_shape(preset: str) -> None:
    """At the class's own dimensions no adaptive rule has to act."""
    p = body_params(preset, **default_dims(preset))
    assert p.wheel_radius == NOMINAL_WHEEL[preset]
    assert wheel_rule_margin(p) >= 0.0
    assert p.bumper_radius < _CORNER_SHARE * min(p.front_overhang, p.rear_overhang)


@pytest.mark.parametrize("preset", PRESETS)
def test_defaults_give_valid_bodies_over_the_class_dimension_box(preset: str) -> None:
    """Every corner of the box of dimensions a user of the class could give (and its centre)
    gives a valid body with the defaults alone; the adapted wheel keeps its stated rule, is
    the largest that does (to the mm) and is at least half the nominal one."""
    box = class_dimension_box(preset)
    adapted = 0
    corners = [dict(zip(box, c, strict=True)) for c in itertools.product(*box.values())]
    centre = {k: 0.5 * (lo + hi) for k, (lo, hi) in box.items()}
    for dims in [*corners, centre]:
        p = body_params(preset, **dims)
        assert wheel_rule_margin(p) >= -1e-12, dims
        assert 0.5 * NOMINAL_WHEEL[preset] <= p.wheel_radius <= NOMINAL_WHEEL[preset]
        if p.wheel_radius < NOMINAL_WHEEL[preset]:
            adapted += 1
            bigger = body_params(preset, **dims, wheel_radius=p.wheel_radius + 0.001)
            assert wheel_rule_margin(bigger) < 0.0, dims
        mesh = generate_body(p, 0.5)
        assert_valid_body(mesh, p)
        assert crossing_pairs(mesh) == 0, dims
    assert adapted > 0 or preset == "bus"  # the box reaches where the rule acts


def test_adaptive_defaults_give_way_to_given_numbers() -> None:
    """A short front overhang shrinks the default wheel (and the edge and corner radii) so the
    body stays valid; the same overhang with the nominal wheel given is refused."""
    p = sedan(front_overhang=0.40)
    assert p.wheel_radius == pytest.approx(0.40 - 0.04 - _ARCH_BUMPER, abs=1e-3)
    assert p.wheel_radius <= 0.40 - 0.04 - _ARCH_BUMPER
    assert p.edge_radius <= p.front_overhang - p.arch_radius
    assert p.bumper_radius == pytest.approx(_CORNER_SHARE * 0.40, rel=1e-15)
    assert_valid_body(generate_body(p, 0.5), p)
    with pytest.raises(ParameterError, match="front_overhang = 0.4 m leaves no bumper"):
        sedan(front_overhang=0.40, wheel_radius=0.32, edge_radius=0.01)
    # a low beltline lowers the wheel (the arch stays under the body side) ...
    q = sedan(beltline=0.7)
    assert q.wheel_radius < 0.31 and wheel_rule_margin(q) >= 0.0
    # ... and a small given wheel lowers the default ground clearance
    r = sedan(wheel_radius=0.16)
    assert r.ground_clearance == pytest.approx(0.75 * 0.16, rel=1e-15)


@pytest.mark.parametrize("resolution", [0.25, 2.0])
def test_resolution_scales_the_mesh_and_keeps_it_valid(resolution: float) -> None:
    p = body_params("van", **default_dims("van"))
    default = generate_body(p)
    mesh = generate_body(p, resolution)
    assert_valid_body(mesh, p)
    assert crossing_pairs(mesh) == 0
    if resolution < 1.0:
        assert len(mesh.faces) < 0.6 * len(default.faces)
    else:
        assert len(mesh.faces) > 2.5 * len(default.faces)
    # a finer loft of the same profiles holds about the same volume
    assert mesh.volume == pytest.approx(default.volume, rel=0.01)


# -- random valid parameter sets ---------------------------------------------------------------


HEIGHTS = (
    "ground_clearance",
    "bumper_bottom",
    "nose_height",
    "hood_height",
    "deck_height",
    "tail_height",
    "beltline",
)
POSITIONS = ("windshield_base", "roof_start", "roof_end", "rear_window_end")
DIM_RANGES = {
    "length": (0.85, 1.2),
    "width": (0.9, 1.1),
    "height": (0.9, 1.15),
    "wheelbase": (0.9, 1.1),
}


def random_params(rng: np.random.Generator) -> BodyParams | None:
    """A random parameter set around a random preset (None when body_params refuses it): the
    dimensions scaled, and each shape parameter (with probability 0.7) scaled from the
    preset's default: heights by 0.85-1.15 (at most the roof), other sizes by 0.75-1.3, and
    the gaps between the profile's positions along the body by 0.7-1.3 (kept in order)."""
    preset = PRESETS[int(rng.integers(len(PRESETS)))]
    dims = default_dims(preset)
    for name, (lo, hi) in DIM_RANGES.items():
        dims[name] *= float(rng.uniform(lo, hi))
    try:
        base = body_params(preset, **dims)
    except ParameterError:
        return None
    shape = {}
    for name in SHAPE_PARAMETERS:
        if name in POSITIONS or rng.uniform() >= 0.7:
            continue
        if name in HEIGHTS:
            shape[name] = min(getattr(base, name) * float(rng.uniform(0.85, 1.15)), base.height)
        else:
            shape[name] = getattr(base, name) * float(rng.uniform(0.75, 1.3))
    if rng.uniform() < 0.7:
        at = np.array([0.0, *(getattr(base, n) for n in POSITIONS), base.length])
        gaps = np.diff(at) * rng.uniform(0.7, 1.3, size=len(at) - 1)
        at = np.cumsum(gaps) * (base.length / gaps.sum())
        shape.update({n: float(v) for n, v in zip(POSITIONS, at[:-1], strict=True)})
    try:
        return body_params(preset, **dims, **shape)
    except ParameterError:
        return None


def random_valid_params(count: int, seed: int) -> list[BodyParams]:
    rng = np.random.default_rng(seed)
    found: list[BodyParams] = []
    tries = 0
    while len(found) < count:
        tries += 1
        assert tries < 20 * count, "too few random parameter sets are valid"
        p = random_params(rng)
        if p is not None:
            found.append(p)
    return found


@functools.cache
def random_sets() -> list[BodyParams]:
    """The 200 random valid parameter sets of the tests (seeded)."""
    return random_valid_params(200, seed=20240611)


def test_random_parameter_sets_cover_every_preset() -> None:
    presets = [p.preset for p in random_sets()]
    assert set(presets) == set(PRESETS)
    assert min(presets.count(pr) for pr in PRESETS) >= 20


# The test run checks the first RANDOM_PER_CHUNK sets of each chunk of 10 (60 bodies, every
# preset and both resolutions); the long run (CRASHSIM_LONG_TESTS=1, README "Testing") all 200.
# The checks of one body take about 0.3 s (exact crossing search and winding numbers).
RANDOM_PER_CHUNK = 10 if os.environ.get("CRASHSIM_LONG_TESTS") == "1" else 3


@pytest.mark.parametrize("k", range(0, 200, 10), ids=lambda k: f"sets{k}-{k + 9}")
def test_random_bodies_are_valid_and_do_not_self_intersect(k: int) -> None:
    rng = np.random.default_rng(k)
    for p in random_sets()[k : k + RANDOM_PER_CHUNK]:
        resolution = 0.5 if k % 40 else 1.0  # a quarter at the default resolution
        mesh = generate_body(p, resolution)
        assert_valid_body(mesh, p)
        assert crossing_pairs(mesh) == 0, p
        failures = winding_failures(mesh, rng, n_probes=50, n_box=50)
        assert not any(failures.values()), (failures, p)


# -- mass properties ---------------------------------------------------------------------------


def rectangle(half_y: float, half_z: float, zc: float, per_side: int = 3) -> np.ndarray:
    """A rectangle centred on (0, zc) as per_side points a side, counter-clockwise in (y, z)
    starting at the bottom-left corner (collinear points on purpose, as in the bodies)."""
    corners = np.array(
        [
            [-half_y, zc - half_z],
            [half_y, zc - half_z],
            [half_y, zc + half_z],
            [-half_y, zc + half_z],
        ]
    )
    t = np.arange(per_side)[:, None] / per_side
    return np.concatenate([corners[k] + t * (corners[(k + 1) % 4] - corners[k]) for k in range(4)])


def frustum_properties(x: np.ndarray, half_y: np.ndarray, half_z: np.ndarray, zc: float):
    """Exact volume, centroid and inertia (about the centroid, density 1) of the solid whose
    section at x is the rectangle |y| <= A(x), |z - zc| <= B(x), with A and B piecewise linear
    through (x, half_y) and (x, half_z), by integrating polynomials slab by slab."""
    m0 = mx = mxx = myy = mzz = 0.0
    for k in range(len(x) - 1):
        span = (x[k], x[k + 1])
        a = Polynomial.fit(span, half_y[k : k + 2], 1).convert()
        b = Polynomial.fit(span, half_z[k : k + 2], 1).convert()
        X = Polynomial([0.0, 1.0])
        area = 4.0 * a * b

        def integral(poly: Polynomial, s: tuple[float, float] = span) -> float:
            anti = poly.integ()
            return float(anti(s[1]) - anti(s[0]))

        m0 += integral(area)
        mx += integral(area * X)
        mxx += integral(area * X * X)
        myy += integral(area * a * a / 3.0)  # integral of y^2 over the section
        mzz += integral(area * b * b / 3.0)  # of (z - zc)^2
    xc = mx / m0
    sxx = mxx - m0 * xc * xc  # integral of (x - xc)^2
    inertia = np.diag([myy + mzz, sxx + mzz, sxx + myy])
    return m0, np.array([xc, 0.0, zc]), inertia


def test_loft_of_rectangles_is_a_box_with_the_analytic_mass_properties() -> None:
    x = np.array([-2.1, -1.3, 0.2, 0.25, 1.9])  # uneven stations
    sec = np.stack([rectangle(0.8, 0.6, 0.9)] * len(x))
    mesh = loft(x, sec)
    assert mesh.is_watertight and mesh.is_volume and mesh.body_count == 1
    a, b, c = 4.0, 1.6, 1.2  # box edges along x, y, z
    volume = a * b * c
    box_inertia = volume / 12.0 * np.diag([b * b + c * c, a * a + c * c, a * a + b * b])
    assert mesh.volume == pytest.approx(volume, rel=1e-12)
    assert np.allclose(mesh.center_mass, [-0.1, 0.0, 0.9], rtol=0, atol=1e-12)
    assert np.allclose(mesh.moment_inertia, box_inertia, rtol=0, atol=1e-9 * box_inertia.max())
    assert crossing_pairs(mesh) == 0


def test_loft_of_changing_rectangles_has_the_integrated_mass_properties() -> None:
    x = np.array([-2.0, -1.7, 0.0, 1.5, 2.2])
    half_y = np.array([0.5, 0.8, 0.9, 0.85, 0.4])
    half_z = np.array([0.2, 0.5, 0.7, 0.6, 0.25])
    zc = 0.75
    sec = np.stack([rectangle(hy, hz, zc, 4) for hy, hz in zip(half_y, half_z, strict=True)])
    mesh = loft(x, sec)
    assert mesh.is_watertight and mesh.is_volume
    volume, centroid, inertia = frustum_properties(x, half_y, half_z, zc)
    assert mesh.volume == pytest.approx(volume, rel=1e-9)
    assert np.allclose(mesh.center_mass, centroid, rtol=0, atol=1e-9)
    assert np.allclose(mesh.moment_inertia, inertia, rtol=0, atol=1e-9 * inertia.max())


def test_body_mass_properties_agree_with_the_engine(preset_body) -> None:
    """The engine's divergence-theorem mass properties (both entry points) against trimesh's,
    to 1e-6 relative (of the volume, the body's length and the largest moment)."""
    p, mesh = preset_body
    tensor = mesh.moment_inertia
    for props in (
        _core.Shape(mesh.vertices, mesh.faces).solid_properties(),
        _core.solid_properties(mesh.vertices, mesh.faces),
    ):
        assert props["volume"] == pytest.approx(mesh.volume, rel=1e-6)
        assert np.allclose(props["centroid"], mesh.center_mass, rtol=0, atol=1e-6 * p.length)
        assert np.allclose(props["inertia"], tensor, rtol=0, atol=1e-6 * np.abs(tensor).max())


def test_loft_refuses_bad_input() -> None:
    sec = np.stack([rectangle(0.5, 0.5, 1.0)] * 3)
    with pytest.raises(MeshError, match="strictly increasing"):
        loft(np.array([0.0, 1.0, 1.0]), sec)
    with pytest.raises(MeshError, match="counter-clockwise"):
        loft(np.array([0.0, 1.0, 2.0]), sec[:, ::-1])


# -- bad input ---------------------------------------------------------------------------------

SEDAN = default_dims("sedan")


def sedan(**changes: float) -> BodyParams:
    args = {**SEDAN, **changes}
    return body_params("sedan", **args)


@pytest.mark.parametrize(
    ("changes", "message"),
    [
        ({"length": float("nan")}, r"length = nan is invalid: give a finite number"),
        ({"width": float("inf")}, r"width = inf is invalid"),
        ({"height": 0.0}, r"height = 0.0 m is invalid: it must be > 0 m"),
        ({"wheelbase": -2.7}, r"wheelbase = -2.7 m is invalid"),
        ({"length": "4.8"}, r"length must be a number of metres, got '4.8'"),
        ({"wheel_radius": -0.3}, r"wheel_radius = -0.3 m is invalid"),
        ({"tumblehome": -0.01}, r"tumblehome = -0.01 m is invalid: it must be >= 0 m"),
        ({"bumper_radius": 0.0}, r"bumper_radius = 0.0 m is invalid"),
        ({"wheelbase": 5.0}, r"wheelbase = 5.0 m is not shorter than length"),
        (
            {"length": 4.85, "wheelbase": 3.5, "front_overhang": 0.95, "wheel_radius": 0.32},
            r"rear overhang .* = 0.4 m\) leaves no bumper behind the rear wheel arch",
        ),
        (
            {"wheelbase": 2.2, "front_overhang": 2.7},
            r"wheelbase \+ front_overhang = 4.9 m is not shorter than length",
        ),
        (
            {"front_overhang": 0.35, "wheel_radius": 0.31},
            r"front_overhang = 0.35 m leaves no bumper ahead",
        ),
        ({"front_overhang": 0.2}, r"front_overhang = 0.2 m leaves no bumper ahead"),
        ({"wheelbase": 0.8, "wheel_radius": 0.4}, r"wheelbase = 0.8 m is too short for two"),
        ({"wheelbase": 0.4}, r"wheelbase = 0.4 m is too short for two wheel arches"),
        ({"wheel_radius": 0.45}, r"front wheel arch does not fit: .* lower wheel_radius"),
        ({"ground_clearance": 0.35}, r"ground_clearance = 0.35 m is not below the wheel centres"),
        ({"bumper_radius": 0.95}, r"bumper_radius = 0.95 m is not less than half the width"),
        ({"width": 1.83, "bumper_radius": 0.915}, r"not less than half the width \(0.915 m\)"),
        ({"width": 3.0, "bumper_radius": 1.2}, r"bumper_radius = 1.2 m is larger than the front"),
        (
            {"height": 1.45, "beltline": 1.5},
            r"beltline = 1.5 m is not below the roof \(height = 1.45 m\)",
        ),
        ({"height": 1.45, "beltline": 1.45}, r"beltline = 1.45 m is not below the roof"),
        ({"hood_height": 1.6}, r"hood_height = 1.6 m is above the roof"),
        ({"roof_start": 1.5}, r"roof_start = 1.5 m \(from the front\) must be at least 0.01 m"),
        ({"rear_window_end": 5.0}, r"rear_window_end = 5 m .* is behind the rear face"),
        ({"arch_depth": 0.8}, r"arch_depth = 0.8 m reaches too far in"),
        ({"arch_depth": 0.01}, r"arch_depth = 0.01 m is too small"),
        ({"tumblehome": 0.5}, r"tumblehome = 0.5 m narrows the roof"),
        (
            {"nose_height": 0.45, "edge_radius": 0.1},
            r"the front face is too low: nose_height - bumper_bottom",
        ),
        ({"nose_height": 0.35}, r"the front face is too low: nose_height - bumper_bottom"),
        ({"bumper_bottom": 0.1}, r"bumper_bottom = 0.1 m is below ground_clearance"),
        ({"beltline": 0.45, "wheel_radius": 0.31}, r"rear wheel arch does not fit: .* or beltline"),
        ({"beltline": 0.4}, r"rear wheel arch does not fit: .* or beltline"),
        (
            {"edge_radius": 0.2, "front_overhang": 0.5, "wheel_radius": 0.32},
            r"edge_radius = 0.2 m reaches into a wheel arch .* 0.14 m\): lower edge_radius",
        ),
    ],
)
def test_bad_parameters_are_named_with_a_fix(changes: dict, message: str) -> None:
    with pytest.raises(ParameterError, match=message):
        sedan(**changes)


def test_unknown_preset_lists_the_known_ones() -> None:
    with pytest.raises(ParameterError, match=r"unknown preset 'coupe': use one of sedan, suv"):
        body_params("coupe", **SEDAN)


def test_unknown_shape_parameter_lists_the_known_ones() -> None:
    with pytest.raises(ParameterError, match=r"unknown shape parameter\(s\) roof_height: .*"):
        body_params("sedan", **SEDAN, roof_height=1.4)


def test_missing_dimension_is_a_type_error() -> None:
    with pytest.raises(TypeError, match="wheelbase"):
        body_params("sedan", length=4.8, width=1.8, height=1.4)  # type: ignore[call-arg]


def test_bad_resolution_and_bad_params_object() -> None:
    p = sedan()
    for bad in (0.0, -1.0, float("nan"), 100.0, "1"):
        with pytest.raises(ParameterError, match="resolution"):
            generate_body(p, bad)  # type: ignore[arg-type]
    with pytest.raises(ParameterError, match="needs a BodyParams"):
        generate_body(SEDAN)  # type: ignore[arg-type]


def test_params_are_frozen_and_defaults_scale_with_the_dimensions() -> None:
    p = sedan()
    with pytest.raises(AttributeError):
        p.length = 5.0  # type: ignore[misc]
    # a changed copy is checked like a new one
    with pytest.raises(ParameterError, match="beltline = 2.0 m is not below the roof"):
        dataclasses.replace(p, beltline=2.0)
    assert dataclasses.replace(p, beltline=0.95).beltline == 0.95
    q = sedan(length=SEDAN["length"] * 1.1)
    assert q.windshield_base == pytest.approx(p.windshield_base * 1.1, rel=1e-12)
    assert q.wheel_radius == p.wheel_radius  # absolute defaults stay
    assert p.rear_overhang == pytest.approx(p.length - p.front_overhang - p.wheelbase)
    given = sedan(bumper_radius=0.4, beltline=0.9)
    assert (given.bumper_radius, given.beltline) == (0.4, 0.9)


# -- determinism and the reference meshes ------------------------------------------------------


def load_script() -> ModuleType:
    path = REPO / "scripts" / "make_meshes.py"
    spec = importlib.util.spec_from_file_location("make_meshes", path)
    assert spec is not None and spec.loader is not None
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


@pytest.mark.parametrize("preset", PRESETS)
def test_reference_mesh_regenerates_bit_for_bit(preset: str) -> None:
    script = load_script()
    committed = MESHES / f"{preset}.ply"
    assert committed.is_file(), f"{committed} is missing: run python3 scripts/make_meshes.py"
    assert script.build(preset) == committed.read_bytes()
    # and the README states its sha256
    digest = hashlib.sha256(committed.read_bytes()).hexdigest()
    assert digest in (MESHES / "README.md").read_text()


def test_reference_mesh_reads_back_as_the_generated_body() -> None:
    p = body_params("suv", **default_dims("suv"))
    mesh = generate_body(p)
    back = trimesh.load_mesh(MESHES / "suv.ply", process=False)
    assert np.array_equal(back.vertices, mesh.vertices)
    assert np.array_equal(back.faces, mesh.faces)


def test_generation_does_not_depend_on_hash_seeds() -> None:
    """Bytes from fresh interpreters with different hash seeds (set and dict ordering) equal
    the bytes made here."""
    code = (
        "import hashlib, sys\n"
        "from crashsim.vehicles.generator import *\n"
        "p = body_params('pickup', **default_dims('pickup'), tumblehome=0.07)\n"
        "sys.stdout.write(hashlib.sha256(ply_bytes(generate_body(p, 0.7))).hexdigest())\n"
    )
    p = body_params("pickup", **default_dims("pickup"), tumblehome=0.07)
    here = hashlib.sha256(ply_bytes(generate_body(p, 0.7))).hexdigest()
    for seed in ("1", "2"):
        env = {**os.environ, "PYTHONHASHSEED": seed}
        out = subprocess.run(
            [sys.executable, "-c", code], env=env, capture_output=True, text=True, check=True
        )
        assert out.stdout == here
