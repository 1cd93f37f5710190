"""The commands on one scene file: ``crashsim run``, ``crashsim view`` (of a run's
report.json) and ``crashsim check`` (the first overlaps against python-fcl)."""

from __future__ import annotations

import argparse
import sys
from pathlib import Path

from crashsim.analysis.crosscheck import cross_check
from crashsim.analysis.report import build_report
from crashsim.cli.common import EXIT_FAILED, _check_writable, _header, _make, _simulate
from crashsim.cli.output import _write_run
from crashsim.errors import ParameterError
from crashsim.io.scenefile import SceneFile, load_scene
from crashsim.io.viewer import PAGE_FILE, view_report


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
