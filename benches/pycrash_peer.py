"""What compare_peers.py and compare_pycrash.py share to run pycrash beside crashsim: where
pycrash runs (this process when it imports here, else a worker subprocess in the venv of
``--pycrash-python``), the worker's environment, versions and the repository's revision.

This module imports only the standard library: the worker runs it in pycrash's venv, where
crashsim and trimesh may not be installed. pycrash (GPL) is imported only inside the
comparison scripts' workers, never by crashsim.
"""

from __future__ import annotations

import contextlib
import io
import json
import platform
import shutil
import subprocess
import sys
import warnings
from importlib import metadata
from pathlib import Path
from typing import Any

#: The pycrash release the comparisons were written against.
PYCRASH_VERSION = "0.0.18"
#: Where the comparisons look for an interpreter with pycrash when it does not import here.
DEFAULT_PYCRASH_PYTHON = "/tmp/pycrash-venv/bin/python"
SET_UP = (
    f"python3 -m venv /tmp/pycrash-venv && /tmp/pycrash-venv/bin/pip install "
    f"pycrash=={PYCRASH_VERSION}"
)


def dist_version(dist: str) -> str:
    """The installed version of distribution ``dist``, or "not installed"."""
    try:
        return metadata.version(dist)
    except metadata.PackageNotFoundError:
        return "not installed"


def git_revision() -> str:
    """``git describe --always --dirty`` of this repository ("" when git cannot say)."""
    repo = Path(__file__).resolve().parent.parent
    try:
        return subprocess.run(
            ["git", "-C", str(repo), "describe", "--always", "--dirty"],
            capture_output=True,
            text=True,
            check=False,
        ).stdout.strip()
    except OSError:
        return ""


def pycrash_imports() -> bool:
    """Whether pycrash imports in this process (its import prints and warns: silenced)."""
    try:
        with contextlib.redirect_stdout(io.StringIO()), warnings.catch_warnings():
            warnings.simplefilter("ignore")
            import pycrash  # noqa: F401 - GPL: only ever imported here and in the workers
    except ImportError:
        return False
    return True


def worker_environment(pycrash: Any, pandas: Any, numpy: Any) -> dict[str, str]:
    """The worker's versions and interpreter, for the comparisons' headers."""
    return {
        "pycrash": dist_version("pycrash"),
        "pandas": pandas.__version__,
        "numpy": numpy.__version__,
        "python": platform.python_version(),
        "executable": sys.executable,
        "module": getattr(pycrash, "__file__", ""),
    }


def run_worker(script: str | Path, spec: dict[str, Any], python: str | None,
               tail: int = 5) -> tuple[dict[str, Any], str]:
    """Runs ``script --pycrash-worker`` under ``python`` (default DEFAULT_PYCRASH_PYTHON)
    with ``spec`` as JSON on its stdin: (its JSON output, where it ran). RuntimeError, with
    how to set pycrash up or the last ``tail`` lines of the worker's stderr, when it cannot."""
    exe = python or DEFAULT_PYCRASH_PYTHON
    if not (Path(exe).exists() or shutil.which(exe)):
        raise RuntimeError(
            f"pycrash is not importable here and there is no interpreter at {exe}; set up: "
            f"{SET_UP}"
        )
    proc = subprocess.run(
        [exe, str(Path(script).resolve()), "--pycrash-worker"],
        input=json.dumps(spec),
        capture_output=True,
        text=True,
        check=False,
    )
    if proc.returncode != 0:
        lines = "\n".join(proc.stderr.strip().splitlines()[-tail:])
        raise RuntimeError(f"the pycrash worker failed in {exe} (exit {proc.returncode}):\n{lines}")
    return json.loads(proc.stdout), f"subprocess {exe}"
