"""Shared test setup. The third-party meshes live in ../shared/meshes beside the repository
(never copied into it); tests that need them skip with a message when the folder is absent.

A test that takes a ``mesh_path`` argument runs once per shared mesh; one that takes
``mesh_pair`` runs once per unordered pair of shared meshes."""

from __future__ import annotations

import itertools
import math
import os
import signal
from pathlib import Path

import crashsim as cs
import pytest
from hypothesis import HealthCheck, settings

# Property-based tests (hypothesis; tests/test_fuzz_*.py). "ci", the default: a bounded,
# reproducible run (fixed seed, no example database written) that keeps every fuzz test
# within a few seconds; "long": many more random examples, as a habit before a release:
#   HYPOTHESIS_PROFILE=long python -m pytest -q -p no:cacheprovider test_fuzz_*.py
# (from tests/; a failing example is printed, and kept in tests/.hypothesis to be replayed).
settings.register_profile(
    "ci",
    max_examples=60,
    deadline=2000,  # ms per example: a slower one is a hang to look at
    derandomize=True,
    database=None,
    suppress_health_check=[HealthCheck.too_slow],
)
settings.register_profile(
    "long",
    max_examples=2000,
    deadline=10_000,
    suppress_health_check=[HealthCheck.too_slow],
)
settings.load_profile(os.environ.get("HYPOTHESIS_PROFILE", "ci"))

# The Ctrl-C tests (test_batch, test_studies, test_studies_cli, test_fitfile) send SIGINT to
# this process or to a child. A shell starts a command run in the background (`pytest &`)
# with SIGINT ignored, which Python and every child it starts then keep, so those tests
# would fail there only; Python's own handler (KeyboardInterrupt) is put back, which a child
# then gets as it would from an interactive shell.
if signal.getsignal(signal.SIGINT) is signal.SIG_IGN:
    signal.signal(signal.SIGINT, signal.default_int_handler)

REPO = Path(__file__).resolve().parents[1]
SHARED_MESHES = REPO.parent / "shared" / "meshes"
MISSING = f"the shared meshes are not at {SHARED_MESHES} (../shared/meshes from the repository)"


# Kerb masses of the shared meshes' vehicles (kg), typical of their kinds, so that each is a
# plausible vehicle (a 1500 kg bus is 15 kg/m^3 and gets a PlausibilityWarning).
MESH_MASS = {
    "sedan_quaternius_normalcar1": 1450.0,
    "suv_quaternius_suv": 1900.0,
    "hatchback_gazebo": 1200.0,
    "pickup_gazebo": 2200.0,
    "van_gazebo_ambulance": 4500.0,
    "bus_gazebo": 12000.0,
}


def mesh_mass(path: Path) -> float:
    """The kerb mass (kg) of a shared mesh's vehicle."""
    return MESH_MASS[Path(path).stem]


def shared_mesh_paths() -> list[Path]:
    """The shared .ply meshes, sorted by name (empty when the folder is absent)."""
    return sorted(SHARED_MESHES.glob("*.ply"))


def pytest_generate_tests(metafunc: pytest.Metafunc) -> None:
    paths = shared_mesh_paths()
    skipped = [pytest.param(None, marks=pytest.mark.skip(reason=MISSING), id="no-meshes")]
    if "mesh_path" in metafunc.fixturenames:
        if paths:
            metafunc.parametrize("mesh_path", paths, ids=[p.stem for p in paths])
        else:
            metafunc.parametrize("mesh_path", skipped)
    if "mesh_pair" in metafunc.fixturenames:
        pairs = list(itertools.combinations(paths, 2))
        if pairs:
            ids = [f"{a.stem}-{b.stem}" for a, b in pairs]
            metafunc.parametrize("mesh_pair", pairs, ids=ids)
        else:
            metafunc.parametrize("mesh_pair", skipped)


def seed_side_impact(
    speed: float,
    heading: float,
    start: tuple[float, float],
    dt: float = 1e-3,
    duration: float = 0.3,
) -> cs.Result:
    """The seed's worked example with box vehicles: red (4.5 x 1.8 x 1.4 m, 1450 kg) at
    `speed` m/s along `heading` rad into the left side of blue (4.6 x 1.8 x 1.45 m, 1500 kg, at
    rest, heading +90 deg: its left side is the plane x = -0.9 m, facing -x); `start` is red's
    CG (x, y), m; depth of penetration 30 ms."""
    red = cs.Vehicle.box(4.5, 1.8, 1.4, mass=1450.0, name="red")
    blue = cs.Vehicle.box(4.6, 1.8, 1.45, mass=1500.0, name="blue")
    scene = cs.Scene(depth_of_penetration=0.030)
    velocity = (speed * math.cos(heading), speed * math.sin(heading), 0.0)
    scene.add(red, position=(*start, 0.7), heading=heading, velocity=velocity)
    scene.add(blue, position=(0.0, 0.0, 0.725), heading=cs.deg(90.0))
    return scene.run(duration=duration, dt=dt)
