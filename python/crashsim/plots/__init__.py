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

The package's modules import one way, with no circle: impact (plot_impact) -> obstacles ->
outline -> common; trajectories (plot_trajectories) -> runout (ground, wheels, tyre marks, a
pedestrian drawn as one), obstacles, outline -> common. outline: silhouette, the pose, the
drawn vehicle and its label; common: colours, the figure, arrows, CG paths, the view.
"""

# Every public name and constant of the former single plots.py, and the private names that
# tests and crashsim.studies.fitplot import (_closed, _new_figure).
from crashsim.plots.common import (  # noqa: F401
    DPI,
    TILT_NOTE_DEG,
    VEHICLE_COLOURS,
    Array,
    _new_figure,
    vehicle_colour,
)
from crashsim.plots.impact import IMPACT_FIGSIZE, plot_impact  # noqa: F401
from crashsim.plots.obstacles import OBSTACLE_COLOUR, OBSTACLE_EDGE, OBSTACLE_REACH  # noqa: F401
from crashsim.plots.outline import (  # noqa: F401
    SLIVER_AREA,
    SNAP_GRID,
    YAW_ONLY_TOL,
    _closed,
    silhouette,
)
from crashsim.plots.runout import MARK_DARKEN, MARK_WIDTH, ZONE_COLOURS, mark_colour  # noqa: F401
from crashsim.plots.trajectories import (  # noqa: F401
    CAPTION_CHARS,
    TRAJECTORY_FIGSIZE,
    plot_trajectories,
)

__all__ = [
    "VEHICLE_COLOURS",
    "plot_impact",
    "plot_trajectories",
    "silhouette",
    "vehicle_colour",
]
