"""One pedestrian strike against issue 22's speed goal: a strike with 3 s of contact, flight,
slide and rest in at most 50 ms of wall time on this machine, so that a Monte Carlo of 10,000
runs takes minutes.

    python3 benches/pedestrian_speed.py              # 5 repeats: about a minute
    python3 benches/pedestrian_speed.py --repeats 3 --no-fine

The strike is benches/pedestrian_studies.py's (and benches/pedestrian_throw.py's) at 40 km/h:
a generated sedan braking at the friction limit from t = 0 strikes a walking 1.75 m, 75 kg
man's left side; soft car-segment contacts (1e5 N/m, damping ratio 0.5, friction 0.3, normal
"volume"); tyre-road friction 0.8. Each run is ``Scene.run(until="rest", max_duration=...)``
as a user's run records it (every 2 ms), the scene's build into the engine included. Cases,
one after the other in each repeat (garbage collection off while timing):

- ``strike 3 s @ 1 ms``: 1 ms steps (a step is cut into sub-steps while a segment presses on
  the car, docs/human.md "Soft contacts"), at most 3 s: the goal's case;
- ``strike 1 s @ 1 ms``: the same run stopped at 1 s (the contact and the flight; the same
  bits as the first second of the 3 s run), so the 3 s run's cost splits into its first
  second and the two after it (the person sliding and lying);
- ``strike 3 s @ 0.2 ms``: the throw table's step (docs/human.md, "Throw distance"), unless
  ``--no-fine``;
- ``car alone 3 s @ 1 ms``: the same car braking with no one in its way, 3 s: the machine's
  pace at the moment, so that runs on a loaded machine can be compared by their ratio to it.

Prints each case's median wall time [least, most], its ms per simulated second, where the
run ended and whether the engine's rest test ended it ("-": a run of fixed length); the goal's
verdict (the 3 s strike at 1 ms, median, against 50 ms); and what a Monte Carlo of 10,000
such runs would take on one core and on two (at the batch's 2-thread speed-up,
benches/README.md "Batches").
Results: benches/README.md ("A pedestrian strike against the 50 ms goal").
"""

from __future__ import annotations

import argparse
import gc
import os
import statistics
import time
import warnings
from collections.abc import Callable
from dataclasses import dataclass

import crashsim as cs
from machine import describe
from pedestrian_studies import strike_scene

GOAL = 0.050  # s of wall time for a 3 s strike (issue 22)
SPEED_KMH = 40.0
RECORD = 2e-3  # s, the history's interval (as benches/pedestrian_throw.py records)
MC_RUNS = 10_000
TWO_THREAD_SPEEDUP = 1.97  # the batch's on 2 threads (benches/README.md, "Batches")


@dataclass
class Case:
    label: str
    simulated: float  # s, the run's longest
    make: Callable[[], Callable[[], cs.Result]]  # builds the scene, returns its run
    walls: list[float]
    until_rest: bool = True  # a run until rest (else of a fixed length)
    ended: float = float("nan")  # s simulated at the run's end
    at_rest: bool = False  # the engine's rest test ended the run


def strike_run(duration: float, dt: float) -> Callable[[], Callable[[], cs.Result]]:
    def make() -> Callable[[], cs.Result]:
        scene = strike_scene(SPEED_KMH)
        return lambda: scene.run(until="rest", max_duration=duration, dt=dt, record_interval=RECORD)

    return make


def car_run(duration: float) -> Callable[[], Callable[[], cs.Result]]:
    def make() -> Callable[[], cs.Result]:
        car = cs.Vehicle.generate("sedan", name="car")
        scene = cs.Scene(ground=cs.Ground(friction=0.8))
        scene.add(
            car,
            (0.0, 0.0),
            heading=0.0,
            velocity=(cs.kmh(SPEED_KMH), 0.0, 0.0),
            inputs=cs.DriverInputs(brake=[(0.0, 1.0), (30.0, 1.0)]),
        )
        return lambda: scene.run(duration, dt=1e-3, record_interval=RECORD)

    return make


def timed(case: Case) -> None:
    run = case.make()
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        gc.collect()
        gc.disable()
        try:
            t0 = time.perf_counter()
            result = run()
            case.walls.append(time.perf_counter() - t0)
        finally:
            gc.enable()
    case.ended = float(result.trajectory(result.vehicles[0]).t[-1])
    case.at_rest = case.until_rest and not any(
        issubclass(w.category, cs.RestNotReachedWarning) for w in caught
    )


def main() -> None:
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--repeats", type=int, default=5)
    p.add_argument("--no-fine", action="store_true", help="leave out the 0.2 ms case")
    a = p.parse_args()
    cases = [
        Case("strike 3 s @ 1 ms", 3.0, strike_run(3.0, 1e-3), []),
        Case("strike 1 s @ 1 ms", 1.0, strike_run(1.0, 1e-3), []),
        Case("car alone 3 s @ 1 ms", 3.0, car_run(3.0), [], until_rest=False),
    ]
    if not a.no_fine:
        cases.insert(2, Case("strike 3 s @ 0.2 ms", 3.0, strike_run(3.0, 2e-4), []))
    print("a pedestrian strike against the 50 ms goal: benches/pedestrian_speed.py")
    print(f"machine: {describe()}; load at start {os.getloadavg()}")
    for k in range(a.repeats):
        for case in cases if k % 2 == 0 else reversed(cases):
            timed(case)
    print(
        f"load at end {os.getloadavg()}; median of {a.repeats} repeats, cases alternating in order"
    )
    print(
        f"  {'case':24s} {'wall (ms)':>10s} {'[least, most]':>18s} {'ms per sim. s':>14s} "
        f"{'ended (s)':>10s} {'at rest':>8s}"
    )
    median = {}
    for case in cases:
        m = statistics.median(case.walls)
        median[case.label] = m
        print(
            f"  {case.label:24s} {m * 1e3:10.1f} [{min(case.walls) * 1e3:7.1f}, "
            f"{max(case.walls) * 1e3:7.1f}] {m * 1e3 / case.ended:14.1f} {case.ended:10.3f} "
            f"{('yes' if case.at_rest else 'no') if case.until_rest else '-':>8s}"
        )
    strike = median["strike 3 s @ 1 ms"]
    first = median["strike 1 s @ 1 ms"]
    car = median["car alone 3 s @ 1 ms"]
    print(
        f"  the 3 s strike: its first second {first * 1e3:.1f} ms, the rest "
        f"{(strike - first) * 1e3:.1f} ms; {strike / car:.1f} x the car alone"
    )
    verdict = "met" if strike <= GOAL else f"MISSED ({strike / GOAL:.1f} x the goal)"
    print(
        f"  goal: the 3 s strike at 1 ms in <= {GOAL * 1e3:.0f} ms: {strike * 1e3:.1f} ms, "
        f"{verdict}"
    )
    one = MC_RUNS * strike / 60.0
    print(
        f"  a Monte Carlo of {MC_RUNS:,} such runs: {one:.0f} min on one core, "
        f"{one / TWO_THREAD_SPEEDUP:.0f} min on two (at the batch's {TWO_THREAD_SPEEDUP} x)"
    )


if __name__ == "__main__":
    main()
