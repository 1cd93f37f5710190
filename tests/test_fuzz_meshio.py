"""Fuzzing the mesh loader (crashsim.vehicles.meshio.load_mesh, Vehicle.from_mesh) with
hypothesis: random, degenerate and near-coplanar triangle soups, NaN and huge vertices,
empty files, and PLY / OBJ / STL / OFF files truncated or with bytes overwritten. Each must
load with finite numbers everywhere or raise a crashsim error (a CrashsimError subclass) -
never another exception, a NumPy or trimesh warning, or a hang (hypothesis' deadline).
Profiles: conftest.py ("ci" by default, "long")."""

from __future__ import annotations

import io
import math
import tempfile
from pathlib import Path

import crashsim as cs
import numpy as np
import pytest
import trimesh
from hypothesis import example, given
from hypothesis import strategies as st
from hypothesis.extra import numpy as hnp

pytestmark = pytest.mark.filterwarnings("ignore::crashsim.PlausibilityWarning")

FORMATS = ("ply", "obj", "stl", "off")


def _finite(a: object) -> bool:
    return bool(np.all(np.isfinite(np.asarray(a, dtype=np.float64))))


def check_mesh_source(source: object) -> None:
    """The property, for the loader and for a vehicle built from it."""
    try:
        mesh = cs.load_mesh(source)  # type: ignore[arg-type]
    except cs.CrashsimError as e:
        assert str(e).strip()
        return
    assert len(mesh.faces) > 0 and _finite(mesh.vertices)
    try:
        quality = cs.mesh_quality(mesh)
    except cs.CrashsimError:
        quality = None
    if quality is not None:
        assert all(math.isfinite(x) for x in quality.extents)
        assert quality.volume is None or math.isfinite(quality.volume)
    try:
        vehicle = cs.Vehicle.from_mesh(source, mass=1500.0)  # type: ignore[arg-type]
    except cs.CrashsimError as e:
        assert str(e).strip()
        return
    assert _finite(vehicle.cg) and _finite(vehicle.inertia) and _finite(vehicle.mesh.vertices)
    assert np.all(np.linalg.eigvalsh(vehicle.inertia) > 0.0)
    assert vehicle.summary()  # formats every number


# -- triangle soups in memory ------------------------------------------------------------------

coordinates = st.floats(min_value=-3.0, max_value=3.0, allow_nan=False, allow_infinity=False)


@st.composite
def soups(draw: st.DrawFn) -> trimesh.Trimesh:
    n = draw(st.integers(3, 16))
    vertices = draw(hnp.arrays(np.float64, (n, 3), elements=coordinates))
    kind = draw(st.sampled_from(["random", "flat", "near-flat", "collinear", "scaled", "bad"]))
    if kind == "flat":
        vertices[:, 2] = 0.5
    elif kind == "near-flat":  # near-coplanar: heights within 1e-9 m
        vertices[:, 2] = 0.5 + 1e-9 * np.tanh(vertices[:, 2])
    elif kind == "collinear":
        vertices = np.outer(vertices[:, 0], [1.0, 0.5, 0.25])
    elif kind == "scaled":
        vertices *= draw(st.sampled_from([1e-7, 1e-3, 1e3, 1e7, 1e11]))
    elif kind == "bad":
        i = draw(st.integers(0, n - 1))
        vertices[i, draw(st.integers(0, 2))] = draw(st.sampled_from([np.nan, np.inf, -np.inf]))
    faces = draw(
        hnp.arrays(np.int64, (draw(st.integers(1, 24)), 3), elements=st.integers(0, n - 1))
    )
    return trimesh.Trimesh(vertices, faces, process=False)


def closed_box(extents: tuple[float, float, float] = (4.5, 1.8, 1.4)) -> trimesh.Trimesh:
    return trimesh.creation.box(extents=extents)


@given(soups())
def test_triangle_soups_load_or_raise_a_crashsim_error(mesh: trimesh.Trimesh) -> None:
    check_mesh_source(mesh)


@given(
    st.sampled_from(["box", "sphere", "open box"]),
    st.floats(min_value=1e-6, max_value=1e6),
    st.floats(min_value=0.0, max_value=1e-6),
)
def test_scaled_and_jittered_closed_meshes_load_or_raise(
    shape: str, scale: float, jitter: float
) -> None:
    mesh = closed_box() if shape != "sphere" else trimesh.creation.icosphere(subdivisions=1)
    if shape == "open box":
        mesh = trimesh.Trimesh(mesh.vertices, mesh.faces[1:], process=False)
    rng = np.random.default_rng(0)
    vertices = mesh.vertices * scale + jitter * rng.standard_normal(mesh.vertices.shape)
    check_mesh_source(trimesh.Trimesh(vertices, mesh.faces, process=False))


# -- files: empty, truncated, corrupted ----------------------------------------------------------


def _file_bytes(fmt: str, binary: bool) -> bytes:
    mesh = closed_box()
    kwargs = {}
    if fmt in ("ply", "stl"):
        kwargs["encoding" if fmt == "ply" else "file_type"] = (
            ("binary" if binary else "ascii")
            if fmt == "ply"
            else ("stl" if binary else "stl_ascii")
        )
    out = mesh.export(file_type=kwargs.pop("file_type", fmt), **kwargs)
    return out.encode() if isinstance(out, str) else bytes(out)


ORIGINALS = {(f, b): _file_bytes(f, b) for f in FORMATS for b in (True, False)}


def check_file(data: bytes, fmt: str) -> None:
    with tempfile.TemporaryDirectory() as folder:
        path = Path(folder) / f"car.{fmt}"
        path.write_bytes(data)
        check_mesh_source(path)


@st.composite
def damaged_files(draw: st.DrawFn) -> tuple[bytes, str]:
    fmt = draw(st.sampled_from(FORMATS))
    data = bytearray(ORIGINALS[(fmt, draw(st.booleans()))])
    how = draw(st.sampled_from(["truncate", "overwrite", "both"]))
    if how in ("overwrite", "both"):
        for _ in range(draw(st.integers(1, 6))):
            i = draw(st.integers(0, len(data) - 1))
            data[i] = draw(st.integers(0, 255))
    if how in ("truncate", "both"):
        data = data[: draw(st.integers(0, len(data)))]
    return bytes(data), fmt


@given(damaged_files())
def test_damaged_mesh_files_load_or_raise_a_crashsim_error(case: tuple[bytes, str]) -> None:
    check_file(*case)


@pytest.mark.parametrize("fmt", FORMATS)
def test_empty_and_undamaged_files(fmt: str) -> None:
    check_file(b"", fmt)
    for binary in (True, False):
        with tempfile.TemporaryDirectory() as folder:
            path = Path(folder) / f"car.{fmt}"
            path.write_bytes(ORIGINALS[(fmt, binary)])
            v = cs.Vehicle.from_mesh(path, mass=1500.0)
            assert np.allclose(v.extents, [4.5, 1.8, 1.4])


def test_the_file_writer_is_what_trimesh_reads() -> None:
    for (fmt, _binary), data in ORIGINALS.items():
        loaded = trimesh.load(io.BytesIO(data), file_type=fmt, force="mesh")
        assert np.allclose(loaded.extents, [4.5, 1.8, 1.4])


@example(b"ply\nformat ascii 1.0\nelement vertex 3\n")
@given(st.binary(max_size=64))
def test_random_bytes_as_a_ply_file(data: bytes) -> None:
    check_file(data, "ply")


# -- what the fuzzing found, kept ------------------------------------------------------------------


def test_nearly_flat_soup_is_a_mesh_error_not_out_of_memory() -> None:
    # Found by test_triangle_soups_load_or_raise_a_crashsim_error: a triangle 2.2e-16 m
    # thick made the winding-number grid 6e6 x 1 x 6e6 cells (269 TiB; the machine's memory
    # ran out). A flat mesh has no solid; a thin one gets a grid of the usual size.
    soup = trimesh.Trimesh(
        [[1.0, 2.220446049250313e-16, 1.0], [0.0, 0.0, 0.0], [0.0, 0.0, 0.0]],
        [[0, 1, 1]],
        process=False,
    )
    with pytest.raises(cs.MeshError, match="encloses no volume .it is flat"):
        cs.Vehicle.from_mesh(soup, mass=1500.0)
    check_mesh_source(soup)
    thin = closed_box((4.0, 1e-4, 1.5))  # 0.1 mm thin: a solid, on a grid of about 50k cells
    mass_properties = cs.vehicles.mass_properties
    counts = mass_properties._grid_counts(thin.extents, mass_properties.WINDING_GRID_CELLS)
    assert counts[1] == 1 and 40_000 < counts.prod() < 60_000


def test_face_indices_beyond_the_vertices_are_a_mesh_error(tmp_path: Path) -> None:
    # Found by test_damaged_mesh_files_load_or_raise_a_crashsim_error: a binary PLY with one
    # overwritten byte named vertex 261 of 8, and trimesh's vertex merging raised IndexError.
    data = bytearray(ORIGINALS[("ply", True)])
    header_end = data.index(b"end_header\n") + len(b"end_header\n")
    first_face = header_end + 8 * 3 * 4  # 8 vertices of 3 float32
    data[first_face + 2] = 1  # the first face's first index: 1 + 256
    path = tmp_path / "car.ply"
    path.write_bytes(bytes(data))
    with pytest.raises(cs.MeshError, match="faces naming vertices it does not have .it has 8."):
        cs.load_mesh(path)
    with pytest.raises(cs.MeshError, match="face 0 = .257, "):
        cs.Vehicle.from_mesh(
            trimesh.Trimesh([[0, 0, 0], [1, 0, 0]], [[257, 0, 1]], process=False), mass=1.0
        )


def test_quality_of_a_closed_mesh_without_volume_has_volume_zero() -> None:
    # Found by test_triangle_soups_load_or_raise_a_crashsim_error: two triangles back to back
    # are closed and consistently wound; trimesh's mass properties divided by their zero
    # volume (RuntimeWarning).
    soup = trimesh.Trimesh(
        [[0.0, 0.0, 0.0], [2.67, 0.0, 0.0], [0.0, 2.19, -0.89], [0.0, 0.0, 1.82]],
        [[0, 1, 2], [0, 2, 1]],
        process=False,
    )
    quality = cs.mesh_quality(soup)
    assert quality.watertight and quality.winding_consistent and quality.volume == 0.0
    assert not quality.is_volume
    check_mesh_source(soup)


@pytest.mark.parametrize(
    "obj, count",
    [
        (b"v -2\n25000000 -0.9 -0.7\nv -2.25 -0.9 0.7\nv -2.25 0.9 -0.7\nf 1 2 3\n", 1),
        (b"v -2.25 -0\nv -2.25 -0.9\nv -2.25 0.9\nf 1 2 3\n", 2),
    ],
)
def test_obj_vertices_without_three_coordinates_are_a_mesh_error(
    obj: bytes, count: int, tmp_path: Path
) -> None:
    # Found by test_damaged_mesh_files_load_or_raise_a_crashsim_error: a line break inside
    # an OBJ 'v' line left vertices of 1 or 2 coordinates; trimesh's vertex merging then
    # raised OverflowError (1) and the quality report a NumPy DeprecationWarning (2).
    path = tmp_path / "car.obj"
    path.write_bytes(obj)
    with pytest.raises(cs.MeshError, match=f"vertices of {count} coordinates"):
        cs.load_mesh(path)
