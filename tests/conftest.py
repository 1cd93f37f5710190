"""Shared test setup. The third-party meshes live in ../shared/meshes beside the repository
(never copied into it); tests that need them skip with a message when the folder is absent.

A test that takes a ``mesh_path`` argument runs once per shared mesh; one that takes
``mesh_pair`` runs once per unordered pair of shared meshes."""

from __future__ import annotations

import itertools
from pathlib import Path

import pytest

REPO = Path(__file__).resolve().parents[1]
SHARED_MESHES = REPO.parent / "shared" / "meshes"
MISSING = f"the shared meshes are not at {SHARED_MESHES} (../shared/meshes from the repository)"


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
