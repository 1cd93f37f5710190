"""The machine a benchmark ran on, as one line (CPU model, cores, Python and library versions),
for the benchmark scripts in this folder (run as ``python3 benches/<script>.py``)."""

from __future__ import annotations

import os
import platform
from pathlib import Path

import crashsim
import numpy as np
import trimesh


def describe() -> str:
    cpu = platform.processor() or platform.machine()
    try:
        for line in Path("/proc/cpuinfo").read_text().splitlines():
            if line.startswith("model name"):
                cpu = line.split(":", 1)[1].strip()
                break
    except OSError:
        pass
    return (
        f"{cpu}, {os.cpu_count()} cores, Python {platform.python_version()}, "
        f"numpy {np.__version__}, trimesh {trimesh.__version__}, crashsim {crashsim.__version__}"
    )
