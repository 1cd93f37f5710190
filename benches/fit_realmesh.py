"""The fit's speed with real meshes (crashsim issue 13; docs/fitting.md): a 4-unknown fit of a
two-car case with 20k-triangle meshes, both cars run to rest, on this machine's cores.

The case: two generated sedans (``crashsim.vehicles.generator``, the "sedan" preset at
resolution 1.0 subdivided once: 21,440 triangles each, the 20k mesh of
benches/compare_peers.py) on the class's wheels and tyres, every wheel locked at the car's
first exchange (as examples/runout-sedan-into-suv.toml); red at 13.4 m/s (30 mph) heading
3 deg into the left side of blue, which crosses at 5 m/s heading 95 deg; dry asphalt (0.8);
depth of penetration 30 ms, restitution 0.1, friction 0.6; steps of 1 ms, until rest. The
evidence, from the true run: both cars' rest positions (tolerance 0.2 m) and headings (2 deg)
and their first exchange's EDR delta-V (0.5 m/s): the batch's columns, so every candidate
runs through the batch engine. The unknowns: both speeds and headings, bounds about
[0.65, 1.35] x the speeds and +-10 deg; the local least-squares solve (method
"least_squares") from speeds 20 % off and headings 5 deg off, then its 95 % ranges (the
Jacobian's and the fit's 200 importance samples, ``--samples``) and its scan: the whole
default fit.

    python benches/fit_realmesh.py                 # 3 fits; the median wall time
    python benches/fit_realmesh.py --repeats 1 --samples 0   # without the sampling
    python benches/fit_realmesh.py --repeats 1 --method global

Prints each fit's wall time, runs and recovery errors (speeds in %, headings in deg), the
median, and the load average before and after (the machine is shared).
"""

from __future__ import annotations

import argparse
import math
import os
import statistics
import sys
import time

import crashsim as cs
import numpy as np
from crashsim.studies.evidence import EDRDeltaV, RestHeading, RestPosition

TRUTH = {
    "red.speed": 13.41,  # m/s (30 mph)
    "blue.speed": 5.0,
    "red.heading": math.radians(3.0),  # rad
    "blue.heading": math.radians(95.0),
}
BOUNDS = {
    "red.speed": (9.0, 18.0),  # m/s
    "blue.speed": (3.2, 6.8),
    "red.heading": (math.radians(-7.0), math.radians(13.0)),  # rad
    "blue.heading": (math.radians(85.0), math.radians(105.0)),
}
START = {  # speeds 20 % off, headings 5 deg off
    "red.speed": 1.2 * TRUTH["red.speed"],
    "blue.speed": 0.8 * TRUTH["blue.speed"],
    "red.heading": TRUTH["red.heading"] - math.radians(5.0),
    "blue.heading": TRUTH["blue.heading"] + math.radians(5.0),
}
TOL_POS, TOL_HEADING, TOL_DV = 0.2, math.radians(2.0), 0.5  # m, rad, m/s
DT, MAX_DURATION = 1e-3, 20.0  # s


def sedan_mesh() -> object:
    """The 20k sedan body (trimesh, model frame)."""
    from crashsim.vehicles.generator import body_params, default_dims, generate_body

    return generate_body(body_params("sedan", **default_dims("sedan")), 1.0).subdivide()


def case() -> tuple[cs.Scene, int]:
    """The scene at the truth and the triangles per car."""
    mesh = sedan_mesh()
    cls = cs.Vehicle.generate("sedan")
    scene = cs.Scene(depth_of_penetration=0.03, restitution=0.1, friction=0.6,
                     ground=cs.Ground(friction=0.8))  # fmt: skip
    length, width = float(mesh.extents[0]), float(mesh.extents[1])
    nose = length / 2.0 - float(cls.cg[0])
    lock = cs.DriverInputs(wheel_states=[("all", "locked", "exchange 1")])
    for name, xy, heading, speed in (
        ("red", (-width / 2.0 - nose - 0.5, 0.3), TRUTH["red.heading"], TRUTH["red.speed"]),
        ("blue", (0.0, 0.0), TRUTH["blue.heading"], TRUTH["blue.speed"]),
    ):
        car = cs.Vehicle(mesh, cls.mass, cls.cg, cls.inertia, name=name,
                         stiffness=cls.stiffness).with_wheels(cls.wheels)  # fmt: skip
        scene.add(car, xy, heading=heading, inputs=lock,
                  velocity=(speed * math.cos(heading), speed * math.sin(heading), 0.0))  # fmt: skip
    return scene, len(mesh.faces)


def evidence_of(result: cs.Result) -> list:
    out: list = []
    for n in ("red", "blue"):
        rest = result.rest(n)
        if rest is None:
            raise SystemExit(f"the true run did not bring {n} to rest in {MAX_DURATION} s")
        out.append(RestPosition(n, float(rest.position[0]), float(rest.position[1]), TOL_POS))
        out.append(RestHeading(n, float(rest.heading), TOL_HEADING))
        body = result.delta_v_body(result.impacts[0], n)  # ISO 8855: lateral + left
        out.append(EDRDeltaV(n, float(body[0]), -float(body[1]), TOL_DV))  # EDR: + right
    return out


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--repeats", type=int, default=3)
    ap.add_argument("--samples", type=int, default=None,
                    help="importance samples of the 95 %% ranges (default the fit's, 50 k = "
                    "200; 0: the Jacobian's only)")  # fmt: skip
    ap.add_argument("--threads", type=int, default=None)
    ap.add_argument("--method", choices=("least_squares", "global"), default="least_squares")
    ap.add_argument("--no-settled-stop", action="store_true",
                    help="the local solve without its stop once a Gauss-Newton step would "
                    "lower chi^2 by less than 0.001 (SETTLED_CHI2 = 0: as before 2026-11-29)")
    a = ap.parse_args()
    if a.no_settled_stop:
        from crashsim.studies.fit import solvers

        solvers.SETTLED_CHI2 = 0.0
    scene, triangles = case()
    t = time.monotonic()
    truth_run = scene.run(dt=DT, until="rest", max_duration=MAX_DURATION)
    one = time.monotonic() - t
    evidence = evidence_of(truth_run)
    print(f"two sedans of {triangles:,} triangles each; the true run: "
          f"{len(truth_run.impacts)} exchange(s), rest at {truth_run.rest('red').time:.2f} s "
          f"(red) and {truth_run.rest('blue').time:.2f} s (blue), {one:.2f} s wall; "
          f"{os.cpu_count()} cores", flush=True)  # fmt: skip
    times = []
    for rep in range(a.repeats):
        load0 = os.getloadavg()[0]
        t = time.monotonic()
        fit = cs.fit(scene, BOUNDS, evidence, start=START, dt=DT, max_duration=MAX_DURATION,
                     progress=False, samples=a.samples, method=a.method,
                     threads=a.threads)  # fmt: skip
        wall = time.monotonic() - t
        times.append(wall)
        err = []
        for k, v in TRUTH.items():
            if k.endswith("speed"):
                err.append(f"{k} {100 * (fit.values[k] / v - 1):+.3f} %")
            else:
                err.append(f"{k} {math.degrees(fit.values[k] - v):+.3f} deg")
        ranges = ", ".join(
            f"{k} {v[0]:.4g}..{v[1]:.4g}" if v else f"{k} {fit.verdict.range_note(k)}"
            for k, v in fit.ranges.items()
        )
        print(f"fit {rep + 1}: {wall:.1f} s, {fit.n_runs} runs, chi2 {fit.objective:.3g} "
              f"({fit.verdict.status}); "
              f"errors {', '.join(err)}; load average {load0:.2f} -> "
              f"{os.getloadavg()[0]:.2f}", flush=True)  # fmt: skip
        print(f"   95 % ranges (Jacobian): {ranges}", flush=True)
        if fit.samples is not None:
            print(f"   sampling: {len(fit.samples.x)} candidates, effective size "
                  f"{fit.samples.ess:.0f}", flush=True)  # fmt: skip
    print(f"median wall time {statistics.median(times):.1f} s over {len(times)} fit(s) "
          f"(target: under 60 s); load average now "
          f"{', '.join(f'{v:.2f}' for v in os.getloadavg())}")  # fmt: skip
    return 0 if np.isfinite(times).all() else 1


if __name__ == "__main__":
    sys.exit(main())
