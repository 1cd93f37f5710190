#!/usr/bin/env python3
"""Regenerate the reference vehicle bodies meshes/<preset>.ply and meshes/README.md.

    python3 scripts/make_meshes.py           # write the files
    python3 scripts/make_meshes.py --check   # compare with the files, exit 1 on a difference

Each body is crashsim.vehicles.generator.generate_body(body_params(preset, **default_dims(preset)))
at the default resolution, written as binary little-endian PLY (float64 vertices, int32
indices) by crashsim.vehicles.generator.ply_bytes, bit for bit the same on every run
(tests/test_generator.py regenerates them and compares the bytes).
"""

from __future__ import annotations

import argparse
import hashlib
import sys
from pathlib import Path

from crashsim.vehicles.generator import (
    PRESETS,
    SHAPE_PARAMETERS,
    body_params,
    default_dims,
    generate_body,
    ply_bytes,
)

REPO = Path(__file__).resolve().parents[1]
MESHES = REPO / "meshes"
COMMAND = "python3 scripts/make_meshes.py"


def build(preset: str) -> bytes:
    """The reference body of a preset as PLY bytes (its parameters in the header comments)."""
    p = body_params(preset, **default_dims(preset))
    comments = {"generator": "crashsim.vehicles.generator (scripts/make_meshes.py)", **p.as_dict()}
    return ply_bytes(generate_body(p), comments)


def readme(files: dict[str, bytes]) -> str:
    """meshes/README.md: how the bodies are made, their parameters and sha256."""
    params = {pr: body_params(pr, **default_dims(pr)) for pr in PRESETS}
    lines = [
        "# Generated vehicle bodies",
        "",
        "Our own meshes, made by `crashsim.vehicles.generator` (no third-party data): one closed,",
        "watertight, single-shell body per preset, in the model frame (m; x forward, y left,",
        "z up; ground at z = 0; bounding box centred in x and y, from ground_clearance to the",
        "roof height in z). Binary little-endian PLY, float64 vertices; the parameters are",
        "repeated in each file's header comments.",
        "",
        f"Made by `{COMMAND}` (check with `{COMMAND} --check`), which calls",
        "`generate_body(body_params(preset, **default_dims(preset)))` at the default",
        "resolution. The dimensions are those of each preset's vehicle class in the built-in",
        "table (`crashsim.vehicles.vehicle_data`, sources in `docs/vehicle-data.md`); the shape",
        "parameters are the presets' defaults.",
        "`tests/test_generator.py` regenerates every file and compares the bytes.",
        "The picture `docs/img/bodies.png` of these bodies is drawn by",
        "`python3 scripts/draw_bodies.py`.",
        "",
        "| file | triangles | vertices | sha256 |",
        "|---|---|---|---|",
    ]
    for preset in PRESETS:
        data = files[preset]
        mesh = generate_body(params[preset])
        lines.append(
            f"| {preset}.ply | {len(mesh.faces)} | {len(mesh.vertices)} | "
            f"`{hashlib.sha256(data).hexdigest()}` |"
        )
    lines += ["", "## Parameters (m)", ""]
    names = ["length", "width", "height", "wheelbase", *SHAPE_PARAMETERS]
    lines.append("| parameter | " + " | ".join(PRESETS) + " |")
    lines.append("|---|" + "---|" * len(PRESETS))
    for name in names:
        row = " | ".join(f"{getattr(params[pr], name):.4g}" for pr in PRESETS)
        lines.append(f"| {name} | {row} |")
    lines.append("")
    return "\n".join(lines)


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--check", action="store_true", help="compare, do not write")
    args = parser.parse_args(argv)
    files = {preset: build(preset) for preset in PRESETS}
    outputs = {MESHES / f"{preset}.ply": data for preset, data in files.items()}
    outputs[MESHES / "README.md"] = readme(files).encode("utf-8")
    if args.check:
        stale = [p for p, data in outputs.items() if not p.is_file() or p.read_bytes() != data]
        for path in stale:
            print(f"differs: {path.relative_to(REPO)}")
        print("up to date" if not stale else f"{len(stale)} file(s) differ: run {COMMAND}")
        return 1 if stale else 0
    MESHES.mkdir(exist_ok=True)
    for path, data in outputs.items():
        path.write_bytes(data)
        print(f"wrote {path.relative_to(REPO)} ({len(data)} bytes)")
    return 0


if __name__ == "__main__":
    sys.exit(main())
