"""Study backends (crashsim.studies.backends): a third backend, registered by a user, runs
studies through the API and the CLI with no change to crashsim.studies.run or the CLI, and
gives the local backend's columns bit for bit; the registry's refusals."""

from __future__ import annotations

from pathlib import Path
from typing import Any

import crashsim as cs
import numpy as np
import pandas as pd
import pytest
from conftest import REPO
from crashsim.batch import run_batch
from crashsim.cli import main
from crashsim.errors import StudyError
from crashsim.io.scenefile import load_scene
from crashsim.studies.backends import (
    _BACKENDS,
    Variants,
    backend_names,
    get_backend,
    register_backend,
)
from crashsim.studies.chunks import empty_columns, place_chunk

SEED = REPO / "examples" / "seed-90deg.toml"
MPH = 0.44704  # m/s


class OneByOne:
    """Each variant its own batch of one, last variant first (as a process pool handing out
    single runs would), on one thread."""

    name = "one-by-one"
    runs_people = False
    takes_scheduler = False

    def __init__(self) -> None:
        self.runs = 0

    def check(self) -> None:
        return None

    def run(self, v: Variants) -> Any:
        columns = empty_columns(v.scene, v.n, int(v.options["max_impacts"]))
        errors: list[Any] = []
        finished = np.zeros(v.n, dtype=bool)
        for k in reversed(range(v.n)):
            b = run_batch(v.scene, {p: a[k : k + 1] for p, a in v.overrides.items()}, n=1,
                          threads=1, progress=None, **v.options)
            place_chunk(columns, b.columns, k, v.n)
            finished[k] = bool(b.finished[0])
            errors += [e.shifted(k) for e in b.errors]
            self.runs += 1
            v.progress(v.n - k)
        return columns, errors, finished, False


@pytest.fixture
def one_by_one() -> Any:
    backend = OneByOne()
    register_backend(backend)
    yield backend
    del _BACKENDS[backend.name]


def _same_columns(a: cs.studies.Study, b: cs.studies.Study) -> None:
    assert list(a.outputs) == list(b.outputs)
    for key in a.outputs:
        x, y = np.asarray(a.outputs[key]), np.asarray(b.outputs[key])
        if x.dtype.kind == "f":
            assert np.array_equal(x.view(np.uint64), y.view(np.uint64)), key
        else:
            assert np.array_equal(x, y), key
    assert list(a.status) == list(b.status)
    assert [e.message for e in a.errors] == [e.message for e in b.errors]


def test_a_registered_backend_runs_a_sweep_as_the_local_one_does(one_by_one: OneByOne) -> None:
    scene = load_scene(SEED).scene
    grid = {"red.speed": [20 * MPH, 30 * MPH, 40 * MPH], "restitution": [0.0, 1.5]}
    mine = cs.sweep(scene, grid, duration=0.3, progress=False, backend="one-by-one")
    local = cs.sweep(scene, grid, duration=0.3, progress=False)
    assert one_by_one.runs == 6
    assert list(mine.status).count("failed") == 3  # restitution 1.5 is refused, variant by variant
    _same_columns(mine, local)
    assert mine.settings["backend"] == "one-by-one"


def test_the_cli_offers_a_registered_backend(one_by_one: OneByOne, tmp_path: Path,
                                             capsys: pytest.CaptureFixture[str]) -> None:
    out = tmp_path / "sweep.csv"
    code = main(["sweep", str(SEED), "--vary", "red.speed=20:40:3 mph", "--backend",
                 "one-by-one", "--out", str(out)])
    assert code == 0, capsys.readouterr()
    assert one_by_one.runs == 3
    frame = pd.read_csv(out, index_col="variant")
    local = cs.sweep(load_scene(SEED).scene, {"red.speed": [20 * MPH, 30 * MPH, 40 * MPH]},
                     duration=load_scene(SEED).run.longest, progress=False)
    assert np.array_equal(frame["impact1.red.delta_v"].to_numpy(), local["impact1.red.delta_v"],
                          equal_nan=True)
    # --scheduler is for a backend that takes one
    assert main(["sweep", str(SEED), "--vary", "red.speed=20:40:3 mph", "--backend",
                 "one-by-one", "--scheduler", "tcp://127.0.0.1:9"]) == 2
    assert "--scheduler is for --backend dask" in capsys.readouterr().err


def test_the_registry_refuses_what_it_cannot_name_or_run(one_by_one: OneByOne) -> None:
    assert backend_names() == ["local", "dask", "one-by-one"]
    assert get_backend("one-by-one") is one_by_one
    register_backend(one_by_one)  # the same object again: no change
    with pytest.raises(StudyError, match="'one-by-one' is already registered"):
        register_backend(OneByOne())
    with pytest.raises(StudyError, match="needs a name"):
        register_backend(type("Nameless", (), {})())
    half = type("Half", (), {"name": "half", "check": lambda self: None})()
    with pytest.raises(StudyError, match="'half' lacks runs_people, takes_scheduler, run"):
        register_backend(half)
    with pytest.raises(StudyError, match='unknown: use "local", "dask" or "one-by-one"'):
        cs.sweep(load_scene(SEED).scene, {"red.speed": [9.0]}, backend="nowhere",
                 progress=False)
