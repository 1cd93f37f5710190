"""The glancing-impact study (docs/glancing.md): delta-V, impulse direction, normal angle,
sliding and energy as functions of the lateral overlap d, and thin walls of growing thickness.

    python3 benches/glancing_study.py                      # measure with the installed engine,
                                                           # plot against the committed "before"
    python3 benches/glancing_study.py --save FILE.json     # measure only, write the figures
    python3 benches/glancing_study.py --plot A.json B.json # plot two saved measurements

The "before" figures (benches/glancing_before.json) were measured with the engine before the
rule of docs/glancing.md (commit 658303c); anyone can re-measure them by installing that
commit and running ``--save``. Pictures go to docs/img/glancing_*.png.

Cases (SI; every car a 4.5 x 1.8 x 1.4 m box of 1450 kg unless said otherwise; default contact
parameters: dt_p 30 ms, restitution 0.1, friction 0.6):

- oncoming: head-on at 20 m/s each, their paths overlapping laterally by d;
- sideswipe: same direction, the follower 10 m/s faster and yawed 3 deg toward the leader, its
  front corner overlapping the leader's rear corner laterally by d (a small-angle corner clip);
- corner: a car at 20 m/s into a car at rest yawed 30 deg, whose nearest corner lies d inside
  the moving car's path;
- meshes: the shared sedan and SUV meshes head-on at 20 m/s each, their outlines overlapping
  laterally by d (skipped when ../shared/meshes is absent);
- walls: a car at 30 m/s square into a wall (box, 1e6 kg) of thickness th.
"""

from __future__ import annotations

import argparse
import json
import math
import sys
import time
from pathlib import Path

import crashsim as cs
import numpy as np

ROOT = Path(__file__).resolve().parents[1]
MESHES = ROOT.parent / "shared" / "meshes"
IMG = ROOT / "docs" / "img"
BEFORE = Path(__file__).resolve().parent / "glancing_before.json"

L, W, H, M = 4.5, 1.8, 1.4, 1450.0
# Lateral overlaps (m): log-spaced at small d, then up to the full width.
OVERLAPS = [
    float(x) for x in np.concatenate([np.geomspace(0.0005, 0.1, 16), np.linspace(0.15, W, 12)])
]
TABLE = [0.001, 0.003, 0.01, 0.02, 0.05, 0.1, 0.3, 0.9]
# The oncoming case on a fine linear grid (the continuity test's grid,
# crates/crashsim-core/tests/integration/glancing.rs).
FINE = [0.0005 * k for k in range(1, 40)] + [0.002 * k for k in range(10, 226)]
WALLS = [0.002, 0.005, 0.01, 0.02, 0.03, 0.05, 0.1, 0.2]


def box(name: str, mass: float = M, length: float = L) -> cs.Vehicle:
    return cs.Vehicle.box(length, W, H, mass=mass, name=name)


def figures(result: cs.Result, names: tuple[str, str]) -> dict[str, object]:
    """Summed delta-V per vehicle over every exchange, and the first exchange's details."""
    dv = {n: np.zeros(3) for n in names}
    energy = 0.0
    for imp in result.impacts:
        for n in names:
            dv[n] = dv[n] + imp.delta_v[n]
        energy += imp.energy_dissipated
    out: dict[str, object] = {
        "dv1": float(np.linalg.norm(dv[names[0]])),
        "dv2": float(np.linalg.norm(dv[names[1]])),
        "dv1_x": float(dv[names[0]][0]),
        "dv1_y": float(dv[names[0]][1]),
        "energy": energy,
        "exchanges": len(result.impacts),
        "no_exchange": [c.reason for c in result.contacts if c.kind == "no_exchange"],
    }
    if result.impacts:
        first = result.impacts[0]
        n, j = first.normal, first.impulse
        out.update(
            normal_deg=math.degrees(math.atan2(n[1], n[0])),
            impulse_deg=math.degrees(math.atan2(j[1], j[0])),
            sliding=bool(first.sliding),
            normal_depth=float(first.normal_time - first.first_contact_time),
            notes=list(first.notes),
        )
    return out


def oncoming(d: float, v: float = 20.0) -> dict[str, object]:
    s = cs.Scene()
    s.add(box("a"), (-2.6, 0.0, H / 2), heading=0.0, velocity=(v, 0, 0))
    s.add(box("b"), (2.6, W - d, H / 2), heading=math.pi, velocity=(-v, 0, 0))
    return figures(s.run(0.4, 1e-3), ("a", "b"))


def sideswipe(d: float, yaw_deg: float = 3.0) -> dict[str, object]:
    # Leader b heading +x at 20 m/s, its rear-left corner at (-L/2, W/2) about its CG (0, 0).
    # Follower a at 30 m/s, yawed toward b by yaw_deg; its front-right corner starts 15 cm
    # behind b's rear and d inside b's left side (so the lateral overlap at first contact is
    # d plus the 30 sin(yaw) x 15 ms it drifts on the way, 2.4 cm at 3 deg).
    yaw = math.radians(yaw_deg)
    c, s_ = math.cos(yaw), math.sin(yaw)
    corner = np.array([-L / 2 - 0.15, W / 2 - d])
    # Front-right corner of a in its frame: (L/2, -W/2), rotated by -yaw (toward -y).
    rot = np.array([[c, s_], [-s_, c]])
    cg = corner - rot @ np.array([L / 2, -W / 2])
    s = cs.Scene()
    s.add(box("a"), (cg[0], cg[1], H / 2), heading=-yaw, velocity=(30.0 * c, -30.0 * s_, 0))
    s.add(box("b"), (0.0, 0.0, H / 2), heading=0.0, velocity=(20.0, 0, 0))
    return figures(s.run(0.6, 1e-3), ("a", "b"))


def corner(d: float, yaw_deg: float = 30.0) -> dict[str, object]:
    yaw = math.radians(yaw_deg)
    pts = np.array([[sx * L / 2, sy * W / 2] for sx in (-1, 1) for sy in (-1, 1)])
    rot = np.array([[math.cos(yaw), -math.sin(yaw)], [math.sin(yaw), math.cos(yaw)]])
    lowest = float((pts @ rot.T)[:, 1].min())
    s = cs.Scene()
    s.add(box("a"), (-4.0, 0.0, H / 2), heading=0.0, velocity=(20.0, 0, 0))
    s.add(box("b"), (1.5, W / 2 - d - lowest, H / 2), heading=yaw)
    return figures(s.run(0.5, 1e-3), ("a", "b"))


_MESH_CACHE: dict[str, cs.Vehicle] = {}


def mesh_vehicle(name: str) -> cs.Vehicle:
    if name not in _MESH_CACHE:
        spec = {
            "sedan": ("sedan_quaternius_normalcar1.ply", 1450.0, 0.50, (450.0, 2000.0, 2250.0)),
            "suv": ("suv_quaternius_suv.ply", 1900.0, 0.68, (700.0, 2900.0, 3100.0)),
        }[name]
        _MESH_CACHE[name] = cs.Vehicle.from_mesh(
            MESHES / spec[0], mass=spec[1], name=name, cg=(0, 0, spec[2]), inertia=np.diag(spec[3])
        )
    return _MESH_CACHE[name]


def meshes(d: float, v: float = 20.0) -> dict[str, object]:
    a, b = mesh_vehicle("sedan"), mesh_vehicle("suv")
    va, vb = a.body_vertices, b.body_vertices
    # b is turned 180 deg (its body y flips): its lowest world y is its CG's minus max body y.
    a_top, b_low = va[:, 1].max(), -vb[:, 1].max()
    gap = 0.3
    xa = -va[:, 0].max() - gap / 2
    xb = vb[:, 0].max() + gap / 2
    cg_a, cg_b = a.cg, b.cg
    s = cs.Scene()
    s.add(a, (xa, 0.0, cg_a[2]), heading=0.0, velocity=(v, 0, 0))
    s.add(b, (xb, a_top - d - b_low, cg_b[2]), heading=math.pi, velocity=(-v, 0, 0))
    return figures(s.run(0.4, 1e-3), ("sedan", "suv"))


def wall(th: float, v: float = 30.0) -> dict[str, object]:
    s = cs.Scene()
    s.add(box("car"), (-3.0, 0.0, H / 2), heading=0.0, velocity=(v, 0, 0))
    s.add(
        cs.Vehicle.box(th, 6.0, 2.0, mass=1e6, name="wall", inertia=np.eye(3) * 1e12),
        (0.0, 0.0, 1.0),
        heading=0.0,
    )
    result = s.run(0.3, 1e-3)
    out = figures(result, ("car", "wall"))
    out["contacts"] = [(c.kind, c.reason) for c in result.contacts]
    return out


def measure() -> dict[str, object]:
    data: dict[str, object] = {"overlaps": OVERLAPS, "walls": WALLS}
    cases = {"oncoming": oncoming, "sideswipe": sideswipe, "corner": corner}
    if MESHES.is_dir():
        cases["meshes"] = meshes
    for name, fn in cases.items():
        t = time.perf_counter()
        grid = OVERLAPS if name != "meshes" else [d for d in OVERLAPS if d <= 1.6]
        data[name] = {"d": grid, "rows": [fn(d) for d in grid]}
        print(f"{name}: {len(grid)} runs in {time.perf_counter() - t:.1f} s", file=sys.stderr)
    data["wall"] = {"th": WALLS, "rows": [wall(th) for th in WALLS]}
    data["table"] = {f"{d * 1e3:g}": oncoming(d) for d in TABLE}
    data["fine"] = {"d": FINE, "dv1": [float(oncoming(d)["dv1"]) for d in FINE]}
    return data


def plot(before: dict, after: dict | None) -> list[Path]:
    import matplotlib

    matplotlib.use("Agg")
    from matplotlib.figure import Figure

    IMG.mkdir(parents=True, exist_ok=True)
    written = []
    cases = [c for c in ("oncoming", "sideswipe", "corner", "meshes") if c in before]
    for case in cases:
        fig = Figure(figsize=(11, 7.5), layout="constrained")
        axes = fig.subplots(2, 2)
        for label, data, style in (("before", before, "o--"), ("after", after, "s-")):
            if data is None or case not in data:
                continue
            d = np.array(data[case]["d"]) * 1e3
            rows = data[case]["rows"]

            def get(key: str, rows: list = rows) -> np.ndarray:
                return np.array([r.get(key, np.nan) for r in rows], dtype=float)

            ax = axes[0, 0]
            ax.plot(d, get("dv1"), style, ms=3, label=f"{label}: vehicle 1")
            ax.plot(d, get("dv2"), style, ms=3, alpha=0.5, label=f"{label}: vehicle 2")
            axes[0, 1].plot(d, get("normal_deg"), style, ms=3, label=f"{label}: normal")
            axes[0, 1].plot(
                d, get("impulse_deg"), style, ms=3, alpha=0.5, label=f"{label}: impulse"
            )
            axes[1, 0].plot(d, get("energy") / 1e3, style, ms=3, label=label)
            sliding = np.array([float(r.get("sliding", np.nan)) for r in rows])
            axes[1, 1].plot(d, sliding, style, ms=3, label=f"{label}: sliding (1) / sticking (0)")
            axes[1, 1].plot(
                d, get("exchanges"), style, ms=3, alpha=0.5, label=f"{label}: exchanges"
            )
        titles = [
            ("|delta-V| summed over the exchanges (m/s)", "linear"),
            ("first exchange: angle from world x (deg)", "linear"),
            ("energy dissipated (kJ)", "linear"),
            ("first exchange sliding; number of exchanges", "linear"),
        ]
        for ax, (title, _) in zip(axes.flat, titles, strict=True):
            ax.set_xscale("log")
            ax.set_xlabel("lateral overlap d (mm)")
            ax.set_title(title, fontsize=10)
            ax.grid(True, which="both", alpha=0.3)
            ax.legend(fontsize=7)
        fig.suptitle(f"glancing study: {case} (docs/glancing.md)")
        path = IMG / f"glancing_{case}.png"
        fig.savefig(path, dpi=90)
        written.append(path)
    # The oncoming case on a linear scale, with the largest change per mm of d.
    fig = Figure(figsize=(7, 4), layout="constrained")
    ax = fig.subplots()
    for label, data, style in (("before", before, "--"), ("after", after, "-")):
        if data is None or "fine" not in data:
            continue
        d, dv = np.array(data["fine"]["d"]), np.array(data["fine"]["dv1"])
        slope = np.max(np.abs(np.diff(dv)) / np.diff(d * 1e3))
        ax.plot(d * 1e3, dv, style, label=f"{label} (largest slope {slope:.2f} m/s per mm)")
    ax.set_xlabel("lateral overlap d (mm)")
    ax.set_ylabel("|delta-V| of each car (m/s)")
    ax.set_title("oncoming boxes, 20 m/s each: delta-V against d (linear)")
    ax.grid(True, alpha=0.3)
    ax.legend(fontsize=8)
    path = IMG / "glancing_oncoming_linear.png"
    fig.savefig(path, dpi=90)
    written.append(path)
    # Thin walls.
    fig = Figure(figsize=(7, 4), layout="constrained")
    ax = fig.subplots()
    for label, data, style in (("before", before, "o--"), ("after", after, "s-")):
        if data is None:
            continue
        th = np.array(data["wall"]["th"]) * 1e2
        ax.plot(th, [r["dv1"] for r in data["wall"]["rows"]], style, label=label)
    m = 1e6
    ax.axhline(1.1 * m / (M + m) * 30.0, color="k", lw=0.8, label="closed form (1+e) m_w/(m+m_w) v")
    ax.set_xscale("log")
    ax.set_xlabel("wall thickness (cm)")
    ax.set_ylabel("car |delta-V| (m/s)")
    ax.set_title("car at 30 m/s into a 1e6 kg wall, dt_p 30 ms")
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=8)
    path = IMG / "glancing_walls.png"
    fig.savefig(path, dpi=90)
    written.append(path)
    return written


def main() -> None:
    p = argparse.ArgumentParser(
        description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter
    )
    p.add_argument("--save", type=Path, help="write the measurement to this JSON file")
    p.add_argument("--plot", nargs=2, type=Path, metavar=("BEFORE", "AFTER"))
    args = p.parse_args()
    if args.plot:
        before, after = (json.loads(f.read_text()) for f in args.plot)
    else:
        after = measure()
        if args.save:
            args.save.write_text(json.dumps(after, indent=1))
        before = json.loads(BEFORE.read_text()) if BEFORE.exists() else after
        print("d (mm)  |dV1| (m/s)  |dV2|  normal (deg)  sliding")
        for k, r in after["table"].items():
            print(
                f"{k:>6}  {r['dv1']:10.2f}  {r['dv2']:6.2f}  "
                f"{r.get('normal_deg', float('nan')):8.1f}  {r.get('sliding')}"
            )
        print("wall (cm)  car |dV| (m/s)")
        for th, r in zip(after["wall"]["th"], after["wall"]["rows"], strict=True):
            print(f"{th * 100:8.1f}  {r['dv1']:8.3f}")
    for path in plot(before, after):
        print(path.relative_to(ROOT))


if __name__ == "__main__":
    main()
