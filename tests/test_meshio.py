"""Mesh loading (formats, units, axes, ground and centre) and the quality report: every count
checked on small hand-built meshes whose answers are known by construction, and on the shared
real meshes against their README and an independent edge count."""

from __future__ import annotations

import itertools
import os
from collections import Counter
from pathlib import Path

import crashsim as cs
import numpy as np
import pytest
import trimesh
from conftest import mesh_mass
from crashsim.vehicles import meshio

# From ../shared/meshes/README.md: watertight as a whole, shells, closed shells.
README_SHELLS = {
    "sedan_quaternius_normalcar1": (True, 7, 7),
    "suv_quaternius_suv": (False, 9, 8),
    "hatchback_gazebo": (False, 7, 7),
    "pickup_gazebo": (False, 9, 9),
    "van_gazebo_ambulance": (False, 18, 14),
    "bus_gazebo": (False, 10, 7),
}

# A tetrahedron with outward faces; volume 1/6.
TET_V = np.array([[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]])
TET_F = np.array([[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]])


def raw(vertices, faces) -> trimesh.Trimesh:
    """A mesh exactly as given (no merging, no removal of anything)."""
    return trimesh.Trimesh(np.asarray(vertices, float), np.asarray(faces), process=False)


def quality(vertices, faces) -> meshio.MeshQuality:
    return meshio.mesh_quality(raw(vertices, faces))


# -- the quality report on hand-built meshes -------------------------------------------------


def test_a_closed_tetrahedron() -> None:
    q = quality(TET_V, TET_F)
    assert (q.triangles, q.vertices, q.edges) == (4, 4, 6)
    assert (q.shells, q.closed_shells, q.closed_shells_filled) == (1, 1, 1)
    assert q.watertight and q.winding_consistent and q.is_volume
    assert (q.open_edges, q.nonmanifold_edges, q.degenerate_faces, q.duplicate_faces) == (
        0,
        0,
        0,
        0,
    )
    assert q.volume == pytest.approx(1.0 / 6.0, rel=1e-14)
    assert q.extents == (1.0, 1.0, 1.0)


def test_a_box_without_one_triangle_has_a_three_edge_hole() -> None:
    box = trimesh.creation.box()
    q = quality(box.vertices, box.faces[1:])
    assert (q.triangles, q.edges, q.open_edges, q.nonmanifold_edges) == (11, 18, 3, 0)
    assert not q.watertight and q.volume is None and not q.is_volume
    # the hole is a triangle: open as it is, closed once trimesh fills 3- and 4-edge holes
    assert (q.shells, q.closed_shells, q.closed_shells_filled) == (1, 0, 1)
    assert q.winding_consistent
    # a lone open tetrahedron is not filled: trimesh repairs shells of 4 faces or more
    tet = quality(TET_V, TET_F[:3])
    assert (tet.open_edges, tet.closed_shells, tet.closed_shells_filled) == (3, 0, 0)


def test_a_box_without_its_top_has_a_hole_too_big_to_fill() -> None:
    box = trimesh.creation.box()
    top = np.flatnonzero(box.face_normals[:, 2] > 0.5)
    assert len(top) == 2
    open_box = raw(box.vertices, np.delete(box.faces, top, axis=0))
    q = meshio.mesh_quality(open_box)
    assert (q.triangles, q.open_edges, q.shells, q.closed_shells) == (10, 4, 1, 0)
    assert q.closed_shells_filled == 1  # a quad hole is filled by trimesh's repair
    assert "shells: 1, closed 0, 1 after filling 3- and 4-edge holes" in str(q)


def test_three_pages_on_one_edge_are_three_open_shells_and_one_non_manifold_edge() -> None:
    v = [[0, 0, 0], [0, 0, 1], [1, 0, 0], [0, 1, 0], [-1, -1, 0]]
    f = [[0, 1, 2], [0, 1, 3], [0, 1, 4]]
    q = quality(v, f)
    assert (q.edges, q.nonmanifold_edges, q.open_edges) == (7, 1, 6)
    # a non-manifold edge does not join faces: each page is its own shell
    assert (q.shells, q.closed_shells, q.closed_shells_filled) == (3, 0, 0)
    assert not q.watertight


def test_two_closed_tetrahedra_sharing_an_edge() -> None:
    # the second is the first mirrored through x = y (rewound to point out); they share
    # the edge (0, 3) on the z axis
    mirror = TET_V[:, [1, 0, 2]] * [-1.0, -1.0, 1.0]
    v = np.vstack([TET_V, mirror[[1, 2]]])  # vertices 0 and 3 are shared
    index = {0: 0, 1: 4, 2: 5, 3: 3}
    second = [[index[a] for a in face[::-1]] for face in TET_F]
    q = quality(v, np.vstack([TET_F, second]))
    assert (q.triangles, q.vertices, q.edges) == (8, 6, 11)
    assert (q.nonmanifold_edges, q.open_edges) == (1, 0)
    assert (q.shells, q.closed_shells) == (2, 2) and not q.watertight
    assert q.volume is None  # not watertight as a whole, though each shell is closed
    shells = meshio.closed_shells(raw(v, np.vstack([TET_F, second])))
    assert [s.volume for s in shells] == pytest.approx([1 / 6, 1 / 6], rel=1e-14)


def test_degenerate_and_duplicate_faces() -> None:
    line = [[2.0, 0.0, 0.0], [3.0, 0.0, 0.0], [4.0, 0.0, 0.0], [5.0, 0.0, 0.0], [6.0, 1.0, 0.0]]
    v = np.vstack([TET_V, line])
    f = np.vstack(
        [
            TET_F,
            [[4, 5, 6]],  # three collinear vertices: zero area
            [[7, 7, 8]],  # a repeated vertex: zero area
            [[1, 3, 2]],  # TET_F[3] again, wound the other way: a duplicate
            [[2, 3, 1]],  # TET_F[3] again, same winding (rotated): a duplicate
        ]
    )
    q = quality(v, f)
    assert q.degenerate_faces == 2
    assert q.duplicate_faces == 2
    # the tetrahedron's face 3 is now four faces on each of its three edges
    assert q.nonmanifold_edges == 3


def test_a_face_thinner_than_round_off_is_degenerate_and_a_thin_one_is_not() -> None:
    v = [[0, 0, 0], [1, 0, 0], [0.5, 1e-12, 0], [0, 0, 1], [1, 0, 1], [0.5, 1e-4, 1]]
    q = quality(v, [[0, 1, 2], [3, 4, 5]])
    assert q.degenerate_faces == 1  # height 1e-12 of a unit edge; 1e-4 is a real sliver


def test_one_flipped_face_breaks_the_winding_and_an_inverted_box_has_negative_volume() -> None:
    flipped = TET_F.copy()
    flipped[2] = flipped[2, ::-1]
    q = quality(TET_V, flipped)
    assert q.watertight and not q.winding_consistent and q.volume is None
    box = trimesh.creation.box(extents=(2.0, 3.0, 4.0))
    inverted = quality(box.vertices, box.faces[:, ::-1])
    assert inverted.watertight and inverted.winding_consistent
    assert inverted.volume == pytest.approx(-24.0, rel=1e-14) and not inverted.is_volume


def test_quality_of_trimesh_primitives_agrees_with_trimesh() -> None:
    torus = trimesh.creation.torus(major_radius=1.0, minor_radius=0.3)
    cases = ((trimesh.creation.icosphere(3), 2), (trimesh.creation.box(), 2), (torus, 0))
    for mesh, euler in cases:
        q = meshio.mesh_quality(mesh)
        assert q.watertight == mesh.is_watertight is True
        assert q.volume == pytest.approx(mesh.volume, rel=1e-12)
        assert q.shells == len(mesh.split(only_watertight=False)) == 1
        assert q.edges == len(mesh.edges_unique)
        # Euler characteristic: V - E + F = 2 for a sphere, 0 for a torus
        assert q.vertices - q.edges + q.triangles == euler


def test_the_report_prints_as_a_short_block() -> None:
    text = str(quality(TET_V, TET_F))
    assert text.splitlines() == [
        "4 triangles, 4 vertices, 1.000 x 1.000 x 1.000 m",
        "  shells: 1, closed 1",
        "  watertight: yes  (open edges 0, non-manifold edges 0)",
        "  winding consistent: yes  (degenerate faces 0, duplicate faces 0)",
        "  volume: 0.1667 m^3",
    ]


# -- the shared real meshes -------------------------------------------------------------------


def independent_counts(mesh: trimesh.Trimesh) -> tuple[int, int, int]:
    """(open edges, non-manifold edges, closed shells) by plain Python counting."""
    faces = [tuple(int(i) for i in f) for f in mesh.faces]

    def sides(f: tuple[int, ...]) -> list[frozenset]:
        return [frozenset((f[0], f[1])), frozenset((f[1], f[2])), frozenset((f[2], f[0]))]

    edges = Counter(e for f in faces for e in sides(f))
    # shells: union-find over faces sharing an edge that belongs to exactly two faces
    parent = list(range(len(faces)))

    def root(i: int) -> int:
        while parent[i] != i:
            parent[i] = parent[parent[i]]
            i = parent[i]
        return i

    owners: dict[frozenset, list[int]] = {}
    for k, f in enumerate(faces):
        for e in sides(f):
            owners.setdefault(e, []).append(k)
    for pair in owners.values():
        if len(pair) == 2:
            parent[root(pair[0])] = root(pair[1])
    shells: dict[int, list[int]] = {}
    for k in range(len(faces)):
        shells.setdefault(root(k), []).append(k)
    closed = 0
    for members in shells.values():
        local = Counter(e for k in members for e in sides(faces[k]))
        closed += all(c == 2 for c in local.values())
    opened = sum(c == 1 for c in edges.values())
    return opened, sum(c > 2 for c in edges.values()), closed


def test_shared_mesh_quality_matches_the_readme(mesh_path: Path) -> None:
    watertight, shells, closed = README_SHELLS[mesh_path.stem]
    mesh = meshio.load_mesh(mesh_path)
    q = meshio.mesh_quality(mesh)
    assert q.watertight is watertight
    assert q.shells == shells
    # the README counts shells closed after trimesh's fill of 3- and 4-edge holes
    assert q.closed_shells_filled == closed
    assert (q.open_edges, q.nonmanifold_edges, q.closed_shells) == independent_counts(mesh)
    assert q.closed_shells <= q.closed_shells_filled <= q.shells
    assert q.winding_consistent  # all six are consistently wound
    assert (q.volume is not None) is watertight
    v = cs.Vehicle.from_mesh(mesh_path, mass=mesh_mass(mesh_path))
    assert v.quality == q


# -- units and axes -----------------------------------------------------------------------------


def test_every_pair_of_different_axes_is_a_proper_rotation() -> None:
    names = ["x", "y", "z", "-x", "-y", "-z", "+x"]
    proper = 0
    for up, forward in itertools.product(names, names):
        if up.lstrip("+-") == forward.lstrip("+-"):
            with pytest.raises(cs.ParameterError, match="same axis"):
                meshio.axes_rotation(up, forward)
            continue
        r = meshio.axes_rotation(up, forward)
        assert np.array_equal(r @ r.T, np.eye(3))
        assert np.linalg.det(r) == pytest.approx(1.0, abs=0)
        # the file's up axis becomes +z, its forward axis +x
        assert np.array_equal(r @ meshio._axis(up, "up"), [0, 0, 1])
        assert np.array_equal(r @ meshio._axis(forward, "forward"), [1, 0, 0])
        proper += 1
    assert proper == 32  # the 24 rotations, and 8 of them spelled again with "+x"
    assert np.array_equal(meshio.axes_rotation(), np.eye(3))


@pytest.mark.parametrize("up, forward", [("q", "x"), ("z", "xx"), ("--z", "x"), (1, "x")])
def test_bad_axis_names_are_parameter_errors(up, forward) -> None:
    with pytest.raises(cs.ParameterError, match="axis"):
        meshio.axes_rotation(up, forward)


def test_unit_names_and_numbers() -> None:
    assert [meshio.unit_scale(u) for u in ("m", "cm", "mm", "in", "ft")] == [
        1.0,
        0.01,
        0.001,
        0.0254,
        0.3048,
    ]
    assert meshio.unit_scale(0.5) == 0.5 and meshio.unit_scale(" MM ") == 0.001
    for bad in ("furlong", 0.0, -1.0, float("nan"), True, None):
        with pytest.raises(cs.ParameterError, match="units"):
            meshio.unit_scale(bad)


def test_a_box_in_mm_with_y_up_and_minus_z_forward_loads_in_metres(tmp_path: Path) -> None:
    # The box in the model frame (m): 4 long (x), 2 wide (y), 1.5 high (z), off-centre so
    # that every axis and sign shows. A tag vertex marks the front-left-top corner.
    model = trimesh.creation.box(extents=(4.0, 2.0, 1.5))
    model.apply_translation([0.3, -0.2, 0.75])
    # The same box as a y-up, -z-forward file in mm: file x = -model y (file x points to
    # the right), file y = model z (up), file z = -model x (the front is -z).
    m = np.asarray(model.vertices)
    file_vertices = 1000.0 * np.column_stack([-m[:, 1], m[:, 2], -m[:, 0]])
    path = tmp_path / "box_mm.ply"
    raw(file_vertices, model.faces).export(path)
    loaded = meshio.load_mesh(path, units="mm", up="y", forward="-z")
    assert np.allclose(loaded.vertices, m, rtol=0, atol=1e-12)
    assert np.array_equal(loaded.faces, model.faces)
    assert loaded.volume == pytest.approx(12.0, rel=1e-12)  # still outward: a rotation
    v = cs.Vehicle.from_mesh(path, mass=1000.0, units="mm", up="y", forward="-z")
    assert np.allclose(v.extents, [4.0, 2.0, 1.5], atol=1e-12)
    assert np.allclose(v.cg, [0.3, -0.2, 0.75], atol=1e-12)
    # ground and centre: lowest point to z = 0, box centred in x and y
    placed = meshio.load_mesh(path, units=0.001, up="y", forward="-z", ground=True, center=True)
    assert np.allclose(placed.bounds, [[-2.0, -1.0, 0.0], [2.0, 1.0, 1.5]], atol=1e-12)


def test_inches_and_feet_and_a_rotation_about_z(tmp_path: Path) -> None:
    mesh = raw(TET_V * 10.0, TET_F)  # 10 in
    path = tmp_path / "tet.stl"
    mesh.export(path)
    loaded = meshio.load_mesh(path, units="in", forward="y")  # the file's +y is the front
    # model x = file y, model y = z x x = file -x
    expected = np.column_stack([TET_V[:, 1], -TET_V[:, 0], TET_V[:, 2]]) * 0.254
    assert sorted(map(tuple, np.round(loaded.vertices, 9))) == sorted(
        map(tuple, np.round(expected, 9))
    )
    assert meshio.load_mesh(path, units="ft").extents == pytest.approx([3.048] * 3, rel=1e-7)


def test_ground_and_center_default_to_off_and_leave_the_input_alone() -> None:
    mesh = raw(TET_V + [5.0, 6.0, 7.0], TET_F)
    kept = meshio.load_mesh(mesh)
    assert np.array_equal(kept.vertices, mesh.vertices)
    moved = meshio.load_mesh(mesh, ground=True, center=True)
    assert np.allclose(moved.bounds, [[-0.5, -0.5, 0.0], [0.5, 0.5, 1.0]], atol=1e-15)
    assert np.array_equal(mesh.vertices, TET_V + [5.0, 6.0, 7.0])  # the input is unchanged


# -- formats: round trips -----------------------------------------------------------------------


def canonical(vertices: np.ndarray, faces: np.ndarray) -> np.ndarray:
    """The triangles as (n, 9) coordinate rows, each started at its smallest corner (winding
    kept), rows sorted: equal for equal geometry whatever the vertex and face order."""
    tris = np.asarray(vertices)[np.asarray(faces)]
    key = np.round(tris, 4)
    start = np.array([min(range(3), key=lambda i, t=t: tuple(t[i])) for t in key])
    rolled = np.stack([np.roll(t, -s, axis=0) for t, s in zip(tris, start, strict=True)])
    flat = rolled.reshape(len(rolled), 9)
    order = np.lexsort(np.round(flat, 4).T[::-1])
    return flat[order]


def a_lumpy_mesh() -> trimesh.Trimesh:
    """A closed, asymmetric mesh with distinct vertices (any axis mix-up shows)."""
    mesh = trimesh.creation.icosphere(subdivisions=2)
    mesh.apply_scale([2.1, 0.9, 0.7])
    mesh.apply_translation([0.4, -0.3, 0.8])
    mesh.vertices[0] += [0.3, 0.1, 0.2]
    return mesh


@pytest.mark.parametrize("suffix", ["obj", "stl", "ply", "off", "glb"])
def test_round_trip_through_every_format(tmp_path: Path, suffix: str) -> None:
    mesh = a_lumpy_mesh()
    path = tmp_path / f"lumpy.{suffix}"
    mesh.export(path)
    loaded = meshio.load_mesh(path)
    assert len(loaded.faces) == len(mesh.faces) == 320
    assert len(loaded.vertices) == len(mesh.vertices)  # STL's soup and OBJ's seams merged
    # STL, PLY and GLB store float32, OBJ writes 8 decimals: 1e-6 m of a 4 m long mesh
    got = canonical(loaded.vertices, loaded.faces)
    assert np.allclose(got, canonical(mesh.vertices, mesh.faces), atol=1e-6, rtol=0)
    assert meshio.mesh_quality(loaded).watertight
    assert loaded.volume == pytest.approx(mesh.volume, rel=1e-5)


def test_a_glb_scene_is_flattened_with_its_node_transforms(tmp_path: Path) -> None:
    part = a_lumpy_mesh()
    turn = trimesh.transformations.rotation_matrix(np.pi / 2, [0, 0, 1])  # +90 deg about z
    turn[:3, 3] = [10.0, 0.0, 0.0]
    scene = trimesh.Scene()
    scene.add_geometry(part, node_name="a")
    scene.add_geometry(part, node_name="b", transform=turn)
    path = tmp_path / "scene.glb"
    scene.export(path)
    loaded = meshio.load_mesh(path)
    moved = np.asarray(part.vertices) @ turn[:3, :3].T + turn[:3, 3]
    expected_v = np.vstack([part.vertices, moved])
    expected_f = np.vstack([part.faces, part.faces + len(part.vertices)])
    assert len(loaded.faces) == 640
    got = canonical(loaded.vertices, loaded.faces)
    assert np.allclose(got, canonical(expected_v, expected_f), atol=1e-5, rtol=0)
    q = meshio.mesh_quality(loaded)
    assert (q.shells, q.closed_shells, q.watertight) == (2, 2, True)


def test_obj_texture_seams_are_merged(tmp_path: Path) -> None:
    # an OBJ with texture coordinates splits corners at seams; load_mesh joins them
    path = tmp_path / "box_uv.obj"
    path.write_text(
        "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0 0 1\nv 1 0 1\nv 1 1 1\nv 0 1 1\n"
        "vt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\n"
        "f 1/1 4/2 3/3\nf 1/1 3/3 2/4\nf 5/1 6/2 7/3\nf 5/1 7/3 8/4\n"
        "f 1/1 2/2 6/3\nf 1/1 6/3 5/4\nf 2/1 3/2 7/3\nf 2/1 7/3 6/4\n"
        "f 3/1 4/2 8/3\nf 3/1 8/3 7/4\nf 4/1 1/2 5/3\nf 4/1 5/3 8/4\n"
    )
    loaded = meshio.load_mesh(path)
    q = meshio.mesh_quality(loaded)
    assert (q.vertices, q.triangles, q.watertight) == (8, 12, True)
    assert q.volume == pytest.approx(1.0, rel=1e-14)


# -- broken input -------------------------------------------------------------------------------


def test_broken_input_is_a_clear_mesh_error(tmp_path: Path) -> None:
    with pytest.raises(cs.MeshError, match="no triangles"):
        meshio.load_mesh(raw(np.zeros((3, 3)), np.zeros((0, 3), dtype=np.int64)))
    nan = raw(TET_V, TET_F)
    nan.vertices[2] = [0.0, np.inf, 0.0]
    with pytest.raises(cs.MeshError, match=r"non-finite.*vertex 2"):
        meshio.load_mesh(nan)
    path = tmp_path / "nan.obj"
    path.write_text("v 0 0 0\nv 1 0 0\nv nan 1 0\nf 1 2 3\n")
    with pytest.raises(cs.MeshError, match=r"nan.obj.*non-finite"):
        meshio.load_mesh(path)
    points = tmp_path / "points.obj"
    points.write_text("v 0 0 0\nv 1 0 0\nv 0 1 0\n")
    with pytest.raises(cs.MeshError, match=r"points.obj.*no triangles"):
        meshio.load_mesh(points)
    with pytest.raises(cs.MeshError, match="no triangles"):
        meshio.mesh_quality(raw(np.zeros((3, 3)), np.zeros((0, 3), dtype=np.int64)))
    with pytest.raises(cs.ParameterError, match="same axis"):
        meshio.load_mesh(raw(TET_V, TET_F), up="x", forward="-x")


def test_a_path_that_is_no_file_says_what_it_is(tmp_path: Path) -> None:
    # issue 24: a folder, a named pipe and a link to /dev/zero all said "no mesh file at"
    folder = tmp_path / "car.ply"
    folder.mkdir()
    fifo = tmp_path / "pipe.ply"
    os.mkfifo(fifo)  # never opened: reading it would wait for a writer
    zero = tmp_path / "zero.ply"
    zero.symlink_to("/dev/zero")
    cases = [
        (folder, "is a folder, not a file"),
        (fifo, r"is a named pipe \(FIFO\), not a file"),
        (zero, r"is a character device \(a link to /dev/zero\), not a file"),
        (tmp_path / "missing.ply", "no mesh file at"),
    ]
    for path, why in cases:
        with pytest.raises(cs.MeshError, match=why):
            meshio.load_mesh(path)
        with pytest.raises(cs.MeshError, match=why):
            cs.Vehicle.from_mesh(path, mass=1500.0)


def test_a_file_not_of_its_format_is_refused_from_its_first_bytes(tmp_path: Path, monkeypatch):
    # issue 24: a 1 GB all-zero .ply took 24 s and 8.5 GB before trimesh said "Not a ply
    # file!". A sparse file costs no disk; trimesh's loader must not be reached at all.
    def never(*args: object, **kwargs: object) -> None:
        raise AssertionError("trimesh was asked to read a file the header check refuses")

    monkeypatch.setattr(meshio.trimesh, "load_scene", never)
    cases = {
        "ply": r'not a \.ply file: it does not start with the line "ply"',
        "stl": r"not a \.stl file: it is neither ASCII.*nor binary.*84 bytes for the 0 triangles",
        "obj": r"not a \.obj file: it holds NUL bytes",
        "off": r'not a \.off file: it does not start with "OFF"',
        "glb": r'not a \.glb file: it does not start with "glTF"',
    }
    for suffix, why in cases.items():
        path = tmp_path / f"zeros.{suffix}"
        with open(path, "wb") as f:
            f.truncate(1 << 30)  # 1 GiB of zeros, sparse
        with pytest.raises(cs.MeshError, match=why):
            meshio.load_mesh(path)
        path.unlink()
    headers = {
        "format.ply": (b"ply\nformat utf8 1.0\nend_header\n", "second line is not"),
        "endless.ply": (b"ply\r\nformat ascii 1.0\r\n" + b"comment x\n" * 200_000,
                        "does not end"),
        "short.stl": (b"\0" * 80 + (3).to_bytes(4, "little") + b"\0" * 50,
                      "234 bytes for the 3 triangles"),
    }
    for name, (text, why) in headers.items():
        (tmp_path / name).write_bytes(text)
        with pytest.raises(cs.MeshError, match=why):
            meshio.load_mesh(tmp_path / name)


@pytest.mark.parametrize("suffix", ["obj", "stl", "ply", "off", "glb"])
def test_the_header_check_takes_what_trimesh_writes(tmp_path: Path, suffix: str) -> None:
    mesh = a_lumpy_mesh()
    encodings = {"ply": ["ascii", "binary"], "stl": ["ascii", "binary"]}.get(suffix, [None])
    for encoding in encodings:
        path = tmp_path / f"lumpy-{encoding}.{suffix}"
        if suffix == "stl" and encoding == "ascii":
            path.write_text(trimesh.exchange.stl.export_stl_ascii(mesh))
        elif suffix == "ply":
            path.write_bytes(trimesh.exchange.ply.export_ply(mesh, encoding=encoding))
        else:
            mesh.export(path)
        meshio._check_header(path, str(path))  # no error
        assert len(meshio.load_mesh(path).faces) == 320
