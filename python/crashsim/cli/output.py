"""The files a run writes: report.json, the time histories and the impacts (CSV), the pictures
(PNG), the 3-D motion (GLB) and the case page (HTML)."""

from __future__ import annotations

import csv
import time
from collections.abc import Callable
from pathlib import Path
from typing import IO

import numpy as np

from crashsim.analysis.report import Report
from crashsim.analysis.report_json import impact_table
from crashsim.io.export import export_glb
from crashsim.io.viewer import view
from crashsim.plots import plot_impact, plot_trajectories
from crashsim.result import Result

REPORT_FILE = "report.json"
CSV_FILE = "time-histories.csv"
IMPACTS_FILE = "impacts.csv"
GLB_FILE = "motion.glb"
TRAJECTORIES_FILE = "trajectories.png"


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


def write_impacts_csv(report: Report, path: str | Path) -> list[str]:
    """Write the impacts: one row per impulse exchange, one column per number or word of the
    report's record of it, named by its JSON path (analysis.report_json.impact_table; units
    as docs/report.md gives them); numbers to 15 significant digits, None empty. Returns the
    header."""
    header, rows = impact_table(report.to_dict())
    with open(path, "w", newline="", encoding="utf-8") as f:
        writer = csv.writer(f)
        writer.writerow(header)
        for row in rows:
            writer.writerow(["" if v is None else f"{v:.15g}" if isinstance(v, float) else v
                             for v in row])  # fmt: skip
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
        if report.impacts:
            written += writing(
                IMPACTS_FILE,
                lambda: one(out / IMPACTS_FILE, lambda p: write_impacts_csv(report, p)),
            )
    if pictures:
        written += writing("the pictures", lambda: _pictures(result, out))
    if glb:
        written += writing(GLB_FILE, lambda: _glb(result, out))
    if html is not None:
        page = html
        written += writing(page.name, lambda: [view(result, page, title=title)])
    return written


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
