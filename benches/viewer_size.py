"""Page size and time to first draw of the case viewer (crashsim.io.viewer) for the 20k and
200k pairs, in headless chromium (Debian's chromium and chromium-driver, WebGL on the CPU by
SwiftShader: a machine with a GPU draws faster).

The pairs are the benchmarks' (benches/compare_peers.py): two generated sedans, resolution 1.0
subdivided once (21,440 triangles each) and resolution 3.5 subdivided once (195,200), in the
seed's 90 deg side impact (30 mph, 0.3 s, dt 1 ms). Each page is written with the default
display budget (DEFAULT_MAX_TRIANGLES per body: the 200k mesh is decimated) and with no
budget (every triangle drawn), then opened ``--repeats`` times; the table gives medians.

"first draw": ``crashsim.firstDrawMs``, the page's own performance.now() when its first frame
is rendered, counted from the start of navigation (so it includes reading and parsing the file,
three.js, inflating the arrays and building the meshes). "ready": the same plus the report
panel and the plots (``crashsim.ready``), as seen from selenium.

    python3 benches/viewer_size.py                 # 20k and 200k, 5 loads each; about 2 min
    python3 benches/viewer_size.py --repeats 3 --sizes 20k
"""

from __future__ import annotations

import argparse
import math
import re
import statistics
import sys
import tempfile
import time
from pathlib import Path

import crashsim as cs
import numpy as np
from crashsim.io.viewer import view
from crashsim.io.viewer.meshes import DEFAULT_MAX_TRIANGLES
from crashsim.vehicles.generator import body_params, default_dims, generate_body

sys.path.insert(0, str(Path(__file__).resolve().parent))
from machine import describe  # noqa: E402

SIZES = {"20k": (1.0, 1), "200k": (3.5, 1)}  # generator resolution, subdivide() calls
SPEED = 30.0 * 0.44704
GAP = 0.30  # m between the bullet car's nose and the struck side


def run_pair(label: str) -> cs.Result:
    resolution, subdivisions = SIZES[label]
    mesh = generate_body(body_params("sedan", **default_dims("sedan")), resolution)
    for _ in range(subdivisions):
        mesh = mesh.subdivide()
    v = cs.Vehicle.generate("sedan")

    def vehicle(name: str) -> cs.Vehicle:
        return cs.Vehicle(mesh, v.mass, v.cg, v.inertia, name=name, stiffness=v.stiffness)

    red, blue = vehicle("red"), vehicle("blue")
    length, width = float(mesh.extents[0]), float(mesh.extents[1])
    nose = length / 2.0 - float(v.cg[0])
    h = float(v.cg[2])
    scene = cs.Scene(depth_of_penetration=0.030)
    scene.add(red, (-width / 2.0 - nose - GAP, 0.3, h), heading=0.0, velocity=(SPEED, 0, 0))
    scene.add(blue, (0.0, 0.0, h), heading=math.pi / 2.0)
    return scene.run(duration=0.3, dt=1e-3)


def driver():  # type: ignore[no-untyped-def]
    from selenium import webdriver
    from selenium.webdriver.chrome.service import Service

    options = webdriver.ChromeOptions()
    options.binary_location = "/usr/bin/chromium"
    for arg in (
        "--headless=new",
        "--no-sandbox",
        "--disable-dev-shm-usage",
        "--use-angle=swiftshader",
        "--enable-unsafe-swiftshader",
        "--window-size=1400,900",
    ):
        options.add_argument(arg)
    return webdriver.Chrome(service=Service("/usr/bin/chromedriver"), options=options)


def load(d, path: Path) -> tuple[float, float]:  # type: ignore[no-untyped-def]
    """(first draw ms, ready ms) of one load."""
    d.get("about:blank")
    t0 = time.perf_counter()
    d.get(path.as_uri())
    while True:
        ready, error = d.execute_script("return [crashsim.ready, crashsim.error]")
        if error:
            raise RuntimeError(error)
        if ready:
            break
        time.sleep(0.01)
    ready_ms = (time.perf_counter() - t0) * 1e3
    return float(d.execute_script("return crashsim.firstDrawMs")), ready_ms


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--repeats", type=int, default=5)
    parser.add_argument("--sizes", default="20k,200k")
    args = parser.parse_args()
    print(f"machine: {describe()}")
    rows = []
    d = driver()
    try:
        with tempfile.TemporaryDirectory() as tmp:
            for label in args.sizes.split(","):
                t = time.perf_counter()
                result = run_pair(label)
                source = len(result.vehicle("red").mesh.faces)
                print(f"{label}: run {time.perf_counter() - t:.1f} s, {source:,} triangles each")
                for budget in (DEFAULT_MAX_TRIANGLES, source):
                    path = Path(tmp) / f"{label}-{budget}.html"
                    t = time.perf_counter()
                    view(result, path, max_triangles=budget)
                    write = time.perf_counter() - t
                    times = [load(d, path) for _ in range(args.repeats)]
                    # what the decimation kept (at most the budget)
                    text = path.read_text(encoding="utf-8")
                    m = re.search(r'"triangles_source":\d+,"triangles":(\d+)', text)
                    drawn = int(m.group(1)) if m else -1
                    rows.append(
                        (
                            label,
                            source,
                            drawn,
                            path.stat().st_size / 1e6,
                            write,
                            statistics.median(x[0] for x in times),
                            statistics.median(x[1] for x in times),
                        )
                    )
    finally:
        d.quit()
    print()
    print(
        "| pair | triangles per car | drawn per car | page (MB) | write (s) | first draw "
        "(ms, median) | ready (ms, median) |"
    )
    print("|---|---|---|---|---|---|---|")
    for label, source, drawn, mb, write, first, ready in rows:
        print(
            f"| {label} | {source:,} | {drawn:,} | {mb:.2f} | {write:.2f} | {first:.0f} | "
            f"{ready:.0f} |"
        )
    print(f"\n{args.repeats} loads each; numpy {np.__version__}")


if __name__ == "__main__":
    main()
