"""What ``crashsim.fit`` returns for a set of cheap fits, written to a folder, so that a
refactoring of crashsim.studies.fit can be shown not to change it:

    python3 scripts/fit_fingerprint.py /tmp/before     # on the old code
    python3 scripts/fit_fingerprint.py /tmp/after      # on the new code
    diff -r /tmp/before /tmp/after                     # empty: nothing changed

The fits (seconds in all): a locked skid to rest (tests/test_fit.py's) by least squares with
the sampling and the scan, by the global search, with a tyre mark (each run a Result, on
threads), interrupted by its progress callback (Ctrl-C's path), and a pedestrian-free run of
fixed length; the module's uncertainty parts on tests/test_fit.py's linear stand-in
(_uncertainty, _jacobian, _covariance, _sample, _scan); and bad input (the FitError's type,
message and key). Each gives CASE.txt: ``to_dict()`` as JSON (every float written with
repr: the bits), ``repr``, ``summary()``, the SHA-256 of the covariance, the samples and the
scans' arrays. Normalised: the wall-clock time (``elapsed`` and the summary's "N runs, 1.5
s") becomes <t>; nothing else. The last line printed is a digest of the whole folder.
"""

from __future__ import annotations

import hashlib
import json
import math
import re
import sys
import time
from pathlib import Path
from typing import Any

import crashsim as cs
import numpy as np
from crashsim.studies import fit as fitmod
from crashsim.studies.evidence import RestHeading, RestPosition, TyreMark

DT, MAX_DURATION = 2e-3, 15.0  # s, as benches/fit_synthetic.py


def _car(name: str) -> cs.Vehicle:
    """benches/fit_synthetic.py's box car on wheels (1450 kg)."""
    return cs.Vehicle.box(4.5, 1.8, 1.25, mass=1450.0, name=name, cg_height=0.55,
                          ground_clearance=0.15).with_wheels(
        wheelbase=2.7, track=1.5, radius=0.3, cg_to_front_axle=1.2,
        spring_rates=30e3, damping=2.5e3,
    )  # fmt: skip


def _skid(speed: float = 15.0, heading: float = 0.1) -> cs.Scene:
    scene = cs.Scene(ground=cs.Ground(friction=0.7))
    scene.add(_car("red"), (0.0, 0.0), heading=heading,
              velocity=(speed * math.cos(heading), speed * math.sin(heading), 0.0),
              inputs=cs.DriverInputs(wheel_states=[("all", "locked", 0.0)]))  # fmt: skip
    return scene


def _evidence(scene: cs.Scene, mark: bool = False) -> list[Any]:
    truth = scene.run(until="rest", max_duration=MAX_DURATION, dt=DT)
    rest = truth.rest("red")
    items: list[Any] = [RestPosition("red", rest.position[0] + 0.1, rest.position[1], 0.2),
                        RestHeading("red", rest.heading, math.radians(2.0))]  # fmt: skip
    if mark:
        items.append(TyreMark("red", "FL", truth.wheel_path("red", "FL")[::50, :2], 0.1))
    return items


BOUNDS = {"red.speed": (10.0, 20.0), "red.heading": (-0.2, 0.4)}
RUN = {"dt": DT, "max_duration": MAX_DURATION, "progress": False}


def _hash(a: Any) -> str:
    return hashlib.sha256(np.ascontiguousarray(np.asarray(a, dtype=np.float64)).tobytes()
                          ).hexdigest()[:16]  # fmt: skip


def _bits(v: Any) -> Any:
    """JSON-able with every float as its repr (so the text holds the bits)."""
    if isinstance(v, dict):
        return {str(k): _bits(x) for k, x in v.items()}
    if isinstance(v, list | tuple):
        return [_bits(x) for x in v]
    if isinstance(v, float):
        return repr(v)
    return v


def _describe(f: Any) -> str:
    d = f.to_dict()
    d["elapsed"] = "<t>"
    lines = [repr(f), json.dumps(_bits(d), indent=1), "== summary", f.summary()]
    lines.append(f"covariance {None if f.covariance is None else _hash(f.covariance)}")
    if f.samples is not None:
        s = f.samples
        lines.append(f"samples x {_hash(s.x)} chi2 {_hash(s.chi2)} weight {_hash(s.weight)} "
                     f"ranges {_hash(s.ranges)} ess {s.ess!r}")  # fmt: skip
    for n, (g, c) in (f.scan or {}).items():
        lines.append(f"scan {n} {_hash(g)} {_hash(c)}")
    lines.append(f"extra {_bits(f.extra)}")
    text = "\n".join(lines) + "\n"
    return re.sub(r"( runs), [0-9.]+ s\b", r"\1, <t> s", text)


def least_squares() -> str:
    scene = _skid()
    return _describe(cs.fit(scene, BOUNDS, _evidence(scene), start={"red.speed": 12.0},
                            samples=40, scan_points=5, **RUN))  # fmt: skip


def global_search() -> str:
    scene = _skid()
    return _describe(cs.fit(scene, BOUNDS, _evidence(scene), method="global", popsize=4,
                            maxiter=3, patience=1, seed=3, samples=0, scan=False,
                            **RUN))  # fmt: skip


def tyre_mark() -> str:
    scene = _skid()
    return _describe(cs.fit(scene, BOUNDS, _evidence(scene, mark=True), threads=2, samples=8,
                            scan=False, max_nfev=4, **RUN))  # fmt: skip


def interrupted() -> str:
    scene = _skid()

    def progress(runs: int, best: float) -> None:
        if runs >= 10:
            raise KeyboardInterrupt

    run = dict(RUN, progress=progress)
    return _describe(cs.fit(scene, BOUNDS, _evidence(scene), samples=0, scan=False, **run))


def fixed_length() -> str:
    scene = _skid()
    truth = scene.run(duration=0.6, dt=DT)
    at = truth.trajectory("red").position[-1]
    items = [RestPosition("red", at[0], at[1] + 0.05, 0.2)]
    return _describe(cs.fit(scene, {"red.speed": (10.0, 20.0)}, items, until=None,
                            duration=0.6, dt=DT, progress=False, samples=6,
                            scan_points=3))  # fmt: skip


class _Linear:
    """tests/test_fit.py's stand-in: residuals A (x - x0) + jumps, in tolerances."""

    def __init__(self, a: np.ndarray, x0: np.ndarray, jump: float = 0.0) -> None:
        self.a, self.x0, self.jump, self.m = a, x0, jump, a.shape[0]

    def residuals(self, xs: np.ndarray) -> np.ndarray:
        d = np.atleast_2d(xs) - self.x0
        r = d @ self.a.T
        return r + self.jump * (np.floor(d[:, :1] / (0.003 * self.x0[0])) % 2 - 0.5)


def parts() -> str:
    a = np.array([[1.2, 0.3], [0.4, -2.0], [0.8, 0.5]]) / np.array([0.15, 0.02])
    x0 = np.array([15.0, 0.1])
    lo, hi = np.array([10.0, -0.2]), np.array([20.0, 0.4])
    prob = _Linear(a, x0, jump=0.2)
    cov, sigma = fitmod._uncertainty(prob, x0, lo, hi, 1e-2)
    u = (x0 - lo) / (hi - lo)
    jac = fitmod._jacobian(prob, u, lo, hi, 1e-3)
    cov2, naive = fitmod._covariance(jac / (hi - lo))
    s = fitmod._sample(_Linear(a, x0), x0, cov, lo, hi, 400, 7)
    assert s is not None
    scans, ranges = fitmod._scan(prob, ["a", "b"], x0, sigma, lo, hi, 7)
    return "\n".join([
        f"uncertainty {_hash(cov)} {_hash(sigma)} {sigma.tolist()!r}",
        f"jacobian {_hash(jac)} covariance {_hash(cov2)} {naive.tolist()!r}",
        f"sample {_hash(s.x)} {_hash(s.chi2)} {_hash(s.weight)} {s.ranges.tolist()!r} {s.ess!r}",
        *(f"scan {n} {_hash(g)} {_hash(c)} {ranges[n]!r}" for n, (g, c) in scans.items()),
        f"constants {fitmod.METHODS} {fitmod.STEP!r} {fitmod.CHI2_95!r} {fitmod.Z_95!r} "
        f"{fitmod.XTOL!r} {fitmod.FTOL!r} {fitmod.GTOL!r} {fitmod.JUMP!r} {fitmod.NU!r} "
        f"{fitmod.SPREAD!r}",
        "",
    ])  # fmt: skip


def bad_input() -> str:
    scene = _skid()
    ev = [RestPosition("red", 30.0, 1.0, 0.2)]
    cases: list[tuple[dict[str, Any], list[Any], dict[str, Any]]] = [
        ({"red.speed": (12.0, 12.0)}, ev, {}),
        ({"red.sped": (1.0, 2.0)}, ev, {}),
        (BOUNDS, [RestPosition("green", 0, 0, 0.2)], {}),
        (BOUNDS, [RestHeading("red", 0.1, 0.0)], {}),
        (BOUNDS, ev, {"start": {"red.speed": 100.0}}),
        (BOUNDS, ev, {"start": {"blue.speed": 1.0}}),
        (BOUNDS, ev, {"method": "newton"}),
        (BOUNDS, [], {}),
        (BOUNDS, ev, {"samples": -1}),
        (BOUNDS, ev, {"patience": 2.5}),
        (BOUNDS, ev, {"step": 0.5}),
        (BOUNDS, ev, {"dt": -1.0}),
        (BOUNDS, ev, {"seed": "x"}),
        (BOUNDS, ev, {"until": "stop"}),
        (BOUNDS, ev, {"until": None}),
        ({}, ev, {}),
        ({"red.speed": "fast"}, ev, {}),
    ]
    lines = []
    for bounds, items, kw in cases:
        try:
            cs.fit(scene, bounds, items, progress=False, **kw)
            lines.append(f"{kw}: no error")
        except Exception as e:  # noqa: BLE001 - the type is the point
            lines.append(f"{type(e).__name__} key={getattr(e, 'key', None)!r}: {e}")
    no_ground = cs.Scene()
    no_ground.add(_car("red"), (0.0, 0.0, 0.7), velocity=(10.0, 0.0, 0.0))
    try:
        cs.fit(no_ground, {"red.speed": (5.0, 15.0)}, ev, progress=False)
    except Exception as e:  # noqa: BLE001
        lines.append(f"{type(e).__name__}: {e}")
    return "\n".join(lines) + "\n"


CASES = {f.__name__: f for f in (least_squares, global_search, tyre_mark, interrupted,
                                 fixed_length, parts, bad_input)}  # fmt: skip


def main(out: Path, names: list[str]) -> None:
    out.mkdir(parents=True, exist_ok=True)
    for name in names:
        start = time.perf_counter()
        (out / f"{name}.txt").write_text(CASES[name](), encoding="utf-8")
        print(f"{name}: {time.perf_counter() - start:.1f} s")
    digest = hashlib.sha256()
    for p in sorted(out.glob("*.txt")):
        digest.update(p.name.encode() + b"\0" + p.read_bytes() + b"\0")
    print(f"digest of {len(names)} cases: {digest.hexdigest()[:16]}")


if __name__ == "__main__":
    if len(sys.argv) < 2:
        sys.exit("usage: fit_fingerprint.py OUTPUT_FOLDER [CASE ...]")
    main(Path(sys.argv[1]), sys.argv[2:] or list(CASES))
