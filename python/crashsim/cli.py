"""The ``crashsim`` command line.

``crashsim run case.toml`` loads a scene file (crashsim.io.scenefile; docs/scene-format.md), runs
it, prints the report's summary table and writes report.json, the time histories (CSV), the
top-down pictures (PNG) and the 3-D motion (GLB) into a folder; with ``--html`` also the case
page (one offline HTML file: the 3-D scene, a timeline and the report; crashsim.io.viewer).

``crashsim view out/report.json`` writes the case page of a run from the report.json that
``crashsim run --out`` wrote and the files beside it (the time histories and the meshes).

``crashsim check case.toml`` runs a scene file and checks the engine's first overlaps against
the independent python-fcl cross-check; it fails (exit 1) when they disagree.

``crashsim demo`` runs the built-in intersection case to rest (crashsim.demo: two generated
cars on dry asphalt, the struck one into a lamp post), prints the report's essentials and
writes the report, pictures and case page into a folder (``--out``, else crashsim-demo-out);
``--impact-only`` runs the seed's first worked example instead (two box cars, no ground,
the first exchange, printed only).

``crashsim sweep case.toml --vary red.speed=10:20:5 --vary restitution=0,0.1,0.2`` and
``crashsim montecarlo case.toml -n 1000 --seed 1 --dist "red.speed=normal(15 m/s, 1 m/s)"`` run
a study of the scene (crashsim.studies; docs/studies.md), or the file's ``[study]`` table; they
print the percentiles of every output, write the variants as CSV or Parquet (``--out``) and
the pictures (``--plots DIR``), on this machine or a Dask cluster (``--backend dask``).

``crashsim fit case.toml`` fits the unknowns of the file's ``[fit]`` table to its
``[[evidence]]`` (crashsim.io.fitfile, crashsim.fit; docs/fitting.md): it prints the best values
with their 95 % ranges and every item's residual in the file's units, and the fit's verdict
(fits, poor fit: a warning, does not fit: exit 1 with the reasons), and writes fit.json,
fit.png and the fitted run's report; Ctrl-C prints and writes the best so far (exit 130).

``crashsim dtp-montecarlo`` samples the depth of penetration dt_p = sqrt(m'/k') over pairs of
the built-in vehicle classes (crashsim.analysis.montecarlo) and prints its percentiles in ms.

Exit codes: 0 success; 1 the run or the check failed (or writing an output failed after the
run, e.g. a full disk); 2 bad input (a malformed scene file, bad arguments, vehicles
overlapping at t = 0, an output folder that cannot be created or written: all found before
the run); 130 interrupted (Ctrl-C). Every error is one line on stderr starting
``crashsim: error:``.

Option values that look like options (``--dt -1ms``, ``--speed -5``) are taken as values, so
that they get this command's own message rather than argparse's "expected one argument".
"""

from __future__ import annotations

import argparse
import csv
import json
import math
import os
import sys
import tempfile
import time
import warnings
from collections.abc import Callable, Sequence
from pathlib import Path
from typing import IO, Any, NoReturn

import numpy as np

from crashsim._core import __version__
from crashsim.analysis.crosscheck import cross_check
from crashsim.analysis.montecarlo import PERCENTILES, dtp_montecarlo, plot_dtp_histogram
from crashsim.analysis.report import Report, build_report
from crashsim.errors import CrashsimError, InputError, ParameterError, SimulationError
from crashsim.io.export import export_glb
from crashsim.io.scenefile import SceneFile, load_scene, parse_quantity
from crashsim.io.viewer import PAGE_FILE, view, view_report
from crashsim.plots import plot_impact, plot_trajectories
from crashsim.result import Result
from crashsim.units import mph

__all__ = ["EXIT_FAILED", "EXIT_INPUT", "EXIT_INTERRUPTED", "main", "write_csv"]

EXIT_FAILED = 1  # the run or the check failed
EXIT_INPUT = 2  # bad input: a malformed scene file, bad arguments
EXIT_INTERRUPTED = 130  # Ctrl-C (128 + SIGINT), as shells report it

REPORT_FILE = "report.json"
CSV_FILE = "time-histories.csv"
GLB_FILE = "motion.glb"
TRAJECTORIES_FILE = "trajectories.png"

DEMO_OUT = "crashsim-demo-out"  # the demo's folder in the current one
DEMO_MAX_DURATION = 15.0  # s: the demo's longest run to rest


class RunFailed(Exception):
    """The run finished but did not do what the command is for (exit 1)."""


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


# -- scene files ---------------------------------------------------------------------------


class ProgressBar:
    """A one-line progress bar on a stream, driven by Scene.run's progress callback (the
    simulated time reached, s)."""

    def __init__(self, duration: float, stream: IO[str], width: int = 30) -> None:
        self.duration = duration
        self.stream = stream
        self.width = width
        self.drawn = False

    def __call__(self, t: float) -> None:
        frac = min(max(t / self.duration, 0.0), 1.0) if self.duration > 0 else 1.0
        filled = int(frac * self.width)
        bar = "#" * filled + "." * (self.width - filled)
        self.drawn = True  # first: a Ctrl-C during the write still gets its line ended
        self.stream.write(f"\r  [{bar}] {100.0 * frac:5.1f} %  t = {t:.3f} of {self.duration:g} s")
        self.stream.flush()

    def close(self, done: bool) -> None:
        """Finish the line (drawn at 100 % when the run completed)."""
        if self.drawn:
            if done:
                self(self.duration)
            self.stream.write("\n")
            self.stream.flush()


def _no_progress(t: float) -> None:
    """A progress callback that shows nothing (it lets the engine notice Ctrl-C)."""


def _positive_time(what: str, example: str) -> Callable[[str], float]:
    """argparse type: a time ("2 ms", "0.5 s" or a number of seconds) that must be > 0;
    ``what`` names it in the message ("the time step"), ``example`` is a valid value."""

    def parse(text: str) -> float:
        try:
            value = parse_quantity(_number_or_text(text), "time")
        except ParameterError as e:
            raise argparse.ArgumentTypeError(str(e)) from None
        if not value > 0.0:  # also NaN
            raise argparse.ArgumentTypeError(
                f"{text!r} is {value:g} s: {what} must be > 0 (e.g. {example!r})"
            )
        return value

    return parse


_step = _positive_time("the time step", "1 ms")
_duration = _positive_time("the simulated time", "0.5 s")
_record_interval = _positive_time("the recording interval", "10 ms")


def _demo_speed(text: str) -> float:
    """argparse type of the demo's speed: a number of mph or a speed with its unit ("60
    km/h"), > 0; m/s."""
    number = _number_or_text(text)
    try:
        value = mph(number) if isinstance(number, float) else parse_quantity(number, "speed")
    except ParameterError:
        raise argparse.ArgumentTypeError(f"{text!r}: give a number of mph or a speed with its "
                                         'unit, e.g. 30 or "50 km/h"') from None  # fmt: skip
    if not (value > 0.0 and math.isfinite(value)):
        raise argparse.ArgumentTypeError(
            f"{text!r}: red must drive towards blue, give a finite speed > 0 (e.g. 30)"
        )
    return value


def _number_or_text(text: str) -> float | str:
    try:
        return float(text)
    except ValueError:
        return text


def _heading(q: np.ndarray) -> np.ndarray:
    """Yaw of the body x axis from world x (rad, counter-clockwise seen from above) for
    quaternions (k, 4) (w, x, y, z), unwrapped so it runs on continuously past +-pi."""
    w, x, y, z = q.T
    return np.unwrap(np.arctan2(2.0 * (w * z + x * y), 1.0 - 2.0 * (y * y + z * z)))


def write_csv(result: Result, path: str | Path) -> list[str]:
    """Write the time histories: one row per sample (step ends, first overlaps, exchanges;
    at an exchange the state after it), a header row with units; SI, world frame. Per
    vehicle: CG x, y, z (m), heading (rad, yaw of the body x axis, unwrapped), orientation
    quaternion qw, qx, qy, qz, CG velocity vx, vy, vz (m/s), angular velocity wx, wy, wz
    (rad/s; wz is the yaw rate). Returns the header."""
    header = ["t [s]"]
    columns = [np.asarray(result.t)]
    parts = [
        ("x [m]", "y [m]", "z [m]"),
        ("heading [rad]",),
        ("qw [1]", "qx [1]", "qy [1]", "qz [1]"),
        ("vx [m/s]", "vy [m/s]", "vz [m/s]"),
        ("wx [rad/s]", "wy [rad/s]", "wz (yaw rate) [rad/s]"),
    ]
    for name in result.vehicles:
        tr = result.trajectory(name)
        blocks = [
            tr.position,
            _heading(np.asarray(tr.orientation))[:, None],
            tr.orientation,
            tr.velocity,
            tr.angular_velocity,
        ]
        for labels, block in zip(parts, blocks, strict=True):
            header += [f"{name} {label}" for label in labels]
            columns += list(np.asarray(block).T)
    table = np.column_stack(columns)
    with open(path, "w", newline="", encoding="utf-8") as f:
        writer = csv.writer(f)
        writer.writerow(header)
        for row in table:
            writer.writerow([f"{x:.15g}" for x in row])
    return header


def _write_run(
    result: Result,
    report: Report,
    out: Path,
    *,
    report_json: bool = True,
    csv: bool = True,
    pictures: bool = True,
    glb: bool = True,
    html: Path | None = None,
    title: str | None = None,
    progress: IO[str] | None = None,
) -> list[Path]:
    """Writes a run's files into the folder ``out`` (made): report.json, the time histories,
    the pictures, the GLB and the case page (at ``html``) as asked; returns their paths.
    ``progress``: a stream that gets a line per output as it is written, with its time (a
    long run's pictures and histories take seconds)."""

    def writing(label: str, write: Callable[[], list[Path]]) -> list[Path]:
        if progress is None:
            return write()
        progress.write(f"  writing {label} ...")
        progress.flush()
        start = time.perf_counter()
        try:
            return write()
        finally:
            progress.write(f" {time.perf_counter() - start:.1f} s\n")
            progress.flush()

    def one(path: Path, write: Callable[[Path], object]) -> list[Path]:
        write(path)
        return [path]

    written: list[Path] = []
    if report_json:
        written += writing(REPORT_FILE, lambda: one(out / REPORT_FILE, report.write_json))
    if csv:
        written += writing(CSV_FILE, lambda: one(out / CSV_FILE, lambda p: write_csv(result, p)))
    if pictures:
        written += writing("the pictures", lambda: _pictures(result, out))
    if glb:
        written += writing(GLB_FILE, lambda: _glb(result, out))
    if html is not None:
        page = html
        written += writing(page.name, lambda: [view(result, page, title=title)])
    return written


def _simulate(args: argparse.Namespace, case: SceneFile) -> Result:
    # until rest, --duration overrides the longest run (the file's max_duration)
    duration = case.run.longest if args.duration is None else args.duration
    dt = case.run.dt if args.dt is None else args.dt
    bar = ProgressBar(duration, sys.stderr) if args.progress or sys.stderr.isatty() else None
    done = False
    try:
        # always a callback: the engine honours Ctrl-C when it calls back into Python
        result = case.simulate(
            duration=duration,
            dt=dt,
            progress=bar or _no_progress,
            record_interval=args.record_interval,
        )
        done = True
    except InputError as e:  # e.g. vehicles overlapping at t = 0: name the file
        raise type(e)(f"{case.path}: {e}") from e
    finally:
        if bar is not None:
            bar.close(done)
    return result


def _header(case: SceneFile) -> str:
    title = case.title or (case.path.stem if case.path else "scene")
    names = ", ".join(v.name for v in case.scene.vehicles)
    return f"crashsim: {title} ({case.path}): {len(case.scene)} vehicles ({names})"


def _out_dir(args: argparse.Namespace, case: SceneFile) -> Path:
    """The output folder, checked before the run (bad input, exit 2): it must be a folder
    that exists and takes files, or one that can be created (nothing is created yet: a run
    that fails leaves no empty folder behind)."""
    if args.out is not None:
        out = Path(args.out)
    elif case.output.dir is not None:
        out = case.output.dir
    else:
        stem = case.path.stem if case.path is not None else "scene"
        out = Path(f"{stem}-out")
    _check_writable(out)
    return out


def _check_writable(out: Path) -> None:
    """ParameterError unless files can be written into ``out`` once it is made: its nearest
    existing ancestor (``out`` itself when it exists) must be a folder in which a file can be
    created (tested with an anonymous temporary file, which leaves nothing behind)."""
    if out.exists() and not out.is_dir():
        raise ParameterError(f"the output folder {out} is a file: give another --out")
    base = out
    while not base.exists() and base != base.parent:
        base = base.parent
    if not base.is_dir():
        raise ParameterError(
            f"cannot create the output folder {out}: {base} is a file, not a folder; give "
            "another --out"
        )
    try:
        with tempfile.TemporaryFile(dir=base):
            pass
    except OSError as e:
        where = "write into the output folder" if base == out else "create the output folder"
        because = "" if base == out else f" (in {base})"
        raise ParameterError(
            f"cannot {where} {out}{because}: {e.strerror or e}; give a writable --out"
        ) from e


def _make(out: Path) -> None:
    """Make the checked output folder (an OSError now is a failed run, exit 1)."""
    try:
        out.mkdir(parents=True, exist_ok=True)
    except OSError as e:
        raise OSError(e.errno, f"cannot create the output folder {out}: {e.strerror or e}") from e


def _run(args: argparse.Namespace) -> int:
    case = load_scene(args.scene)
    out = _out_dir(args, case)  # checked before the run, made after it
    html = _html_path(args, out)  # the case page's path, checked before the run too
    print(_header(case))
    result = _simulate(args, case)
    _make(out)
    want = case.output
    report = build_report(result)
    written = _write_run(
        result,
        report,
        out,
        report_json=want.report,
        csv=want.csv,
        pictures=want.pictures and not args.no_pictures,
        glb=want.glb and not args.no_pictures,
        html=html,
        title=case.title or None,
        progress=sys.stderr if args.progress or sys.stderr.isatty() else None,
    )
    # printed last: the files are complete even when the reader of stdout stops early
    print(report.summary_table())
    if not result.impacts:
        print("no impulse exchange happened within the run")
    print("wrote: " + ", ".join(str(p) for p in written) if written else "wrote nothing")
    return 0


def _html_path(args: argparse.Namespace, out: Path) -> Path | None:
    """Where ``--html`` puts the case page (None without it): PAGE_FILE in the output
    folder, or the path given; a given path's folder must exist and take files."""
    if args.html is None:
        return None
    if args.html is True:
        return out / PAGE_FILE
    path = Path(args.html)
    if path.suffix.lower() not in (".html", ".htm"):
        raise ParameterError(f"--html {args.html}: give a path ending in .html (or no path)")
    if not path.parent.is_dir():
        raise ParameterError(f"--html {args.html}: the folder {path.parent} does not exist")
    _check_writable(path.parent)
    return path


def _view(args: argparse.Namespace) -> int:
    path = view_report(args.report, args.out, force=args.force)
    print(f"wrote: {path}")
    return 0


def _pictures(result: Result, out: Path) -> list[Path]:
    plot_trajectories(result, out / TRAJECTORIES_FILE)
    paths = [out / TRAJECTORIES_FILE]
    for k in range(len(result.impacts)):  # with a vehicle or a fixed obstacle
        path = out / f"impact-{k + 1}.png"
        plot_impact(result, path, impact=k)
        paths.append(path)
    return paths


def _glb(result: Result, out: Path) -> list[Path]:
    path = out / GLB_FILE
    export_glb(result, path)
    return [path]


def _check(args: argparse.Namespace) -> int:
    case = load_scene(args.scene)  # also checks the file's [study], [fit] and [[evidence]]
    print(_header(case))
    if case.fit is not None:
        fit = case.fit
        what = ", ".join(fit.unknowns) if fit.unknowns else "none in the file (give --unknown)"
        print(f"fit: unknowns {what}; {len(fit.evidence)} evidence items "
              f"({', '.join(fit.types)}): checked")  # fmt: skip
    result = _simulate(args, case)
    check = cross_check(result)
    print(check)
    return 0 if check.ok else EXIT_FAILED


# -- fits ----------------------------------------------------------------------------------

FIT_JSON = "fit.json"
FIT_PICTURE = "fit.png"
FITTED_REPORT = "fitted-report.json"


def _fit_spec(args: argparse.Namespace, case: SceneFile) -> Any:
    """The fit to run: the file's [fit] and [[evidence]] with the command line's --unknown
    (replacing the file's entry of the same path), --start, --method and --seed."""
    import dataclasses

    from crashsim.io.fitfile import FitSpec
    from crashsim.io.studyfile import parse_assignment, parse_values
    from crashsim.studies.paths import parse_path

    spec = case.fit if case.fit is not None else FitSpec()
    if not spec.evidence:
        raise ParameterError(
            f"{case.path}: nothing to fit to: add [[evidence]] sections (and a [fit] table with "
            "its unknowns) to the file (docs/fitting.md)"
        )
    unknowns = dict(spec.unknowns)
    units = dict(spec.units)
    for text in args.unknown or []:
        key, value = parse_assignment(text, "--unknown")
        p = parse_path(case.scene, key)
        bounds = parse_values(key, value, p.dimension)
        if not isinstance(bounds, list) or len(bounds) != 2:
            raise ParameterError(
                f"--unknown {text!r}: give the two bounds lo,hi, e.g. --unknown "
                f'"{key}=20,50 mph"'
            )
        lo, hi = bounds
        if not lo < hi:
            raise ParameterError(f"--unknown {text!r}: the bounds ({lo:g}, {hi:g}) {p.unit} need "
                                 "lo < hi")  # fmt: skip
        unknowns[p.name] = (lo, hi)
        units.pop(p.name, None)
    if not unknowns:
        raise ParameterError(
            f"{case.path}: nothing to fit: give the unknowns in [fit.unknowns] or as --unknown "
            'PATH=LO,HI (e.g. --unknown "red.speed=20,50 mph")'
        )
    # the file's start values that still lie within the (perhaps new) bounds
    start = {k: v for k, v in spec.start.items()
             if k in unknowns and unknowns[k][0] <= v <= unknowns[k][1]}  # fmt: skip
    for text in args.start or []:
        key, value = parse_assignment(text, "--start")
        p = parse_path(case.scene, key)
        values = parse_values(key, value, p.dimension)
        if not isinstance(values, list) or len(values) != 1:
            raise ParameterError(f"--start {text!r}: give one value, e.g. --start "
                                 f'"{key}=40 mph"')  # fmt: skip
        if p.name not in unknowns:
            raise ParameterError(f"--start {text!r}: {p.name} is not one of the unknowns "
                                 f"({', '.join(unknowns)})")  # fmt: skip
        lo, hi = unknowns[p.name]
        if not lo <= values[0] <= hi:
            raise ParameterError(f"--start {text!r}: {values[0]:g} {p.unit} lies outside the "
                                 f"bounds ({lo:g}, {hi:g}) {p.unit}")  # fmt: skip
        start[p.name] = values[0]
    method = args.method if args.method is not None else spec.method
    options = dict(spec.options)
    if method != "global":
        for k in ("seed", "popsize", "maxiter"):
            options.pop(k, None)
    if args.seed is not None:
        if method != "global":
            raise ParameterError("--seed is for --method global (differential evolution)")
        options["seed"] = args.seed
    if args.no_scan:
        options["scan"] = False
    return dataclasses.replace(spec, unknowns=unknowns, units=units, start=start,
                               method=method, options=options)  # fmt: skip


def _fit_out_dir(args: argparse.Namespace, case: SceneFile) -> Path:
    """--out, else the file's output.dir, else <scene name>-fit; checked before the fit."""
    if args.out is not None:
        out = Path(args.out)
    elif case.output.dir is not None:
        out = case.output.dir
    else:
        out = Path(f"{case.path.stem if case.path is not None else 'scene'}-fit")
    _check_writable(out)
    return out


def _fit(args: argparse.Namespace) -> int:
    from crashsim.io.fitfile import format_fit
    from crashsim.studies.fit import fit as run_fit
    from crashsim.studies.verdict import DOES_NOT_FIT

    case = load_scene(args.scene)
    spec = _fit_spec(args, case)
    out = _fit_out_dir(args, case)
    duration = case.run.longest if args.duration is None else args.duration
    dt = case.run.dt if args.dt is None else args.dt
    run: dict[str, Any] = {"dt": dt, "until": case.run.until}
    run["max_duration" if case.run.until == "rest" else "duration"] = duration
    print(_header(case))
    print(f"fit ({spec.method}): {', '.join(spec.unknowns)} to {len(spec.evidence)} evidence "
          f"items ({', '.join(spec.types)})")  # fmt: skip
    sys.stdout.flush()
    fit = run_fit(
        case.scene,
        spec.unknowns,
        spec.evidence,
        progress=bool(args.progress or sys.stderr.isatty()),
        threads=args.threads,
        **run,
        **spec.kwargs(),
    )
    _make(out)
    written: list[Path] = []
    data = {
        "scene": str(case.path),
        "units_written": dict(spec.units),
        "evidence_types": list(spec.types),
        **fit.to_dict(),
    }
    with open(out / FIT_JSON, "w", encoding="utf-8") as f:
        json.dump(data, f, indent=2, allow_nan=False)
        f.write("\n")
    written.append(out / FIT_JSON)
    if not args.no_pictures:
        import matplotlib.pyplot as plt

        fig = fit.plot(out / FIT_PICTURE, units=spec.display_units())  # the table's units
        plt.close(fig)
        written.append(out / FIT_PICTURE)
    if fit.result is not None and case.output.report:
        build_report(fit.result).write_json(out / FITTED_REPORT)
        written.append(out / FITTED_REPORT)
    print(format_fit(fit, spec))
    print("wrote: " + ", ".join(str(p) for p in written))
    if fit.interrupted:
        raise KeyboardInterrupt
    if fit.result is None:
        raise RunFailed("the run at the fitted values failed (see the residuals above)")
    verdict = fit.verdict
    if verdict is not None and verdict.status == DOES_NOT_FIT:
        raise RunFailed(f"the fit does not fit: {'; '.join(verdict.reasons)}")
    if verdict is not None and not verdict.fits:
        print(f"crashsim: warning: {verdict.status}: {'; '.join(verdict.reasons)}",
              file=sys.stderr)  # fmt: skip
    return 0


# -- studies -------------------------------------------------------------------------------


def _study_out(text: str | None) -> Path | None:
    """The study's table file, checked before the run: .csv or .parquet in a writable folder."""
    if text is None:
        return None
    path = Path(text)
    if path.suffix.lower() not in (".csv", ".parquet", ".pq"):
        raise ParameterError(f"--out {text}: give a file ending in .csv or .parquet")
    if not path.parent.is_dir():
        raise ParameterError(f"--out {text}: the folder {path.parent} does not exist")
    _check_writable(path.parent)
    return path


def _study_spec(args: argparse.Namespace, case: SceneFile, kind: str) -> Any:
    """The study to run: the file's [study] (when its kind is this command's) with the command
    line's --vary / --dist added (replacing the file's entry of the same path)."""
    from crashsim.io.studyfile import StudySpec, parse_assignment, parse_distribution, parse_values
    from crashsim.studies.paths import parse_path

    file_spec = case.study if case.study is not None and case.study.kind == kind else None
    given = args.vary if kind == "sweep" else args.dist
    option = "--vary" if kind == "sweep" else "--dist"
    if file_spec is None and not given:
        other = f" (its [study] is a {case.study.kind} study)" if case.study is not None else ""
        raise ParameterError(
            f"{case.path}: nothing to vary{other}: give {option} PATH="
            + ("VALUES (e.g. --vary red.speed=10:20:5)" if kind == "sweep"
               else '"DIST" (e.g. --dist "red.speed=normal(15 m/s, 1 m/s)")')
            + f', or a [study] table with kind = "{kind}" in the file'
        )
    vary = dict(file_spec.vary) if file_spec is not None else {}
    dists = dict(file_spec.distributions) if file_spec is not None else {}
    for text in given or []:
        key, value = parse_assignment(text, option)
        dim = parse_path(case.scene, key).dimension
        if kind == "sweep":
            vary[key] = parse_values(key, value, dim)
        else:
            dists[key] = parse_distribution(key, value, dim)
            dists[key].check(key)
    n = seed = None
    if kind == "montecarlo":
        n = args.n if args.n is not None else (file_spec.n if file_spec is not None else None)
        seed = args.seed if args.seed is not None else (
            file_spec.seed if file_spec is not None else None)
        if n is None:
            raise ParameterError("give the number of variants: -n N (or n = ... in [study])")
    return StudySpec(kind=kind, vary=vary, distributions=dists, n=n, seed=seed)


def _study(args: argparse.Namespace, kind: str) -> int:
    from crashsim.studies import monte_carlo, sweep, tornado
    from crashsim.studies.plots import plot_histograms, plot_tornado
    from crashsim.studies.summary import format_summary

    case = load_scene(args.scene)
    spec = _study_spec(args, case, kind)
    out = _study_out(args.out)
    plots = Path(args.plots) if args.plots is not None else None
    if plots is not None:
        _check_writable(plots)
    if args.backend != "dask" and args.scheduler is not None:
        raise ParameterError("--scheduler is for --backend dask")
    duration = case.run.longest if args.duration is None else args.duration
    dt = case.run.dt if args.dt is None else args.dt
    run = {
        "duration": duration,
        "dt": dt,
        "until": case.run.until,
        "backend": args.backend,
        "client": args.scheduler,
        "threads": args.threads,
        "progress": bool(args.progress or sys.stderr.isatty()),
        "max_impacts": args.max_impacts,
    }
    print(_header(case))
    if kind == "sweep":
        what = ", ".join(f"{k} ({_count(v)})" for k, v in spec.vary.items())
        print(f"sweep: {what}")
        study = sweep(case.scene, spec.vary, **run)
    else:
        what = ", ".join(f"{k} ~ {d}" for k, d in spec.distributions.items())
        print(f"montecarlo: n = {spec.n}, seed = {spec.seed}: {what}")
        study = monte_carlo(case.scene, spec.distributions, spec.n, spec.seed, **run)
    written: list[Path] = []
    if out is not None:
        study.write(out)
        written.append(out)
    histograms: list[Path] = []
    if plots is not None:
        histograms = plot_histograms(study, plots)
    lines = [
        f"{study.n} variants: {int(study.ok.sum())} ran, {len(study.errors)} failed"
        + (f", {int((~study.finished).sum())} not run (interrupted)" if study.interrupted
           else "")
    ]
    for e in study.errors[:10]:
        lines.append(f"  failed: {' '.join(str(e).split())}")
    if len(study.errors) > 10:
        lines.append(f"  ... and {len(study.errors) - 10} more (the status column of --out)")
    if study.ok.any():
        lines.append("percentiles over the variants that ran (units: m, m/s, s, J, deg):")
        lines.append(format_summary(study.summary()))
    if args.tornado and not study.interrupted:
        ranges: dict[str, Any] = (
            dict(spec.distributions) if kind == "montecarlo"
            else {k: (float(np.min(study[k])), float(np.max(study[k]))) for k in spec.vary
                  if np.ptp(study[k]) > 0}
        )
        run["progress"] = False
        t = tornado(case.scene, ranges, **run)
        for output in t.outputs:
            lines.append(f"tornado of {output} (one input at a time, low and high):")
            lines.append(t.table(output).to_string(float_format=lambda x: f"{x:.6g}"))
            if plots is not None:
                path = plots / f"tornado-{output}.png"
                plot_tornado(t, output, path)
                written.append(path)
    print("\n".join(lines))
    shown = [str(p) for p in written]
    if histograms:
        shown.insert(1 if out is not None else 0, f"{len(histograms)} histograms in {plots}")
    print("wrote: " + ", ".join(shown) if shown else "wrote nothing")
    if study.interrupted:
        raise KeyboardInterrupt
    if not study.ok.any():
        raise RunFailed("every variant failed (see above)")
    return 0


def _count(values: Any) -> int:
    from crashsim.studies.design import Linspace

    return values.count if isinstance(values, Linspace) else len(values)


def _sweep(args: argparse.Namespace) -> int:
    return _study(args, "sweep")


def _montecarlo(args: argparse.Namespace) -> int:
    return _study(args, "montecarlo")


def _study_arguments(p: argparse.ArgumentParser) -> None:
    _scene_arguments(p)
    p.add_argument("--out", metavar="FILE", help="write the variants (inputs, outputs, status) "
                   "as a .csv or .parquet file")
    p.add_argument("--plots", metavar="DIR", help="write a histogram PNG of every output into "
                   "DIR (created if needed)")
    p.add_argument("--tornado", action="store_true", help="also run the one-at-a-time design "
                   "(each input at its low and high value: the grid's ends, or the "
                   "distribution's 5th and 95th percentiles) and print (and with --plots draw) "
                   "the tornado of the first impact's delta-V")
    p.add_argument("--backend", choices=("local", "dask"), default="local",
                   help="where the variants run: this machine (local) or a Dask cluster")
    p.add_argument("--scheduler", metavar="ADDR", help="with --backend dask: the address of a "
                   "running scheduler (tcp://host:8786); default a LocalCluster on this machine")
    p.add_argument("--threads", type=_positive_int, help="threads (local) or worker processes "
                   "of the LocalCluster (dask); default all cores")
    p.add_argument("--max-impacts", type=_positive_int, default=2,
                   help="impacts reported per variant as columns (2)")


def _positive_int(text: str) -> int:
    try:
        value = int(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"{text!r} is not a whole number") from None
    if value < 1:
        raise argparse.ArgumentTypeError(f"{text!r} must be >= 1")
    return value


def _seed(text: str) -> int:
    try:
        value = int(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"{text!r} is not a whole number") from None
    if value < 0:
        raise argparse.ArgumentTypeError(f"{text!r} must be >= 0")
    return value


# -- the parser ----------------------------------------------------------------------------


class _Parser(argparse.ArgumentParser):
    """argparse with a one-line error message (``crashsim: error: ...``, exit 2) that takes
    an option's value even when it starts with "-" (``--dt -1ms``): argparse would read
    "-1ms" as an unknown option and say "expected one argument"."""

    def add_argument(self, *args: Any, **kwargs: Any) -> argparse.Action:
        action = super().add_argument(*args, **kwargs)
        if not hasattr(self, "_crashsim_options"):  # add_argument runs inside __init__ (-h)
            self._crashsim_options: set[str] = set()
            self._crashsim_value_options: set[str] = set()
        self._crashsim_options.update(action.option_strings)
        if action.option_strings and kwargs.get("action", "store") == "store":
            self._crashsim_value_options.update(action.option_strings)  # takes one value
        return action

    def parse_known_args(  # type: ignore[override]
        self, args: Sequence[str] | None = None, namespace: argparse.Namespace | None = None
    ) -> tuple[argparse.Namespace, list[str]]:
        argv = list(sys.argv[1:] if args is None else args)
        return super().parse_known_args(self._join_values(argv), namespace)

    def _join_values(self, argv: list[str]) -> list[str]:
        """``--opt -x`` -> ``--opt=-x`` for this parser's one-value options when "-x" is not
        one of its options (subcommands' parsers do the same for their own arguments)."""
        options = getattr(self, "_crashsim_options", set())
        values = getattr(self, "_crashsim_value_options", set())
        out: list[str] = []
        i = 0
        while i < len(argv):
            word = argv[i]
            if word == "--":
                out += argv[i:]
                break
            following = argv[i + 1] if i + 1 < len(argv) else None
            if (
                word in values
                and following is not None
                and following.startswith("-")
                and following != "--"
                and following.split("=", 1)[0] not in options
            ):
                out.append(f"{word}={following}")
                i += 2
                continue
            out.append(word)
            i += 1
        return out

    def error(self, message: str) -> NoReturn:
        self.exit(EXIT_INPUT, f"crashsim: error: {message} (see {self.prog} --help)\n")


def _scene_arguments(p: argparse.ArgumentParser) -> None:
    p.add_argument("scene", type=Path, help="the scene file (TOML, docs/scene-format.md)")
    p.add_argument(
        "--dt",
        type=_step,
        help='largest time step ("2 ms" or seconds), overriding the file\'s run.dt',
    )
    p.add_argument(
        "--duration",
        type=_duration,
        help='simulated time ("0.5 s" or seconds), overriding the file\'s run.duration (or '
        "its run.max_duration when it runs until rest)",
    )
    p.add_argument(
        "--record-interval",
        type=_record_interval,
        help='keep a sample of the states every so often ("10 ms" or seconds), overriding the '
        "file's run.record_interval (default: every step, or about 100,000 samples in all for "
        "longer runs; first overlaps and exchanges are always kept)",
    )
    p.add_argument(
        "--progress",
        action="store_true",
        help="show the progress bar and a line per output written on stderr even when it is "
        "not a terminal",
    )


def _parser() -> argparse.ArgumentParser:
    parser = _Parser(
        prog="crashsim",
        description="Open 3-D vehicle collision engine (depth of penetration, Kudlich-Slibar "
        "impulse). SI units inside.",
        epilog="Exit codes: 0 success, 1 the run or check failed, 2 bad input, 130 interrupted. "
        "Every error is one line on stderr starting 'crashsim: error:'.",
    )
    parser.add_argument("--version", action="version", version=f"crashsim {__version__}")
    sub = parser.add_subparsers(dest="command", required=True, metavar="command")
    run = sub.add_parser(
        "run",
        help="run a scene file; print the summary; write the report, CSV, pictures, GLB",
        description="Runs a scene file (docs/scene-format.md) and prints the summary table. "
        f"Writes into the output folder: {REPORT_FILE} (the full report), {CSV_FILE} (time "
        f"histories, SI, one row per sample), {TRAJECTORIES_FILE} (the run from above), "
        "impact-N.png (top-down picture of each exchange) "
        f"and {GLB_FILE} (the 3-D motion). Folder: --out, else the file's output.dir, else "
        "<scene name>-out in the current folder.",
        epilog="Exit codes: 0 success, 1 the run failed (or writing its outputs did), 2 bad "
        "input (also an output folder that cannot be created or written), 130 interrupted.",
    )
    _scene_arguments(run)
    run.add_argument("--out", metavar="DIR", help="output folder (created if needed)")
    run.add_argument(
        "--no-pictures",
        action="store_true",
        help="write neither the PNG pictures nor the GLB motion (faster)",
    )
    run.add_argument(
        "--html",
        nargs="?",
        const=True,
        metavar="PATH",
        help=f"also write the case page (one offline HTML file: 3-D scene, timeline, report): "
        f"{PAGE_FILE} in the output folder, or PATH (docs/viewer.md)",
    )
    run.set_defaults(func=_run)
    view_cmd = sub.add_parser(
        "view",
        help="write the case page (offline HTML) of a report.json written by `run --out`",
        description="Writes the case page of a run (docs/viewer.md) from the report.json "
        "that `crashsim run --out DIR` wrote and the files beside it: time-histories.csv (the "
        "motion) and the meshes (the report's own, when written with meshes, else motion.glb). "
        "An existing page is replaced only when it was written from a report too (or with "
        "--force).",
        epilog="Exit codes: 0 success, 1 writing the page failed, 2 bad input (a missing or "
        "malformed report or file beside it, an unwritable --out, a page there that was not "
        "written from a report).",
    )
    view_cmd.add_argument("report", type=Path, help="the report.json of a run")
    view_cmd.add_argument(
        "--out",
        metavar="PATH",
        help=f"the page to write (default: {PAGE_FILE} beside the report)",
    )
    view_cmd.add_argument(
        "--force",
        action="store_true",
        help="replace the page even when it is not one written from a report (e.g. the richer "
        "page of `run --html`: tyre marks, zones, rest outlines)",
    )
    view_cmd.set_defaults(func=_view)
    check = sub.add_parser(
        "check",
        help="run a scene file and cross-check its first overlaps with python-fcl",
        description="Runs a scene file and compares the engine's first overlaps with the "
        "independent python-fcl check; prints the comparison.",
        epilog="Exit codes: 0 they agree, 1 they disagree (or the check is unavailable), "
        "2 bad input, 130 interrupted.",
    )
    _scene_arguments(check)
    check.set_defaults(func=_check)
    demo = sub.add_parser(
        "demo",
        help="run the built-in intersection case to rest; print it; write pictures and page",
        description="Two generated cars at an intersection on dry asphalt: red (a sedan, 60 "
        "km/h) into the left side of blue (an SUV crossing at 30 km/h), which then strikes a "
        "lamp post; both run on their tyres to rest. Prints each impact's delta-V, PDOF, "
        "energy and EES and each car's rest, and writes into the output folder the report "
        f"({REPORT_FILE}), the time histories, the pictures ({TRAJECTORIES_FILE}, "
        f"impact-N.png), the 3-D motion ({GLB_FILE}) and the case page ({PAGE_FILE}). "
        "--impact-only runs the seed's first worked example instead (two box cars, 30 mph, no "
        "ground) and prints its first exchange (writes nothing).",
        epilog="Exit codes: 0 success, 1 no exchange within the run (or writing failed), 2 bad "
        "input (also an output folder that cannot be created or written), 130 interrupted.",
    )
    demo.add_argument("--out", metavar="DIR",
                      help=f"output folder (default {DEMO_OUT} in the current folder)")  # fmt: skip
    demo.add_argument("--speed", type=_demo_speed, help='red\'s speed: mph, or with its unit '
                      '("50 km/h"); default 60 km/h, with --impact-only 30 mph')  # fmt: skip
    demo.add_argument("--impact-only", action="store_true", help="the seed's first worked "
                      "example: two box cars, no ground, its first exchange printed")  # fmt: skip
    demo.add_argument("--dt", type=_step, help='largest time step ("1 ms" or seconds; 1 ms)')
    demo.add_argument("--duration", type=_duration, help='simulated time ("0.5 s" or seconds): '
                      f"the longest run to rest ({DEMO_MAX_DURATION:g} s), with --impact-only "
                      "the run (0.5 s)")  # fmt: skip
    demo.add_argument("--no-pictures", action="store_true",
                      help="write neither the PNG pictures nor the GLB (faster)")  # fmt: skip
    demo.add_argument("--json", action="store_true", help="print the run's result as JSON "
                      "(Result.to_dict) instead of the summary")  # fmt: skip
    demo.set_defaults(func=_demo)
    sw = sub.add_parser(
        "sweep",
        help="run a grid of variants of a scene file (docs/studies.md)",
        description="Runs the full factorial of the --vary values (and the file's [study] "
        'table when its kind = "sweep") and prints the percentiles of every output.',
        epilog="VALUES: start:stop:count (\"10:20:5 mph\"), a list (\"0,0.1,0.2\") or one "
        "value; a unit after the last value applies to all; plain numbers are SI. Exit codes: "
        "0 success (some variants may have failed: listed), 1 every variant failed, 2 bad "
        "input, 130 interrupted (what finished is written).",
    )
    _study_arguments(sw)
    sw.add_argument("--vary", action="append", metavar="PATH=VALUES",
                    help="a parameter path and its values, e.g. red.speed=10:20:5 (repeat)")
    sw.set_defaults(func=_sweep)
    mcs = sub.add_parser(
        "montecarlo",
        help="run a Monte Carlo study of a scene file (docs/studies.md)",
        description="Draws n variants from the --dist distributions (and the file's [study] "
        'table when its kind = "montecarlo") and prints the percentiles of every output.',
        epilog="DIST: uniform(lo, hi), normal(mean, sd), normal(mean, sd, lo, hi), "
        "triangular(lo, mode, hi), class(sedan[, figure]); each number with its unit or one "
        "unit after the parenthesis. Exit codes as for sweep.",
    )
    _study_arguments(mcs)
    mcs.add_argument("--dist", action="append", metavar="PATH=DIST",
                     help='e.g. "red.speed=normal(15 m/s, 1 m/s)" (repeat)')
    mcs.add_argument("-n", type=_positive_int, help="number of variants")
    mcs.add_argument("--seed", type=_seed, help="random seed, >= 0 (default: the file's, else "
                     "fresh entropy)")
    mcs.set_defaults(func=_montecarlo)
    fit_cmd = sub.add_parser(
        "fit",
        help="fit a scene file's unknowns to its evidence ([fit], [[evidence]]; docs/fitting.md)",
        description="Fits the unknowns of the file's [fit] table (and --unknown) to its "
        "[[evidence]] sections by least squares (or a global search first) and prints the best "
        "values with their 95 % ranges and every item's residual, in the file's units, and the "
        "verdict: fits, poor fit (chi^2 too large for its degrees of freedom, an unknown at a "
        "bound: the ranges widened or withheld, a warning) or does not fit. Writes "
        f"into the output folder: {FIT_JSON} (verdict, values, residuals, ranges, objective, "
        "interrupted), "
        f"{FIT_PICTURE} (the fitted run over the evidence, the objective along each unknown) "
        f"and {FITTED_REPORT} (the report of the fitted run). Folder: --out, else the file's "
        "output.dir, else <scene name>-fit in the current folder. The runs take the file's "
        "[run] (--dt and --duration override it).",
        epilog="Exit codes: 0 success (the fit fits, or fits poorly: a warning), 1 the fit does "
        "not fit (the reasons on stderr), the fitted run failed or writing the outputs did, 2 "
        "bad input (the file, --unknown, --start, an unwritable --out), 130 interrupted (the "
        "best so far is printed and written).",
    )
    fit_cmd.add_argument("scene", type=Path, help="the scene file (TOML) with [fit] and "
                         "[[evidence]]")
    fit_cmd.add_argument("--method", choices=("least_squares", "global"),
                         help="the solver, overriding the file's fit.method (least_squares)")
    fit_cmd.add_argument("--unknown", action="append", metavar="PATH=LO,HI",
                         help='an unknown and its bounds, e.g. "red.speed=20,50 mph", adding to '
                         "or replacing the file's (repeat)")
    fit_cmd.add_argument("--start", action="append", metavar="PATH=VALUE",
                         help='where the least-squares solve starts, e.g. "red.speed=40 mph" '
                         "(repeat; default the file's fit.start, else the scene's value)")
    fit_cmd.add_argument("--seed", type=_seed, help="with --method global: the random seed")
    fit_cmd.add_argument("--threads", type=_positive_int, help="threads (default all cores)")
    fit_cmd.add_argument("--out", metavar="DIR", help="output folder (created if needed)")
    fit_cmd.add_argument("--dt", type=_step, help='largest time step ("2 ms" or seconds), '
                         "overriding the file's run.dt")
    fit_cmd.add_argument("--duration", type=_duration, help='simulated time ("0.5 s" or '
                         "seconds), overriding the file's run.duration (or run.max_duration "
                         "until rest)")
    fit_cmd.add_argument("--no-scan", action="store_true", help="skip the scan of the "
                         "objective along each unknown (faster; no scan ranges)")
    fit_cmd.add_argument("--no-pictures", action="store_true", help=f"do not write {FIT_PICTURE}")
    fit_cmd.add_argument("--progress", action="store_true", help="show the progress line on "
                         "stderr even when it is not a terminal")
    fit_cmd.set_defaults(func=_fit)
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


def _show_warning(
    message: Warning | str,
    category: type[Warning],
    filename: str,
    lineno: int,
    file: Any = None,
    line: str | None = None,
) -> None:
    print(f"crashsim: warning: {' '.join(str(message).split())}", file=sys.stderr)


def main(argv: Sequence[str] | None = None) -> int:
    """Entry point of the ``crashsim`` command; returns the exit code (0 success, 1 the run
    or check failed, 2 bad input, 130 interrupted). Bad arguments exit 2 through SystemExit,
    as argparse does."""
    args = _parser().parse_args(argv)
    func: Callable[[argparse.Namespace], int] = args.func
    try:
        with warnings.catch_warnings():
            warnings.simplefilter("default")  # every warning once, as one line on stderr
            warnings.showwarning = _show_warning
            code = int(func(args))
        sys.stdout.flush()  # here, so a closed pipe is caught below
        return code
    except KeyboardInterrupt:
        print("crashsim: interrupted", file=sys.stderr)
        return EXIT_INTERRUPTED
    except (SimulationError, RunFailed) as e:
        print(f"crashsim: error: {' '.join(str(e).split())}", file=sys.stderr)
        return EXIT_FAILED
    except CrashsimError as e:  # the input is at fault
        print(f"crashsim: error: {' '.join(str(e).split())}", file=sys.stderr)
        return EXIT_INPUT
    except BrokenPipeError:  # stdout's reader stopped (crashsim run ... | head)
        os.dup2(os.open(os.devnull, os.O_WRONLY), sys.stdout.fileno())  # no error at exit
        return EXIT_FAILED
    except OSError as e:  # writing an output failed (disk full, permissions, ...)
        print(f"crashsim: error: {' '.join(str(e).split())}", file=sys.stderr)
        return EXIT_FAILED


def console_main() -> NoReturn:
    """The ``crashsim`` executable: :func:`main`, then the exit. After Ctrl-C it exits at once
    (the streams flushed, the interpreter's teardown skipped: it took about 0.5 s with the
    scientific libraries loaded, and the README promises a stop within 0.5 s)."""
    code = main()
    if code == EXIT_INTERRUPTED:
        sys.stdout.flush()
        sys.stderr.flush()
        os._exit(code)
    sys.exit(code)


if __name__ == "__main__":
    console_main()
