"""The pictures of docs/studies.md: a histogram, the tornado and the Sobol indices of the
seed's first worked example as a Monte Carlo study (examples/seed-90deg-study.toml).

    python3 scripts/study_pictures.py        # writes docs/img/study-*.png (about 10 s)
"""

from __future__ import annotations

from pathlib import Path

import crashsim as cs
from crashsim.io.scenefile import load_scene
from crashsim.studies.plots import plot_histogram

ROOT = Path(__file__).resolve().parent.parent
IMG = ROOT / "docs" / "img"


def main() -> None:
    case = load_scene(ROOT / "examples" / "seed-90deg-study.toml")
    spec = case.study
    run = {"duration": case.run.duration, "dt": case.run.dt, "progress": False}
    study = cs.monte_carlo(case.scene, spec.distributions, spec.n, spec.seed, **run)
    plot_histogram(study, "impact1.blue.delta_v", IMG / "study-histogram.png")
    t = cs.tornado(case.scene, spec.distributions, **run)
    t.plot(IMG / "study-tornado.png", "impact1.blue.delta_v")
    s = cs.sobol(case.scene, spec.distributions, 256, seed=1, **run)
    s.plot(IMG / "study-sobol.png", "impact1.blue.delta_v")
    print(s.of("impact1.blue.delta_v"))
    for name in ("study-histogram.png", "study-tornado.png", "study-sobol.png"):
        print("wrote", IMG / name)


if __name__ == "__main__":
    main()
