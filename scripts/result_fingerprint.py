"""Everything a crashsim Result gives of a few short runs, written to a folder and hashed, so
that a refactoring of crashsim.result can be shown not to change it:

    python3 scripts/result_fingerprint.py /tmp/before --pickle /tmp/pickles   # old code
    python3 scripts/result_fingerprint.py /tmp/after --unpickle /tmp/pickles  # new code
    diff -r /tmp/before /tmp/after                                            # empty

The last line printed is the sha256 of all the files (the same on both sides when nothing
changed). The runs (examples/*.toml scenes, cut short): a two-car impact without ground
(seed-90deg), a run-out to rest on a ground with wheels and tyre marks (runout-sedan-into-suv),
a car towing a car through a joint (towed-car), a tractor and semitrailer on its
fifth wheel (tractor-semitrailer-jackknife, 1.5 s), an obstacle impact on the ground
(runout-sedan-into-pole, 0.4 s) and a pedestrian strike with soft contacts
(pedestrian-sedan-40kmh, 0.05 s at dt 0.2 ms). Each case's file holds: ``to_dict`` with
trajectories, the rest states, separations, wheel records, wheel paths, centres and steering,
tyre marks, states between samples, state_before, pose and heading, impacts (every field,
impulse_on, speed_change, closing_speed, moving, to_dict), joint records and events, the
reprs, and the same again of the Result's pickle round trip. ``--pickle FOLDER`` also writes
each Result's pickle there; ``--unpickle FOLDER`` fingerprints those pickles (made by older
code) instead of pickling afresh, so that old pickles are shown to load to the same Result.
"""

from __future__ import annotations

import dataclasses
import hashlib
import pickle
import sys
from pathlib import Path
from typing import Any

import numpy as np
from crashsim.io.scenefile import load_scene
from crashsim.result import Result

ROOT = Path(__file__).resolve().parent.parent

# name: (example, run settings)
CASES: dict[str, tuple[str, dict[str, Any]]] = {
    "two-cars-no-ground": ("seed-90deg", {"duration": 0.3, "dt": 1e-3}),
    "runout-to-rest": (
        "runout-sedan-into-suv",
        {"until": "rest", "max_duration": 15.0, "dt": 1e-3, "record_interval": 0.01},
    ),
    "car-and-trailer": ("towed-car", {"duration": 2.0, "dt": 1e-3, "record_interval": 0.01}),
    "tractor-and-semitrailer": (
        "tractor-semitrailer-jackknife",
        {"duration": 1.5, "dt": 1e-3, "record_interval": 0.01},
    ),
    "obstacle-impact": ("runout-sedan-into-pole", {"duration": 0.4, "dt": 1e-3}),
    "pedestrian-strike": ("pedestrian-sedan-40kmh", {"duration": 0.05, "dt": 2e-4}),
}


def dump(x: Any, depth: int = 0) -> str:
    """A text of ``x`` that changes when any bit of it does."""
    if depth > 8:
        return f"<{type(x).__name__}>"
    if x is None or isinstance(x, bool | int | str):
        return repr(x)
    if isinstance(x, float | np.floating):
        return float(x).hex()
    if isinstance(x, np.ndarray):
        data = np.ascontiguousarray(x).tobytes()
        return f"array {x.dtype} {x.shape} {x.flags.writeable} {hashlib.sha256(data).hexdigest()}"
    if isinstance(x, dict):
        return "{" + ", ".join(f"{dump(k)}: {dump(v, depth + 1)}" for k, v in x.items()) + "}"
    if hasattr(x, "_asdict"):  # a NamedTuple: its class name and fields
        return f"{type(x).__qualname__}({dump(x._asdict(), depth + 1)})"
    if isinstance(x, list | tuple):
        return "[" + ", ".join(dump(v, depth + 1) for v in x) + "]"
    if dataclasses.is_dataclass(x) and not isinstance(x, type):
        values = {f.name: getattr(x, f.name) for f in dataclasses.fields(x)}
        return f"{type(x).__qualname__}({dump(values, depth + 1)})"
    return repr(x)


def attempt(f: Any, *args: Any) -> str:
    """dump(f(*args)), or the error it raises."""
    try:
        return dump(f(*args))
    except Exception as e:  # noqa: BLE001 - the error is part of the fingerprint
        return f"error: {type(e).__qualname__}: {e}"


def describe(result: Result) -> list[str]:
    """Every public view of a Result, one line each."""
    lines = [
        f"repr: {result!r}",
        f"bodies: {result.bodies} vehicles: {result.vehicles} obstacles: {result.obstacles}",
        f"settings: {dump([result.duration, result.dt, result.record_interval])} "
        f"on_ground: {result.on_ground} scene: {type(result.scene).__qualname__}",
        f"t: {dump(result.t)}",
        f"to_dict: {attempt(result.to_dict, True)}",
        f"to_dict short: {attempt(result.to_dict)}",
        f"contacts: {dump(result.contacts)}",
        f"contact reprs: {[repr(c) for c in result.contacts]}",
        f"joints: {dump(result.joints)}",
        f"joint events: {dump(result.joint_events)}",
    ]
    for name in result.bodies:
        tr = result.trajectory(name)
        lines.append(f"{name} trajectory: {dump(tr)}")
        lines.append(f"{name} is_obstacle: {result.is_obstacle(name)}")
        if result.is_obstacle(name):
            continue
        t0, t1 = float(tr.t[0]), float(tr.t[-1])
        times = np.linspace(t0, t1, 23)[1:-1] + 1e-7  # between samples, mostly
        lines += [
            f"{name} rest: {attempt(result.rest, name)}",
            f"{name} separations: {attempt(result.separations, name)}",
            f"{name} wheels: {attempt(result.wheels, name)}",
            f"{name} wheel_path: {attempt(result.wheel_path, name, 0)}",
            f"{name} wheel_centres: {attempt(result.wheel_centres, name)}",
            f"{name} wheel_steer: {attempt(result.wheel_steer, name)}",
            f"{name} tyre_marks: {attempt(result.tyre_marks, name)}",
            f"{name} tyre_marks 0.5: {attempt(result.tyre_marks, name, 0.5)}",
            f"{name} states: {attempt(result.states, name, times)}",
            f"{name} state mid: {attempt(result.state, name, (t0 + t1) / 3)}",
            f"{name} state_at end: {attempt(result.state_at, name, t1)}",
            f"{name} pose: {attempt(result.pose, name, (t0 + t1) / 2)}",
            f"{name} heading: {attempt(result.heading, name, t1)}",
            f"{name} vehicle: {attempt(lambda n=name: result.vehicle(n).name)}",
        ]
    for k, imp in enumerate(result.impacts):
        lines += [
            f"impact {k}: {dump(imp)}",
            f"impact {k} repr sha256: {hashlib.sha256(repr(imp).encode()).hexdigest()}",
            f"impact {k} to_dict: {dump(imp.to_dict())}",
            f"impact {k} closing_speed: {dump(imp.closing_speed)} moving: {imp.moving}",
        ]
        for name in imp.vehicles:
            lines += [
                f"impact {k} {name} impulse_on: {attempt(imp.impulse_on, name)}",
                f"impact {k} {name} speed_change: {attempt(imp.speed_change, name)}",
                f"impact {k} {name} state_before: " + attempt(result.state_before, name, imp),
                f"impact {k} {name} delta_v_body: " + attempt(result.delta_v_body, imp, name),
            ]
    return lines


def main(out: Path, pickles: Path | None, unpickle: bool) -> None:
    out.mkdir(parents=True, exist_ok=True)
    digest = hashlib.sha256()
    for case, (example, settings) in CASES.items():
        result = load_scene(ROOT / "examples" / f"{example}.toml").scene.run(**settings)
        lines = describe(result)
        if unpickle:
            assert pickles is not None
            data = (pickles / f"{case}.pickle").read_bytes()
        else:
            data = pickle.dumps(result)
            if pickles is not None:
                pickles.mkdir(parents=True, exist_ok=True)
                (pickles / f"{case}.pickle").write_bytes(data)
        lines += ["-- pickle round trip", *describe(pickle.loads(data))]
        text = "\n".join(lines) + "\n"
        (out / f"{case}.txt").write_text(text, encoding="utf-8")
        digest.update(case.encode() + b"\0" + text.encode())
        print(f"{case}: {len(result.impacts)} impact(s), {result.t.size} samples")
    print(digest.hexdigest())


if __name__ == "__main__":
    args = sys.argv[1:]
    if len(args) not in (1, 3) or (len(args) == 3 and args[1] not in ("--pickle", "--unpickle")):
        sys.exit("usage: result_fingerprint.py OUTPUT_FOLDER [--pickle|--unpickle FOLDER]")
    main(Path(args[0]), Path(args[2]) if len(args) == 3 else None, args[1:2] == ["--unpickle"])
