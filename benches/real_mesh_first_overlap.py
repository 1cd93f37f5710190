"""The first overlap of two real meshes: the engine's run from a metre apart to one step after
the meshes first overlap, for every pair of the shared meshes (../shared/meshes, most of them
open), as tests/test_fcl_crosscheck.py runs it (issue 23; benches/README.md, "Open real
meshes").

Each pair gets the same seeded random approaches (headings, direction, closing speed 5-30 m/s,
lateral offset) on every run of the script; each approach is placed by bisecting the engine's
own overlap query along the approach (no python-fcl needed) and started START_GAP before it.
The run is timed alone (the scene built before the clock starts): the median over the
approaches and their sum per pair, and the whole sum.

    python3 benches/real_mesh_first_overlap.py                 # 10 approaches per pair
    python3 benches/real_mesh_first_overlap.py --approaches 3 \
        --pairs bus_gazebo-sedan_quaternius_normalcar1

To compare two builds, run it under each (PYTHONPATH pointing at the other tree's python/
folder with its own built _core) one after the other, or alternated.
"""

from __future__ import annotations

import argparse
import itertools
import math
import os
import statistics
import sys
import time
import zlib
from pathlib import Path

import crashsim as cs
import numpy as np
from crashsim import _core

REPO = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(REPO / "tests"))
from conftest import mesh_mass, shared_mesh_paths  # noqa: E402

START_GAP = 1.0  # m of travel before the meshes meet, as the test
DT = 1e-3  # s


def yaw(h: float) -> np.ndarray:
    """Unit quaternion (w, x, y, z) of a turn about world z by h rad (body -> world)."""
    return np.array([math.cos(0.5 * h), 0.0, 0.0, math.sin(0.5 * h)])


def overlapping(a: cs.Vehicle, b: cs.Vehicle, qa, qb, pa, pb) -> bool:
    """Whether the two posed meshes overlap (the engine's own query)."""
    return bool(_core.shapes_overlap(a.shape, pa, qa, b.shape, pb, qb))


def approach(a: cs.Vehicle, b: cs.Vehicle, rng: np.random.Generator) -> float | None:
    """One seeded approach: the engine's run time (s) to one step after the first overlap, or
    None when the meshes miss each other."""
    ha, hb, theta = rng.uniform(0.0, 2.0 * math.pi, 3)
    closing = rng.uniform(5.0, 30.0)
    share = rng.uniform(0.0, 1.0)
    radius = [float(np.max(np.linalg.norm(v.body_vertices[:, :2], axis=1))) for v in (a, b)]
    lateral = rng.uniform(-0.6, 0.6) * min(radius)
    d = np.array([math.cos(theta), math.sin(theta), 0.0])
    side = np.array([-d[1], d[0], 0.0])
    pa = np.array([0.0, 0.0, a.cg[2] + rng.uniform(0.001, 0.01)])
    far = pa + d * (sum(radius) + 0.5) + side * lateral
    far[2] = b.cg[2] + rng.uniform(0.001, 0.01)
    ra, rb = yaw(ha), yaw(hb)
    travel = sum(radius) + 0.5
    if not overlapping(a, b, ra, rb, pa, far - d * travel):
        return None
    lo, hi = 0.0, travel  # apart at lo, overlapping at hi: bisect to 1 mm
    while hi - lo > 1e-3:
        mid = 0.5 * (lo + hi)
        if overlapping(a, b, ra, rb, pa, far - d * mid):
            hi = mid
        else:
            lo = mid
    pb = far - d * max(lo - START_GAP, 0.0)
    va, vb = d * closing * share, -d * closing * (1.0 - share)
    scene = cs.Scene(depth_of_penetration=0.030)
    scene.add(a, position=pa, heading=ha, velocity=va)
    scene.add(b, position=pb, heading=hb, velocity=vb)
    spec = scene.to_spec(duration=START_GAP / closing + DT, dt=DT)
    start = time.perf_counter()
    spec.run()
    return time.perf_counter() - start


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--approaches", type=int, default=10, help="per pair (default 10)")
    parser.add_argument("--pairs", default="", help="comma-separated NAME-NAME (default all)")
    args = parser.parse_args()
    paths = shared_mesh_paths()
    if not paths:
        sys.exit("the shared meshes (../shared/meshes) are not there")
    vehicles = {
        p.stem: cs.Vehicle.from_mesh(p, mass=mesh_mass(p), name=p.stem) for p in paths
    }
    wanted = {w for w in args.pairs.split(",") if w}
    print(f"crashsim from {Path(cs.__file__).parent}; load {os.getloadavg()}")
    total = 0.0
    for a, b in itertools.combinations(sorted(vehicles), 2):
        if wanted and f"{a}-{b}" not in wanted:
            continue
        rng = np.random.default_rng(zlib.crc32(f"{a}|{b}".encode()))
        times = [approach(vehicles[a], vehicles[b], rng) for _ in range(args.approaches)]
        made = [t for t in times if t is not None]
        if not made:
            print(f"{a:30s} {b:30s} no contact")
            continue
        total += sum(made)
        median = statistics.median(made) * 1e3
        print(f"{a:30s} {b:30s} {len(made):3d} runs: median {median:8.2f} ms, "
              f"sum {sum(made):7.3f} s")  # fmt: skip
    print(f"all pairs: {total:.3f} s; load {os.getloadavg()}")


if __name__ == "__main__":
    main()
