"""The joints' accuracy figures of docs/joints.md (issue 21): a pendulum's period against its
closed form, a passive double pendulum's energy and its joints' drift over 10 s, a chain of 20
links over 5 s, all at the default 1 ms step, and each run's wall time per simulated second.

    python3 benches/joint_accuracy.py

Bodies hang 30 m above a plane they never reach: gravity and the joints are the only forces.
The tests (crates/crashsim-core/tests/integration/joints/, tests/test_joints.py) hold the same
runs to their tolerances; this prints the figures.
"""

from __future__ import annotations

import math
import time

import crashsim as cs
import numpy as np
from crashsim.result import rotation_matrix

G = 9.80665
HIGH = 30.0


def chain(n: int, length: float, kind: str, pitch: float) -> cs.Scene:
    """``n`` rods of ``length`` m (5 kg, 5 cm thick) from a pivot at (0, 0, HIGH), tilted
    ``pitch`` rad below the horizontal, joined end to end by ``kind`` about world y."""
    scene = cs.Scene(ground=cs.Ground())
    direction = np.array([math.cos(pitch), 0.0, -math.sin(pitch)])
    q = (math.cos(pitch / 2), 0.0, math.sin(pitch / 2), 0.0)
    pivot = np.array([0.0, 0.0, HIGH])
    axes = (math.cos(-math.pi / 4), math.sin(-math.pi / 4), 0.0, 0.0)  # z along world y
    for k in range(n):
        rod = cs.Vehicle.box(length, 0.05, 0.05, mass=5.0, name=f"rod{k}")
        scene.add(rod, tuple(pivot + direction * length * (k + 0.5)), orientation=q)
    scene.join("rod0", at=tuple(pivot), kind=kind, axes=axes)
    for k in range(1, n):
        end = pivot + direction * length * k
        scene.join(f"rod{k - 1}", f"rod{k}", at=tuple(end), kind=kind, axes=axes)
    return scene


def energy(result: cs.Result, n: int) -> np.ndarray:
    """Kinetic plus potential energy (J) at every sample."""
    total = np.zeros(len(result.t))
    for k in range(n):
        tr = result.trajectory(f"rod{k}")
        v = result.scene.vehicles[k]
        r = rotation_matrix(tr.orientation)  # (k, 3, 3)
        inertia = r @ v.inertia @ np.transpose(r, (0, 2, 1))
        om = tr.angular_velocity
        rot = 0.5 * np.einsum("ki,kij,kj->k", om, inertia, om)
        total += 0.5 * v.mass * (tr.velocity**2).sum(axis=1) + rot + v.mass * G * tr.position[:, 2]
    return total


def timed(scene: cs.Scene, duration: float) -> tuple[cs.Result, float]:
    t0 = time.perf_counter()
    result = scene.run(duration)
    return result, (time.perf_counter() - t0) / duration


def main() -> None:
    theta0 = math.radians(5.0)
    result, cost = timed(chain(1, 1.0, "revolute", math.pi / 2 - theta0), 6.0)
    c = result.trajectory("rod0").position
    angle = np.arctan2(c[:, 0], HIGH - c[:, 2])
    up = np.flatnonzero((angle[:-1] < 0) & (angle[1:] >= 0))
    t = result.t
    crossings = t[up] - angle[up] * (t[up + 1] - t[up]) / (angle[up + 1] - angle[up])
    period = float(np.diff(crossings).mean())
    i_o = 5.0 / 12.0 * (1.0 + 0.05**2) + 5.0 * 0.25
    closed = 2 * math.pi * math.sqrt(i_o / (5.0 * G * 0.5)) * (1 + theta0**2 / 16)
    print(
        f"pendulum (1 m rod, 5 deg): period {period:.6f} s, closed form {closed:.6f} s "
        f"({(period / closed - 1) * 1e6:+.1f} ppm); {cost * 1e3:.1f} ms per simulated s"
    )

    runs = ((2, 1.0, "revolute", 0.0, 10.0), (20, 0.3, "spherical", 0.3, 5.0))
    for n, length, kind, pitch, duration in runs:
        result, cost = timed(chain(n, length, kind, pitch), duration)
        e = energy(result, n)
        fall = sum(5.0 * G * length * (k + 0.5) for k in range(n))
        ends = []
        for k in range(n):
            tr = result.trajectory(f"rod{k}")
            ax = rotation_matrix(tr.orientation)[:, :, 0]  # the body x axis, world
            ends.append((tr.position - ax * length / 2, tr.position + ax * length / 2))
        gap = float(np.linalg.norm(ends[0][0] - [0, 0, HIGH], axis=1).max())
        for k in range(1, n):
            gap = max(gap, float(np.linalg.norm(ends[k][0] - ends[k - 1][1], axis=1).max()))
        print(
            f"{n} links ({kind}), {duration:g} s: energy within {np.abs(e - e[0]).max():.3e} J "
            f"of {fall:.1f} J ({np.abs(e - e[0]).max() / fall * 100:.2e} %), joints apart at most "
            f"{gap:.2e} m; {cost * 1e3:.1f} ms per simulated s"
        )


if __name__ == "__main__":
    main()
