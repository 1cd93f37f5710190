"""crashsim.small_linalg: products in one fixed order, and what crashsim builds and reports is
the same bits whichever OpenBLAS kernel numpy loaded (the CPU picks it; OPENBLAS_CORETYPE
forces one), which plain numpy ``@`` is not."""

from __future__ import annotations

import os
import platform
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest
from crashsim.small_linalg import dot, matmul, norm, transform_points

ROOT = Path(__file__).resolve().parent.parent


def _sequential(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """a @ b with each entry summed left to right in Python floats (one rounding per step)."""
    out = np.empty((a.shape[0], b.shape[1]))
    for i in range(a.shape[0]):
        for j in range(b.shape[1]):
            s = float(a[i, 0]) * float(b[0, j])
            for k in range(1, a.shape[1]):
                s = s + float(a[i, k]) * float(b[k, j])
            out[i, j] = s
    return out


def _bits(x: np.ndarray) -> list[int]:
    return np.ascontiguousarray(x, dtype=np.float64).view(np.uint64).ravel().tolist()


def test_every_product_is_summed_in_index_order_with_one_rounding_per_step():
    rng = np.random.default_rng(7)
    for _ in range(50):
        a, b = rng.normal(size=(3, 3)) * 1e3, rng.normal(size=(3, 3)) * 1e-3
        assert _bits(matmul(a, b)) == _bits(_sequential(a, b))
        points = rng.normal(size=(20, 3))
        assert _bits(matmul(points, a.T)) == _bits(_sequential(points, a.T))
        v = rng.normal(size=3)
        assert _bits(matmul(a, v)) == _bits(_sequential(a, v[:, None])[:, 0])
        assert _bits(matmul(v, a)) == _bits(_sequential(v[None, :], a)[0])
        assert _bits(dot(v, a[0])) == _bits(_sequential(v[None, :], a[0][:, None]))
        assert float(norm(v)) == float(np.sqrt(_sequential(v[None, :], v[:, None])[0, 0]))


def test_the_products_have_numpys_shapes_and_values():
    rng = np.random.default_rng(8)
    cases = [((3, 3), (3, 3)), ((3, 3), (3,)), ((3,), (3, 3)), ((40, 3), (3, 3)),
             ((5, 3, 3), (5, 3, 3)), ((5, 3, 3), (3, 3)), ((2, 4), (4, 6))]  # fmt: skip
    for sa, sb in cases:
        a, b = rng.normal(size=sa), rng.normal(size=sb)
        got, want = matmul(a, b), a @ b
        assert got.shape == want.shape
        np.testing.assert_allclose(got, want, rtol=1e-14, atol=1e-14)
    v = rng.normal(size=(6, 3))
    np.testing.assert_allclose(norm(v), np.linalg.norm(v, axis=-1), rtol=1e-15)
    np.testing.assert_allclose(dot(v, v[::-1]), np.sum(v * v[::-1], axis=-1), rtol=1e-15)
    m = np.eye(4)
    m[:3, :3] = [[0.0, -1.0, 0.0], [1.0, 0.0, 0.0], [0.0, 0.0, 1.0]]
    m[:3, 3] = (1.0, 2.0, 3.0)
    assert transform_points([[1.0, 0.0, 0.0]], m).tolist() == [[1.0, 3.0, 3.0]]
    with pytest.raises(ValueError, match="scalar"):
        matmul(2.0, np.eye(3))


# One process per OpenBLAS kernel: numpy's own `@` on fixed matrices (to see that the kernels
# do round differently here), then what crashsim makes of the scenes that used to differ
# (the pedestrian's and the cyclist's engine spec, a short strike's result, the impact
# reports of seed-45deg and three-vehicles, a real mesh's inertia).
_PROBE = r"""
import hashlib, json, sys, warnings
import numpy as np
warnings.simplefilter("ignore")
rng = np.random.default_rng(3)
a, b = rng.normal(size=(64, 3)), rng.normal(size=(3, 3))
numpy_bits = hashlib.sha256((a @ b).tobytes() + np.linalg.norm(a[0]).tobytes()).hexdigest()
from crashsim.analysis.report import build_report
from crashsim.io.scenefile import load_scene
h = hashlib.sha256()
for name in ("pedestrian-sedan-40kmh", "cyclist-sedan-side-40kmh"):
    case = load_scene(f"examples/{name}.toml")
    h.update(case.scene.to_spec(0.1, 1e-3).to_json().encode())
case = load_scene("examples/pedestrian-sedan-40kmh.toml")
result = case.scene.run(0.02, dt=2e-4)
for body in ("car", "pedestrian/head", "pedestrian/pelvis"):
    tr = result.trajectory(body)
    h.update(tr.position.tobytes() + tr.velocity.tobytes())
runout = load_scene("examples/runout-sedan-into-suv.toml").scene.run(1.5, record_interval=0.05)
for name in ("sedan", "suv"):  # between the samples: Hermite positions, slerped orientations
    between = runout.states(name, np.linspace(0.0013, 1.4987, 61))
    h.update(between["position"].tobytes() + between["orientation"].tobytes())
for name in ("seed-45deg", "three-vehicles"):
    h.update(build_report(load_scene(f"examples/{name}.toml").simulate()).to_json().encode())
import crashsim as cs
mesh = sys.argv[1]
if mesh:
    v = cs.Vehicle.from_mesh(mesh, mass=1500.0, name="m")
    h.update(np.asarray(v.inertia).tobytes() + np.asarray(v.cg).tobytes())
print(json.dumps({"numpy": numpy_bits, "crashsim": h.hexdigest()}))
"""


def _kernels() -> list[str]:
    """The OpenBLAS kernels this CPU can run: Prescott (SSE3) on every x86-64, Haswell with
    AVX2 and FMA, SkylakeX with AVX-512."""
    flags = set()
    try:
        for line in Path("/proc/cpuinfo").read_text().splitlines():
            if line.startswith("flags"):
                flags = set(line.split(":", 1)[1].split())
                break
    except OSError:
        pass
    kernels = ["Prescott"]
    if {"avx2", "fma"} <= flags:
        kernels.append("Haswell")
    if "avx512f" in flags:
        kernels.append("SkylakeX")
    return kernels


def _numpy_simd_above_baseline() -> list[str]:
    """The SIMD levels numpy dispatches to on this CPU above its build's baseline (turned
    off by NPY_DISABLE_CPU_FEATURES); [] when numpy does not say."""
    try:
        from numpy._core import _multiarray_umath as umath

        found = umath.__cpu_features__
        return [f for f in umath.__cpu_dispatch__ if found.get(f)]
    except (ImportError, AttributeError):
        return []


@pytest.mark.skipif(platform.machine() not in ("x86_64", "AMD64"), reason="x86-64 kernels")
def test_crashsims_answers_are_the_same_bits_under_every_blas_kernel(tmp_path):
    import json

    kernels = _kernels()
    if len(kernels) < 2:
        pytest.skip(f"this CPU runs one OpenBLAS kernel only ({kernels})")
    meshes = sorted((ROOT.parent / "shared" / "meshes").rglob("*.obj"))
    mesh = str(meshes[0]) if meshes else ""
    runs = {k: {"OPENBLAS_CORETYPE": k} for k in kernels}
    simd = _numpy_simd_above_baseline()
    if simd:  # and numpy's own SIMD (its sin, arccos, power...) off: its baseline code only
        runs["Prescott, numpy baseline"] = {"OPENBLAS_CORETYPE": "Prescott",
                                            "NPY_DISABLE_CPU_FEATURES": " ".join(simd)}
    out = {}
    for label, extra in runs.items():
        env = dict(os.environ, OPENBLAS_VERBOSE="0", **extra)
        run = subprocess.run([sys.executable, "-c", _PROBE, mesh], cwd=ROOT, env=env,
                             capture_output=True, text=True, timeout=300)  # fmt: skip
        assert run.returncode == 0, run.stderr[-2000:]
        out[label] = json.loads(run.stdout.strip().splitlines()[-1])
    if len({o["numpy"] for o in out.values()}) == 1:
        pytest.skip(f"numpy's @ gives the same bits under {kernels} here: nothing to compare")
    assert len({o["crashsim"] for o in out.values()}) == 1, out
