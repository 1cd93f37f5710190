"""Load benchmark: a vehicle from a ~200k-triangle PLY file, with its engine shape.

Two shared meshes are subdivided (each triangle into four, trimesh's ``subdivide``) and
written to a temporary PLY: the sedan three times (watertight, 189,056 triangles; its mass
properties come from the mesh volume) and the hatchback four times (open, 201,728 triangles;
mass properties from its winding-number solid, the default for open meshes). Each run times
``Vehicle.from_mesh(path, mass=...)`` (read, checks, vertex merge, mass properties) and then
``vehicle.shape`` (the engine's body-frame mesh, BVH and winding-number dipoles), in a fresh
process state for the shape (a new Vehicle each run). The quality report (computed on first
use, not part of loading) is timed separately. Prints the median of the runs and the machine.
Target: under 1 s.

    python3 benches/load_mesh.py [--runs 5] [--profile]
"""

from __future__ import annotations

import argparse
import cProfile
import pstats
import statistics
import tempfile
import time
from pathlib import Path

import crashsim as cs
from crashsim.vehicles import meshio
from machine import describe  # benches/machine.py (this folder is on sys.path)

REPO = Path(__file__).resolve().parents[1]
MESHES = REPO.parent / "shared" / "meshes"
CASES = {"sedan_quaternius_normalcar1": 3, "hatchback_gazebo": 4}


def write_subdivided(name: str, times: int, folder: Path) -> Path:
    mesh = meshio.load_mesh(MESHES / f"{name}.ply")
    for _ in range(times):
        mesh = mesh.subdivide()
    path = folder / f"{name}_x{4**times}.ply"
    mesh.export(path)
    return path


def one_run(path: Path) -> dict[str, float]:
    t0 = time.perf_counter()
    vehicle = cs.Vehicle.from_mesh(path, mass=1500.0)
    t1 = time.perf_counter()
    shape = vehicle.shape
    t2 = time.perf_counter()
    quality = vehicle.quality
    t3 = time.perf_counter()
    assert shape.n_triangles == quality.triangles
    return {"from_mesh": t1 - t0, "shape": t2 - t1, "load+shape": t2 - t0, "quality": t3 - t2}


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--runs", type=int, default=5)
    parser.add_argument("--profile", action="store_true", help="profile one load of each")
    args = parser.parse_args()
    if not MESHES.is_dir():
        raise SystemExit(f"the shared meshes are not at {MESHES}")
    with tempfile.TemporaryDirectory() as tmp:
        for name, times in CASES.items():
            path = write_subdivided(name, times, Path(tmp))
            runs = [one_run(path) for _ in range(args.runs)]
            v = cs.Vehicle.from_mesh(path, mass=1500.0)
            q = v.quality
            print(
                f"{path.name}: {q.triangles} triangles, {q.vertices} vertices, "
                f"{path.stat().st_size / 1e6:.1f} MB, watertight {q.watertight}, "
                f"mass properties from {v.sources['inertia']}"
            )
            for key in runs[0]:
                values = [r[key] for r in runs]
                print(
                    f"  {key:<11} median {statistics.median(values):7.3f} s  "
                    f"(min {min(values):.3f}, max {max(values):.3f}, {len(values)} runs)"
                )
            if args.profile:
                profiler = cProfile.Profile()
                profiler.enable()
                _ = cs.Vehicle.from_mesh(path, mass=1500.0).shape
                profiler.disable()
                pstats.Stats(profiler).sort_stats("cumulative").print_stats(18)
    print(f"machine: {describe()}")


if __name__ == "__main__":
    main()
