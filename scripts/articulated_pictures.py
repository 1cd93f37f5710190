"""The articulated-vehicle examples of docs/joints.md, with their pictures (issue 21).

1. A tractor and a laden box-van semitrailer at 80 km/h following a 250 m curve on a wet road
   (friction 0.35): as it is, and with the tractor's drive axles locked at 1 s (a jackknife).
2. A car towing a 1.3 t caravan at 100 km/h given a 2 deg, 0.4 s steering pulse: with the
   caravan's CG 0.40 m ahead of its axle (a nose load of 9.8 % of its weight) and 0.30 m
   behind it (a tail-heavy caravan lifting the ball by 7.3 %).
3. The jackknifing combination of 1 swinging into an oncoming car in the other lane.

Run from the repository: ``python scripts/articulated_pictures.py [--out docs/img]``; it prints
each figure it quotes in docs/joints.md and writes the PNGs there.
"""

from __future__ import annotations

import argparse
import math
from pathlib import Path

import crashsim as cs
import numpy as np
from matplotlib.figure import Figure

REPO = Path(__file__).resolve().parents[1]


def combination(name: str = "tractor") -> tuple[cs.Vehicle, cs.Vehicle]:
    """A 6x4 tractor and a laden tridem box-van semitrailer (dimensions: docs/joints.md)."""
    tractor = cs.tractor(
        mass=7500.0,
        wheelbase=3.9,
        tandem_spread=1.3,
        driven_axles=2,
        fifth_wheel_ahead=0.3,
        fifth_wheel_height=1.2,
        cg_to_front_axle=1.5,
        cg_height=1.0,
        track=2.0,
        radius=0.5,
        length=6.5,
        name=name,
    )
    semi = cs.Trailer.box(
        "semitrailer",
        length=13.6,
        width=2.5,
        height=2.7,
        mass=25000.0,
        ground_clearance=1.25,
        coupler=1.2,
        coupler_height=1.2,
        axles=[10.0, 11.3, 12.6],
        track=2.0,
        radius=0.5,
        cg_height=2.0,
        cg_from_front=7.0,
        name="semitrailer",
    )
    return tractor, semi


def curve_scene(lock_at: float | None, oncoming: bool = False) -> cs.Scene:
    tractor, semi = combination()
    radius, speed = 250.0, 80.0 / 3.6
    arc = np.linspace(0.0, 1.2, 400)
    path = np.c_[radius * np.sin(arc), radius * (1.0 - np.cos(arc))]
    locks = []
    if lock_at is not None:
        locks = [(w, "locked", lock_at) for w in tractor.wheels.names if w.startswith("drive")]
    inputs = cs.DriverInputs(path=path, wheel_states=locks)
    scene = cs.Scene(ground=cs.Ground(friction=0.35))
    # The trailer's front may strike the cab (collide): where a jackknife ends.
    scene.add(
        tractor,
        (0, 0),
        heading=0.0,
        velocity=(speed, 0, 0),
        inputs=inputs,
        trailers=[semi],
        coupling={"collide": True},
    )
    if oncoming:
        # In the other lane, 4 m outside the combination's path, 128 m along the curve,
        # driving back along it: where the trailer's swing reaches at about 3.5 s.
        car = cs.Vehicle.generate("sedan", name="oncoming")
        back = np.linspace(128.0 / radius, 0.0, 200)
        lane = np.c_[(radius + 4.0) * np.sin(back), radius - (radius + 4.0) * np.cos(back)]
        heading = back[0] + math.pi
        v = 60.0 / 3.6
        scene.add(
            car,
            tuple(lane[0]),
            heading=heading,
            velocity=(v * math.cos(heading), v * math.sin(heading), 0),
            inputs=cs.DriverInputs(path=lane),
        )
    return scene


def sway_scene(cg_from_front: float) -> tuple[cs.Scene, float]:
    car = cs.Vehicle.generate("sedan", name="car")
    rear = (car.mesh.bounds[0] - car.cg)[0]
    car = car.with_hitch(car.cg + [rear - 0.15, 0.0, 0.45 - car.cg[2]], "ball")
    caravan = cs.Trailer.box(
        "centre_axle",
        length=5.0,
        width=2.2,
        height=2.2,
        mass=1300.0,
        ground_clearance=0.45,
        coupler=1.3,
        coupler_height=0.45,
        axles=[2.8],
        track=1.8,
        radius=0.3,
        cg_height=1.0,
        cg_from_front=cg_from_front,
        name="caravan",
    )
    nose = caravan.wheels.coupling_load(caravan.mass) / (caravan.mass * 9.80665)
    speed = 100.0 / 3.6
    pulse = np.array([[0.5, 0.0], [0.7, math.radians(2.0)], [0.9, 0.0], [1.0, 0.0]])
    scene = cs.Scene(ground=cs.Ground(friction=0.9))
    scene.add(
        car,
        (0, 0),
        heading=0.0,
        velocity=(speed, 0, 0),
        inputs=cs.DriverInputs(steer=pulse),
        trailers=[caravan],
    )
    return scene, nose


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--out", type=Path, default=REPO / "docs" / "img")
    args = parser.parse_args()
    args.out.mkdir(parents=True, exist_ok=True)

    # 1. The jackknife.
    fig = Figure(figsize=(7, 4))
    ax = fig.add_subplot()
    for lock, label in ((None, "free rolling"), (1.0, "drive axles locked at 1 s")):
        result = curve_scene(lock).run(8.0, record_interval=0.01)
        art = np.degrees(result.joints["tractor-semitrailer"].angle("articulation"))
        ax.plot(result.t, art, label=label)
        at = [f"{art[np.searchsorted(result.t, t)]:.1f}" for t in (2, 3, 4)]
        print(f"jackknife, {label}: articulation at 2, 3, 4 s = {', '.join(at)} deg")
        if lock is not None:
            cs.plot_trajectories(result, args.out / "articulated-jackknife.png")
    ax.set_xlabel("time (s)")
    ax.set_ylabel("articulation (deg, trailer about the kingpin)")
    ax.set_title("Tractor-semitrailer at 80 km/h on a wet 250 m curve")
    ax.grid(True, alpha=0.3)
    ax.legend()
    fig.savefig(args.out / "articulated-jackknife-angle.png", dpi=110, bbox_inches="tight")

    # 2. The caravan's sway.
    fig = Figure(figsize=(7, 4))
    ax = fig.add_subplot()
    for cg in (2.4, 3.1):
        scene, nose = sway_scene(cg)
        result = scene.run(12.0, record_interval=0.01)
        art = np.degrees(result.joints["car-caravan"].angles[:, 2])
        label = f"nose load {100 * nose:+.1f} % of the caravan's weight"
        ax.plot(result.t, art, label=label)
        peaks = [np.abs(art[(result.t > a) & (result.t < a + 2)]).max() for a in (1, 3, 5, 7)]
        print(f"sway, {label}: largest |yaw| in 1-3, 3-5, 5-7, 7-9 s = {np.round(peaks, 2)} deg")
    ax.set_xlabel("time (s)")
    ax.set_ylabel("caravan yaw relative to the car (deg)")
    ax.set_title("Car and 1.3 t caravan at 100 km/h, a 2 deg steering pulse at 0.5 s")
    ax.grid(True, alpha=0.3)
    ax.legend()
    fig.savefig(args.out / "articulated-caravan-sway.png", dpi=110, bbox_inches="tight")

    # 3. The semitrailer swinging into an oncoming car.
    result = curve_scene(1.0, oncoming=True).run(8.0, record_interval=0.01)
    for imp in result.impacts:
        dv = {k: float(np.linalg.norm(v)) for k, v in imp.delta_v.items()}
        print(f"impact {imp.vehicles} at {imp.time:.3f} s: delta-V {dv} m/s")
    cs.plot_trajectories(result, args.out / "articulated-into-oncoming.png")


if __name__ == "__main__":
    main()
