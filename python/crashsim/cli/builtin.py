"""The commands that need no scene file: ``crashsim demo`` (the built-in scenes of
crashsim.demo) and ``crashsim dtp-montecarlo`` (the depth of penetration over the vehicle
classes)."""

from __future__ import annotations

import argparse
import json
from pathlib import Path
from typing import Any

from crashsim.analysis.montecarlo import PERCENTILES, dtp_montecarlo, plot_dtp_histogram
from crashsim.analysis.report import build_report
from crashsim.cli.common import RunFailed, _check_writable, _make, _no_progress
from crashsim.cli.output import _write_run
from crashsim.errors import ParameterError
from crashsim.io.viewer import PAGE_FILE

DEMO_OUT = "crashsim-demo-out"  # the demo's folder in the current one
DEMO_MAX_DURATION = 15.0  # s: the demo's longest run to rest


def _demo(args: argparse.Namespace) -> int:
    from crashsim import demo

    dt = 1e-3 if args.dt is None else args.dt
    if args.impact_only:
        speed = demo.IMPACT_SPEED if args.speed is None else args.speed
        duration = 0.5 if args.duration is None else args.duration
        scene = demo.impact_scene(speed)
        result = scene.run(duration=duration, dt=dt)
        if not result.impacts:
            raise RunFailed(demo.no_exchange(result, duration, demo.IMPACT_GAP))
        print(json.dumps(result.to_dict(), indent=2) if args.json
              else demo.impact_summary(result, scene, speed))  # fmt: skip
        return 0
    out = Path(DEMO_OUT if args.out is None else args.out)
    _check_writable(out)  # before the run
    speed = demo.SPEED if args.speed is None else args.speed
    longest = DEMO_MAX_DURATION if args.duration is None else args.duration
    result = demo.intersection_scene(speed).run(
        until="rest", max_duration=longest, dt=dt, progress=_no_progress
    )
    if not result.impacts:
        raise RunFailed(demo.no_exchange(result, longest, demo.intersection_gap()))
    _make(out)
    report = build_report(result)
    title = "crashsim demo: a two-car intersection case run to rest"
    written = _write_run(result, report, out, pictures=not args.no_pictures,
                         glb=not args.no_pictures, html=out / PAGE_FILE, title=title)  # fmt: skip
    if args.json:
        print(json.dumps(result.to_dict(), indent=2))
        return 0
    print(demo.intersection_summary(report, speed))
    print("wrote: " + ", ".join(str(p) for p in written))
    print(f"open {out / PAGE_FILE} in a browser: the 3-D scene, its timeline and the report")
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
    if plot is not None:
        if not plot.parent.is_dir():
            raise ParameterError(f"--plot {plot}: the folder {plot.parent} does not exist")
        _check_writable(plot.parent)
    result = dtp_montecarlo(samples=args.samples, seed=args.seed)
    summary = result.summary()
    pairing = {c: len(p) for c, p in result.pairs.items()}
    if plot is not None:
        plot_dtp_histogram(result, plot, source="crashsim.vehicles.vehicle_data")
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
