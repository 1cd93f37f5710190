"""Engine queries exposed to Python: ray hits, solid mass properties, free motion, and the run
progress hook (which must not change the results)."""

from __future__ import annotations

import crashsim as cs
import numpy as np
import pytest
import trimesh
from crashsim import _core


def test_ray_hits_of_a_box() -> None:
    box = cs.Vehicle.box(4.0, 2.0, 1.0, mass=1000.0).shape  # body frame: centred on the CG
    assert box.ray_hits((-5.0, 0.1, 0.2), (2.0, 0.0, 0.0)).tolist() == pytest.approx([3.0, 7.0])
    assert box.ray_hits((-5.0, 0.1, 0.2), (1.0, 0.0, 0.0), 4.0).tolist() == pytest.approx([3.0])
    assert box.ray_hits((-5.0, 3.0, 0.0), (1.0, 0.0, 0.0)).size == 0
    with pytest.raises(cs.ParameterError, match="non-zero"):
        box.ray_hits((0, 0, 0), (0, 0, 0))


def test_solid_properties_agree_with_trimesh() -> None:
    rng = np.random.default_rng(7)
    for mesh in (trimesh.creation.icosphere(3), trimesh.creation.annulus(0.5, 1.0, 0.7)):
        mesh.apply_transform(trimesh.transformations.random_rotation_matrix(rng.random(3)))
        mesh.apply_translation([3.0, -2.0, 1.0])
        p = _core.Shape(mesh.vertices, mesh.faces).solid_properties()
        assert p["volume"] == pytest.approx(mesh.volume, rel=1e-12)
        assert np.allclose(p["centroid"], mesh.center_mass, rtol=0, atol=1e-12)
        scale = np.abs(mesh.moment_inertia).max()
        assert np.allclose(p["inertia"], mesh.moment_inertia, rtol=0, atol=1e-12 * scale)


def test_free_motion_conserves_momentum_and_runs_back() -> None:
    inertia = np.diag([500.0, 2500.0, 2800.0])
    q0 = np.array([1.0, 0.0, 0.0, 0.0])
    w0 = np.array([0.3, 2.0, 0.5])  # tumbling about an asymmetric body's axes
    p, q, v, w = _core.free_motion(1500.0, inertia, (1, 2, 3), q0, (4, 5, 6), w0, 0.7)
    assert p == pytest.approx([1 + 4 * 0.7, 2 + 5 * 0.7, 3 + 6 * 0.7], abs=1e-12)
    assert v.tolist() == [4.0, 5.0, 6.0]

    def world_momentum(q: np.ndarray, w: np.ndarray) -> np.ndarray:
        r = cs.result.rotation_matrix(q)
        return r @ inertia @ r.T @ w

    assert world_momentum(q, w) == pytest.approx(world_momentum(q0, w0), rel=1e-12)
    assert not np.allclose(w, w0)  # w evolves although L is constant
    back = _core.free_motion(1500.0, inertia, p, q, v, w, -0.7)
    assert back[0] == pytest.approx([1, 2, 3], abs=1e-12)
    assert back[1] == pytest.approx(q0, abs=1e-6)


def _long_scene() -> cs.Scene:
    box = cs.Vehicle.box(4.0, 2.0, 1.0, mass=1000.0)
    scene = cs.Scene()
    scene.add(box.renamed("a"), position=(-5.0, 0.0, 0.5), velocity=(10.0, 0.0, 0.0))
    scene.add(box.renamed("b"), position=(0.0, 0.3, 0.5), heading=0.2)
    return scene


def test_a_progress_hook_does_not_change_the_bits() -> None:
    scene = _long_scene()
    seen: list[float] = []
    hooked = scene.run(duration=10.0, dt=1e-5, progress=seen.append)  # a few seconds of work
    plain = scene.run(duration=10.0, dt=1e-5)
    assert seen and all(0.0 < t <= 10.0 for t in seen) and seen == sorted(seen)
    assert np.array_equal(hooked.t, plain.t)
    for name in ("a", "b"):
        for a, b in zip(hooked.trajectory(name), plain.trajectory(name), strict=True):
            assert np.array_equal(a, b)
    assert [i.to_dict() for i in hooked.impacts] == [i.to_dict() for i in plain.impacts]


def test_an_exception_in_the_progress_hook_stops_the_run() -> None:
    def stop(t: float) -> None:
        raise KeyboardInterrupt

    with pytest.raises(KeyboardInterrupt):
        _long_scene().run(duration=10.0, dt=1e-5, progress=stop)
