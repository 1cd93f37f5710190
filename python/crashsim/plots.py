"""Top-down pictures of a run: the impact diagram and the whole motion.

Everything is drawn in the world's x-y plane seen from above (z up, out of the page), in
metres with equal axes, so lengths can be read off the grid. A vehicle's outline is its true
silhouette: the union of its mesh triangles projected on the ground plane (shapely), not a
convex hull, so mirrors, wheels and notches show as they are.

Figures are matplotlib ``Figure`` objects on the Agg canvas, built without pyplot, so the
functions are safe in library code, threads and on machines without a display.

    from crashsim.plots import plot_impact, plot_trajectories
    plot_impact(result, "impact.png")         # timer start | exchange, one impact
    plot_trajectories(result, "motion.png")   # the whole run, outlines at regular times
"""

from __future__ import annotations

import functools
import math
from pathlib import Path
from typing import TYPE_CHECKING, Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

from crashsim.errors import ParameterError, SceneError
from crashsim.units import to_mph

if TYPE_CHECKING:
    from matplotlib.axes import Axes
    from matplotlib.figure import Figure

    from crashsim.result import Impact, Result
    from crashsim.vehicles.vehicle import Vehicle

__all__ = [
    "VEHICLE_COLOURS",
    "plot_impact",
    "plot_trajectories",
    "silhouette",
    "vehicle_colour",
]

Array = NDArray[np.float64]

# One colour per vehicle, by its order in the scene (also used by crashsim.io.export).
VEHICLE_COLOURS = ("#d62728", "#1f77b4", "#2ca02c", "#9467bd", "#ff7f0e", "#8c564b")

IMPACT_FIGSIZE = (15.0, 8.2)  # inches: plot_impact's figure
TRAJECTORY_FIGSIZE = (12.0, 8.5)  # inches: plot_trajectories' figure
DPI = 120  # pixels per inch of the PNGs written

# Holes of the projected outline smaller than this are round-off slivers between triangles
# (measured: below 1e-8 m^2 on the shared meshes), not holes through the vehicle (m^2).
SLIVER_AREA = 1e-4
# A rotation is a pure yaw when its z column is (0, 0, 1) to this tolerance: the outline is
# then the body-frame one turned and moved (exact), else the mesh is projected afresh.
YAW_ONLY_TOL = 1e-12
# When GEOS cannot union the projected triangles as they are (a "non-noded intersection" of
# nearly parallel edges, met on a generated sedan tilted 0.2 deg), they are united again with
# their vertices snapped to this grid (m): far below what a picture shows.
SNAP_GRID = 1e-6


def vehicle_colour(index: int) -> str:
    """The colour (hex) of the vehicle added ``index``-th to the scene."""
    return VEHICLE_COLOURS[index % len(VEHICLE_COLOURS)]


# -- silhouettes ---------------------------------------------------------------------------


def _import_shapely() -> Any:
    try:
        import shapely
    except ImportError as e:  # shapely is needed for pictures only
        raise ImportError("vehicle outlines need shapely: pip install shapely") from e
    return shapely


def _projected_union(xy: Array, faces: NDArray[np.int64]) -> Any:
    """The union of the triangles (x-y of their vertices, m) as a shapely (Multi)Polygon,
    with round-off slivers dropped. Triangles seen edge-on (zero projected area) add no area
    and are skipped."""
    shapely = _import_shapely()
    tri = xy[faces]
    e1, e2 = tri[:, 1] - tri[:, 0], tri[:, 2] - tri[:, 0]
    area2 = np.abs(e1[:, 0] * e2[:, 1] - e1[:, 1] * e2[:, 0])
    scale = float(np.max(np.abs(xy))) if xy.size else 1.0
    keep = area2 > 1e-14 * max(scale, 1.0) ** 2
    if not np.any(keep):
        raise SceneError(
            "the mesh has no area seen from above (every triangle is edge-on): it cannot be "
            "drawn top-down"
        )
    # Shared vertices are projected once, so neighbouring triangles share exact edges.
    polygons = shapely.polygons(tri[keep])
    try:
        union = shapely.union_all(polygons)
    except shapely.errors.GEOSException:
        union = shapely.union_all(polygons, grid_size=SNAP_GRID)
    return _clean(union)


def _clean(geom: Any) -> Any:
    """Drops holes and parts smaller than SLIVER_AREA (round-off between triangles)."""
    shapely = _import_shapely()
    from shapely.geometry import MultiPolygon, Polygon

    parts = []
    for g in shapely.get_parts(geom):
        if not isinstance(g, Polygon) or g.area < SLIVER_AREA:
            continue
        holes = [r for r in g.interiors if Polygon(r).area >= SLIVER_AREA]
        parts.append(Polygon(g.exterior, holes))
    if not parts:
        raise SceneError("the vehicle's outline seen from above is empty (a degenerate mesh?)")
    return parts[0] if len(parts) == 1 else MultiPolygon(parts)


@functools.lru_cache(maxsize=32)
def _closed(vehicle: Vehicle) -> bool:
    """Whether the vehicle's mesh bounds a solid (watertight, consistently wound outward): its
    outline seen from above is then the union of the triangles facing up alone (the top of the
    solid over every point of its shadow), half of them."""
    mesh = vehicle.mesh
    return bool(mesh.is_watertight and mesh.is_winding_consistent and mesh.volume > 0.0)


@functools.lru_cache(maxsize=32)
def _body_silhouette(vehicle: Vehicle) -> Any:
    """The outline of the body-frame mesh projected along body z (m, CG at the origin)."""
    return _projected_union(*_shadow_faces(vehicle, vehicle.body_vertices))


def _shadow_faces(vehicle: Vehicle, points: Array) -> tuple[Array, NDArray[np.int64]]:
    """The x-y of the mesh's vertices at ``points`` (n, 3) and the triangles whose union is
    its outline seen from above: those facing up for a closed mesh, else all."""
    faces = np.asarray(vehicle.mesh.faces, dtype=np.int64)
    if _closed(vehicle):
        tri = points[faces]
        faces = faces[np.cross(tri[:, 1] - tri[:, 0], tri[:, 2] - tri[:, 0])[:, 2] > 0.0]
    return points[:, :2].copy(), faces


def silhouette(
    vehicle: Vehicle, position: ArrayLike = (0.0, 0.0, 0.0), rotation: ArrayLike | None = None
) -> Any:
    """The vehicle's outline seen from above at a pose: the union of its mesh triangles
    projected on the world x-y plane, a shapely Polygon (or MultiPolygon when parts are
    apart), in world metres.

    position: the CG in the world (m); rotation: (3, 3) body -> world (default identity). A
    pure yaw turns and moves the body-frame outline (computed once per vehicle); any roll or
    pitch projects the turned mesh afresh."""
    p = np.asarray(position, dtype=np.float64).reshape(3)
    r = np.eye(3) if rotation is None else np.asarray(rotation, dtype=np.float64).reshape(3, 3)
    if not (np.all(np.isfinite(p)) and np.all(np.isfinite(r))):
        raise ParameterError("position and rotation must be finite")
    if np.max(np.abs(r[:, 2] - (0.0, 0.0, 1.0))) <= YAW_ONLY_TOL:
        from shapely import affinity

        base = _body_silhouette(vehicle)
        return affinity.affine_transform(
            base, [r[0, 0], r[0, 1], r[1, 0], r[1, 1], float(p[0]), float(p[1])]
        )
    return _projected_union(*_shadow_faces(vehicle, vehicle.body_vertices @ r.T + p))


# -- drawing helpers -----------------------------------------------------------------------


def _patch(geom: Any, **kw: Any) -> Any:
    """A matplotlib PathPatch of a shapely (Multi)Polygon, holes included."""
    import shapely
    from matplotlib.patches import PathPatch
    from matplotlib.path import Path as MPath
    from shapely.geometry.polygon import orient

    verts: list[Any] = []
    codes: list[int] = []
    for poly in shapely.get_parts(geom):
        poly = orient(poly, 1.0)  # exterior counter-clockwise, holes clockwise
        for ring in [poly.exterior, *poly.interiors]:
            xy = np.asarray(ring.coords)
            verts.extend(xy)
            codes.extend([MPath.MOVETO] + [MPath.LINETO] * (len(xy) - 2) + [MPath.CLOSEPOLY])
    return PathPatch(MPath(np.asarray(verts), codes), **kw)


def _nice(x: float) -> float:
    """The number of the form 1, 2, 2.5 or 5 times a power of ten nearest to x (x > 0), by
    ratio: an arrow scale a reader can multiply with."""
    e = 10.0 ** math.floor(math.log10(x))
    candidates = [m * e for m in (1.0, 2.0, 2.5, 5.0, 10.0)]
    return min(candidates, key=lambda c: abs(math.log(c / x)))


def _fmt(x: float) -> str:
    return f"{x:g}"


def _arrow(
    ax: Axes,
    tail: Array,
    vec: Array,
    colour: str,
    lw: float,
    z: float,
    *,
    style: str = "-|>",
    head: float = 16.0,
    edge: str | None = None,
) -> None:
    """An arrow from ``tail`` along ``vec`` (data units: m), filled with ``colour`` and
    outlined with ``edge`` (default the same colour); none when ``vec`` is shorter than 1 nm."""
    from matplotlib.patches import FancyArrowPatch

    if float(np.hypot(vec[0], vec[1])) < 1e-9:
        return
    ax.add_patch(
        FancyArrowPatch(
            (float(tail[0]), float(tail[1])),
            (float(tail[0] + vec[0]), float(tail[1] + vec[1])),
            arrowstyle=style,
            mutation_scale=head,
            facecolor=colour,
            edgecolor=colour if edge is None else edge,
            linewidth=lw,
            shrinkA=0.0,
            shrinkB=0.0,
            zorder=z,
        )
    )


def _arrow_handler() -> Any:
    """A legend handler that draws a FancyArrowPatch proxy as a short arrow."""
    from matplotlib.legend_handler import HandlerBase
    from matplotlib.patches import FancyArrowPatch

    class ArrowHandler(HandlerBase):
        def create_artists(  # type: ignore[override]
            self,
            legend: Any,
            orig_handle: Any,
            xdescent: float,
            ydescent: float,
            width: float,
            height: float,
            fontsize: float,
            trans: Any,
        ) -> list[Any]:
            y = height / 2.0 - ydescent
            a = FancyArrowPatch(
                (-xdescent, y),
                (width - xdescent, y),
                arrowstyle=orig_handle.get_arrowstyle(),
                mutation_scale=12.0,
                facecolor=orig_handle.get_facecolor(),
                edgecolor=orig_handle.get_edgecolor(),
                linewidth=orig_handle.get_linewidth(),
                transform=trans,
            )
            return [a]

    return ArrowHandler()


def _arrow_proxy(colour: str, lw: float, style: str = "-|>", edge: str | None = None) -> Any:
    from matplotlib.patches import FancyArrowPatch

    return FancyArrowPatch(
        (0, 0),
        (1, 0),
        arrowstyle=style,
        facecolor=colour,
        edgecolor=colour if edge is None else edge,
        linewidth=lw,
    )


def _new_figure(figsize: tuple[float, float]) -> Figure:
    try:
        from matplotlib.backends.backend_agg import FigureCanvasAgg
        from matplotlib.figure import Figure
    except ImportError as e:  # matplotlib is needed for pictures only
        raise ImportError("pictures need matplotlib: pip install matplotlib") from e
    fig = Figure(figsize=figsize, layout="constrained")
    FigureCanvasAgg(fig)
    return fig


class _Pose:
    """A vehicle's pose at one time, with what the drawings need from it (world, m)."""

    def __init__(self, result: Result, name: str, time: float) -> None:
        self.name = name
        self.vehicle = result.vehicle(name)
        self.position, self.rotation = result.pose(name, time)
        self.outline = silhouette(self.vehicle, self.position, self.rotation)
        body = self.vehicle.body_vertices
        self.front = float(np.max(body[:, 0]))  # body x of the foremost point (m)
        self.rear = float(np.min(body[:, 0]))
        self.half_width = 0.5 * float(np.ptp(body[:, 1]))
        self.length = self.front - self.rear
        # angle between the body z axis and world z (deg): roll and pitch together
        self.tilt = math.degrees(math.acos(float(np.clip(self.rotation[2, 2], -1.0, 1.0))))

    def world(self, body_xy: ArrayLike) -> Array:
        """World x-y of body-frame points (x, y) at the CG's height."""
        b = np.atleast_2d(np.asarray(body_xy, dtype=np.float64))
        pts = np.column_stack([b, np.zeros(len(b))]) @ self.rotation.T + self.position
        return pts[:, :2]


def _draw_vehicle(
    ax: Axes,
    pose: _Pose,
    colour: str,
    *,
    fill_alpha: float = 0.22,
    edge_alpha: float = 1.0,
    lw: float = 1.6,
    ls: str | tuple[float, tuple[float, ...]] = "-",
    details: bool = True,
    gid: str | None = None,
    z: float = 2.0,
) -> None:
    """The outline (filled), and with ``details`` the body x axis, the front marker and the
    CG symbol."""
    from matplotlib.colors import to_rgba

    patch = _patch(
        pose.outline,
        facecolor=to_rgba(colour, fill_alpha),
        edgecolor=to_rgba(colour, edge_alpha),
        linewidth=lw,
        linestyle=ls,
        zorder=z,
    )
    if gid is not None:
        patch.set_gid(gid)
    ax.add_patch(patch)
    if not details:
        return
    # Body x axis from the rear to the front, and a filled chevron pointing forward.
    axis = pose.world([[pose.rear, 0.0], [pose.front, 0.0]])
    ax.plot(axis[:, 0], axis[:, 1], color=colour, lw=0.9, ls="-.", zorder=z + 0.1)
    w = min(0.2 * pose.half_width, 0.06 * pose.length)
    tip = pose.front - 0.04 * pose.length
    chevron = pose.world([[tip, 0.0], [tip - 1.6 * w, w], [tip - 1.6 * w, -w]])
    ax.fill(chevron[:, 0], chevron[:, 1], color=colour, alpha=0.9, lw=0, zorder=z + 0.2)
    cg = pose.position
    ax.plot([cg[0]], [cg[1]], marker="o", ms=9, mfc="white", mec=colour, mew=1.8, zorder=z + 3.0)
    ax.plot([cg[0]], [cg[1]], marker="+", ms=9, color=colour, mew=1.8, zorder=z + 3.1)


def _label(
    ax: Axes, pose: _Pose, colour: str, obstacles: Array, text: str, small: bool = False
) -> None:
    """The vehicle's name inside its outline, at the candidate spot farthest from the
    ``obstacles`` (world x-y points, m: arrows, paths, the centroid) so it hides none;
    ``small``: a smaller label in a dashed box (the outline at the end of a run)."""
    cand = np.array(
        [
            [fx * end, fy * pose.half_width]
            for end in (pose.front, pose.rear)
            for fx in (0.62, 0.35)
            for fy in (0.0, 0.45, -0.45)
        ]
    )
    spots = pose.world(cand)
    obs = np.asarray(obstacles, dtype=np.float64).reshape(-1, 2)
    if len(obs):
        gap = np.min(np.linalg.norm(spots[:, None, :] - obs[None, :, :], axis=2), axis=1)
        x, y = spots[int(np.argmax(gap))]
    else:
        x, y = spots[0]
    ax.text(
        x,
        y,
        text,
        color=colour,
        fontsize=9 if small else 11,
        fontweight="bold",
        ha="center",
        va="center",
        zorder=9.0,
        bbox={
            "boxstyle": "round,pad=0.25",
            "facecolor": "white",
            "edgecolor": colour,
            "alpha": 0.85,
            "linestyle": "--" if small else "-",
        },
    )


def _segment_points(tail: ArrayLike, vec: ArrayLike, n: int = 12) -> Array:
    """Points along an arrow (x-y, m), for keeping labels off it."""
    t = np.asarray(tail, dtype=np.float64)[:2]
    v = np.asarray(vec, dtype=np.float64)[:2]
    return t + np.linspace(0.0, 1.0, n)[:, None] * v


def _path_points(result: Result) -> Array:
    """Every vehicle's CG path (x-y, m), thinned to at most 200 points each."""
    pts = []
    for name in result.vehicles:
        xy = result.trajectory(name).position[:, :2]
        pts.append(xy[:: max(1, len(xy) // 200)])
    return np.concatenate(pts)


def _persons(result: Result) -> dict[str, str]:
    """Each pedestrian segment's vehicle name -> its pedestrian's name (none without a
    scene)."""
    scene = getattr(result, "scene", None)
    people = scene.pedestrians if scene is not None else {}
    return {seg.name: name for name, person in people.items() for seg in person.segments}


def _units(result: Result) -> list[tuple[str, list[str]]]:
    """What a picture draws as one thing, in order: each vehicle alone, and each pedestrian
    (name, its segments), at the place of its first segment."""
    person_of = _persons(result)
    out: list[tuple[str, list[str]]] = []
    for name in result.vehicles:
        person = person_of.get(name)
        if person is None:
            out.append((name, [name]))
        elif not out or out[-1][0] != person:
            out.append((person, [name]))
        else:
            out[-1][1].append(name)
    return out


def _draw_paths(ax: Axes, result: Result, split_time: float) -> None:
    """Every vehicle's CG path (a pedestrian's pelvis's): solid up to ``split_time``, dashed
    after it."""
    for k, (_, members) in enumerate(_units(result)):
        name = next((m for m in members if m.endswith("/pelvis")), members[0])
        tr = result.trajectory(name)
        xy = tr.position[:, :2]
        before = tr.t <= split_time
        after = tr.t >= split_time
        c = vehicle_colour(k)
        ax.plot(xy[before, 0], xy[before, 1], color=c, lw=1.2, ls="-", zorder=1.5)
        ax.plot(xy[after, 0], xy[after, 1], color=c, lw=1.2, ls=(0, (4, 3)), zorder=1.5)


TILT_NOTE_DEG = 5.0  # a vehicle tilted more than this gets a note under the title


def _tilt_note(result: Result, tilts: dict[str, float]) -> str:
    """A note naming the vehicles whose body z axis leaves world z by more than
    TILT_NOTE_DEG (their outline is then the tilted body's projection)."""
    big = [f"{n} {tilts[n]:.0f} deg" for n in result.vehicles if tilts.get(n, 0.0) > TILT_NOTE_DEG]
    if not big:
        return ""
    why = (
        "rolled or pitched on the ground"
        if getattr(result, "on_ground", False)
        else "no ground or tyres in the model"
    )
    return (
        "note: largest roll/pitch drawn: " + ", ".join(big) + f" ({why}; a tilted vehicle's "
        "outline is its projection)"
    )


def _impact_of(result: Result, impact: int | Impact) -> tuple[int, Impact]:
    if not result.impacts:
        raise SceneError(
            "this result has no impacts to draw: the vehicles never exchanged an impulse "
            "(use plot_trajectories to see the motion)"
        )
    if isinstance(impact, int | np.integer) and not isinstance(impact, bool):
        i = int(impact)
        if not -len(result.impacts) <= i < len(result.impacts):
            raise ParameterError(
                f"impact = {i} is out of range: this result has {len(result.impacts)} "
                f"impact(s), numbered 0 to {len(result.impacts) - 1}"
            )
        i %= len(result.impacts)
        return i, result.impacts[i]
    for i, imp in enumerate(result.impacts):
        if imp is impact:
            return i, imp
    raise ParameterError("impact must be an index into result.impacts or one of its Impacts")


def _check_scene(result: Result) -> None:
    if result.scene is None:
        raise SceneError(
            "this result has no scene, so no vehicle meshes to draw: draw the Result that "
            "Scene.run returned"
        )


def _bounds(geoms: list[Any], points: list[Array]) -> tuple[float, float, float, float]:
    import shapely

    lo = np.array([np.inf, np.inf])
    hi = -lo
    for g in geoms:
        b = shapely.bounds(g)
        lo, hi = np.minimum(lo, b[:2]), np.maximum(hi, b[2:])
    for p in points:
        p = np.atleast_2d(p)[:, :2]
        lo, hi = np.minimum(lo, p.min(axis=0)), np.maximum(hi, p.max(axis=0))
    return float(lo[0]), float(lo[1]), float(hi[0]), float(hi[1])


def _set_view(
    fig: Figure, axes: list[Axes], box: tuple[float, float, float, float], margin: float
) -> None:
    """Equal axes in metres showing ``box`` (x0, y0, x1, y1) plus ``margin`` of its larger
    side, widened along x or y to the panel's own shape so that no space is wasted. Call it
    last: it lays the figure out (titles, legend) to learn the panels' shape."""
    x0, y0, x1, y1 = box
    pad = margin * max(x1 - x0, y1 - y0, 1e-3)
    x0, y0, x1, y1 = x0 - pad, y0 - pad, x1 + pad, y1 + pad
    for ax in axes:
        ax.grid(True, color="0.88", lw=0.6)
        ax.set_axisbelow(True)
        ax.set_xlabel("world x (m)")
        ax.set_xlim(x0, x1)
        ax.set_ylim(y0, y1)
    engine = fig.get_layout_engine()
    if engine is not None:
        engine.execute(fig)
    pos = axes[0].get_position()
    shape = (pos.width * fig.get_figwidth()) / max(pos.height * fig.get_figheight(), 1e-9)
    w, h = x1 - x0, y1 - y0
    if w / h < shape:  # too narrow for the panel: widen x about its middle
        cx, w = 0.5 * (x0 + x1), h * shape
        x0, x1 = cx - w / 2.0, cx + w / 2.0
    else:
        cy, h = 0.5 * (y0 + y1), w / shape
        y0, y1 = cy - h / 2.0, cy + h / 2.0
    for ax in axes:
        ax.set_xlim(x0, x1)
        ax.set_ylim(y0, y1)
        ax.set_aspect("equal", adjustable="box")  # exact metres; the box is already right


def _speeds(v: float) -> str:
    return f"{v:.2f} m/s ({to_mph(v):.1f} mph)"


# -- the impact diagram --------------------------------------------------------------------


def plot_impact(
    result: Result, path: str | Path | None = None, impact: int | Impact = 0, *, dpi: int = DPI
) -> Figure:
    """The top-down diagram of one impact: two panels, when its timer started (the first
    overlap, or for a secondary exchange the engaged pair closing again, with how deep the
    meshes then are inside each other and why they closed again) and at the impulse
    exchange, with both vehicles' outlines (true silhouettes), their body x axes and fronts,
    CGs, CG paths over the whole run (solid before the exchange, dashed after), and:

    - timer start: each CG's velocity (arrow, m/s);
    - exchange: the overlap region (the engine's region points, their 2-D hull), the impulse
      centroid, the contact normal n (vehicle 1 into 2, fixed length) and the contact plane,
      the impulse on each vehicle at the centroid (horizontal part, N s) and each CG's
      delta-V (m/s); the outlines at the timer's start dotted, to show the travel in between.

    Velocity and delta-V arrows share one scale, impulses have their own; both scales are in
    the legend (1 m of arrow = ...). An impact with a fixed obstacle draws the obstacle filled
    grey (as far as a vehicle's length beyond the vehicles), the impulse on it in grey, and
    neither a velocity nor a delta-V for it. ``impact`` is an index into ``result.impacts`` or
    one of them. Writes a PNG (or any format matplotlib knows by the suffix) to ``path`` when given,
    IMPACT_FIGSIZE inches at ``dpi``; returns the Figure (Agg canvas, no pyplot state)."""
    _check_scene(result)
    index, imp = _impact_of(result, impact)
    from matplotlib.colors import to_rgba
    from matplotlib.lines import Line2D
    from matplotlib.patches import FancyArrowPatch, Patch

    names = list(imp.vehicles)  # the pair: two vehicles, or a vehicle and a fixed obstacle
    moving = list(imp.moving)
    start = _timer_start(result, index, imp)
    colours = {n: vehicle_colour(result.vehicles.index(n)) for n in result.vehicles}
    if imp.obstacle is not None:
        colours[imp.obstacle] = OBSTACLE_EDGE
    others = [n for n in result.vehicles if n not in names]
    t0, t1 = imp.first_contact_time, imp.time
    at_contact = {n: _Pose(result, n, t0) for n in result.vehicles}
    at_exchange = {n: _Pose(result, n, t1) for n in result.vehicles}
    velocity = {n: result.state(n, t0)["velocity"][:2] for n in moving}
    dv = {n: imp.delta_v[n][:2] for n in moving}
    j_on = {n: imp.impulse_on(n)[:2] for n in names}
    size = max(p.length for p in at_exchange.values())
    outlines = [p.outline for p in [*at_contact.values(), *at_exchange.values()]]
    obstacle = (
        None if imp.obstacle is None else _obstacle_near(result, imp.obstacle, outlines, size)
    )

    # Arrow scales (unit per m of arrow): the longest velocity about half the longest vehicle,
    # the impulses shorter, so that the one on vehicle 1 rarely reaches its CG's delta-V.
    v_max = max(float(np.linalg.norm(v)) for v in [*velocity.values(), *dv.values()])
    v_unit = _nice(max(v_max, 1e-6) / (0.55 * size))  # m/s per m of arrow
    j_max = max(float(np.linalg.norm(j)) for j in j_on.values())
    j_unit = _nice(max(j_max, 1e-6) / (0.3 * size))  # N s per m of arrow
    n_len = 0.12 * size  # m: the normal's drawn length

    fig = _new_figure(IMPACT_FIGSIZE)
    ax1 = fig.add_subplot(1, 2, 1)
    ax2 = fig.add_subplot(1, 2, 2, sharex=ax1, sharey=ax1)
    centroid = np.asarray(imp.centroid)

    # Panel 1: the timer's start (first overlap or closing again).
    _draw_paths(ax1, result, t1)
    paths = _path_points(result)
    if obstacle is not None:
        for ax in (ax1, ax2):
            _draw_obstacle(ax, obstacle, imp.obstacle)
    for n in result.vehicles:
        _draw_vehicle(ax1, at_contact[n], colours[n], gid=f"silhouette:{n}:first_contact")
    tips = []
    busy = [paths, centroid[None, :2]]  # where labels should not go
    for n in moving:
        cg = at_contact[n].position
        _arrow(ax1, cg, velocity[n] / v_unit, colours[n], 2.6, 6.0)
        busy.append(_segment_points(cg, velocity[n] / v_unit))
        if float(np.linalg.norm(velocity[n])) < 0.005:  # m/s: no arrow to see
            ax1.annotate(
                "at rest",
                (cg[0], cg[1]),
                xytext=(8, -14),
                textcoords="offset points",
                color=colours[n],
                fontsize=9,
                zorder=9.0,
            )
        tips.append(cg[:2] + velocity[n] / v_unit)
    for n in result.vehicles:
        _label(ax1, at_contact[n], colours[n], np.concatenate(busy), n)
    ax1.set_title(f"{start['title']}, t = {t0:.4f} s\n({start['what']})", fontsize=11)
    ax1.set_ylabel("world y (m)")

    # Panel 2: the exchange.
    _draw_paths(ax2, result, t1)
    for n in result.vehicles:
        _draw_vehicle(
            ax2,
            at_contact[n],
            colours[n],
            fill_alpha=0.0,
            edge_alpha=0.55,
            lw=1.0,
            ls=":",
            details=False,
            z=1.8,
        )
        _draw_vehicle(ax2, at_exchange[n], colours[n], gid=f"silhouette:{n}:exchange")
    busy = [paths, centroid[None, :2]]
    import shapely

    region = shapely.convex_hull(shapely.multipoints(np.asarray(imp.region_points)[:, :2]))
    if region.geom_type == "Polygon" and region.area > 0.0:
        ax2.add_patch(
            _patch(
                region,
                facecolor=to_rgba("0.25", 0.35),
                edgecolor="0.1",
                hatch="////",
                linewidth=1.0,
                zorder=4.0,
            )
        )
    nrm = np.asarray(imp.normal)[:2]
    nrm_len = float(np.linalg.norm(nrm))
    if nrm_len > 1e-9:
        # The contact plane's trace through the centroid, and n drawn from a point on it off
        # the centroid, so that it does not sit on the impulse arrows.
        u = nrm / nrm_len
        t_dir = np.array([-u[1], u[0]])
        half = 0.3 * size
        ends = np.array([centroid[:2] - t_dir * half, centroid[:2] + t_dir * half])
        ax2.plot(ends[:, 0], ends[:, 1], color="black", lw=1.0, ls=(0, (6, 2, 1, 2)), zorder=6.5)
        foot = centroid[:2] + t_dir * 0.8 * half
        _arrow(ax2, foot, u * n_len, "black", 1.6, 7.5)
        ax2.annotate(
            "n",
            tuple(foot + u * n_len),
            xytext=(4, 4),
            textcoords="offset points",
            fontsize=11,
            fontstyle="italic",
            fontweight="bold",
            zorder=9.0,
        )
        tips += [*ends, foot + u * n_len]
        busy += [_segment_points(ends[0], ends[1] - ends[0], 30), _segment_points(foot, u * n_len)]
    for n in names:
        _arrow(
            ax2,
            centroid,
            j_on[n] / j_unit,
            colours[n],
            1.2,
            7.0,
            style="fancy",
            head=22.0,
            edge="black",
        )
        tips.append(centroid[:2] + j_on[n] / j_unit)
        busy.append(_segment_points(centroid, j_on[n] / j_unit))
    for n in moving:
        cg = at_exchange[n].position
        _arrow(ax2, cg, dv[n] / v_unit, colours[n], 3.2, 8.0, style="simple", head=20.0)
        tips.append(cg[:2] + dv[n] / v_unit)
        busy.append(_segment_points(cg, dv[n] / v_unit))
    for n in result.vehicles:
        _label(ax2, at_exchange[n], colours[n], np.concatenate(busy), n)
    ax2.plot(
        [centroid[0]],
        [centroid[1]],
        marker="X",
        ms=11,
        mfc="gold",
        mec="black",
        mew=1.2,
        zorder=9.5,
    )
    dtp_ms = 1e3 * (t1 - t0)
    ax2.set_title(
        f"Impulse exchange, t = {t1:.4f} s ({dtp_ms:.1f} ms after {start['word']})\n"
        "(the impulse acts at the centroid; velocities jump by delta-V)",
        fontsize=11,
    )

    view = _bounds(outlines + ([] if obstacle is None else [obstacle]), [*tips, centroid])

    # Legend: vehicles, then symbols, then arrows with their scales.
    handles: list[Any] = []
    labels: list[str] = []
    for n in result.vehicles:
        v = result.vehicle(n)
        handles.append(Patch(facecolor=to_rgba(colours[n], 0.22), edgecolor=colours[n]))
        labels.append(f"{n}: {v.mass:.0f} kg, outline seen from above")
    if imp.obstacle is not None:
        handles.append(Patch(facecolor=OBSTACLE_COLOUR, edgecolor="0.1", alpha=0.9))
        labels.append(f"{imp.obstacle}: fixed obstacle (infinite mass)")
    handles += [
        Line2D([], [], color="0.3", lw=0.9, ls="-.", marker=">", ms=7, mfc="0.3", mec="0.3"),
        Line2D([], [], ls="", marker="o", ms=9, mfc="white", mec="0.3", mew=1.8),
        Line2D([], [], color="0.3", lw=1.2, ls="-"),
        Line2D([], [], color="0.3", lw=1.2, ls=(0, (4, 3))),
        Line2D([], [], color="0.3", lw=1.0, ls=":"),
        Patch(facecolor=to_rgba("0.25", 0.35), edgecolor="0.1", hatch="////"),
        Line2D([], [], ls="", marker="X", ms=11, mfc="gold", mec="black"),
        _arrow_proxy("black", 1.6),
        Line2D([], [], color="black", lw=1.0, ls=(0, (6, 2, 1, 2))),
        _arrow_proxy("0.3", 2.6),
        _arrow_proxy("0.3", 1.2, style="fancy", edge="black"),
        _arrow_proxy("0.3", 3.2, style="simple"),
    ]
    labels += [
        "body x axis, front (chevron)",
        "centre of gravity (CG)",
        "CG path up to the exchange",
        "CG path after the exchange",
        f"outline at {start['word']}",
        "overlap region at the exchange",
        "impulse centroid",
        f"contact normal n ({names[0]} into {names[1]})",
        "contact plane (normal to n)",
        f"velocity at {start['word']} (1 m = {_fmt(v_unit)} m/s)",
        f"impulse on the vehicle of its colour (1 m = {_fmt(j_unit / 1e3)} kN s)",
        f"delta-V of the CG (1 m = {_fmt(v_unit)} m/s)",
    ]
    fig.legend(
        handles,
        labels,
        loc="outside lower center",
        ncols=4,
        fontsize=9,
        handler_map={FancyArrowPatch: _arrow_handler()},
        frameon=False,
    )

    # Caption: the key numbers.
    j = np.asarray(imp.impulse)
    title = (
        f"Impact {index + 1} of {len(result.impacts)}: {names[0]} and {names[1]}"
        + (" (secondary exchange)" if imp.secondary else "")
        + " - top view, world frame (z up, out of the page), metres"
    )
    line2 = f"closing speed {_speeds(imp.closing_speed)} at the centroid;  " + ";  ".join(
        f"delta-V {n} {_speeds(imp.speed_change(n))}" for n in moving
    )
    if imp.obstacle is not None:
        line2 += f";  {imp.obstacle} is fixed (no delta-V)"
    line3 = (
        f"impulse {np.linalg.norm(j) / 1e3:.2f} kN s (vertical part "
        f"{round(j[2] / 1e3, 2) + 0.0:+.2f} kN s, "
        f"not drawn);  depth of penetration {dtp_ms:.1f} ms ({imp.depth_of_penetration_mode});"
        f"  energy dissipated {imp.energy_dissipated / 1e3:.1f} kJ"
        + (";  sliding (tangential impulse limited by friction)" if imp.sliding else "")
    )
    if others:
        line3 += f";  also in the scene: {', '.join(others)}"
    if imp.secondary:
        line3 += f"\n{start['caption']}"
    tilts = {n: max(at_contact[n].tilt, at_exchange[n].tilt) for n in result.vehicles}
    note = _tilt_note(result, tilts)
    fig.suptitle(f"{title}\n{line2}\n{line3}" + (f"\n{note}" if note else ""), fontsize=11)
    _set_view(fig, [ax1, ax2], view, 0.06)
    if path is not None:
        fig.savefig(Path(path), dpi=dpi)
    return fig


# Characters of an 11 pt caption line that fit the trajectories figure's width (12 in at
# about 0.55 em per character, with a margin).
CAPTION_CHARS = 125


def _wrap(items: list[str], lead: str) -> list[str]:
    """Caption lines of at most CAPTION_CHARS characters (so that none is cut at the figure's
    edges): ``lead`` then the items joined by "; ", broken between items (an item longer than
    a line is broken between words)."""
    import textwrap

    lines: list[str] = []
    line = lead
    for item in items:
        sep = "" if line == lead else "; "
        if line != lead and len(line) + len(sep) + len(item) > CAPTION_CHARS:
            lines.append(line + ";")
            line = ""
            sep = ""
        line += sep + item
    lines.append(line)
    return [w for text in lines for w in textwrap.wrap(text, width=CAPTION_CHARS)]


def _outline_points(geom: Any) -> Array:
    """The vertices of an outline's exterior rings (world x-y, m)."""
    import shapely

    rings = shapely.get_rings(shapely.get_parts(geom))
    return np.concatenate([shapely.get_coordinates(r) for r in rings] or [np.zeros((0, 2))])


def _number_points(fig: Figure, ax: Axes, points: Array, busy: list[Array]) -> None:
    """Writes 1, 2, ... beside ``points`` (world x-y, m) so that no two numbers overlap each
    other or a marker: each number takes the first free place on rings of growing radius
    around its point (display space, after the layout), joined to it by a thin leader line
    when it had to move out. ``busy``: other points a number should rather not cover."""
    if len(points) == 0:
        return
    to_px = ax.transData.transform
    px_per_pt = fig.dpi / 72.0
    marks = to_px(points)
    others = to_px(np.concatenate(busy)) if busy else np.zeros((0, 2))
    taken: list[tuple[float, float, float, float]] = []  # placed boxes (x0, y0, x1, y1), px
    for k, (anchor, point) in enumerate(zip(marks, points, strict=True)):
        text = str(k + 1)
        half_w = (3.5 + 3.3 * len(text)) * px_per_pt  # px: 10 pt bold digits
        half_h = 6.5 * px_per_pt
        best: tuple[float, Array] | None = None
        for radius in (13.0, 22.0, 32.0, 44.0, 58.0, 74.0):  # pt
            for step in range(12):
                angle = math.pi / 4 + step * math.pi / 6
                offset = radius * np.array([math.cos(angle), math.sin(angle)])
                c = anchor + offset * px_per_pt
                box = (c[0] - half_w, c[1] - half_h, c[0] + half_w, c[1] + half_h)
                if any(
                    box[0] < b[2] and b[0] < box[2] and box[1] < b[3] and b[1] < box[3]
                    for b in taken
                ):
                    continue
                gap = half_w + 6.0 * px_per_pt  # clear of every marker (11 pt across)
                if np.any(np.all(np.abs(marks - c) < gap, axis=1)):
                    continue
                near = int(np.sum(np.all(np.abs(others - c) < [half_w, half_h], axis=1)))
                if best is None or near < best[0]:
                    best = (near, offset)
                if near == 0:
                    break
            if best is not None and best[0] == 0:
                break
        offset = best[1] if best is not None else np.array([13.0, 13.0])
        c = anchor + offset * px_per_pt
        taken.append((c[0] - half_w, c[1] - half_h, c[0] + half_w, c[1] + half_h))
        leader = float(np.hypot(*offset)) > 13.5
        ax.annotate(
            text,
            (float(point[0]), float(point[1])),
            xytext=(float(offset[0]), float(offset[1])),
            textcoords="offset points",
            ha="center",
            va="center",
            fontsize=10,
            fontweight="bold",
            zorder=9.6,
            gid=f"impact-number:{k + 1}",
            bbox={"boxstyle": "round,pad=0.15", "fc": "white", "ec": "0.3", "lw": 0.6},
            arrowprops={"arrowstyle": "-", "color": "0.2", "lw": 0.7, "shrinkA": 0, "shrinkB": 6}
            if leader
            else None,
        )


def _overlap_depth(result: Result, imp: Impact, time: float) -> float:
    """How deep (m) the impact's two meshes overlap at ``time``: the extent of the engine's
    overlap region along the impact's normal (0 when they only touch or are apart)."""
    from crashsim import _core

    posed = []
    for name in imp.vehicles:
        state = result.state(name, time)
        posed += [result.vehicle(name).shape, state["position"], state["orientation"]]
    points = np.asarray(_core.overlap_region(*posed)["points"], dtype=np.float64).reshape(-1, 3)
    if len(points) == 0:
        return 0.0
    return float(np.ptp(points @ np.asarray(imp.normal)))


def _timer_start(result: Result, index: int, imp: Impact) -> dict[str, str]:
    """The words for the instant the impact's timer started: a first overlap (the meshes
    first touch) or, for a secondary exchange, the engaged pair closing again (the meshes
    still deep inside each other; how deep and why it closed again are said)."""
    if not imp.secondary:
        return {
            "title": "First overlap",
            "word": "first overlap",
            "what": "the meshes first touch; the depth-of-penetration timer starts",
            "caption": "",
        }
    from crashsim.analysis.engagements import engagement_of, secondary_cause

    depth = _overlap_depth(result, imp, imp.first_contact_time)
    engaged = engagement_of(result, imp)
    primary = (
        "" if engaged is None or engaged.primary is None else f" of impact {engaged.primary + 1}"
    )
    return {
        "title": "Closing again (secondary exchange)",
        "word": "closing again",
        "what": f"still engaged, the meshes {depth:.2f} m inside each other along n; a new "
        "timer starts",
        "caption": f"secondary exchange: the pair stayed engaged after the exchange{primary}; "
        + secondary_cause(result, index),
    }


def _auto_count(result: Result) -> int:
    """Outlines per vehicle that put the most-travelled vehicle's about half a length apart."""
    spacings = []
    for name in result.vehicles:
        xy = result.trajectory(name).position[:, :2]
        travel = float(np.sum(np.linalg.norm(np.diff(xy, axis=0), axis=1)))
        length = float(np.ptp(result.vehicle(name).body_vertices[:, 0]))
        spacings.append(travel / (0.5 * length))
    return int(np.clip(round(max(spacings)) + 1, 4, 15))


# -- the whole run -------------------------------------------------------------------------


def plot_trajectories(
    result: Result,
    path: str | Path | None = None,
    *,
    count: int | None = None,
    dpi: int = DPI,
) -> Figure:
    """The whole run from above: each vehicle's outline at ``count`` regular times from the
    start to the end (faded, darker as time goes on, each marked with its time; by default
    as many as put the farthest-travelling vehicle's outlines about half its length apart,
    4 to 15), the outline
    at every exchange drawn bold, the CG paths (solid before the first exchange, dashed
    after), the start and end positions and every impulse centroid numbered as in
    ``result.impacts``. Writes a PNG to ``path`` when given (TRAJECTORY_FIGSIZE inches at
    ``dpi``); returns the Figure (Agg canvas, no pyplot state).

    A run on a ground (``result.on_ground``) also shows the run-out: the outlines are spaced
    by the distance travelled (the same for every vehicle) rather than by time, so a vehicle
    slowing to rest does not pile them up; every wheel's path (where its tyre met the
    ground; thin, the vehicle's colour), the tyre marks (where a contact patch slid; thick,
    dark), each vehicle's outline at the end of the run (dashed, labelled with its rest time,
    or "still moving"), the friction zones (tinted, with their friction in the legend) and a
    terrain's extent; the caption gives each vehicle's rest. Fixed obstacles are drawn filled
    (grey, named) in any run. The legend of such a run is below the plot."""
    _check_scene(result)
    if count is None:
        count = _auto_count(result)
    if not isinstance(count, int | np.integer) or isinstance(count, bool) or count < 2:
        raise ParameterError(f"count must be an integer >= 2 (outlines per vehicle), got {count!r}")
    from matplotlib.colors import to_rgba
    from matplotlib.lines import Line2D
    from matplotlib.patches import Patch

    on_ground = bool(getattr(result, "on_ground", False))
    extended = on_ground or bool(result.obstacles)
    t_start, t_end = float(result.t[0]), float(result.t[-1])
    times = np.linspace(t_start, t_end, int(count))
    split = result.impacts[0].time if result.impacts else t_end
    fig = _new_figure(TRAJECTORY_FIGSIZE)
    ax = fig.add_subplot(1, 1, 1)
    handles: list[Any] = []
    labels: list[str] = []
    extra_points: list[Array] = []  # world x-y (m) the view must show besides the outlines
    if on_ground:
        handles, labels = _draw_ground(ax, result)
        extra_points += _draw_wheels_and_marks(ax, result)
    _draw_paths(ax, result, split)
    outlines = []
    tilts: dict[str, float] = {}
    spacing = _outline_spacing(result, int(count)) if on_ground else 0.0
    rests: list[str] = []
    person_of = _persons(result)
    for k, (person, members) in enumerate(_units(result)):
        if members[0] in person_of:
            rests.append(_draw_person(ax, result, person, members, vehicle_colour(k), spacing,
                                      times, on_ground, outlines))  # fmt: skip
            continue
        name = person
        c = vehicle_colour(k)
        last: Array | None = None  # CG of the last time stamp written
        vtimes = _spaced_times(result, name, spacing) if on_ground else times
        for i, t in enumerate(vtimes):
            pose = _Pose(result, name, float(t))
            outlines.append(pose.outline)
            tilts[name] = max(tilts.get(name, 0.0), pose.tilt)
            share = i / max(len(vtimes) - 1, 1)
            _draw_vehicle(
                ax,
                pose,
                c,
                fill_alpha=0.03 + 0.05 * share,
                edge_alpha=0.3 + 0.5 * share,
                lw=0.9,
                details=False,
                z=2.0 + share,
            )
            cg = pose.position
            ax.plot([cg[0]], [cg[1]], marker=".", ms=5, color=c, zorder=3.5)
            if last is not None and float(np.linalg.norm(cg[:2] - last)) < 0.4:
                continue  # m: the previous stamp is in the way (the vehicle hardly moved)
            last = cg[:2]
            ax.annotate(
                f"{t:.2f} s",
                (cg[0], cg[1]),
                xytext=(4, 4),
                textcoords="offset points",
                fontsize=7.5,
                color=c,
                alpha=0.9,
                zorder=3.6,
            )
        for imp in result.impacts:
            if name in imp.vehicles:  # the pose at each exchange, bold (numbered at its centroid)
                pose = _Pose(result, name, imp.time)
                outlines.append(pose.outline)
                _draw_vehicle(ax, pose, c, fill_alpha=0.25, lw=1.8, z=4.0)
        first = _Pose(result, name, t_start)
        if on_ground:
            end = _Pose(result, name, t_end)
            outlines.append(end.outline)
            tilts[name] = max(tilts.get(name, 0.0), end.tilt)
            rest = result.rest(name)
            _draw_vehicle(ax, end, c, fill_alpha=0.10, lw=1.6, ls=(0, (5, 3)), z=4.5)
            when = (
                f"at rest, t = {rest.time:.2f} s"
                if rest is not None
                else f"still moving at t = {t_end:.2f} s"
            )
            rests.append(_rest_words(result, name))
            moved = float(np.linalg.norm(end.position[:2] - first.position[:2]))
            turned = abs(math.degrees(_yaw_between(first.rotation, end.rotation)))
            if moved < 0.15 * first.length and turned < 10.0:  # one label: it hardly moved
                _label(ax, first, c, _path_points(result), f"{name} (start; {when})")
                continue
            _label(ax, end, c, _path_points(result), f"{name} {when}", small=True)
        _label(ax, first, c, _path_points(result), f"{name} (start)")
    if result.obstacles:
        obstacle_handles, obstacle_labels, shown = _draw_obstacles(ax, result, outlines)
        handles += obstacle_handles
        labels += obstacle_labels
        extra_points += shown
    centroids = np.array([np.asarray(imp.centroid)[:2] for imp in result.impacts]).reshape(-1, 2)
    for p in centroids:
        ax.plot([p[0]], [p[1]], marker="X", ms=11, mfc="gold", mec="black", zorder=9.5)
    ax.set_ylabel("world y (m)")
    vehicle_handles: list[Any] = []
    vehicle_labels: list[str] = []
    for k, (name, members) in enumerate(_units(result)):
        c = vehicle_colour(k)
        vehicle_handles.append(Patch(facecolor=to_rgba(c, 0.12), edgecolor=to_rgba(c, 0.6)))
        if members[0] in person_of:
            vehicle_labels.append(f"{name} (a pedestrian: its segments from above; darker = later)")
        elif on_ground:
            vehicle_labels.append(f"{name} every {spacing:.3g} m of travel (darker = later)")
        else:
            vehicle_labels.append(f"{name} every {(times[1] - times[0]):.3g} s (darker = later)")
    vehicle_handles += [
        Patch(facecolor=to_rgba("0.3", 0.25), edgecolor="0.3", lw=1.8),
        Line2D([], [], color="0.3", lw=1.2, ls="-"),
        Line2D([], [], color="0.3", lw=1.2, ls=(0, (4, 3))),
        Line2D([], [], ls="", marker="X", ms=11, mfc="gold", mec="black"),
    ]
    vehicle_labels += [
        "at an impulse exchange (with body x axis, front chevron, CG)",
        "CG path before the first exchange",
        "CG path after it",
        "impulse centroid, numbered as the impacts in the caption",
    ]
    if on_ground:
        vehicle_handles += [
            Patch(facecolor=to_rgba("0.3", 0.10), edgecolor="0.3", lw=1.6, ls=(0, (5, 3))),
            Line2D([], [], color="0.3", lw=0.6, alpha=0.7),
            Line2D([], [], color=mark_colour(0), lw=MARK_WIDTH, solid_capstyle="butt"),
        ]
        vehicle_labels += [
            "at the end of the run (dashed)",
            "wheel paths (where each tyre met the ground)",
            "tyre marks (a tyre sliding at the friction limit)",
        ]
    if extended:
        fig.legend(
            vehicle_handles + handles,
            vehicle_labels + labels,
            loc="outside lower center",
            ncols=3,
            fontsize=8.5,
            frameon=False,
        )
    else:
        ax.legend(vehicle_handles, vehicle_labels, loc="best", fontsize=8.5, framealpha=0.9)
    summary = [
        f"{i + 1} at {imp.time:.3f} s {imp.vehicles[0]}-{imp.vehicles[1]}"
        + (" (secondary)" if imp.secondary else "")
        + f", closing {imp.closing_speed:.1f} m/s"
        for i, imp in enumerate(result.impacts)
    ]
    note = _tilt_note(result, tilts)
    lines = [f"The run from above, {t_start:g} to {t_end:g} s (world frame, z up, metres)"]
    lines += _wrap(summary, "impacts: ") if summary else ["no impacts"]
    if on_ground:
        lines += _wrap(rests, "run-out: ")
        lines += _wrap([_ground_words(result)], "")
    lines += _wrap([note], "") if note else []
    fig.suptitle("\n".join(lines), fontsize=11)
    _set_view(fig, [ax], _bounds(outlines, extra_points), 0.05)
    _number_points(fig, ax, centroids, [_outline_points(o) for o in outlines])
    if path is not None:
        fig.savefig(Path(path), dpi=dpi)
    return fig


def _draw_person(
    ax: Axes,
    result: Result,
    person: str,
    members: list[str],
    colour: str,
    spacing: float,
    times: Array,
    on_ground: bool,
    outlines: list[Any],
) -> str:
    """A pedestrian from above as one thing: its segments' outlines at the pelvis's spaced
    times (thin, darker as time goes on), at the end bold, one label; returns its caption
    words (where its centre of mass ends)."""
    pelvis = next((m for m in members if m.endswith("/pelvis")), members[0])
    when = _spaced_times(result, pelvis, spacing) if on_ground else times
    t_end = float(result.t[-1])
    shown = [*map(float, when), t_end]
    for i, t in enumerate(shown):
        share = i / max(len(shown) - 1, 1)
        last = i == len(shown) - 1
        for m in members:
            pose = _Pose(result, m, t)
            outlines.append(pose.outline)
            _draw_vehicle(ax, pose, colour, fill_alpha=0.10 if last else 0.04 + 0.06 * share,
                          edge_alpha=0.9 if last else 0.25 + 0.4 * share,
                          lw=1.2 if last else 0.6, details=False, z=2.0 + share)  # fmt: skip
    from crashsim.analysis.pedestrian import rest_of

    scene = result.scene
    assert scene is not None  # a pedestrian is known from its scene
    x, speed = rest_of(result, scene.pedestrians[person])
    start = _Pose(result, pelvis, float(result.t[0])).position
    ax.annotate(f"{person} (start)", (start[0], start[1]), xytext=(6, -14),
                textcoords="offset points", fontsize=8.5, color=colour, zorder=8)  # fmt: skip
    ax.annotate(f"{person} at {t_end:.2f} s", (x[0], x[1]), xytext=(6, 6),
                textcoords="offset points", fontsize=8.5, color=colour, zorder=8)  # fmt: skip
    return (
        f"{person} (its centre of mass) at ({x[0]:.2f}, {x[1]:.2f}) m at {t_end:.2f} s, "
        f"{speed:.2f} m/s"
    )


# -- the run-out on the ground -------------------------------------------------------------

MARK_DARKEN = 0.6  # tyre marks: the vehicle's colour this much of the way to black
MARK_WIDTH = 2.4  # pt
OBSTACLE_COLOUR = "0.55"
OBSTACLE_EDGE = "0.35"  # the impulse on a fixed obstacle in an impact diagram
# Tints of the friction zones, in the order given (cycled).
ZONE_COLOURS = ("#6cbf6c", "#6fa8dc", "#e0b050", "#b48ad6", "#e07b7b", "#7fcfc4")
OBSTACLE_REACH = 6.0  # m: an obstacle is drawn, and widens the view, this far beyond the run


def _outline_spacing(result: Result, count: int) -> float:
    """The distance (m, seen from above) between a ground run's outlines: the longest CG path
    over ``count - 1``, at least 0.2 m."""
    longest = max(
        float(np.sum(np.linalg.norm(np.diff(result.trajectory(n).position[:, :2], axis=0), axis=1)))
        for n in result.vehicles
    )
    return max(longest / max(count - 1, 1), 0.2)


def _spaced_times(result: Result, name: str, spacing: float) -> Array:
    """The times at which a vehicle's CG has travelled 0, spacing, 2 spacing, ... (m, seen
    from above), without the end of the run (drawn as the rest outline)."""
    tr = result.trajectory(name)
    xy = tr.position[:, :2]
    s = np.concatenate([[0.0], np.cumsum(np.linalg.norm(np.diff(xy, axis=0), axis=1))])
    marks = np.arange(0.0, s[-1] - 0.5 * spacing, spacing)
    k = np.minimum(np.searchsorted(s, marks, side="left"), len(s) - 1)
    return np.unique(tr.t[k])


def _yaw_between(r0: Array, r1: Array) -> float:
    """The yaw (rad) turned from body rotation r0 to r1, seen from above, in (-pi, pi]."""
    a = math.atan2(float(r1[1, 0]), float(r1[0, 0])) - math.atan2(float(r0[1, 0]), float(r0[0, 0]))
    return math.atan2(math.sin(a), math.cos(a))


def _rest_words(result: Result, name: str) -> str:
    """One vehicle's rest for the caption."""
    from crashsim.analysis.runout import run_out

    r = run_out(result, name)
    where = f"({r.position[0]:.2f}, {r.position[1]:.2f}) m, heading {r.end_heading:.0f} deg"
    since = {
        "separation": "from separation",
        "exchange": "from its last exchange",
        "start": "from the start",
    }[r.start]
    if r.at_rest:
        return (
            f"{name} at rest at {r.rest_time:.2f} s at {where}, {r.distance:.2f} m {since} "
            f"({r.speed:.1f} m/s)"
        )
    return f"{name} STILL MOVING at {r.end_time:.2f} s ({r.end_speed:.2f} m/s) at {where}"


def _ground_words(result: Result) -> str:
    ground = result.scene.ground if result.scene is not None else None
    if ground is None:  # pragma: no cover - on_ground runs have one
        return ""
    where = (
        f"terrain mesh ({ground.terrain_source})"
        if ground.terrain is not None
        else f"the plane z = {ground.height:g} m"
    )
    mu = f"{ground.tyre_friction:g}" + (f" ({ground.surface})" if ground.surface else "")
    zones = f", {len(ground.zones)} friction zone(s) tinted" if ground.zones else ""
    return f"ground: {where}, tyre-road friction {mu}{zones}"


def _draw_ground(ax: Axes, result: Result) -> tuple[list[Any], list[str]]:
    """The terrain's extent and the friction zones (below everything); their legend
    entries."""
    from matplotlib.colors import to_rgba
    from matplotlib.patches import Patch, Polygon

    ground = result.scene.ground if result.scene is not None else None
    handles: list[Any] = []
    labels: list[str] = []
    if ground is None:  # pragma: no cover - on_ground runs have one
        return handles, labels
    if ground.terrain is not None:
        outline = _terrain_outline(ground.terrain)
        ax.add_patch(_patch(outline, facecolor="#f1ead8", edgecolor="#b9a77a", lw=1.0, zorder=0.2))
        lo, hi = ground.terrain.bounds[0][2], ground.terrain.bounds[1][2]
        handles.append(Patch(facecolor="#f1ead8", edgecolor="#b9a77a"))
        labels.append(f"terrain seen from above (heights {lo:.2f} to {hi:.2f} m)")
    for k, zone in enumerate(ground.zones):
        colour = ZONE_COLOURS[k % len(ZONE_COLOURS)]
        poly = np.asarray(zone.polygon, dtype=np.float64)
        ax.add_patch(
            Polygon(
                poly,
                closed=True,
                facecolor=to_rgba(colour, 0.28),
                edgecolor=to_rgba(colour, 0.9),
                lw=1.0,
                zorder=0.3,
                gid=f"zone:{k}",
            )
        )
        handles.append(Patch(facecolor=to_rgba(colour, 0.28), edgecolor=to_rgba(colour, 0.9)))
        labels.append(f"{zone.label(k)}: tyre friction {zone.friction:g}")
    return handles, labels


def _terrain_outline(terrain: Any) -> Any:
    """A terrain mesh seen from above: the union of its triangles (its convex hull when it has
    more than 20,000)."""
    import shapely

    xy = np.asarray(terrain.vertices, dtype=np.float64)[:, :2]
    faces = np.asarray(terrain.faces, dtype=np.int64)
    if len(faces) > 20_000:
        return shapely.convex_hull(shapely.multipoints(xy))
    return _projected_union(xy, faces)


def mark_colour(index: int) -> tuple[float, float, float]:
    """The tyre marks' colour of the vehicle added ``index``-th: its colour darkened (RGB)."""
    from matplotlib.colors import to_rgb

    rgb = np.asarray(to_rgb(vehicle_colour(index)))
    r, g, b = (1.0 - MARK_DARKEN) * rgb
    return (float(r), float(g), float(b))


def _draw_wheels_and_marks(ax: Axes, result: Result) -> list[Array]:
    """Every wheel's path (thin, the vehicle's colour) and the tyre marks (thick, the
    vehicle's colour darkened); returns the paths' points (x-y, m)."""
    points: list[Array] = []
    for k, name in enumerate(result.vehicles):
        try:
            record = result.wheels(name)
        except SceneError:  # a vehicle without wheels
            continue
        c = vehicle_colour(k)
        for w in range(len(record.names)):
            # only where the tyre touched (a wheel in the air leaves no path)
            xy = np.where((record.load[w] > 0.0)[:, None], record.contact[w][:, :2], np.nan)
            ax.plot(xy[:, 0], xy[:, 1], color=c, lw=0.6, alpha=0.7, zorder=1.4)
            on = xy[~np.isnan(xy[:, 0])]
            points.append(on[:: max(1, len(on) // 200)])
        for wheel, lines in result.tyre_marks(name).items():
            for line in lines:
                ax.plot(
                    line[:, 0],
                    line[:, 1],
                    color=mark_colour(k),
                    lw=MARK_WIDTH,
                    alpha=0.9,
                    solid_capstyle="butt",
                    zorder=1.8,
                    gid=f"tyre-mark:{name}:{wheel}",
                )
    return points


def _obstacle_outline(result: Result, name: str) -> Any:
    """A fixed obstacle's outline seen from above at its place (world x-y, m)."""
    obstacle = result.obstacle(name)
    position, rotation = result.pose(name, float(result.t[0]))
    world = np.asarray(obstacle.mesh.vertices, dtype=np.float64) @ np.asarray(rotation).T
    world += np.asarray(position)
    return _projected_union(world[:, :2].copy(), np.asarray(obstacle.mesh.faces, dtype=np.int64))


def _obstacle_near(result: Result, name: str, outlines: list[Any], reach: float) -> Any:
    """The part of a fixed obstacle's outline within ``reach`` (m) of the box around
    ``outlines`` (a long wall or barrier is cut there, so the view stays on the impact)."""
    import shapely

    x0, y0, x1, y1 = _bounds(outlines, [])
    near = shapely.box(x0 - reach, y0 - reach, x1 + reach, y1 + reach)
    return shapely.intersection(_obstacle_outline(result, name), near)


def _draw_obstacle(ax: Axes, outline: Any, name: str) -> None:
    """A fixed obstacle's outline, filled grey (as plot_trajectories draws it)."""
    patch = _patch(
        outline, facecolor=OBSTACLE_COLOUR, edgecolor="0.1", lw=1.0, alpha=0.9, zorder=1.9
    )
    patch.set_gid(f"obstacle:{name}")
    ax.add_patch(patch)
    spot = np.asarray(outline.representative_point().coords)[0]
    ax.annotate(
        name,
        (float(spot[0]), float(spot[1])),
        xytext=(8, -8),
        textcoords="offset points",
        ha="left",
        va="top",
        fontsize=9,
        color="0.1",
        zorder=9.0,
        bbox={"boxstyle": "round,pad=0.2", "fc": "white", "ec": "0.4", "lw": 0.6, "alpha": 0.85},
    )


def _draw_obstacles(
    ax: Axes, result: Result, outlines: list[Any]
) -> tuple[list[Any], list[str], list[Array]]:
    """The fixed obstacles, filled and named, as far as OBSTACLE_REACH beyond the vehicles'
    outlines; returns legend entries and the drawn parts' points (for the view)."""
    import shapely
    from matplotlib.patches import Patch

    x0, y0, x1, y1 = _bounds(outlines, [])
    near = shapely.box(
        x0 - OBSTACLE_REACH, y0 - OBSTACLE_REACH, x1 + OBSTACLE_REACH, y1 + OBSTACLE_REACH
    )
    busy = np.concatenate(
        [_path_points(result)] + [np.asarray(imp.centroid)[None, :2] for imp in result.impacts]
    )
    shown: list[Array] = []
    for name in result.obstacles:
        outline = _obstacle_outline(result, name)
        part = shapely.intersection(outline, near)
        if part.is_empty:
            continue
        ax.add_patch(
            _patch(part, facecolor=OBSTACLE_COLOUR, edgecolor="0.1", lw=1.0, alpha=0.9, zorder=1.9)
        )
        corners = _outline_points(part)
        shown.append(corners)
        # the name at the corner of the drawn part farthest from the paths and centroids
        spots = np.vstack([corners, np.asarray(part.representative_point().coords)])
        gap = np.min(np.linalg.norm(spots[:, None, :] - busy[None, :, :], axis=2), axis=1)
        c = spots[int(np.argmax(gap))]
        ax.annotate(
            name,
            (float(c[0]), float(c[1])),
            xytext=(6, -6),
            textcoords="offset points",
            ha="left",
            va="top",
            fontsize=8.5,
            color="0.1",
            zorder=9.0,
            gid=f"obstacle:{name}",
            bbox={
                "boxstyle": "round,pad=0.2",
                "fc": "white",
                "ec": "0.4",
                "lw": 0.6,
                "alpha": 0.85,
            },
        )
    handles = [Patch(facecolor=OBSTACLE_COLOUR, edgecolor="0.1", alpha=0.9)]
    labels = ["fixed obstacle"]
    return handles, labels, shown
