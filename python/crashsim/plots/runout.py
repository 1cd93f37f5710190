"""The run-out on a ground in the run from above: outlines spaced by distance travelled, the
ground (terrain extent, friction zones), wheel paths and tyre marks, the rest words of the
caption, and a pedestrian or a cyclist drawn as one thing.

Imports crashsim.plots.outline and crashsim.plots.common.
"""

from __future__ import annotations

import math
from typing import TYPE_CHECKING, Any

import numpy as np

from crashsim.errors import SceneError
from crashsim.plots.common import Array, _bicycle_bodies, _patch, shade, vehicle_colour
from crashsim.plots.outline import _draw_vehicle, _Pose, _projected_union

if TYPE_CHECKING:
    from matplotlib.axes import Axes

    from crashsim.result import Result

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
    """A pedestrian or a cyclist from above as one thing: its bodies' outlines at the
    pelvis's spaced times (thin, darker as time goes on), at the end bold, one label (a
    cyclist's bicycle in the second shade of its colour, labelled at its end); returns its
    caption words (where its centre of mass ends, and a bicycle's frame)."""
    from crashsim.analysis.pedestrian import rest_of

    bicycle = {m for m in members if _bicycle_bodies(result).get(m) == person}
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
            _draw_vehicle(ax, pose, shade(colour) if m in bicycle else colour,
                          fill_alpha=0.10 if last else 0.04 + 0.06 * share,
                          edge_alpha=0.9 if last else 0.25 + 0.4 * share,
                          lw=1.2 if last else 0.6, details=False, z=2.0 + share)  # fmt: skip
    scene = result.scene
    assert scene is not None  # a person is known from its scene
    cyclist = scene.cyclists.get(person)
    x, speed = rest_of(result, scene.pedestrians[person] if cyclist is None else cyclist.rider)
    start = _Pose(result, pelvis, float(result.t[0])).position
    ax.annotate(f"{person} (start)", (start[0], start[1]), xytext=(6, -14),
                textcoords="offset points", fontsize=8.5, color=colour, zorder=8)  # fmt: skip
    ax.annotate(f"{person} at {t_end:.2f} s", (x[0], x[1]), xytext=(6, 6),
                textcoords="offset points", fontsize=8.5, color=colour, zorder=8)  # fmt: skip
    words = (
        f"{person} (its centre of mass) at ({x[0]:.2f}, {x[1]:.2f}) m at {t_end:.2f} s, "
        f"{speed:.2f} m/s"
    )
    if cyclist is None:
        return words
    frame = result.trajectory(cyclist.bicycle.frame.name)
    end, v = frame.position[-1], float(np.linalg.norm(frame.velocity[-1]))
    ax.annotate(f"{person}'s bicycle at {t_end:.2f} s", (end[0], end[1]), xytext=(6, -14),
                textcoords="offset points", fontsize=8.5, color=shade(colour),
                zorder=8)  # fmt: skip
    return words + f"; its bicycle's frame at ({end[0]:.2f}, {end[1]:.2f}) m, {v:.2f} m/s"


MARK_DARKEN = 0.6  # tyre marks: the vehicle's colour this much of the way to black
MARK_WIDTH = 2.4  # pt
# Tints of the friction zones, in the order given (cycled).
ZONE_COLOURS = ("#6cbf6c", "#6fa8dc", "#e0b050", "#b48ad6", "#e07b7b", "#7fcfc4")


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
