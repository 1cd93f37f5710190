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
three.js r111 (MIT, static/three/), its own script (static/viewer.js) and the data.
"""

from __future__ import annotations

import os
from pathlib import Path
from typing import TYPE_CHECKING

from crashsim.io.viewer.data import DEFAULT_MAX_SAMPLES, page_data
from crashsim.io.viewer.files import ReportFileError, check_report_path, report_page_data
from crashsim.io.viewer.meshes import DEFAULT_MAX_TRIANGLES
from crashsim.io.viewer.page import check_output_path, write_page

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
    max_triangles: int = DEFAULT_MAX_TRIANGLES,
    max_samples: int = DEFAULT_MAX_SAMPLES,
) -> Path:
    """Writes the case page of a report.json written by ``crashsim run --out`` (the files
    beside it give the motion and the meshes; see :mod:`.files`) to ``path`` (default:
    case.html beside the report); returns the path. ReportFileError (an InputError) when
    the report or the files it needs are missing or malformed."""
    src = Path(report)
    check_report_path(src)  # first: a missing report is the mistake to name
    out = check_output_path(src.parent / PAGE_FILE if path is None else path)
    data = report_page_data(src, max_triangles=max_triangles, max_samples=max_samples)
    return write_page(data, out)
