"""The binding's stub (python/crashsim/_core.pyi) is checked against the built module with
mypy's stubtest: every name, signature and class the extension exports must match."""

from __future__ import annotations

import subprocess
import sys


def test_the_stub_matches_the_built_extension() -> None:
    # --ignore-disjoint-bases: PEP 800 markers are not needed for a private module's stub.
    run = subprocess.run(
        [sys.executable, "-m", "mypy.stubtest", "crashsim._core", "--ignore-disjoint-bases"],
        capture_output=True,
        text=True,
        timeout=600,
    )
    assert run.returncode == 0, run.stdout + run.stderr
