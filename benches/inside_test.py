"""Which inside test suits real, messy vehicle meshes? A measurement on the shared meshes.

The engine decides "inside" (vertices of one mesh inside the other, a mesh wholly inside
another) by the generalized winding number > 1/2 (crates/crashsim-core/src/shape.rs). This
script compares it with the alternatives on the six shared meshes (../shared/meshes):

- winding number: ``crashsim._core.Shape(v, f).winding_numbers(p) > 0.5`` (the engine's,
  with its far-field dipole approximation);
- winding number exact: the same sum over every triangle in numpy (slow; the reference for
  the engine's approximation);
- ray parity: trimesh's ``Trimesh.contains`` (a ray each way, parity of the crossings; a
  random retry direction where they disagree, seeded here; the "unstable" column is the
  fraction of grid points whose answer changes with another seed);
- closed shells: inside any closed shell (each edge in exactly two of the shell's faces);
  open shells ignored. Decided by the winding number of the closed shells alone, which is
  exactly 0 or 1 there, so any sound test gives the same answer;
- closed shells filled: the same after trimesh fills holes of 3 and 4 edges in each shell;
- convex hull: inside the convex hull of all vertices.

Point sets, per mesh (seeded, deterministic):

- grid: a regular grid over the mesh's bounding box; no truth, used for agreement with the
  winding number and for the timing (time per 10k queries, after the one-off build);
- in, near closed shells: points EPS inside a closed shell, along the inward normal of a
  random point of its surface, kept when that shell's own winding number is 1 there (the
  shell is thicker than EPS): inside by construction;
- in, near open shells: the same from faces of open shells, kept when the nearest surface
  point of the whole mesh is the sample itself (no other surface within EPS): inside by the
  mesh's own orientation (its faces point outwards);
- out, near surface: points EPS outside any face along its outward normal, kept when the
  nearest surface point is the sample and the point is outside every closed shell;
- cabin: a small block of points deep inside the body (chosen per mesh from the slices);
- gaps: blocks of points that are outside the vehicle but inside its box: under the floor
  between the axles and, for the pickup, in the load bed (chosen per mesh from the slices).

Prints a table per mesh and method: the fraction of each labelled set classified as
expected, the fraction of grid points on which the method disagrees with the winding number,
and the time per 10k queries; then the machine. Writes docs/img/inside_<mesh>.png: one
horizontal and one vertical slice per method.

    python3 benches/inside_test.py            # about 12 min; --only NAME, --no-images
    python3 benches/inside_test.py --mass-properties   # the solids' mass properties
"""

from __future__ import annotations

import argparse
import time
from collections.abc import Callable
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
import trimesh  # noqa: E402
from crashsim import _core, meshio  # noqa: E402
from machine import describe  # noqa: E402 - benches/machine.py (this folder is on sys.path)
from scipy.spatial import ConvexHull  # noqa: E402

REPO = Path(__file__).resolve().parents[1]
MESHES = REPO.parent / "shared" / "meshes"
EPS = 0.005  # m, offset of the near-surface points
SAMPLES = 3000  # surface samples per mesh and set
GRID = 40_000  # grid points per mesh
SEED = 20261123

# Hand-picked blocks (model frame, m): (centre, half size). Checked on the slice images.
CABIN = {
    "sedan_quaternius_normalcar1": ((0.0, 0.0, 0.75), (0.6, 0.4, 0.15)),
    "suv_quaternius_suv": ((0.0, 0.0, 0.95), (0.6, 0.45, 0.2)),
    "hatchback_gazebo": ((0.0, 0.0, 0.95), (0.6, 0.45, 0.2)),
    "pickup_gazebo": ((0.9, 0.0, 1.2), (0.4, 0.5, 0.2)),
    "van_gazebo_ambulance": ((0.0, 0.0, 1.6), (1.5, 0.8, 0.4)),
    "bus_gazebo": ((0.0, 0.0, 2.0), (3.0, 0.8, 0.6)),
}
GAPS: dict[str, list[tuple[tuple[float, float, float], tuple[float, float, float]]]] = {
    "sedan_quaternius_normalcar1": [((0.0, 0.0, 0.06), (0.6, 0.4, 0.03))],
    "suv_quaternius_suv": [((0.0, 0.0, 0.1), (0.6, 0.4, 0.05))],
    "hatchback_gazebo": [((0.0, 0.0, 0.1), (0.6, 0.4, 0.05))],
    "pickup_gazebo": [((0.0, 0.0, 0.15), (0.8, 0.5, 0.08)), ((-1.8, 0.0, 1.3), (0.6, 0.6, 0.2))],
    "van_gazebo_ambulance": [((0.0, 0.0, 0.15), (1.0, 0.6, 0.08))],
    "bus_gazebo": [((0.0, 0.0, 0.15), (3.0, 0.6, 0.08))],
}

Classifier = Callable[[np.ndarray], np.ndarray]


# -- the methods --------------------------------------------------------------------------------


def winding(mesh: trimesh.Trimesh) -> Classifier:
    shape = _core.Shape(np.asarray(mesh.vertices), np.asarray(mesh.faces))
    return lambda p: shape.winding_numbers(p) > 0.5


def exact_winding(mesh: trimesh.Trimesh) -> Classifier:
    """The generalized winding number summed exactly over every triangle (numpy; the
    Van Oosterom-Strackee solid angle), no far-field approximation."""
    tri = np.asarray(mesh.triangles)

    def inside(points: np.ndarray) -> np.ndarray:
        out = np.empty(len(points))
        for i, x in enumerate(points):
            a, b, c = tri[:, 0] - x, tri[:, 1] - x, tri[:, 2] - x
            la, lb, lc = (np.sqrt(np.einsum("ij,ij->i", v, v)) for v in (a, b, c))
            det = np.einsum("ij,ij->i", a, np.cross(b, c))
            den = (
                la * lb * lc
                + np.einsum("ij,ij->i", a, b) * lc
                + np.einsum("ij,ij->i", b, c) * la
                + np.einsum("ij,ij->i", c, a) * lb
            )
            out[i] = np.sum(np.arctan2(det, den)) / (2.0 * np.pi)
        return out > 0.5

    return inside


def ray_parity(mesh: trimesh.Trimesh, seed: int = 1) -> Classifier:
    """trimesh's contains. Where the two opposite rays disagree it retries with a random
    direction from trimesh's shared, OS-seeded generator: the answer then depends on the run.
    Here the generator is seeded per call so the table is reproducible."""
    m = mesh.copy()
    _ = m.triangles_tree  # build the r-tree now (part of the build time)
    original = trimesh.util.random_generator

    def inside(points: np.ndarray) -> np.ndarray:
        trimesh.util.random_generator = lambda *_: np.random.default_rng(seed)
        try:
            return np.asarray(m.contains(points), dtype=bool)
        finally:
            trimesh.util.random_generator = original

    return inside


def union_of(shells: list[trimesh.Trimesh]) -> Classifier:
    if not shells:
        return lambda p: np.zeros(len(p), dtype=bool)
    return winding(trimesh.util.concatenate(shells))


def closed_shells(mesh: trimesh.Trimesh) -> Classifier:
    return union_of(meshio.closed_shells(mesh))


def closed_shells_filled(mesh: trimesh.Trimesh) -> Classifier:
    shells = [s for s in mesh.split(only_watertight=False, repair=True) if s.is_watertight]
    with np.errstate(invalid="ignore", divide="ignore"):  # zero-volume shells
        for s in shells:
            if s.volume < 0:
                s.invert()
    return union_of(shells)


def convex_hull(mesh: trimesh.Trimesh) -> Classifier:
    eq = ConvexHull(np.asarray(mesh.vertices)).equations  # a.x + b <= 0 inside
    return lambda p: np.all(p @ eq[:, :3].T + eq[:, 3] <= 0.0, axis=1)


METHODS: dict[str, Callable[[trimesh.Trimesh], Classifier]] = {
    "winding number": winding,
    "winding number exact": exact_winding,
    "ray parity": ray_parity,
    "closed shells": closed_shells,
    "closed shells filled": closed_shells_filled,
    "convex hull": convex_hull,
}


# -- the point sets -----------------------------------------------------------------------------


def grid_points(mesh: trimesh.Trimesh, count: int) -> np.ndarray:
    lo, hi = mesh.bounds
    ext = hi - lo
    side = (np.prod(ext) / count) ** (1 / 3)
    n = np.maximum(1, np.round(ext / side)).astype(int)
    # cell centres, shifted off the symmetry plane y = 0 where many vertices lie
    axes = [lo[i] + (np.arange(n[i]) + 0.5) * ext[i] / n[i] for i in range(3)]
    return np.stack(np.meshgrid(*axes, indexing="ij"), -1).reshape(-1, 3)


def surface_samples(mesh: trimesh.Trimesh, faces: np.ndarray, rng: np.random.Generator):
    """(points on the given faces, their unit normals), area-weighted."""
    area = mesh.area_faces[faces]
    pick = faces[rng.choice(len(faces), size=SAMPLES, p=area / area.sum())]
    r = rng.random((SAMPLES, 2))
    flip = r.sum(axis=1) > 1.0
    r[flip] = 1.0 - r[flip]
    tri = mesh.triangles[pick]
    points = tri[:, 0] + r[:, :1] * (tri[:, 1] - tri[:, 0]) + r[:, 1:] * (tri[:, 2] - tri[:, 0])
    return points, mesh.face_normals[pick], pick


def nearest_is_own(mesh: trimesh.Trimesh, probe: np.ndarray, surface: np.ndarray) -> np.ndarray:
    """True where the mesh's nearest surface point to each probe is its sample (no other
    surface closer than EPS)."""
    _, dist, _ = trimesh.proximity.closest_point(mesh, probe)
    return np.abs(dist - np.linalg.norm(probe - surface, axis=1)) < 1e-9 * EPS + 1e-12


def escapes(mesh: trimesh.Trimesh, points: np.ndarray, normals: np.ndarray) -> np.ndarray:
    """True where a straight ray from the point, along its normal or one of the six axis
    directions, leaves without meeting the mesh: the point is seen from outside."""
    dirs = [normals] + [np.tile(d, (len(points), 1)) for d in np.vstack([np.eye(3), -np.eye(3)])]
    out = np.zeros(len(points), dtype=bool)
    for d in dirs:
        todo = np.flatnonzero(~out)
        if len(todo) == 0:
            break
        hit = mesh.ray.intersects_any(points[todo], d[todo])
        out[todo[~hit]] = True
    return out


def blocks(spec) -> np.ndarray:
    pts = []
    for centre, half in spec:
        axes = [np.linspace(c - h, c + h, 6) for c, h in zip(centre, half, strict=True)]
        pts.append(np.stack(np.meshgrid(*axes, indexing="ij"), -1).reshape(-1, 3))
    return np.vstack(pts)


def labelled_sets(
    mesh: trimesh.Trimesh, name: str, seed: int
) -> dict[str, tuple[np.ndarray, bool]]:
    rng = np.random.default_rng(seed)
    labels = meshio.shell_labels(mesh)
    faces = np.asarray(mesh.faces)
    closed_ids = [k for k in range(labels.max() + 1) if meshio._closed(faces[labels == k])]
    in_closed = np.isin(labels, closed_ids)
    nonzero = mesh.area_faces > 0
    shells_closed = union_of(meshio.closed_shells(mesh))
    sets: dict[str, tuple[np.ndarray, bool]] = {}
    # inside closed shells: verified by the shell's own (exact) winding number
    idx = np.flatnonzero(in_closed & nonzero)
    if len(idx):
        p, n, pick = surface_samples(mesh, idx, rng)
        q = p - EPS * n
        keep = np.zeros(len(q), dtype=bool)
        for k in np.unique(labels[pick]):
            sel = labels[pick] == k
            shell = mesh.submesh([np.flatnonzero(labels == k)], append=True, repair=False)
            w = _core.Shape(np.asarray(shell.vertices), np.asarray(shell.faces)).winding_numbers(
                q[sel]
            )
            # exactly 0 or 1 off a closed outward shell; the engine's fast approximation is
            # within 0.02 of it there (measured), far from 1/2
            keep[sel] = np.abs(w - 1.0) < 0.25
        sets["in, near closed"] = (q[keep], True)
    idx = np.flatnonzero(~in_closed & nonzero)
    if len(idx):
        p, n, _ = surface_samples(mesh, idx, rng)
        q = p - EPS * n
        sets["in, near open"] = (q[nearest_is_own(mesh, q, p)], True)
    p, n, _ = surface_samples(mesh, np.flatnonzero(nonzero), rng)
    q = p + EPS * n
    keep = nearest_is_own(mesh, q, p) & ~shells_closed(q)
    keep[keep] = escapes(mesh, q[keep], n[keep])
    sets["out, near surface"] = (q[keep], False)
    sets["cabin"] = (blocks([CABIN[name]]), True)
    sets["gaps"] = (blocks(GAPS[name]), False)
    return sets


# -- slices ---------------------------------------------------------------------------------------


def slice_points(mesh: trimesh.Trimesh, axis: int, value: float, res: float):
    lo, hi = mesh.bounds
    pad = 0.05 * (hi - lo)
    lo, hi = lo - pad, hi + pad
    a, b = [i for i in range(3) if i != axis]
    u = np.arange(lo[a], hi[a], res) + res / 2
    v = np.arange(lo[b], hi[b], res) + res / 2
    uu, vv = np.meshgrid(u, v)
    pts = np.zeros((uu.size, 3))
    pts[:, a], pts[:, b], pts[:, axis] = uu.ravel(), vv.ravel(), value
    return pts, uu.shape, (u[0] - res / 2, u[-1] + res / 2, v[0] - res / 2, v[-1] + res / 2)


def draw(name: str, mesh: trimesh.Trimesh, classifiers: dict[str, Classifier], out: Path) -> None:
    lo, hi = mesh.bounds
    ext = hi - lo
    res = ext[0] / 240
    z_cut, y_cut = lo[2] + 0.4 * ext[2], 0.3 * ext[1] / 2
    cuts = [
        (2, z_cut, f"horizontal, z = {z_cut:.2f} m"),
        (1, y_cut, f"vertical, y = {y_cut:.2f} m"),
    ]
    n = len(classifiers)
    width = 3.6 * n
    height = width / n * (ext[1] + ext[2]) / ext[0] * 1.25 + 1.0
    fig, axes = plt.subplots(2, n, figsize=(width, height), squeeze=False)
    labelled = [(CABIN[name], "green")] + [(g, "orange") for g in GAPS[name]]
    for row, (axis, value, title) in enumerate(cuts):
        pts, shape, extent = slice_points(mesh, axis, value, res)
        origin = np.zeros(3)
        origin[axis] = value
        segments = trimesh.intersections.mesh_plane(mesh, np.eye(3)[axis], origin)
        a, b = [i for i in range(3) if i != axis]
        for col, (method, inside) in enumerate(classifiers.items()):
            ax = axes[row, col]
            img = inside(pts).reshape(shape)
            ax.imshow(
                img,
                origin="lower",
                extent=extent,
                cmap="Blues",
                vmin=-0.25,
                vmax=1.25,
                interpolation="nearest",
            )
            for seg in segments:
                ax.plot(seg[:, a], seg[:, b], color="red", lw=0.4)
            for (centre, half), colour in labelled:
                ax.add_patch(
                    plt.Rectangle(
                        (centre[a] - half[a], centre[b] - half[b]),
                        2 * half[a],
                        2 * half[b],
                        fill=False,
                        edgecolor=colour,
                        lw=0.8,
                    )
                )
            ax.set_aspect("equal")
            ax.tick_params(labelsize=6)
            if row == 0:
                ax.set_title(method, fontsize=8)
            if col == 0:
                ax.set_ylabel(title, fontsize=7)
    fig.suptitle(
        f"{name}: inside (dark blue) by each method; red: mesh section; green: cabin "
        "block (inside); orange: gap blocks (outside)",
        fontsize=8,
    )
    fig.tight_layout()
    fig.savefig(out, dpi=110)
    plt.close(fig)


# -- main -----------------------------------------------------------------------------------------


SETS = ["in, near closed", "in, near open", "out, near surface", "cabin", "gaps"]


def study(path: Path, seed: int, images: Path | None) -> list[str]:
    """The table rows of one mesh."""
    mesh = meshio.load_mesh(path)
    name = path.stem
    sets = labelled_sets(mesh, name, seed)
    grid = grid_points(mesh, GRID)
    counts = ", ".join(f"{s} {len(sets[s][0])}" for s in SETS if s in sets)
    rows = [f"{name} ({len(grid)} grid points; {counts})"]
    classifiers: dict[str, Classifier] = {}
    reference = None
    for method, build in METHODS.items():
        t0 = time.perf_counter()
        inside = build(mesh)
        t1 = time.perf_counter()
        on_grid = inside(grid)
        t2 = time.perf_counter()
        classifiers[method] = inside
        if reference is None:
            reference = on_grid
        cells = []
        for s in SETS:
            if s not in sets or len(sets[s][0]) == 0:
                cells.append(f"{'-':>8}")
                continue
            pts, expected = sets[s]
            cells.append(f"{100 * np.mean(inside(pts) == expected):>7.1f}%")
        differ = np.mean(on_grid != reference)
        per_10k = (t2 - t1) / len(grid) * 10_000
        unstable = "0"
        if method == "ray parity":  # another retry direction: how many answers change
            unstable = f"{100 * np.mean(ray_parity(mesh, seed=2)(grid) != on_grid):.2f}%"
        rows.append(
            f"  {method:<21}"
            + "".join(f"{c:>{len(h) + 2}}" for c, h in zip(cells, SETS, strict=True))
            + f"{100 * differ:>12.2f}%{t1 - t0:>9.3f}{per_10k:>9.3f}{unstable:>10}"
        )
    if images is not None:
        images.mkdir(parents=True, exist_ok=True)
        draw(name, mesh, classifiers, images / f"inside_{name}.png")
    return rows


def mass_properties_table(paths: list[Path]) -> list[str]:
    """Per mesh and solid: volume, CG and radii of gyration over the length, as
    Vehicle.from_mesh computes them (mass 1500 kg)."""
    import crashsim as cs

    rows = [
        f"{'mesh':<28} {'solid':<21} {'volume m^3':>10} {'CG x, y, z (m)':>22}"
        f" {'kx/L':>6} {'ky/L':>6} {'kz/L':>6} {'time s':>7}"
    ]
    for path in paths:
        for solid in ("convex hull", "closed shells", "winding number"):
            t0 = time.perf_counter()
            try:
                v = cs.Vehicle.from_mesh(path, mass=1500.0, solid=solid)
            except cs.MeshError as e:
                rows.append(f"{path.stem:<28} {solid:<21} MeshError: {e}")
                continue
            dt = time.perf_counter() - t0
            k = np.sqrt(np.diag(v.inertia) / v.mass) / v.extents[0]
            volume = v.summary().split("[")[3].split(" m^3")[0].split()[-1]
            cg = ", ".join(f"{c:6.3f}" for c in v.cg)
            rows.append(
                f"{path.stem:<28} {v.sources['inertia']:<21} {volume:>10} {cg:>22}"
                f" {k[0]:6.3f} {k[1]:6.3f} {k[2]:6.3f} {dt:7.3f}"
            )
    return rows


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--meshes", type=Path, default=MESHES)
    parser.add_argument("--images", type=Path, default=REPO / "docs" / "img")
    parser.add_argument("--no-images", action="store_true")
    parser.add_argument("--only", default="", help="only meshes whose name contains this")
    parser.add_argument(
        "--mass-properties", action="store_true", help="only the table of mass properties"
    )
    args = parser.parse_args()
    paths = [p for p in sorted(args.meshes.glob("*.ply")) if args.only in p.stem]
    if not paths:
        raise SystemExit(f"no meshes in {args.meshes}")
    if args.mass_properties:
        print("\n".join(mass_properties_table(paths)))
        print(f"machine: {describe()}")
        return
    print("Fraction of each labelled set classified as expected; grid points on which the")
    print("method disagrees with the winding number; build time (s); time per 10k queries (s);")
    print("grid points whose answer changes with the random retry direction (ray parity)")
    header = f"  {'method':<21}" + "".join(f"  {s}" for s in SETS)
    print(header + f"{'vs winding':>13}{'build s':>9}{'s/10k':>9}{'unstable':>10}")
    for i, path in enumerate(paths):
        images = None if args.no_images else args.images
        print("\n".join(study(path, SEED + i, images)), flush=True)
    print(f"\nsurface offsets EPS = {EPS} m, {SAMPLES} samples per surface set, seed {SEED}")
    print(f"machine: {describe()}")


if __name__ == "__main__":
    main()
