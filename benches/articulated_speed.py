"""Jointed vehicles against free ones (issue 21, "Speed"): the wall time per simulated second
of runs on the ground with joints and of the same bodies unjoined, side by side in one
process, and the batch's scaling on 2 threads with a joint. The goal: an articulated vehicle
costs at most 2x the same number of free vehicles per simulated second; the batch keeps its
scaling on 2 cores.

    python3 benches/articulated_speed.py            # 15 repeats, batches of 32: 40-55 s
    python3 benches/articulated_speed.py --quick    # a smoke run: a few seconds
    python3 benches/articulated_speed.py --only runs --repeats 31

1. **Runs** (`Scene.run(2.0)` at 1 ms steps, the history recorded as a user's run records
   it; world building included, 0.1 ms of it). Each case is a free scene and a joined one:
   - two generated sedans at 15 m/s, the front one braking at 0.3 (tests/test_joints.py's
     `_towed`): free, side by side 10 m apart (they never touch), against the second towed
     by the first on a spherical joint at the middle of a 0.6 m gap (the bar);
   - three: the car and two towed sedans, two joints, against three sedans 10 m apart;
   - a chain of 20 boxes (0.3 x 0.05 x 0.05 m, 1 kg) hanging from the world 50 m up,
     released 0.3 rad below the horizontal, each joined to the one before by a spherical
     joint at their shared end (the first to the world), against the same 20 boxes falling
     free, each moved 0.1 m further along y (they never touch).
   Each repeat runs every scene once, free and joined alternating which goes first; a figure
   is the median over the repeats, a ratio the ratio of the medians, its range the
   per-repeat ratios. Garbage collection is off while timing. Before timing, each scene is
   run once and checked: no contact and no impact in any of them.
2. **Kinds**: the towed pair with each kind of joint at the bar (spherical, revolute about
   the vertical, fifth wheel, fixed) against the free pair, runs as in 1: a spherical
   joint's angles (a swing and a twist) against the others' (atan2), and 3 to 6 rows.
3. **Batch** (`crashsim.batch.run_batch`, no history): the towed pair and the free pair over
   n variants of the ground's tyre friction (0.5-1.0, drawn with a seed: an override that
   keeps the joint's frames where they are; a position or velocity override moving one
   jointed body alone is refused by the engine, variant by variant), each 2 s at 1 ms, on 1
   and 2 threads (alternating): variants per minute, the 2-thread speed-up and the CPU per
   variant summed over the pool's threads (equal on 1 and 2 threads: nothing serial).

The machine is shared: compare the ratios (both sides of one see the same load), not the
absolute times; the load average is printed at the start and the end.
Results: benches/README.md ("Jointed vehicles against free ones").
"""

from __future__ import annotations

import argparse
import gc
import math
import os
import statistics
import time
from collections.abc import Callable
from typing import Any

import crashsim as cs
import numpy as np
from crashsim.batch import run_batch
from machine import describe

DURATION = 2.0  # s
DT = 1e-3  # s
SPEED = 15.0  # m/s
BRAKE = 0.3  # the front car's brake (fraction of the friction)
GAP = 0.6  # m between bumpers, the bar's length
APART = 10.0  # m between free vehicles side by side
GOAL = 2.0  # joined / free per simulated second, at most

LINKS = 20
LINK = 0.3  # m, a link's length
HIGH = 50.0  # m, the chain's pivot above the ground
TILT = 0.3  # rad below the horizontal at the start


def train(units: int, joined: bool, kind: str = "spherical") -> cs.Scene:
    """``units`` generated sedans at SPEED, the first braking: nose to tail, each towing the
    next on a joint of ``kind`` halfway across the GAP (``joined``; its axes the car's), or
    side by side APART m."""
    cars = [cs.Vehicle.generate("sedan", name=n) for n in ("car", "towed", "towed2")[:units]]
    lo, hi = cars[0].mesh.bounds - cars[0].cg
    pitch = lo[0] - GAP - hi[0]  # m, from one CG to the next (< 0: behind)
    scene = cs.Scene(ground=cs.Ground(friction=0.8))
    for k, car in enumerate(cars):
        inputs = cs.DriverInputs(brake=BRAKE) if k == 0 else None
        where = (k * pitch, 0.0) if joined else (0.0, k * APART)
        scene.add(car, where, heading=0.0, velocity=(SPEED, 0.0, 0.0), inputs=inputs)
    if joined:
        for k in range(1, units):
            x = (k - 1) * pitch + lo[0] - GAP / 2
            scene.join(cars[k - 1], cars[k], at=(x, 0.0, 0.5), kind=kind, name=f"bar{k}")
    return scene


def chain(joined: bool) -> cs.Scene:
    """LINKS boxes end to end from (0, 0, HIGH), TILT rad below the horizontal along +x:
    joined end to end (the first to the world), or free and LINKS apart along y."""
    scene = cs.Scene(ground=cs.Ground())
    along = np.array([math.cos(TILT), 0.0, -math.sin(TILT)])
    pivot = np.array([0.0, 0.0, HIGH])
    q = (math.cos(TILT / 2), 0.0, math.sin(TILT / 2), 0.0)  # body x along `along`
    for k in range(LINKS):
        centre = pivot + along * LINK * (k + 0.5)
        if not joined:
            centre += (0.0, 0.1 * k, 0.0)
        box = cs.Vehicle.box(LINK, 0.05, 0.05, mass=1.0, name=f"link{k}")
        scene.add(box, centre, orientation=q)
    if joined:
        scene.join("link0", at=pivot)
        for k in range(1, LINKS):
            scene.join(f"link{k - 1}", f"link{k}", at=pivot + along * LINK * k)
    return scene


def timed(f: Callable[[], Any]) -> tuple[float, float]:
    """(wall s, CPU s of every thread of this process) of one call."""
    t0, c0 = time.perf_counter(), time.process_time()
    f()
    return time.perf_counter() - t0, time.process_time() - c0


def ratio_of(a: list[float], b: list[float]) -> tuple[float, float, float]:
    """median(a) / median(b), and the range of the per-repeat ratios."""
    per = [x / y for x, y in zip(a, b, strict=True)]
    return statistics.median(a) / statistics.median(b), min(per), max(per)


def runs(repeats: int, duration: float, with_chain: bool) -> list[str]:
    cases = {
        "two sedans: towed on a bar (1 joint)": (train(2, False), train(2, True)),
        "three sedans: car + 2 towed (2 joints)": (train(3, False), train(3, True)),
    }
    if with_chain:
        cases[f"{LINKS} boxes: a hanging chain ({LINKS} joints)"] = (chain(False), chain(True))
    for name, pair in cases.items():
        for scene in pair:
            r = scene.run(duration, DT)
            assert not r.contacts and not r.impacts, (name, r.contacts[:2], r.impacts[:2])
    times = {name: ([], []) for name in cases}  # per case: free, joined (s per run)
    gc.collect()
    gc.disable()
    try:
        for rep in range(repeats):
            for name, pair in cases.items():
                order = (0, 1) if rep % 2 == 0 else (1, 0)
                for side in order:
                    t0 = time.perf_counter()
                    pair[side].run(duration, DT)
                    times[name][side].append(time.perf_counter() - t0)
    finally:
        gc.enable()
    lines = [
        f"runs of {duration:g} s at {DT * 1e3:g} ms steps (Scene.run, history recorded), median "
        f"of {repeats}, free and joined interleaved; ratio = joined / free [per-repeat range]",
        f"  {'case':42s} {'free':>10s} {'joined':>10s}  {'ratio':>5s} {'range':14s} goal",
        f"  {'':42s} {'ms per s':>10s} {'ms per s':>10s}",
    ]
    for name, (free, joined) in times.items():
        r, lo, hi = ratio_of(joined, free)
        verdict = "met" if r <= GOAL else "MISSED"
        lines.append(
            f"  {name:42s} {statistics.median(free) / duration * 1e3:10.2f} "
            f"{statistics.median(joined) / duration * 1e3:10.2f}  {r:5.2f} "
            f"[{lo:.2f}, {hi:.2f}]  <= {GOAL:g}: {verdict}"
        )
    return lines


def kinds(repeats: int, duration: float) -> list[str]:
    """The towed pair with each kind of joint (the hitch's axes the car's: a revolute one
    turns about the vertical), against the free pair, interleaved: what the kind's rows and
    angles cost (a spherical joint's angles are a swing and a twist, the others' atan2)."""
    scenes = {"free": train(2, False)}
    for kind in ("spherical", "revolute", "fifth_wheel", "fixed"):
        scenes[kind] = train(2, True, kind)
    for name, scene in scenes.items():
        r = scene.run(duration, DT)
        assert not r.contacts and not r.impacts, (name, r.contacts[:2], r.impacts[:2])
    times: dict[str, list[float]] = {name: [] for name in scenes}
    gc.collect()
    gc.disable()
    try:
        for rep in range(repeats):
            for name in list(scenes)[:: 1 if rep % 2 == 0 else -1]:
                t0 = time.perf_counter()
                scenes[name].run(duration, DT)
                times[name].append(time.perf_counter() - t0)
    finally:
        gc.enable()
    lines = [
        f"the towed pair by the joint's kind, runs as above, median of {repeats}; ratio = "
        "joined / free [per-repeat range]:",
    ]
    for name, ts in times.items():
        r, lo, hi = ratio_of(ts, times["free"])
        lines.append(
            f"  {name:12s} {statistics.median(ts) / duration * 1e3:8.2f} ms per s  "
            f"{r:5.2f} [{lo:.2f}, {hi:.2f}]"
        )
    return lines


def batches(n: int, repeats: int, duration: float) -> list[str]:
    rng = np.random.default_rng(0)
    overrides = {"ground.tyre_friction": rng.uniform(0.5, 1.0, n)}
    scenes = {"two sedans, free": train(2, False), "two sedans, towed": train(2, True)}

    def batch(scene: cs.Scene, threads: int) -> None:
        b = run_batch(scene, overrides, duration=duration, dt=DT, threads=threads)
        assert not b.errors, b.errors[:3]

    for scene in scenes.values():
        batch(scene, 1)  # warm-up and check
    wall: dict[tuple[str, int], list[float]] = {(s, t): [] for s in scenes for t in (1, 2)}
    cpu: dict[tuple[str, int], list[float]] = {key: [] for key in wall}
    gc.collect()
    gc.disable()
    try:
        for rep in range(repeats):
            names = list(scenes) if rep % 2 == 0 else list(scenes)[::-1]
            for name in names:
                for threads in (1, 2) if rep % 2 == 0 else (2, 1):
                    w, c = timed(lambda s=scenes[name], th=threads: batch(s, th))
                    wall[name, threads].append(w)
                    cpu[name, threads].append(c)
    finally:
        gc.enable()
    lines = [
        f"batch of {n} variants (ground.tyre_friction drawn in 0.5-1.0), {duration:g} s at "
        f"{DT * 1e3:g} ms, no history, median of {repeats}, 1 and 2 threads interleaved:",
        f"  {'scene':20s} {'1 thread':>22s} {'2 threads':>22s} {'speed-up [range]':>20s} "
        f"{'CPU per variant (1 / 2)':>25s}",
    ]
    for name in scenes:
        t1, t2 = statistics.median(wall[name, 1]), statistics.median(wall[name, 2])
        r, lo, hi = ratio_of(wall[name, 1], wall[name, 2])
        c1, c2 = statistics.median(cpu[name, 1]), statistics.median(cpu[name, 2])
        lines.append(
            f"  {name:20s} {t1 / n * 1e3:7.2f} ms ({60 * n / t1:6,.0f}/min) "
            f"{t2 / n * 1e3:7.2f} ms ({60 * n / t2:6,.0f}/min) {r:7.2f} x [{lo:.2f}, {hi:.2f}] "
            f"{c1 / n * 1e3:9.2f} / {c2 / n * 1e3:.2f} ms"
        )
    free, towed = (statistics.median(wall[s, 1]) for s in scenes)
    lines.append(f"  towed / free on 1 thread: {towed / free:.2f}")
    return lines


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--quick", action="store_true", help="a smoke run: 0.5 s runs, few repeats")
    ap.add_argument("--repeats", type=int, help="runs' repeats (default 15, --quick 3)")
    ap.add_argument("--n", type=int, help="variants per batch (default 32, --quick 4)")
    ap.add_argument("--only", default="runs,kinds,batch", help="runs, kinds, batch")
    ap.add_argument("--no-chain", action="store_true", help="leave the 20-link chain out")
    a = ap.parse_args()
    duration = 0.5 if a.quick else DURATION
    repeats = a.repeats or (3 if a.quick else 15)
    n = a.n or (4 if a.quick else 32)
    print("jointed vehicles against free ones: benches/articulated_speed.py")
    print(f"machine: {describe()}")
    print(f"load average at start: {os.getloadavg()[0]:.2f}")
    parts = {
        "runs": lambda: runs(repeats, duration, not a.no_chain),
        "kinds": lambda: kinds(repeats, duration),
        "batch": lambda: batches(n, 1 if a.quick else 7, duration),
    }
    for name in a.only.split(","):
        print()
        for line in parts[name.strip()]():
            print(line, flush=True)
    print(f"\nload average at end: {os.getloadavg()[0]:.2f}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
