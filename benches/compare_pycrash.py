"""crashsim's vehicle motion side by side with pycrash's (crashsim issue 11).

The same manoeuvres of the same car run in crashsim (``crashsim._core.World`` with ground,
wheels and tyres, docs/model.md "Vehicles on the ground") and in pycrash 0.0.18's planar
vehicle model (``pycrash.vehicle_model.vehicle_model`` for one vehicle, ``pycrash.Impact``
with "IMPC" for two), and the figures are printed side by side with the closed forms:

1. **Locked-wheel skid** from 20 m/s to rest: distance and time against v^2 / (2 mu g) and
   v / (mu g).
2. **Steady cornering** at 0.2 g, 20 m/s, constant road-wheel angle: yaw rate against the
   linear single-track gain r / delta = u / (L + K u^2).
3. **Step steer** to 0.4 g at 20 m/s (ramped over 0.1 s): peak yaw rate and lateral
   acceleration and their timing, against the linear single-track model's response.
4. **Braking in a turn** (combined slip): steady 0.4 g turn, then every wheel braked at half
   the friction to rest: rest position and heading, peak yaw rate, time and path to rest.
5. **Impact with run-out**: a 90 deg intersection impact of two of the cars, both sliding to
   rest on locked wheels after it: delta-V, rest positions and headings.
6. **Speed**: wall time per simulated second of each side, for the skid and for the impact
   scene, at the same 1 ms step and at pycrash's default 10 ms, as ratios of medians.

The car (both sides): 1500 kg, CG 1.1 m behind the front axle and 1.6 m ahead of the rear one
(wheelbase 2.7 m), track 1.55 m, CG 0.55 m above the ground, tyre radius 0.3 m, a box body
4.6 x 1.8 x 1.4 m (front overhang 0.9 m, rear 1.0 m, from 0.15 m above the ground), yaw inertia
m (L / 2)^2 = 2734 kg m^2 (roll and pitch inertia of the uniform box: crashsim only). Tyre-road
friction 0.8. The reconstruction tyre on both sides: lateral force linear in the slip angle
with cornering stiffness C = Fz / 10 deg up to mu Fz (crashsim's default since issue 19;
pycrash's with its default alpha_max = 10 deg, which it scales by mu to saturate at mu x 10
deg), locked wheels sliding at mu Fz against the patch velocity. Both front wheels steer alike
(crashsim's linkage set to parallel steer with the axle centre's angle as the input) so the
closed forms of the single-track model apply. crashsim's rolling resistance is 0 (its
default; pycrash has none); every other crashsim parameter is its default (suspension 1.3 Hz,
damping ratio 0.3, no anti-roll bars at this level of the binding, relaxation length 0.1 m).
pycrash takes weight in lb and divides by 32.2 ft/s^2: the weight is set so that its mass
is 1500 kg; its g is then 9.8146 m/s^2 against crashsim's 9.80665 (0.08 %).

pycrash (GPL) is only ever imported here, guarded, and only its public functions are called.
It runs in this process when ``import pycrash`` works, else in the interpreter given by
``--pycrash-python`` (default /tmp/pycrash-venv/bin/python) through a subprocess that runs and
times the cases itself. pycrash 0.0.18 needs pandas < 3; set it up with
``python3 -m venv /tmp/pycrash-venv && /tmp/pycrash-venv/bin/pip install pycrash==0.0.18``.

    python3 benches/compare_pycrash.py                 # every case; 25-33 min (pycrash)
    python3 benches/compare_pycrash.py --pycrash-repeats 1   # the timed scenes once, not 3x
    python3 benches/compare_pycrash.py --quick         # pycrash at 10 ms, once; ~2 min
    python3 benches/compare_pycrash.py --only skid,corner --plot out/compare_pycrash.png

Results and the differences explained: benches/COMPARISON.md, section "pycrash: vehicle
motion".
"""

from __future__ import annotations

import argparse
import contextlib
import copy
import datetime
import io
import json
import math
import os
import statistics
import sys
import time
import warnings
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np
from pycrash_peer import (  # benches/pycrash_peer.py (this folder is on sys.path)
    DEFAULT_PYCRASH_PYTHON,
    git_revision,
    pycrash_imports,
    run_worker,
    worker_environment,
)

# -- configuration ---------------------------------------------------------------------------

G = 9.80665  # m/s^2, crashsim's gravity
MU = 0.8  # tyre-road friction
ALPHA_SAT = math.radians(10.0)  # saturation angle of the reconstruction tyre (rad)
DT = 1e-3  # s, the common step
PYCRASH_DEFAULT_DT = 0.01  # s, pycrash's default step (Impact, Vehicle)
REST_SPEED = 0.05  # m/s   } crashsim's rest criterion, applied to pycrash's traces too
REST_YAW_RATE = math.radians(0.5)  # rad/s
REST_TIME = 0.2  # s

CASES = ("skid", "corner", "step", "lane", "brake_turn", "impact", "speed")

# pycrash units (ft, lb, mph, slug)
M_PER_FT = 0.3048
N_PER_LB = 4.4482216152605
KG_PER_SLUG = 14.593902937206364
KGM2_PER_SLUGFT2 = 1.3558179483314004
M_S_PER_MPH = 0.44704
G_PYCRASH = 32.2  # ft/s^2: pycrash's mass is weight / 32.2


@dataclass(frozen=True)
class Car:
    """The car of every case (SI; body frame x forward, y left, z up, origin at the CG)."""

    mass: float = 1500.0
    a: float = 1.1  # CG to front axle
    b: float = 1.6  # CG to rear axle
    track: float = 1.55
    h_cg: float = 0.55  # CG above the ground
    radius: float = 0.3  # tyre
    length: float = 4.6
    width: float = 1.8
    height: float = 1.4
    front_overhang: float = 0.9
    clearance: float = 0.15  # the box's underside above the ground

    @property
    def wheelbase(self) -> float:
        return self.a + self.b

    @property
    def rear_overhang(self) -> float:
        return self.length - self.wheelbase - self.front_overhang

    @property
    def izz(self) -> float:
        return self.mass * (0.5 * self.wheelbase) ** 2

    @property
    def inertia(self) -> np.ndarray:
        m, lx, ly, lz = self.mass, self.length, self.width, self.height
        return np.diag([m / 12 * (ly**2 + lz**2), m / 12 * (lx**2 + lz**2), self.izz])

    @property
    def wheel_xy(self) -> np.ndarray:
        """Front left, front right, rear left, rear right (m from the CG)."""
        a, b, t = self.a, self.b, self.track / 2
        return np.array([[a, t], [a, -t], [-b, t], [-b, -t]])

    @property
    def box_center(self) -> np.ndarray:
        x = (self.a + self.front_overhang - (self.b + self.rear_overhang)) / 2
        z = self.clearance + self.height / 2 - self.h_cg
        return np.array([x, 0.0, z])


CAR = Car()


# -- traces: what each side's run is reduced to ----------------------------------------------


@dataclass
class Trace:
    """One vehicle's run in crashsim's convention: world x east, y north, yaw and yaw rate
    counter-clockwise seen from above, body y left. SI units."""

    t: np.ndarray
    x: np.ndarray
    y: np.ndarray
    yaw: np.ndarray  # rad, unwrapped
    u: np.ndarray  # forward speed (m/s)
    speed: np.ndarray  # horizontal CG speed (m/s)
    r: np.ndarray  # yaw rate (rad/s)
    ay: np.ndarray  # lateral acceleration (horizontal force / m, body left; m/s^2)
    loads: np.ndarray  # (4, k) wheel loads (N): FL, FR, RL, RR
    rest: float | None = None  # when it came to rest (s)
    extra: dict[str, Any] = field(default_factory=dict)

    def at(self, time_s: float) -> int:
        return min(int(np.searchsorted(self.t, time_s - 1e-9)), len(self.t) - 1)


def rest_time(t: np.ndarray, speed: np.ndarray, r: np.ndarray) -> float | None:
    """crashsim's rest criterion on a trace: the first time from which the speed stays below
    REST_SPEED and the yaw rate below REST_YAW_RATE for REST_TIME (or to the end, if the run
    ends at least REST_TIME later)."""
    slow = (speed < REST_SPEED) & (np.abs(r) < REST_YAW_RATE)
    since = None
    for k in range(len(t)):
        if slow[k]:
            if since is None:
                since = k
            if t[k] - t[since] >= REST_TIME - 1e-9:
                return float(t[since])
        else:
            since = None
    return None


def first_below(t: np.ndarray, speed: np.ndarray, v: float = REST_SPEED) -> float | None:
    k = np.flatnonzero(speed < v)
    return float(t[k[0]]) if len(k) else None


# -- crashsim --------------------------------------------------------------------------------


def _yaw_of(q: np.ndarray) -> np.ndarray:
    """Heading of the body x axis seen from above, from quaternions (k, 4) (w, x, y, z)."""
    w, x, y, z = q[:, 0], q[:, 1], q[:, 2], q[:, 3]
    return np.unwrap(np.arctan2(2 * (w * z + x * y), 1 - 2 * (y * y + z * z)))


class Setup:
    """A scene being set up through the binding's SceneSpec (its setup calls), run as a World
    is: ``ready()`` builds the world (outside the timings), ``run`` builds and runs it."""

    def __init__(self, core: Any) -> None:
        self.core = core
        self.spec = core.SceneSpec()

    def __getattr__(self, name: str) -> Any:
        return getattr(self.spec, name)

    def set_contact(self, body1: int, body2: int, **params: Any) -> None:
        self.spec.set_contact(body1, body2, self.core.ContactParams(**params))

    def set_ground(self, **kwargs: Any) -> None:
        self.spec.set_ground(self.core.Ground(**kwargs))

    def ready(self) -> Any:
        return self.spec.build()

    def run(self, duration: float, dt: float, **options: Any) -> Any:
        return self.ready().run(duration, dt, **options)


def _ready(w: Any) -> Any:
    """The world to time: a Setup built, anything else as it is."""
    return w.ready() if isinstance(w, Setup) else w


class Crashsim:
    """crashsim's side, through the binding (the Python vehicle layer is not there yet)."""

    def __init__(self, car: Car) -> None:
        import trimesh
        from crashsim import _core

        self.core = _core
        self.car = car
        box = trimesh.creation.box(extents=(car.length, car.width, car.height))
        box.apply_translation(car.box_center)
        self.shape = _core.Shape(np.asarray(box.vertices), np.asarray(box.faces))
        self.loads = _core.static_loads(car.wheel_xy, car.mass * G)
        springs = [_core.suspension(float(f)) for f in self.loads]
        self.spring_rates = [s[0] for s in springs]
        self.damping = [s[1] for s in springs]
        self.centers = np.column_stack([car.wheel_xy, np.full(4, car.radius - car.h_cg)])

    def world(self) -> Setup:
        w = Setup(self.core)
        w.set_ground(tyre_friction=MU)
        return w

    def add_car(
        self,
        w: Any,
        pos: tuple[float, float],
        yaw: float,
        speed: float,
        steer: np.ndarray | None = None,
        brake: float | np.ndarray | None = None,
        switches: list[tuple[int, str, float, str, float]] | None = None,
        rolling_resistance: float = 0.0,
        relaxation_length: float | None = None,
    ) -> int:
        """A car at rest on its springs at pos (m), heading yaw (rad), rolling at speed (m/s);
        steer a (k, 2) table of (s, road-wheel rad); brake a (k, 2) table of (s, fraction of
        the friction) for every wheel; wheel-state switches as the binding takes them."""
        c = self.car
        q = np.array([math.cos(yaw / 2), 0.0, 0.0, math.sin(yaw / 2)])
        v = (speed * math.cos(yaw), speed * math.sin(yaw), 0.0)
        i = w.add_body(self.shape, c.mass, c.inertia, (pos[0], pos[1], c.h_cg), q, v, (0, 0, 0))
        w.set_vehicle(
            i,
            centers=self.centers,
            radii=[c.radius] * 4,
            steerable=[True, True, False, False],
            static_loads=self.loads,
            spring_rates=self.spring_rates,
            damping=self.damping,
            tyre=self.core.Tyre(
                "linear",
                rolling_resistance=rolling_resistance,
                relaxation_length=relaxation_length,
            ),
            ackermann=0.0,
            steering_reference="centre",
            steer=None if steer is None else ("road_wheel", steer),
            brake=[("fraction", np.asarray(brake), None)] * 4 if brake is not None else [],
            switches=switches or [],
        )
        return i

    def run(self, w: Any, duration: float, dt: float = DT) -> dict[str, Any]:
        return w.run(duration, dt, until_rest=True)

    def trace(self, out: dict[str, Any], body: int = 0) -> Trace:
        return crashsim_trace(out, body, self.car)


def crashsim_trace(out: dict[str, Any], body: int, car: Car) -> Trace:
    """One body of a crashsim run (``World.run``'s dict) as a trace."""
    t = np.asarray(out["t"])
    pos = out["position"][body]
    vel = out["velocity"][body]
    yaw = _yaw_of(out["orientation"][body])
    fwd = np.column_stack([np.cos(yaw), np.sin(yaw)])
    left = np.column_stack([-np.sin(yaw), np.cos(yaw)])
    w0 = 4 * body
    force = out["wheel_force"][w0 : w0 + 4].sum(axis=0)  # (k, 3), ground on the tyres
    return Trace(
        t=t,
        x=pos[:, 0],
        y=pos[:, 1],
        yaw=yaw,
        u=np.einsum("ij,ij->i", vel[:, :2], fwd),
        speed=np.hypot(vel[:, 0], vel[:, 1]),
        r=out["angular_velocity"][body][:, 2],
        ay=np.einsum("ij,ij->i", force[:, :2], left) / car.mass,
        loads=np.asarray(out["wheel_load"][w0 : w0 + 4]),
        rest=out["rest"][body],
    )


# -- pycrash: the worker (runs wherever pycrash imports; numpy and pandas only) ---------------


def pycrash_vehicle_inputs(
    car: Car, name: str, pos: tuple[float, float], yaw: float, speed: float
) -> dict[str, Any]:
    """The car in pycrash's terms: ft, lb, mph, deg; global X east, Y south, headings
    clockwise seen from above; vehicle x forward, y right."""
    ft = 1.0 / M_PER_FT
    return {
        "year": 2020,
        "vehmake": "crashsim",
        "vehmodel": "comparison car",
        "weight": car.mass / KG_PER_SLUG * G_PYCRASH,  # lb, so that weight / 32.2 = mass
        "vin": "none",
        "brake": 0.0,
        "steer_ratio": 1.0,  # the steer column is the road-wheel angle (deg)
        "init_x_pos": pos[0] * ft,
        "init_y_pos": -pos[1] * ft,
        "head_angle": -math.degrees(yaw),
        "width": car.width * ft,
        "length": car.length * ft,
        "hcg": car.h_cg * ft,
        "lcgf": car.a * ft,
        "lcgr": car.b * ft,
        "wb": car.wheelbase * ft,
        "track": car.track * ft,
        "f_hang": car.front_overhang * ft,
        "r_hang": car.rear_overhang * ft,
        "tire_d": 2 * car.radius * ft,
        "tire_w": 0.2 * ft,
        "izz": car.izz / KGM2_PER_SLUGFT2,
        "fwd": 1,
        "rwd": 0,
        "awd": 0,
        "A": 0.0,
        "B": 0.0,
        "k": 0.0,
        "L": 0.0,
        "c": 0.0,
        "vx_initial": speed / M_S_PER_MPH,
        "vy_initial": 0.0,
        "omega_z": 0.0,
    }


def pycrash_sim_defaults(dt: float) -> dict[str, float]:
    # pycrash's tyre saturates at alpha_max * mu_max: its C = Fz / alpha_max, 10 deg as
    # crashsim's linear tyre
    return {"dt_motion": dt, "mu_max": MU, "alpha_max": ALPHA_SAT}


MODEL_COLUMNS = [
    "t",
    "Dx",
    "Dy",
    "theta_rad",
    "oz_rad",
    "vx",
    "vy",
    "Vx",
    "Vy",
    "au",
    "av",
    "lf_fz",
    "rf_fz",
    "lr_fz",
    "rr_fz",
]


def _driver_frame(pd: Any, table: dict[str, list[list[float]]], dt: float, duration: float) -> Any:
    """pycrash's driver-input table on its step grid, linear between the given points."""
    t = np.round(np.arange(0.0, duration + dt / 2, dt), 6)
    cols: dict[str, Any] = {"t": t}
    for key in ("throttle", "brake", "steer"):
        pts = np.asarray(table.get(key, [[0.0, 0.0]]), dtype=float)
        cols[key] = np.interp(t, pts[:, 0], pts[:, 1])
    return pd.DataFrame(cols)


def _model_columns(model: Any) -> dict[str, list[float]]:
    return {c: [float(v) for v in model[c].to_numpy(dtype=float)] for c in MODEL_COLUMNS}


def pycrash_worker(spec: dict[str, Any]) -> dict[str, Any]:
    """Run and time each case of ``spec`` in pycrash. pycrash prints a lot: swallowed.

    Timed: ``vehicle_model`` (one vehicle) and ``Impact(...)`` + ``simulate()`` (two), each
    without pycrash's drawing data (``position_data_motion``: vehicle outlines and wheel
    corners per step, for its plots), which SingleMotion and simulate() add at their end and
    which grows faster than the run: simulate()'s call of it is replaced by a no-op while
    timing, and it is timed apart once where the case asks (``drawing``)."""
    buf = io.StringIO()
    with warnings.catch_warnings(), contextlib.redirect_stdout(buf):
        warnings.simplefilter("ignore")
        import pandas as pd
        import pycrash
        import pycrash.impact_main
        from pycrash import Impact, Vehicle
        from pycrash.model_calcs.position_data import position_data_motion
        from pycrash.vehicle_model import vehicle_model

        out: dict[str, Any] = {**worker_environment(pycrash, pd, np), "cases": {}}
        drawing = pycrash.impact_main.position_data_motion
        pycrash.impact_main.position_data_motion = lambda veh: veh
        try:
            for case in spec["cases"]:
                out["cases"][case["name"]] = _pycrash_case(
                    case, pd, Vehicle, Impact, vehicle_model, position_data_motion
                )
        finally:
            pycrash.impact_main.position_data_motion = drawing
    return out


def _pycrash_case(
    case: dict[str, Any],
    pd: Any,
    vehicle_cls: Any,
    impact_cls: Any,
    vehicle_model: Any,
    position_data_motion: Any,
) -> dict[str, Any]:
    dt, duration = case["dt"], case["duration"]
    defaults = pycrash_sim_defaults(dt)
    times: list[float] = []
    res: dict[str, Any] = {}
    for _ in range(case.get("repeats", 1)):
        vehicles = []
        for vs in case["vehicles"]:
            veh = vehicle_cls(vs["name"], vs["inputs"])
            veh.driver_input = _driver_frame(pd, vs["driver"], dt, duration)
            veh.isTrailer = False  # 0.0.18's Vehicle never sets it; Impact reads it
            vehicles.append(veh)
        if case["kind"] == "single":
            vehicles[0].striking = False  # as SingleMotion sets it
            t0 = time.perf_counter()
            veh = vehicle_model(vehicles[0], copy.deepcopy(defaults))
            times.append(time.perf_counter() - t0)
            res = {"models": [_model_columns(veh.model)]}
            sims = [veh]
        else:
            imp = case["impact"]
            vehicles[0].striking = True
            vehicles[0].impact_points = [tuple(imp["point"])]
            vehicles[1].striking = False
            vehicles[1].edgeimpact = [imp["edge"]]
            vehicles[1].edgeimpact_points = [tuple(imp["edge_points"])]
            t0 = time.perf_counter()
            sim = impact_cls(
                "crashsim comparison",
                duration,
                "IMPC",
                vehicles,
                impact_order=[[0, 1]],
                impc_inputs={0: {"vehicle_mu": imp["mu"], "cor": imp["cor"]}},
                user_sim_defaults=copy.deepcopy(defaults),
            )
            sim.simulate(show_results=False)
            times.append(time.perf_counter() - t0)
            res = {
                "models": [_model_columns(v.model) for v in sim.vehicles],
                "impact_index": [int(k) for k in sorted(sim._impactIndex)],
                "impc": _plain(sim.impc_results.get(0)),
            }
            sims = sim.vehicles
    if case.get("drawing"):
        t0 = time.perf_counter()
        for veh in sims:
            position_data_motion(veh)
        res["drawing_time"] = time.perf_counter() - t0
    res["times"] = times
    return res


def _plain(obj: Any) -> Any:
    """JSON-safe copy (numpy scalars to floats)."""
    if isinstance(obj, dict):
        return {str(k): _plain(v) for k, v in obj.items()}
    if isinstance(obj, (list, tuple)):
        return [_plain(v) for v in obj]
    if isinstance(obj, (bool, str)) or obj is None:
        return obj
    try:
        return float(obj)
    except (TypeError, ValueError):
        return str(obj)


def run_pycrash(spec: dict[str, Any], python: str | None) -> tuple[dict[str, Any], str]:
    """(worker output, where it ran). Raises RuntimeError when pycrash cannot be run."""
    if pycrash_imports() and not python:
        return pycrash_worker(spec), "this process"
    return run_worker(__file__, spec, python, tail=8)


def pycrash_trace(model: dict[str, list[float]]) -> Trace:
    """A pycrash model table in crashsim's convention (Y south -> y north, clockwise ->
    counter-clockwise, vehicle y right -> left), SI.

    pycrash integrates the body-frame velocity (vx, vy, with the yaw-rate terms) and the
    world-frame velocity (Vx, Vy, from the forces turned by the heading) separately, and its
    positions come from the latter. The two part after a fast spin, so a vehicle whose
    body-frame velocity (the one its tyres see) has come to rest can keep a world velocity
    and drift. The speed and the rest criterion here use the body-frame velocity; the world
    speed at the end is kept as ``extra["drift"]``."""
    m = {k: np.asarray(v, dtype=float) for k, v in model.items()}
    ft = M_PER_FT
    t = m["t"]
    speed = np.hypot(m["vx"], m["vy"]) * ft
    r = -m["oz_rad"]
    loads = np.vstack([m["lf_fz"], m["rf_fz"], m["lr_fz"], m["rr_fz"]]) * N_PER_LB
    return Trace(
        t=t,
        x=m["Dx"] * ft,
        y=-m["Dy"] * ft,
        yaw=-m["theta_rad"],
        u=m["vx"] * ft,
        speed=speed,
        r=r,
        ay=-m["av"] * ft,
        loads=loads,
        rest=rest_time(t, speed, r),
        extra={"drift": float(np.hypot(m["Vx"][-1], m["Vy"][-1]) * ft)},
    )


# -- the cases -------------------------------------------------------------------------------


@dataclass
class Case:
    """One manoeuvre: its crashsim run, its pycrash spec and, once run, both traces."""

    name: str
    title: str
    cs_out: dict[str, Any]
    cs_wall: float
    spec: dict[str, Any]
    steer: np.ndarray | None = None  # the road-wheel angle table (s, rad), if any
    cs: list[Trace] = field(default_factory=list)
    pc: list[Trace] = field(default_factory=list)
    extra: dict[str, Any] = field(default_factory=dict)


def steer_table(points: list[tuple[float, float]]) -> np.ndarray:
    return np.array(points, dtype=float)


def single_spec(
    name: str,
    duration: float,
    dt: float,
    speed: float,
    steer: np.ndarray | None = None,
    brake: np.ndarray | None = None,
    repeats: int = 1,
    drawing: bool = False,
) -> dict[str, Any]:
    driver: dict[str, list[list[float]]] = {}
    if steer is not None:  # pycrash steers right for a positive angle: our left is negative
        driver["steer"] = [[float(t), -math.degrees(v)] for t, v in steer]
    if brake is not None:
        driver["brake"] = [[float(t), float(v)] for t, v in brake]
    return {
        "name": name,
        "kind": "single",
        "dt": dt,
        "duration": duration,
        "repeats": repeats,
        "drawing": drawing,
        "vehicles": [
            {
                "name": "car",
                "inputs": pycrash_vehicle_inputs(CAR, "car", (0.0, 0.0), 0.0, speed),
                "driver": driver,
            }
        ],
    }


def timed_run(side: Crashsim, build: Any, duration: float, dt: float = DT) -> tuple[Any, float]:
    w = _ready(build())
    t0 = time.perf_counter()
    out = side.run(w, duration, dt)
    return out, time.perf_counter() - t0


# manoeuvre parameters
SKID_SPEED = 20.0
CORNER_SPEED = 20.0
CORNER_G = 0.2
STEP_G = 0.4
STEP_AT = 0.5  # s, the steer ramp's start
STEP_RAMP = 0.1  # s
LANE_G = 0.3  # amplitude: the neutral-steer angle of this lateral acceleration
LANE_AT = 0.5  # s
LANE_PERIOD = 2.5  # s
TURN_G = 0.4
TURN_BRAKE_AT = 2.0  # s
TURN_BRAKE = 0.5  # fraction of the friction, every wheel
TURN_BRAKE_RAMP = 0.2  # s


def neutral_steer(speed: float, lat_g: float) -> float:
    """Road-wheel angle (rad) of a neutral-steer car turning at lat_g at speed: L / R."""
    return CAR.wheelbase * lat_g * G / speed**2


def make_skid(side: Crashsim, dt_pc: float) -> Case:
    lock = [(k, "time", 0.0, "locked", 0.0) for k in range(4)]

    def build() -> Any:
        w = side.world()
        side.add_car(w, (0.0, 0.0), 0.0, SKID_SPEED, switches=lock)
        return w

    out, wall = timed_run(side, build, 20.0)
    duration = SKID_SPEED / (MU * G) + 1.0
    spec = single_spec("skid", duration, dt_pc, SKID_SPEED, brake=np.array([[0.0, 1.0]]))
    return Case("skid", "1. locked-wheel skid from 20 m/s", out, wall, spec)


def make_corner(side: Crashsim, dt_pc: float) -> Case:
    delta = neutral_steer(CORNER_SPEED, CORNER_G)
    steer = steer_table([(0.0, 0.0), (0.5, delta)])

    def build() -> Any:
        w = side.world()
        side.add_car(w, (0.0, 0.0), 0.0, CORNER_SPEED, steer=steer)
        return w

    w = build()
    out = w.run(5.0, DT)
    spec = single_spec("corner", 5.0, dt_pc, CORNER_SPEED, steer=steer)
    case = Case("corner", "2. steady cornering at 0.2 g, 20 m/s", out, 0.0, spec)
    # the same with a rolling resistance of 0.012 (a typical car tyre's): for the notes
    w = side.world()
    side.add_car(w, (0.0, 0.0), 0.0, CORNER_SPEED, steer=steer, rolling_resistance=0.012)
    case.extra["rolling_tyre"] = w.run(5.0, DT)
    return case


def make_step(side: Crashsim, dt_pc: float) -> Case:
    delta = neutral_steer(CORNER_SPEED, STEP_G)
    steer = steer_table([(0.0, 0.0), (STEP_AT, 0.0), (STEP_AT + STEP_RAMP, delta)])
    w = side.world()
    side.add_car(w, (0.0, 0.0), 0.0, CORNER_SPEED, steer=steer)
    out = w.run(3.5, DT)
    spec = single_spec("step", 3.5, dt_pc, CORNER_SPEED, steer=steer)
    return Case("step", "3a. step steer to 0.4 g at 20 m/s (0.1 s ramp)", out, 0.0, spec, steer)


def lane_steer() -> np.ndarray:
    """One period of a sine of road-wheel angle (left, then right), as a table at 10 ms."""
    delta = neutral_steer(CORNER_SPEED, LANE_G)
    t = np.round(np.arange(0.0, LANE_PERIOD + 1e-9, 0.01), 6)
    pts = [(0.0, 0.0)] + [(LANE_AT + x, delta * math.sin(2 * math.pi * x / LANE_PERIOD)) for x in t]
    return steer_table(pts)


def make_lane(side: Crashsim, dt_pc: float) -> Case:
    steer = lane_steer()
    duration = LANE_AT + LANE_PERIOD + 1.5
    w = side.world()
    side.add_car(w, (0.0, 0.0), 0.0, CORNER_SPEED, steer=steer)
    out = w.run(duration, DT)
    spec = single_spec("lane", duration, dt_pc, CORNER_SPEED, steer=steer)
    title = "3b. lane change: one sine period of steer, 0.3 g quasi-static, 2.5 s, 20 m/s"
    case = Case("lane", title, out, 0.0, spec, steer)
    # the same with a 10x shorter relaxation length, for the notes: the tread's damper leads
    # the slip angle by 2 sqrt(sigma alpha_sat / (mu g)), 94 ms at 0.1 m, 30 ms at 0.01 m
    w = side.world()
    side.add_car(w, (0.0, 0.0), 0.0, CORNER_SPEED, steer=steer, relaxation_length=0.01)
    case.extra["short_relaxation"] = w.run(duration, DT)
    return case


def make_brake_turn(side: Crashsim, dt_pc: float) -> Case:
    delta = neutral_steer(CORNER_SPEED, TURN_G)
    steer = steer_table([(0.0, 0.0), (0.5, delta)])
    t1 = TURN_BRAKE_AT + TURN_BRAKE_RAMP
    brake = steer_table([(0.0, 0.0), (TURN_BRAKE_AT, 0.0), (t1, TURN_BRAKE)])
    w = side.world()
    side.add_car(w, (0.0, 0.0), 0.0, CORNER_SPEED, steer=steer, brake=brake)
    out = w.run(20.0, DT, until_rest=True)
    rest = out["rest"][0] or float(out["t"][-1])
    spec = single_spec(
        "brake_turn", round(rest + 1.0, 2), dt_pc, CORNER_SPEED, steer=steer, brake=brake
    )
    return Case("brake_turn", "4. braking in a 0.4 g turn (combined slip)", out, 0.0, spec)


# impact scene: B heads north at 10 m/s through the origin; A heads east at 15 m/s into B's
# left side, A's centre line IMPACT_OFFSET m north of B's CG at the impact; every wheel of
# both cars locks at the exchange
IMPACT_SPEED_A = 15.0
IMPACT_SPEED_B = 10.0
IMPACT_OFFSET = -0.5  # m: A's centre line passes 0.5 m behind B's CG (B spins)
IMPACT_GAP = 1.0  # m between A's nose and B's left side at t = 0
IMPACT_DTP = 0.030  # s, crashsim's depth of penetration
IMPACT_RESTITUTION = 0.1
IMPACT_FRICTION = 0.6


def impact_start() -> dict[str, tuple[tuple[float, float], float, float]]:
    """Initial (position, heading, speed) of A and B: at t = IMPACT_GAP / v_A the nose of A
    touches B's left side with A's centre line IMPACT_OFFSET from B's CG along B's axis."""
    t_touch = IMPACT_GAP / IMPACT_SPEED_A
    xa = -(CAR.width / 2 + IMPACT_GAP + CAR.a + CAR.front_overhang)
    return {
        "A": ((xa, 0.0), 0.0, IMPACT_SPEED_A),
        "B": ((0.0, -IMPACT_OFFSET - IMPACT_SPEED_B * t_touch), math.pi / 2, IMPACT_SPEED_B),
    }


def build_impact(side: Crashsim, centroid: tuple[float, float, float] | None = None) -> Any:
    """The impact scene; ``centroid`` fixes the impulse centroid in A's frame (m) instead of
    the engine's automatic one."""
    w = side.world()
    lock = [(k, "exchange", 1.0, "locked", 0.0) for k in range(4)]
    ids = []
    for pos, yaw, speed in impact_start().values():
        ids.append(side.add_car(w, pos, yaw, speed, switches=lock))
    fixed: dict[str, Any] = {}
    if centroid is not None:
        fixed = {"centroid": "body", "centroid_point": centroid, "centroid_body": ids[0]}
    w.set_contact(
        ids[0],
        ids[1],
        depth_of_penetration=IMPACT_DTP,
        restitution=IMPACT_RESTITUTION,
        friction=IMPACT_FRICTION,
        **fixed,
    )
    return w


def _rot_z(yaw: float) -> np.ndarray:
    c, s = math.cos(yaw), math.sin(yaw)
    return np.array([[c, -s], [s, c]])


def first_impact(out: dict[str, Any]) -> dict[str, Any]:
    """The run's first exchange (the binding's typed ``Impact``) as the fields read here."""
    imp = out["impacts"][0]
    keys = ("time", "first_contact_time", "centroid", "normal", "velocity_before",
            "velocity_after", "angular_velocity_after", "effective_mass")  # fmt: skip
    return {k: getattr(imp, k) for k in keys}


def impact_spec(
    out: dict[str, Any], dt: float, duration: float, repeats: int, drawing: bool = False
) -> dict[str, Any]:
    """pycrash's impact scene from crashsim's: the striking point at crashsim's impulse
    centroid (A's frame), the impact plane along crashsim's normal, and B's struck edge (its
    left side) moved to where the centroid lies in B's frame at the exchange, so that
    pycrash, which exchanges when the point crosses the edge, exchanges at the same poses."""
    imp = first_impact(out)
    k = int(np.searchsorted(out["t"], imp["time"] - 1e-12))
    c = np.asarray(imp["centroid"])[:2]
    n = np.asarray(imp["normal"])[:2]
    local = []
    for body in (0, 1):
        yaw = float(_yaw_of(out["orientation"][body][k : k + 1])[0])
        rt = _rot_z(yaw).T
        local.append((rt @ (c - out["position"][body][k][:2]), rt @ n))
    (ca, na), (cb, _) = local
    ft = 1.0 / M_PER_FT
    front = (CAR.a + CAR.front_overhang) * ft
    rear = (CAR.b + CAR.rear_overhang) * ft
    edge_y = -abs(cb[1]) * ft  # pycrash: y right; B's left side is at negative y
    brake_at = float(imp["time"])
    vehicles = []
    for name, (pos, yaw, speed) in impact_start().items():
        vehicles.append(
            {
                "name": name,
                "inputs": pycrash_vehicle_inputs(CAR, name, pos, yaw, speed),
                # every wheel locks at the impact (pycrash: brake 1 = locked)
                "driver": {"brake": [[0.0, 0.0], [brake_at - 1e-6, 0.0], [brake_at, 1.0]]},
            }
        )
    return {
        "name": "impact",
        "kind": "impact",
        "dt": dt,
        "duration": duration,
        "repeats": repeats,
        "drawing": drawing,
        "vehicles": vehicles,
        "impact": {
            "point": [
                float(ca[0]) * ft,
                -float(ca[1]) * ft,
                math.degrees(math.atan2(-float(na[1]), float(na[0]))),
            ],
            "edge": 3,  # the struck car's left side, rear to front in its frame
            "edge_points": [-rear, edge_y, front, edge_y],
            "mu": IMPACT_FRICTION,
            "cor": IMPACT_RESTITUTION,
            # for the report
            "centroid_a": [float(v) for v in ca],
            "centroid_b": [float(v) for v in cb],
            "time": brake_at,
        },
    }


def make_impact(side: Crashsim, dt_pc: float, repeats: int) -> Case:
    out, wall = timed_run(side, lambda: build_impact(side), 20.0)
    rest = max(r or float(out["t"][-1]) for r in out["rest"])
    # pycrash has no rest criterion: it runs for a set time, here 30 % longer than crashsim's
    duration = round(1.3 * rest + 0.5, 2)
    spec = impact_spec(out, dt_pc, duration, repeats)
    case = Case("impact", "5. intersection impact and run-out to rest", out, wall, spec)
    # the same with the impulse centroid at the CG's height (its x, y from the run above): a
    # planar impulse, as pycrash's
    ca = spec["impact"]["centroid_a"]
    planar = build_impact(side, (ca[0], ca[1], 0.0)).run(20.0, DT, until_rest=True)
    case.extra["planar"] = planar
    return case


# -- figures ---------------------------------------------------------------------------------


@dataclass
class Row:
    what: str
    unit: str
    cs: float | None
    pc: float | None
    ref: float | None = None
    fmt: str = ".3f"
    # how the last three columns compare: "rel" in percent, "abs" as a difference in the
    # unit; "auto": abs for times, angles, percentages, positions and offsets, else rel
    diff: str = "auto"

    def __post_init__(self) -> None:
        if self.diff == "auto":
            absolute = self.unit in ("s", "deg", "%") or any(
                w in self.what for w in ("position", "offset", "from the ref")
            )
            self.diff = "abs" if absolute else "rel"


def _fmt(v: float | None, fmt: str) -> str:
    return "-" if v is None or not math.isfinite(v) else format(v, fmt)


def _pct(v: float | None, ref: float | None, row: Row | None = None) -> str:
    if v is None or ref is None or not math.isfinite(v) or not math.isfinite(ref):
        return "-"
    if row is not None and row.diff == "abs":
        return f"{v - ref:+{row.fmt}} {row.unit}"
    if ref == 0:
        return "-"
    return f"{100 * (v / ref - 1):+.2f} %"


def print_rows(title: str, rows: list[Row], ref_name: str, md: list[str]) -> None:
    print(title)
    head = (
        f"  {'figure':<44} {'unit':<6} {'crashsim':>10} {'pycrash':>10} {ref_name:>12} "
        f"{'cs vs ref':>10} {'pc vs ref':>10} {'pc vs cs':>10}"
    )
    print(head)
    md.append(f"**{title.strip()}**")
    md.append("")
    md.append(
        f"| figure | unit | crashsim | pycrash | {ref_name} | cs vs ref | pc vs ref | pc vs cs |"
    )
    md.append("|---|---|---|---|---|---|---|---|")
    for r in rows:
        cells = [
            _fmt(r.cs, r.fmt),
            _fmt(r.pc, r.fmt),
            _fmt(r.ref, r.fmt),
            _pct(r.cs, r.ref, r),
            _pct(r.pc, r.ref, r),
            _pct(r.pc, r.cs, r),
        ]
        print(
            f"  {r.what:<44} {r.unit:<6} {cells[0]:>10} {cells[1]:>10} {cells[2]:>12} "
            f"{cells[3]:>10} {cells[4]:>10} {cells[5]:>10}"
        )
        md.append(f"| {r.what} | {r.unit} | " + " | ".join(cells) + " |")
    md.append("")


def skid_rows(case: Case) -> list[Row]:
    v, a = SKID_SPEED, MU * G
    d_ref, t_ref = v * v / (2 * a), v / a
    # the first sample below the rest speed: the closed form's time and distance to it
    d_first, t_first = (v * v - REST_SPEED**2) / (2 * a), (v - REST_SPEED) / a
    first: list[tuple[float | None, float | None]] = []
    rest: list[tuple[float | None, float | None]] = []
    for tr in (case.cs[0], case.pc[0]):
        t1 = first_below(tr.t, tr.speed)
        first.append((t1, float(tr.x[tr.at(t1)]) if t1 is not None else None))
        rest.append((tr.rest, float(tr.x[tr.at(tr.rest)]) if tr.rest is not None else None))
    return [
        Row("distance to the first stop (< 0.05 m/s)", "m", first[0][1], first[1][1], d_first),
        Row("time to the first stop", "s", first[0][0], first[1][0], t_first),
        Row("distance at rest (rest criterion)", "m", rest[0][1], rest[1][1], d_ref),
        Row("time to rest (slow for 0.2 s)", "s", rest[0][0], rest[1][0], t_ref),
        Row(
            "largest backward speed after the stop",
            "m/s",
            *(float(max(0.0, -tr.u.min())) for tr in (case.cs[0], case.pc[0])),
            None,
            diff="abs",
        ),
    ]


def understeer_gradient(loads: np.ndarray, car: Car) -> float:
    """K (rad s^2/m) of the single-track model with the axle cornering stiffnesses
    C = Fz / alpha_sat of the given wheel loads (N, FL FR RL RR)."""
    cf = (loads[0] + loads[1]) / ALPHA_SAT
    cr = (loads[2] + loads[3]) / ALPHA_SAT
    return car.mass / car.wheelbase * (car.b / cf - car.a / cr)


def steady(tr: Trace, t0: float) -> dict[str, float]:
    k = tr.t >= t0
    loads = tr.loads[:, k].mean(axis=1)
    return {
        "u": float(tr.u[k].mean()),
        "r": float(tr.r[k].mean()),
        "ay": float(tr.ay[k].mean()),
        "K": understeer_gradient(loads, CAR),
    }


def corner_rows(case: Case) -> list[Row]:
    delta = neutral_steer(CORNER_SPEED, CORNER_G)
    s = [steady(tr, 4.0) for tr in (case.cs[0], case.pc[0])]
    gain = [x["r"] / delta for x in s]
    # the closed form with crashsim's own u and K (pycrash's are in the notes)
    ref = [x["u"] / (CAR.wheelbase + x["K"] * x["u"] ** 2) for x in s]
    rows = [
        Row("yaw-rate gain r / delta (4-5 s)", "1/s", gain[0], gain[1], ref[0], ".4f"),
        Row(
            "yaw rate",
            "deg/s",
            math.degrees(s[0]["r"]),
            math.degrees(s[1]["r"]),
            math.degrees(ref[0] * delta),
            ".4f",
        ),
        Row(
            "lateral acceleration",
            "g",
            s[0]["ay"] / G,
            s[1]["ay"] / G,
            s[0]["u"] * ref[0] * delta / G,
            ".4f",
        ),
        Row("forward speed", "m/s", s[0]["u"], s[1]["u"], CORNER_SPEED, ".4f"),
        Row(
            "understeer gradient K (axle loads)",
            "mrad/g",
            s[0]["K"] * G * 1e3,
            s[1]["K"] * G * 1e3,
            0.0,
            ".4f",
        ),
    ]
    case.extra["corner_ref_pc"] = ref[1]
    return rows


def linear_single_track(steer: np.ndarray, speed: float, t: np.ndarray) -> dict[str, np.ndarray]:
    """The linear single-track model's response to a road-wheel angle table (linear between
    its points): constant forward speed, axle cornering stiffnesses Fz / alpha_sat at the
    static axle loads, no tyre lag; yaw rate, lateral acceleration, heading and lateral
    position (integrated to a relative tolerance of 1e-10)."""
    from scipy.integrate import solve_ivp

    c = CAR
    m, iz, a, b, u = c.mass, c.izz, c.a, c.b, speed
    cf = c.mass * G * b / c.wheelbase / ALPHA_SAT
    cr = c.mass * G * a / c.wheelbase / ALPHA_SAT

    def forces(time_s: float, v: float, r: float) -> tuple[float, float]:
        delta = float(np.interp(time_s, steer[:, 0], steer[:, 1]))
        return cf * (delta - (v + a * r) / u), cr * (-(v - b * r) / u)

    def rhs(time_s: float, y: np.ndarray) -> list[float]:
        v, r, yaw, _ = y
        ff, fr = forces(time_s, v, r)
        lateral = u * math.sin(yaw) + v * math.cos(yaw)
        return [(ff + fr) / m - u * r, (a * ff - b * fr) / iz, r, lateral]

    sol = solve_ivp(
        rhs,
        (0.0, float(t[-1])),
        [0.0, 0.0, 0.0, 0.0],
        t_eval=t,
        rtol=1e-10,
        atol=1e-12,
        max_step=0.01,
        first_step=1e-4,
    )
    if not sol.success:  # pragma: no cover - a linear system
        raise RuntimeError(sol.message)
    ay = np.array([sum(forces(tt, y[0], y[1])) / m for tt, y in zip(sol.t, sol.y.T, strict=True)])
    return {"r": sol.y[1], "ay": ay, "yaw": sol.y[2], "y": sol.y[3]}


def rise(t: np.ndarray, x: np.ndarray, t0: float) -> dict[str, float]:
    """A step response from t0: its final value (mean of the last 0.5 s), its peak and
    overshoot, and the times after t0 to 50 % and 90 % of the final value."""
    k = t >= t0
    tk, xk = t[k], x[k]
    final = float(xk[tk >= tk[-1] - 0.5].mean())
    i = int(np.argmax(np.abs(xk)))

    def reach(f: float) -> float:
        j = np.flatnonzero(np.abs(xk) >= f * abs(final))
        return float(tk[j[0]] - t0) if len(j) else float("nan")

    return {
        "final": final,
        "peak": float(xk[i]),
        "overshoot": 100 * (abs(xk[i]) / abs(final) - 1) if final else float("nan"),
        "t50": reach(0.5),
        "t90": reach(0.9),
    }


def step_rows(case: Case) -> list[Row]:
    steer = case.steer
    t = np.arange(0.0, case.spec["duration"] + DT / 2, DT)
    lin = linear_single_track(steer, CORNER_SPEED, t)
    case.extra["linear"] = {"t": t, **lin}
    trs = [case.cs[0], case.pc[0]]
    r = [rise(tr.t, tr.r, STEP_AT) for tr in trs] + [rise(t, lin["r"], STEP_AT)]
    a = [rise(tr.t, tr.ay, STEP_AT) for tr in trs] + [rise(t, lin["ay"], STEP_AT)]
    ramp_end = STEP_AT + STEP_RAMP + 0.05
    ramp = [float(np.max(tr.ay[(tr.t >= STEP_AT) & (tr.t <= ramp_end)])) / G for tr in trs] + [
        float(np.max(lin["ay"][(t >= STEP_AT) & (t <= ramp_end)])) / G
    ]
    deg = math.degrees
    return [
        Row("yaw rate, end (mean of the last 0.5 s)", "deg/s", *(deg(x["final"]) for x in r)),
        Row("yaw-rate overshoot over the end value", "%", *(x["overshoot"] for x in r), ".2f"),
        Row("time to 50 % of the end yaw rate", "s", *(x["t50"] for x in r)),
        Row("time to 90 % of the end yaw rate", "s", *(x["t90"] for x in r)),
        Row("lateral acceleration, end", "g", *(x["final"] / G for x in a), ".4f"),
        Row("largest lat. acc. in the ramp (+50 ms)", "g", *ramp, ".4f"),
        Row("time to 50 % of the end lat. acc.", "s", *(x["t50"] for x in a)),
        Row("time to 90 % of the end lat. acc.", "s", *(x["t90"] for x in a)),
        Row("forward speed, end", "m/s", *(float(tr.u[-1]) for tr in trs), CORNER_SPEED),
    ]


def peaks(t: np.ndarray, x: np.ndarray, t0: float) -> list[tuple[float, float]]:
    """The largest positive and the largest negative value after t0, each with its time
    after t0, in the order they occur."""
    k = t >= t0
    tk, xk = t[k], x[k]
    i, j = int(np.argmax(xk)), int(np.argmin(xk))
    out = [(float(xk[i]), float(tk[i] - t0)), (float(xk[j]), float(tk[j] - t0))]
    return sorted(out, key=lambda p: p[1])


def lane_rows(case: Case) -> list[Row]:
    steer = case.steer
    t = np.arange(0.0, case.spec["duration"] + DT / 2, DT)
    lin = linear_single_track(steer, CORNER_SPEED, t)
    case.extra["linear"] = {"t": t, **lin}
    trs = [case.cs[0], case.pc[0]]
    series = {
        "r": [tr.r for tr in trs] + [lin["r"]],
        "ay": [tr.ay for tr in trs] + [lin["ay"]],
    }
    times = [tr.t for tr in trs] + [t]
    rows = []
    for key, unit, scale, label in (
        ("r", "deg/s", 180 / math.pi, "yaw rate"),
        ("ay", "g", 1 / G, "lat. acc."),
    ):
        pk = [peaks(tt, xx, LANE_AT) for tt, xx in zip(times, series[key], strict=True)]
        for n, word in ((0, "first"), (1, "second")):
            rows.append(Row(f"{word} peak {label}", unit, *(p[n][0] * scale for p in pk), ".4f"))
            rows.append(Row("  its time after the steer starts", "s", *(p[n][1] for p in pk)))
    rows.append(
        Row("lateral offset at the end", "m", *(float(tr.y[-1]) for tr in trs), float(lin["y"][-1]))
    )
    rows.append(
        Row(
            "heading at the end",
            "deg",
            *(math.degrees(float(tr.yaw[-1])) for tr in trs),
            math.degrees(float(lin["yaw"][-1])),
            ".3f",
        )
    )
    return rows


def _path_length(tr: Trace, until: float | None) -> float:
    k = tr.at(until) if until is not None else len(tr.t) - 1
    return float(np.hypot(np.diff(tr.x[: k + 1]), np.diff(tr.y[: k + 1])).sum())


def brake_turn_rows(case: Case) -> list[Row]:
    rows = []
    vals = []
    for tr in (case.cs[0], case.pc[0]):
        kb = tr.at(TURN_BRAKE_AT)
        after = tr.t >= TURN_BRAKE_AT
        i = int(np.argmax(np.abs(tr.r) * after))
        rest = tr.rest
        kr = tr.at(rest) if rest is not None else len(tr.t) - 1
        vals.append(
            {
                "r0": math.degrees(float(tr.r[kb])),
                "r1": math.degrees(float(tr.r[tr.at(TURN_BRAKE_AT + 1.0)])),
                "rpk": math.degrees(float(tr.r[i])),
                "t_rpk": float(tr.t[i] - TURN_BRAKE_AT),
                "rest": rest,
                "stop": first_below(tr.t, tr.speed),
                "x": float(tr.x[kr]),
                "y": float(tr.y[kr]),
                "yaw": math.degrees(float(tr.yaw[kr])),
                "dyaw": math.degrees(float(tr.yaw[kr] - tr.yaw[kb])),
                "path": _path_length(tr, rest) - _path_length(tr, TURN_BRAKE_AT),
            }
        )
    cs, pc = vals
    rows.append(Row("yaw rate when the brakes apply (2.0 s)", "deg/s", cs["r0"], pc["r0"], None))
    rows.append(Row("yaw rate 1 s after the brakes apply", "deg/s", cs["r1"], pc["r1"], None))
    rows.append(Row("peak yaw rate while braking", "deg/s", cs["rpk"], pc["rpk"], None))
    rows.append(Row("  its time after the brakes apply", "s", cs["t_rpk"], pc["t_rpk"], None))
    rows.append(Row("first below 0.05 m/s", "s", cs["stop"], pc["stop"], None))
    rows.append(Row("time to rest", "s", cs["rest"], pc["rest"], None))
    rows.append(Row("path from the brakes to rest", "m", cs["path"], pc["path"], None))
    rows.append(Row("rest position x", "m", cs["x"], pc["x"], None))
    rows.append(Row("rest position y", "m", cs["y"], pc["y"], None))
    rows.append(Row("heading at rest", "deg", cs["yaw"], pc["yaw"], None))
    rows.append(Row("heading change, brakes to rest", "deg", cs["dyaw"], pc["dyaw"], None))
    return rows


def _delta_v(imp: dict[str, Any], body: int) -> float:
    before = np.asarray(imp["velocity_before"][body])[:2]
    return float(np.linalg.norm(np.asarray(imp["velocity_after"][body])[:2] - before))


def impact_rows(case: Case) -> list[Row]:
    """crashsim (automatic 3-D centroid), pycrash, and in the reference column crashsim with
    the impulse at the CG's height (planar, as pycrash's)."""
    out, planar = case.cs_out, case.extra["planar"]
    imp, imp_p = first_impact(out), first_impact(planar)
    impc = case.extra.get("impc") or {}
    pc_k = case.extra.get("impact_index") or [None]
    pc_t = float(case.pc[0].t[pc_k[0]]) if pc_k[0] is not None else None
    rows = [Row("impact (exchange) time", "s", float(imp["time"]), pc_t, float(imp_p["time"]))]
    for body, name, key in ((0, "A", "veh1_impc_result"), (1, "B", "veh2_impc_result")):
        res = impc.get(key, {})
        dv_pc = res.get("dv")
        rows.append(
            Row(
                f"delta-V of {name}",
                "m/s",
                _delta_v(imp, body),
                dv_pc * M_PER_FT if dv_pc is not None else None,
                _delta_v(imp_p, body),
            )
        )
        w_pc = res.get("oz_rad_post")
        rows.append(
            Row(
                f"yaw rate of {name} after the impact",
                "deg/s",
                math.degrees(float(imp["angular_velocity_after"][body][2])),
                -math.degrees(w_pc) if w_pc is not None else None,
                math.degrees(float(imp_p["angular_velocity_after"][body][2])),
                ".2f",
            )
        )
    planar_traces = [crashsim_trace(planar, b, CAR) for b in (0, 1)]
    for body, name in ((0, "A"), (1, "B")):
        trs = (case.cs[body], case.pc[body], planar_traces[body])
        ks = [tr.at(tr.rest) if tr.rest is not None else len(tr.t) - 1 for tr in trs]
        rows.append(
            Row(f"{name}: first below 0.05 m/s", "s", *(first_below(tr.t, tr.speed) for tr in trs))
        )
        rows.append(Row(f"{name}: time to rest", "s", *(tr.rest for tr in trs)))
        for label, attr in (("x", "x"), ("y", "y")):
            rows.append(
                Row(
                    f"{name}: rest position {label}",
                    "m",
                    *(float(getattr(tr, attr)[k]) for tr, k in zip(trs, ks, strict=True)),
                )
            )
        yaws = [math.degrees(float(tr.yaw[k])) for tr, k in zip(trs, ks, strict=True)]
        rows.append(Row(f"{name}: heading at rest", "deg", *yaws, fmt=".2f"))
        ref = trs[2]
        gaps = [
            float(np.hypot(tr.x[k] - ref.x[ks[2]], tr.y[k] - ref.y[ks[2]]))
            for tr, k in zip(trs, ks, strict=True)
        ]
        rows.append(
            Row(f"{name}: rest position's distance from the ref's", "m", gaps[0], gaps[1], 0.0)
        )
        rows.append(
            Row(
                f"{name}: heading at rest minus the ref's",
                "deg",
                yaws[0] - yaws[2],
                yaws[1] - yaws[2],
                0.0,
                ".2f",
            )
        )
    return rows


def rest_pose(tr: Trace) -> tuple[float, float, float]:
    """(x, y, heading in deg) at rest, or at the end if the trace never rests."""
    k = tr.at(tr.rest) if tr.rest is not None else len(tr.t) - 1
    return float(tr.x[k]), float(tr.y[k]), math.degrees(float(tr.yaw[k]))


# -- speed -----------------------------------------------------------------------------------


def crashsim_times(
    build: Any, side: Crashsim, dt: float, repeats: int
) -> tuple[list[float], float]:
    """Wall times of ``repeats`` runs until rest, and the simulated duration."""
    times = []
    sim = 0.0
    for _ in range(repeats):
        w = _ready(build())
        t0 = time.perf_counter()
        out = side.run(w, 20.0, dt)
        times.append(time.perf_counter() - t0)
        sim = float(out["t"][-1])
    return times, sim


def _fmt_time(s: float) -> str:
    if s < 1e-3:
        return f"{s * 1e6:.1f} us"
    if s < 1.0:
        return f"{s * 1e3:.2f} ms"
    return f"{s:.3f} s"


# -- plot ------------------------------------------------------------------------------------


def plot(cases: dict[str, Case], path: Path) -> None:
    import matplotlib

    matplotlib.use("Agg")
    from matplotlib.figure import Figure

    fig = Figure(figsize=(15, 13), layout="constrained")
    axes = fig.subplots(3, 3)
    cs_style = {"color": "tab:blue", "lw": 1.6, "label": "crashsim"}
    pc_style = {"color": "tab:red", "lw": 1.2, "ls": "--", "label": "pycrash"}
    ref_style = {"color": "k", "lw": 0.9, "ls": ":"}
    if "skid" in cases:
        ax = axes[0, 0]
        c = cases["skid"]
        for tr, st in ((c.cs[0], cs_style), (c.pc[0], pc_style)):
            ax.plot(tr.t, tr.u, **st)
        t = np.linspace(0, SKID_SPEED / (MU * G), 50)
        ax.plot(t, SKID_SPEED - MU * G * t, label="v - mu g t", **ref_style)
        inset = ax.inset_axes((0.45, 0.45, 0.5, 0.45))
        for tr, st in ((c.cs[0], cs_style), (c.pc[0], pc_style)):
            k = (tr.t > 2.3) & (tr.t < 3.3)
            inset.plot(tr.t[k], tr.x[k], **{k2: v for k2, v in st.items() if k2 != "label"})
        inset.axhline(SKID_SPEED**2 / (2 * MU * G), **ref_style)
        inset.set_title("x (m) near the stop", fontsize=8)
        inset.tick_params(labelsize=7)
        ax.set(title="1. locked skid: forward speed", xlabel="t (s)", ylabel="u (m/s)")
        ax.legend(loc="lower left", fontsize=8)
    if "corner" in cases:
        ax = axes[0, 1]
        c = cases["corner"]
        for tr, st in ((c.cs[0], cs_style), (c.pc[0], pc_style)):
            ax.plot(tr.t, np.degrees(tr.r), **st)
        delta = neutral_steer(CORNER_SPEED, CORNER_G)
        ax.axhline(
            math.degrees(CORNER_SPEED * delta / CAR.wheelbase), label="u delta / L", **ref_style
        )
        ax.set(title="2. steady cornering 0.2 g: yaw rate", xlabel="t (s)", ylabel="r (deg/s)")
        ax.legend(fontsize=8)
    if "step" in cases:
        c = cases["step"]
        lin = c.extra["linear"]
        for ax, key, scale, lab in (
            (axes[0, 2], "r", 180 / math.pi, "r (deg/s)"),
            (axes[1, 0], "ay", 1 / G, "a_y (g)"),
        ):
            for tr, st in ((c.cs[0], cs_style), (c.pc[0], pc_style)):
                ax.plot(tr.t, getattr(tr, key) * scale, **st)
            ax.plot(lin["t"], lin[key] * scale, label="linear single-track", **ref_style)
            ax.set(
                title=f"3. step steer 0.4 g: {lab.split()[0]}",
                xlabel="t (s)",
                ylabel=lab,
                xlim=(0.3, 2.0),
            )
            ax.legend(fontsize=8)
    if "lane" in cases:
        c = cases["lane"]
        lin = c.extra["linear"]
        for ax, key, scale, lab in (
            (axes[1, 1], "r", 180 / math.pi, "r (deg/s)"),
            (axes[1, 2], "ay", 1 / G, "a_y (g)"),
        ):
            for tr, st in ((c.cs[0], cs_style), (c.pc[0], pc_style)):
                ax.plot(tr.t, getattr(tr, key) * scale, **st)
            ax.plot(lin["t"], lin[key] * scale, label="linear single-track", **ref_style)
            ax.plot(
                c.steer[:, 0],
                np.degrees(c.steer[:, 1]) * (10 if key == "r" else 0.1),
                color="0.6",
                lw=0.8,
                label="steer (deg) x 10" if key == "r" else "steer (deg) / 10",
            )
            ax.set(title=f"3b. lane change: {lab.split()[0]}", xlabel="t (s)", ylabel=lab)
            ax.legend(fontsize=8)
    if "brake_turn" in cases:
        c = cases["brake_turn"]
        ax = axes[2, 1]
        for tr, st in ((c.cs[0], cs_style), (c.pc[0], pc_style)):
            ax.plot(tr.t, np.degrees(tr.r), **st)
        ax.axvline(TURN_BRAKE_AT, color="0.6", lw=0.8)
        ax.set(
            title="4. braking in a turn: yaw rate (line: brakes on)",
            xlabel="t (s)",
            ylabel="r (deg/s)",
        )
        ax.legend(fontsize=8)
        ax = axes[2, 0]
        for tr, st in ((c.cs[0], cs_style), (c.pc[0], pc_style)):
            ax.plot(tr.x, tr.y, **st)
            k = tr.at(TURN_BRAKE_AT)
            ax.plot(tr.x[k], tr.y[k], "o", color=st["color"], ms=4)
        ax.set(
            title="4. braking in a turn: CG path (dot: brakes on)",
            xlabel="x (m)",
            ylabel="y (m)",
            aspect="equal",
        )
        ax.legend(fontsize=8)
    if "impact" in cases:
        ax = axes[2, 2]
        c = cases["impact"]
        planar = [crashsim_trace(c.extra["planar"], b, CAR) for b in (0, 1)]
        pl_style = {"color": "tab:green", "lw": 1.0, "ls": ":", "label": "crashsim, planar impulse"}
        for trs, st in ((c.cs, cs_style), (c.pc, pc_style), (planar, pl_style)):
            for j, tr in enumerate(trs):
                lab = st["label"] if j == 0 else None
                k = tr.at(tr.rest) if tr.rest is not None else len(tr.t) - 1
                ax.plot(tr.x[: k + 1], tr.y[: k + 1], **{**st, "label": lab})
                if k < len(tr.t) - 1 and trs is c.pc:  # pycrash's drift after its rest
                    ax.plot(tr.x[k:], tr.y[k:], color=st["color"], lw=0.6, alpha=0.5)
                ax.plot(
                    *_outline(tr.x[k], tr.y[k], tr.yaw[k]),
                    color=st["color"],
                    lw=0.8,
                    ls=st.get("ls", "-"),
                )
                if trs is c.cs:
                    ax.annotate("AB"[j], (tr.x[0], tr.y[0]), fontsize=9)
        for tr in c.cs:
            ax.plot(*_outline(tr.x[0], tr.y[0], tr.yaw[0]), color="0.6", lw=0.6)
        ax.set(
            title="5. impact: CG paths, start (grey) and rest",
            xlabel="x (m)",
            ylabel="y (m)",
            aspect="equal",
        )
        ax.legend(fontsize=8)
    for ax in axes.flat:
        ax.grid(alpha=0.3)
    fig.suptitle(
        "crashsim vs pycrash 0.0.18: the same car and manoeuvres (benches/compare_pycrash.py)"
    )
    path.parent.mkdir(parents=True, exist_ok=True)
    fig.savefig(path, dpi=90)


def _outline(x: float, y: float, yaw: float) -> tuple[np.ndarray, np.ndarray]:
    c = CAR
    f, r, h = c.a + c.front_overhang, -(c.b + c.rear_overhang), c.width / 2
    pts = np.array([[f, h], [f, -h], [r, -h], [r, h], [f, h]]) @ _rot_z(yaw).T
    return pts[:, 0] + x, pts[:, 1] + y


# -- main ------------------------------------------------------------------------------------


def machine_lines(pycrash_where: str, pycrash_info: dict[str, Any]) -> list[str]:
    sys.path.insert(0, str(Path(__file__).resolve().parent))
    from machine import describe  # benches/machine.py

    load = os.getloadavg()
    rev = git_revision()
    return [
        f"date: {datetime.datetime.now().isoformat(timespec='seconds')}; crashsim git "
        f"{rev or 'unknown'}; load average (1/5/15 min) {load[0]:.2f} / {load[1]:.2f} / "
        f"{load[2]:.2f}",
        f"machine: {describe()}",
        f"pycrash {pycrash_info.get('pycrash')} in {pycrash_where} (python "
        f"{pycrash_info.get('python')}, numpy {pycrash_info.get('numpy')}, pandas "
        f"{pycrash_info.get('pandas')})",
    ]


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--quick", action="store_true", help="pycrash at 10 ms only, 1 repeat")
    ap.add_argument("--only", default=",".join(CASES), help=f"comma-separated of {CASES}")
    ap.add_argument("--repeats", type=int, help="crashsim timing repeats (default 15; quick 5)")
    ap.add_argument(
        "--pycrash-repeats", type=int, help="pycrash runs of each timed scene (default 3; quick 1)"
    )
    ap.add_argument("--pycrash-python", help=f"interpreter with pycrash ({DEFAULT_PYCRASH_PYTHON})")
    ap.add_argument("--plot", type=Path, help="write the traces to this PNG")
    ap.add_argument("--markdown", type=Path, help="also write the tables as Markdown here")
    ap.add_argument("--pycrash-worker", action="store_true", help=argparse.SUPPRESS)
    args = ap.parse_args(argv)
    if args.pycrash_worker:
        spec = json.loads(sys.stdin.read())
        sys.stdout.write(json.dumps(pycrash_worker(spec)))
        return 0
    only = [s.strip() for s in args.only.split(",") if s.strip()]
    unknown = set(only) - set(CASES)
    if unknown:
        ap.error(f"unknown cases {sorted(unknown)}; choose from {CASES}")
    dt_pc = PYCRASH_DEFAULT_DT if args.quick else DT
    repeats = args.repeats or (5 if args.quick else 15)
    pc_repeats = args.pycrash_repeats or (1 if args.quick else 3)

    side = Crashsim(CAR)
    makers = {
        "skid": lambda: make_skid(side, dt_pc),
        "corner": lambda: make_corner(side, dt_pc),
        "step": lambda: make_step(side, dt_pc),
        "lane": lambda: make_lane(side, dt_pc),
        "brake_turn": lambda: make_brake_turn(side, dt_pc),
        "impact": lambda: make_impact(side, dt_pc, 1),
    }
    cases = {name: makers[name]() for name in only if name in makers}
    if "speed" in only:
        # the skid's and the impact's runs at the case step are also timed: repeat them
        for name in ("skid", "impact"):
            if name in cases:
                cases[name].spec["repeats"] = pc_repeats
    specs = [c.spec for c in cases.values()]
    speed_specs: list[dict[str, Any]] = []
    if "speed" in only:
        # single-vehicle: the skid at pycrash's default step, repeated; SingleMotion's drawing
        # data timed once; the skid at 1 ms comes from case 1 (or runs here)
        skid = cases.get("skid") or make_skid(side, dt_pc)
        s10 = copy.deepcopy(skid.spec)
        s10.update(name="speed_skid_10ms", dt=PYCRASH_DEFAULT_DT, repeats=pc_repeats, drawing=True)
        speed_specs.append(s10)
        if "skid" not in cases and not args.quick:
            s1 = copy.deepcopy(skid.spec)
            s1.update(name="speed_skid_1ms", dt=DT, repeats=pc_repeats)
            speed_specs.append(s1)
        imp = cases.get("impact") or make_impact(side, dt_pc, 1)
        i10 = impact_spec(
            imp.cs_out, PYCRASH_DEFAULT_DT, imp.spec["duration"], pc_repeats, drawing=True
        )
        i10["name"] = "speed_impact_10ms"
        speed_specs.append(i10)
        if "impact" not in cases and not args.quick:
            i1 = impact_spec(imp.cs_out, DT, imp.spec["duration"], pc_repeats)
            i1["name"] = "speed_impact_1ms"
            speed_specs.append(i1)

    # crashsim timing before pycrash (the load changes over minutes; again after it)
    builds = {
        "skid": lambda: _skid_world(side),
        "impact": lambda: build_impact(side),
    }
    cs_times: dict[tuple[str, float], list[float]] = {}
    cs_sim: dict[tuple[str, float], float] = {}
    if "speed" in only:
        for key in builds:
            for dt in (DT, PYCRASH_DEFAULT_DT):
                ts, sim = crashsim_times(builds[key], side, dt, repeats)
                cs_times[(key, dt)] = ts
                cs_sim[(key, dt)] = sim

    t_pc = time.perf_counter()
    try:
        pc_out, where = run_pycrash({"cases": specs + speed_specs}, args.pycrash_python)
    except RuntimeError as e:
        # the peer is missing or broken: nothing to compare, which is not this script's failure
        print(f"compare_pycrash: nothing compared: {e}", file=sys.stderr)
        return 0
    t_pc = time.perf_counter() - t_pc
    if "speed" in only:
        for key in builds:
            for dt in (DT, PYCRASH_DEFAULT_DT):
                ts, _ = crashsim_times(builds[key], side, dt, repeats)
                cs_times[(key, dt)] += ts

    for line in machine_lines(where, pc_out):
        print(line)
    print(
        f"pycrash total wall time in this run: {t_pc:.1f} s; pycrash step for cases 1-5: "
        f"{dt_pc * 1e3:g} ms; crashsim: steps of {DT * 1e3:g} ms (RK4 sub-steps <= 1 ms)"
    )
    print()
    md: list[str] = []
    for name, case in cases.items():
        res = pc_out["cases"][name]
        case.extra.update({k: v for k, v in res.items() if k != "models"})
        case.pc = [pycrash_trace(m) for m in res["models"]]
        n = len(case.pc)
        case.cs = [side.trace(case.cs_out, b) for b in range(n)]
    table_of = {
        "skid": (skid_rows, "closed form"),
        "corner": (corner_rows, "single-track"),
        "step": (step_rows, "linear model"),
        "lane": (lane_rows, "linear model"),
        "brake_turn": (brake_turn_rows, "-"),
        "impact": (impact_rows, "cs planar"),
    }
    for name, case in cases.items():
        fn, ref = table_of[name]
        print_rows(case.title, fn(case), ref, md)
        for note in case_notes(case):
            print(f"  note: {note}")
            md.append(f"- {note}")
        md.append("")
        print()

    if "speed" in only:
        durations = {s["name"]: s["duration"] for s in specs + speed_specs}
        speed_lines = speed_section(durations, cases, pc_out, cs_times, cs_sim, dt_pc, args.quick)
        for line in speed_lines:
            print(line)
        md.append("**6. speed**")
        md.append("")
        md.append("```")
        md.extend(speed_lines)
        md.append("```")
    if args.plot:
        plot(cases, args.plot)
        print(f"\nplot: {args.plot}")
    if args.markdown:
        args.markdown.parent.mkdir(parents=True, exist_ok=True)
        args.markdown.write_text("\n".join(md) + "\n")
    return 0


def _skid_world(side: Crashsim) -> Any:
    w = side.world()
    lock = [(k, "time", 0.0, "locked", 0.0) for k in range(4)]
    side.add_car(w, (0.0, 0.0), 0.0, SKID_SPEED, switches=lock)
    return w


def case_notes(case: Case) -> list[str]:
    """Figures the tables do not hold but the explanations use."""
    notes = []
    if case.name == "skid":
        cs = case.cs[0]
        k1 = cs.at(first_below(cs.t, cs.speed) or cs.t[-1])
        pitch = case.cs_out["angular_velocity"][0][:, 1]
        notes.append(
            f"crashsim after the first stop: the body pitches back (peak pitch rate "
            f"{math.degrees(float(np.abs(pitch[k1:]).max())):.1f} deg/s) and the CG moves "
            f"{100 * (float(cs.x[k1]) - float(cs.x[-1])):.1f} cm back by the end of the run "
            f"({float(cs.t[-1]):.3f} s, when the body has settled; rest is at "
            f"{cs.rest if cs.rest is not None else float('nan'):.3f} s)"
        )
        back = float(cs.x[k1]) - float(cs.x[k1:].min())
        notes.append(
            f"crashsim after the first stop: the CG moves back up to {100 * back:.1f} cm; "
            f"Result.rest's position (the end of the run) is {float(cs.x[-1]):.3f} m from the "
            f"start ({100 * (float(cs.x[-1]) / (SKID_SPEED**2 / (2 * MU * G)) - 1):+.2f} % of "
            f"v^2 / (2 mu g))"
        )
        kk = cs.t < 1.0
        front = float((cs.loads[0][kk][-1] + cs.loads[1][kk][-1]) / (CAR.mass * G))
        pcf = case.pc[0]
        k2 = pcf.at(1.0)
        notes.append(
            f"front axle share of the weight while skidding (1.0 s): crashsim {front:.3f}, "
            f"pycrash {float(pcf.loads[0][k2] + pcf.loads[1][k2]) / (CAR.mass * G):.3f}, "
            f"static {CAR.b / CAR.wheelbase:.3f}, quasi-static with mu h / L "
            f"{CAR.b / CAR.wheelbase + MU * CAR.h_cg / CAR.wheelbase:.3f}"
        )
    if case.name == "corner":
        default = case.extra.get("rolling_tyre")
        if default is not None:
            s = steady(crashsim_trace(default, 0, CAR), 4.0)
            delta = neutral_steer(CORNER_SPEED, CORNER_G)
            notes.append(
                f"crashsim with rolling resistance 0.012 (0 is its default): gain "
                f"{s['r'] / delta:.4f} 1/s, speed {s['u']:.3f} m/s (rolling resistance is "
                f"heavier on the outer wheels: an understeering yaw moment)"
            )
        ref_pc = case.extra.get("corner_ref_pc")
        if ref_pc is not None:
            notes.append(f"the single-track gain with pycrash's own u and K: {ref_pc:.4f} 1/s")
    if case.name == "lane" and "short_relaxation" in case.extra:
        tr = crashsim_trace(case.extra["short_relaxation"], 0, CAR)
        pk = peaks(tr.t, tr.r, LANE_AT)
        pa = peaks(tr.t, tr.ay, LANE_AT)
        notes.append(
            "crashsim with relaxation length 0.01 m instead of 0.1 (the tread damper's lead "
            f"30 ms instead of 94): yaw-rate peaks {math.degrees(pk[0][0]):.4f} at "
            f"{pk[0][1]:.3f} s and {math.degrees(pk[1][0]):.4f} deg/s at {pk[1][1]:.3f} s, "
            f"lat. acc. peaks {pa[0][0] / G:.4f} and {pa[1][0] / G:.4f} g, lateral offset "
            f"{float(tr.y[-1]):.3f} m"
        )
    if case.name == "brake_turn":
        shares = []
        for tr in (case.cs[0], case.pc[0]):
            vals = []
            for dt in (0.0, 0.1, 0.3, 0.6):
                k = tr.at(TURN_BRAKE_AT + TURN_BRAKE_RAMP + dt)
                vals.append(float(tr.loads[0][k] + tr.loads[1][k]) / (CAR.mass * G))
            shares.append(" / ".join(f"{v:.3f}" for v in vals))
        notes.append(
            f"front axle share of the weight 0, 0.1, 0.3, 0.6 s after the brakes reach "
            f"{TURN_BRAKE}: crashsim {shares[0]}, pycrash {shares[1]}"
        )
        notes.append(f"pycrash's world speed at the end: {case.pc[0].extra['drift']:.3f} m/s")
        pc = case.pc[0]
        stop = first_below(pc.t, pc.speed)
        if stop is not None:
            notes.append(
                f"pycrash's largest |yaw rate| after its stop ({stop:.3f} s): "
                f"{math.degrees(float(np.abs(pc.r[pc.at(stop) :]).max())):.2f} deg/s"
            )
    if case.name == "impact":
        imp = case.spec["impact"]
        out = case.cs_out
        notes.append(
            f"crashsim: first overlap {first_impact(out)['first_contact_time']:.4f} s, exchange "
            f"{imp['time']:.4f} s (depth of penetration {IMPACT_DTP * 1e3:g} ms), "
            f"{len(out['impacts'])} exchange(s); centroid in A's frame "
            f"({imp['centroid_a'][0]:.3f}, {imp['centroid_a'][1]:.3f}) m, in B's "
            f"({imp['centroid_b'][0]:.3f}, {imp['centroid_b'][1]:.3f}) m; "
            f"normal at {-imp['point'][2]:.2f} deg in A's frame"
        )
        planar = case.extra["planar"]
        m_own = first_impact(out)["effective_mass"]
        m_planar = first_impact(planar)["effective_mass"]
        notes.append(
            f"effective masses along the normal: crashsim A {m_own[0]:.0f}, B {m_own[1]:.0f} kg; "
            f"planar A {m_planar[0]:.0f}, B {m_planar[1]:.0f} kg"
        )
        t_imp = float(imp["time"])
        for b, name in ((0, "A"), (1, "B")):
            pc, ref = case.pc[b], crashsim_trace(planar, b, CAR)
            v_ref = np.interp(pc.t, ref.t, ref.speed)
            r_ref = np.interp(pc.t, ref.t, ref.r)
            after = pc.t > t_imp + 0.01
            gaps = []
            for v in (2.0, 1.0):
                m = after & (pc.speed > v)
                gaps.append(float((np.abs(v_ref[m] - pc.speed[m]) / pc.speed[m]).max()) * 100)
            dr = np.degrees(np.abs(r_ref[after] - pc.r[after]))
            turn = [math.degrees(float(tr.yaw[tr.at(tr.rest)] - tr.yaw[0])) for tr in (pc, ref)]
            stops = [first_below(tr.t, tr.speed, 0.5) for tr in (pc, ref)]
            t1, t2 = first_below(pc.t, pc.speed), first_below(ref.t, ref.speed)
            rock = ""
            if t1 is not None and t2 is not None:
                k1, k2 = ref.at(t1), ref.at(t2) + 1
                rock = (
                    f"; crashsim planar from pycrash's first < 0.05 m/s ({t1:.3f} s) to its own "
                    f"({t2:.3f} s): speed up to {float(ref.speed[k1:k2].max()):.3f} m/s, forward "
                    f"speed {float(ref.u[k1:k2].min()):+.3f} to {float(ref.u[k1:k2].max()):+.3f} "
                    f"m/s"
                )
            notes.append(
                f"{name} after the impact, pycrash against crashsim planar: speeds apart by up "
                f"to {gaps[0]:.2f} % while above 2 m/s, {gaps[1]:.2f} % above 1 m/s; first "
                f"below 0.5 m/s {stops[0]:.3f} and {stops[1]:.3f} s; yaw rates apart by up to "
                f"{float(dr.max()):.2f} deg/s (at {float(pc.t[after][dr.argmax()]):.3f} s); "
                f"heading change to rest {turn[0]:.1f} and {turn[1]:.1f} deg" + rock
            )
        own_b = case.cs[1]
        off = (own_b.loads[0] <= 0.0) & (own_b.loads[2] <= 0.0)
        if off.any():
            notes.append(
                f"crashsim (own centroid): both of B's left wheels off the ground from "
                f"{float(own_b.t[off][0]):.3f} to {float(own_b.t[off][-1]):.3f} s"
            )
        drift = [tr.extra.get("drift", 0.0) for tr in case.pc]
        notes.append(
            f"pycrash after its rest (body-frame speed and yaw rate below the thresholds): "
            f"the world velocity it integrates apart stays at {drift[0]:.3f} m/s (A) and "
            f"{drift[1]:.3f} m/s (B) at the end, so its positions drift on"
        )
        notes.append(
            "pycrash: the same striking point and plane, B's struck edge moved to the "
            "centroid's depth so that it exchanges at crashsim's poses; IMPC at detection "
            f"({case.extra.get('impc', {}).get('impc_conditions', {})})"
        )
    return notes


def speed_section(
    durations: dict[str, float],
    cases: dict[str, Case],
    pc_out: dict[str, Any],
    cs_times: dict[tuple[str, float], list[float]],
    cs_sim: dict[tuple[str, float], float],
    dt_pc: float,
    quick: bool,
) -> list[str]:
    lines = [
        "6. speed: wall time per simulated second, median of repeats (crashsim: World.run until "
        "rest, timed before and after pycrash; pycrash: vehicle_model, or Impact + simulate, "
        "without the drawing data)",
        f"  {'scene':<34} {'step':>6} {'crashsim':>22} {'pycrash':>26} {'ratio pc/cs':>12} "
        "[range over single runs]",
    ]
    summary = []
    for key, label in (
        ("skid", "skid 20 m/s to rest (1 car)"),
        ("impact", "impact + run-out (2 cars)"),
    ):
        for dt in (DT, PYCRASH_DEFAULT_DT):
            ts = cs_times[(key, dt)]
            sim = cs_sim[(key, dt)]
            cs_per = statistics.median(ts) / sim
            name = f"speed_{key}_{'1ms' if dt == DT else '10ms'}"
            if name not in pc_out["cases"] and dt == dt_pc and key in cases:
                name = key  # the case itself ran at this step
            if name not in pc_out["cases"]:
                continue
            res = pc_out["cases"][name]
            dur = durations[name]
            pts = res["times"]
            pc_per = statistics.median(pts) / dur
            ratio = pc_per / cs_per
            # the widest the ratio could be from single runs: slowest pycrash / fastest
            # crashsim and the other way round
            lo = min(pts) / dur / (max(ts) / sim)
            hi = max(pts) / dur / (min(ts) / sim)
            lines.append(
                f"  {label:<34} {dt * 1e3:>4g} ms {_fmt_time(cs_per):>10}/s (n={len(ts)}, "
                f"{sim:.2f} s) {_fmt_time(pc_per):>10}/s (n={len(pts)}, {dur:.2f} s) "
                f"{ratio:>10,.0f}x [{lo:,.0f}-{hi:,.0f}]"
            )
            if "drawing_time" in res:
                where = "SingleMotion" if key == "skid" else "simulate()"
                lines.append(
                    f"  {'':<34} {'':>6} {'':>22}   not counted: {where}'s drawing data, "
                    f"{_fmt_time(res['drawing_time'] / dur)}/s more"
                )
            summary.append((key, dt, ratio))
            if dt != DT and key in cases and cases[key].spec["dt"] == DT:
                # what the coarser step changes in pycrash's own results
                diffs = []
                for b, (coarse, fine) in enumerate(
                    zip(res["models"], pc_out["cases"][key]["models"], strict=True)
                ):
                    pc, pf = rest_pose(pycrash_trace(coarse)), rest_pose(pycrash_trace(fine))
                    diffs.append(
                        f"{'AB'[b] if len(res['models']) > 1 else 'car'} "
                        f"{math.hypot(pc[0] - pf[0], pc[1] - pf[1]):.3f} m, "
                        f"{pc[2] - pf[2]:+.2f} deg"
                    )
                lines.append(
                    f"  {'':<34} {'':>6} {'':>22}   pycrash at 10 ms against its 1 ms run, rest "
                    f"pose: {'; '.join(diffs)}"
                )
    for key, dt, ratio in summary:
        if key == "impact":
            verdict = "met" if ratio >= 1000 else "MISSED"
            lines.append(
                f"  target (issue 11): crashsim >= 1000x faster on the impact scene with run-out; "
                f"at {dt * 1e3:g} ms: {ratio:,.0f}x: {verdict}"
            )
    if quick:
        lines.append("  (--quick: pycrash at 10 ms only)")
    load = os.getloadavg()
    lines.append(f"  load average at the end {load[0]:.2f} / {load[1]:.2f} / {load[2]:.2f}")
    return lines


if __name__ == "__main__":
    sys.exit(main())
