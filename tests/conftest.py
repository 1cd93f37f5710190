"""Shared fixtures: the third-party meshes live in ../shared/meshes beside the repository."""

from pathlib import Path

import pytest

SHARED_MESHES = Path(__file__).resolve().parents[1].parent / "shared" / "meshes"


def shared_mesh_paths() -> list[Path]:
    return sorted(SHARED_MESHES.glob("*.ply"))


@pytest.fixture
def mesh_paths() -> list[Path]:
    paths = shared_mesh_paths()
    if not paths:
        pytest.skip(f"the shared meshes are not at {SHARED_MESHES}")
    return paths
