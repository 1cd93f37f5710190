"""The ``crashsim`` command's argument parser: every command's options, help and the
function that runs it."""

from __future__ import annotations

import argparse
import sys
from collections.abc import Sequence
from pathlib import Path
from typing import Any, NoReturn

from crashsim._core import __version__
from crashsim.cli.argtypes import (
    _demo_speed,
    _duration,
    _positive_int,
    _record_interval,
    _seed,
    _step,
)
from crashsim.cli.builtin import DEMO_MAX_DURATION, DEMO_OUT, _demo, _dtp_montecarlo
from crashsim.cli.common import EXIT_INPUT
from crashsim.cli.fits import FIT_JSON, FIT_PICTURE, FITTED_REPORT, _fit
from crashsim.cli.output import (
    CSV_FILE,
    GLB_FILE,
    IMPACTS_FILE,
    REPORT_FILE,
    TRAJECTORIES_FILE,
)
from crashsim.cli.scenes import _check, _run, _view
from crashsim.cli.studies import _montecarlo, _sweep
from crashsim.io.viewer import PAGE_FILE
from crashsim.studies.backends import backend_names


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
    p.add_argument("--backend", choices=backend_names(), default="local",
                   help="where the variants run: this machine (local), a Dask cluster (dask) "
                   "or a registered backend (crashsim.studies.backends)")
    p.add_argument("--scheduler", metavar="ADDR", help="with --backend dask: the address of a "
                   "running scheduler (tcp://host:8786); default a LocalCluster on this machine")
    p.add_argument("--threads", type=_positive_int, help="threads (local) or worker processes "
                   "of the LocalCluster (dask); default all cores")
    p.add_argument("--max-impacts", type=_positive_int, default=2,
                   help="impacts reported per variant as columns (2)")


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
    _add_run(sub)
    _add_view(sub)
    _add_check(sub)
    _add_demo(sub)
    _add_sweep(sub)
    _add_montecarlo(sub)
    _add_fit(sub)
    _add_dtp_montecarlo(sub)
    return parser


def _add_run(sub: argparse._SubParsersAction[argparse.ArgumentParser]) -> None:
    """`crashsim run`: its help, options and function."""
    run = sub.add_parser(
        "run",
        help="run a scene file; print the summary; write the report, CSV, pictures, GLB",
        description="Runs a scene file (docs/scene-format.md) and prints the summary table. "
        f"Writes into the output folder: {REPORT_FILE} (the full report), {CSV_FILE} (time "
        f"histories, SI, one row per sample), {IMPACTS_FILE} (one row per exchange, the report's "
        f"numbers), {TRAJECTORIES_FILE} (the run from above), "
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


def _add_view(sub: argparse._SubParsersAction[argparse.ArgumentParser]) -> None:
    """`crashsim view`: its help, options and function."""
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


def _add_check(sub: argparse._SubParsersAction[argparse.ArgumentParser]) -> None:
    """`crashsim check`: its help, options and function."""
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


def _add_demo(sub: argparse._SubParsersAction[argparse.ArgumentParser]) -> None:
    """`crashsim demo`: its help, options and function."""
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


def _add_sweep(sub: argparse._SubParsersAction[argparse.ArgumentParser]) -> None:
    """`crashsim sweep`: its help, options and function."""
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


def _add_montecarlo(sub: argparse._SubParsersAction[argparse.ArgumentParser]) -> None:
    """`crashsim montecarlo`: its help, options and function."""
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


def _add_fit(sub: argparse._SubParsersAction[argparse.ArgumentParser]) -> None:
    """`crashsim fit`: its help, options and function."""
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


def _add_dtp_montecarlo(sub: argparse._SubParsersAction[argparse.ArgumentParser]) -> None:
    """`crashsim dtp-montecarlo`: its help, options and function."""
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
