"""Throw distance against impact speed, crashsim's multibody pedestrian against the published
corridors (docs/human.md, "Throw distance").

    python3 benches/pedestrian_throw.py                  # 20-70 km/h, four fronts, the picture
    python3 benches/pedestrian_throw.py --speeds 30 --fronts sedan --no-picture
    python3 benches/pedestrian_throw.py --fronts flat_van --no-picture   # a flat-fronted van

A walking 50th-percentile man (1.75 m, 75 kg) struck on his left side, his nearest point 5 cm
ahead of the vehicle's foremost point, as scripts/pedestrian_strike.py does: soft car-segment
contacts (1e5 N/m, damping ratio 0.5, friction 0.3, normal "volume"), 0.2 ms steps, tyre-road
friction 0.8, the vehicle braking at the friction limit from the start (3-19 ms before the
first contact). The pedestrian's segments slide on the road with the person's own road
friction (Pedestrian.road_friction: 0.66, the default; before 2026-11-29 they slid with
the ground's body friction, a car body's 0.45). Each run goes until every body is at rest
(``run(until="rest")``), at most 1 s + 1.2 v / (0.45 g) (v the impact speed; the slide
from v at 0.45 g takes v / (0.45 g), longer than at the person's 0.66, which leaves the lying
body time to settle); the table says when it ended, whether the engine's rest test passed,
and the pelvis speed at the end.

Prints a row per run (speed, front, throw distance of the whole-body CG, the head's first
contact time and speed relative to the vehicle, the pelvis speed at the end, the trajectory
type of crashsim.analysis.throw.trajectory_type, wall time) and
draws docs/img/pedestrian-throw.png (crashsim's points over the corridors).
"""

from __future__ import annotations

import argparse
import time
import warnings
from dataclasses import dataclass
from pathlib import Path

import crashsim as cs
import numpy as np
from crashsim.analysis.pedestrian import segment_contacts
from crashsim.analysis.throw import (
    VKU_FRICTION,
    VKU_THROW_FACTORS,
    G,
    first_contact_time,
    searle_distance,
    throw_distance,
    trajectory_type,
    vku_throw_distance,
)
from crashsim.human.pedestrian import ROAD_FRICTION  # the person's default friction on the road

# The run's length is sized by a slide at this friction (the ground's body friction, lower
# than the person's): a body sliding at 0.66 stops sooner but still settles for seconds.
LENGTH_FRICTION = 0.45
REST_SPEED = 0.1  # m/s, the pelvis below this at the end: at rest
FRONTS = ("sedan", "suv", "van", "truck")
# Not in the default table: a forward-control van, the generated van (its class's data,
# docs/vehicle-data.md) with the bus preset's front profile at the van's size, a flat and
# upright face (the class's own 1990s minivan has a short sloping hood).
EXTRA_FRONTS = ("flat_van",)
FLAT_FRONT = ("nose_height", "hood_height", "windshield_base", "roof_start")
SPEEDS = (20.0, 30.0, 40.0, 50.0, 60.0, 70.0)  # km/h
PICTURE = Path(__file__).resolve().parent.parent / "docs" / "img" / "pedestrian-throw.png"


def vehicle(front: str) -> cs.Vehicle:
    """The striking vehicle: a generated sedan, SUV or van, the laden rigid truck (18 t, its
    flat cab front), or the flat-fronted van (EXTRA_FRONTS)."""
    if front == "truck":
        return cs.rigid_truck("rigid_truck", name="car")
    if front == "flat_van":
        from crashsim.vehicles.generator import body_params, default_dims

        bus = body_params("bus", **default_dims("van")).as_dict()
        return cs.Vehicle.generate("van", name="car", **{k: bus[k] for k in FLAT_FRONT})
    return cs.Vehicle.generate(front, name="car")


def duration_for(speed_kmh: float) -> float:
    """The run's length (s): 1 s for the contact and flight, then 1.2 times the slide from
    the impact speed at LENGTH_FRICTION."""
    return 1.0 + 1.2 * cs.kmh(speed_kmh) / (LENGTH_FRICTION * G)


@dataclass(frozen=True)
class Strike:
    speed_kmh: float
    front: str
    throw: float  # m, the whole-body CG from the first contact to the end
    first_contact: float  # s
    head_time: float | None  # s, the head's first contact with the vehicle
    head_speed: float | None  # m/s, the head relative to the vehicle at the point it touched
    head_wad: float | None  # m, that point's wrap-around distance (None off the front)
    pelvis_end_speed: float  # m/s at the end of the run
    duration: float  # s simulated: the end of the run
    at_rest: bool  # every body passed the engine's rest test before the longest run
    trajectory: str  # crashsim.analysis.throw.trajectory_type
    wall: float  # s


def strike(speed_kmh: float, front: str, duration: float | None = None, dt: float = 2e-4
           ) -> Strike:  # fmt: skip
    car = vehicle(front)
    ped = cs.Pedestrian(height=1.75, mass=75.0, sex="male", pose="walking")
    scene = cs.Scene(ground=cs.Ground(friction=0.8))
    ahead = float(car.mesh.bounds[1, 0] - car.cg[0])  # the CG to the front, m
    duration = duration_for(speed_kmh) if duration is None else duration
    scene.add(car, (0.0, 0.0), heading=0.0, velocity=(cs.kmh(speed_kmh), 0.0, 0.0),
              inputs=cs.DriverInputs(brake=[(0.0, 1.0), (duration, 1.0)]))
    # facing across the vehicle's path (+y), his left side (body y, world -x) 5 cm ahead of
    # the vehicle's foremost point (the arm's capsule reaches 0.22 m left of the mid-plane)
    left = float(ped.vertices()[:, 1].max())
    scene.add(ped, (ahead + 0.05 + left, 0.0), heading=np.pi / 2)
    for seg in ped.segments:
        scene.contact(car, seg, depth_of_penetration=0.0, restitution=0.1, friction=0.3,
                      normal="volume")
    scene.soft_contact(car, ped, stiffness=1e5, damping_ratio=0.5)
    t0 = time.perf_counter()
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        result = scene.run(until="rest", max_duration=duration, dt=dt, record_interval=2e-3)
    at_rest = not any(issubclass(w.category, cs.RestNotReachedWarning) for w in caught)
    wall = time.perf_counter() - t0
    head = segment_contacts(result, ped, car).get("head")
    head_time, head_speed, head_wad = ((None, None, None) if head is None
                                       else (head.time, head.relative_speed, head.wrap_around))
    pelvis = result.trajectory(f"{ped.name}/pelvis")
    return Strike(
        speed_kmh, front, throw_distance(result, "car", ped),
        first_contact_time(result, "car", ped), head_time, head_speed, head_wad,
        float(np.linalg.norm(pelvis.velocity[-1])), float(pelvis.t[-1]), at_rest,
        trajectory_type(result, car, ped), wall,
    )


def table(rows: list[Strike]) -> str:
    lines = ["| km/h | front | throw (m) | first contact (s) | head contact (s) | head rel. speed "
             "(m/s) | head WAD (m) | pelvis at end (m/s) | ended (s) | at rest | trajectory "
             "| wall (s) |",
             "| ---: | --- | ---: | ---: | ---: | ---: | ---: | ---: | ---: | --- | --- | ---: |"]
    for r in rows:
        head_t = "none" if r.head_time is None else f"{r.head_time:.3f}"
        head_v = "-" if r.head_speed is None else f"{r.head_speed:.2f}"
        wad = "-" if r.head_wad is None else f"{r.head_wad:.2f}"
        lines.append(f"| {r.speed_kmh:.0f} | {r.front} | {r.throw:.2f} | {r.first_contact:.4f} | "
                     f"{head_t} | {head_v} | {wad} | {r.pelvis_end_speed:.3f} | {r.duration:.2f} | "
                     f"{'yes' if r.at_rest else 'no'} | {r.trajectory} | {r.wall:.1f} |")
    return "\n".join(lines)


def picture(rows: list[Strike], path: Path) -> None:
    from matplotlib.figure import Figure

    fig = Figure(figsize=(8.0, 5.6), layout="constrained")
    ax = fig.add_subplot()
    kmh = np.linspace(15.0, 75.0, 121)
    v = kmh / 3.6
    lo, hi = np.array([searle_distance(x, ROAD_FRICTION) for x in v]).T
    ax.fill_between(kmh, lo, hi, color="tab:blue", alpha=0.18,
                    label=f"Searle (1983), mu {ROAD_FRICTION:g} (the person's), v = impact speed")
    for (name, f), color in zip(VKU_THROW_FACTORS.items(), ("tab:green", "tab:olive"), strict=True):
        ax.plot(kmh, [vku_throw_distance(x, name, VKU_FRICTION) for x in v], color=color, lw=1.4,
                label=f"VKU 1997 adult, {name} (f_w {f:g}), mu {VKU_FRICTION:g}")
    ax.errorbar([50.0], [20.0], xerr=[[10.0], [10.0]], fmt="none", ecolor="0.3", capsize=4,
                label="20 m: 40-60 km/h (unfallanalyse.hamburg's table)")
    markers = {"sedan": "o", "suv": "s", "van": "^", "truck": "D", "flat_van": "v"}
    colors = {"sedan": "tab:red", "suv": "tab:purple", "van": "tab:orange", "truck": "k",
              "flat_van": "tab:brown"}
    for front in FRONTS:
        pts = [(r.speed_kmh, r.throw, r.at_rest or r.pelvis_end_speed < REST_SPEED) for r in rows
               if r.front == front]
        if not pts:
            continue
        xs, ys, rest = zip(*pts, strict=True)
        c = colors[front]
        ax.plot(xs, ys, color=c, lw=0.8, alpha=0.6)
        ax.scatter(xs, ys, marker=markers[front], s=42, zorder=3,
                   facecolors=[c if r else "white" for r in rest], edgecolors=c,
                   label=f"crashsim, {front}")
    ax.set_xlabel("impact speed (km/h)")
    ax.set_ylabel("throw distance, whole-body CG, first contact to rest (m)")
    ax.set_title("Pedestrian throw distance: crashsim (walking 1.75 m, 75 kg, struck on the side)"
                 "\nover the published corridors (hollow marker: still moving at the run's end)",
                 fontsize=10)
    ax.set_xlim(15.0, 75.0)
    ax.set_ylim(0.0, None)
    ax.grid(True, alpha=0.3)
    ax.legend(fontsize=7, loc="upper left")
    fig.savefig(path, dpi=110)


def main() -> None:
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--speeds", type=float, nargs="+", default=SPEEDS, help="km/h")
    p.add_argument("--fronts", nargs="+", default=FRONTS, choices=FRONTS + EXTRA_FRONTS)
    p.add_argument("--duration", type=float, default=None,
                   help="s, the same for every run (default: from the speed)")
    p.add_argument("--dt", type=float, default=2e-4,
                   help="s, the run's step (longer than 0.4 ms: sub-steps while a segment "
                        "presses on the vehicle; the table and picture are at 0.2 ms)")
    p.add_argument("--no-picture", action="store_true")
    p.add_argument("--out", type=Path, default=PICTURE)
    a = p.parse_args()
    rows = []
    t0 = time.perf_counter()
    for front in a.fronts:
        for speed in a.speeds:
            r = strike(speed, front, a.duration, a.dt)
            rows.append(r)
            print(f"{speed:4.0f} km/h {front:8s} throw {r.throw:6.2f} m, head "
                  f"{'none' if r.head_time is None else f'{r.head_time:.3f} s'}, pelvis "
                  f"{r.pelvis_end_speed:.3f} m/s at {r.duration:.2f} s, at rest {r.at_rest}, "
                  f"wall {r.wall:.1f} s",
                  flush=True)
    print(table(rows))
    print(f"total wall {time.perf_counter() - t0:.0f} s")
    if not a.no_picture:
        picture(rows, a.out)
        print(f"wrote {a.out}")


if __name__ == "__main__":
    main()
