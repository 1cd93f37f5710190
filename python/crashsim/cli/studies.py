"""``crashsim sweep`` and ``crashsim montecarlo``: the study of a scene file's [study] with
the command line's --vary / --dist, its table file, what it prints and draws."""

from __future__ import annotations

import argparse
import sys
from pathlib import Path
from typing import Any

import numpy as np

from crashsim.cli.common import RunFailed, _check_writable, _header
from crashsim.errors import ParameterError
from crashsim.io.scenefile import SceneFile, load_scene
from crashsim.studies.backends import get_backend


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
    if args.scheduler is not None and not get_backend(args.backend).takes_scheduler:
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
