"""What the scene-file reader makes of every example and of the scene texts in the scene-file
tests, written to a folder, so that a refactoring of crashsim.io can be shown not to change it:

    python3 scripts/scenefile_fingerprint.py /tmp/before     # on the old code
    python3 scripts/scenefile_fingerprint.py /tmp/after      # on the new code
    diff -r /tmp/before /tmp/after                           # empty: nothing changed

For each examples/*.toml, and each string constant in tests/test_scenefile*.py that holds a
whole scene (it has ``format_version``), one file: the engine's scene
(``scene.to_spec(...).to_json()``, with the file's run settings), the run and output settings,
title, description, study and fit; or the error's type and message when it does not load.
"""

from __future__ import annotations

import ast
import hashlib
import sys
from pathlib import Path

from crashsim.io.scenefile import SceneFile, load_scene, loads_scene

ROOT = Path(__file__).resolve().parent.parent


def fingerprint(load: object) -> str:
    """The text of what ``load()`` (a SceneFile's loader) gives, or of the error it raises."""
    try:
        case = load()  # type: ignore[operator]
        assert isinstance(case, SceneFile)
        run = case.run
        if run.until == "rest":
            spec = case.scene.to_spec(
                dt=run.dt,
                until="rest",
                max_duration=run.longest,
                record_interval=run.record_interval,
            )
        else:
            spec = case.scene.to_spec(run.duration, run.dt, record_interval=run.record_interval)
        return "\n".join(
            (
                f"run: {run!r}",
                f"output: {case.output!r}",
                f"title: {case.title!r}",
                f"description: {case.description!r}",
                f"study: {case.study!r}",
                f"fit: {case.fit!r}",
                spec.to_json(),
                "",
            )
        )
    except Exception as e:  # noqa: BLE001 - the error is the fingerprint
        return f"{type(e).__module__}.{type(e).__qualname__}: {e}\n"


def scene_texts(test_file: Path) -> list[str]:
    """The string constants of a test file that hold a whole scene (with format_version)."""
    tree = ast.parse(test_file.read_text(encoding="utf-8"))
    return [
        node.value
        for node in ast.walk(tree)
        if isinstance(node, ast.Constant)
        and isinstance(node.value, str)
        and "format_version" in node.value
    ]


def main(out: Path) -> None:
    out.mkdir(parents=True, exist_ok=True)
    n = 0
    for path in sorted((ROOT / "examples").glob("*.toml")):
        (out / f"example-{path.stem}.txt").write_text(fingerprint(lambda p=path: load_scene(p)))
        n += 1
    for test_file in sorted((ROOT / "tests").glob("test_scenefile*.py")):
        for text in scene_texts(test_file):
            digest = hashlib.sha256(text.encode()).hexdigest()[:16]
            name = f"{test_file.stem}-{digest}.txt"
            base = test_file.parent
            (out / name).write_text(
                fingerprint(lambda t=text, b=base: loads_scene(t, base_dir=b, source="<text>"))
            )
            n += 1
    print(f"{n} fingerprints in {out}")


if __name__ == "__main__":
    if len(sys.argv) != 2:
        sys.exit("usage: scenefile_fingerprint.py OUTPUT_FOLDER")
    main(Path(sys.argv[1]))
