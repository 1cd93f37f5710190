"""``crashsim fit``: the fit of a scene file's [fit] and [[evidence]] with the command
line's changes, its output folder, what it prints and writes."""

from __future__ import annotations

import argparse
import json
import sys
from pathlib import Path
from typing import Any

from crashsim.analysis.report import build_report
from crashsim.cli.common import RunFailed, _check_writable, _header, _make
from crashsim.errors import ParameterError
from crashsim.io.scenefile import SceneFile, load_scene

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
