"""The Dask backend of studies on a LocalCluster of 2 worker processes (loopback only):
results equal to the local backend bit for bit, the scene sent once, a worker killed
mid-study loses nothing and counts nothing twice, Ctrl-C keeps what finished."""

from __future__ import annotations

import copyreg
import os
import signal
from collections.abc import Iterator
from typing import Any

import crashsim as cs
import numpy as np
import pytest
from crashsim.studies import normal, uniform

distributed = pytest.importorskip("distributed")

DURATION = 0.3  # s
DT = 1e-3  # s


def _scene() -> cs.Scene:
    red = cs.Vehicle.box(4.5, 1.8, 1.4, mass=1450.0, name="red")
    blue = cs.Vehicle.box(4.6, 1.8, 1.45, mass=1500.0, name="blue")
    scene = cs.Scene(depth_of_penetration=0.03, restitution=0.1, friction=0.6)
    scene.add(red, (-3.65, 0.3, 0.7), heading=0.0, velocity=(13.4112, 0.0, 0.0))
    scene.add(blue, (0.0, 0.0, 0.725), heading=np.pi / 2)
    return scene


DISTRIBUTIONS = {
    "red.speed": normal(13.0, 1.5),
    "red.heading": uniform(-0.15, 0.15),
    "restitution": uniform(0.0, 0.3),
    # some variants start overlapping (red's nose 0.5 m from blue's side at x = -3.65):
    "red.position_x": uniform(-3.8, -2.9),
}


def _cluster() -> Any:
    from crashsim.studies.dask_backend import local_cluster

    return local_cluster(2)


@pytest.fixture(scope="module")
def client() -> Iterator[Any]:
    cluster = _cluster()
    c = distributed.Client(cluster)
    yield c
    c.close()
    cluster.close()


@pytest.fixture(scope="module")
def local() -> cs.Study:
    return cs.monte_carlo(_scene(), DISTRIBUTIONS, n=120, seed=7, duration=DURATION, dt=DT,
                          progress=False)


def _same(a: cs.Study, b: cs.Study) -> None:
    assert a.n == b.n
    assert list(a.outputs) == list(b.outputs)
    for k in a.outputs:
        assert a[k].dtype == b[k].dtype, k
        assert np.array_equal(a[k], b[k], equal_nan=True), k
    assert np.array_equal(a.status, b.status)
    assert [(e.index, e.kind, e.message) for e in a.errors] == [
        (e.index, e.kind, e.message) for e in b.errors
    ]


def test_shrinking_chunks_cover_every_variant_once_and_end_small() -> None:
    from crashsim.studies.chunks import shrinking_bounds

    for n, size, workers in [(1000, 125, 2), (1, 1, 2), (7, 2, 3), (10_000, 256, 2), (120, 15, 2)]:
        bounds = shrinking_bounds(n, size, workers)
        assert bounds[0][0] == 0 and bounds[-1][1] == n
        assert all(a[1] == b[0] for a, b in zip(bounds, bounds[1:], strict=False))
        sizes = [stop - start for start, stop in bounds]
        assert sizes == sorted(sizes, reverse=True) and 1 <= sizes[-1] and sizes[0] <= size
    sizes = [b - a for a, b in shrinking_bounds(1000, 125, 2)]
    assert sizes[:5] == [125] * 5 and max(sizes[-4:]) <= 4  # the last ones: size / 32


def test_dask_equals_local_bit_for_bit(client: Any, local: cs.Study) -> None:
    assert local.errors, "the design should have variants overlapping at t = 0"
    assert all(e.kind == "InitialOverlapError" for e in local.errors)
    assert int(local.ok.sum()) > 60
    on_dask = cs.monte_carlo(_scene(), DISTRIBUTIONS, n=120, seed=7, duration=DURATION, dt=DT,
                             progress=False, backend="dask", client=client, chunk_size=16)
    _same(local, on_dask)
    # a scheduler's address works too (the backend connects, then closes its own client)
    by_address = cs.monte_carlo(_scene(), DISTRIBUTIONS, n=120, seed=7, duration=DURATION,
                                dt=DT, progress=False, backend="dask",
                                client=client.scheduler.address)
    _same(local, by_address)
    assert client.status == "running"  # the caller's client is left open


def test_the_scene_is_sent_once_not_per_chunk(client: Any) -> None:
    pickled = []

    def count(scene: cs.Scene) -> Any:
        pickled.append(1)
        return scene.__reduce_ex__(4)

    copyreg.pickle(cs.Scene, count)
    try:
        study = cs.sweep(_scene(), {"red.speed": np.linspace(10, 16, 40)}, duration=DURATION,
                         dt=DT, progress=False, backend="dask", client=client, chunk_size=4)
    finally:
        del copyreg.dispatch_table[cs.Scene]
    assert study.ok.all() and study.n == 40
    assert len(pickled) == 1  # 10 chunks, one scatter (broadcast to both workers)


def test_a_local_cluster_is_started_and_closed_when_no_client_is_given(
    monkeypatch: pytest.MonkeyPatch,
) -> None:
    from crashsim.studies import dask_backend

    started: list[Any] = []
    original = dask_backend.local_cluster

    def spy(n_workers: int | None = None) -> Any:
        started.append(original(n_workers))
        return started[-1]

    monkeypatch.setattr(dask_backend, "local_cluster", spy)
    scene = _scene()
    study = cs.sweep(scene, {"restitution": [0.0, 0.2]}, duration=DURATION, dt=DT,
                     progress=False, backend="dask", threads=1)  # one worker: a quick start
    ref = cs.sweep(scene, {"restitution": [0.0, 0.2]}, duration=DURATION, dt=DT, progress=False)
    _same(ref, study)
    assert len(started) == 1
    assert started[0].status.name == "closed"
    assert started[0].scheduler_address.startswith("tcp://127.0.0.1:")  # loopback only


def test_an_unreachable_scheduler_is_a_study_error(monkeypatch: pytest.MonkeyPatch) -> None:
    from crashsim.studies import dask_backend

    monkeypatch.setattr(dask_backend, "CONNECT_TIMEOUT", "1s")
    with pytest.raises(cs.StudyError, match="cannot reach the Dask scheduler"):
        cs.sweep(_scene(), {"restitution": [0.0]}, duration=DURATION, progress=False,
                 backend="dask", client="tcp://127.0.0.1:9")


def test_a_worker_killed_mid_study_loses_nothing_and_counts_nothing_twice(
    client: Any, local: cs.Study
) -> None:
    # last in this file: it kills one of the module's workers (its nanny starts another)
    c = client
    before = set(c.run(os.getpid).values())
    killed: list[tuple[str, int, int]] = []

    def progress(done: int, n: int) -> None:
        if killed:
            return
        busy = {w: ts for w, ts in c.processing().items() if ts}
        if not busy:  # between chunks (a loaded machine): kill at a later report
            return
        worker = sorted(busy)[0]
        pid = c.run(os.getpid, workers=[worker])[worker]
        os.kill(pid, signal.SIGKILL)
        killed.append((worker, pid, len(busy[worker])))

    study = cs.monte_carlo(_scene(), DISTRIBUTIONS, n=120, seed=7, duration=DURATION, dt=DT,
                           progress=progress, backend="dask", client=c, chunk_size=6)
    assert killed, "no report found a worker running a chunk to kill"
    assert killed[0][2] >= 1  # the worker died with a chunk in hand
    assert killed[0][1] in before
    assert killed[0][1] not in set(c.run(os.getpid).values())  # it is gone
    assert not study.interrupted
    assert int((study.status != "not run").sum()) == 120  # every variant once
    _same(local, study)
