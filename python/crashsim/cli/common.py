"""What every command of ``crashsim`` shares: the exit codes, the failure that is no
error of the input, the progress bar, a scene file's run and header, the output folder's
checks."""

from __future__ import annotations

import argparse
import sys
import tempfile
from pathlib import Path
from typing import IO

from crashsim.errors import InputError, ParameterError
from crashsim.io.scenefile import SceneFile
from crashsim.result import Result

EXIT_FAILED = 1  # the run or the check failed
EXIT_INPUT = 2  # bad input: a malformed scene file, bad arguments
EXIT_INTERRUPTED = 130  # Ctrl-C (128 + SIGINT), as shells report it


class RunFailed(Exception):
    """The run finished but did not do what the command is for (exit 1)."""


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
