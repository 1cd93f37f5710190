"""Top-down pictures (crashsim.plots): the drawn outlines are the meshes' true silhouettes,
the arrows are the impact's numbers at the stated scales, and the PNGs reopen at their size.

Silhouettes are checked against closed forms (a box's rectangle, a rolled box's wider strip)
and, for the shared real meshes, against an independent rasterisation: every triangle
filled by barycentric tests on a 1 cm grid of pixel centres, which must agree with the
silhouette at every pixel centre farther than 1 um from its boundary.
"""

from __future__ import annotations

import math
import re
import warnings
from pathlib import Path

import crashsim as cs
import matplotlib.image as mpimg
import numpy as np
import pytest
import shapely
import trimesh
from conftest import mesh_mass, seed_side_impact
from crashsim import _core, plots
from crashsim.plots import (
    DPI,
    IMPACT_FIGSIZE,
    SLIVER_AREA,
    TRAJECTORY_FIGSIZE,
    plot_impact,
    plot_trajectories,
    silhouette,
)
from matplotlib.patches import FancyArrowPatch, PathPatch

RED = (4.5, 1.8, 1.4)  # m, the seed's bullet vehicle
BLUE = (4.6, 1.8, 1.45)  # m, the struck vehicle


@pytest.fixture(scope="module")
def seed90() -> cs.Result:
    return seed_side_impact(cs.mph(30.0), 0.0, (-3.65, 0.3))


@pytest.fixture(scope="module")
def seed45() -> cs.Result:
    return seed_side_impact(cs.mph(60.0), cs.deg(45.0), (-4.0, -3.0))


def rotation(yaw: float = 0.0, pitch: float = 0.0, roll: float = 0.0) -> np.ndarray:
    """Body -> world, R = Rz(yaw) Ry(pitch) Rx(roll) (rad)."""
    cy, sy, cp, sp, cr, sr = (f(a) for a in (yaw, pitch, roll) for f in (math.cos, math.sin))
    rz = np.array([[cy, -sy, 0.0], [sy, cy, 0.0], [0.0, 0.0, 1.0]])
    ry = np.array([[cp, 0.0, sp], [0.0, 1.0, 0.0], [-sp, 0.0, cp]])
    rx = np.array([[1.0, 0.0, 0.0], [0.0, cr, -sr], [0.0, sr, cr]])
    return rz @ ry @ rx


def patch_polygon(fig, gid: str) -> shapely.Geometry:
    """The drawn outline with this gid, rebuilt as a shapely polygon from its path."""
    found = [a for ax in fig.axes for a in ax.patches if a.get_gid() == gid]
    assert len(found) == 1, gid
    patch = found[0]
    assert isinstance(patch, PathPatch)
    rings = [shapely.Polygon(r) for r in patch.get_path().to_polygons(closed_only=True)]
    out = rings[0]
    for ring in rings[1:]:  # even-odd: a hole's ring cuts it out, a part's ring adds it
        out = out.symmetric_difference(ring)
    return out


def patch_polygon_in(fig, ax, gid: str) -> shapely.Geometry:
    """patch_polygon of one panel."""
    found = [a for a in ax.patches if a.get_gid() == gid]
    assert len(found) == 1, gid
    rings = [shapely.Polygon(r) for r in found[0].get_path().to_polygons(closed_only=True)]
    return shapely.union_all(rings)


def arrows(fig, colour: str) -> list[np.ndarray]:
    """(tail, head) of the FancyArrowPatches of one colour, per arrow (data units, m)."""
    from matplotlib.colors import to_rgba

    out = []
    for ax in fig.axes:
        for a in ax.patches:
            if isinstance(a, FancyArrowPatch) and a.get_facecolor() == to_rgba(colour):
                out.append(np.asarray(a._posA_posB, dtype=float))  # tail, head (m)
    return out


def legend_scale(fig, prefix: str) -> float:
    """The number in '<prefix> (1 m = N unit)' of the figure legend."""
    texts = [t.get_text() for leg in fig.legends for t in leg.get_texts()]
    for t in texts:
        if t.startswith(prefix):
            m = re.search(r"\(1 m = ([0-9.eE+-]+) ", t)
            assert m, t
            return float(m.group(1))
    raise AssertionError(f"no legend entry starting {prefix!r} in {texts}")


# -- silhouettes: closed forms -------------------------------------------------------------


@pytest.mark.parametrize("yaw_deg", [0.0, 30.0, 90.0, -135.0])
def test_box_silhouette_is_its_rectangle(yaw_deg: float) -> None:
    box = cs.Vehicle.box(*RED, mass=1450.0, name="red")
    p = np.array([1.25, -2.5, 0.7])
    r = rotation(math.radians(yaw_deg))
    sil = silhouette(box, p, r)
    assert sil.geom_type == "Polygon" and not sil.interiors
    assert sil.area == pytest.approx(RED[0] * RED[1], abs=1e-9)  # 8.1 m^2
    corners = np.array([[sx * RED[0] / 2, sy * RED[1] / 2] for sx in (-1, 1) for sy in (-1, 1)])
    world = corners @ r[:2, :2].T + p[:2]
    assert np.allclose(shapely.bounds(sil), [*world.min(0), *world.max(0)], rtol=0, atol=1e-9)
    # the corners are the outline's vertices: each lies on it (to round-off)
    assert max(sil.exterior.distance(shapely.Point(c)) for c in world) < 1e-9


def test_rolled_box_silhouette_is_the_wider_strip() -> None:
    # rolled by phi about its x axis, a W x H cross-section projects to W cos phi + H sin phi
    box = cs.Vehicle.box(*RED, mass=1450.0, name="red")
    phi = math.radians(25.0)
    sil = silhouette(box, (0.0, 0.0, 1.0), rotation(roll=phi))
    width = RED[1] * math.cos(phi) + RED[2] * math.sin(phi)
    assert sil.area == pytest.approx(RED[0] * width, abs=1e-9)
    assert np.allclose(
        shapely.bounds(sil), [-RED[0] / 2, -width / 2, RED[0] / 2, width / 2], rtol=0, atol=1e-9
    )


def test_a_closed_mesh_is_outlined_by_its_up_facing_triangles_an_open_one_by_all() -> None:
    # The outline of a solid is the union of its triangles facing up (half of them: 1.7 s ->
    # 1.3 s for the demo's run picture); an open mesh keeps them all.
    car = cs.Vehicle.generate("sedan")
    faces = np.asarray(car.mesh.faces)
    for r in (rotation(0.3, 0.1, 0.2), rotation(2.0, -0.3, 0.5), rotation(0.0, 0.0, 3.0)):
        p = np.array([1.0, -2.0, 0.6])
        world = (car.body_vertices @ r.T + p)[:, :2]
        every = shapely.union_all(shapely.polygons(world[faces]), grid_size=1e-9)
        assert silhouette(car, p, r).symmetric_difference(every).area < 1e-8
    box = trimesh.creation.box((4.0, 1.8, 1.4))
    roofless = trimesh.Trimesh(box.vertices, box.faces[box.face_normals[:, 2] < 0.5])
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # an open mesh: the loader says so
        open_car = cs.Vehicle.from_mesh(roofless, mass=1500.0, cg=(0.0, 0.0, 0.0))
    closed_car = cs.Vehicle.from_mesh(box, mass=1500.0, cg=(0.0, 0.0, 0.0))
    p, r = np.array([0.0, 0.0, 0.7]), rotation(0.2, 0.1, 0.0)
    assert plots._closed(closed_car) and not plots._closed(open_car)
    assert silhouette(open_car, p, r).symmetric_difference(silhouette(closed_car, p, r)).area < 1e-8


def test_silhouette_where_geos_meets_a_non_noded_intersection() -> None:
    # The generated sedan at rest after the demo's impact (tilted 0.2 deg): GEOS's union of its
    # projected triangles raised "TopologyException: found non-noded intersection"; they are
    # united again snapped to SNAP_GRID (1 um). The outline covers every projected vertex and
    # reaches the projection's bounds (to the snapping).
    car = cs.Vehicle.generate("sedan", name="red")
    p = np.array([1.3421106093799675, -0.9782412717082506, 0.5471214573812396])
    r = np.array(
        [
            [0.04828542092909405, -0.9988302382733881, -0.0025832608128058022],
            [0.9988319826573678, 0.048289805862297586, -0.0016628501235617596],
            [0.001785650148272198, -0.0024999521012177275, 0.9999952808353846],
        ]
    )
    world = (car.body_vertices @ r.T + p)[:, :2]
    tri = world[np.asarray(car.mesh.faces)]
    with pytest.raises(shapely.errors.GEOSException, match="non-noded"):
        shapely.union_all(shapely.polygons(tri))  # what the picture met
    sil = silhouette(car, p, r)
    assert sil.geom_type == "Polygon"
    assert np.allclose(shapely.bounds(sil), [*world.min(0), *world.max(0)], rtol=0, atol=2e-6)
    assert shapely.buffer(sil, 2e-6).contains(shapely.multipoints(world))
    # the area of the snapped union is the unsnapped one's to round-off (1 nm grid)
    fine = shapely.union_all(shapely.polygons(tri), grid_size=1e-9)
    assert sil.area == pytest.approx(fine.area, abs=1e-5)


def test_drawn_box_outlines_equal_the_rectangles(seed90: cs.Result) -> None:
    fig = plot_impact(seed90)
    imp = seed90.impacts[0]
    for name, (length, width, _), heading in (("red", RED, 0.0), ("blue", BLUE, 90.0)):
        for when, t in (("first_contact", imp.first_contact_time), ("exchange", imp.time)):
            drawn = patch_polygon(fig, f"silhouette:{name}:{when}")
            cg = seed90.pose(name, t)[0]
            assert drawn.area == pytest.approx(length * width, abs=1e-9)
            extent = (length, width) if heading == 0.0 else (width, length)  # along x, y
            half = np.array(extent) / 2
            expected = [*(cg[:2] - half), *(cg[:2] + half)]
            assert np.allclose(shapely.bounds(drawn), expected, rtol=0, atol=1e-9)


# -- silhouettes: real meshes against a rasterisation ----------------------------------------


def rasterise(xy: np.ndarray, faces: np.ndarray, pixel: float) -> tuple[np.ndarray, ...]:
    """Pixel centres (X, Y) over the points' box and whether each lies in some triangle
    (barycentric coordinates >= 0), an implementation independent of shapely."""
    lo, hi = xy.min(axis=0), xy.max(axis=0)
    xs = np.arange(lo[0] + pixel / 2, hi[0], pixel)
    ys = np.arange(lo[1] + pixel / 2, hi[1], pixel)
    inside = np.zeros((ys.size, xs.size), dtype=bool)
    for a, b, c in xy[faces]:
        det = (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0])
        if abs(det) < 1e-14:
            continue  # edge-on: no area
        tri = np.array([a, b, c])
        i0 = max(int(np.ceil((tri[:, 0].min() - xs[0]) / pixel)), 0)
        i1 = int(np.floor((tri[:, 0].max() - xs[0]) / pixel)) + 1
        j0 = max(int(np.ceil((tri[:, 1].min() - ys[0]) / pixel)), 0)
        j1 = int(np.floor((tri[:, 1].max() - ys[0]) / pixel)) + 1
        if i1 <= i0 or j1 <= j0:
            continue
        x, y = np.meshgrid(xs[i0:i1], ys[j0:j1])
        l1 = ((b[0] - x) * (c[1] - y) - (b[1] - y) * (c[0] - x)) / det
        l2 = ((c[0] - x) * (a[1] - y) - (c[1] - y) * (a[0] - x)) / det
        inside[j0:j1, i0:i1] |= (l1 >= 0) & (l2 >= 0) & (1.0 - l1 - l2 >= 0)
    x, y = np.meshgrid(xs, ys)
    return x, y, inside


PIXEL = 0.01  # m


def check_against_raster(sil: shapely.Geometry, xy: np.ndarray, faces: np.ndarray) -> None:
    x, y, inside = rasterise(xy, faces, PIXEL)
    drawn = shapely.contains_xy(sil, x, y)
    differ = drawn != inside
    if differ.any():  # only on the boundary (round-off) or in dropped slivers
        d = shapely.distance(sil.boundary, shapely.points(x[differ], y[differ]))
        assert np.max(d) < 1e-6 or differ.sum() * PIXEL**2 < SLIVER_AREA, (differ.sum(), d.max())
    # area: the pixel count misses at most a pixel-wide band along the boundary
    raster_area = inside.sum() * PIXEL**2
    assert abs(sil.area - raster_area) <= 0.5 * sil.boundary.length * PIXEL


def test_real_mesh_silhouette_is_its_projection_not_its_hull(mesh_path: Path) -> None:
    v = cs.Vehicle.from_mesh(mesh_path, mass=mesh_mass(mesh_path))
    sil = silhouette(v)
    xy = v.body_vertices[:, :2]
    hull = shapely.convex_hull(shapely.multipoints(xy))
    assert 0.5 * hull.area < sil.area < hull.area
    # the hull would be visibly wrong: it adds 2-8 % on the shared meshes (measured)
    assert hull.area - sil.area > 0.01 * hull.area
    check_against_raster(sil, xy, np.asarray(v.mesh.faces))


def test_tilted_real_mesh_silhouette_is_its_projection() -> None:
    from conftest import shared_mesh_paths

    paths = [p for p in shared_mesh_paths() if p.stem.startswith("sedan")]
    if not paths:
        pytest.skip("the shared sedan mesh is absent")
    v = cs.Vehicle.from_mesh(paths[0], mass=1450.0)
    r = rotation(yaw=0.5, pitch=0.17, roll=0.35)  # not a pure yaw: projected afresh
    p = np.array([2.0, -1.0, 0.6])
    sil = silhouette(v, p, r)
    world = (v.body_vertices @ r.T + p)[:, :2]
    check_against_raster(sil, world, np.asarray(v.mesh.faces))
    assert sil.area > silhouette(v).area  # rolled and pitched, the car shows more of itself


# -- the impact diagram ----------------------------------------------------------------------


def test_impact_png_reopens_with_its_size_and_two_panels(seed90: cs.Result, tmp_path: Path):
    path = tmp_path / "impact.png"
    fig = plot_impact(seed90, path)
    image = mpimg.imread(path)
    w, h = IMPACT_FIGSIZE
    assert image.shape == (round(h * DPI), round(w * DPI), 4)
    assert len(fig.axes) == 2
    first, exchange = fig.axes
    assert first.get_title().startswith("First overlap, t = 0.0373 s")
    assert exchange.get_title().startswith("Impulse exchange, t = 0.0673 s (30.0 ms")
    for ax in fig.axes:  # metres on both axes, the same view in both panels
        assert ax.get_aspect() == 1.0
        assert ax.get_xlim() == first.get_xlim() and ax.get_ylim() == first.get_ylim()
    # the image is not blank: outlines and arrows put many colours in it
    rgba8 = np.ascontiguousarray(np.round(image * 255).astype(np.uint8)).view(np.uint32)
    assert np.unique(rgba8).size > 100
    caption = fig.get_suptitle()
    assert "closing speed 13.41 m/s (30.0 mph)" in caption
    assert "delta-V red 7.35 m/s" in caption and "delta-V blue 7.10 m/s" in caption


@pytest.mark.parametrize("case", ["seed90", "seed45"])
def test_arrows_are_the_impacts_numbers_at_the_stated_scales(case: str, request) -> None:
    result: cs.Result = request.getfixturevalue(case)
    imp = result.impacts[0]
    fig = plot_impact(result)
    v_unit = legend_scale(fig, "delta-V of the CG")  # m/s per m of arrow
    assert legend_scale(fig, "velocity at first overlap") == v_unit
    j_unit = legend_scale(fig, "impulse on the vehicle") * 1e3  # N s per m of arrow
    for name, colour in (("red", "#d62728"), ("blue", "#1f77b4")):
        drawn = {tuple(np.round(a[0], 9)): a[1] - a[0] for a in arrows(fig, colour)}
        cg_contact = result.pose(name, imp.first_contact_time)[0][:2]
        cg_exchange = result.pose(name, imp.time)[0][:2]
        v = result.state(name, imp.first_contact_time)["velocity"][:2]
        expected = {
            "velocity": (cg_contact, v / v_unit),
            "delta-V": (cg_exchange, imp.delta_v[name][:2] / v_unit),
            "impulse": (imp.centroid[:2], imp.impulse_on(name)[:2] / j_unit),
        }
        for what, (tail, vec) in expected.items():
            if np.linalg.norm(vec) < 1e-9:
                continue  # blue is at rest at first contact: no arrow
            key = tuple(np.round(tail, 9))
            assert key in drawn, (name, what)
            assert np.allclose(drawn[key], vec, rtol=0, atol=1e-9), (name, what)
        # the impulse on blue (vehicle 2) points along n; the one on red against it
        sign = 1.0 if name == "blue" else -1.0
        j = imp.impulse_on(name)[:2]
        assert sign * float(j @ imp.normal[:2]) > 0.0
    # the normal arrow: black, unit direction n
    (n_arrow,) = arrows(fig, "black")
    d = n_arrow[1] - n_arrow[0]
    assert np.allclose(d / np.linalg.norm(d), imp.normal[:2] / np.linalg.norm(imp.normal[:2]))


def test_real_mesh_impact_draws_the_true_outlines(tmp_path: Path) -> None:
    from conftest import shared_mesh_paths

    paths = {p.stem.split("_")[0]: p for p in shared_mesh_paths()}
    if not {"sedan", "pickup"} <= paths.keys():
        pytest.skip("the shared sedan and pickup meshes are absent")
    sedan = cs.Vehicle.from_mesh(paths["sedan"], mass=1450.0, name="sedan")
    pickup = cs.Vehicle.from_mesh(paths["pickup"], mass=2200.0, name="pickup")
    scene = cs.Scene(depth_of_penetration=0.030)
    scene.add(sedan, position=(-3.6, 0.4, sedan.cg[2] + 0.005), velocity=(cs.mph(30.0), 0, 0))
    scene.add(pickup, position=(0.0, 0.0, pickup.cg[2] + 0.005), heading=cs.deg(90.0))
    result = scene.run(duration=0.15, dt=1e-3)
    fig = plot_impact(result, tmp_path / "sedan_pickup.png")
    imp = result.impacts[0]
    for name in ("sedan", "pickup"):
        p, r = result.pose(name, imp.time)
        drawn = patch_polygon(fig, f"silhouette:{name}:exchange")
        expected = silhouette(result.vehicle(name), p, r)
        assert drawn.symmetric_difference(expected).area < 1e-9
    assert (tmp_path / "sedan_pickup.png").stat().st_size > 0


def test_an_impact_with_a_fixed_obstacle_is_drawn(tmp_path: Path) -> None:
    # Was: plot_impact drew two vehicles only (a KeyError on the obstacle's delta-V), and
    # `crashsim run` wrote no impact-N.png for an obstacle. The pole is drawn where it stands,
    # the impulse on it at the centroid in grey; only the car has a velocity and a delta-V.
    car = cs.Vehicle.box(*RED, mass=1450.0, name="red")
    scene = cs.Scene(depth_of_penetration=0.030)
    scene.add(car, position=(-3.0, 0.4, 0.7), velocity=(10.0, 0.0, 0.0))
    scene.add_obstacle(cs.Obstacle.pole(0.3, name="pole"), (0.0, 0.0, 0.0))
    result = scene.run(duration=0.2, dt=1e-3)
    (imp,) = result.impacts
    assert imp.obstacle == "pole"
    fig = plot_impact(result, tmp_path / "impact-1.png")
    assert (tmp_path / "impact-1.png").stat().st_size > 10_000
    pole = cs.Obstacle.pole(0.3)
    for drawn in (patch_polygon_in(fig, ax, "obstacle:pole") for ax in fig.axes):
        outline = shapely.union_all(shapely.polygons(pole.mesh.vertices[pole.mesh.faces][..., :2]))
        assert drawn.symmetric_difference(outline).area < 1e-9  # at (0, 0), heading 0
    j_unit = legend_scale(fig, "impulse on the vehicle") * 1e3  # N s per m of arrow
    v_unit = legend_scale(fig, "delta-V of the CG")
    (on_pole,) = arrows(fig, plots.OBSTACLE_EDGE)
    assert np.allclose(on_pole[0], imp.centroid[:2], rtol=0, atol=1e-9)
    assert np.allclose(on_pole[1] - on_pole[0], imp.impulse_on("pole")[:2] / j_unit, atol=1e-9)
    red = {tuple(np.round(a[0], 9)): a[1] - a[0] for a in arrows(fig, "#d62728")}
    assert len(red) == 3  # velocity at first overlap, impulse on red, delta-V
    cg = result.pose("red", imp.time)[0][:2]
    assert np.allclose(red[tuple(np.round(cg, 9))], imp.delta_v["red"][:2] / v_unit, atol=1e-9)
    caption = fig.get_suptitle()
    assert caption.startswith("Impact 1 of 1: red and pole")
    assert f"delta-V red {imp.speed_change('red'):.2f} m/s" in caption
    assert "pole is fixed (no delta-V)" in caption
    texts = [t.get_text() for leg in fig.legends for t in leg.get_texts()]
    assert "pole: fixed obstacle (infinite mass)" in texts


def test_impact_errors(seed90: cs.Result) -> None:
    with pytest.raises(cs.ParameterError, match="out of range"):
        plot_impact(seed90, impact=1)
    miss = cs.Scene()
    miss.add(cs.Vehicle.box(*RED, mass=1450.0, name="a"), position=(0, 0, 0.7))
    miss.add(cs.Vehicle.box(*RED, mass=1450.0, name="b"), position=(0, 5, 0.7))
    with pytest.raises(cs.SceneError, match="no impacts"):
        plot_impact(miss.run(duration=0.01))
    bare = seed_side_impact(cs.mph(30.0), 0.0, (-3.65, 0.3))
    bare.scene = None
    with pytest.raises(cs.SceneError, match="no scene"):
        plot_impact(bare)
    with pytest.raises(cs.SceneError, match="no scene"):
        plot_trajectories(bare)


# -- the whole run --------------------------------------------------------------------------


def test_trajectory_png_reopens_with_its_size(seed45: cs.Result, tmp_path: Path) -> None:
    path = tmp_path / "run.png"
    fig = plot_trajectories(seed45, path, count=5)
    image = mpimg.imread(path)
    w, h = TRAJECTORY_FIGSIZE
    assert image.shape == (round(h * DPI), round(w * DPI), 4)
    (ax,) = fig.axes
    assert ax.get_aspect() == 1.0
    # 5 faded outlines per vehicle plus one bold at the exchange, each a PathPatch
    outlines = [a for a in ax.patches if isinstance(a, PathPatch)]
    assert len(outlines) == 2 * (5 + 1)
    stamps = sorted(t.get_text() for t in ax.texts if t.get_text().endswith(" s"))
    assert stamps.count("0.00 s") == 2 and stamps.count("0.30 s") == 2
    with pytest.raises(cs.ParameterError, match="count"):
        plot_trajectories(seed45, count=1)


# -- several impacts: captions and labels ---------------------------------------------------


@pytest.fixture(scope="module")
def three() -> cs.Result:
    from conftest import REPO
    from crashsim.io.scenefile import load_scene

    return load_scene(REPO / "examples" / "three-vehicles.toml").simulate()


def test_trajectories_title_fully_visible_and_numbers_do_not_overlap(three: cs.Result) -> None:
    # Was: the second title line (all impacts on one line) was cut at both edges, and the
    # "impact N, t s" labels of six exchanges piled over each other.
    fig = plot_trajectories(three)
    renderer = fig.canvas.get_renderer()
    fig.canvas.draw()
    page = fig.bbox
    title = fig._suptitle.get_window_extent(renderer)
    assert page.x0 <= title.x0 and title.x1 <= page.x1 and title.y1 <= page.y1
    caption = fig.get_suptitle().splitlines()
    assert all(len(line) <= plots.CAPTION_CHARS for line in caption)
    for k, imp in enumerate(three.impacts, start=1):
        assert f"{k} at {imp.time:.3f} s {imp.vehicles[0]}-{imp.vehicles[1]}" in " ".join(caption)
    (ax,) = fig.axes
    numbers = [t for t in ax.texts if (t.get_gid() or "").startswith("impact-number:")]
    assert sorted(t.get_text() for t in numbers) == ["1", "2", "3", "4", "5", "6"]
    boxes = [t.get_bbox_patch().get_window_extent(renderer) for t in numbers]
    for i, a in enumerate(boxes):
        for b in boxes[i + 1 :]:
            assert not a.overlaps(b)
    marks = ax.transData.transform([imp.centroid[:2] for imp in three.impacts])
    for box in boxes:  # no number covers a centroid marker
        assert not any(box.contains(x, y) for x, y in marks)
    assert not [t for t in ax.texts if t.get_text().startswith("impact ")]


def test_secondary_exchange_picture_says_so_and_how_deep(three: cs.Result) -> None:
    # Was: "the meshes touch" over a secondary exchange whose meshes were 0.65 m inside
    # each other when its timer started.
    first = plot_impact(three, impact=0)
    assert first.axes[0].get_title().startswith("First overlap, t = 0.0420 s")
    assert "the meshes first touch" in first.axes[0].get_title()
    assert "secondary" not in first.get_suptitle()
    imp = three.impacts[2]
    assert imp.secondary
    fig = plot_impact(three, impact=2)
    left, right = (ax.get_title() for ax in fig.axes)
    assert left.startswith("Closing again (secondary exchange), t = 0.1489 s")
    assert "touch" not in left
    depth = float(left.split("the meshes ")[1].split(" m inside")[0])
    region = _core.overlap_region(
        *[
            x
            for name in imp.vehicles
            for x in (
                three.vehicle(name).shape,
                three.state(name, imp.first_contact_time)["position"],
                three.state(name, imp.first_contact_time)["orientation"],
            )
        ]
    )
    along = np.asarray(region["points"]) @ imp.normal
    assert depth == pytest.approx(float(np.ptp(along)), abs=0.005) and depth > 0.5
    assert right.startswith("Impulse exchange, t = 0.1789 s (30.0 ms after closing again)")
    caption = fig.get_suptitle()
    assert "secondary exchange: the pair stayed engaged after the exchange of impact 1" in caption
    assert "impact 2 (blue-green) at 0.148892 s changed blue's velocity" in caption
    assert legend_scale(fig, "velocity at closing again") > 0
