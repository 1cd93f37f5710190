"""The ``crashsim`` command line.

``crashsim demo`` runs the built-in side impact (the seed's first worked example): a red box
car at 30 mph square into the driver (left) side of a stationary blue box car, with the
default contact parameters (depth of penetration 30 ms, restitution 0.1, friction 0.6).
"""

from __future__ import annotations

import argparse
import json
import sys
from collections.abc import Sequence

import numpy as np

from crashsim._core import __version__
from crashsim.errors import CrashsimError
from crashsim.result import Result
from crashsim.scene import Scene
from crashsim.units import deg, mph, to_ft, to_mph
from crashsim.vehicle import Vehicle

__all__ = ["demo_scene", "main"]

DEMO_GAP = 0.5  # m between red's front and blue's side at t = 0


def demo_scene(speed_mph: float = 30.0) -> Scene:
    """The demo: red (4.5 x 1.8 x 1.4 m, 1450 kg) heading +x at ``speed_mph`` into the left
    side of blue (4.6 x 1.8 x 1.45 m, 1500 kg, at rest, heading +90 deg so its left side faces
    -x), 0.3 m ahead of blue's CG. Both stand on the ground (z = 0); default parameters."""
    red = Vehicle.box(length=4.5, width=1.8, height=1.4, mass=1450.0, name="red")
    blue = Vehicle.box(length=4.6, width=1.8, height=1.45, mass=1500.0, name="blue")
    scene = Scene()
    # Blue's left side is the plane x = -0.9 m (half its width); red's front is 2.25 m ahead
    # of its CG.
    red_x = -0.9 - DEMO_GAP - 4.5 / 2.0
    scene.add(red, position=(red_x, 0.3, 0.7), heading=0.0, velocity=(mph(speed_mph), 0, 0))
    scene.add(blue, position=(0.0, 0.0, 0.725), heading=deg(90.0))
    return scene


def _vec(v: np.ndarray, digits: int = 3) -> str:
    # + 0.0 turns a rounded -0.0 into 0.0
    return "(" + ", ".join(f"{round(float(x), digits) + 0.0:.{digits}f}" for x in v) + ")"


def _report(result: Result, scene: Scene, speed_mph: float) -> str:
    """The demo's first exchange, in words and numbers."""
    imp = result.impacts[0]
    p = scene.contact_parameters("red", "blue")
    red0 = result.state_at("red", imp.first_contact_time)["position"]
    red1 = result.state_at("red", imp.time)["position"]
    travel = float(np.linalg.norm(red1 - red0))
    lines = [
        f"crashsim demo: red ({speed_mph:g} mph) square into the driver side of blue (at rest)",
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


def _demo(args: argparse.Namespace) -> int:
    scene = demo_scene(args.speed)
    result = scene.run(duration=args.duration, dt=args.dt)
    if args.json:
        print(json.dumps(result.to_dict(), indent=2))
        return 0
    if not result.impacts:
        print("no impulse exchange happened within the run")
        return 1
    print(_report(result, scene, args.speed))
    return 0


def _parser() -> argparse.ArgumentParser:
    parser = argparse.ArgumentParser(
        prog="crashsim",
        description="Open 3-D vehicle collision engine (depth of penetration, Kudlich-Slibar "
        "impulse). SI units inside.",
    )
    parser.add_argument("--version", action="version", version=f"crashsim {__version__}")
    sub = parser.add_subparsers(dest="command", required=True, metavar="command")
    demo = sub.add_parser(
        "demo",
        help="run the built-in 30 mph side impact and print what happened",
        description="A red box car drives square into the driver side of a stationary blue "
        "box car; prints the first overlap, the exchange, the centroid, normal, impulse, "
        "delta-V and the energy dissipated.",
    )
    demo.add_argument("--speed", type=float, default=30.0, help="red's speed, mph (30)")
    demo.add_argument("--dt", type=float, default=1e-3, help="largest time step, s (0.001)")
    demo.add_argument("--duration", type=float, default=0.5, help="simulated time, s (0.5)")
    demo.add_argument("--json", action="store_true", help="print the result as JSON")
    demo.set_defaults(func=_demo)
    return parser


def main(argv: Sequence[str] | None = None) -> int:
    """Entry point of the ``crashsim`` command; returns the exit code."""
    args = _parser().parse_args(argv)
    try:
        return int(args.func(args))
    except CrashsimError as e:
        print(f"crashsim: error: {e}", file=sys.stderr)
        return 2


if __name__ == "__main__":
    sys.exit(main())
