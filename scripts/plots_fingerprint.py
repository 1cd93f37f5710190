"""The pictures of a set of example runs, written to a folder, so that a refactoring of
crashsim.plots can be shown not to change them:

    python3 scripts/plots_fingerprint.py /tmp/before     # on the old code
    python3 scripts/plots_fingerprint.py /tmp/after      # on the new code
    diff -r /tmp/before /tmp/after                       # empty: nothing changed

Each example (examples/NAME.toml; the default set runs in seconds and needs no ../shared
mesh; give names after the folder to choose others) is run with its file's run settings, as
``crashsim run`` does, and gives: NAME-impact-K.png (``plot_impact`` of impact K, each one),
NAME-run.png (``plot_trajectories``), NAME-run-3.png (``plot_trajectories`` with three
outlines), and NAME.txt: every text of those figures (titles, captions, legends, labels) and
each vehicle's outline at the end of the run (``silhouette``, WKT, 9 decimals).
"""

from __future__ import annotations

import sys
import time
from pathlib import Path

from crashsim.io.scenefile import load_scene
from crashsim.plots import plot_impact, plot_trajectories, silhouette

ROOT = Path(__file__).resolve().parent.parent

# impacts (vehicle-vehicle, obstacle, secondary), three vehicles, a towed car, run-out on a
# ground with wheels, tyre marks and obstacles, a pedestrian
CASES = (
    "seed-90deg",
    "seed-45deg",
    "three-vehicles",
    "generated-offset-frontal",
    "towed-car",
    "runout-sedan-into-pole",
    "runout-small-overlap-barrier",
    "pedestrian-sedan-40kmh",
)


def _texts(fig) -> list[str]:  # type: ignore[no-untyped-def]
    from matplotlib.text import Text

    return [t.get_text() for t in fig.findobj(Text) if t.get_text()]


def main(out: Path, names: tuple[str, ...]) -> None:
    out.mkdir(parents=True, exist_ok=True)
    for name in names:
        start = time.perf_counter()
        result = load_scene(ROOT / "examples" / f"{name}.toml").simulate()
        lines: list[str] = []
        for k in range(len(result.impacts)):
            fig = plot_impact(result, out / f"{name}-impact-{k}.png", k)
            lines += [f"== impact {k}", *_texts(fig)]
        fig = plot_trajectories(result, out / f"{name}-run.png")
        lines += ["== run", *_texts(fig)]
        fig = plot_trajectories(result, out / f"{name}-run-3.png", count=3)
        lines += ["== run, count 3", *_texts(fig)]
        t_end = float(result.t[-1])
        for v in result.vehicles:
            position, rotation = result.pose(v, t_end)
            outline = silhouette(result.vehicle(v), position, rotation)
            lines += [f"== outline {v}", _wkt(outline)]
        (out / f"{name}.txt").write_text("\n".join(lines) + "\n", encoding="utf-8")
        print(f"{name}: {len(result.impacts)} impact(s), {time.perf_counter() - start:.1f} s")


def _wkt(geom) -> str:  # type: ignore[no-untyped-def]
    import shapely

    return shapely.to_wkt(geom, rounding_precision=9)


if __name__ == "__main__":
    if len(sys.argv) < 2:
        sys.exit("usage: plots_fingerprint.py OUTPUT_FOLDER [EXAMPLE_NAME ...]")
    main(Path(sys.argv[1]), tuple(sys.argv[2:]) or CASES)
