"""crashsim against the reference program's run of issue 19 that has published numbers: PC-Crash's
15 mph steering-wheel ramp of a 2004 Chevrolet Malibu, whose CG path and steering-wheel input
are plotted (with their data) in pycrash's validation notebook (repository joe-cormier/pycrash,
projects/validation - single vehicle motion/notebooks/Validation - Single Vehicle - PC Crash
Simulations.ipynb, commit 979f90f28d3c63553dde3ff9bda1a54162d8d06a, trace "validate" of the
figure "Vehicle Motion in Global Reference Frame"; the input at commit
fc50afe2c6b8f5fd11a439293f91202620a4699c, figure "Driver Inputs for Veh1"). Those data are not
in this repository: give the folder with the two CSV files read from them,
``15mph_steer_cg_path_DxDy.csv`` (t_s, Dx_ft, Dy_ft) and ``15mph_steer_driver_input_steer.csv``
(t_s, steer_deg), comment lines starting with '#'.

The car is built from the published data only (examples/reference-sedan-steer-15mph.toml: the
same numbers) and driven by the exported steering-wheel angle; friction 0.76 as the runs. The
script prints the CG path's largest distance from PC-Crash's over the 0.1 s samples, its time,
and the course angle's offset once the ramp has ended.

    python3 benches/pccrash_reference.py --data /path/to/pccrash
"""

from __future__ import annotations

import argparse
import math
from pathlib import Path

import crashsim as cs
import numpy as np
from crashsim.io.scenefile import load_scene

REPO = Path(__file__).resolve().parents[1]
FT = 0.3048


def read(path: Path) -> dict[str, np.ndarray]:
    lines = [ln for ln in path.read_text(encoding="utf-8").splitlines() if not ln.startswith("#")]
    names = lines[0].split(",")
    rows = np.array([[float(v) for v in ln.split(",")] for ln in lines[1:] if ln.strip()])
    return {n: rows[:, k] for k, n in enumerate(names)}


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--data", type=Path, required=True, help="the folder of the two CSV files")
    args = parser.parse_args()
    path = read(args.data / "15mph_steer_cg_path_DxDy.csv")
    steer = read(args.data / "15mph_steer_driver_input_steer.csv")
    case = load_scene(REPO / "examples" / "reference-sedan-steer-15mph.toml")
    scene = case.scene
    # the exported steering-wheel angle, sample for sample (the example has its ramp)
    table = np.c_[steer["t_s"], np.radians(steer["steer_deg"])]
    inputs = cs.DriverInputs(steering_wheel=table)
    (vehicle,) = scene.vehicles
    fresh = cs.Scene(ground=scene.ground)
    fresh.add(vehicle, (0.0, 0.0), velocity=(cs.mph(15.0), 0.0, 0.0), inputs=inputs)
    result = fresh.run(case.run.longest, dt=case.run.dt)
    tr = result.trajectory("sedan")
    t = path["t_s"]
    x = np.interp(t, result.t, tr.position[:, 0])
    y = np.interp(t, result.t, tr.position[:, 1])
    rx, ry = path["Dx_ft"] * FT, path["Dy_ft"] * FT
    miss = np.hypot(x - rx, y - ry)
    k = int(np.argmax(miss))

    def course(px: np.ndarray, py: np.ndarray) -> np.ndarray:
        return np.degrees(np.unwrap(np.arctan2(np.gradient(py, t), np.gradient(px, t))))

    after = t >= 3.0
    offset = course(x, y)[after] - course(rx, ry)[after]
    at = ", ".join(f"{miss[np.searchsorted(t, s)]:.2f}" for s in (2, 4, 6, 8, 10))
    print(
        f"CG path: largest distance from PC-Crash's {miss.max():.2f} m at {t[k]:.1f} s "
        f"(at 2, 4, 6, 8, 10 s: {at} m)"
    )
    print(
        f"course after the ramp: {np.median(offset):+.2f} deg from PC-Crash's "
        f"(range {offset.min():+.2f} .. {offset.max():+.2f})"
    )
    speed = np.hypot(np.gradient(rx, t), np.gradient(ry, t))
    ours = np.interp(t, result.t, np.linalg.norm(tr.velocity[:, :2], axis=1))
    print(f"speed: largest difference {np.abs(ours - speed)[1:-1].max():.3f} m/s")
    steer = ", ".join(f"{math.degrees(a):.2f}" for a in result.wheel_steer("sedan")[:2, -1])
    print(f"steered wheels at the end: {steer} deg")


if __name__ == "__main__":
    main()
