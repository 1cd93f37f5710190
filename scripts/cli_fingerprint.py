"""What the ``crashsim`` command prints, returns and writes for a set of short invocations,
written to a folder, so that a refactoring of crashsim.cli can be shown not to change it:

    python3 scripts/cli_fingerprint.py /tmp/before     # on the old code
    python3 scripts/cli_fingerprint.py /tmp/after      # on the new code
    diff -r /tmp/before /tmp/after                     # empty: nothing changed

Every command runs in this process (``crashsim.cli.main``), in a fresh empty working folder
(a temporary one), on the examples the tests use: run (with --html and --no-pictures), view,
check, demo (to rest without pictures, --impact-only, --json), sweep, montecarlo (with
--tornado), fit (--no-scan, --no-pictures), dtp-montecarlo, ``--help`` of every command and
--version, and bad input (exit 2). Each gives CASE.txt: the arguments, the exit code (or
SystemExit's), stdout, stderr and the SHA-256 of every file the command wrote (by path within
its working folder). Normalised: the repository's path becomes <repo> and the working
folder's becomes <work> (both appear in the scene paths and the "wrote:" lines), and a fit's
wall-clock time becomes <t> (its "N runs, 1.5 s" line and fit.json's "elapsed" value, hashed
after that replacement); nothing else (the outputs hold no other times, no dates). The last
line printed is a digest of the whole folder.
"""

from __future__ import annotations

import contextlib
import hashlib
import io
import os
import re
import sys
import tempfile
import time
from pathlib import Path

from crashsim.cli import main

os.environ["COLUMNS"] = "100"  # argparse wraps --help to the terminal's width

ROOT = Path(__file__).resolve().parent.parent
EX = ROOT / "examples"
SEED = str(EX / "seed-90deg.toml")
STUDY = str(EX / "seed-90deg-study.toml")
FIT = str(EX / "fit-skid.toml")

# name -> argv; "{work}" is the case's working folder (files made there first: see PREPARE)
CASES: dict[str, list[str]] = {
    "help": ["--help"],
    "version": ["--version"],
    **{
        f"help-{c}": [c, "--help"]
        for c in ("run", "view", "check", "demo", "sweep", "montecarlo", "fit", "dtp-montecarlo")
    },
    "run-seed": ["run", SEED, "--out", "o", "--html"],
    "run-seed-default-out": ["run", SEED, "--no-pictures"],
    "run-45deg": ["run", str(EX / "seed-45deg.toml"), "--out", "o", "--dt", "2 ms"],
    "run-pole": [
        "run",
        str(EX / "runout-sedan-into-pole.toml"),
        "--out",
        "o",
        "--no-pictures",
        "--record-interval",
        "10 ms",
    ],
    "run-html-path": ["run", SEED, "--out", "o", "--no-pictures", "--html", "page.html"],
    "view": ["view", "o/report.json"],
    "view-force": ["view", "o/report.json", "--out", "o/case.html", "--force"],
    "check-seed": ["check", SEED],
    "check-fit": ["check", FIT],
    "demo-impact": ["demo", "--impact-only"],
    "demo-impact-json": ["demo", "--impact-only", "--json", "--speed", "25"],
    "demo-no-exchange": ["demo", "--impact-only", "--duration", "10 ms"],
    "demo-rest": ["demo", "--out", "d", "--no-pictures", "--speed", "50 km/h"],
    "sweep": [
        "sweep",
        SEED,
        "--vary",
        "red.speed=20:40:3 mph",
        "--vary",
        "restitution=0,0.1",
        "--out",
        "s.csv",
        "--plots",
        "p",
        "--threads",
        "1",
    ],
    "sweep-tornado": [
        "sweep",
        SEED,
        "--vary",
        "red.speed=20,30 mph",
        "--tornado",
        "--threads",
        "1",
    ],
    "sweep-file": ["sweep", STUDY, "--vary", "red.speed=20,30 mph", "--threads", "1"],
    "montecarlo": [
        "montecarlo",
        STUDY,
        "-n",
        "6",
        "--seed",
        "3",
        "--out",
        "m.csv",
        "--threads",
        "1",
        "--tornado",
    ],
    "montecarlo-dist": [
        "montecarlo",
        SEED,
        "-n",
        "4",
        "--seed",
        "1",
        "--dist",
        "red.speed=normal(15 m/s, 1 m/s)",
        "--threads",
        "1",
    ],
    "sweep-all-fail": ["sweep", SEED, "--vary", "red.position_x=-2,-1.5", "--threads", "1"],
    "fit": ["fit", FIT, "--out", "f", "--no-scan", "--no-pictures", "--threads", "1"],
    "fit-unknown-start": [
        "fit",
        FIT,
        "--out",
        "f",
        "--no-scan",
        "--no-pictures",
        "--unknown",
        "red.speed=40,80 km/h",
        "--start",
        "red.speed=55 km/h",
        "--threads",
        "1",
    ],
    "dtp": ["dtp-montecarlo", "--samples", "2000", "--seed", "4"],
    "dtp-json": ["dtp-montecarlo", "--samples", "2000", "--json", "--plot", "h.png"],
    # bad input
    "bad-command": ["frobnicate"],
    "bad-dt": ["run", SEED, "--dt", "3 mph"],
    "bad-duration": ["run", SEED, "--duration", "-1"],
    "bad-dt-missing": ["run", SEED, "--dt", "--progress"],
    "bad-no-scene": ["run"],
    "bad-missing-file": ["check", "missing.toml"],
    "bad-scene": ["run", "bad.toml"],
    "bad-out-file": ["run", SEED, "--out", "taken"],
    "bad-html": ["run", SEED, "--html", "x.txt"],
    "bad-view": ["view", "nothing.json"],
    "bad-demo-speed": ["demo", "--speed", "3 kg"],
    "bad-demo-speed-negative": ["demo", "--speed", "-5"],
    "bad-sweep-nothing": ["sweep", SEED],
    "bad-sweep-out": ["sweep", SEED, "--vary", "red.speed=20,30 mph", "--out", "s.txt"],
    "bad-montecarlo-n": ["montecarlo", SEED, "--dist", "red.speed=normal(15, 1)"],
    "bad-montecarlo-scheduler": ["montecarlo", STUDY, "-n", "4", "--scheduler", "tcp://x:1"],
    "bad-fit-nothing": ["fit", SEED],
    "bad-fit-unknown": ["fit", FIT, "--unknown", "red.speed=90,30 km/h"],
    "bad-fit-start": ["fit", FIT, "--start", "red.speed=200 km/h"],
    "bad-fit-seed": ["fit", FIT, "--seed", "3"],
    "bad-fit-method": ["fit", FIT, "--method", "newton"],
    "bad-dtp-plot": ["dtp-montecarlo", "--samples", "10", "--plot", "no/h.png"],
}

# files a case's working folder holds before it runs
PREPARE = {
    "view": "run-45deg",
    "view-force": "run-seed",
}


def _prepare(name: str, work: Path) -> None:
    if name in PREPARE:
        _call(CASES[PREPARE[name]])
    if name == "bad-scene":
        (work / "bad.toml").write_text("format_version = 1\nmass = 3\n", encoding="utf-8")
    if name == "bad-out-file":
        (work / "taken").write_text("", encoding="utf-8")


def _call(argv: list[str]) -> tuple[str, str, str]:
    out, err = io.StringIO(), io.StringIO()
    with contextlib.redirect_stdout(out), contextlib.redirect_stderr(err):
        try:
            code = f"exit {main(argv)}"
        except SystemExit as e:
            code = f"SystemExit {e.code}"
    return code, out.getvalue(), err.getvalue()


def _files(work: Path) -> dict[str, str]:
    return {str(p.relative_to(work)): hashlib.sha256(_bytes(p)).hexdigest()
            for p in sorted(work.rglob("*")) if p.is_file()}  # fmt: skip


def _bytes(path: Path) -> bytes:
    """The file's bytes, a fit's wall-clock time replaced (fit.json's "elapsed")."""
    data = path.read_bytes()
    if path.name == "fit.json":
        data = re.sub(rb'"elapsed": [0-9.e+-]+', b'"elapsed": "<t>"', data)
    return data


def run_case(name: str, scratch: Path) -> str:
    work = scratch / name
    work.mkdir()
    cwd = os.getcwd()
    os.chdir(work)
    try:
        _prepare(name, work)
        before = _files(work)
        code, out, err = _call(CASES[name])
        written = {k: v for k, v in _files(work).items() if before.get(k) != v}
    finally:
        os.chdir(cwd)
    text = "\n".join([
        "argv: " + " ".join(CASES[name]), code, "== stdout", out, "== stderr", err,
        "== files", *(f"{k} {v}" for k, v in written.items()), "",
    ])  # fmt: skip
    text = re.sub(r"( runs?), [0-9.]+ s\b", r"\1, <t> s", text)  # a fit's wall-clock time
    return text.replace(str(work), "<work>").replace(str(ROOT), "<repo>")


def main_(out: Path, names: list[str]) -> None:
    out.mkdir(parents=True, exist_ok=True)
    with tempfile.TemporaryDirectory() as scratch:
        for name in names:
            start = time.perf_counter()
            text = run_case(name, Path(scratch))
            (out / f"{name}.txt").write_text(text, encoding="utf-8")
            print(f"{name}: {text.splitlines()[1]}, {time.perf_counter() - start:.1f} s")
    digest = hashlib.sha256()
    for p in sorted(out.glob("*.txt")):
        digest.update(p.name.encode() + b"\0" + p.read_bytes() + b"\0")
    print(f"digest of {len(names)} cases: {digest.hexdigest()[:16]}")


if __name__ == "__main__":
    if len(sys.argv) < 2:
        sys.exit("usage: cli_fingerprint.py OUTPUT_FOLDER [CASE ...]")
    main_(Path(sys.argv[1]), sys.argv[2:] or list(CASES))
