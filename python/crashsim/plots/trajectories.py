"""The whole run from above (plot_trajectories): outlines at regular times (or distances on a
ground), the outlines at the exchanges, CG paths, the numbered impulse centroids, the caption.

Imports crashsim.plots.runout, crashsim.plots.obstacles, crashsim.plots.outline and
crashsim.plots.common.
"""

from __future__ import annotations

import math
from pathlib import Path
from typing import TYPE_CHECKING, Any

import numpy as np

from crashsim.errors import ParameterError
from crashsim.plots.common import (
    DPI,
    Array,
    _bicycle_bodies,
    _bounds,
    _check_scene,
    _draw_paths,
    _new_figure,
    _path_points,
    _persons,
    _set_view,
    _tilt_note,
    _units,
    shade,
    vehicle_colour,
)
from crashsim.plots.obstacles import _draw_obstacles
from crashsim.plots.outline import _draw_vehicle, _label, _outline_points, _Pose
from crashsim.plots.runout import (
    MARK_WIDTH,
    _draw_ground,
    _draw_person,
    _draw_wheels_and_marks,
    _ground_words,
    _outline_spacing,
    _rest_words,
    _spaced_times,
    _yaw_between,
    mark_colour,
)

if TYPE_CHECKING:
    from matplotlib.axes import Axes
    from matplotlib.figure import Figure

    from crashsim.result import Result

TRAJECTORY_FIGSIZE = (12.0, 8.5)  # inches: plot_trajectories' figure
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


def _auto_count(result: Result) -> int:
    """Outlines per vehicle that put the most-travelled vehicle's about half a length apart."""
    spacings = []
    for name in result.vehicles:
        xy = result.trajectory(name).position[:, :2]
        travel = float(np.sum(np.linalg.norm(np.diff(xy, axis=0), axis=1)))
        length = float(np.ptp(result.vehicle(name).body_vertices[:, 0]))
        spacings.append(travel / (0.5 * length))
    return int(np.clip(round(max(spacings)) + 1, 4, 15))


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
    outlines: list[Any] = []
    tilts: dict[str, float] = {}
    spacing = _outline_spacing(result, int(count)) if on_ground else 0.0
    rests: list[str] = []
    person_of = _persons(result)
    for k, (person, members) in enumerate(_units(result)):
        if members[0] in person_of:
            rests.append(_draw_person(ax, result, person, members, vehicle_colour(k), spacing,
                                      times, on_ground, outlines))  # fmt: skip
            continue
        vtimes = _spaced_times(result, person, spacing) if on_ground else times
        _draw_vehicle_run(ax, result, person, vehicle_colour(k), vtimes, outlines, tilts)
        _draw_start_and_end(
            ax, result, person, vehicle_colour(k), on_ground, outlines, tilts, rests
        )
    if result.obstacles:
        obstacle_handles, obstacle_labels, shown = _draw_obstacles(ax, result, outlines)
        handles += obstacle_handles
        labels += obstacle_labels
        extra_points += shown
    centroids = np.array([np.asarray(imp.centroid)[:2] for imp in result.impacts]).reshape(-1, 2)
    for p in centroids:
        ax.plot([p[0]], [p[1]], marker="X", ms=11, mfc="gold", mec="black", zorder=9.5)
    ax.set_ylabel("world y (m)")
    vehicle_handles, vehicle_labels = _vehicle_legend(result, on_ground, spacing, times)
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
    lines = _caption_lines(result, on_ground, tilts, rests)
    fig.suptitle("\n".join(lines), fontsize=11)
    _set_view(fig, [ax], _bounds(outlines, extra_points), 0.05)
    _number_points(fig, ax, centroids, [_outline_points(o) for o in outlines])
    if path is not None:
        fig.savefig(Path(path), dpi=dpi)
    return fig


def _draw_vehicle_run(
    ax: Axes,
    result: Result,
    name: str,
    c: Any,
    vtimes: Array,
    outlines: list[Any],
    tilts: dict[str, float],
) -> None:
    """A vehicle's faded outlines at ``vtimes`` (s; darker = later), each CG marked and
    stamped with its time (unless the last stamp is in the way), then its outline at each of
    its exchanges, bold. Appends to ``outlines`` and raises ``tilts[name]``."""
    last: Array | None = None  # CG of the last time stamp written
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


def _draw_start_and_end(
    ax: Axes,
    result: Result,
    name: str,
    c: Any,
    on_ground: bool,
    outlines: list[Any],
    tilts: dict[str, float],
    rests: list[str],
) -> None:
    """A vehicle's start label and, on a ground, its outline at the end of the run (dashed,
    labelled with its rest; one label for both when it hardly moved) and its rest's words
    (appended to ``rests``)."""
    t_start, t_end = float(result.t[0]), float(result.t[-1])
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
            return
        _label(ax, end, c, _path_points(result), f"{name} {when}", small=True)
    _label(ax, first, c, _path_points(result), f"{name} (start)")


def _vehicle_legend(
    result: Result, on_ground: bool, spacing: float, times: Array
) -> tuple[list[Any], list[str]]:
    """The legend's entries for the vehicles (and people, bicycles) and the symbols; on a
    ground also the end outline, the wheel paths and the tyre marks."""
    from matplotlib.colors import to_rgba
    from matplotlib.lines import Line2D
    from matplotlib.patches import Patch

    person_of = _persons(result)
    vehicle_handles: list[Any] = []
    vehicle_labels: list[str] = []
    bicycles = _bicycle_bodies(result)
    for k, (name, members) in enumerate(_units(result)):
        c = vehicle_colour(k)
        vehicle_handles.append(Patch(facecolor=to_rgba(c, 0.12), edgecolor=to_rgba(c, 0.6)))
        if members[0] in person_of and name in bicycles.values():
            vehicle_labels.append(f"{name} (a cyclist: the rider's segments from above; darker "
                                  "= later)")  # fmt: skip
            vehicle_handles.append(Patch(facecolor=to_rgba(shade(c), 0.12),
                                         edgecolor=to_rgba(shade(c), 0.6)))  # fmt: skip
            vehicle_labels.append(f"{name}'s bicycle (frame and wheels from above)")
        elif members[0] in person_of:
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
    return vehicle_handles, vehicle_labels


def _caption_lines(
    result: Result, on_ground: bool, tilts: dict[str, float], rests: list[str]
) -> list[str]:
    """The caption's lines: the run's span, the impacts, on a ground the run-out and the
    ground, and the tilt note (each wrapped to CAPTION_CHARS)."""
    t_start, t_end = float(result.t[0]), float(result.t[-1])
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
    return lines
