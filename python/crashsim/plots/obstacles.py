"""Fixed obstacles seen from above: their outlines at their place, cut to the view, filled
grey and named (in the impact diagram and the run from above).

Imports crashsim.plots.outline and crashsim.plots.common.
"""

from __future__ import annotations

from typing import TYPE_CHECKING, Any

import numpy as np

from crashsim.plots.common import Array, _bounds, _patch, _path_points
from crashsim.plots.outline import _outline_points, _projected_union

if TYPE_CHECKING:
    from matplotlib.axes import Axes

    from crashsim.result import Result

OBSTACLE_COLOUR = "0.55"
OBSTACLE_EDGE = "0.35"  # the impulse on a fixed obstacle in an impact diagram
OBSTACLE_REACH = 6.0  # m: an obstacle is drawn, and widens the view, this far beyond the run


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
