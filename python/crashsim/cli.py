"""The ``crashsim`` command line.

``crashsim demo`` runs the built-in side impact (the seed's first worked example): a red box
car at 30 mph square into the driver (left) side of a stationary blue box car, with the
default contact parameters (depth of penetration 30 ms, restitution 0.1, friction 0.6).

``crashsim dtp-montecarlo`` samples the depth of penetration dt_p = sqrt(m'/k') over pairs of
the built-in vehicle classes (crashsim.montecarlo) and prints its percentiles in ms.
"""

from __future__ import annotations

import argparse
import json
import sys
from collections.abc import Sequence
from pathlib import Path
from typing import Any

import numpy as np

from crashsim._core import __version__
from crashsim.errors import CrashsimError, ParameterError
from crashsim.montecarlo import PERCENTILES, dtp_montecarlo, plot_dtp_histogram
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


def _dtp_table(summary: dict[str, Any], header: str) -> str:
    """The Monte Carlo summary (s) as a table in ms."""
    lo, hi = (1e3 * b for b in summary["band"])
    keys = [f"{p:g}" for p in PERCENTILES]
    band = f"{lo:g}-{hi:g} ms"
    cols = f"{'configuration':<14}{'n':>9}{'mean':>7}" + "".join(f"{'P' + k:>7}" for k in keys)
    lines = [header, "  dt_p percentiles (ms):", "  " + cols + f"  {'in ' + band:>12}"]
    rows = [("all", summary["overall"]), *summary["by_configuration"].items()]
    for name, s in rows:
        pc = s["percentiles"]
        cells = "".join(f"{1e3 * pc[k]:7.1f}" for k in keys)
        share = f"{100.0 * s['fraction_in_band']:.1f} %"
        lines.append(f"  {name:<14}{s['n']:>9}{1e3 * s['mean']:7.1f}{cells}  {share:>12}")
    return "\n".join(lines)


def _dtp_montecarlo(args: argparse.Namespace) -> int:
    plot = Path(args.plot) if args.plot is not None else None
    if plot is not None and not plot.parent.is_dir():
        raise ParameterError(f"--plot {plot}: the folder {plot.parent} does not exist")
    result = dtp_montecarlo(samples=args.samples, seed=args.seed)
    summary = result.summary()
    pairing = {c: len(p) for c, p in result.pairs.items()}
    if plot is not None:
        plot_dtp_histogram(result, plot, source="crashsim.vehicle_data")
    if args.json:
        out = {
            "units": "s",
            "classes": list(result.class_names),
            "pairs_per_configuration": pairing,
            "excluded": {c: list(v) for c, v in result.excluded.items() if v},
            **summary,
            "plot": None if plot is None else str(plot),
        }
        print(json.dumps(out, indent=2))
        return 0
    header = (
        f"crashsim dtp-montecarlo: {len(result):,} samples, seed {result.seed}, "
        f"{len(result.class_names)} vehicle classes ({', '.join(result.class_names)}); "
        "ordered pairs, configurations weighted equally"
    )
    print(_dtp_table(summary, header))
    for c, names in result.excluded.items():
        if names:
            print(f"  {c}: left out for missing face data: {', '.join(names)}")
    if plot is not None:
        print(f"  histogram written to {plot}")
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
    mc = sub.add_parser(
        "dtp-montecarlo",
        help="Monte Carlo of the depth of penetration over vehicle-class pairs",
        description="Samples dt_p = sqrt(m'/k') (reduced mass over series stiffness, "
        "k = B W) for every ordered pair of the built-in vehicle classes in front-front, "
        "front-rear, front-side and rear-side impacts (full width, in line, the narrower "
        "width; mass, width and B uniform within one standard deviation) and prints the "
        "percentiles in ms, overall and per configuration.",
    )
    mc.add_argument("--samples", type=int, default=1_000_000, help="number of samples (1000000)")
    mc.add_argument("--seed", type=int, default=0, help="random seed, >= 0 (0)")
    mc.add_argument("--plot", metavar="PATH", help="write the histogram picture (PNG) here")
    mc.add_argument("--json", action="store_true", help="print the summary as JSON (seconds)")
    mc.set_defaults(func=_dtp_montecarlo)
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
