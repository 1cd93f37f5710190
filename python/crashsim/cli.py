"""The `crashsim` command line. `crashsim demo` runs the built-in 30 mph side impact."""

from __future__ import annotations

import argparse
import sys

import numpy as np

from crashsim.errors import CrashsimError
from crashsim.scene import Scene
from crashsim.units import deg, mph, to_ft, to_mph
from crashsim.vehicle import Vehicle


def demo_scene(speed_mph: float = 30.0) -> Scene:
    """A red box car at `speed_mph` square into the driver (left) side of a stationary blue
    car; default contact parameters (30 ms, eps 0.1, mu 0.6)."""
    red = Vehicle.box(length=4.5, width=1.8, height=1.4, mass=1450.0, name="red")
    blue = Vehicle.box(length=4.6, width=1.8, height=1.45, mass=1500.0, name="blue")
    scene = Scene()
    # Blue heads +y, so its left side faces -x; red starts 0.5 m short of it heading +x.
    scene.add(red, position=(-0.9 - 2.25 - 0.5, 0.3, 0.7), velocity=(mph(speed_mph), 0, 0))
    scene.add(blue, position=(0.0, 0.0, 0.725), heading=deg(90.0))
    return scene


def _demo(args: argparse.Namespace) -> int:
    scene = demo_scene(args.speed)
    result = scene.run(duration=0.5, dt=1e-3)
    if not result.impacts:
        print("no impact happened")
        return 1
    imp = result.impacts[0]
    red0 = result.state_at("red", imp.first_contact_time)["position"]
    red1 = result.state_at("red", imp.time)["position"]
    travel = float(np.linalg.norm(red1 - red0))
    print(f"crashsim demo: red ({args.speed:g} mph) into the driver side of blue (at rest)")
    print(f"  first overlap        t0 = {imp.first_contact_time * 1e3:8.3f} ms")
    print(
        f"  impulse exchange     t  = {imp.time * 1e3:8.3f} ms  (depth of penetration "
        f"{imp.depth_of_penetration * 1e3:.1f} ms)"
    )
    print(f"  red's travel past first overlap: {travel:.4f} m = {to_ft(travel):.3f} ft")
    print(f"  centroid (world)     {np.round(imp.centroid, 4).tolist()} m")
    print(f"  normal (red -> blue) {np.round(imp.normal, 6).tolist()}")
    print(
        f"  impulse on blue      {np.round(imp.impulse, 1).tolist()} N s "
        f"({'sliding' if imp.sliding else 'full'} impact)"
    )
    for name in imp.vehicles:
        dv = imp.delta_v[name]
        n = float(np.linalg.norm(dv))
        print(
            f"  delta-V {name:5s} {np.round(dv, 3).tolist()} m/s, |dV| = {n:.3f} m/s "
            f"= {to_mph(n):.2f} mph"
        )
    print(f"  energy dissipated    {imp.energy_dissipated / 1e3:.2f} kJ")
    return 0


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(
        prog="crashsim", description="Open 3-D vehicle collision engine (Kudlich-Slibar)."
    )
    sub = parser.add_subparsers(dest="command", required=True)
    demo = sub.add_parser("demo", help="run the built-in 30 mph side impact and print it")
    demo.add_argument("--speed", type=float, default=30.0, help="red car's speed, mph")
    demo.set_defaults(func=_demo)
    args = parser.parse_args(argv)
    try:
        return int(args.func(args))
    except CrashsimError as e:
        print(f"crashsim: error: {e}", file=sys.stderr)
        return 2


if __name__ == "__main__":
    sys.exit(main())
