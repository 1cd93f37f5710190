"""The pictures and report excerpts of docs/whole-event.md: the set-up example (a car swerving
and braking on a sloping terrain into a tree at the edge of a grass verge: the page's own
code) and the four examples/runout-*.toml, each run to rest and drawn from above
(docs/img/runout_*.png); the report's run-out sections are printed for the page.

    python3 scripts/whole_event_pictures.py       # from the repository; needs ../shared/meshes
"""

from __future__ import annotations

import contextlib
import io
import tempfile
import warnings
from pathlib import Path
from typing import Any

import crashsim as cs
from crashsim.io.scenefile import load_scene
from crashsim.plots import plot_trajectories

REPO = Path(__file__).resolve().parents[1]
IMG = REPO / "docs" / "img"

EXAMPLES = {
    "runout_sedan_into_suv": "runout-sedan-into-suv.toml",
    "runout_small_overlap": "runout-small-overlap-barrier.toml",
    "runout_pole": "runout-sedan-into-pole.toml",
    "runout_rollover": "runout-rollover-kerb.toml",
}


def setup_example() -> cs.Result:
    """The set-up example of docs/whole-event.md: the page's first python block itself, run in
    a temporary folder (it writes run.png and run.glb); its ``result``."""
    text = (REPO / "docs" / "whole-event.md").read_text(encoding="utf-8")
    code = text.split("```python\n", 1)[1].split("```", 1)[0]
    ns: dict[str, Any] = {}
    with tempfile.TemporaryDirectory() as tmp, contextlib.chdir(tmp):
        with contextlib.redirect_stdout(io.StringIO()):
            exec(code, ns)  # noqa: S102 - the page's own example
    return ns["result"]


def main() -> None:
    warnings.simplefilter("ignore", cs.DepthOfPenetrationWarning)
    runs = {"runout_setup": setup_example()}
    for picture, example in EXAMPLES.items():
        runs[picture] = load_scene(REPO / "examples" / example).simulate()
    for picture, result in runs.items():
        plot_trajectories(result, IMG / f"{picture}.png")
        text = str(cs.report(result))
        print(f"== {picture}\n{text[text.index('Run-out') :]}\n")


if __name__ == "__main__":
    main()
