"""Every ```python block of README.md and docs/*.md runs as shown and prints what the page says
(the conventions: docs/README.md).

- The blocks of one page run in order in one namespace (a block may use what an earlier block
  of the page made), in a fresh folder holding the fixtures: ``car.ply`` (a generated sedan's
  body, metres, x forward, z up), ``car.glb`` (the same in centimetres, y up, -z forward),
  ``examples/`` (the repository's), ``docs/img/`` (empty: the pictures a page's script
  makes go there), ``out/`` (what ``crashsim run examples/seed-90deg.toml
  --out out/`` writes; made for the pages that name out/report.json) and ``../shared/meshes``
  (the shared meshes: a page that uses them is skipped, saying so, when they are absent).
- A ```text block after a python block (before the next one) is what that block prints:
  line by line, runs of spaces as one, a line ``...`` standing for any lines and a ``...`` in
  a line for any text; numbers agree to one unit in their last digit shown (a number without
  a decimal point exactly).
- ``# -> value`` at the end of a statement: its value (an expression's, or what it assigned)
  is the value written: a Python literal (numbers to one unit in their last digit), or
  numbers with their units, separated by commas, compared in order with the value's numbers.
- A block whose first line is ``# not run: <why>`` is not run (a signature, a fragment).

When the engine's figures move, the failure shows the page, the line and the whole output;
``CRASHSIM_UPDATE_DOCS=1 python -m pytest tests/test_docs_examples.py`` rewrites the numbers
(and the lines) that differ in the text blocks and the ``# ->`` comments whose wording still
matches. Warnings are errors here, as in the rest of the suite: an example that warns says so.
"""

from __future__ import annotations

import ast
import contextlib
import io
import math
import os
import re
import tokenize
import traceback
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np
import pytest
from conftest import REPO, SHARED_MESHES

PAGES = [REPO / "README.md", *sorted((REPO / "docs").glob("*.md"))]
FENCE = re.compile(r"^```([\w-]*)[^\n]*\n(.*?)^```[ \t]*$", re.MULTILINE | re.DOTALL)
NOT_RUN = "# not run:"
ARROW = re.compile(r"#\s*->\s*(.*)$")
NUMBER = re.compile(r"[-+]?(?:\d+\.\d+|\.\d+|\d+)(?:[eE][-+]?\d+)?")
UPDATE = os.environ.get("CRASHSIM_UPDATE_DOCS") == "1"


@dataclass
class Text:
    """A ```text block: what the python block before it prints."""

    line: int  # of its first content line, 1-based
    start: int  # offsets of its content in the page
    end: int
    content: str


@dataclass
class Example:
    line: int  # of its first code line, 1-based
    code: str
    output: Text | None = None


@dataclass
class Page:
    path: Path
    text: str
    examples: list[Example] = field(default_factory=list)


def read_page(path: Path) -> Page:
    text = path.read_text(encoding="utf-8")
    page = Page(path, text)
    for m in FENCE.finditer(text):
        lang, body = m.group(1), m.group(2)
        line = text.count("\n", 0, m.start(2)) + 1
        if lang == "python":
            page.examples.append(Example(line, body))
        elif lang == "text":
            if not page.examples or page.examples[-1].output is not None:
                raise AssertionError(
                    f"{path.name}:{line}: a ```text block is the output of the python block "
                    "before it, and there is none (or that one has its text already)"
                )
            page.examples[-1].output = Text(line, m.start(2), m.end(2), body)
    return page


# -- numbers ------------------------------------------------------------------------------------


def _unit(token: str) -> float:
    """One unit in the last digit shown of a number token (0 for an integer: exact)."""
    mantissa, _, exponent = token.lower().partition("e")
    decimals = len(mantissa.split(".")[1]) if "." in mantissa else None
    if decimals is None:
        return 0.0 if not exponent else 10.0 ** int(exponent)
    return 10.0 ** (int(exponent or 0) - decimals)


def _close(expected: str, actual: float, exact_ints: bool = True) -> bool:
    tol = _unit(expected)
    if tol == 0.0 and not exact_ints:
        tol = 1.0
    return abs(actual - float(expected)) <= tol * (1.0 + 1e-9)


def _pattern(line: str) -> re.Pattern[str]:
    """The regular expression of an expected line: its numbers captured, runs of spaces as
    one, ``...`` any text, everything else as written."""
    parts = []
    for token in re.findall(rf"{NUMBER.pattern}|\s+|.", _spaced(line.strip())):
        if token == "\0":
            parts.append(".*?")
        elif NUMBER.fullmatch(token):
            parts.append(f"({NUMBER.pattern})")
        elif token.isspace():
            parts.append(r"\s+")
        else:
            parts.append(re.escape(token))
    return re.compile("".join(parts))


def _numbers_in(expected: str, actual: str) -> list[str] | None:
    """The actual line's numbers where the expected line has its own (None: no match)."""
    m = _pattern(expected).fullmatch(actual.strip())
    return None if m is None else list(m.groups())


def align(expected: list[str], actual: list[str]) -> list[int | None] | None:
    """For each expected line the index of the actual line it matches (None for a "..."
    line), in order, covering every actual line; None when they cannot be aligned."""

    def go(i: int, j: int) -> list[int | None] | None:
        if i == len(expected):
            return [] if j == len(actual) else None
        if expected[i].strip() == "...":
            for k in range(j, len(actual) + 1):
                rest = go(i + 1, k)
                if rest is not None:
                    return [None, *rest]
            return None
        if j < len(actual) and _numbers_in(expected[i], actual[j]) is not None:
            rest = go(i + 1, j + 1)
            if rest is not None:
                return [j, *rest]
        return None

    return go(0, 0)


def _with_numbers(line: str, numbers: list[str]) -> str:
    """The expected line with its numbers replaced (in order) by ``numbers``."""
    given = iter(numbers)
    parts = re.split(r"(\.\.\.)", line)  # "..." is never a number's
    return "".join(p if p == "..." else NUMBER.sub(lambda m: next(given), p) for p in parts)


def compare_output(expected: str, actual: str) -> tuple[list[str], str | None]:
    """Problems (empty when the output is the one written) and the text block with the
    printed numbers (None when the two cannot be aligned line by line)."""
    want = expected.rstrip("\n").split("\n")
    got = actual.rstrip("\n").split("\n") if actual.strip() else []
    where = align(want, got)
    if where is None:
        lost = [
            e.strip()
            for e in want
            if e.strip() != "..." and not any(_numbers_in(e, g) is not None for g in got)
        ]
        return [f"not printed: {e!r}" for e in lost] or [
            "every written line is printed, but not in this order or with other lines "
            "between them (write those, or a line '...')"
        ], None
    problems, rewritten = [], []
    for e, j in zip(want, where, strict=True):
        if j is None:
            rewritten.append(e)
            continue
        printed = _numbers_in(e, got[j]) or []
        written = NUMBER.findall(_elided(e))
        if not all(_close(x, float(y)) for x, y in zip(written, printed, strict=True)):
            problems.append(f"written {e.strip()!r}\n   printed {got[j].strip()!r}")
        rewritten.append(_with_numbers(e, printed))
    return problems, "\n".join(rewritten) + "\n"


def _elided(line: str) -> str:
    """The line without its "..." (whose dots are not numbers)."""
    return line.replace("...", " ")


def _spaced(line: str) -> str:
    """The line with each "..." as one NUL character (a token of its own)."""
    return line.replace("...", "\0")


def _numbers_of(value: Any) -> list[float] | None:
    """The numbers of a value (a number, or nested tuples / lists / arrays of them)."""
    if isinstance(value, bool):
        return None
    if isinstance(value, int | float | np.integer | np.floating):
        return [float(value)]
    if isinstance(value, np.ndarray) and value.dtype.kind in "iuf":
        return [float(x) for x in value.ravel()]
    if isinstance(value, tuple | list):
        out: list[float] = []
        for v in value:
            n = _numbers_of(v)
            if n is None:
                return None
            out += n
        return out
    return None


def _same(expected: Any, actual: Any, text: str) -> bool:
    """A literal against a value: numbers to one unit of their last digit (their tokens are
    found in ``text`` in order), everything else equal."""
    if isinstance(expected, int | float) and not isinstance(expected, bool):
        return isinstance(actual, int | float | np.integer | np.floating) and _close(
            NUMBER.findall(text)[0], float(actual), exact_ints=isinstance(actual, int | np.integer)
        )
    if isinstance(expected, tuple | list):
        if not isinstance(actual, tuple | list | np.ndarray) or len(actual) != len(expected):
            return False
        return all(_same(e, a, repr(e)) for e, a in zip(expected, actual, strict=True))
    return bool(expected == actual)


def check_arrow(comment: str, value: Any) -> str | None:
    """None when ``value`` is what ``# -> comment`` says, else the problem."""
    try:
        literal = ast.literal_eval(comment)
    except (ValueError, SyntaxError):
        literal = None
    else:
        return None if _same(literal, value, comment) else f"the value is {value!r}"
    written = []
    for part in comment.split(","):
        m = re.match(rf"\s*({NUMBER.pattern})(?![\w.])", part)
        if m is None:
            break
        written.append(m.group(1))
    numbers = _numbers_of(value)
    if not written:
        return "write a Python literal, or numbers (with units) separated by commas"
    if numbers is None or len(numbers) != len(written):
        return f"the value is {value!r}"
    exact = isinstance(value, int | np.integer)
    if all(_close(w, n, exact_ints=exact) for w, n in zip(written, numbers, strict=True)):
        return None
    return f"the value is {value!r}"


def rewrite_arrow(comment: str, value: Any) -> str:
    """The comment with its numbers replaced by the value's, to as many decimals."""
    numbers = iter(_numbers_of(value) or [])

    def sub(m: re.Match[str]) -> str:
        token, x = m.group(0), next(numbers, None)
        if x is None:
            return token
        mantissa, _, exponent = token.lower().partition("e")
        decimals = len(mantissa.split(".")[1]) if "." in mantissa else 0
        scale = 10.0 ** int(exponent or 0)
        return f"{x / scale:.{decimals}f}" + (token[len(mantissa) :] if exponent else "")

    return NUMBER.sub(sub, comment, count=len(_numbers_of(value) or []))


# -- running a page -----------------------------------------------------------------------------


def _arrows(code: str) -> dict[int, str]:
    """Line (1-based, in the block) -> the text after ``# ->`` of the comments that have one."""
    out = {}
    for tok in tokenize.generate_tokens(io.StringIO(code).readline):
        if tok.type == tokenize.COMMENT:
            m = ARROW.match(tok.string)
            if m:
                out[tok.start[0]] = m.group(1).strip()
    return out


def _assigned(stmt: ast.stmt, ns: dict[str, Any]) -> Any:
    targets = stmt.targets if isinstance(stmt, ast.Assign) else [stmt.target]  # type: ignore[attr-defined]
    values = []
    for t in targets[:1]:
        names = [t] if isinstance(t, ast.Name) else list(getattr(t, "elts", []))
        got = [ns[n.id] for n in names if isinstance(n, ast.Name)]
        values.append(got[0] if isinstance(t, ast.Name) else tuple(got))
    return values[0]


def run_example(page: Page, ex: Example, ns: dict[str, Any]) -> tuple[str, list[str], dict]:
    """Runs one block; returns what it printed, the problems of its ``# ->`` comments and the
    comments to rewrite {line in the page: (old, new)}."""
    name = f"{page.path.name}:{ex.line}"
    tree = ast.parse(ex.code, filename=name)
    arrows = _arrows(ex.code)
    problems: list[str] = []
    rewrites: dict[int, tuple[str, str]] = {}
    out = io.StringIO()
    with contextlib.redirect_stdout(out):
        for stmt in tree.body:
            line = ex.line + stmt.lineno - 1
            comment = arrows.get(stmt.end_lineno or stmt.lineno)
            try:
                if isinstance(stmt, ast.Expr) and comment is not None:
                    code = compile(ast.Expression(stmt.value), name, "eval")
                    value = eval(code, ns)  # noqa: S307 - the page's own example
                else:
                    exec(compile(ast.Module([stmt], []), name, "exec"), ns)  # noqa: S102
                    value = _assigned(stmt, ns) if comment is not None else None
            except Exception:
                raise AssertionError(
                    f"{page.path.name}:{line}: the example fails:\n{traceback.format_exc()}"
                    f"\nprinted so far:\n{out.getvalue()}"
                ) from None
            if comment is not None:
                problem = check_arrow(comment, value)
                if problem is not None:
                    at = ex.line + (stmt.end_lineno or stmt.lineno) - 1
                    problems.append(f"{page.path.name}:{at}: '# -> {comment}': {problem}")
                    rewrites[at] = (comment, rewrite_arrow(comment, value))
    return out.getvalue(), problems, rewrites


def _write_fixtures(folder: Path, page: Page) -> None:
    import crashsim as cs
    import trimesh
    from crashsim.vehicles.generator import body_params, default_dims, generate_body

    body = generate_body(body_params("sedan", **default_dims("sedan")))  # x fwd, y left, z up
    body.export(folder / "car.ply")
    # centimetres, y up, -z forward: file (X, Y, Z) = (-y, z, -x) of the model, times 100
    v = np.asarray(body.vertices)
    glb = trimesh.Trimesh(100.0 * np.column_stack([-v[:, 1], v[:, 2], -v[:, 0]]), body.faces)
    glb.export(folder / "car.glb")
    (folder / "examples").symlink_to(REPO / "examples", target_is_directory=True)
    (folder / "docs" / "img").mkdir(parents=True)  # where the pages' picture scripts write
    if SHARED_MESHES.is_dir():
        (folder.parent / "shared").symlink_to(SHARED_MESHES.parent, target_is_directory=True)
    if "out/report.json" in page.text:
        from crashsim.cli import main

        with contextlib.redirect_stdout(io.StringIO()):
            assert main(["run", "examples/seed-90deg.toml", "--out", "out"]) == 0
    assert cs  # the package imports before any page's example


def _runnable(page: Page) -> list[Example]:
    return [ex for ex in page.examples if not ex.code.lstrip().startswith(NOT_RUN)]


RUN = [p for p in PAGES if _runnable(read_page(p))]


def test_blocks_that_do_not_run_are_few_and_say_why() -> None:
    # the pages' python blocks are examples that run; a signature or a cluster address is not
    skipped = [
        (p.path.name, ex.line, ex.code.lstrip().splitlines()[0])
        for p in map(read_page, PAGES)
        for ex in p.examples
        if ex not in _runnable(p)
    ]
    assert len(skipped) <= 2, skipped
    assert all(len(why) > len(NOT_RUN) + 10 for *_, why in skipped), skipped
    assert len(RUN) >= 10  # README.md and the pages with examples


@pytest.mark.parametrize("path", RUN, ids=[p.name for p in RUN])
def test_the_pages_examples_run_and_print_what_the_page_says(
    path: Path, tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    page = read_page(path)
    runnable = _runnable(page)
    if "../shared" in page.text and not SHARED_MESHES.is_dir():
        pytest.skip(f"{path.name} uses the shared meshes, which are absent ({SHARED_MESHES})")
    folder = tmp_path / "repo"
    folder.mkdir()
    monkeypatch.chdir(folder)
    _write_fixtures(folder, page)
    ns: dict[str, Any] = {"__name__": "__docs__"}
    problems: list[str] = []
    edits: list[tuple[int, int, str]] = []  # (start, end, new text) in the page
    lines = page.text.split("\n")
    for ex in runnable:
        printed, wrong, rewrites = run_example(page, ex, ns)
        problems += wrong
        for at, (old, new) in rewrites.items():
            start = sum(len(x) + 1 for x in lines[: at - 1])
            k = page.text.index(old, start)
            edits.append((k, k + len(old), new))
        if ex.output is None:
            continue
        bad, rewritten = compare_output(ex.output.content, printed)
        if bad:
            problems.append(
                f"{path.name}:{ex.output.line}: the output of the block at line {ex.line} is "
                "not the one written:\n  "
                + "\n  ".join(bad)
                + "\n--- printed ---\n"
                + printed
                + "--- end ---"
            )
            if rewritten is not None:
                edits.append((ex.output.start, ex.output.end, rewritten))
    if problems and UPDATE and edits:
        text = page.text
        for start, end, new in sorted(edits, reverse=True):
            text = text[:start] + new + text[end:]
        path.write_text(text, encoding="utf-8")
    assert not problems, "\n\n".join(problems)


# -- the checker itself -------------------------------------------------------------------------


def test_numbers_agree_to_one_unit_of_their_last_digit() -> None:
    ok, _ = compare_output("t = 0.0363 s, impact 1\n", "t = 0.0364 s, impact 1\n")
    assert ok == []
    bad, _ = compare_output("t = 0.0363 s, impact 1\n", "t = 0.0365 s, impact 1\n")
    assert len(bad) == 1
    bad, _ = compare_output("t = 0.0363 s, impact 1\n", "t = 0.0363 s, impact 2\n")
    assert len(bad) == 1  # a whole number exactly
    bad, rewritten = compare_output("a 1.0\n...\nz 2.00\n", "a 1.0\nb\nc\nz 2.50\n")
    assert len(bad) == 1 and rewritten == "a 1.0\n...\nz 2.50\n"
    bad, rewritten = compare_output("a 1.0\nz 2.00\n", "a 1.0\nb\nz 2.00\n")
    assert bad and rewritten is None  # an extra line
    assert compare_output("x  =   1.5\n", "x = 1.5\n")[0] == []  # runs of spaces as one


def test_arrow_comments_take_literals_or_numbers_with_units() -> None:
    assert check_arrow("0.0363 s", 0.036312) is None
    assert check_arrow("0.0363 s", 0.03645) is not None
    assert check_arrow("1.70e6, 0.85e6 N/m", (1.7e6, 0.85e6)) is None
    assert check_arrow("1084 kg", 1084.4) is None
    assert check_arrow("['small_car', 'sedan']", ["small_car", "sedan"]) is None
    assert check_arrow("(1825.0, 367.2)", (1825.04, 367.21)) is None
    assert check_arrow("'wall'", "wall") is None and check_arrow("'wall'", "tree") is not None
    assert check_arrow("0.162 m front, 0.325 m side", (0.1621, 0.3249)) is None
    assert rewrite_arrow("0.0363 s", 0.03651) == "0.0365 s"
    assert rewrite_arrow("1.70e6, 0.85e6 N/m", (1.72e6, 0.85e6)) == "1.72e6, 0.85e6 N/m"
    assert math.isclose(float(NUMBER.findall("-2.5e-3")[0]), -2.5e-3)
