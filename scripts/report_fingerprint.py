"""The report of a set of example runs, written to a folder, so that a refactoring of
crashsim.analysis can be shown not to change it:

    python3 scripts/report_fingerprint.py /tmp/before     # on the old code
    python3 scripts/report_fingerprint.py /tmp/after      # on the new code
    diff -r /tmp/before /tmp/after                        # empty: nothing changed

Each example (examples/NAME.toml; the default set runs in seconds and needs no ../shared
mesh; give names after the folder to choose others) is run with its file's run settings, as
``crashsim run`` does, and gives two files: NAME.json (``report.to_json()``) and NAME.txt
(``report.summary_table()``).
"""

from __future__ import annotations

import sys
import time
from pathlib import Path

from crashsim.analysis.report import build_report
from crashsim.io.scenefile import load_scene

ROOT = Path(__file__).resolve().parent.parent

# impacts (vehicle-vehicle, obstacle, secondary), run-out on a ground, wheels, joints,
# pedestrians, no impact at all
CASES = (
    "seed-90deg",
    "seed-45deg",
    "three-vehicles",
    "generated-offset-frontal",
    "towed-car",
    "runout-sedan-into-pole",
    "runout-small-overlap-barrier",
    "tractor-semitrailer-jackknife",
    "manoeuvre-step-steer",
    "pedestrian-sedan-40kmh",
    "manoeuvre-fishhook",
    "manoeuvre-lane-change",
    "reference-sedan-steer-15mph",
    "fit-skid",
    "seed-90deg-study",
)


def main(out: Path, names: tuple[str, ...]) -> None:
    out.mkdir(parents=True, exist_ok=True)
    for name in names:
        start = time.perf_counter()
        case = load_scene(ROOT / "examples" / f"{name}.toml")
        report = build_report(case.simulate())  # the file's duration, dt and record interval
        (out / f"{name}.json").write_text(report.to_json(), encoding="utf-8")
        (out / f"{name}.txt").write_text(report.summary_table(), encoding="utf-8")
        print(f"{name}: {len(report.impacts)} impact(s), {time.perf_counter() - start:.1f} s")


if __name__ == "__main__":
    if len(sys.argv) < 2:
        sys.exit("usage: report_fingerprint.py OUTPUT_FOLDER [EXAMPLE_NAME ...]")
    main(Path(sys.argv[1]), tuple(sys.argv[2:]) or CASES)
