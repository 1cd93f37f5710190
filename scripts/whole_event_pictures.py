"""The pictures and report excerpts of docs/whole-event.md: the set-up example (a car swerving
and braking on a sloping terrain, onto a grass verge and into a tree) and the four
examples/runout-*.toml, each run to rest and drawn from above (docs/img/runout_*.png); the
report's run-out sections are printed for the page.

    python3 scripts/whole_event_pictures.py       # from the repository; needs ../shared/meshes
"""

from __future__ import annotations

import warnings
from pathlib import Path

import crashsim as cs
import numpy as np
import trimesh
from crashsim.io.scenefile import load_scene
from crashsim.plots import plot_trajectories

REPO = Path(__file__).resolve().parents[1]
IMG = REPO / "docs" / "img"

EXAMPLES = {
    "runout_sedan_into_suv": "runout-sedan-into-suv.toml",
    "runout_small_overlap": "runout-small-overlap-barrier.toml",
    "runout_pole": "runout-sedan-into-pole.toml",
    "runout_rollover": "runout-rollover-kerb.toml",
}


def setup_example() -> cs.Result:
    """The set-up example of docs/whole-event.md (the same code)."""
    # A road 80 m x 40 m falling 3 % along +x: a terrain mesh in world coordinates (m, z up)
    xs, ys = np.linspace(-10.0, 70.0, 17), np.linspace(-30.0, 10.0, 9)
    x, y = (a.ravel() for a in np.meshgrid(xs, ys, indexing="ij"))
    n = len(ys)
    quads = [
        (i * n + j, (i + 1) * n + j, (i + 1) * n + j + 1, i * n + j + 1)
        for i in range(len(xs) - 1)
        for j in range(n - 1)
    ]
    triangles = [f for a, b, c, d in quads for f in ((a, b, c), (a, c, d))]
    road = trimesh.Trimesh(np.c_[x, y, -0.03 * x], triangles)

    ground = cs.Ground(
        terrain=road,  # or a file: cs.Ground(terrain="road.ply", units="m", up="z")
        friction="dry asphalt",  # 0.8 outside the zones
        zones=[
            cs.FrictionZone([(-10, -30), (70, -30), (70, -4), (-10, -4)], "grass", name="verge")
        ],
    )
    car = cs.Vehicle.generate("sedan", name="car")  # on its wheels: the class's axles, track
    inputs = cs.DriverInputs(
        steering_wheel=[(0.0, 0.0), (0.4, 0.0), (0.7, cs.deg(-120)), (1.0, cs.deg(-120))],
        steering_ratio=16.0,  # a swerve to the right from 0.4 s
        brake=[(0.0, 0.0), (0.6, 0.0), (0.8, 1.0)],  # braking from 0.6 s (fraction of mu)
        wheel_states=[("all", "locked", 1.0)],  # the wheels lock at 1 s
    )
    scene = cs.Scene(ground=ground)
    scene.add(car, (0.0, 0.0), heading=0.0, velocity=(cs.kmh(70), 0.0, 0.0), inputs=inputs)
    scene.add_obstacle(cs.Obstacle.tree(0.4), (38.5, -4.6))
    return scene.run(until="rest", max_duration=20.0)


def main() -> None:
    warnings.simplefilter("ignore", cs.DepthOfPenetrationWarning)
    runs = {"runout_setup": setup_example()}
    for picture, example in EXAMPLES.items():
        runs[picture] = load_scene(REPO / "examples" / example).simulate()
    for picture, result in runs.items():
        plot_trajectories(result, IMG / f"{picture}.png")
        text = str(cs.report(result))
        print(f"== {picture}\n{text[text.index('Run-out') :]}\n")


if __name__ == "__main__":
    main()
