"""Re-mint the regression suite's golden values (README.md beside this file).

    python3 tests/regression/mint.py                  # every case with a golden check
    python3 tests/regression/mint.py --only NAME ...  # just these cases (expected/NAME.json)
    python3 tests/regression/mint.py --dry-run        # print the differences, write nothing
    python3 tests/regression/mint.py --only NAME --add-golden   # give a case a golden check
    python3 tests/regression/mint.py --reset-tolerances         # GOLDEN_TOLERANCES everywhere
    python3 tests/regression/mint.py --sensitivity [N]  # golden tolerances vs last-bit noise

For each case it runs the scene, replaces the figures of its golden check (``"golden": true``)
with the run's, and prints every figure that changed (old -> new), flagging those that moved by
more than their tolerance (the ones the suite was failing on). A scene file in scenes/ that no
case runs gets a new expected file with a golden check. The tolerances already in a golden
check are kept (--reset-tolerances resets those without a "tolerances_why"); a new one gets
regression_suite.GOLDEN_TOLERANCES.
Other checks (published figures, closed forms, mirror images) are never touched: they are
written by hand.

Re-mint only after a change to the engine that is meant to move the answers, and say in the
commit which figures moved and why (README.md: what each figure's change means).
"""

from __future__ import annotations

import argparse
import sys
import tomllib
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))

import numpy as np  # noqa: E402
import regression_suite as suite  # noqa: E402

GOLDEN_SOURCE = "golden values minted by mint.py"


def _new_case(scene: str) -> dict[str, object]:
    title = tomllib.loads((suite.SCENES / scene).read_text(encoding="utf-8")).get("title", "")
    return {
        "scene": scene,
        "description": f"{title}. Golden values (mint.py).".lstrip(". "),
        "checks": [],
    }


def _unused_scenes() -> list[str]:
    """Scene files no expected file runs (directly or as a mirror image)."""
    used = set()
    for name in suite.case_names():
        case = suite.load_case(name)
        used.add(case["scene"])
        used.update(c["scene"] for c in case["checks"] if c["kind"] == "mirror")
    return sorted(p.name for p in suite.SCENES.glob("*.toml") if p.name not in used)


def mint(name: str, case: dict, dry_run: bool, reset_tolerances: bool = False) -> bool:
    """Re-mint one case's golden check; True when something changed."""
    scene = suite.SCENES / case["scene"]
    reason = suite.missing_inputs(scene)
    if reason is not None:
        print(f"{name}: skipped: {reason}")
        return False
    golden = [c for c in case["checks"] if c.get("golden")]
    if not golden:
        golden = [{"kind": "values", "golden": True, "source": GOLDEN_SOURCE}]
        case["checks"].append(golden[0])
    check = golden[0]
    run = suite.run_scene(scene)
    old = check.get("expected")
    tolerances = check.get("tolerances")
    if not tolerances or (reset_tolerances and "tolerances_why" not in check):
        tolerances = dict(suite.GOLDEN_TOLERANCES)  # tolerances with a reason are kept
    new = run.figures
    if old is None:
        print(f"{name}: new golden values ({new['exchanges']} exchange(s))")
    else:
        changes = suite.differences(old, new)
        beyond = {f.split(":", 1)[0] for f in suite.compare(old, new, tolerances)}
        if not changes and tolerances == check.get("tolerances"):
            print(f"{name}: unchanged")
            return False
        print(f"{name}: {len(changes)} figure(s) changed, {len(beyond)} beyond tolerance (!)")
        for line in changes:
            print(f"  {'!' if line.split(':', 1)[0] in beyond else ' '} {line}")
    for w in run.warnings:
        print(f"    (engine warning: {w})")
    check.update(
        {
            "kind": "values",
            "golden": True,
            "source": check.get("source", GOLDEN_SOURCE),
            "minted": suite.provenance(),
            "tolerances": tolerances,
            "expected": new,
        }
    )
    if not dry_run:
        suite.write_case(name, case)
    return True


def sensitivity(name: str, case: dict, trials: int, margin: float) -> bool:
    """Run a golden case ``trials`` times with its inputs moved by up to 4 units in their last
    place and print how close the figures came to their golden tolerance: the worst ratio of
    difference to allowed difference. True when it stays below 1/margin."""
    scene = suite.SCENES / case["scene"]
    reason = suite.missing_inputs(scene)
    golden = [c for c in case["checks"] if c.get("golden")]
    if reason is not None or not golden:
        print(f"{name}: skipped: {reason or 'no golden check'}")
        return True
    base = suite.run_scene(scene).figures
    rng = np.random.default_rng(sum(map(ord, name)))  # seeded per case: repeatable
    worst: dict[str, tuple[float, str]] = {}
    for _ in range(trials):
        run = suite.perturbed_run(scene, rng)
        for path, ratio, message in suite.deviations(base, run.figures, golden[0]["tolerances"]):
            if ratio > worst.get(path, (0.0, ""))[0]:
                worst[path] = (ratio, message)
    top = sorted(worst.items(), key=lambda kv: -kv[1][0])
    ratio = top[0][1][0] if top else 0.0
    ok = ratio <= 1.0 / margin
    where = f" ({top[0][0]})" if top else ""
    print(f"{name}: worst figure at {ratio:.2g} of its tolerance{where} in {trials} runs")
    if not ok:
        for _, (r, message) in top[:8]:
            if r > 1.0 / margin:
                print(f"  ~ {r:.2g}: {message}")
    return ok


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--only", nargs="+", metavar="NAME", help="cases to re-mint (stems)")
    parser.add_argument("--dry-run", action="store_true", help="print, write nothing")
    parser.add_argument(
        "--add-golden", action="store_true", help="give the --only cases a golden check"
    )
    parser.add_argument(
        "--sensitivity",
        type=int,
        nargs="?",
        const=4,
        metavar="N",
        help="instead of minting: run each golden case N times (default 4) with its inputs "
        "moved in their last bits and report how close the figures come to their tolerance",
    )
    parser.add_argument(
        "--margin",
        type=float,
        default=100.0,
        help="--sensitivity fails a case whose figures come within this factor (default 100)",
    )
    parser.add_argument(
        "--reset-tolerances",
        action="store_true",
        help="write regression_suite.GOLDEN_TOLERANCES into the golden checks",
    )
    args = parser.parse_args(argv)
    names = suite.case_names()
    cases = {n: suite.load_case(n) for n in names}
    new = []
    if args.only:
        unknown = [n for n in args.only if n not in names]
        for n in unknown:
            if (suite.SCENES / f"{n}.toml").is_file():
                new.append(n)
            else:
                parser.error(f"no case or scene named {n!r} (cases: expected/*.json)")
        names = [n for n in args.only if n in names]
    else:
        new = [Path(s).stem for s in _unused_scenes()]
    for n in new:
        cases[n] = _new_case(f"{n}.toml")
    changed = 0
    if args.add_golden and not args.only:
        parser.error("--add-golden needs --only NAME ...")
    if args.sensitivity is not None:
        ok = [sensitivity(n, cases[n], args.sensitivity, args.margin) for n in names]
        print(f"{sum(ok)} of {len(ok)} case(s) stay within 1/{args.margin:g} of their tolerance")
        return 0 if all(ok) else 1
    for n in [*names, *new]:
        if n in new or args.add_golden or any(c.get("golden") for c in cases[n]["checks"]):
            changed += mint(n, cases[n], args.dry_run, args.reset_tolerances)
    verb = "would change" if args.dry_run else "changed"
    print(f"{changed} expected file(s) {verb}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
