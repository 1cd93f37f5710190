"""A study on Dask against the local batch, in one run: a Monte Carlo of the 20k-mesh
two-sedan seed scene (benches/compare_peers.py's whole scene: the seed's 90 deg side impact,
two generated sedans of about 21,000 triangles, 30 mph, dt_p 30 ms, 1 s at 1 ms steps) run
by the local backend (``threads`` = the workers) and by a Dask LocalCluster of ``--workers``
processes (one thread each, loopback), with the results checked equal bit for bit.

    python3 benches/studies_dask.py              # 1,000 variants, 2 workers
    python3 benches/studies_dask.py --n 100      # a quick run

Prints each backend's wall time (the cluster's start and close timed apart), the ratio
dask / local, the variants per second, which crashsim.batch implementation ran, and where
the Dask run's time went: per worker its chunks, their compute time, and when it started
its first and ended its last (from the run's start; the scheduler's task stream).
``--chunk-size K`` gives the Dask run fixed chunks of K variants (default: the backend's).
``--bracket`` runs the local study again after the Dask one and compares Dask with the mean
of the two local times, so a load that rises or falls during the run (a shared machine)
does not land on one backend alone; the load average is printed before each run.
"""

from __future__ import annotations

import argparse
import math
import os
import sys
import time
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))

import compare_peers as cp  # noqa: E402  (the 20k sedan mesh and the scene's numbers)


def scene() -> tuple[object, int]:
    """The seed's 90 deg side impact with two 20k sedans (compare_peers.make_scene's), and
    the mesh's triangle count."""
    import crashsim as cs

    mesh = cp.make_mesh(cp.SCENE_SIZE)
    v = cp._class_vehicle()

    def vehicle(name: str) -> cs.Vehicle:
        return cs.Vehicle(mesh, v.mass, v.cg, v.inertia, name=name, stiffness=v.stiffness)

    red, blue = vehicle("red"), vehicle("blue")
    length, width = float(mesh.extents[0]), float(mesh.extents[1])
    nose = length / 2.0 - float(v.cg[0])
    h = float(v.cg[2])
    s = cs.Scene(depth_of_penetration=cp.DTP, restitution=cp.RESTITUTION, friction=cp.FRICTION)
    s.add(red, (-width / 2.0 - nose - cp.SCENE_GAP, cp.LATERAL_OFFSET, h), heading=0.0,
          velocity=(cp.SPEED, 0.0, 0.0))
    s.add(blue, (0.0, 0.0, h), heading=math.pi / 2.0)
    return s, len(mesh.faces)


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--n", type=int, default=1000, help="variants (1000)")
    ap.add_argument("--workers", type=int, default=2, help="Dask workers = local threads (2)")
    ap.add_argument("--seed", type=int, default=1)
    ap.add_argument("--chunk-size", type=int, default=None, help="Dask chunks (the backend's)")
    ap.add_argument("--bracket", action="store_true",
                    help="run the local study again after the Dask one (load drift)")
    args = ap.parse_args()

    import crashsim as cs
    import crashsim.batch
    from crashsim.studies import normal, uniform
    from crashsim.studies.dask_backend import local_cluster
    from distributed import Client, get_task_stream

    base, triangles = scene()
    dists = {
        "red.speed": normal(cp.SPEED, 0.9),  # m/s: 30 mph +- 2 mph
        "red.heading": uniform(-0.05, 0.05),  # rad: about +- 3 deg
        "restitution": uniform(0.05, 0.2),
    }
    run = {"duration": cp.DURATION, "dt": cp.DT, "progress": False}
    impl = (crashsim.batch.__doc__ or "").split("\n\n")[1].split(":")[0].strip()
    print(f"crashsim.batch: {impl}")
    print(f"scene: two sedans, {triangles:,} triangles each; {args.n} variants, "
          f"{cp.DURATION:g} s at {cp.DT * 1e3:g} ms; {args.workers} workers")

    def run_local() -> tuple[cs.Study, float]:
        print(f"load average {os.getloadavg()[0]:.2f}")
        t0 = time.perf_counter()
        study = cs.monte_carlo(base, dists, args.n, args.seed, threads=args.workers, **run)
        t = time.perf_counter() - t0
        print(f"local : {t:8.2f} s  ({args.n / t:7.1f} variants/s), "
              f"{int(study.ok.sum())} ok, {len(study.errors)} failed")
        return study, t

    local, t_local = run_local()

    t0 = time.perf_counter()
    cluster = local_cluster(args.workers)
    client = Client(cluster)
    t_start = time.perf_counter() - t0
    print(f"load average {os.getloadavg()[0]:.2f}")
    try:
        with get_task_stream(client) as stream:
            t0 = time.perf_counter()
            start_wall = time.time()
            dask = cs.monte_carlo(base, dists, args.n, args.seed, backend="dask",
                                  client=client, chunk_size=args.chunk_size, **run)
            t_dask = time.perf_counter() - t0
    finally:
        t0 = time.perf_counter()
        client.close()
        cluster.close()
        t_close = time.perf_counter() - t0
    print(f"dask  : {t_dask:8.2f} s  ({args.n / t_dask:7.1f} variants/s); the cluster's start "
          f"{t_start:.2f} s and close {t_close:.2f} s apart")
    per_worker: dict[str, list[tuple[float, float]]] = {}
    for task in stream.data:
        if not str(task.get("key", "")).startswith("('_run_chunk") and "_run_chunk" not in str(
            task.get("key", "")
        ):
            continue
        for part in task["startstops"]:
            if part["action"] == "compute":
                per_worker.setdefault(task["worker"], []).append(
                    (part["start"] - start_wall, part["stop"] - start_wall)
                )
    for w, spans in sorted(per_worker.items()):
        busy = sum(b - a for a, b in spans)
        print(f"  worker {w}: {len(spans)} chunks, computing {busy:.2f} s, first from "
              f"{min(a for a, _ in spans):.2f} s, last to {max(b for _, b in spans):.2f} s")
    if args.bracket:
        again, t_again = run_local()
        assert all(np.array_equal(local[k], again[k], equal_nan=True) for k in local.outputs)
        t_local = 0.5 * (t_local + t_again)
        print(f"local : {t_local:8.2f} s, the mean of the runs before and after Dask")
    print(f"load average {os.getloadavg()[0]:.2f}")
    same = all(np.array_equal(local[k], dask[k], equal_nan=True) for k in local.outputs)
    print(f"results equal bit for bit: {same}")
    print(f"ratio dask / local = {t_dask / t_local:.3f} "
          f"(with the cluster's start and close: {(t_dask + t_start + t_close) / t_local:.3f})")
    if not same:
        raise SystemExit("the Dask results differ from the local ones")


if __name__ == "__main__":
    main()
