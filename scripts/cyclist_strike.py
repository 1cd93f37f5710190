"""A cyclist struck from the side or from behind by a generated sedan (docs/human.md, "The
cyclist"), and the bicycle or the cyclist alone, in figures.

    python3 scripts/cyclist_strike.py --strike side     # 40 km/h into a crossing cyclist
    python3 scripts/cyclist_strike.py --strike rear     # 40 km/h into a cyclist ahead
    python3 scripts/cyclist_strike.py --alone bicycle   # the bicycle alone at 5 m/s, 3 s
    python3 scripts/cyclist_strike.py --alone cyclist   # the cyclist alone at 15 km/h, 1 s

A strike: soft contacts between the car and every body of the cyclist (the rider's segments
and the bicycle's bodies; 1e5 N/m, damping ratio 0.5, friction 0.3, normal "volume"), 0.2 ms
steps, the car braking at the friction limit from t = 0, the cyclist riding at 15 km/h; its
nearest point 5 cm ahead of the car's front. Prints each body's first contact with the car
(crashsim.analysis.pedestrian.segment_contacts on the rider; the bicycle's from the contact
log), the head's contact, the rider's and the bicycle's travel from the first contact, the
throw distance, the joints' largest gap and the wall time.
"""

from __future__ import annotations

import argparse
import time

import crashsim as cs
import numpy as np
from crashsim.analysis.pedestrian import rest_of, segment_contacts
from crashsim.analysis.throw import first_contact_time, throw_distance
from crashsim.result import rotation_matrix


def joint_gap(scene: cs.Scene, result: cs.Result) -> float:
    """The largest distance (m) between a joint's anchor on its two bodies over the run."""
    worst = 0.0
    for j in scene.joints:
        (pa, _), (pb, _) = j.frames
        ta, tb = result.trajectory(j.vehicles[0]), result.trajectory(j.vehicles[1])
        wa = ta.position + np.einsum("nij,j->ni", rotation_matrix(ta.orientation), pa)
        wb = tb.position + np.einsum("nij,j->ni", rotation_matrix(tb.orientation), pb)
        worst = max(worst, float(np.linalg.norm(wa - wb, axis=1).max()))
    return worst


def roll_deg(result: cs.Result, name: str) -> np.ndarray:
    """A body's roll (deg): the angle of its y axis out of the horizontal, at every sample."""
    r = rotation_matrix(result.trajectory(name).orientation)
    return np.degrees(np.arcsin(np.clip(r[:, 2, 1], -1.0, 1.0)))


def alone(what: str, duration: float, speed: float) -> None:
    thing = cs.Bicycle() if what == "bicycle" else cs.Cyclist()
    scene = cs.Scene(ground=cs.Ground(friction=0.8))
    scene.add(thing, (0.0, 0.0), heading=0.0, velocity=(speed, 0.0, 0.0))
    t0 = time.perf_counter()
    result = scene.run(duration)
    wall = time.perf_counter() - t0
    frame = result.trajectory(f"{thing.name}/frame")
    roll = roll_deg(result, f"{thing.name}/frame")
    print(f"{what} alone at {speed:g} m/s for {duration:g} s: wall {wall:.2f} s")
    for t in np.arange(0.0, duration + 1e-9, 0.25):
        k = min(int(np.searchsorted(frame.t, t - 1e-9)), len(frame.t) - 1)
        line = (
            f"  t {frame.t[k]:.2f} s: frame x {frame.position[k, 0]:.3f} m, speed "
            f"{np.linalg.norm(frame.velocity[k, :2]):.3f} m/s, roll {roll[k]:+.2f} deg"
        )
        if what == "cyclist":
            head = result.trajectory(f"{thing.name}/head")
            line += f", head CG z {head.position[k, 2]:.3f} m"
        print(line)
    for limit in (1.0, 10.0, 45.0):
        over = np.flatnonzero(np.abs(roll) > limit)
        when = f"{frame.t[over[0]]:.2f} s" if over.size else "never"
        print(f"  |roll| over {limit:g} deg: {when}")
    wheel = result.trajectory(f"{thing.name}/rear_wheel")
    radius = (
        float(thing.bicycle.data["rear_wheel"]["radius"])
        if what == "cyclist"
        else float(thing.data["rear_wheel"]["radius"])
    )
    print(
        f"  rear wheel's CG lowest {wheel.position[:, 2].min():.4f} m (radius {radius:.4f}); "
        f"exchanges {len(result.impacts)}; joints' largest gap {joint_gap(scene, result):.1e} m"
    )


def strike(
    kind: str,
    speed_kmh: float,
    cyclist_kmh: float,
    duration: float,
    brake: float,
    stiffness: float,
    dt: float,
) -> None:
    car = cs.Vehicle.generate("sedan", name="car")
    cyclist = cs.Cyclist()
    scene = cs.Scene(ground=cs.Ground(friction=0.8), normal="volume", friction=0.3)
    front = float(car.mesh.bounds[1, 0] - car.cg[0])  # the car's CG to its front, m
    inputs = cs.DriverInputs(brake=[(0.0, brake), (duration, brake)]) if brake else None
    scene.add(car, (0.0, 0.0), heading=0.0, velocity=(cs.kmh(speed_kmh), 0.0, 0.0), inputs=inputs)
    v = cs.kmh(cyclist_kmh)
    bodies = np.vstack([b.mesh.bounds for b in cyclist.bicycle.bodies[:1]])
    if kind == "side":  # crossing the car's path towards +y, the bicycle's middle ahead of it
        half = float(np.abs(bodies[:, 1]).max())  # the frame's half width (handlebar)
        scene.add(cyclist, (front + 0.05 + half, 0.0), heading=np.pi / 2, velocity=(0.0, v, 0.0))
    else:  # riding ahead of the car, its rear wheel 5 cm ahead of the car's front
        back = cyclist.bicycle.wheelbase / 2.0 + float(cyclist.bicycle.data["rear_wheel"]["radius"])
        scene.add(cyclist, (front + 0.05 + back, 0.0), heading=0.0, velocity=(v, 0.0, 0.0))
    scene.soft_contact(car, cyclist, stiffness=stiffness, damping_ratio=0.5)
    t0 = time.perf_counter()
    result = scene.run(duration, dt=dt)
    wall = time.perf_counter() - t0
    print(
        f"{kind} strike: sedan at {speed_kmh:g} km/h (brake {brake:g}), cyclist at "
        f"{cyclist_kmh:g} km/h, soft contacts {stiffness:g} N/m, dt {dt * 1e3:g} ms: "
        f"{len(result.impacts)} exchanges, wall {wall:.2f} s for {duration:g} s"
    )
    contacts = segment_contacts(result, cyclist.rider, car)
    bike = segment_contacts(result, cyclist.bicycle, car)  # type: ignore[arg-type]
    for c in sorted([*contacts.values(), *bike.values()], key=lambda c: c.time)[:8]:
        wad = "-" if c.wrap_around is None else f"{c.wrap_around:.2f} m"
        print(
            f"    {c.segment:16s} first contact {c.time:.4f} s, {c.relative_speed:5.2f} m/s "
            f"relative to the car (peak {c.peak_relative_speed:5.2f}), wrap-around {wad}"
        )
    head = contacts.get("head")
    if head is None:
        print("  the head never touched the car")
    else:
        print(
            f"  head: first contact {head.time:.4f} s, wrap-around "
            f"{'-' if head.wrap_around is None else f'{head.wrap_around:.2f} m'}, "
            f"{head.relative_speed:.2f} m/s relative to the car (peak "
            f"{head.peak_relative_speed:.2f}), at model x {head.point[0]:.2f} z "
            f"{head.point[2]:.2f} m"
        )
    t_first = first_contact_time(result, "car", cyclist.rider)
    rest, speed = rest_of(result, cyclist.rider)
    frame = result.trajectory(f"{cyclist.name}/frame")
    k0 = int(np.searchsorted(frame.t, t_first))
    car_tr = result.trajectory("car")
    print(
        f"  rider: throw distance {throw_distance(result, 'car', cyclist.rider):.2f} m "
        f"(centre of mass from its first contact, {t_first:.4f} s, to {duration:g} s), then "
        f"{speed:.2f} m/s at z {rest[2]:.2f} m"
    )
    print(
        f"  bicycle frame: {np.linalg.norm(frame.position[-1, :2] - frame.position[k0, :2]):.2f}"
        f" m from the rider's first contact, then {np.linalg.norm(frame.velocity[-1]):.2f} m/s;"
        f" car at x {car_tr.position[-1, 0]:.2f} m, {np.linalg.norm(car_tr.velocity[-1]):.2f}"
        " m/s"
    )
    head_tr = result.trajectory(f"{cyclist.name}/head")
    print(
        f"  head CG highest {head_tr.position[:, 2].max():.2f} m; joints' largest gap "
        f"{joint_gap(scene, result):.1e} m"
    )


def main() -> None:
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--strike", choices=("side", "rear"), default=None)
    p.add_argument("--alone", choices=("bicycle", "cyclist"), default=None)
    p.add_argument("--speed", type=float, default=40.0, help="the car's, km/h")
    p.add_argument("--cyclist-speed", type=float, default=15.0, help="km/h")
    p.add_argument("--duration", type=float, default=None, help="s")
    p.add_argument("--brake", type=float, default=1.0, help="the car's braking, fraction of mu")
    p.add_argument("--soft", type=float, default=1e5, help="car-cyclist stiffness, N/m")
    p.add_argument("--dt", type=float, default=2e-4, help="the step, s")
    a = p.parse_args()
    if a.alone == "bicycle":
        alone("bicycle", a.duration or 3.0, 5.0)
    elif a.alone == "cyclist":
        alone("cyclist", a.duration or 1.0, cs.kmh(a.cyclist_speed))
    else:
        strike(
            a.strike or "side", a.speed, a.cyclist_speed, a.duration or 2.0, a.brake, a.soft, a.dt
        )


if __name__ == "__main__":
    main()
