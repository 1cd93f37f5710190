"""The case viewer: one self-contained, offline HTML page per run, with the 3-D scene (meshes,
ground, obstacles, friction zones, tyre marks, rest positions; orbit, pan, zoom, top and side
views), a timeline (play, pause, a slider over the run, markers at first overlaps and
exchanges; at an exchange the overlap region, centroid, normal, impulse and delta-V arrows)
and the report beside it (the per-impact tables of ``crashsim.report(result).to_dict()``,
speed-time plots, the scene's inputs with units). docs/viewer.md describes the page.

    import crashsim as cs
    cs.view(result, "case.html")                     # from a run
    cs.io.viewer.view_report("out/report.json")      # from `crashsim run --out out/`

Data flow: Result -> report -> page data (:mod:`.data`) -> page (:mod:`.page`); nothing
imports this package but the command line and the package's top level. The page embeds
three.js r111 (MIT, static/three/), its own scripts (static/viewer.js, people.js, report.js)
and the data.
"""

from __future__ import annotations

import os
from pathlib import Path
from typing import TYPE_CHECKING

from crashsim.errors import ParameterError
from crashsim.io.viewer.data import DEFAULT_MAX_SAMPLES, page_data
from crashsim.io.viewer.files import ReportFileError, check_report_path, report_page_data
from crashsim.io.viewer.meshes import DEFAULT_MAX_TRIANGLES
from crashsim.io.viewer.page import check_output_path, page_source, write_page

if TYPE_CHECKING:
    from crashsim.result import Result

__all__ = [
    "DEFAULT_MAX_SAMPLES",
    "DEFAULT_MAX_TRIANGLES",
    "PAGE_FILE",
    "ReportFileError",
    "view",
    "view_report",
]

PAGE_FILE = "case.html"  # the page's name beside a run's other outputs


def view(
    result: Result,
    path: str | os.PathLike[str] = PAGE_FILE,
    *,
    title: str | None = None,
    max_triangles: int = DEFAULT_MAX_TRIANGLES,
    max_samples: int = DEFAULT_MAX_SAMPLES,
) -> Path:
    """Writes the case page of a run (a Result that keeps its scene) to ``path``; returns
    the path. ``max_triangles``: triangles drawn per body (a larger mesh is decimated for
    display); ``max_samples``: samples kept per body (a longer run keeps every k-th and
    every event sample). SceneError for a result without a scene, ParameterError for a path
    that cannot be written (checked first) or a bad limit."""
    out = check_output_path(path)
    return write_page(
        page_data(result, title=title, max_triangles=max_triangles, max_samples=max_samples),
        out,
    )


def view_report(
    report: str | os.PathLike[str],
    path: str | os.PathLike[str] | None = None,
    *,
    force: bool = False,
    max_triangles: int = DEFAULT_MAX_TRIANGLES,
    max_samples: int = DEFAULT_MAX_SAMPLES,
) -> Path:
    """Writes the case page of a report.json written by ``crashsim run --out`` (the files
    beside it give the motion and the meshes; see :mod:`.files`) to ``path`` (default:
    case.html beside the report); returns the path. ReportFileError (an InputError) when
    the report or the files it needs are missing or malformed.

    It replaces an existing file only when that is a page written from a report too (nothing
    is lost), or with ``force``: a page written from the run (``crashsim run --html``,
    ``cs.view``) has what a report cannot give (tyre marks, friction zones, rest outlines,
    the overlap points), and any other file is not ours; ParameterError, before any work."""
    src = Path(report)
    check_report_path(src)  # first: a missing report is the mistake to name
    out = check_output_path(src.parent / PAGE_FILE if path is None else path)
    if out.exists() and not force and page_source(out) != "report":
        what = (
            "a case page written from the run (crashsim run --html), with the tyre marks, "
            "zones, rest outlines and overlap points a report cannot give"
            if page_source(out) == "run"
            else "not a case page written from a report"
        )
        raise ParameterError(
            f"{out} exists and is {what}: give another --out, or --force to replace it"
        )
    data = report_page_data(src, max_triangles=max_triangles, max_samples=max_samples)
    return write_page(data, out)
