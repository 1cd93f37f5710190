"""Everything crashsim.Scene makes of many scenes built through its public API, written to a
folder and hashed, so that a refactoring of crashsim.scene can be shown not to change it:

    python3 scripts/scene_fingerprint.py /tmp/before     # on the old code
    python3 scripts/scene_fingerprint.py /tmp/after      # on the new code
    diff -r /tmp/before /tmp/after                       # empty: nothing changed

The last line printed is the sha256 of all the files (the same on both sides when nothing
changed). One file per case; a case builds a scene (every kind of add: vehicles by (x, y) and
(x, y, z), heading, quaternion and matrix; trailers and their couplings; obstacles; flat,
raised, zoned and terrain grounds, set before and after the vehicles; pedestrians, cyclists
and bicycles; joints of every kind with limits, axes and axes2; contact overrides both ways
round, soft contacts, no-contact pairs; driver inputs) and writes: the engine's spec
(``to_spec(...).to_json()``, with several run settings), the scene's public views (pairs,
contact_parameters, defaults, vehicles, obstacles, joints, pedestrians, cyclists, bicycles,
inputs, len, repr) and its private state (floats as float.hex, arrays as their bytes'
sha256); the spec and state of its pickle round trip; ``Scene.with_`` variants as the studies
make them; short runs' raw output (``SceneSpec.run()``) and Scene.run's result (impacts,
trajectories, rest, the warnings it raises); the errors of bad inputs (type and message) at
whichever call raises them.
"""

from __future__ import annotations

import dataclasses
import hashlib
import math
import pickle
import sys
import warnings
from collections.abc import Callable
from pathlib import Path
from typing import Any

import crashsim as cs
import numpy as np
import trimesh
from crashsim import _core

SEDAN = cs.vehicle_data.vehicle_class("sedan").stiffness.to_dict()


def dump(x: Any, depth: int = 0) -> str:
    """A text of ``x`` that changes when any bit of it does."""
    if depth > 7:
        return f"<{type(x).__name__}>"
    if x is None or isinstance(x, bool | int | str):
        return repr(x)
    if isinstance(x, float | np.floating):
        return float(x).hex()
    if isinstance(x, np.ndarray):
        data = np.ascontiguousarray(x).tobytes()
        return f"array {x.dtype} {x.shape} {hashlib.sha256(data).hexdigest()}"
    if isinstance(x, dict):
        # keys as dump gives them: a frozenset's repr follows the (salted) string hashes
        return "{" + ", ".join(f"{dump(k)}: {dump(v, depth + 1)}" for k, v in x.items()) + "}"
    if isinstance(x, set | frozenset):
        return "{" + ", ".join(sorted(dump(v, depth + 1) for v in x)) + "}"
    if isinstance(x, list | tuple):
        return "[" + ", ".join(dump(v, depth + 1) for v in x) + "]"
    if isinstance(x, trimesh.Trimesh):
        return f"Trimesh(vertices={dump(x.vertices)}, faces={dump(np.asarray(x.faces))})"
    if isinstance(x, _core.Shape):
        return f"Shape({dump(x.vertices)}, {dump(x.triangles)})"
    if isinstance(x, cs.Vehicle):  # the vehicles' own fingerprint: scripts/vehicles_fingerprint
        return f"Vehicle({x.name!r}, {float(x.mass).hex()}, {dump(x.cg)}, {dump(x.inertia)})"
    if dataclasses.is_dataclass(x) and not isinstance(x, type):
        fields = {f.name: getattr(x, f.name) for f in dataclasses.fields(x)}
        return f"{type(x).__qualname__}({dump(fields, depth + 1)})"
    if type(x).__module__.startswith("crashsim") and not hasattr(x, "__dict__"):
        # the engine's objects (an Impact, a Joint, ...): every public attribute, no method
        names = [n for n in dir(x) if not n.startswith("_") and not callable(getattr(x, n))]
        return f"{type(x).__qualname__}({dump({n: getattr(x, n) for n in names}, depth + 1)})"
    if hasattr(x, "__dict__") and not callable(x):
        return f"{type(x).__qualname__}({dump(dict(sorted(vars(x).items())), depth + 1)})"
    return repr(x)


def error(e: BaseException) -> str:
    return f"error: {type(e).__module__}.{type(e).__qualname__}: {e}"


def attempt(make: Callable[[], Any]) -> str:
    try:
        return dump(make())
    except Exception as e:  # noqa: BLE001 - the error is the fingerprint
        return error(e)


def spec_json(scene: cs.Scene, *args: Any, **kw: Any) -> str:
    try:
        return scene.to_spec(*args, **kw).to_json()
    except Exception as e:  # noqa: BLE001
        return error(e)


def describe(scene: cs.Scene) -> list[str]:
    """The scene's public views, its private state and its spec under several run settings,
    then the same of its pickle round trip."""
    lines = [
        f"repr: {scene!r}",
        f"len: {len(scene)}",
        f"iter: {[v.name for v in scene]}",
        f"defaults: {dump(scene.defaults)}",
        f"vehicles: {[v.name for v in scene.vehicles]}",
        f"obstacles: {dump(scene.obstacles)}",
        f"pairs: {dump(scene.pairs())}",
        f"joints: {dump(scene.joints)}",
        f"pedestrians: {sorted(scene.pedestrians)}",
        f"cyclists: {sorted(scene.cyclists)}",
        f"bicycles: {sorted(scene.bicycles)}",
        f"ground: {scene.ground!r}",
    ]
    names = [v.name for v in scene.vehicles] + [o.name for o in scene.obstacles]
    for a in names[:6]:
        lines.append(f"inputs {a}: {attempt(lambda a=a: scene.inputs(a))}")
        for b in names[:6]:
            lines.append(
                f"params {a} {b}: {attempt(lambda a=a, b=b: scene.contact_parameters(a, b))}"
            )
    lines.append(f"state: {dump(dict(sorted(vars(scene).items())))}")
    lines.append(f"spec 1s: {spec_json(scene)}")
    lines.append(f"spec 0.5s dt 2e-4 interval: {spec_json(scene, 0.5, 2e-4, record_interval=0.01)}")
    lines.append(f"spec bytes: {spec_json(scene, 2.0, 1e-3, max_history_bytes=2**20)}")
    lines.append(f"spec rest: {spec_json(scene, until='rest')}")
    lines.append(f"spec rest max: {spec_json(scene, until='rest', max_duration=3.0)}")
    lines.append(f"spec rest dur: {spec_json(scene, 4.0, until='rest')}")
    try:
        lines.append(f"world: {type(scene.build_world()).__qualname__}")
    except Exception as e:  # noqa: BLE001
        lines.append(f"world: {error(e)}")
    try:
        back = pickle.loads(pickle.dumps(scene))
    except Exception as e:  # noqa: BLE001 - a scene with joints does not pickle (yet)
        lines.append(f"pickled: {error(e)}")
        return lines
    lines.append(f"pickled repr: {back!r}")
    lines.append(f"pickled state: {dump(dict(sorted(vars(back).items())))}")
    lines.append(f"pickled spec: {spec_json(back, 0.5, 1e-3)}")
    return lines


def case(make: Callable[[], Any]) -> str:
    """The text of what ``make()`` gives (a scene, a list of lines or anything else) with the
    warnings raised while it ran, or of the error it raises."""
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        try:
            made = make()
        except Exception as e:  # noqa: BLE001 - the error is the fingerprint
            lines = [error(e)]
        else:
            if isinstance(made, cs.Scene):
                lines = describe(made)
            elif isinstance(made, list) and all(isinstance(s, str) for s in made):
                lines = made
            else:
                lines = [dump(made)]
    for w in caught:
        lines.append(
            f"warning: {w.category.__qualname__}: {w.message} [{Path(w.filename).name}:{w.lineno}]"
        )
    return "\n".join(lines) + "\n"


# -- the things a scene holds ---------------------------------------------------------------


def box(name: str, mass: float = 1500.0, **kw: Any) -> cs.Vehicle:
    return cs.Vehicle.box(4.5, 1.8, 1.4, mass, name=name, **kw)


def wheeled(name: str = "car", **kw: Any) -> cs.Vehicle:
    return cs.Vehicle.box(4.6, 1.8, 1.4, mass=1500.0, name=name, ground_clearance=0.15,
                          cg_height=0.55, wheelbase=2.7, track=1.55, wheel_radius=0.3,
                          cg_to_front_axle=1.1, **kw)  # fmt: skip


def sheet(size: float = 40.0, slope: float = 0.0, tilt_y: float = 0.0) -> trimesh.Trimesh:
    """A square sheet z = slope x + tilt_y y centred on the origin (two triangles)."""
    h = size / 2
    v = np.array([[-h, -h, 0.0], [h, -h, 0.0], [h, h, 0.0], [-h, h, 0.0]])
    v[:, 2] = slope * v[:, 0] + tilt_y * v[:, 1]
    return trimesh.Trimesh(v, [[0, 1, 2], [0, 2, 3]], process=False)


def two_boxes(**defaults: Any) -> cs.Scene:
    scene = cs.Scene(**defaults)
    scene.add(box("red", stiffness=SEDAN), (-5.0, 0.0, 0.7), velocity=(20.0, 0.0, 0.0))
    scene.add(box("blue", 1200.0, stiffness=SEDAN), (0.0, -5.0, 0.7), heading=math.pi / 2,
              velocity=(0.0, 10.0, 0.0))  # fmt: skip
    return scene


def rot_z(a: float) -> np.ndarray:
    c, s = math.cos(a), math.sin(a)
    return np.array([[c, -s, 0.0], [s, c, 0.0], [0.0, 0.0, 1.0]])


def construction_cases() -> dict[str, Callable[[], Any]]:
    S = cs.Scene
    out: dict[str, Callable[[], Any]] = {
        "defaults": lambda: S(),
        "defaults-all-given": lambda: two_boxes(
            depth_of_penetration=0.03,
            restitution=0.2,
            friction=0.5,
            restitution_mode="normal",
            normal="volume",
            pitch=0.1,
            centroid=(1.0, 2.0, 0.5),
        ),  # fmt: skip
        "defaults-auto-stiffness": lambda: two_boxes(
            depth_of_penetration="auto", centroid="stiffness"
        ),
        "defaults-normal-vector": lambda: two_boxes(normal=(0.0, 1.0, 0.0), centroid="auto"),
        "defaults-normal-horizontal": lambda: two_boxes(normal="horizontal"),
        "defaults-centroid-in-vehicle": lambda: two_boxes(centroid=("red", (1.0, 0.0, 0.0))),
        "defaults-int-values": lambda: two_boxes(depth_of_penetration=0, restitution=1, pitch=0),
        "defaults-numpy-values": lambda: two_boxes(
            restitution=np.float64(0.3), friction=np.int64(1)
        ),
    }
    bad: dict[str, dict[str, Any]] = {
        "dtp-large": {"depth_of_penetration": 0.1},
        "dtp-negative": {"depth_of_penetration": -0.01},
        "dtp-word": {"depth_of_penetration": "fast"},
        "dtp-nan": {"depth_of_penetration": float("nan")},
        "restitution": {"restitution": 2.0},
        "restitution-str": {"restitution": "high"},
        "restitution-bool": {"restitution": True},
        "friction": {"friction": -1.0},
        "mode": {"restitution_mode": "partial"},
        "mode-int": {"restitution_mode": 3},
        "normal-word": {"normal": "up"},
        "normal-short": {"normal": (1.0, 0.0)},
        "normal-zero": {"normal": (0.0, 0.0, 0.0)},
        "pitch": {"pitch": "a"},
        "pitch-large": {"pitch": 3.0},
        "centroid-word": {"centroid": "middle"},
        "centroid-short": {"centroid": (1.0, 2.0)},
        "centroid-nan": {"centroid": (1.0, float("nan"), 0.0)},
        "ground": {"ground": "flat"},
    }
    for name, kw in bad.items():
        out[f"defaults-bad-{name}"] = lambda kw=kw: S(**kw)
    return out


def vehicle_cases() -> dict[str, Callable[[], Any]]:
    def scene_with(*adds: Callable[[cs.Scene], Any], ground: Any = None) -> cs.Scene:
        scene = cs.Scene(ground=ground)
        for add in adds:
            add(scene)
        return scene

    quat = np.array([math.cos(0.3), 0.0, 0.0, math.sin(0.3)])
    tilted = rot_z(0.4) @ np.array([[1.0, 0.0, 0.0], [0.0, math.cos(0.1), -math.sin(0.1)],
                                    [0.0, math.sin(0.1), math.cos(0.1)]])  # fmt: skip
    brake = cs.DriverInputs(brake=0.5)
    steer = cs.DriverInputs(steer=np.array([[0.0, 0.0], [0.5, 0.05], [1.0, 0.05]]))
    out: dict[str, Callable[[], Any]] = {
        "add-xyz": lambda: scene_with(lambda s: s.add(box("a"), (1.0, 2.0, 0.7))),
        "add-heading": lambda: scene_with(
            lambda s: s.add(
                box("a"),
                (1.0, 2.0, 0.7),
                heading=0.7,
                velocity=(3.0, 1.0, 0.0),
                angular_velocity=(0.0, 0.0, 0.5),
            )  # fmt: skip
        ),
        "add-heading-int": lambda: scene_with(lambda s: s.add(box("a"), (0, 0, 1), heading=1)),
        "add-quaternion": lambda: scene_with(
            lambda s: s.add(box("a"), (0.0, 0.0, 0.7), orientation=quat)
        ),
        "add-matrix": lambda: scene_with(
            lambda s: s.add(box("a"), (0.0, 0.0, 0.9), orientation=tilted)
        ),
        "add-matrix-negative-trace": lambda: scene_with(
            lambda s: s.add(box("a"), (0.0, 0.0, 0.9), orientation=rot_z(3.0))
        ),
        "add-matrix-pi-x": lambda: scene_with(
            lambda s: s.add(box("a"), (0.0, 0.0, 0.9), orientation=np.diag([1.0, -1.0, -1.0]))
        ),
        "add-matrix-pi-y": lambda: scene_with(
            lambda s: s.add(box("a"), (0.0, 0.0, 0.9), orientation=np.diag([-1.0, 1.0, -1.0]))
        ),
        "add-reflection-error": lambda: scene_with(
            lambda s: s.add(box("a"), (0.0, 0.0, 0.9), orientation=np.diag([1.0, 1.0, -1.0]))
        ),
        "add-not-orthonormal-error": lambda: scene_with(
            lambda s: s.add(box("a"), (0.0, 0.0, 0.9), orientation=np.eye(3) * 2.0)
        ),
        "add-matrix-nan-error": lambda: scene_with(
            lambda s: s.add(box("a"), (0.0, 0.0, 0.9), orientation=np.full((3, 3), np.nan))
        ),
        "add-bad-quaternion-error": lambda: scene_with(
            lambda s: s.add(box("a"), (0.0, 0.0, 0.9), orientation=(1.0, 1.0, 0.0, 0.0))
        ),
        "add-quaternion-str-error": lambda: scene_with(
            lambda s: s.add(box("a"), (0.0, 0.0, 0.9), orientation="up")
        ),
        "add-heading-and-orientation-error": lambda: scene_with(
            lambda s: s.add(box("a"), (0.0, 0.0, 0.7), heading=0.1, orientation=quat)
        ),
        "add-heading-nan-error": lambda: scene_with(
            lambda s: s.add(box("a"), (0.0, 0.0, 0.7), heading=float("nan"))
        ),
        "add-heading-str-error": lambda: scene_with(
            lambda s: s.add(box("a"), (0.0, 0.0, 0.7), heading="north")
        ),
        "add-xy-no-ground-error": lambda: scene_with(lambda s: s.add(box("a"), (0.0, 0.0))),
        "add-position-str-error": lambda: scene_with(lambda s: s.add(box("a"), "here")),
        "add-position-inf-error": lambda: scene_with(
            lambda s: s.add(box("a"), (0.0, math.inf, 0.0))
        ),
        "add-velocity-nan-error": lambda: scene_with(
            lambda s: s.add(box("a"), (0.0, 0.0, 0.7), velocity=(math.nan, 0.0, 0.0))
        ),
        "add-omega-short-error": lambda: scene_with(
            lambda s: s.add(box("a"), (0.0, 0.0, 0.7), angular_velocity=(0.0, 0.0))
        ),
        "add-not-vehicle-error": lambda: scene_with(lambda s: s.add("car", (0.0, 0.0, 0.7))),
        "add-twice-error": lambda: scene_with(
            lambda s: [s.add(v := box("a"), (0.0, 0.0, 0.7)), s.add(v, (9.0, 0.0, 0.7))]
        ),
        "add-same-name-error": lambda: scene_with(
            lambda s: s.add(box("a"), (0.0, 0.0, 0.7)).add(box("a"), (9.0, 0.0, 0.7))
        ),
        "add-name-of-obstacle-error": lambda: scene_with(
            lambda s: s.add_obstacle(cs.Obstacle.pole(0.3, name="a"), (0.0, 5.0, 0.0)).add(
                box("a"), (9.0, 0.0, 0.7)
            )
        ),
        "ground-xy": lambda: scene_with(
            lambda s: s.add(
                wheeled(), (3.0, 1.0), heading=0.2, velocity=(10.0, 0.0, 0.0), inputs=brake
            ),  # fmt: skip
            ground=cs.Ground(friction=0.8),
        ),
        "ground-xy-no-wheels": lambda: scene_with(
            lambda s: s.add(box("a"), (3.0, 1.0)), ground=cs.Ground(height=0.5)
        ),
        "ground-xyz": lambda: scene_with(
            lambda s: s.add(wheeled(), (3.0, 1.0, 0.55), inputs=steer), ground=cs.Ground()
        ),
        "ground-xy-orientation-error": lambda: scene_with(
            lambda s: s.add(wheeled(), (3.0, 1.0), orientation=quat), ground=cs.Ground()
        ),
        "ground-zones": lambda: scene_with(
            lambda s: s.add(wheeled(), (0.0, 0.0), velocity=(15.0, 0.0, 0.0), inputs=brake),
            ground=cs.Ground(
                body_friction=0.5,
                zones=[
                    cs.FrictionZone(
                        [(-10, -10), (200, -10), (200, 10), (-10, 10)], "wet asphalt", name="wet"
                    )
                ],  # fmt: skip
            ),
        ),
        "ground-set-after": lambda: _ground_after(),
        "ground-set-none": lambda: _ground_none(),
        "ground-bad-set-error": lambda: setattr(cs.Scene(), "ground", 3.0),
        "terrain-slope": lambda: scene_with(
            lambda s: s.add(wheeled(), (4.0, 1.0), heading=0.3),
            lambda s: s.add(box("b"), (-6.0, 2.0)),
            ground=cs.Ground(terrain=sheet(slope=0.05, tilt_y=-0.03)),
        ),
        "terrain-flat-sheet": lambda: scene_with(
            lambda s: s.add(wheeled(), (4.0, 1.0)), ground=cs.Ground(terrain=sheet())
        ),
        "terrain-off-edge-error": lambda: scene_with(
            lambda s: s.add(wheeled(), (19.0, 0.0), heading=0.0),
            ground=cs.Ground(terrain=sheet()),
        ),
        "terrain-far-error": lambda: scene_with(
            lambda s: s.add(box("b"), (100.0, 0.0)), ground=cs.Ground(terrain=sheet())
        ),
        "terrain-hole-at-spec": lambda: scene_with(
            lambda s: s.add(wheeled(), (19.0, 0.0, 0.55), heading=0.0),
            ground=cs.Ground(terrain=sheet()),
        ),
        "inputs-no-wheels-error": lambda: scene_with(
            lambda s: s.add(box("a"), (0.0, 0.0, 0.7), inputs=brake)
        ),
        "inputs-wrong-type-error": lambda: scene_with(
            lambda s: s.add(wheeled(), (0.0, 0.0, 0.7), inputs={"brake": 0.5})
        ),
        "inputs-bad-wheel-error": lambda: scene_with(
            lambda s: s.add(
                wheeled(), (0.0, 0.0, 0.7), inputs=cs.DriverInputs(brake={"rear_middle": 0.3})
            )  # fmt: skip
        ),
        "inputs-no-ground": lambda: scene_with(
            lambda s: s.add(wheeled(), (0.0, 0.0, 0.7), inputs=steer)
        ),
        "inputs-of-obstacle-error": lambda: scene_with(
            lambda s: s.add(box("a"), (0.0, 0.0, 0.7)).add_obstacle(
                cs.Obstacle.pole(0.3), (5.0, 5.0, 0.0)
            )
        ).inputs("pole"),
        "inputs-unknown-error": lambda: cs.Scene().inputs("nobody"),
        "empty-spec-error": lambda: cs.Scene().to_spec(),
    }
    return out


def _ground_after() -> cs.Scene:
    scene = cs.Scene()
    scene.add(wheeled(), (0.0, 0.0, 0.6)).add(box("b"), (8.0, 0.0, 0.7))
    scene.add_obstacle(cs.Obstacle.wall(5.0), (0.0, 8.0))
    scene.ground = cs.Ground(height=0.3)
    scene.add(wheeled("c"), (-8.0, 0.0))
    scene.ground = cs.Ground(height=-0.2)
    return scene


def _ground_none() -> cs.Scene:
    scene = cs.Scene(ground=cs.Ground(height=0.4))
    scene.add(wheeled(), (0.0, 0.0)).add_obstacle(cs.Obstacle.kerb(3.0), (0.0, 5.0))
    scene.ground = None
    return scene


def trailer_cases() -> dict[str, Callable[[], Any]]:
    def semi(coupling: Any = None, inputs: Any = None, **kw: Any) -> cs.Scene:
        scene = cs.Scene(ground=cs.Ground(friction=0.4))
        t = cs.Trailer.generate("box_van")
        trailers = [(t, inputs)] if inputs is not None else [t]
        scene.add(cs.Vehicle.generate("tractor"), (0.0, 0.0), velocity=(15.0, 0.0, 0.0),
                  angular_velocity=(0.0, 0.0, 0.1), trailers=trailers, coupling=coupling,
                  **kw)  # fmt: skip
        return scene

    def caravan(coupling: Any = None, height: float = 0.45, mass: float | None = None) -> Any:
        car = cs.Vehicle.generate("sedan", name="car")
        lo = (car.mesh.bounds[0] - car.cg)[0]
        car = car.with_hitch(car.cg + [lo - 0.15, 0.0, 0.45 - car.cg[2]], "ball")
        kw = {} if mass is None else {"mass": mass}
        van = cs.Trailer.generate("caravan", coupler_height=height, **kw)
        scene = cs.Scene(ground=cs.Ground(friction=0.8))
        scene.add(car, (0.0, 0.0), heading=0.3, velocity=(14.0, 0.0, 0.0), trailers=[van],
                  coupling=coupling)  # fmt: skip
        return scene

    def drawbar(coupling: Any = None) -> cs.Scene:
        truck = cs.rigid_truck("rigid_truck")
        dolly, body = cs.Trailer.drawbar(
            length=7.0, width=2.5, height=2.5, mass=9000.0, ground_clearance=1.1,
            turntable=1.0, rear_axles=[5.5, 6.8], drawbar=2.5,
            eye_height=float((truck.hitch.point + truck.cg)[2]), track=2.0, radius=0.5,
            dolly_mass=800.0,
        )  # fmt: skip
        scene = cs.Scene(ground=cs.Ground(friction=0.8))
        scene.add(truck, (0.0, 0.0), velocity=(12.0, 0.0, 0.0), trailers=[dolly, body],
                  coupling=coupling)  # fmt: skip
        return scene

    return {
        "trailer-semi": lambda: semi(),
        "trailer-semi-limits": lambda: semi(
            {"limits": {"articulation": (-1.2, 1.2)}, "friction": 50.0}
        ),  # fmt: skip
        "trailer-semi-inputs": lambda: semi(inputs=cs.DriverInputs(brake=0.3)),
        "trailer-caravan": lambda: caravan(),
        "trailer-caravan-damped": lambda: caravan(
            {"stiffness": 100.0, "damping": 20.0, "collide": True}
        ),  # fmt: skip
        "trailer-drawbar": lambda: drawbar(),
        "trailer-drawbar-list": lambda: drawbar([None, {"limits": {"angle": (-1, 1)}}]),
        "trailer-coupling-count-error": lambda: drawbar([None]),
        "trailer-coupling-str-error": lambda: drawbar("stiff"),
        "trailer-coupling-entry-error": lambda: drawbar([None, 3]),
        "trailer-coupling-key-error": lambda: semi({"colour": "red"}),
        "trailer-heavy-error": lambda: caravan(mass=16000.0),
        "trailer-height-error": lambda: caravan(height=0.8),
        "trailer-not-vehicle-error": lambda: cs.Scene(ground=cs.Ground()).add(
            cs.Vehicle.generate("tractor"), (0.0, 0.0), trailers=["semi"]
        ),
        "trailer-no-hitch-error": lambda: cs.Scene(ground=cs.Ground()).add(
            wheeled(), (0.0, 0.0), trailers=[cs.Trailer.generate("caravan")]
        ),
        "trailer-no-ground": lambda: cs.Scene().add(
            cs.Vehicle.generate("tractor"),
            (0.0, 0.0, 1.2),
            trailers=[cs.Trailer.generate("box_van")],
        ),
    }


def obstacle_cases() -> dict[str, Callable[[], Any]]:
    def with_obstacles(ground: Any = None, *placed: tuple[Any, tuple, dict]) -> cs.Scene:
        scene = cs.Scene(ground=ground)
        scene.add(box("car", stiffness=SEDAN), (-10.0, 0.0, 0.7), velocity=(15.0, 0.0, 0.0))
        for o, at, kw in placed:
            scene.add_obstacle(o, at, **kw)
        return scene

    Ob = cs.Obstacle
    return {
        "obstacles-flat": lambda: with_obstacles(
            cs.Ground(),
            (Ob.wall(6.0, 0.3, 1.0), (4.0, 0.0), {"heading": 0.2}),
            (Ob.pole(0.3), (0.0, 6.0), {}),
            (Ob.barrier(10.0), (0.0, -6.0, 0.0), {}),
            (Ob.kerb(3.0, name="k"), (8.0, 8.0, 0.0), {"orientation": rot_z(0.5)}),
            (Ob.tree(0.5, stiffness=(1e4, 2e5)), (-8.0, 8.0), {}),
        ),
        "obstacles-no-ground": lambda: with_obstacles(
            None,
            (Ob.wall(6.0, stiffness=(1e5, 1e6)), (4.0, 0.0), {}),
            (Ob.pole(0.3), (0.0, 6.0, 0.5), {"orientation": (1.0, 0.0, 0.0, 0.0)}),
        ),
        "obstacles-terrain": lambda: with_obstacles(
            cs.Ground(terrain=sheet(slope=0.02)), (Ob.pole(0.3), (3.0, 6.0), {})
        ),
        "obstacle-off-terrain-error": lambda: with_obstacles(
            cs.Ground(terrain=sheet()), (Ob.pole(0.3), (30.0, 6.0), {})
        ),
        "obstacle-not-obstacle-error": lambda: with_obstacles(None, (box("b"), (0.0, 5.0), {})),
        "obstacle-twice-error": lambda: with_obstacles(
            None, (p := Ob.pole(0.3), (0.0, 5.0), {}), (p, (0.0, 9.0), {})
        ),
        "obstacle-same-name-error": lambda: with_obstacles(
            None, (Ob.pole(0.3), (0.0, 5.0), {}), (Ob.tree(0.4, name="pole"), (0.0, 9.0), {})
        ),
        "obstacle-name-of-vehicle-error": lambda: with_obstacles(
            None, (Ob.pole(0.3, name="car"), (0.0, 5.0), {})
        ),
        "obstacle-bad-position-error": lambda: with_obstacles(
            None, (Ob.pole(0.3), (0.0, math.nan, 0.0), {})
        ),
        "obstacle-bad-heading-error": lambda: with_obstacles(
            None, (Ob.pole(0.3), (0.0, 5.0), {"heading": "east"})
        ),
        "obstacle-xy-orientation-error": lambda: with_obstacles(
            None, (Ob.pole(0.3), (0.0, 5.0), {"orientation": (1.0, 0.0, 0.0, 0.0)})
        ),
    }


def joint_cases() -> dict[str, Callable[[], Any]]:
    def pair(ground: bool = True) -> cs.Scene:
        scene = cs.Scene(ground=cs.Ground() if ground else None)
        scene.add(box("a"), (0.0, 0.0, 0.7)).add(box("b"), (5.0, 0.0, 0.7), heading=0.1)
        return scene

    q = np.array([math.cos(0.2), 0.0, math.sin(0.2), 0.0])
    return {
        "join-spherical": lambda: pair().join("a", "b", at=(2.5, 0.0, 0.7)),
        "join-spherical-axes2": lambda: pair().join(
            "a",
            "b",
            at=(2.5, 0.0, 0.7),
            axes=q,
            axes2=rot_z(0.3),
            limits={"swing": (0.0, 1.0)},
            name="hip",
        ),  # fmt: skip
        "join-revolute": lambda: pair().join(
            "a",
            "b",
            at=(2.5, 0.0, 0.7),
            kind="revolute",
            axes=rot_z(0.5),
            limits={"angle": (-0.5, 0.8)},
            stiffness=10.0,
            damping=2.0,
            friction=1.0,
        ),  # fmt: skip
        "join-fixed": lambda: pair().join(
            "a", "b", at=(2.5, 0.0, 0.7), kind="fixed", collide=True
        ),  # fmt: skip
        "join-fifth-wheel": lambda: pair().join(
            "a",
            "b",
            at=(2.5, 0.0, 1.0),
            kind="fifth_wheel",
            limits={"articulation": (-1.5, 1.5), "pitch": (-0.2, 0.2)},
        ),  # fmt: skip
        "join-world": lambda: pair().join("a", at=(0.0, 0.0, 2.0), kind="revolute"),
        "join-objects": lambda: _join_objects(),
        "join-no-ground": lambda: pair(False).join("a", "b", at=(2.5, 0.0, 0.7)),
        "join-same-error": lambda: pair().join("a", "a", at=(0.0, 0.0, 0.7)),
        "join-unknown-error": lambda: pair().join("a", "c", at=(0.0, 0.0, 0.7)),
        "join-kind-error": lambda: pair().join("a", "b", at=(0.0, 0.0, 0.7), kind="ball"),
        "join-axes-error": lambda: pair().join("a", "b", at=(0.0, 0.0, 0.7), axes=(1, 2, 3)),
        "join-axes-matrix-error": lambda: pair().join(
            "a", "b", at=(0.0, 0.0, 0.7), axes=np.eye(3) * 3
        ),
        "join-axes2-kind-error": lambda: pair().join(
            "a", "b", at=(0.0, 0.0, 0.7), kind="revolute", axes2=q
        ),
        "join-axes2-bad-error": lambda: pair().join("a", "b", at=(0.0, 0.0, 0.7), axes2=(0, 0)),
        "join-at-error": lambda: pair().join("a", "b", at=(0.0, math.nan, 0.7)),
        "join-limit-error": lambda: pair().join(
            "a", "b", at=(0.0, 0.0, 0.7), kind="revolute", limits={"angle": (1.0, -1.0)}
        ),
        "join-limit-name-error": lambda: pair().join(
            "a", "b", at=(0.0, 0.0, 0.7), kind="revolute", limits={"swing": (0.0, 1.0)}
        ),
        "join-duplicate-error": lambda: (
            pair().join("a", "b", at=(2.5, 0.0, 0.7)).join("b", "a", at=(2.5, 0.0, 0.7))
        ),
        "join-duplicate-name-error": lambda: _join_same_name(),
        "join-obstacle-error": lambda: (
            pair()
            .add_obstacle(cs.Obstacle.pole(0.3), (0.0, 5.0))
            .join("pole", "a", at=(0.0, 5.0, 0.5))
        ),
        "join-obstacle-second": lambda: (
            pair()
            .add_obstacle(cs.Obstacle.pole(0.3), (0.0, 5.0))
            .join("a", "pole", at=(0.0, 5.0, 0.5))
        ),
        "join-negative-stiffness-error": lambda: pair().join(
            "a", "b", at=(2.5, 0.0, 0.7), stiffness=-1.0
        ),
    }


def _join_objects() -> cs.Scene:
    a, b = box("a"), box("b")
    scene = cs.Scene(ground=cs.Ground())
    scene.add(a, (0.0, 0.0)).add(b, (5.0, 0.0), heading=0.05)
    return scene.join(a, b, at=(2.5, 0.0, 0.7))


def _join_same_name() -> cs.Scene:
    scene = cs.Scene(ground=cs.Ground())
    scene.add(box("a"), (0.0, 0.0)).add(box("b"), (5.0, 0.0)).add(box("c"), (10.0, 0.0))
    return scene.join("a", "b", at=(2.5, 0.0, 0.7), name="j").join(
        "b", "c", at=(7.5, 0.0, 0.7), name="j"
    )


def contact_cases() -> dict[str, Callable[[], Any]]:
    def three(**defaults: Any) -> cs.Scene:
        scene = two_boxes(**defaults)
        scene.add(box("green", 900.0), (10.0, 0.0, 0.7))
        scene.add_obstacle(cs.Obstacle.wall(5.0, name="wall"), (0.0, 10.0, 0.0))
        scene.add_obstacle(cs.Obstacle.pole(0.3, stiffness=(1e4, 2e5)), (0.0, -12.0, 0.0))
        return scene

    return {
        "contact-override": lambda: three().contact("red", "blue", restitution=0.3, friction=0.2),
        "contact-add-to": lambda: (
            three()
            .contact("red", "blue", restitution=0.3)
            .contact("red", "blue", pitch=0.05, normal="volume")
        ),
        "contact-reversed": lambda: (
            three().contact("red", "blue", restitution=0.3).contact("blue", "red", friction=0.1)
        ),
        "contact-every-key": lambda: three().contact(
            "red",
            "blue",
            depth_of_penetration="auto",
            restitution=0.0,
            friction=0.0,
            restitution_mode="normal",
            normal=(0.0, 1.0, 0.0),
            pitch=0.0,
            centroid=("blue", (0.5, 0.0, 0.0)),
        ),  # fmt: skip
        "contact-centroid-stiffness": lambda: three().contact("red", "blue", centroid="stiffness"),
        "contact-centroid-point": lambda: three().contact("red", "wall", centroid=(0, 10, 0.5)),
        "contact-obstacle": lambda: three().contact("wall", "red", restitution=0.1),
        "contact-rigid-obstacle-auto": lambda: three().contact(
            "red", "wall", depth_of_penetration="auto"
        ),
        "contact-objects": lambda: _contact_objects(),
        "contact-auto-default": lambda: three(depth_of_penetration="auto"),
        "contact-centroid-default-in-vehicle": lambda: three(centroid=("red", (1.0, 0.0, 0.0))),
        "contact-centroid-not-in-pair-error": lambda: three().contact(
            "green", "blue", centroid=("red", (0.5, 0.0, 0.0))
        ),
        "contact-centroid-word-error": lambda: three().contact("red", "blue", centroid="middle"),
        "contact-same-error": lambda: three().contact("red", "red", restitution=0.1),
        "contact-two-obstacles-error": lambda: three().contact("wall", "pole", restitution=0.1),
        "contact-unknown-error": lambda: three().contact("red", "yellow", restitution=0.1),
        "contact-bad-value-error": lambda: three().contact("red", "blue", restitution=1.5),
        "contact-mode-error": lambda: three().contact("red", "blue", restitution_mode=1),
        "contact-normal-error": lambda: three().contact("red", "blue", normal="down"),
        "contact-auto-no-stiffness-error": lambda: three().contact(
            "red", "green", depth_of_penetration="auto"
        ),
        "contact-auto-partial-obstacle-error": lambda: _partial_obstacle(),
        "contact-no-contact-pair-error": lambda: (
            three().no_contact("red", "blue").contact("red", "blue", restitution=0.1)
        ),
        "no-contact": lambda: three().no_contact("red", "blue").no_contact("wall", "green"),
        "no-contact-same-error": lambda: three().no_contact("red", "red"),
        "no-contact-obstacles-error": lambda: three().no_contact("wall", "pole"),
        "no-contact-overridden-error": lambda: (
            three().contact("blue", "red", restitution=0.1).no_contact("red", "blue")
        ),
        "no-contact-soft-error": lambda: (
            three().soft_contact("red", "blue", 1e5).no_contact("red", "blue")
        ),
        "soft-contact": lambda: (
            three()
            .soft_contact("red", "blue", 2e5, 0.3)
            .soft_contact("wall", "green", stiffness=1e6)
        ),
        "soft-contact-int": lambda: three().soft_contact("red", "blue", 200000, 1),
        "soft-contact-again": lambda: (
            three().soft_contact("red", "blue", 2e5).soft_contact("blue", "red", 3e5, 0.1)
        ),
        "soft-contact-stiff-error": lambda: three().soft_contact("red", "blue", 1e9),
        "soft-contact-zeta-error": lambda: three().soft_contact("red", "blue", 1e5, 3.0),
        "soft-contact-str-error": lambda: three().soft_contact("red", "blue", "soft"),
        "soft-contact-same-error": lambda: three().soft_contact("red", "red", 1e5),
        "soft-contact-obstacles-error": lambda: three().soft_contact("wall", "pole", 1e5),
        "soft-contact-no-contact-error": lambda: (
            three().no_contact("red", "blue").soft_contact("red", "blue", 1e5)
        ),
        "contact-parameters-unknown-error": lambda: three().contact_parameters("red", "x"),
    }


def _contact_objects() -> cs.Scene:
    scene = two_boxes()
    red, blue = scene.vehicles
    return scene.contact(blue, red, restitution=0.4)


def _partial_obstacle() -> cs.Scene:
    scene = two_boxes()
    half = cs.Obstacle.wall(5.0, stiffness={"front": {"A": 5e4, "B": 5e5}}, name="half")
    scene.add_obstacle(half, (0.0, 10.0, 0.0))
    return scene.contact("red", "half", depth_of_penetration="auto")


def human_cases() -> dict[str, Callable[[], Any]]:
    def with_car(ground: Any = None, **defaults: Any) -> cs.Scene:
        scene = cs.Scene(ground=cs.Ground() if ground is None else ground, **defaults)
        scene.add(cs.Vehicle.generate("sedan", name="car"), (-6.0, 0.0),
                  velocity=(11.0, 0.0, 0.0))  # fmt: skip
        return scene

    return {
        "pedestrian-standing": lambda: with_car().add(
            cs.Pedestrian(1.75, 75.0, "male"), (0.0, 0.0), heading=math.pi / 2
        ),
        "pedestrian-walking": lambda: (
            with_car(normal="volume", friction=0.3)
            .add(
                cs.Pedestrian(pose="walking", name="ped"),
                (0.0, 0.5),
                heading=1.2,
                velocity=(0.0, 1.4, 0.0),
            )  # fmt: skip
            .soft_contact("car", _ped(), 2e5, 0.5)
        ),
        "pedestrian-female-xyz": lambda: with_car(cs.Ground(height=0.2)).add(
            cs.Pedestrian(1.62, 60.0, "female", name="p2"), (0.0, 0.0, 0.25)
        ),
        "pedestrian-percentile": lambda: with_car().add(
            cs.Pedestrian(percentile=95, name="tall"), (0.0, 1.0), heading=0
        ),
        "pedestrian-terrain": lambda: with_car(cs.Ground(terrain=sheet(slope=0.03))).add(
            cs.Pedestrian(), (0.0, 0.0)
        ),
        "pedestrian-two": lambda: (
            with_car()
            .add(cs.Pedestrian(name="p1"), (0.0, 0.0))
            .add(cs.Pedestrian(name="p2", pose="walking"), (0.0, 2.0), heading=-0.5)
        ),
        "pedestrian-no-ground-error": lambda: cs.Scene().add(cs.Pedestrian(), (0.0, 0.0)),
        "pedestrian-twice-error": lambda: (
            with_car().add(cs.Pedestrian(), (0.0, 0.0)).add(cs.Pedestrian(), (0.0, 3.0))
        ),
        "pedestrian-off-terrain-error": lambda: cs.Scene(
            ground=cs.Ground(terrain=sheet(size=10.0))
        ).add(cs.Pedestrian(), (30.0, 0.0)),
        "pedestrian-heading-error": lambda: with_car().add(
            cs.Pedestrian(), (0.0, 0.0), heading="west"
        ),
        "cyclist": lambda: with_car(normal="volume", friction=0.3).add(
            cs.Cyclist(), (0.0, 0.0), heading=math.pi / 2, velocity=(0.0, 4.0, 0.0)
        ),
        "cyclist-soft": lambda: _cyclist_soft(),
        "cyclist-named-rider": lambda: with_car().add(
            cs.Cyclist(rider=cs.Pedestrian(pose="cycling", name="rider")), (0.0, 0.0)
        ),
        "bicycle": lambda: with_car().add(
            cs.Bicycle(), (0.0, 3.0), heading=0.4, velocity=(3.0, 1.0, 0.0)
        ),  # fmt: skip
        "bicycle-and-cyclist": lambda: (
            with_car()
            .add(cs.Bicycle(name="bike"), (0.0, 3.0))
            .add(cs.Cyclist(name="cy"), (0.0, -3.0))
        ),
        "cyclist-no-ground-error": lambda: cs.Scene().add(cs.Cyclist(), (0.0, 0.0)),
        "cyclist-twice-error": lambda: (
            with_car().add(cs.Bicycle(), (0.0, 3.0)).add(cs.Bicycle(), (0.0, 8.0))
        ),
        "cyclist-name-of-pedestrian-error": lambda: (
            with_car()
            .add(cs.Pedestrian(name="x"), (0.0, 3.0))
            .add(cs.Bicycle(name="x"), (0.0, 8.0))
        ),
        "soft-pedestrian-bad-error": lambda: (
            with_car()
            .add(cs.Pedestrian(), (0.0, 0.0))
            .soft_contact("car", cs.Pedestrian(name="elsewhere"), 1e5)
        ),
    }


def _ped() -> cs.Pedestrian:
    return cs.Pedestrian(pose="walking", name="ped")


def _cyclist_soft() -> cs.Scene:
    scene = cs.Scene(ground=cs.Ground(friction=0.8), normal="volume", friction=0.3)
    car = cs.Vehicle.generate("sedan", name="car")
    scene.add(car, (-6.0, 0.0), velocity=(11.0, 0.0, 0.0))
    c = cs.Cyclist()
    scene.add(c, (0.0, 0.0), heading=math.pi / 2)
    return scene.soft_contact(car, c, 2e5).contact("car", "cyclist/frame", friction=0.2)


def run_setting_cases() -> dict[str, Callable[[], Any]]:
    def s() -> cs.Scene:
        return two_boxes()

    def g() -> cs.Scene:
        scene = cs.Scene(ground=cs.Ground())
        scene.add(wheeled(), (0.0, 0.0))
        return scene

    return {
        "settings-until-word-error": lambda: g().to_spec(until="stop"),
        "settings-rest-no-ground-error": lambda: s().to_spec(until="rest"),
        "settings-rest-both-error": lambda: g().to_spec(2.0, until="rest", max_duration=3.0),
        "settings-max-duration-error": lambda: g().to_spec(max_duration=3.0),
        "settings-duration-str-error": lambda: s().to_spec("long"),
        "settings-duration-negative-error": lambda: s().to_spec(-1.0),
        "settings-dt-error": lambda: s().to_spec(1.0, 0.0),
        "settings-dt-str-error": lambda: s().to_spec(1.0, "fine"),
        "settings-interval-error": lambda: s().to_spec(1.0, record_interval=-1.0),
        "settings-interval-str-error": lambda: s().to_spec(1.0, record_interval="often"),
        "settings-bytes-bool-error": lambda: s().to_spec(1.0, max_history_bytes=True),
        "settings-bytes-zero-error": lambda: s().to_spec(1.0, max_history_bytes=0),
        "settings-bytes-float-error": lambda: s().to_spec(1.0, max_history_bytes=1.5),
        "settings-bytes-small-error": lambda: s().to_spec(10.0, max_history_bytes=100),
        "settings-bytes-numpy": lambda: (
            s().to_spec(1.0, max_history_bytes=np.int64(2**20)).to_json()
        ),
        "settings-run-bytes-error": lambda: s().run(10.0, max_history_bytes=100),
        "settings-run-rest-no-ground-error": lambda: s().run(until="rest"),
    }


# -- runs ----------------------------------------------------------------------------------


def describe_result(result: cs.Result) -> list[str]:
    lines = [f"vehicles: {result.vehicles}", f"impacts: {dump(result.impacts)}"]
    for name in result.vehicles:
        t = result.trajectory(name)
        lines.append(f"trajectory {name}: {dump(t)}")
        if result.on_ground:
            lines.append(f"rest {name}: {dump(result.rest(name))}")
    lines.append(f"joints: {dump(result.joints)}")
    return lines


def run_cases() -> dict[str, Callable[[], Any]]:
    def raw(scene: cs.Scene, *args: Any, **kw: Any) -> list[str]:
        out = scene.to_spec(*args, **kw).run()
        return [f"raw: {dump(out)}"]

    def ran(scene: cs.Scene, *args: Any, **kw: Any) -> list[str]:
        return describe_result(scene.run(*args, **kw))

    def overlapping() -> cs.Scene:
        scene = cs.Scene()
        scene.add(box("a"), (0.0, 0.0, 0.7)).add(box("b"), (1.0, 0.5, 0.7))
        scene.add(box("c"), (20.0, 0.0, 0.7))
        scene.add_obstacle(cs.Obstacle.pole(0.3), (20.5, 0.0, 0.0))
        return scene

    def joined_overlapping() -> cs.Scene:
        scene = cs.Scene(ground=cs.Ground())
        scene.add(box("a"), (0.0, 0.0)).add(box("b"), (1.0, 0.0))
        return scene.join("a", "b", at=(0.5, 0.0, 0.7))

    def below_ground() -> cs.Scene:
        scene = cs.Scene(ground=cs.Ground())
        scene.add(wheeled(), (0.0, 0.0, -0.5))
        return scene

    def leaves_terrain() -> cs.Scene:
        scene = cs.Scene(ground=cs.Ground(terrain=sheet()))
        scene.add(wheeled(), (10.0, 0.0), heading=0.0, velocity=(10.0, 0.0, 0.0))
        return scene

    def rolling() -> cs.Scene:
        scene = cs.Scene(ground=cs.Ground(friction=0.8))
        scene.add(wheeled(), (0.0, 0.0), velocity=(10.0, 0.0, 0.0))
        return scene

    def pedestrian() -> cs.Scene:
        scene = cs.Scene(ground=cs.Ground(), normal="volume", friction=0.3)
        car = cs.Vehicle.generate("sedan", name="car")
        scene.add(car, (-2.9, 0.0), velocity=(11.0, 0.0, 0.0))
        ped = cs.Pedestrian()
        scene.add(ped, (0.0, 0.0), heading=math.pi / 2)
        return scene.soft_contact(car, ped, 2e5)

    def caravan() -> cs.Scene:
        car = cs.Vehicle.generate("sedan", name="car")
        lo = (car.mesh.bounds[0] - car.cg)[0]
        car = car.with_hitch(car.cg + [lo - 0.15, 0.0, 0.45 - car.cg[2]], "ball")
        van = cs.Trailer.generate("caravan", coupler_height=0.45)
        scene = cs.Scene(ground=cs.Ground(friction=0.8))
        steer = cs.DriverInputs(steer=np.array([[0.0, 0.0], [0.3, 0.05], [1.0, 0.05]]))
        scene.add(car, (0.0, 0.0), velocity=(14.0, 0.0, 0.0), inputs=steer, trailers=[van],
                  coupling={"limits": {"swing": (0.0, 1.2)}})  # fmt: skip
        return scene

    def wall() -> cs.Scene:
        scene = cs.Scene(ground=cs.Ground(), depth_of_penetration="auto", centroid="stiffness")
        scene.add(wheeled(stiffness=SEDAN), (-6.0, 0.0), velocity=(12.0, 0.0, 0.0))
        scene.add_obstacle(cs.Obstacle.wall(6.0, 0.5, 1.5), (0.0, 0.0), heading=math.pi / 2)
        return scene

    return {
        "raw-two-boxes": lambda: raw(two_boxes(), 0.5, 1e-3),
        "raw-two-boxes-auto": lambda: raw(two_boxes(depth_of_penetration="auto"), 0.5, 1e-3),
        "raw-rolling-rest": lambda: raw(rolling(), until="rest", max_duration=1.0),
        "raw-pedestrian": lambda: raw(pedestrian(), 0.25, 2e-4, record_interval=0.01),
        "raw-caravan": lambda: raw(caravan(), 0.8, 1e-3, record_interval=0.01),
        "raw-wall": lambda: raw(wall(), 0.4, 1e-3),
        "run-two-boxes": lambda: ran(two_boxes(), 0.5, 1e-3),
        "run-two-boxes-auto": lambda: ran(
            two_boxes(depth_of_penetration="auto", centroid="stiffness"), 0.5, 1e-3
        ),
        "run-rolling-not-at-rest": lambda: ran(rolling(), until="rest", max_duration=0.5),
        "run-rolling-duration-rest": lambda: ran(rolling(), 0.5, until="rest"),
        "run-pedestrian": lambda: ran(pedestrian(), 0.2, 2e-4, record_interval=0.01),
        "run-caravan": lambda: ran(caravan(), 0.5, 1e-3, record_interval=0.01),
        "run-wall": lambda: ran(wall(), 0.4, 1e-3),
        "run-progress": lambda: _progress_run(),
        "run-overlap-error": lambda: ran(overlapping(), 0.1),
        "run-joined-overlap": lambda: ran(joined_overlapping(), 0.1),
        "run-below-ground-error": lambda: ran(below_ground(), 0.1),
        "run-leaves-terrain-error": lambda: ran(leaves_terrain(), 2.0),
        "run-pickled": lambda: ran(pickle.loads(pickle.dumps(two_boxes())), 0.4, 1e-3),
        "build-world": lambda: type(two_boxes().build_world()).__qualname__,
    }


def _progress_run() -> list[str]:
    seen: list[float] = []
    result = two_boxes().run(0.3, 1e-3, progress=seen.append)
    # how often progress is called depends on wall time: only that it took floats
    return [*describe_result(result), f"progress floats: {all(isinstance(t, float) for t in seen)}"]


# -- studies: with_, overrides, batches -----------------------------------------------------


def study_cases() -> dict[str, Callable[[], Any]]:
    from crashsim.batch import run_batch
    from crashsim.studies import paths

    def seed() -> cs.Scene:
        scene = two_boxes()
        scene.add_obstacle(cs.Obstacle.wall(5.0, name="wall"), (0.0, 10.0, 0.0))
        return scene

    def grounded() -> cs.Scene:
        scene = cs.Scene(ground=cs.Ground(friction=0.8))
        scene.add(wheeled("red"), (-8.0, 0.0), velocity=(15.0, 0.0, 0.0))
        scene.add(wheeled("blue"), (0.0, -1.0), heading=1.5)
        return scene

    def walker() -> cs.Scene:
        scene = cs.Scene(ground=cs.Ground(), normal="volume", friction=0.3)
        car = cs.Vehicle.generate("sedan", name="car")
        scene.add(car, (-6.0, 0.0), velocity=(11.0, 0.0, 0.0))
        ped = cs.Pedestrian(name="ped")
        scene.add(ped, (0.0, 0.0), heading=math.pi / 2)
        return scene.soft_contact(car, ped, 2e5).contact("car", "ped/head", friction=0.2)

    out: dict[str, Callable[[], Any]] = {}
    changes = {
        "speed": (seed, {"red.speed": 12.0}),
        "direction": (seed, {"red.direction": 0.2}),
        "velocity": (seed, {"blue.velocity_x": 1.0, "blue.velocity_y": 3.0}),
        "heading-speed": (seed, {"red.heading": 0.1, "red.speed": 20.0}),
        "position": (seed, {"red.position_x": -6.0, "blue.position_y": -4.0}),
        "yaw-rate": (seed, {"red.yaw_rate": 0.3}),
        "mass": (seed, {"red.mass": 1800.0}),
        "restitution": (seed, {"restitution": 0.2, "friction": 0.4}),
        "dtp-nan": (seed, {"depth_of_penetration": float("nan")}),
        "pitch": (seed, {"pitch": 0.05}),
        "pair": (seed, {"red/blue.restitution": 0.5, "wall/red.friction": 0.2}),
        "ground": (grounded, {"ground.friction": 0.4, "red.mass": 2000.0}),
        "ground-position": (grounded, {"red.position_x": -9.0, "blue.heading": 1.2}),
        "ground-body-friction": (grounded, {"ground.body_friction": 0.3}),
        "ped-height": (walker, {"ped.height": 1.6}),
        "ped-pose-mass": (walker, {"ped.pose": 1, "ped.mass": 60.0}),
        "ped-place": (walker, {"ped.position_x": 0.5, "ped.heading": 1.0, "ped.speed": 1.2}),
        "ped-percentile": (walker, {"ped.percentile": 5.0}),
        "ped-pair": (
            walker,
            {"car/ped.friction": 0.4, "car/ped.stiffness": 3e5, "car/ped.damping_ratio": 0.3},
        ),  # fmt: skip
        "unknown-error": (seed, {"red.sped": 10.0}),
        "both-error": (seed, {"red.speed": 10.0, "red.velocity_x": 3.0}),
        "not-mapping-error": (seed, [("red.speed", 1.0)]),
        "ped-bad-error": (walker, {"ped.height": 3.5}),
    }
    for name, (make, change) in changes.items():
        out[f"with-{name}"] = lambda m=make, c=change: m().with_(c)
    out["with-keywords"] = lambda: seed().with_(restitution=0.3)
    out["with-run"] = lambda: describe_result(
        seed().with_({"red.speed": 15.0, "restitution": 0.3}).run(0.4, 1e-3)
    )
    out["with-ped-run"] = lambda: describe_result(
        walker().with_({"ped.height": 1.6, "car/ped.stiffness": 3e5}).run(0.2, 2e-4)
    )

    def batch() -> list[str]:
        values = {
            "red.speed": np.array([15.0, 20.0, 25.0]),
            "restitution": np.array([0.1, 0.2, 0.3]),
        }
        arrays = paths.overrides(seed(), values)
        b = run_batch(seed(), arrays, duration=0.5, dt=1e-3, threads=1)
        return [f"arrays: {dump(arrays)}", f"batch: {dump(vars(b))}"]

    out["batch"] = batch
    out["apply-overrides"] = lambda: paths.apply_overrides(
        seed(), paths.overrides(seed(), {"blue.speed": np.array([3.0, 4.0])}), 1
    )
    return out


def main(out: Path) -> None:
    out.mkdir(parents=True, exist_ok=True)
    groups = (
        construction_cases,
        vehicle_cases,
        trailer_cases,
        obstacle_cases,
        joint_cases,
        contact_cases,
        human_cases,
        run_setting_cases,
        run_cases,
        study_cases,
    )
    total = hashlib.sha256()
    n = 0
    for group in groups:
        for name, make in group().items():
            text = case(make)
            (out / f"{name}.txt").write_text(text, encoding="utf-8")
            total.update(name.encode() + b"\0" + text.encode() + b"\0")
            n += 1
    print(f"{n} cases")
    print(f"sha256 {total.hexdigest()}")


if __name__ == "__main__":
    if len(sys.argv) != 2:
        sys.exit("usage: scene_fingerprint.py OUTPUT_FOLDER")
    main(Path(sys.argv[1]))
