"""The case viewer's screenshots in docs/viewer.md (docs/img/viewer_*.png): three examples'
pages written by crashsim.io.viewer and photographed in headless chromium (Debian's chromium
and chromium-driver) at 1400 x 900 px, each at a moment of the run and from a set view.

    python3 scripts/viewer_pictures.py            # from the repository; needs ../shared/meshes
"""

from __future__ import annotations

import sys
import tempfile
import time
from pathlib import Path

from crashsim.io.scenefile import load_scene
from crashsim.io.viewer import view
from selenium import webdriver
from selenium.webdriver.chrome.service import Service

REPO = Path(__file__).resolve().parents[1]
IMG = REPO / "docs" / "img"

# picture name -> (example, view, time: "exchange N" + offset s, or a time in s)
SHOTS = {
    "viewer_seed_90deg": ("seed-90deg.toml", "3d", (1, 0.004)),
    "viewer_sedan_into_pickup": ("mesh-sedan-into-pickup.toml", "3d", (1, 0.004)),
    "viewer_three_vehicles_top": ("three-vehicles.toml", "top", (2, 0.002)),
    "viewer_three_vehicles_end": ("three-vehicles.toml", "3d", None),
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
            for name, (example, kind, when) in SHOTS.items():
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
                else:
                    number, offset = when
                    t = result.impacts[number - 1].time + offset
                d.execute_script(
                    "crashsim.setView(arguments[0]); crashsim.setTime(arguments[1])", kind, t
                )
                time.sleep(0.2)
                out = IMG / f"{name}.png"
                d.save_screenshot(str(out))
                print(f"{out.relative_to(REPO)}: {example} at t = {t:.4f} s, {kind} view")
    finally:
        d.quit()


if __name__ == "__main__":
    main()
