"""The standard handling manoeuvres of docs/vehicle-model.md, run on the reference mid-size
sedan built from published data only (the 2004 Chevrolet Malibu whose PC-Crash runs issue 19
compares with; its data as entered in PC-Crash and published with pycrash's validation
project: 3298 lb, wheelbase 106 in, CG 38.1 in behind the front axle and 21.5 in high, track
60 in, yaw inertia 2040 lb ft s^2, steering ratio 15.9, tyres 26.2 in):

- ISO 4138 steady-state circular driving, the constant steer angle method: the steering wheel
  held, the speed raised slowly by a drive force; the steer angle the path needs against the
  lateral acceleration (the understeer gradient);
- ISO 7401 step steer at 80 km/h to the steering-wheel angle of 4 m/s^2, against the linear
  single-track model with the same axle cornering stiffnesses;
- ISO 3888-1 double lane change at 80 km/h, a driver following the lanes' centre line (the
  path input, pure pursuit), drawn with the cones;
- the NHTSA fishhook at 35, 40 and 45 mph: 6.5 times the steering-wheel angle that gives 0.3 g
  in a slowly increasing steer at 50 mph, at 720 deg/s, a 250 ms dwell, the countersteer held
  3 s; the inner wheels' lowest loads and the largest roll.

Each writes its pictures to docs/img/manoeuvre_*.png and prints its figures:

    python3 scripts/manoeuvres.py [--only iso4138,iso7401,iso3888,fishhook]
"""

from __future__ import annotations

import argparse
import math
from pathlib import Path

import crashsim as cs
import numpy as np
from crashsim.result import rotation_matrix
from matplotlib.backends.backend_agg import FigureCanvasAgg
from matplotlib.figure import Figure

REPO = Path(__file__).resolve().parents[1]
IMG = REPO / "docs" / "img"
IN, LB, SLUG_FT2 = 0.0254, 0.45359237, 1.3558179483314004

# the reference sedan (SI)
MASS = 3298 * LB
WHEELBASE = 106 * IN
CG_TO_FRONT = 38.1 * IN
CG_HEIGHT = 21.5 * IN
TRACK = 60 * IN
IZZ = 2040 * SLUG_FT2
RATIO = 15.9
RADIUS = 26.2 * IN / 2
LENGTH, WIDTH, HEIGHT = 187 * IN, 70 * IN, 1.45


def sedan() -> cs.Vehicle:
    """The reference sedan as a box of its length and width on its published axles."""
    inertia = np.diag([MASS / 12 * (WIDTH**2 + HEIGHT**2), IZZ, IZZ])
    box = cs.Vehicle.box(LENGTH, WIDTH, HEIGHT, mass=MASS, name="sedan", ground_clearance=0.15,
                         cg_height=CG_HEIGHT, inertia=inertia)  # fmt: skip
    wheels = cs.Wheels(WHEELBASE, TRACK, CG_TO_FRONT, CG_HEIGHT, RADIUS, steering_ratio=RATIO)
    return box.with_wheels(wheels)


def run(inputs: cs.DriverInputs, speed: float, duration: float, mu: float = 0.8) -> cs.Result:
    scene = cs.Scene(ground=cs.Ground(friction=mu))
    scene.add(sedan(), (0.0, 0.0), velocity=(speed, 0.0, 0.0), inputs=inputs)
    return scene.run(duration)


def lateral_acceleration(result: cs.Result) -> np.ndarray:
    """(k,) the CG's acceleration across the vehicle (m/s^2, + left), from the velocity."""
    tr = result.trajectory("sedan")
    acc = np.gradient(tr.velocity, result.t, axis=0)
    left = np.array([rotation_matrix(q)[:, 1] for q in tr.orientation])
    return np.einsum("ki,ki->k", acc, left)


def roll(result: cs.Result) -> np.ndarray:
    """(k,) roll angle (rad, + left side up)."""
    rot = [rotation_matrix(q) for q in result.trajectory("sedan").orientation]
    return np.array([math.atan2(r[2, 1], r[2, 2]) for r in rot])


def save(fig: Figure, name: str) -> None:
    FigureCanvasAgg(fig)
    fig.savefig(IMG / name, dpi=110)
    print(f"  wrote docs/img/{name}")


# -- ISO 4138 -----------------------------------------------------------------------------------


def iso4138() -> None:
    print("ISO 4138 steady-state circular driving, constant steer angle (60 deg), speed raised")
    sw = math.radians(60.0)
    inputs = cs.DriverInputs(steering_wheel=sw, drive={"front": [(0.0, 0.1 * MASS * 9.80665)]})
    result = run(inputs, 5.0, 30.0)
    tr = result.trajectory("sedan")
    speed = np.linalg.norm(tr.velocity[:, :2], axis=1)
    r = tr.angular_velocity[:, 2]
    ay = speed * r
    radius = speed / np.maximum(r, 1e-9)
    keep = (result.t > 2.0) & (ay > 0.3)
    delta_needed = WHEELBASE / radius[keep]  # Ackermann angle of the path (rad)
    steer = result.wheel_steer("sedan")
    delta = 0.5 * (steer[0] + steer[1])[keep]  # the front wheels' mean angle, as run
    understeer = np.degrees(delta - delta_needed)  # road-wheel deg
    g = ay[keep] / 9.80665
    lin = g < 0.4
    slope = np.polyfit(g[lin], understeer[lin], 1)[0]
    print(f"  understeer gradient below 0.4 g: {slope:.2f} deg/g (road wheel); "
          f"{slope * RATIO:.1f} deg/g at the steering wheel; "
          f"largest a_y {g.max():.2f} g")  # fmt: skip
    fig = Figure(figsize=(11, 4.5))
    ax1, ax2 = fig.subplots(1, 2)
    ax1.plot(tr.position[:, 0], tr.position[:, 1], lw=1.0)
    ax1.set_aspect("equal")
    ax1.set_xlabel("x (m)")
    ax1.set_ylabel("y (m)")
    ax1.set_title("the path: steering wheel at 60 deg, the speed raised by 0.1 g of drive")
    ax2.plot(g, understeer, lw=1.2, label="front wheels' mean angle - L / R")
    ax2.plot(g[lin], slope * g[lin] + np.polyfit(g[lin], understeer[lin], 1)[1], "--",
             label=f"fit below 0.4 g: {slope:.2f} deg/g")  # fmt: skip
    ax2.set_xlabel("lateral acceleration (g)")
    ax2.set_ylabel("deg")
    ax2.set_title("ISO 4138: steer angle beyond the path's Ackermann angle")
    ax2.legend()
    fig.tight_layout()
    save(fig, "manoeuvre_iso4138.png")


# -- ISO 7401 -----------------------------------------------------------------------------------


def single_track(speed: float, delta: np.ndarray, t: np.ndarray, sigma: float) -> np.ndarray:
    """Yaw rate (rad/s) of the linear single-track model (axle stiffnesses c F_axle, c 1 per
    10 deg, first-order tyre lag over sigma) for the road-wheel angle delta(t)."""
    c = 1.0 / math.radians(10.0)
    a, b = CG_TO_FRONT, WHEELBASE - CG_TO_FRONT
    cf, cr = c * MASS * 9.80665 * b / WHEELBASE, c * MASS * 9.80665 * a / WHEELBASE
    s = np.zeros(4)  # v, r, Ff, Fr
    out = np.zeros_like(t)
    for k in range(1, len(t)):
        h = t[k] - t[k - 1]
        for _ in range(10):
            v, r, ff, fr = s
            d = np.interp(t[k - 1], t, delta)
            af, ar = (v + a * r) / speed - d, (v - b * r) / speed
            rate = np.array([(ff + fr) / MASS - speed * r, (a * ff - b * fr) / IZZ,
                             speed / sigma * (-cf * af - ff),
                             speed / sigma * (-cr * ar - fr)])  # fmt: skip
            s = s + rate * h / 10
        out[k] = s[1]
    return out


def iso7401() -> None:
    print("ISO 7401 step steer at 80 km/h to the steering-wheel angle of 4 m/s^2, 400 deg/s")
    speed = 80 / 3.6
    # the angle of 4 m/s^2 in the steady state of a first run
    probe = math.radians(30.0)
    probe_input = cs.DriverInputs(steering_wheel=[(0.0, 0.0), (0.5, 0.0), (0.575, probe)])
    first = run(probe_input, speed, 4.0)
    ay0 = float(np.median(lateral_acceleration(first)[first.t > 3.0]))
    sw = probe * 4.0 / ay0
    ramp = sw / math.radians(400.0)
    table = [(0.0, 0.0), (0.5, 0.0), (0.5 + ramp, sw)]
    result = run(cs.DriverInputs(steering_wheel=table), speed, 4.0)
    t = result.t
    r = result.trajectory("sedan").angular_velocity[:, 2]
    ay = lateral_acceleration(result)
    steady = float(np.median(r[t > 3.0]))
    t50 = 0.5 + ramp / 2
    t90 = float(t[np.argmax(r >= 0.9 * steady)])
    peak = float(r.max())
    delta = np.interp(t, [0.0, 0.5, 0.5 + ramp], [0.0, 0.0, sw / RATIO])
    model = single_track(speed, delta, t, 0.1)
    print(f"  steering wheel {math.degrees(sw):.1f} deg; "
          f"steady yaw rate {math.degrees(steady):.2f} deg/s "
          f"(the single-track model {math.degrees(model[-1]):.2f}); response time to 90 % "
          f"{1000 * (t90 - t50):.0f} ms from the input's 50 %; "
          f"overshoot {100 * (peak / steady - 1):.1f} %; "
          f"roll {math.degrees(roll(result)[-1]):.2f} deg")  # fmt: skip
    fig = Figure(figsize=(11, 4.5))
    ax1, ax2 = fig.subplots(1, 2)
    ax1.plot(t, np.degrees(r), label="crashsim")
    ax1.plot(t, np.degrees(model), "--", label="linear single-track model")
    ax1.set_xlabel("t (s)")
    ax1.set_ylabel("yaw rate (deg/s)")
    ax1.legend()
    ax1.set_title(f"ISO 7401 step steer, 80 km/h, {math.degrees(sw):.0f} deg at 400 deg/s")
    ax2.plot(t, ay, label="lateral acceleration (m/s^2)")
    ax2.plot(t, np.degrees(roll(result)), label="roll (deg)")
    ax2.set_xlabel("t (s)")
    ax2.legend()
    fig.tight_layout()
    save(fig, "manoeuvre_iso7401.png")


# -- ISO 3888-1 ---------------------------------------------------------------------------------


def cones(width: float) -> list[tuple[float, float, float]]:
    """ISO 3888-1 sections (start x m, length m, lane centre y m, lane width m)."""
    w1, w2, w3 = 1.1 * width + 0.25, 1.2 * width + 0.25, 1.3 * width + 0.25
    out = [(0.0, 15.0, 0.0, w1)]
    out.append((45.0, 25.0, w2 / 2 - w1 / 2 + 3.5, w2))  # the left lane: offset 3.5 m + halves
    out.append((95.0, 15.0, (w3 - w1) / 2, w3))  # right edges aligned with section 1
    return out  # type: ignore[return-value]


def lane_path(x: np.ndarray, sections: list[tuple[float, float, float, float]]) -> np.ndarray:
    """The lanes' centre line (m) at x: straight in each section, a smooth step (cosine)
    between them."""
    y = np.zeros_like(x)
    (s1, l1, c1, _), (s2, l2, c2, _), (s3, _, c3, _) = sections
    for a, b, ya, yb in ((s1 + l1, s2, c1, c2), (s2 + l2, s3, c2, c3)):
        u = np.clip((x - a) / (b - a), 0.0, 1.0)
        y = np.where(x >= a, ya + (yb - ya) * (1 - np.cos(np.pi * u)) / 2, y)
    return y


def lane_clearance(result: cs.Result, sections: list[tuple[float, float, float, float]]) -> float:
    """The least clearance (m) between the vehicle's outline (its half width and the sweep of
    its yaw) and the cones' lines over the three sections; -inf for a section never reached."""
    tr = result.trajectory("sedan")
    x, y = tr.position[:, 0], tr.position[:, 1]
    heading = np.unwrap([math.atan2(rotation_matrix(q)[1, 0], rotation_matrix(q)[0, 0])
                         for q in tr.orientation])  # fmt: skip
    out = []
    for start, length, centre, lane in sections:
        on = (x >= start) & (x <= start + length)
        half = 0.5 * (WIDTH * np.cos(heading[on]) + LENGTH * np.abs(np.sin(heading[on])))
        gap = lane / 2 - np.abs(y[on] - centre) - half
        out.append(float(np.min(gap)) if gap.size else -math.inf)
    return min(out)


def iso3888() -> None:
    print("ISO 3888-1 double lane change: a driver following the lanes' centre line")
    sections = cones(WIDTH)
    xs = np.linspace(-5.0, 140.0, 581)
    path = np.c_[xs, lane_path(xs, sections)]
    # The standard is a closed-loop test: its result is the highest entrance speed at which the
    # driver keeps the car inside the cones. crashsim's driver (pure pursuit, the path input)
    # at each speed with the preview (0.4-1.5 s) that keeps the most clearance.
    table = []
    for kmh in (40.0, 50.0, 60.0, 70.0, 80.0):
        speed = kmh / 3.6
        runs = [(lane_clearance(run(cs.DriverInputs(path=path, preview=p), speed, 130.0 / speed),
                                sections), p)
                for p in (0.4, 0.6, 0.8, 1.0, 1.2, 1.5)]  # fmt: skip
        table.append((kmh, *max(runs)))
    for kmh, clearance, preview in table:
        print(f"  {kmh:.0f} km/h: least clearance to the cones {clearance:+.2f} m "
              f"(preview {preview:g} s)")  # fmt: skip
    passed = [row for row in table if row[1] >= 0.0]
    kmh, clearance, preview = passed[-1] if passed else table[0]
    speed = kmh / 3.6
    result = run(cs.DriverInputs(path=path, preview=preview), speed, 130.0 / speed)
    tr = result.trajectory("sedan")
    x, y = tr.position[:, 0], tr.position[:, 1]
    steer = result.wheel_steer("sedan")
    print(f"  drawn: {kmh:.0f} km/h, preview {preview:g} s; largest road-wheel angle "
          f"{math.degrees(np.abs(steer[:2]).max()):.1f} deg; largest a_y "
          f"{np.abs(lateral_acceleration(result)).max() / 9.80665:.2f} g")  # fmt: skip
    from crashsim.plots import silhouette

    fig = Figure(figsize=(12, 5.5))
    ax1, ax2 = fig.subplots(2, 1, gridspec_kw={"height_ratios": [1.3, 1]})
    vehicle = result.vehicle("sedan")
    for k in range(0, len(result.t), max(1, len(result.t) // 40)):
        p, r = result.pose("sedan", float(result.t[k]))
        outline = silhouette(vehicle, p, r)
        ax1.fill(*outline.exterior.xy, color="tab:red", alpha=0.12, lw=0)
    ax1.plot(x, y, color="tab:red", lw=1.0, label="CG path")
    centre_label = "the lanes' centre line (the path)"
    ax1.plot(xs, path[:, 1], color="grey", lw=0.8, ls=":", label=centre_label)
    for start, length, centre, lane in sections:
        for edge in (centre - lane / 2, centre + lane / 2):
            stations = [start, start + length / 2, start + length]
            ax1.plot(stations, [edge] * 3, "o", color="orange", ms=4)
    ax1.plot([], [], "o", color="orange", ms=4, label="ISO 3888-1 cones")
    ax1.set_xlim(-5.0, 125.0)
    ax1.set_xlabel("x (m)")
    ax1.set_ylabel("y (m), stretched")
    ax1.legend(loc="upper right", fontsize=8)
    ax1.set_title(f"ISO 3888-1 double lane change: the reference sedan at {kmh:.0f} km/h "
                  f"following the lanes (pure pursuit, {preview:g} s preview); "
                  f"least clearance {clearance:+.2f} m", fontsize=10)  # fmt: skip
    ax2.plot([row[0] for row in table], [row[1] for row in table], "o-")
    ax2.axhline(0.0, color="grey", lw=0.8)
    ax2.set_xlabel("entrance speed (km/h)")
    ax2.set_ylabel("least clearance to the cones (m)")
    fig.tight_layout()
    save(fig, "manoeuvre_iso3888.png")


# -- NHTSA fishhook -----------------------------------------------------------------------------


def fishhook() -> None:
    print("NHTSA fishhook: 6.5 x the steering-wheel angle of 0.3 g (SIS at 50 mph, 13.5 deg/s)")
    sis = run(cs.DriverInputs(steering_wheel=[(0.0, 0.0), (1.0, 0.0), (21.0, math.radians(270))]),
              50 * 0.44704, 20.0)  # fmt: skip
    ay = lateral_acceleration(sis)
    k = int(np.argmax(ay >= 0.3 * 9.80665))
    sw = float(np.interp(sis.t[k], [1.0, 21.0], [0.0, math.radians(270)]))
    amp = 6.5 * sw
    print(f"  0.3 g at {math.degrees(sw):.1f} deg of steering wheel: the fishhook's amplitude "
          f"{math.degrees(amp):.0f} deg")
    rate = math.radians(720.0)
    fig = Figure(figsize=(11, 4.5))
    ax1, ax2 = fig.subplots(1, 2)
    for mph in (35.0, 40.0, 45.0):
        t1 = 0.5 + amp / rate
        t2 = t1 + 0.25
        t3 = t2 + 2 * amp / rate
        table = [(0.0, 0.0), (0.5, 0.0), (t1, amp), (t2, amp), (t3, -amp), (t3 + 3.0, -amp),
                 (t3 + 4.0, 0.0)]  # fmt: skip
        result = run(cs.DriverInputs(steering_wheel=table), mph * 0.44704, t3 + 4.5)
        loads = result.wheels("sedan").load
        phi = np.degrees(roll(result))
        lift = np.min(loads, axis=1)
        names = result.wheels("sedan").names
        lowest = ", ".join(f"{n} {lo:.0f} N" for n, lo in zip(names, lift, strict=True))
        print(f"  {mph:.0f} mph: largest roll {np.abs(phi).max():.1f} deg; "
              f"lowest wheel loads {lowest}")  # fmt: skip
        ax1.plot(result.t, phi, label=f"{mph:.0f} mph")
        ax2.plot(result.t, loads[0] + loads[2], label=f"{mph:.0f} mph, left wheels")
    ax1.set_xlabel("t (s)")
    ax1.set_ylabel("roll (deg)")
    ax1.set_title(f"NHTSA fishhook, {math.degrees(amp):.0f} deg at 720 deg/s")
    ax1.legend()
    ax2.set_xlabel("t (s)")
    ax2.set_ylabel("left wheels' load (N)")
    ax2.legend()
    fig.tight_layout()
    save(fig, "manoeuvre_fishhook.png")


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--only", default="iso4138,iso7401,iso3888,fishhook")
    args = parser.parse_args()
    for name in args.only.split(","):
        {"iso4138": iso4138, "iso7401": iso7401, "iso3888": iso3888, "fishhook": fishhook}[name]()


if __name__ == "__main__":
    main()
