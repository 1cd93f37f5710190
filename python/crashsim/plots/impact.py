"""The impact diagram (plot_impact): one impact at its timer's start and at the exchange.

Imports crashsim.plots.obstacles, crashsim.plots.outline and crashsim.plots.common.
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path
from typing import TYPE_CHECKING, Any

import numpy as np

from crashsim.errors import ParameterError, SceneError
from crashsim.plots.common import (
    DPI,
    _arrow,
    _arrow_handler,
    _arrow_proxy,
    _bounds,
    _check_scene,
    _draw_paths,
    _fmt,
    _new_figure,
    _nice,
    _patch,
    _path_points,
    _segment_points,
    _set_view,
    _speeds,
    _tilt_note,
    vehicle_colour,
)
from crashsim.plots.obstacles import OBSTACLE_COLOUR, OBSTACLE_EDGE, _draw_obstacle, _obstacle_near
from crashsim.plots.outline import _draw_vehicle, _label, _Pose

if TYPE_CHECKING:
    from matplotlib.figure import Figure

    from crashsim.records import Impact
    from crashsim.result import Result

IMPACT_FIGSIZE = (15.0, 8.2)  # inches: plot_impact's figure


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
    d = _ImpactDrawing.of(result, index, imp)

    fig = _new_figure(IMPACT_FIGSIZE)
    ax1 = fig.add_subplot(1, 2, 1)
    ax2 = fig.add_subplot(1, 2, 2, sharex=ax1, sharey=ax1)

    # Panel 1: the timer's start (first overlap or closing again).
    _draw_paths(ax1, result, d.t1)
    paths = _path_points(result)
    if d.obstacle is not None:
        for ax in (ax1, ax2):
            _draw_obstacle(ax, d.obstacle, imp.obstacle)
    tips = _draw_timer_start(ax1, result, d, paths)

    # Panel 2: the exchange.
    tips += _draw_exchange(ax2, result, d, paths)

    outlines = d.outlines + ([] if d.obstacle is None else [d.obstacle])
    view = _bounds(outlines, [*tips, d.centroid])
    _draw_legend(fig, result, d)
    fig.suptitle(_caption(result, d), fontsize=11)
    _set_view(fig, [ax1, ax2], view, 0.06)
    if path is not None:
        fig.savefig(Path(path), dpi=dpi)
    return fig


@dataclass
class _ImpactDrawing:
    """What both panels, the legend and the caption of one impact's diagram share."""

    index: int  # into result.impacts
    imp: Impact
    names: list[str]  # the pair: two vehicles, or a vehicle and a fixed obstacle
    moving: list[str]
    start: dict[str, str]  # _timer_start's words
    colours: dict[str, Any]
    others: list[str]  # the vehicles not in the pair
    t0: float  # s: the timer's start
    t1: float  # s: the exchange
    at_contact: dict[str, _Pose]
    at_exchange: dict[str, _Pose]
    velocity: dict[str, np.ndarray]  # m/s, horizontal, at t0
    dv: dict[str, np.ndarray]  # m/s, horizontal
    j_on: dict[str, np.ndarray]  # N s, horizontal
    size: float  # m: the longest vehicle
    outlines: list[Any]
    obstacle: Any
    v_unit: float  # m/s per m of arrow
    j_unit: float  # N s per m of arrow
    n_len: float  # m: the normal's drawn length
    centroid: np.ndarray

    @classmethod
    def of(cls, result: Result, index: int, imp: Impact) -> _ImpactDrawing:
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

        # Arrow scales (unit per m of arrow): the longest velocity about half the longest
        # vehicle, the impulses shorter, so that the one on vehicle 1 rarely reaches its CG's
        # delta-V.
        v_max = max(float(np.linalg.norm(v)) for v in [*velocity.values(), *dv.values()])
        v_unit = _nice(max(v_max, 1e-6) / (0.55 * size))  # m/s per m of arrow
        j_max = max(float(np.linalg.norm(j)) for j in j_on.values())
        j_unit = _nice(max(j_max, 1e-6) / (0.3 * size))  # N s per m of arrow
        n_len = 0.12 * size  # m: the normal's drawn length
        return cls(
            index=index,
            imp=imp,
            names=names,
            moving=moving,
            start=start,
            colours=colours,
            others=others,
            t0=t0,
            t1=t1,
            at_contact=at_contact,
            at_exchange=at_exchange,
            velocity=velocity,
            dv=dv,
            j_on=j_on,
            size=size,
            outlines=outlines,
            obstacle=obstacle,
            v_unit=v_unit,
            j_unit=j_unit,
            n_len=n_len,
            centroid=np.asarray(imp.centroid),
        )


def _draw_timer_start(ax1: Any, result: Result, d: _ImpactDrawing, paths: Any) -> list[Any]:
    """Panel 1's outlines, CG velocities (or "at rest") and labels; the arrows' tips."""
    for n in result.vehicles:
        _draw_vehicle(ax1, d.at_contact[n], d.colours[n], gid=f"silhouette:{n}:first_contact")
    tips = []
    busy = [paths, d.centroid[None, :2]]  # where labels should not go
    for n in d.moving:
        cg = d.at_contact[n].position
        _arrow(ax1, cg, d.velocity[n] / d.v_unit, d.colours[n], 2.6, 6.0)
        busy.append(_segment_points(cg, d.velocity[n] / d.v_unit))
        if float(np.linalg.norm(d.velocity[n])) < 0.005:  # m/s: no arrow to see
            ax1.annotate(
                "at rest",
                (cg[0], cg[1]),
                xytext=(8, -14),
                textcoords="offset points",
                color=d.colours[n],
                fontsize=9,
                zorder=9.0,
            )
        tips.append(cg[:2] + d.velocity[n] / d.v_unit)
    for n in result.vehicles:
        _label(ax1, d.at_contact[n], d.colours[n], np.concatenate(busy), n)
    ax1.set_title(f"{d.start['title']}, t = {d.t0:.4f} s\n({d.start['what']})", fontsize=11)
    ax1.set_ylabel("world y (m)")
    return tips


def _draw_exchange(ax2: Any, result: Result, d: _ImpactDrawing, paths: Any) -> list[Any]:
    """Panel 2: the outlines then (dotted) and now, the overlap region, the normal and the
    contact plane, the impulses, the delta-Vs, the labels and the centroid; the arrows' tips."""
    imp, centroid = d.imp, d.centroid
    _draw_paths(ax2, result, d.t1)
    for n in result.vehicles:
        _draw_vehicle(
            ax2,
            d.at_contact[n],
            d.colours[n],
            fill_alpha=0.0,
            edge_alpha=0.55,
            lw=1.0,
            ls=":",
            details=False,
            z=1.8,
        )
        _draw_vehicle(ax2, d.at_exchange[n], d.colours[n], gid=f"silhouette:{n}:exchange")
    busy = [paths, centroid[None, :2]]
    _draw_overlap_region(ax2, imp)
    tips = _draw_normal(ax2, imp, centroid, d.size, d.n_len, busy)
    for n in d.names:
        _arrow(
            ax2,
            centroid,
            d.j_on[n] / d.j_unit,
            d.colours[n],
            1.2,
            7.0,
            style="fancy",
            head=22.0,
            edge="black",
        )
        tips.append(centroid[:2] + d.j_on[n] / d.j_unit)
        busy.append(_segment_points(centroid, d.j_on[n] / d.j_unit))
    for n in d.moving:
        cg = d.at_exchange[n].position
        _arrow(ax2, cg, d.dv[n] / d.v_unit, d.colours[n], 3.2, 8.0, style="simple", head=20.0)
        tips.append(cg[:2] + d.dv[n] / d.v_unit)
        busy.append(_segment_points(cg, d.dv[n] / d.v_unit))
    for n in result.vehicles:
        _label(ax2, d.at_exchange[n], d.colours[n], np.concatenate(busy), n)
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
    dtp_ms = 1e3 * (d.t1 - d.t0)
    ax2.set_title(
        f"Impulse exchange, t = {d.t1:.4f} s ({dtp_ms:.1f} ms after {d.start['word']})\n"
        "(the impulse acts at the centroid; velocities jump by delta-V)",
        fontsize=11,
    )
    return tips


def _draw_overlap_region(ax2: Any, imp: Impact) -> None:
    """The 2-D hull of the engine's overlap region points, hatched (when it has an area)."""
    import shapely
    from matplotlib.colors import to_rgba

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


def _draw_normal(
    ax2: Any, imp: Impact, centroid: np.ndarray, size: float, n_len: float, busy: list[Any]
) -> list[Any]:
    """The contact plane's trace and the normal n (when it has a horizontal part); adds their
    points to ``busy`` and returns their tips."""
    nrm = np.asarray(imp.normal)[:2]
    nrm_len = float(np.linalg.norm(nrm))
    if nrm_len <= 1e-9:
        return []
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
    busy += [_segment_points(ends[0], ends[1] - ends[0], 30), _segment_points(foot, u * n_len)]
    return [*ends, foot + u * n_len]


def _draw_legend(fig: Figure, result: Result, d: _ImpactDrawing) -> None:
    """The legend: vehicles, then symbols, then arrows with their scales."""
    from matplotlib.colors import to_rgba
    from matplotlib.lines import Line2D
    from matplotlib.patches import FancyArrowPatch, Patch

    imp, colours, start, names = d.imp, d.colours, d.start, d.names
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
        f"velocity at {start['word']} (1 m = {_fmt(d.v_unit)} m/s)",
        f"impulse on the vehicle of its colour (1 m = {_fmt(d.j_unit / 1e3)} kN s)",
        f"delta-V of the CG (1 m = {_fmt(d.v_unit)} m/s)",
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


def _caption(result: Result, d: _ImpactDrawing) -> str:
    """The figure's title and key numbers (and the tilt note, when any)."""
    imp, names = d.imp, d.names
    j = np.asarray(imp.impulse)
    dtp_ms = 1e3 * (d.t1 - d.t0)
    title = (
        f"Impact {d.index + 1} of {len(result.impacts)}: {names[0]} and {names[1]}"
        + (" (secondary exchange)" if imp.secondary else "")
        + " - top view, world frame (z up, out of the page), metres"
    )
    line2 = f"closing speed {_speeds(imp.closing_speed)} at the centroid;  " + ";  ".join(
        f"delta-V {n} {_speeds(imp.speed_change(n))}" for n in d.moving
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
    if d.others:
        line3 += f";  also in the scene: {', '.join(d.others)}"
    if imp.secondary:
        line3 += f"\n{d.start['caption']}"
    tilts = {n: max(d.at_contact[n].tilt, d.at_exchange[n].tilt) for n in result.vehicles}
    note = _tilt_note(result, tilts)
    return f"{title}\n{line2}\n{line3}" + (f"\n{note}" if note else "")


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
