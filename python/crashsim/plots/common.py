"""What every picture of crashsim.plots shares: the vehicles' colours, the figure (Agg
canvas, no pyplot), arrows and their legend entries, patches of shapely outlines, the run's
units (a vehicle, or a pedestrian's segments) and CG paths, the view in metres, the tilt note.

Imports nothing else of crashsim.plots.
"""

from __future__ import annotations

import math
from typing import TYPE_CHECKING, Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

from crashsim.errors import SceneError
from crashsim.units import to_mph

if TYPE_CHECKING:
    from matplotlib.axes import Axes
    from matplotlib.figure import Figure

    from crashsim.result import Result

Array = NDArray[np.float64]
# One colour per vehicle, by its order in the scene (also used by crashsim.io.export).
VEHICLE_COLOURS = ("#d62728", "#1f77b4", "#2ca02c", "#9467bd", "#ff7f0e", "#8c564b")
DPI = 120  # pixels per inch of the PNGs written


def vehicle_colour(index: int) -> str:
    """The colour (hex) of the vehicle added ``index``-th to the scene."""
    return VEHICLE_COLOURS[index % len(VEHICLE_COLOURS)]


SHADE = 0.45  # a cyclist's bicycle: its rider's colour this much of the way to black


def shade(colour: str) -> tuple[float, float, float]:
    """The second shade of a person's colour (RGB): a cyclist's bicycle is drawn in it."""
    from matplotlib.colors import to_rgb

    r, g, b = (1.0 - SHADE) * np.asarray(to_rgb(colour))
    return (float(r), float(g), float(b))


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
    """Each body of a pedestrian or a cyclist (its rider's segments and its bicycle's
    bodies): its vehicle name -> the person's name (none without a scene)."""
    from crashsim.analysis.pedestrian import person_bodies

    return person_bodies(getattr(result, "scene", None))


def _bicycle_bodies(result: Result) -> dict[str, str]:
    """Each cyclist's bicycle body: its vehicle name -> the cyclist's name."""
    scene = getattr(result, "scene", None)
    cyclists = scene.cyclists if scene is not None else {}
    return {b.name: name for name, c in cyclists.items() for b in c.bicycle.segments}


def _units(result: Result) -> list[tuple[str, list[str]]]:
    """What a picture draws as one thing, in order: each vehicle alone, and each pedestrian
    or cyclist (name, its bodies), at the place of its first body."""
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
    """Every vehicle's CG path (a person's pelvis's, a cyclist's bicycle frame's in the
    second shade): solid up to ``split_time``, dashed after it."""
    bicycle = _bicycle_bodies(result)
    for k, (_, members) in enumerate(_units(result)):
        paths = [(next((m for m in members if m.endswith("/pelvis")), members[0]),
                  vehicle_colour(k))]  # fmt: skip
        paths += [(m, shade(vehicle_colour(k))) for m in members if m.endswith("/frame")
                  and m in bicycle]  # fmt: skip
        for name, c in paths:
            tr = result.trajectory(name)
            xy = tr.position[:, :2]
            before = tr.t <= split_time
            after = tr.t >= split_time
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
