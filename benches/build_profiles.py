"""The release profile's cost in build time against its speed (issue 23, item 4): the extension
built from scratch under each profile, then the same run-time figures with each build.

    python3 benches/build_profiles.py                      # every profile: about 20 min
    python3 benches/build_profiles.py --only current,thin16

Each profile overrides `[profile.release]` through cargo's environment variables
(CARGO_PROFILE_RELEASE_LTO, _CODEGEN_UNITS, _OPT_LEVEL) and builds `crashsim-py` in its own
fresh target folder under /tmp (`cargo build --release -p crashsim-py`, what maturin builds;
the dependencies included, as on a fresh machine): wall time and CPU time of the build (all
of cargo's processes). Then a copy of python/crashsim with that build's extension runs, in a
subprocess and interleaved with the other builds' copies:

- "box batch": the seed's box scene (examples/seed-90deg.toml, 1 s at 1 ms), 2,000 variants
  of red's speed and offset (benches/batch_throughput.py's) on one thread: ms per variant;
- "20k run to rest": the two 20k sedans of benches/compare_peers.py run to rest
  (`Scene.run(until="rest")`): ms per run.

Each figure is the median of the repeats; the machine is shared, so run it when nothing else
does. Results: benches/README.md ("The release profile").
"""

from __future__ import annotations

import argparse
import json
import os
import resource
import shutil
import statistics
import subprocess
import sys
import time
from pathlib import Path

HERE = Path(__file__).resolve().parent
REPO = HERE.parent

# name: (lto, codegen-units, opt-level)
PROFILES = {
    "current": ("thin", "4", "3"),
    "thin16": ("thin", "16", "3"),
    "nolto16": ("off", "16", "3"),
    "fat1": ("fat", "1", "3"),
    "thin4-O2": ("thin", "4", "2"),
}

WORKLOAD = r"""
import json, statistics, sys, time
sys.path.insert(0, sys.argv[1])
import numpy as np
import batch_throughput as bt
import compare_peers as cp
from crashsim.batch import run_batch

out = {}
box = bt.box_scene()
overrides = bt.box_overrides(2000)
run_batch(box, overrides, duration=1.0, dt=1e-3, threads=1)
times = []
for _ in range(int(sys.argv[2])):
    t0 = time.perf_counter()
    run_batch(box, overrides, duration=1.0, dt=1e-3, threads=1)
    times.append(time.perf_counter() - t0)
out["box batch"] = statistics.median(times) / 2000 * 1e3
setup = cp.make_runout_scene(cp.make_body("20k"))
setup.scene.run(dt=1e-3, until="rest", max_duration=cp.RUNOUT_MAX_DURATION)
times = []
for _ in range(int(sys.argv[2])):
    t0 = time.perf_counter()
    setup.scene.run(dt=1e-3, until="rest", max_duration=cp.RUNOUT_MAX_DURATION)
    times.append(time.perf_counter() - t0)
out["20k run to rest"] = statistics.median(times) * 1e3
print(json.dumps(out))
"""


def build(name: str, lto: str, units: str, opt: str) -> tuple[Path, float, float]:
    """Builds the extension under a profile in a fresh target folder: (the library, wall s,
    CPU s)."""
    target = Path(f"/tmp/crashsim-build-{name}")
    shutil.rmtree(target, ignore_errors=True)
    env = dict(os.environ, CARGO_TARGET_DIR=str(target),
               CARGO_PROFILE_RELEASE_LTO=lto, CARGO_PROFILE_RELEASE_CODEGEN_UNITS=units,
               CARGO_PROFILE_RELEASE_OPT_LEVEL=opt)  # fmt: skip
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    t0 = time.perf_counter()
    subprocess.run(["cargo", "build", "--release", "-q", "-p", "crashsim-py"], cwd=REPO,
                   env=env, check=True)  # fmt: skip
    wall = time.perf_counter() - t0
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    cpu = (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)
    return target / "release" / "lib_core.so", wall, cpu


def package_with(lib: Path, name: str) -> Path:
    """A copy of python/crashsim whose extension is ``lib``; returns the folder to import
    from."""
    root = Path(f"/tmp/crashsim-pkg-{name}")
    shutil.rmtree(root, ignore_errors=True)
    shutil.copytree(REPO / "python" / "crashsim", root / "crashsim",
                    ignore=shutil.ignore_patterns("_core*.so", "__pycache__"))  # fmt: skip
    shutil.copy2(lib, root / "crashsim" / "_core.abi3.so")
    return root


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--only", default=",".join(PROFILES), help="comma-separated profiles")
    ap.add_argument("--repeats", type=int, default=5, help="runs per figure and build")
    ap.add_argument("--rounds", type=int, default=3, help="interleaved rounds over the builds")
    a = ap.parse_args()
    names = a.only.split(",")
    print("the release profile: benches/build_profiles.py")
    print(f"machine: {os.cpu_count()} cores; load at start {os.getloadavg()}")
    builds = {}
    for name in names:
        lto, units, opt = PROFILES[name]
        lib, wall, cpu = build(name, lto, units, opt)
        builds[name] = (package_with(lib, name), wall, cpu, lib.stat().st_size)
        print(f"  built {name}: lto {lto}, codegen-units {units}, opt-level {opt}: "
              f"{wall:.0f} s wall, {cpu:.0f} s CPU", flush=True)  # fmt: skip
    figures: dict[str, dict[str, list[float]]] = {name: {} for name in names}
    for _ in range(a.rounds):
        for name in names:
            root = builds[name][0]
            env = dict(os.environ, PYTHONPATH=f"{root}{os.pathsep}{HERE}")
            done = subprocess.run([sys.executable, "-c", WORKLOAD, str(HERE), str(a.repeats)],
                                  env=env, check=True, capture_output=True, text=True)  # fmt: skip
            for key, value in json.loads(done.stdout.splitlines()[-1]).items():
                figures[name].setdefault(key, []).append(value)
    print(f"\nload at end {os.getloadavg()}; figures: median of {a.rounds} rounds of "
          f"{a.repeats} runs (the median of each round)")  # fmt: skip
    print("| profile | build wall (s) | build CPU (s) | library (MB) | box batch (ms/variant) "
          "| 20k run to rest (ms) |")  # fmt: skip
    print("|---|---|---|---|---|---|")
    for name in names:
        _, wall, cpu, size = builds[name]
        lto, units, opt = PROFILES[name]
        f = {k: statistics.median(v) for k, v in figures[name].items()}
        box, rest = f["box batch"], f["20k run to rest"]
        print(f"| {name} (lto {lto}, cgu {units}, O{opt}) | {wall:.0f} | {cpu:.0f} | "
              f"{size / 1e6:.1f} | {box:.4f} | {rest:.1f} |")  # fmt: skip
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
