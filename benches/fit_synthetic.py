"""Synthetic truth for cs.fit (docs/fitting.md): random two-car scenes on the ground run to
rest, evidence generated from a known run, fitted back.

    python benches/fit_synthetic.py recover [--n 10]       # recovery from starts 20 % off
    python benches/fit_synthetic.py calibrate [--n 100]    # coverage of the 95 % ranges
    python benches/fit_synthetic.py scan [--n 3]           # residuals' jumps along each unknown
    python benches/fit_synthetic.py picture --out docs/fitting-two-cars.png

The scenes: two box cars on wheels (body 0.15 m above the road), red into blue's side,
every wheel locked at the car's first exchange, run to rest (steps of 2 ms). The evidence:
both cars' rest positions (0.2 m) and headings (2 deg) and their first exchange's EDR
delta-V (0.5 m/s), the batch's columns; ``--items all`` adds the point of impact and the
speeds at separation (each run's Result).

recover: the impact speeds must come back within 0.5 % and the headings within 0.5 deg
(speeds start 20 % off, headings 5 deg off; ``--method global`` by default). calibrate: the
evidence gets Gaussian noise with the stated tolerance as its standard deviation, the fit
starts at the truth (least squares); the script counts the trials whose true values lie
inside the reported 95 % ranges, the Jacobian's and the sampling's (each unknown, and all
four at once, which four independent 95 % ranges do in about 81 % of trials).
tests/test_fit.py imports case() from here.
"""

from __future__ import annotations

import argparse
import math
import sys
import time

import crashsim as cs
import numpy as np
from crashsim.studies.evidence import (
    EDRDeltaV,
    ImpactPoint,
    PostImpactSpeed,
    RestHeading,
    RestPosition,
)

UNKNOWNS = ("red.speed", "blue.speed", "red.heading", "blue.heading")
TOL_POS, TOL_HEADING, TOL_DV = 0.2, math.radians(2.0), 0.5  # m, rad, m/s
TOL_POI, TOL_SPEED = 0.3, 0.3  # m, m/s
DT, MAX_DURATION = 2e-3, 15.0  # s


def _car(name: str, mass: float) -> cs.Vehicle:
    """A box car on wheels: body from 0.15 m to 1.4 m above the road, CG 0.55 m up."""
    return cs.Vehicle.box(4.5, 1.8, 1.25, mass=mass, name=name, cg_height=0.55,
                          ground_clearance=0.15).with_wheels(
        wheelbase=2.7, track=1.5, radius=0.3, cg_to_front_axle=1.2,
        spring_rates=30e3, damping=2.5e3,
    )  # fmt: skip


def case(seed: int) -> tuple[cs.Scene, dict[str, float], dict[str, tuple[float, float]]]:
    """A random two-car side impact on the ground: the scene at the truth, the true values
    {path: SI} and bounds around them (not centred on the truth)."""
    rng = np.random.default_rng(seed)
    truth = {
        "red.speed": float(rng.uniform(10.0, 18.0)),  # m/s
        "blue.speed": float(rng.uniform(4.0, 10.0)),
        "red.heading": float(np.radians(rng.uniform(-8.0, 8.0))),  # rad
        "blue.heading": float(np.pi / 2 + np.radians(rng.uniform(-8.0, 8.0))),
    }
    scene = cs.Scene(ground=cs.Ground(friction=0.7), restitution=0.1, friction=0.4,
                     depth_of_penetration=0.03)  # fmt: skip
    y0 = float(rng.uniform(-0.8, 0.8))  # m: where red meets blue's side
    locked = cs.DriverInputs(wheel_states=[("all", "locked", "exchange 1")])
    scene.add(_car("red", float(rng.uniform(1200, 1700))), (-3.9, y0), heading=truth["red.heading"],
              velocity=(truth["red.speed"] * math.cos(truth["red.heading"]),
                        truth["red.speed"] * math.sin(truth["red.heading"]), 0.0),
              inputs=locked)  # fmt: skip
    hb = truth["blue.heading"]
    scene.add(_car("blue", float(rng.uniform(1200, 1700))), (0.0, 0.0), heading=hb,
              velocity=(truth["blue.speed"] * math.cos(hb), truth["blue.speed"] * math.sin(hb),
                        0.0), inputs=locked)  # fmt: skip
    bounds = {}
    for k, v in truth.items():
        if k.endswith("speed"):
            bounds[k] = (v * float(rng.uniform(0.6, 0.7)), v * float(rng.uniform(1.3, 1.4)))
        else:
            bounds[k] = (v - np.radians(rng.uniform(8, 12)), v + np.radians(rng.uniform(8, 12)))
    return scene, truth, bounds


def evidence_of(result: cs.Result, items: str = "batch") -> list:
    """Rest positions and headings of both cars and their first impact's EDR delta-V (the
    batch's columns: candidates run as batches); with ``items="all"`` also the point of
    impact and the speeds at separation (where the run separates), which need each run's
    Result."""
    out: list = []
    if items == "all":
        c = result.impacts[0].centroid
        out.append(ImpactPoint(float(c[0]), float(c[1]), TOL_POI))
    for n in ("red", "blue"):
        rest = result.rest(n)
        assert rest is not None
        out.append(RestPosition(n, float(rest.position[0]), float(rest.position[1]), TOL_POS))
        out.append(RestHeading(n, float(rest.heading), TOL_HEADING))
        body = result.delta_v_body(result.impacts[0], n)  # ISO 8855: lateral + left
        out.append(EDRDeltaV(n, float(body[0]), -float(body[1]), TOL_DV))  # EDR: + right
        t = result.impacts[0].time
        sep = next((s for s in result.separations(n) if s.time >= t), None)
        if items == "all" and sep is not None:
            out.append(PostImpactSpeed(n, float(sep.speed), TOL_SPEED))
    return out


def noisy(evidence: list, rng: np.random.Generator) -> list:
    """The evidence with Gaussian noise of its tolerance added to every value."""
    import dataclasses

    out = []
    for e in evidence:
        if isinstance(e, RestPosition):
            out.append(dataclasses.replace(e, x=e.x + rng.normal(0, e.tolerance),
                                           y=e.y + rng.normal(0, e.tolerance)))  # fmt: skip
        elif isinstance(e, RestHeading):
            out.append(dataclasses.replace(e, heading=e.heading + rng.normal(0, e.tolerance)))
        elif isinstance(e, ImpactPoint):
            out.append(dataclasses.replace(e, x=e.x + rng.normal(0, e.tolerance),
                                           y=e.y + rng.normal(0, e.tolerance)))  # fmt: skip
        elif isinstance(e, PostImpactSpeed):
            out.append(dataclasses.replace(e, speed=e.speed + rng.normal(0, e.tolerance)))
        else:
            out.append(dataclasses.replace(
                e, longitudinal=e.longitudinal + rng.normal(0, e.tolerance),
                lateral=e.lateral + rng.normal(0, e.tolerance)))  # fmt: skip
    return out


def start_of(truth: dict[str, float], rng: np.random.Generator) -> dict[str, float]:
    """Speeds 20 % off (up or down), headings 5 deg off."""
    out = {}
    for k, v in truth.items():
        sign = 1.0 if rng.random() < 0.5 else -1.0
        out[k] = v * (1 + 0.2 * sign) if k.endswith("speed") else v + sign * math.radians(5.0)
    return out


def truth_run(scene: cs.Scene) -> cs.Result:
    return scene.run(dt=DT, until="rest", max_duration=MAX_DURATION)


def recover(
    scene_seed: int, items: str = "batch", **kw
) -> tuple[cs.FitResult, dict[str, float]]:
    """Fit scene ``scene_seed`` back from its exact evidence, from a start off the truth
    (start_of); ``kw`` go to cs.fit."""
    scene, truth, bounds = case(scene_seed)
    evidence = evidence_of(truth_run(scene), items)
    start = start_of(truth, np.random.default_rng(1000 + scene_seed))
    fit = cs.fit(scene, bounds, evidence, start=start, dt=DT, max_duration=MAX_DURATION,
                 **{"progress": False, **kw})  # fmt: skip
    return fit, truth


def errors(fit: cs.FitResult, truth: dict[str, float]) -> dict[str, float]:
    """Speed errors in %, heading errors in deg."""
    return {k: (100 * (fit.values[k] / v - 1) if k.endswith("speed")
                else math.degrees(fit.values[k] - v)) for k, v in truth.items()}  # fmt: skip


def _scan(a: argparse.Namespace) -> int:
    """Each residual along each unknown through the truth, at fine steps (0.05 % of a speed,
    0.025 deg of a heading; 41 points), one batch per unknown: the largest jump of each
    residual (its largest second difference, in tolerances) and whether the number of
    exchanges changes along the way."""
    from crashsim.batch import run_batch
    from crashsim.studies import paths

    for s in range(a.seed, a.seed + (a.n or 3)):
        scene, truth, _ = case(s)
        evidence = evidence_of(truth_run(scene), "batch")
        labels = [f"{e.label}.{c}" if c else e.label for e in evidence for c in e.components]
        print(f"scene {s}:")
        for k in UNKNOWNS:
            if k.endswith("speed"):
                grid = truth[k] * (1 + np.linspace(-0.01, 0.01, 41))
            else:
                grid = truth[k] + np.radians(np.linspace(-0.5, 0.5, 41))
            values = {n: (grid if n == k else np.full(len(grid), v)) for n, v in truth.items()}
            br = run_batch(scene, paths.overrides(scene, values, n=len(grid)),
                           duration=MAX_DURATION, dt=DT, until="rest")  # fmt: skip
            r = np.array([
                np.concatenate([e.normalised(e.difference(e.measured(br.columns, i)))
                                for e in evidence])
                for i in range(len(grid))
            ])  # fmt: skip
            chi = np.einsum("ij,ij->i", r, r)
            d2 = np.abs(r[2:] - 2 * r[1:-1] + r[:-2]).max(axis=0)
            worst = np.argsort(-d2)[:2]
            impacts = sorted({int(v) for v in br.columns["n_impacts"]})
            print(f"  {k:<13} chi2 at the ends {chi[0]:6.3g} {chi[-1]:6.3g}; largest jumps: "
                  + ", ".join(f"{labels[j]} {d2[j]:.3f}" for j in worst)
                  + f" tolerances; exchanges {impacts}", flush=True)  # fmt: skip
    return 0


def _picture(a: argparse.Namespace) -> int:
    """docs/fitting.md's picture: scene ``--seed`` fitted from noisy evidence (trial 5000 +
    seed's noise) by the global method, with the samples and the scan."""
    scene, truth, bounds = case(a.seed)
    evidence = noisy(evidence_of(truth_run(scene), a.items), np.random.default_rng(5000 + a.seed))
    start = start_of(truth, np.random.default_rng(1000 + a.seed))
    fit = cs.fit(scene, bounds, evidence, start=start, dt=DT, max_duration=MAX_DURATION,
                 method=a.method or "global", samples=a.samples, seed=a.seed,
                 progress=False)  # fmt: skip
    print(fit.summary())
    print("truth: " + ", ".join(f"{k} {v:.5g}" for k, v in truth.items()))
    fit.plot(a.out)
    print(f"written {a.out}")
    return 0


def _recover(a: argparse.Namespace) -> int:
    n = a.n or 10
    worst_s = worst_h = 0.0
    ok = 0
    for s in range(a.seed, a.seed + n):
        t = time.monotonic()
        fit, truth = recover(s, scan=False, method=a.method, samples=0, items=a.items)
        e = errors(fit, truth)
        es = max(abs(e[k]) for k in e if k.endswith("speed"))
        eh = max(abs(e[k]) for k in e if k.endswith("heading"))
        worst_s, worst_h = max(worst_s, es), max(worst_h, eh)
        good = es <= 0.5 and eh <= 0.5
        ok += good
        print(f"scene {s}: speed error max {es:.4f} %, heading error max {eh:.4f} deg, "
              f"chi2 {fit.objective:.3g}, {fit.n_runs} runs, {time.monotonic() - t:.1f} s"
              f"{'' if good else '  FAIL'}", flush=True)  # fmt: skip
    print(f"{ok}/{n} recovered ({a.method}, evidence: {a.items}); worst speed error "
          f"{worst_s:.4f} %, worst heading error {worst_h:.4f} deg")  # fmt: skip
    return 0 if ok == n else 1


def _calibrate(a: argparse.Namespace) -> int:
    n = a.n or 100
    kinds = ("Jacobian", "sampling", "all at once")
    inside = {(w, k): 0 for w in kinds for k in UNKNOWNS}
    joint = dict.fromkeys(kinds, 0)
    verdicts: dict[str, int] = {}
    for trial in range(a.seed, a.seed + n):
        t = time.monotonic()
        scene, truth, bounds = case(trial % 10)
        rng = np.random.default_rng(5000 + trial)
        evidence = noisy(evidence_of(truth_run(scene), a.items), rng)
        fit = cs.fit(scene, bounds, evidence, start=truth, dt=DT, max_duration=MAX_DURATION,
                     progress=False, scan=False, method=a.method, samples=a.samples,
                     seed=trial)  # fmt: skip
        line = []
        for w, ranges in zip(
            kinds, (fit.ranges, fit.sample_ranges, fit.joint_ranges), strict=True
        ):
            if ranges is None:
                continue
            # a range the verdict withholds (None) holds nothing
            hits = {k: ranges[k] is not None and ranges[k][0] <= truth[k] <= ranges[k][1]
                    for k in UNKNOWNS}  # fmt: skip
            for k in UNKNOWNS:
                inside[w, k] += hits[k]
            joint[w] += all(hits.values())
            line.append(f"{w} {sum(hits.values())}/{len(hits)}")
        ess = f", ess {fit.samples.ess:.0f}" if fit.samples is not None else ""
        verdicts[fit.verdict.status] = verdicts.get(fit.verdict.status, 0) + 1
        print(f"trial {trial} (scene {trial % 10}): chi2 {fit.objective:.3g}, "
              f"{fit.verdict.status}, inside: "
              f"{', '.join(line)}; {fit.n_runs} runs{ess}, {time.monotonic() - t:.1f} s",
              flush=True)  # fmt: skip
    for w in kinds:
        if a.samples == 0 and w == "sampling":
            continue
        head = (f"{w}: true value inside its 95 % range: " if w != "all at once" else
                f"{w} (the box of the joint 95 % ellipsoid): true value inside its range: ")
        print(head + ", ".join(f"{k} {inside[w, k]}/{n}" for k in UNKNOWNS)
              + f"; all four at once {joint[w]}/{n}")  # fmt: skip
    print("verdicts: " + ", ".join(f"{k} {v}/{n}" for k, v in sorted(verdicts.items())))
    return 0


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("what", choices=("recover", "calibrate", "scan", "picture"))
    ap.add_argument("--n", type=int, default=None, help="scenes (recover) or trials")
    ap.add_argument("--seed", type=int, default=0, help="the first scene or trial")
    ap.add_argument("--method", choices=("global", "least_squares"), default=None,
                    help="default: global for recover, least_squares (from the truth) "
                    "for calibrate")  # fmt: skip
    ap.add_argument("--items", choices=("batch", "all"), default="batch",
                    help="evidence: the batch's columns (rest, EDR) or all (with the point "
                    "of impact and the speeds at separation: runs as Results)")  # fmt: skip
    ap.add_argument("--samples", type=int, default=None,
                    help="calibrate: candidates of the importance sampling (None: 50 k)")
    ap.add_argument("--out", default="fit.png", help="picture: the file written")
    ap.add_argument("--no-settled-stop", action="store_true",
                    help="the local solve without its stop once a Gauss-Newton step would "
                    "lower chi^2 by less than 0.001 (SETTLED_CHI2 = 0: as before 2026-11-29)")
    a = ap.parse_args()
    if a.no_settled_stop:
        from crashsim.studies.fit import solvers

        solvers.SETTLED_CHI2 = 0.0
    if a.what == "picture":
        return _picture(a)
    if a.what == "scan":
        return _scan(a)
    if a.what == "recover":
        a.method = a.method or "global"
        return _recover(a)
    a.method = a.method or "least_squares"
    return _calibrate(a)


if __name__ == "__main__":
    sys.exit(main())
