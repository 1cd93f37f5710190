"""The scenes of ``crashsim demo`` and what it prints about them (the command itself, which
runs them and writes the files, is crashsim.cli).

The demo (:func:`intersection_scene`): a two-car intersection case run to rest on the
ground, with bodies generated from the built-in vehicle classes (nothing to download). Red,
a sedan, drives along +x at 60 km/h into the left side of blue, an SUV crossing along +y at
30 km/h, just ahead of blue's centre of gravity; red's wheels lock at the impact, blue's
driver brakes at half the friction. Blue, spun and pushed across the junction, strikes a
lamp post on the grass at the far corner. Dry asphalt; the depth of penetration of the
cars is ``"auto"`` (from their classes' face stiffness), the lamp post's 30 ms.

The seed's first worked example (:func:`impact_scene`, ``crashsim demo --impact-only``):
a red box car at 30 mph square into the driver side of a blue one at rest, no ground, the
first exchange only.
"""

from __future__ import annotations

import numpy as np

from crashsim.analysis.report import Report
from crashsim.environment.ground import FrictionZone, Ground
from crashsim.environment.obstacles import Obstacle
from crashsim.result import Result
from crashsim.scene import Scene
from crashsim.units import deg, kmh, mph, to_ft, to_kmh, to_mph
from crashsim.vehicles.inputs import DriverInputs
from crashsim.vehicles.vehicle import Vehicle

__all__ = [
    "IMPACT_GAP",
    "IMPACT_SPEED",
    "SPEED",
    "impact_scene",
    "impact_summary",
    "intersection_gap",
    "intersection_scene",
    "intersection_summary",
    "no_exchange",
]

SPEED = kmh(60.0)  # m/s: red's speed in the intersection case
BLUE_SPEED = kmh(30.0)  # m/s
RED_START = (-12.0, -1.75)  # m: red's CG, in the middle of its lane (the road along x)
STRIKE_AHEAD_OF_CG = 0.6  # m: where red's front meets blue's left side, ahead of blue's CG
ROAD_HALF_WIDTH = 3.5  # m: both roads are 7 m wide, crossing at the origin
LAMP_POST = (4.1, 3.7)  # m: on the grass at the junction's far corner, in blue's way
IMPACT_SPEED = mph(30.0)  # m/s: red's speed in the seed's example (--impact-only)
IMPACT_GAP = 0.5  # m between red's front and blue's side at t = 0 (--impact-only)


def intersection_scene(speed: float = SPEED) -> Scene:
    """The demo's intersection case with red at ``speed`` (m/s, > 0). Blue starts where it
    meets red's front STRIKE_AHEAD_OF_CG ahead of its CG whatever the speed (both keep their
    speeds up to the impact)."""
    red, blue = _cars()
    h, far = ROAD_HALF_WIDTH, 40.0
    corner = FrictionZone([(h, h), (far, h), (far, far), (h, far)], "grass", name="corner verge")
    scene = Scene(ground=Ground(friction="dry asphalt", zones=[corner]),
                  depth_of_penetration=0.030, restitution=0.1, friction=0.6)  # fmt: skip
    scene.add(red, RED_START, heading=0.0, velocity=(speed, 0.0, 0.0),
              inputs=DriverInputs(wheel_states=[("all", "locked", "exchange")]))  # fmt: skip
    t = intersection_gap() / speed  # red's front reaches blue's left side
    blue_y = RED_START[1] - STRIKE_AHEAD_OF_CG - BLUE_SPEED * t
    scene.add(blue, (0.0, blue_y), heading=deg(90.0), velocity=(0.0, BLUE_SPEED, 0.0),
              inputs=DriverInputs(wheel_states=[("all", "braked", "exchange", 0.5)]))  # fmt: skip
    scene.contact(red, blue, depth_of_penetration="auto")  # the classes' face stiffness
    scene.add_obstacle(Obstacle.pole(0.25, name="lamp post"), LAMP_POST)
    return scene


def _cars() -> tuple[Vehicle, Vehicle]:
    return Vehicle.generate("sedan", name="red"), Vehicle.generate("suv", name="blue")


def intersection_gap() -> float:
    """Between red's front and blue's left side (blue heads +y: its left faces -x) along x at
    t = 0 in the intersection case, m."""
    red, blue = _cars()
    red_front = RED_START[0] + float(np.max(red.body_vertices[:, 0]))
    return -float(np.max(blue.body_vertices[:, 1])) - red_front


def no_exchange(result: Result, duration: float, gap: float) -> str:
    """Why a demo run made no exchange, and what to give instead: red stopped short of blue
    (``gap`` m away at the start: a longer run or a higher speed), or passed through it (an
    overlap that brief is taken for a graze: a lower speed)."""
    x = result.trajectory("red").position[:, 0]  # m, red drives along +x
    speed = f"{to_mph(float(result.trajectory('red').velocity[0, 0])):g} mph"
    if x[-1] - x[0] < gap:  # its front never reached blue's side
        what, advice = f"did not reach blue ({gap:g} m away)", "a longer --duration or a higher"
    else:
        what, advice = ("passed through blue without one (an overlap that brief is taken for a "
                        "graze)", "a lower")  # fmt: skip
    return (f"no impulse exchange happened within the {duration:g} s run: red at {speed} "
            f"{what}; give {advice} --speed")  # fmt: skip


def _kmh(v: float) -> str:
    return f"{v:.2f} m/s ({to_kmh(v):.1f} km/h)"


def intersection_summary(report: Report, speed: float) -> str:
    """What the demo prints: the case in a line, then per impact its time, closing speed,
    depth of penetration and energy, and per vehicle its delta-V, PDOF, clock and EES; then
    each vehicle's run-out (rest time, position, heading, distance, tyre marks)."""
    result = report.result
    masses = {n: result.vehicle(n).mass for n in result.vehicles}
    lines = [
        f"crashsim demo: red (generated sedan, {masses['red']:.0f} kg) at {to_kmh(speed):.0f} "
        f"km/h into the left side of blue (generated SUV, {masses['blue']:.0f} kg) crossing "
        f"at {to_kmh(BLUE_SPEED):.0f} km/h; dry asphalt, grass on the far corner with a lamp "
        "post; run to rest",
    ]
    for imp in report.impacts:
        a, b = imp.vehicles
        dtp = f"{imp.depth_of_penetration * 1e3:.1f} ms ({imp.depth_of_penetration_mode})"
        lines.append(
            f"  impact {imp.number}: {a} -> {b} at {imp.exchange_time:.3f} s, closing "
            f"{_kmh(imp.closing_speed)}, depth of penetration {dtp}, energy dissipated "
            f"{imp.energy_dissipated / 1e3:.1f} kJ"
        )
        for p in imp.parties:
            pdof = "-" if p.pdof_deg is None else f"{p.pdof_deg:.0f} deg ({p.clock} o'clock)"
            ees = "" if p.ees is None else f", EES {_kmh(p.ees)}"
            lines.append(f"    {p.name:<5} delta-V {_kmh(p.delta_v_magnitude)}, PDOF {pdof}{ees}")
    for r in report.run_out:
        where = f"({r.position[0]:.2f}, {r.position[1]:.2f}) m, heading {r.end_heading:.0f} deg"
        when = (f"at rest at {r.rest_time:.2f} s" if r.at_rest and r.rest_time is not None
                else f"still moving at {r.end_time:.2f} s")  # fmt: skip
        marks = sum(m.length for m in r.tyre_marks.values())
        lines.append(
            f"  {r.vehicle:<5} {when} at {where}; {r.distance:.2f} m from its {r.start_words} "
            f"at {_kmh(r.speed)}; tyre marks {marks:.1f} m in all"
        )
    return "\n".join(lines)


def impact_scene(speed: float = IMPACT_SPEED) -> Scene:
    """The seed's first worked example: red (4.5 x 1.8 x 1.4 m, 1450 kg) heading +x at
    ``speed`` (m/s) into the left side of blue (4.6 x 1.8 x 1.45 m, 1500 kg, at rest, heading
    +90 deg so its left side faces -x), 0.3 m ahead of blue's CG. No ground; default
    parameters (depth of penetration 30 ms, restitution 0.1, friction 0.6)."""
    red = Vehicle.box(length=4.5, width=1.8, height=1.4, mass=1450.0, name="red")
    blue = Vehicle.box(length=4.6, width=1.8, height=1.45, mass=1500.0, name="blue")
    scene = Scene()
    # Blue's left side is the plane x = -0.9 m (half its width); red's front is 2.25 m ahead
    # of its CG.
    red_x = -0.9 - IMPACT_GAP - 4.5 / 2.0
    scene.add(red, position=(red_x, 0.3, 0.7), heading=0.0,
              velocity=(speed, 0, 0))  # fmt: skip
    scene.add(blue, position=(0.0, 0.0, 0.725), heading=deg(90.0))
    return scene


def _vec(v: np.ndarray, digits: int = 3) -> str:
    # + 0.0 turns a rounded -0.0 into 0.0
    return "(" + ", ".join(f"{round(float(x), digits) + 0.0:.{digits}f}" for x in v) + ")"


def impact_summary(result: Result, scene: Scene, speed: float) -> str:
    """The seed example's first exchange, in words and numbers."""
    imp = result.impacts[0]
    p = scene.contact_parameters("red", "blue")
    red0 = result.state_at("red", imp.first_contact_time)["position"]
    red1 = result.state_at("red", imp.time)["position"]
    travel = float(np.linalg.norm(red1 - red0))
    lines = [
        f"crashsim demo: red ({to_mph(speed):g} mph) square into the driver side of blue (at "
        "rest)",
        f"  depth of penetration {p['depth_of_penetration'] * 1e3:g} ms, restitution "
        f"{p['restitution']:g}, friction {p['friction']:g}",
        f"  first overlap            t0 = {imp.first_contact_time * 1e3:8.3f} ms",
        f"  impulse exchange         t  = {imp.time * 1e3:8.3f} ms",
        f"  red's travel past first overlap: {travel:.4f} m = {to_ft(travel):.3f} ft",
        f"  impulse centroid (world) {_vec(imp.centroid)} m",
        f"  normal (red -> blue)     {_vec(imp.normal, 4)}",
        f"  impulse on blue          {_vec(imp.impulse, 1)} N s "
        f"({'sliding' if imp.sliding else 'full'} impact)",
    ]
    for name in imp.vehicles:
        dv = imp.delta_v[name]
        body = result.delta_v_body(imp, name)
        size = float(np.linalg.norm(dv))
        lines += [
            f"  delta-V {name:<5}            {_vec(dv)} m/s = {_vec(to_mph(dv), 2)} mph (world)",
            f"    |dV| = {size:.3f} m/s = {to_mph(size):.2f} mph; in {name}'s frame: "
            f"longitudinal {body[0]:+.3f} m/s, lateral {-body[1]:+.3f} m/s (+right)",
        ]
    lines.append(f"  energy dissipated        {imp.energy_dissipated / 1e3:.2f} kJ")
    if len(result.impacts) > 1:
        lines.append(f"  ({len(result.impacts) - 1} further exchange(s) follow)")
    return "\n".join(lines)
