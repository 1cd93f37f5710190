"""The case viewer's screenshots in docs/viewer.md (docs/img/viewer_*.png): four examples'
pages written by crashsim.io.viewer and photographed in headless chromium (Debian's chromium
and chromium-driver) at 1400 x 900 px, each at a moment of the run and from a set view (the
camera brought to a person for the cyclist's).

    python3 scripts/viewer_pictures.py            # from the repository; needs ../shared/meshes
    python3 scripts/viewer_pictures.py viewer_cyclist_side   # only the pictures named
"""

from __future__ import annotations

import sys
import tempfile
import time
from pathlib import Path
from typing import Any

from crashsim.io.scenefile import load_scene
from crashsim.io.viewer import view
from selenium import webdriver
from selenium.webdriver.chrome.service import Service

REPO = Path(__file__).resolve().parents[1]
IMG = REPO / "docs" / "img"

# picture name -> (example, view, time: (exchange N, offset s), a time in s, or None: the end;
# then optionally (a person or body, m of the scene around it in view) to bring the camera to)
SHOTS: dict[str, tuple[Any, ...]] = {
    "viewer_seed_90deg": ("seed-90deg.toml", "3d", (1, 0.004)),
    "viewer_sedan_into_pickup": ("mesh-sedan-into-pickup.toml", "3d", (1, 0.004)),
    "viewer_three_vehicles_top": ("three-vehicles.toml", "top", (2, 0.002)),
    "viewer_three_vehicles_end": ("three-vehicles.toml", "3d", None),
    "viewer_cyclist_side": ("cyclist-sedan-side-40kmh.toml", "3d", 0.19, ("cyclist", 2.5)),
}


def main() -> None:
    options = webdriver.ChromeOptions()
    options.binary_location = "/usr/bin/chromium"
    for arg in (
        "--headless=new",
        "--no-sandbox",
        "--disable-dev-shm-usage",
        "--use-angle=swiftshader",
        "--enable-unsafe-swiftshader",
        "--window-size=1400,900",
        "--hide-scrollbars",
    ):
        options.add_argument(arg)
    d = webdriver.Chrome(service=Service("/usr/bin/chromedriver"), options=options)
    results = {}
    try:
        with tempfile.TemporaryDirectory() as tmp:
            for name, (example, kind, when, *focus) in SHOTS.items():
                if sys.argv[1:] and name not in sys.argv[1:]:
                    continue
                if example not in results:
                    case = load_scene(REPO / "examples" / example)
                    result = case.simulate(duration=case.run.duration, dt=case.run.dt)
                    page = view(result, Path(tmp) / f"{Path(example).stem}.html", title=case.title)
                    results[example] = (result, page)
                result, page = results[example]
                d.get(page.as_uri())
                while not d.execute_script("return crashsim.ready"):
                    if d.execute_script("return crashsim.error"):
                        sys.exit(d.execute_script("return crashsim.error"))
                    time.sleep(0.05)
                if when is None:
                    t = float(result.t[-1])
                elif isinstance(when, float):
                    t = when
                else:
                    number, offset = when
                    t = result.impacts[number - 1].time + offset
                d.execute_script(
                    "crashsim.setView(arguments[0]); crashsim.setTime(arguments[1])", kind, t
                )
                if focus:
                    d.execute_script("crashsim.focus(arguments[0], arguments[1])", *focus[0])
                time.sleep(0.2)
                out = IMG / f"{name}.png"
                d.save_screenshot(str(out))
                print(f"{out.relative_to(REPO)}: {example} at t = {t:.4f} s, {kind} view")
    finally:
        d.quit()


if __name__ == "__main__":
    main()
