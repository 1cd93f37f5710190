"""A vehicle seen from above: its outline (the union of its mesh triangles projected on the
ground plane, shapely) at a pose, the pose with what the drawings need from it, the drawn
vehicle (outline, body x axis, front chevron, CG) and its label.

Imports crashsim.plots.common only.
"""

from __future__ import annotations

import functools
import math
from typing import TYPE_CHECKING, Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

from crashsim.errors import ParameterError, SceneError
from crashsim.plots.common import Array, _patch

if TYPE_CHECKING:
    from matplotlib.axes import Axes

    from crashsim.result import Result
    from crashsim.vehicles.vehicle import Vehicle

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


def _outline_points(geom: Any) -> Array:
    """The vertices of an outline's exterior rings (world x-y, m)."""
    import shapely

    rings = shapely.get_rings(shapely.get_parts(geom))
    return np.concatenate([shapely.get_coordinates(r) for r in rings] or [np.zeros((0, 2))])
