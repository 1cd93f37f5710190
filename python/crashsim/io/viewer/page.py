"""The case page: one self-contained HTML file (template, style, three.js r111, the viewer's
scripts (viewer.js; people.js: pedestrians and cyclists as one person each; report.js: the
report panel) and the data, all inline), written atomically."""

from __future__ import annotations

import html
import json
import os
import re
import tempfile
from importlib import resources
from pathlib import Path
from typing import Any

from crashsim._core import __version__
from crashsim.errors import ParameterError

__all__ = ["THREE_REVISION", "check_output_path", "page_source", "render_page", "write_page"]

THREE_REVISION = "111"  # the vendored three.js (static/three/README.md)
_PLACEHOLDER = re.compile(r"\{\{([A-Z]+)\}\}")


def _static(*parts: str) -> str:
    return (
        resources.files("crashsim.io.viewer").joinpath("static", *parts).read_text(encoding="utf-8")
    )


def _script(text: str, what: str) -> str:
    """A script's text, refused if it could end its <script> element early."""
    if re.search(r"</script|<!--", text, flags=re.IGNORECASE):
        raise RuntimeError(f"{what} contains '</script' or '<!--'")  # a packaging fault
    return text


def render_page(data: dict[str, Any]) -> str:
    """The HTML text of a page holding ``data`` (a page_data dict)."""
    # JSON inside <script>: "<" only ever occurs inside strings, where \u003c means the same
    payload = json.dumps(data, separators=(",", ":"), allow_nan=False).replace("<", "\\u003c")
    values = {
        "TITLE": html.escape(str(data.get("title", "crashsim case"))),
        "SOURCE": html.escape(str(data.get("source", "run"))),
        "VERSION": html.escape(str(__version__)),
        "CSS": _static("viewer.css"),
        "DATA": payload,
        "THREE": _script(_static("three", "three.min.js"), "three.min.js"),
        "ORBIT": _script(_static("three", "OrbitControls.js"), "OrbitControls.js"),
        "PEOPLE": _script(_static("people.js"), "people.js"),
        "REPORT": _script(_static("report.js"), "report.js"),
        "VIEWER": _script(_static("viewer.js"), "viewer.js"),
    }
    # one pass: text put in is never searched for placeholders again
    return _PLACEHOLDER.sub(lambda m: values[m.group(1)], _static("page.html"))


_SOURCE = re.compile(rb'<meta name="crashsim-source" content="([a-z]+)">')
_HEAD_BYTES = 4096  # the <meta> elements come first: a page's head fits in this


def page_source(path: str | os.PathLike[str]) -> str | None:
    """What an existing case page was made from: "run" (a Result: ``cs.view``, ``crashsim run
    --html``) or "report" (``crashsim view``); None for any other file or a page written before
    pages said so."""
    try:
        with open(path, "rb") as f:
            head = f.read(_HEAD_BYTES)
    except OSError:
        return None
    found = _SOURCE.search(head)
    return found.group(1).decode() if found else None


def check_output_path(path: str | os.PathLike[str]) -> Path:
    """The page's path, checked before any work: ParameterError unless it names a file (not a
    folder) in an existing folder where files can be created."""
    out = Path(path)
    if out.is_dir():
        raise ParameterError(f"{out} is a folder: give the page's file name (e.g. case.html)")
    folder = out.parent
    if not folder.is_dir():
        raise ParameterError(f"cannot write {out}: the folder {folder} does not exist")
    try:
        with tempfile.TemporaryFile(dir=folder):
            pass
    except OSError as e:
        raise ParameterError(f"cannot write {out}: {e.strerror or e} (in {folder})") from e
    return out


def write_page(data: dict[str, Any], path: str | os.PathLike[str]) -> Path:
    """Writes the page (UTF-8) to ``path`` through a temporary file in the same folder, so a
    failed write leaves no half page; returns the path."""
    out = check_output_path(path)
    text = render_page(data)
    # a plain new file (the umask's permissions, unlike mkstemp's 0600) beside the target
    tmp = out.parent / f".{out.name}.{os.getpid()}.tmp"
    try:
        with open(tmp, "x", encoding="utf-8") as f:
            f.write(text)
        os.replace(tmp, out)
    except BaseException:
        tmp.unlink(missing_ok=True)
        raise
    return out
