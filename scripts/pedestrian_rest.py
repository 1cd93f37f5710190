"""Does ``run(until="rest")`` end for a pedestrian? (docs/human.md, "Rest of a lying body")

    python3 scripts/pedestrian_rest.py            # four falls alone, four strikes
    python3 scripts/pedestrian_rest.py --alone    # the falls only (about 20 s of wall time)

Falls: a 1.75 m, 75 kg man alone on the road (friction 0.8), standing or walking, given a
push (0-1.5 m/s) at a heading. Strikes: the scene of benches/pedestrian_throw.py (a walking
man struck on his left side, soft contacts 1e5 N/m, 0.2 ms steps, the vehicle braking at the
friction limit). Each runs until rest, at most ``--max`` s. Prints per run when it ended,
whether every body came to rest, the throw distance (strikes) and the largest yaw rate and
speed of any segment at the end.
"""

from __future__ import annotations

import argparse
import sys
import time
import warnings
from pathlib import Path

import crashsim as cs
import numpy as np
from crashsim.analysis.throw import throw_distance

sys.path.insert(0, str(Path(__file__).resolve().parent.parent / "benches"))
import pedestrian_throw  # noqa: E402  (the strike's vehicles)

FALLS = (("standing", 0.0, 0.0), ("walking", 1.0, 0.0), ("walking", 1.5, 1.0),
         ("standing", 0.5, 2.0))  # pose, push m/s, heading rad
STRIKES = ((20.0, "sedan"), (40.0, "sedan"), (40.0, "suv"), (60.0, "van"))  # km/h, front


def fall(pose: str, push: float, heading: float) -> tuple[cs.Scene, cs.Pedestrian, float]:
    ped = cs.Pedestrian(pose=pose)
    scene = cs.Scene(ground=cs.Ground(friction=0.8), depth_of_penetration=0.0)
    scene.add(ped, (0.0, 0.0), heading=heading, velocity=(push, 0.0, 0.0))
    return scene, ped, 1e-3


def strike(kmh: float, front: str, longest: float) -> tuple[cs.Scene, cs.Pedestrian, float]:
    car = pedestrian_throw.vehicle(front)
    ped = cs.Pedestrian(pose="walking")
    scene = cs.Scene(ground=cs.Ground(friction=0.8))
    ahead = float(car.mesh.bounds[1, 0] - car.cg[0])
    scene.add(car, (0.0, 0.0), heading=0.0, velocity=(cs.kmh(kmh), 0.0, 0.0),
              inputs=cs.DriverInputs(brake=[(0.0, 1.0), (longest, 1.0)]))
    scene.add(ped, (ahead + 0.05 + float(ped.vertices()[:, 1].max()), 0.0), heading=np.pi / 2)
    for seg in ped.segments:
        scene.contact(car, seg, depth_of_penetration=0.0, restitution=0.1, friction=0.3,
                      normal="volume")
    scene.soft_contact(car, ped, stiffness=1e5, damping_ratio=0.5)
    return scene, ped, 2e-4


def report(label: str, scene: cs.Scene, ped: cs.Pedestrian, dt: float, longest: float,
           struck: bool) -> None:
    t0 = time.perf_counter()
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        result = scene.run(until="rest", max_duration=longest, dt=dt, record_interval=0.01)
    wall = time.perf_counter() - t0
    rest = not any(issubclass(w.category, cs.RestNotReachedWarning) for w in caught)
    end = result.trajectory(ped.segments[0].name).t[-1]
    yaw = max(abs(np.degrees(result.trajectory(s.name).angular_velocity[-1][2]))
              for s in ped.segments)
    speed = max(np.linalg.norm(result.trajectory(s.name).velocity[-1]) for s in ped.segments)
    throw = f"throw {throw_distance(result, 'car', ped):6.2f} m  " if struck else ""
    print(f"{label:34s} ended {end:6.2f} s  at rest {str(rest):5s}  {throw}largest yaw "
          f"{yaw:4.2f} deg/s  speed {speed * 1e3:4.1f} mm/s  wall {wall:5.1f} s")


def main() -> None:
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("--alone", action="store_true", help="the falls only")
    p.add_argument("--max", type=float, default=20.0, help="the longest run, s")
    args = p.parse_args()
    for pose, push, heading in FALLS:
        report(f"alone, {pose}, {push} m/s at {heading} rad", *fall(pose, push, heading),
               args.max, False)
    if not args.alone:
        for kmh, front in STRIKES:
            report(f"struck, {front} at {kmh:.0f} km/h", *strike(kmh, front, args.max),
                   args.max, True)


if __name__ == "__main__":
    main()
