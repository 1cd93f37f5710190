"""The first multibody pedestrian struck from the side by a generated sedan (docs/human.md,
"The multibody pedestrian (first version)"): what the engine does with it, in figures.

    python3 scripts/pedestrian_strike.py                        # 40 km/h, dt_p 0, volume normal
    python3 scripts/pedestrian_strike.py --dtp 0.030 --normal horizontal   # the defaults
    python3 scripts/pedestrian_strike.py --stand 1.0             # the pedestrian alone

Prints the car-segment exchanges (first contact, exchange, closing speed), the exchanges
between the pedestrian's own segments, the head's first exchange with the car, the pelvis's
travel from first contact, the joints' largest gap and the wall time.
"""

from __future__ import annotations

import argparse
import time
import warnings
from collections import Counter

import crashsim as cs
import numpy as np
from crashsim.analysis.pedestrian import rest_of, segment_contacts
from crashsim.result import rotation_matrix


def joint_gap(scene: cs.Scene, result: cs.Result) -> float:
    """The largest distance (m) between a joint's anchor on its two bodies over the run."""
    worst = 0.0
    for j in scene.joints:
        (pa, _), (pb, _) = j.frames
        ta, tb = result.trajectory(j.vehicles[0]), result.trajectory(j.vehicles[1])
        for k in range(len(ta.t)):
            wa = ta.position[k] + rotation_matrix(ta.orientation[k]) @ pa
            wb = tb.position[k] + rotation_matrix(tb.orientation[k]) @ pb
            worst = max(worst, float(np.linalg.norm(wa - wb)))
    return worst


def stand(duration: float, pose: str) -> None:
    ped = cs.Pedestrian(pose=pose)
    scene = cs.Scene(ground=cs.Ground(friction=0.8))
    scene.add(ped, (0.0, 0.0), heading=0.0)
    t0 = time.perf_counter()
    result = scene.run(duration)
    wall = time.perf_counter() - t0
    head = result.trajectory(f"{ped.name}/head")
    print(f"{pose}, alone on the ground for {duration:g} s: wall {wall:.2f} s")
    for t in np.arange(0.0, duration + 1e-9, 0.1):
        k = min(int(np.searchsorted(head.t, t)), len(head.t) - 1)
        print(f"  t {t:.1f} s: head CG z {head.position[k, 2]:.3f} m")
    pairs = Counter(tuple(sorted(i.vehicles)) for i in result.impacts)
    print(f"  exchanges between its own segments: {len(result.impacts)} {dict(pairs)}")
    print(f"  limit stops (events): {len(result.joint_events)}")
    print(f"  joints' largest gap: {joint_gap(scene, result):.1e} m")


def strike(speed_kmh: float, dtp: float, normal: str, duration: float, pose: str,
           brake: float, soft: float | None = None, damping_ratio: float = 0.5,
           dt: float | None = None) -> None:
    car = cs.Vehicle.generate("sedan", name="car")
    ped = cs.Pedestrian(pose=pose)
    scene = cs.Scene(ground=cs.Ground(friction=0.8))
    front = float(car.mesh.bounds[1, 0] - car.cg[0])  # the CG to the front, m
    # braking from the first contact (about 0.02 s after the start)
    inputs = cs.DriverInputs(brake=[(0.0, brake), (duration, brake)]) if brake else None
    scene.add(car, (0.0, 0.0), heading=0.0, velocity=(cs.kmh(speed_kmh), 0.0, 0.0),
              inputs=inputs)
    # facing across the car's path (+y), its left side 5 cm from the bumper
    scene.add(ped, (front + 0.2, 0.0), heading=np.pi / 2)
    for seg in ped.segments:
        scene.contact(car, seg, depth_of_penetration=dtp, restitution=0.1, friction=0.3,
                      normal=None if normal == "horizontal" else normal)
    if soft is not None:
        scene.soft_contact(car, ped, stiffness=soft, damping_ratio=damping_ratio)
    t0 = time.perf_counter()
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", cs.DepthOfPenetrationWarning)
        # (Scene.run takes a number: None means the engine's default step)
        result = scene.run(duration) if dt is None else scene.run(duration, dt=dt)
    wall = time.perf_counter() - t0
    if soft is not None:
        soft_report(scene, result, ped, car, speed_kmh, soft, damping_ratio, wall, duration)
        return
    print(f"sedan at {speed_kmh:g} km/h into a {pose} pedestrian, dt_p {dtp * 1e3:g} ms, normal "
          f"{normal}, brake {brake:g}: {len(scene.pairs())} pairs, wall {wall:.2f} s for "
          f"{duration:g} s")
    with_car = [i for i in result.impacts if "car" in i.vehicles]
    own = [i for i in result.impacts if "car" not in i.vehicles]
    first: dict[str, cs.Impact] = {}
    for i in with_car:
        seg = next(n for n in i.vehicles if n != "car").split("/")[1]
        first.setdefault(seg, i)
    print(f"  car-segment exchanges {len(with_car)} "
          f"({sum(i.secondary for i in with_car)} secondary); first of each segment:")
    for seg, i in sorted(first.items(), key=lambda kv: kv[1].time):
        print(f"    {seg:16s} first contact {i.first_contact_time:.4f} s, exchange "
              f"{i.time:.4f} s, closing {i.closing_speed:5.2f} m/s, centroid z "
              f"{i.centroid[2]:.2f} m")
    repeats = Counter(next(n for n in i.vehicles if n != "car").split("/")[1] for i in with_car)
    print(f"  exchanges per segment with the car: {dict(repeats.most_common())}")
    pairs = Counter(tuple(n.split("/")[1] for n in sorted(i.vehicles)) for i in own)
    print(f"  exchanges between its own segments {len(own)}: {dict(pairs.most_common(6))}")
    t_first = min(i.first_contact_time for i in with_car) if with_car else 0.0
    pelvis = result.trajectory(f"{ped.name}/pelvis")
    head = result.trajectory(f"{ped.name}/head")
    car_tr = result.trajectory("car")
    k0 = int(np.searchsorted(pelvis.t, t_first))
    travel = float(np.linalg.norm(pelvis.position[-1, :2] - pelvis.position[k0, :2]))
    print(f"  pelvis: {travel:.2f} m from first contact to {duration:g} s, then "
          f"{np.linalg.norm(pelvis.velocity[-1]):.2f} m/s at z {pelvis.position[-1, 2]:.2f} m;"
          f" car {np.linalg.norm(car_tr.velocity[-1]):.2f} m/s, its front "
          f"{car_tr.position[-1, 0] + front - pelvis.position[-1, 0]:+.2f} m from the pelvis")
    print(f"  head CG highest {head.position[:, 2].max():.2f} m, lowest "
          f"{head.position[:, 2].min():.2f} m")
    lowest = min(float(result.trajectory(s.name).position[:, 2].min()) for s in ped.segments)
    print(f"  lowest segment CG {lowest:.3f} m; limit stops {len(result.joint_events)}; joints' "
          f"largest gap {joint_gap(scene, result):.1e} m")


def soft_report(scene: cs.Scene, result: cs.Result, ped: cs.Pedestrian, car: cs.Vehicle,
                speed_kmh: float, stiffness: float, damping_ratio: float, wall: float,
                duration: float) -> None:
    """What a strike with soft car-segment contacts did: each segment's first contact
    (crashsim.analysis.pedestrian), the pelvis's travel, the person's end."""
    print(f"sedan at {speed_kmh:g} km/h, soft contacts {stiffness:g} N/m, damping ratio "
          f"{damping_ratio:g}: {len(result.impacts)} exchanges, wall {wall:.2f} s for "
          f"{duration:g} s")
    contacts = segment_contacts(result, ped, car)
    for c in contacts.values():
        wad = "-" if c.wrap_around is None else f"{c.wrap_around:.2f} m"
        print(f"    {c.segment:16s} first contact {c.time:.4f} s, {c.relative_speed:5.2f} m/s "
              f"relative to the car there (peak {c.peak_relative_speed:5.2f}), wrap-around {wad}")
    car_tr = result.trajectory("car")
    pelvis = result.trajectory(f"{ped.name}/pelvis")
    t0 = min((c.time for c in contacts.values()), default=0.0)
    k0 = int(np.searchsorted(pelvis.t, t0))
    travel = float(np.linalg.norm(pelvis.position[-1, :2] - pelvis.position[k0, :2]))
    rest, speed = rest_of(result, ped)
    print(f"  pelvis {travel:.2f} m from first contact to {duration:g} s; centre of mass at "
          f"({rest[0]:.2f}, {rest[1]:.2f}) m, {speed:.2f} m/s; car at x "
          f"{car_tr.position[-1, 0]:.2f} m, {np.linalg.norm(car_tr.velocity[-1]):.2f} m/s")
    head = result.trajectory(f"{ped.name}/head")
    print(f"  head CG highest {head.position[:, 2].max():.2f} m; joints' largest gap "
          f"{joint_gap(scene, result):.1e} m")


def main() -> None:
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--speed", type=float, default=40.0, help="km/h")
    p.add_argument("--dtp", type=float, default=0.0, help="car-segment depth of penetration, s")
    p.add_argument("--normal", default="volume", choices=("horizontal", "volume"))
    p.add_argument("--duration", type=float, default=2.5, help="s")
    p.add_argument("--pose", default="standing", choices=cs.human.pedestrian.POSES)
    p.add_argument("--brake", type=float, default=0.0, help="the car's braking, fraction of mu")
    p.add_argument("--stand", type=float, default=None, help="the pedestrian alone for this long")
    p.add_argument("--soft", type=float, default=None,
                   help="soft car-segment contacts of this stiffness, N/m (no timer, no exchange)")
    p.add_argument("--damping-ratio", type=float, default=0.5, help="of the soft contacts")
    p.add_argument("--dt", type=float, default=None, help="the step, s (the engine's: 1 ms)")
    a = p.parse_args()
    if a.stand is not None:
        stand(a.stand, a.pose)
    else:
        strike(a.speed, a.dtp, a.normal, a.duration, a.pose, a.brake, a.soft, a.damping_ratio,
               a.dt)


if __name__ == "__main__":
    main()
