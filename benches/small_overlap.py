"""The small-overlap study (docs/glancing.md section 7, issue 19 item 8): a mid-size sedan
into a rigid barrier at 25 % overlap on the driver side at 40 mph, its delta-V, impulse centre
and yaw-rate change under the automatic geometry and under the crush rule, against the
published small-overlap tests.

    python3 benches/small_overlap.py              # the tables (about 10 s)
    python3 benches/small_overlap.py --json FILE  # also keep the figures

Rules (contact parameters of the pair; everything else the defaults):

- automatic: dt_p 30 ms, the centre of the overlap region (the default);
- stiffness centroid: dt_p 30 ms, centroid="stiffness" (against the rigid barrier: on its face);
- automatic dt_p: depth_of_penetration="auto" (sqrt(m'/k'), k' = the car's B W);
- crush rule: both, the seed's spring model against a rigid barrier.

Cars: the 2008 Ford Fusion of IIHS CF11002 (reference-cases.md section 2: 1621.2 kg, Izz
3167.5 kg m^2; 4.83 x 1.83 m; its CG 2.375 m behind the front bumper: pycrash's vehicle data,
wheelbase 107 in, 50/50, front overhang 40 in) on a generated sedan body with the sedan class
stiffness, at 39.95 mph with restitution 0 as Brach's fits; the sedan class car
(``Vehicle.generate("sedan")``) and the shared sedan mesh (class mass, stiffness and empirical
yaw inertia; skipped without ../shared/meshes) at 17.9 m/s with the default restitution 0.1.
The barrier is the IIHS one: rigid, 1.524 m tall, its struck edge rounded to 150 mm; no
stiffness, so the engine takes it as rigid. Overlap: 25 % of the body's width on its left.
"""

from __future__ import annotations

import argparse
import json
import math
import time
from pathlib import Path

import crashsim as cs
import numpy as np
import trimesh
from crashsim.result import rotation_matrix

ROOT = Path(__file__).resolve().parents[1]
MESH = ROOT.parent / "shared" / "meshes" / "sedan_quaternius_normalcar1.ply"

MPH = 0.44704  # m/s
FT = 0.3048  # m

RULES = {
    "automatic": {},
    "stiffness centroid": {"centroid": "stiffness"},
    "automatic dt_p": {"depth_of_penetration": "auto"},
    "crush rule": {"depth_of_penetration": "auto", "centroid": "stiffness"},
}

# The IIHS tests Brach fitted with planar impact mechanics, as kept in the pycrash project
# (github.com/joe-cormier/pycrash, projects/validation impact momentum/src/
# test_inputs_brach.py): 2008-10 Ford Fusion, driver side, 25 %. Measured delta-V in ft/s
# (the file converts them with 0.681818 to mph), yaw-rate change in deg/s; Brach's impulse
# centre as radius d (ft) and angle phi from the x axis to the struck side, the crush surface
# at gamma (deg; the normal 90 - gamma deg from the x axis, to the struck side); restitution 0.
TESTS = {
    "CF11002": {"mph": 39.95, "dvx_fts": 38.49, "dvy_fts": 10.69, "yaw": 102.75,
                "d_ft": 4.14, "phi": 29.0, "gamma": 74.6},
    "CF10017": {"mph": 40.0, "dvx_fts": 54.82, "dvy_fts": 9.94, "yaw": 157.23,
                "d_ft": 4.6, "phi": 23.8, "gamma": 74.6},
    "CF10023": {"mph": 40.0, "dvx_fts": 31.9, "dvy_fts": 7.3, "yaw": 196.28,
                "d_ft": 4.6, "phi": 26.3, "gamma": 77.0},
}  # fmt: skip
# The planar model of CF11002 with Brach's inputs (Carpenter et al.'s spreadsheet,
# reference-cases.md section 2): delta-V (m/s) and yaw-rate change (deg/s).
CARPENTER_CF11002 = {"dvx": -15.972, "dvy": -3.397, "yaw": 176.43}


def published() -> list[dict[str, float | str]]:
    """The tests in SI: measured delta-V (rearward, toward the right) and yaw-rate change, and
    Brach's impulse centre (m, ahead of the CG and to the struck side) and normal angle."""
    rows: list[dict[str, float | str]] = []
    for name, t in TESTS.items():
        d, phi = t["d_ft"] * FT, math.radians(t["phi"])
        dvx, dvy = t["dvx_fts"] * FT, t["dvy_fts"] * FT
        rows.append(
            {
                "test": name,
                "speed": t["mph"] * MPH,
                "dvx": -dvx,
                "dvy": -dvy,
                "dv": math.hypot(dvx, dvy),
                "yaw": t["yaw"],
                "px": d * math.cos(phi),
                "py": d * math.sin(phi),
                "normal_deg": 90.0 - t["gamma"],
            }
        )
    return rows


def fusion() -> cs.Vehicle:
    # generated body x in [-2.415, 2.415]: CG x 0.04 puts the bumper 2.375 m ahead of it
    return cs.Vehicle.generate(
        "sedan", name="fusion", length=4.83, width=1.83, height=1.45, wheelbase=2.72,
        mass=1621.2, cg=(0.04, 0.0, 0.55), inertia=np.diag([600.0, 2900.0, 3167.5]),
        front_overhang=1.016,
    )  # fmt: skip


def sedan_mesh() -> cs.Vehicle | None:
    if not MESH.is_file():
        return None
    vc = cs.vehicle_class("sedan")
    return cs.Vehicle.from_mesh(
        MESH, mass=vc.mass.value, name="sedan_mesh", inertia="empirical", wheelbase=2.69,
        stiffness=vc.stiffness,
    )  # fmt: skip


def barrier(radius: float = 0.15) -> cs.Obstacle:
    """A rigid block 1 m deep (x), 3 m wide (y), 1.524 m tall; its face x = 0, its edge at
    y = 0 (the block covers y > 0) rounded to ``radius`` (m)."""
    arc = np.linspace(0.0, math.pi / 2.0, 9)
    outline = [(1.0, 0.0), (1.0, 3.0), (0.0, 3.0)] + [
        (radius * (1.0 - math.cos(a)), radius * (1.0 - math.sin(a))) for a in arc
    ]
    points = np.array([(x, y, z) for x, y in outline for z in (0.0, 1.524)])
    return cs.Obstacle(trimesh.convex.convex_hull(points), name="barrier", kind="barrier")


def run(car: cs.Vehicle, speed: float, rule: dict, overlap: float = 0.25,
        restitution: float = 0.1) -> dict[str, object]:  # fmt: skip
    """The car at ``speed`` (m/s, +x) with ``overlap`` of its width (its left side) on the
    barrier, 2 cm from its face; the summed figures of every exchange."""
    lo, hi = np.asarray(car.mesh.bounds)
    cg = np.asarray(car.cg)
    front, left, width = hi[0] - cg[0], hi[1] - cg[1], hi[1] - lo[1]
    s = cs.Scene(restitution=restitution)
    s.add(car, (0.0, 0.0, cg[2]), heading=0.0, velocity=(speed, 0.0, 0.0))
    wall = barrier()
    s.add_obstacle(wall, (front + 0.02, left - overlap * width), heading=0.0)
    if rule:
        s.contact(car, wall, **rule)
    result = s.run(0.25, 1e-3)
    dv = sum((np.asarray(i.delta_v[car.name]) for i in result.impacts), np.zeros(3))
    yaw = sum(float(i.delta_omega[car.name][2]) for i in result.impacts)
    first = result.impacts[0]
    pose = result.state_at(car.name, first.time)
    rot = rotation_matrix(pose["orientation"])
    p = rot.T @ (np.asarray(first.centroid) - np.asarray(pose["position"]))
    n = rot.T @ np.asarray(first.normal)
    return {
        "exchanges": len(result.impacts),
        "dt_p": float(first.depth_of_penetration),
        "crush": float(first.region_max[0] - first.region_min[0]),
        "px": float(p[0]),
        "py": float(p[1]),
        "normal_deg": math.degrees(math.atan2(n[1], n[0])),
        "dvx": float(dv[0]),
        "dvy": float(dv[1]),
        "dv": float(np.linalg.norm(dv)),
        "yaw": math.degrees(yaw),
        "sliding": bool(first.sliding),
    }


def cars() -> list[tuple[str, cs.Vehicle, float, float]]:
    """(label, car, speed m/s, restitution)."""
    out = [
        ("Fusion (CF11002 data), e = 0", fusion(), 39.95 * MPH, 0.0),
        ("sedan class", cs.Vehicle.generate("sedan"), 17.9, 0.1),
    ]
    mesh = sedan_mesh()
    if mesh is not None:
        out.append(("sedan mesh", mesh, 17.9, 0.1))
    return out


def measure() -> dict[str, object]:
    figures: dict[str, object] = {"published": published(), "cases": [], "sweep": [], "tests": []}
    for row in figures["published"]:  # type: ignore[union-attr]
        runs = {
            rule: run(fusion(), float(row["speed"]), RULES[rule], restitution=0.0)
            for rule in ("automatic", "crush rule")
        }
        figures["tests"].append({**row, "crashsim": runs})  # type: ignore[union-attr]
    for label, car, speed, e in cars():
        for rule, params in RULES.items():
            row = {"car": label, "rule": rule, **run(car, speed, params, restitution=e)}
            figures["cases"].append(row)  # type: ignore[union-attr]
    car = fusion()
    for overlap in (0.15, 0.2, 0.25, 0.3, 0.4, 0.5):
        for rule in ("automatic", "crush rule"):
            row = run(car, 39.95 * MPH, RULES[rule], overlap=overlap, restitution=0.0)
            figures["sweep"].append({"overlap": overlap, "rule": rule, **row})  # type: ignore[union-attr]
    return figures


def tables(figures: dict) -> str:
    lines = ["Published (Brach's fits, pycrash's table; SI):", ""]
    lines.append("| test | speed (m/s) | dV x, y (m/s) | \\|dV\\| (m/s) | yaw-rate change (deg/s) "
                 "| impulse centre x, y (m) | normal (deg) |")  # fmt: skip
    lines.append("|---|---|---|---|---|---|---|")
    for r in figures["published"]:
        lines.append(
            f"| {r['test']} | {r['speed']:.2f} | {r['dvx']:.2f}, {r['dvy']:.2f} | {r['dv']:.2f} "
            f"| {r['yaw']:.1f} | {r['px']:.2f}, {r['py']:.2f} | {r['normal_deg']:.1f} |"
        )
    lines += [
        "",
        "Against the tests (the Fusion at each test's speed, 25 %, restitution 0 as the fits; "
        "automatic -> crush rule):",
        "",
        "| test | speed (m/s) | overlap | measured \\|dV\\| (m/s) | measured yaw-rate change "
        "(deg/s) | crashsim \\|dV\\| (m/s) | crashsim yaw-rate change (deg/s) |",
        "|---|---|---|---|---|---|---|",
    ]
    for r in figures["tests"]:
        a, b = r["crashsim"]["automatic"], r["crashsim"]["crush rule"]
        lines.append(
            f"| {r['test']} | {r['speed']:.2f} | 25 % | {r['dv']:.2f} | {r['yaw']:.1f} "
            f"| {a['dv']:.2f} -> {b['dv']:.2f} | {a['yaw']:.1f} -> {b['yaw']:.1f} |"
        )
    c = CARPENTER_CF11002
    lines += [
        "",
        f"Planar model with Brach's CF11002 inputs (Carpenter): dV {c['dvx']:.2f}, "
        f"{c['dvy']:.2f} m/s, yaw-rate change {c['yaw']:.1f} deg/s",
        "",
        "crashsim (first exchange's dt_p, overlap depth along n and impulse centre in the car's "
        "frame; delta-V and yaw-rate change summed over the exchanges):",
        "",
        "| car | rule | dt_p (ms) | overlap depth (m) | P x, y (m) | normal (deg) "
        "| dV x, y (m/s) | \\|dV\\| (m/s) | yaw-rate change (deg/s) | exchanges |",
        "|---|---|---|---|---|---|---|---|---|---|",
    ]
    for r in figures["cases"]:
        lines.append(
            f"| {r['car']} | {r['rule']} | {r['dt_p'] * 1e3:.1f} | {r['crush']:.3f} "
            f"| {r['px']:.3f}, {r['py']:.3f} | {r['normal_deg']:.1f} "
            f"| {r['dvx']:.2f}, {r['dvy']:.2f} | {r['dv']:.2f} | {r['yaw']:.1f} "
            f"| {r['exchanges']}{' (sliding)' if r['sliding'] else ''} |"
        )
    lines += ["", "Fusion, e = 0, by overlap (automatic -> crush rule):", ""]
    lines.append("| overlap | yaw-rate change (deg/s) | \\|dV\\| (m/s) | P x (m) | dt_p (ms) |")
    lines.append("|---|---|---|---|---|")
    sweep = figures["sweep"]
    for a, b in zip(sweep[::2], sweep[1::2], strict=True):
        lines.append(
            f"| {a['overlap']:.0%} | {a['yaw']:.1f} -> {b['yaw']:.1f} | {a['dv']:.2f} -> "
            f"{b['dv']:.2f} | {a['px']:.2f} -> {b['px']:.2f} | {a['dt_p'] * 1e3:.1f} -> "
            f"{b['dt_p'] * 1e3:.1f} |"
        )
    return "\n".join(lines)


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--json", type=Path, help="write the figures to this file")
    args = ap.parse_args()
    t0 = time.perf_counter()
    figures = measure()
    print(tables(figures))
    print(f"\n({time.perf_counter() - t0:.1f} s)")
    if args.json:
        args.json.write_text(json.dumps(figures, indent=1))


if __name__ == "__main__":
    main()
