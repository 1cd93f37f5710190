"""How fast `crashsim run` stops on Ctrl-C (SIGINT): the time from the signal to the exit
(exit code 130 expected), at random moments of runs of the seed box scene and of the
sedan-into-pickup scene with the shared real meshes (about 20k triangles each), and of the
same with the meshes subdivided (190k and 280k triangles). The README promises 0.5 s.

    python3 benches/interrupt_latency.py [--trials 10]

Prints, per scene, the median and largest latency and the exit codes seen. Wall-clock
figures on a shared machine: read the median.
"""

from __future__ import annotations

import argparse
import os
import random
import signal
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

from machine import describe

REPO = Path(__file__).resolve().parents[1]
SHARED = REPO.parent / "shared" / "meshes"


def scene_files(tmp: Path) -> dict[str, Path]:
    seed = (REPO / "examples" / "seed-90deg.toml").read_text()
    seed = seed.replace('duration = "0.3 s"', 'duration = "1e4 s"')
    pickup = (REPO / "examples" / "mesh-sedan-into-pickup.toml").read_text()
    pickup = pickup.replace("../../shared/meshes", str(SHARED)).replace(
        'duration = "0.5 s"', 'duration = "200 s"'
    )
    out = {"seed boxes, 1e4 s": seed, "sedan into pickup 20k, 200 s": pickup}
    if SHARED.is_dir():
        import trimesh

        for name in ("sedan_quaternius_normalcar1", "pickup_gazebo"):
            mesh = trimesh.load(SHARED / f"{name}.ply", force="mesh", process=False)
            while len(mesh.faces) < 150_000:
                mesh = mesh.subdivide()
            mesh.export(tmp / f"{name}.ply")
        out["sedan into pickup, meshes subdivided to 190k + 280k, 200 s"] = pickup.replace(
            str(SHARED), str(tmp)
        )
    files = {}
    for i, (label, text) in enumerate(out.items()):
        path = tmp / f"scene{i}.toml"
        path.write_text(text)
        files[label] = path
    return files


def one_trial(path: Path, out: Path, delay: float) -> tuple[float, int, str]:
    """Starts the run, waits until its progress bar shows, then `delay` s more, sends SIGINT
    and returns (seconds from the signal to the exit, exit code, the phase it was in)."""
    env = dict(os.environ, PYTHONUNBUFFERED="1")
    proc = subprocess.Popen(
        [sys.executable, "-m", "crashsim", "run", str(path), "--out", str(out), "--progress"],
        stdout=subprocess.DEVNULL,
        stderr=subprocess.PIPE,
        env=env,
        bufsize=0,
        preexec_fn=lambda: signal.signal(signal.SIGINT, signal.SIG_DFL),
    )
    assert proc.stderr is not None
    seen = b""
    while b"%" not in seen:
        byte = proc.stderr.read(1)
        if not byte:
            break
        seen += byte
    time.sleep(delay)
    sent = time.perf_counter()
    proc.send_signal(signal.SIGINT)
    proc.stderr.read()
    code = proc.wait()
    return time.perf_counter() - sent, code, "run" if b"%" in seen else "before the run"


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--trials", type=int, default=10)
    args = parser.parse_args()
    print(describe())
    rng = random.Random(0)
    with tempfile.TemporaryDirectory() as tmp_name:
        tmp = Path(tmp_name)
        for label, path in scene_files(tmp).items():
            latencies, codes = [], set()
            for k in range(args.trials):
                lat, code, _ = one_trial(path, tmp / f"out{k}", rng.uniform(0.0, 3.0))
                latencies.append(lat)
                codes.add(code)
            print(
                f"{label}: median {statistics.median(latencies) * 1e3:.0f} ms, largest "
                f"{max(latencies) * 1e3:.0f} ms over {args.trials} trials; "
                f"exit codes {sorted(codes)}"
            )


if __name__ == "__main__":
    main()
