"""Studies and fits with a pedestrian (docs/studies.md and docs/fitting.md, "Pedestrians"):
a Monte Carlo of the throw distance over the uncertain inputs, and the vehicle's impact
speed fitted back from the person's rest position and the head-strike point.

    python3 benches/pedestrian_studies.py --mc 100            # Monte Carlo, 100 variants
    python3 benches/pedestrian_studies.py --fit               # fit 45 km/h back from 35
    python3 benches/pedestrian_studies.py --fit --method global   # the global search
    python3 benches/pedestrian_studies.py --scan              # the evidence against speed
    python3 benches/pedestrian_studies.py --passive           # the passive moments' factor
    python3 benches/pedestrian_studies.py --mc 8 --duration 1.0   # a quick look

The scene is benches/pedestrian_throw.py's: a generated sedan braking at the friction limit
from t = 0 strikes a 1.75 m, 75 kg man's left side (his nearest point 5 cm ahead of its
foremost point); soft car-segment contacts 1e5 N/m, damping ratio 0.5, friction 0.3, normal
"volume"; tyre-road friction 0.8; 0.2 ms steps.

Monte Carlo at 40 km/h (``--mc N``, seed 1): the pedestrian-road friction
(``pedestrian.road_friction``) uniform(0.50, 0.70), the pose (``pedestrian.pose``) standing or
walking with equal weights, the stature (``pedestrian.height``) normal(1.756 m, 0.0686 m)
truncated to 1.55-1.95 m (ANSUR II men, docs/human.md); 4.0 s runs (the bench's length at
40 km/h and 0.45). Prints the throw distance's mean, standard deviation, 5th, 50th and 95th
percentiles, the rest position's, and the wall time per run.

Fit (``--fit``): the evidence is read off a run at 45 km/h (4.5 s): the person's rest position
(tolerance 0.25 m) and the head-strike point on the car (0.05 m per coordinate, the car's
model frame); ``cs.fit`` of ``car.speed`` within 25-70 km/h from 35 km/h, least squares
(``--method global``: differential evolution, then least squares), runs of the same length.
Prints the recovered speed, its 95 % range, the verdict, the runs and the wall time.

Passive moments (``--passive``): a sweep of ``pedestrian.passive_moments`` (the factor on the
leg's published passive joint moments: 0, 0.5, 1, 2 and 4) at 40 km/h, runs of 4.0 s; prints
per factor the throw distance, the rest position, the centre of mass's speed at the end, the
head's first contact (time, wrap-around distance, speed relative to the car) and the
trajectory type (crashsim.analysis.throw.trajectory_type, from the variant's own run).

Scan (``--scan``): a sweep of the speed over 30-60 km/h in steps of 1 km/h, runs of 4.5 s;
prints per speed the person's rest position, the head-strike point and the throw distance,
and the rest's scatter: each coordinate's residual from a straight line fitted over the
sweep (the scatter a fit's tolerance on the rest position must allow for).
"""

from __future__ import annotations

import argparse
import time
import warnings

import crashsim as cs
import numpy as np
from crashsim.studies import choice, normal, uniform
from crashsim.studies.evidence import HeadStrike, PedestrianRest
from crashsim.studies.pedestrians import columns_of
from crashsim.studies.scene_runs import run_one

STIFFNESS = 1e5  # N/m, the car-segment soft contact (docs/human.md, "Soft contacts")
DT = 2e-4  # s


def strike_scene(speed_kmh: float, pose: str = "walking") -> cs.Scene:
    """The sedan at ``speed_kmh`` braking from t = 0, the pedestrian's left side 5 cm ahead
    of it (benches/pedestrian_throw.py's scene)."""
    car = cs.Vehicle.generate("sedan", name="car")
    person = cs.Pedestrian(height=1.75, mass=75.0, sex="male", pose=pose)
    scene = cs.Scene(ground=cs.Ground(friction=0.8))
    ahead = float(car.mesh.bounds[1, 0] - car.cg[0])  # the CG to the front, m
    scene.add(car, (0.0, 0.0), heading=0.0, velocity=(cs.kmh(speed_kmh), 0.0, 0.0),
              inputs=cs.DriverInputs(brake=[(0.0, 1.0), (30.0, 1.0)]))
    left = float(person.vertices()[:, 1].max())  # his left side (body y), m
    scene.add(person, (ahead + 0.05 + left, 0.0), heading=np.pi / 2)
    for seg in person.segments:
        scene.contact(car, seg, depth_of_penetration=0.0, restitution=0.1, friction=0.3,
                      normal="volume")
    scene.soft_contact(car, person, stiffness=STIFFNESS, damping_ratio=0.5)
    return scene


def monte_carlo(n: int, duration: float, threads: int | None, dt: float = DT) -> None:
    scene = strike_scene(40.0)
    dists = {
        "pedestrian.road_friction": uniform(0.50, 0.70),
        "pedestrian.pose": choice([0, 1]),
        "pedestrian.height": normal(1.756, 0.0686, 1.55, 1.95),
    }
    t0 = time.perf_counter()
    study = cs.monte_carlo(scene, dists, n=n, seed=1, duration=duration, dt=dt,
                           threads=threads, progress=True)
    wall = time.perf_counter() - t0
    ok = study.ok
    print(f"{n} variants, {int(ok.sum())} ran, {len(study.errors)} failed; {duration:g} s runs "
          f"at {dt:g} s; wall {wall:.0f} s ({wall / n:.2f} s per variant on "
          f"{threads or 'all'} threads)")
    for e in study.errors:
        print(" ", e)
    throw = study["pedestrian.car.throw_distance"][ok]
    p5, p50, p95 = np.percentile(throw, [5, 50, 95])
    print(f"throw distance: mean {throw.mean():.2f} m, sd {throw.std(ddof=1):.2f} m, P5 {p5:.2f}, "
          f"P50 {p50:.2f}, P95 {p95:.2f} m (min {throw.min():.2f}, max {throw.max():.2f})")
    for col in ("pedestrian.rest_x", "pedestrian.final_x", "pedestrian.final_speed",
                "pedestrian.car.head_time", "pedestrian.car.head_wrap_around",
                "pedestrian.car.head_relative_speed"):
        v = study[col][ok]
        v = v[np.isfinite(v)]
        if v.size < 2:
            print(f"{col}: {v.size} finite")
            continue
        print(f"{col}: {v.size} finite, mean {v.mean():.3f}, sd {v.std(ddof=1):.3f}, P5 "
              f"{np.percentile(v, 5):.3f}, P95 {np.percentile(v, 95):.3f}")
    frame = study.frame[ok]
    for pose, name in ((0, "standing"), (1, "walking")):
        sel = frame["pedestrian.pose"] == pose
        t = frame.loc[sel, "pedestrian.car.throw_distance"]
        print(f"  {name}: {int(sel.sum())} runs, throw mean {t.mean():.2f} m, sd {t.std():.2f} m")
    r = np.corrcoef(frame["pedestrian.road_friction"],
                    frame["pedestrian.car.throw_distance"])[0, 1]
    print(f"  correlation of the throw distance with pedestrian.road_friction: {r:.2f}")


def passive(duration: float, dt: float = DT) -> None:
    """Each factor's variant (``Scene.with_``, as a study makes it) run once: its study row
    (columns_of) and its trajectory type from the same run."""
    from crashsim.analysis.throw import trajectory_type

    factors = [0.0, 0.5, 1.0, 2.0, 4.0]
    base = strike_scene(40.0)
    t0 = time.perf_counter()
    print(" factor  throw (m)  rest x (m)  rest y (m)  end speed (m/s)  head (s)  head WAD (m)"
          "  head rel. (m/s)  trajectory")
    for factor in factors:
        variant = base.with_({"pedestrian.passive_moments": factor})
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            result = run_one(variant, {"duration": duration, "dt": dt})
        row = columns_of(result, variant, 2)
        kind = trajectory_type(result, variant.vehicles[0], variant.pedestrians["pedestrian"])
        print(f"{factor:7.1f}  {row['pedestrian.car.throw_distance']:9.2f}  "
              f"{row['pedestrian.final_x']:10.2f}  {row['pedestrian.final_y']:10.2f}  "
              f"{row['pedestrian.final_speed']:15.3f}  {row['pedestrian.car.head_time']:8.4f}  "
              f"{row['pedestrian.car.head_wrap_around']:12.3f}  "
              f"{row['pedestrian.car.head_relative_speed']:15.2f}  {kind}")
    print(f"{len(factors)} runs of {duration:g} s at 40 km/h, one after the other; wall "
          f"{time.perf_counter() - t0:.0f} s")


def scan(duration: float, threads: int | None, dt: float = DT) -> None:
    from crashsim.studies import linspace

    t0 = time.perf_counter()
    study = cs.sweep(strike_scene(35.0), {"car.speed": linspace(cs.kmh(30.0), cs.kmh(60.0), 31)},
                     duration=duration, dt=dt, threads=threads, progress=True)  # fmt: skip
    wall = time.perf_counter() - t0
    f = study.frame
    kmh = f["car.speed"].to_numpy() * 3.6
    print(f"31 runs of {duration:g} s, {len(study.errors)} failed; wall {wall:.0f} s")
    print(" km/h  rest x (m)  rest y (m)  head x (m)  head z (m)  throw (m)")
    cols = ("pedestrian.final_x", "pedestrian.final_y", "pedestrian.car.head_x",
            "pedestrian.car.head_z", "pedestrian.car.throw_distance")  # fmt: skip
    for k in range(len(f)):
        print(f"{kmh[k]:5.0f}" + "".join(f"  {f[c].iloc[k]:10.3f}" for c in cols))
    for col in ("pedestrian.final_x", "pedestrian.final_y"):
        v = f[col].to_numpy()
        slope, icpt = np.polyfit(kmh, v, 1)
        res = v - (slope * kmh + icpt)
        print(f"{col}: {slope:+.3f} m per km/h; residual from the line sd {res.std(ddof=2):.3f} m, "
              f"largest {np.abs(res).max():.3f} m; between neighbours 1 km/h apart the change "
              f"less the line's: largest {np.abs(np.diff(res)).max():.3f} m")


def fit(duration: float, threads: int | None, method: str = "least_squares", dt: float = DT
        ) -> None:  # fmt: skip
    truth = strike_scene(45.0)
    t0 = time.perf_counter()
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        row = columns_of(run_one(truth, {"duration": duration, "dt": dt}), truth, 2)
    print(f"evidence run (45 km/h, {duration:g} s): {time.perf_counter() - t0:.1f} s wall; "
          f"rest ({row['pedestrian.final_x']:.3f}, {row['pedestrian.final_y']:.3f}) m at "
          f"{row['pedestrian.final_speed']:.3f} m/s; head strike at "
          f"{row['pedestrian.car.head_time']:.4f} s, point ({row['pedestrian.car.head_x']:.3f}, "
          f"{row['pedestrian.car.head_y']:.3f}, {row['pedestrian.car.head_z']:.3f}) m, WAD "
          f"{row['pedestrian.car.head_wrap_around']:.3f} m")
    evidence = [
        PedestrianRest("pedestrian", row["pedestrian.final_x"], row["pedestrian.final_y"], 0.25),
        HeadStrike("pedestrian", "car", row["pedestrian.car.head_x"],
                   row["pedestrian.car.head_y"], row["pedestrian.car.head_z"], 0.05),
    ]
    t0 = time.perf_counter()
    result = cs.fit(strike_scene(35.0), {"car.speed": (cs.kmh(25.0), cs.kmh(70.0))}, evidence,
                    method=method, until=None, duration=duration, dt=dt, samples=0, scan=False,
                    threads=threads, progress=True)
    wall = time.perf_counter() - t0
    print(result.summary())
    v = result.values["car.speed"]
    lo, hi = result.ranges["car.speed"] or (float("nan"), float("nan"))
    print(f"recovered {v * 3.6:.3f} km/h (true 45), sigma {result.sigma['car.speed'] * 3.6:.3f} "
          f"km/h, 95 % {lo * 3.6:.3f}-{hi * 3.6:.3f} km/h; {result.n_runs} runs, wall {wall:.0f} s")


def main() -> None:
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--mc", type=int, default=None, help="Monte Carlo variants")
    p.add_argument("--fit", action="store_true")
    p.add_argument("--method", choices=("least_squares", "global"), default="least_squares",
                   help="the fit's method (default least_squares)")
    p.add_argument("--scan", action="store_true", help="the evidence against the speed")
    p.add_argument("--passive", action="store_true",
                   help="a sweep of the factor on the leg's passive joint moments")
    p.add_argument("--duration", type=float, default=None,
                   help="s per run (default 4.0 for --mc, 4.5 for --fit and --scan)")
    p.add_argument("--threads", type=int, default=None)
    p.add_argument("--dt", type=float, default=DT,
                   help="s, the runs' step (default 0.2 ms; longer: sub-steps while a segment "
                        "presses on the car)")
    a = p.parse_args()
    if a.mc is None and not a.fit and not a.scan and not a.passive:
        p.error("give --mc N, --fit, --scan and/or --passive")
    if a.mc is not None:
        monte_carlo(a.mc, a.duration or 4.0, a.threads, a.dt)
    if a.scan:
        scan(a.duration or 4.5, a.threads, a.dt)
    if a.passive:
        passive(a.duration or 4.0, a.dt)
    if a.fit:
        fit(a.duration or 4.5, a.threads, a.method, a.dt)


if __name__ == "__main__":
    main()
