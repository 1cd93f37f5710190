"""A terrain's cost against the plane (issue 23, item 6): the same 2 s runs of the generated
sedan on the plane z = 0 and on terrain meshes, interleaved in one process; the median wall
time per run and its ratio to the plane's (the goal: a terrain at most 2x the plane).

    python3 benches/terrain_speed.py              # 15 repeats per case, about 30 s
    python3 benches/terrain_speed.py --repeats 5

The runs (steps of 1 ms, `Scene.run(2.0)`; world building included, as a user pays it):
"locked", every wheel locked from t = 0 at 15 m/s (a skid; on the slopes uphill), and
"rolling", the wheels free at 15 m/s (on the slopes downhill, gathering speed). The grounds:
the plane; a level two-triangle terrain; a 10 deg slope of two triangles (400 m square); a
10 deg slope of 1 m triangles with 5 cm bumps (121 x 401 vertices, 96,000 triangles).
"""

from __future__ import annotations

import argparse
import math
import statistics
import time

import crashsim as cs
import numpy as np
import trimesh
from machine import describe

SLOPE_DEG = 10.0
SPEED = 15.0  # m/s
DURATION = 2.0  # s
DT = 1e-3  # s


def two_triangles(slope_deg: float) -> trimesh.Trimesh:
    """A 400 m square rising slope_deg along x, through the origin."""
    half, tan = 200.0, math.tan(math.radians(slope_deg))
    v = [[-half, -half, -half * tan], [half, -half, half * tan],
         [half, half, half * tan], [-half, half, -half * tan]]  # fmt: skip
    return trimesh.Trimesh(v, [[0, 1, 2], [0, 2, 3]], process=False)


def bumpy_grid(slope_deg: float) -> trimesh.Trimesh:
    """1 m triangles over x -100..300 m, y -60..60 m rising slope_deg along x, bumps 5 cm."""
    x, y = np.meshgrid(np.arange(-100.0, 301.0), np.arange(-60.0, 61.0), indexing="ij")
    z = x * math.tan(math.radians(slope_deg)) + 0.05 * np.sin(0.9 * x) * np.cos(1.3 * y)
    nx, ny = x.shape
    ids = np.arange(nx * ny).reshape(nx, ny)
    a, b = ids[:-1, :-1].ravel(), ids[1:, :-1].ravel()
    c, d = ids[1:, 1:].ravel(), ids[:-1, 1:].ravel()
    faces = np.concatenate([np.c_[a, b, c], np.c_[a, c, d]])
    return trimesh.Trimesh(np.c_[x.ravel(), y.ravel(), z.ravel()], faces, process=False)


def scene(ground: cs.Ground, locked: bool, downhill: bool) -> cs.Scene:
    car = cs.Vehicle.generate("sedan")
    s = cs.Scene(ground=ground)
    states = [(w, "locked", 0.0) for w in car.wheels] if locked else []
    heading = math.pi if downhill else 0.0
    s.add(car, (0.0, 0.0), heading=heading,
          velocity=(SPEED * math.cos(heading), SPEED * math.sin(heading), 0.0),
          inputs=cs.DriverInputs(wheel_states=states))  # fmt: skip
    return s


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--repeats", type=int, default=15)
    a = ap.parse_args()
    grounds = {
        "plane": cs.Ground(),
        "level terrain, 2 triangles": cs.Ground(terrain=two_triangles(0.0)),
        f"{SLOPE_DEG:g} deg slope, 2 triangles": cs.Ground(terrain=two_triangles(SLOPE_DEG)),
        f"{SLOPE_DEG:g} deg slope, 96,000 triangles, bumps": cs.Ground(
            terrain=bumpy_grid(SLOPE_DEG)
        ),
    }
    print("terrain against the plane: benches/terrain_speed.py")
    print(f"machine: {describe()}")
    print(f"median of {a.repeats} runs of {DURATION:g} s at {DT * 1e3:g} ms steps, cases "
          f"interleaved; ratio = terrain / plane")  # fmt: skip
    for run_kind, locked in (("locked", True), ("rolling", False)):
        scenes = {name: scene(g, locked, downhill=not locked) for name, g in grounds.items()}
        times: dict[str, list[float]] = {name: [] for name in scenes}
        ends: dict[str, np.ndarray] = {}
        for _ in range(a.repeats):
            for name, s in scenes.items():
                t0 = time.perf_counter()
                r = s.run(DURATION, DT)
                times[name].append(time.perf_counter() - t0)
                ends[name] = r.trajectory("sedan").velocity[-1]
        base = statistics.median(times["plane"])
        print(f"\n{run_kind} at {SPEED:g} m/s:")
        for name, ts in times.items():
            m = statistics.median(ts)
            v = float(np.linalg.norm(ends[name]))
            print(f"  {name:42s} {m * 1e3:8.2f} ms  ratio {m / base:6.2f}  "
                  f"(speed at the end {v:5.2f} m/s)")  # fmt: skip
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
