"""Names of what a scene holds (vehicles, obstacles, wheels, friction zones): the one rule.

A name labels output columns, CSV headers, report tables, the case page and messages, so it
is printable text: not empty or blank, and without control characters (Unicode category Cc:
a newline splits a CSV header), line or paragraph separators (Zl, Zp) or the bidirectional
controls (U+061C, U+200E, U+200F, U+202A-U+202E, U+2066-U+2069: a right-to-left override
shows what follows it reversed).
"""

from __future__ import annotations

import unicodedata

from crashsim.errors import ParameterError

__all__ = ["BIDI_CONTROLS", "check_name"]

# Unicode's Bidi_Control characters: marks, embeddings, overrides and isolates.
BIDI_CONTROLS = frozenset(
    "\u061c\u200e\u200f" + "".join(map(chr, range(0x202A, 0x202F)))
    + "".join(map(chr, range(0x2066, 0x206A)))
)
_REFUSED_CATEGORIES = ("Cc", "Zl", "Zp")


def check_name(name: object, what: str) -> str:
    """``name`` when it is a valid name of ``what`` ("a vehicle", "an obstacle", "a wheel",
    ...); else a ParameterError saying why, naming a refused character by its code point."""
    if not isinstance(name, str) or not name.strip():
        raise ParameterError(f"{what} needs a non-blank name (a str), got {name!r}")
    for i, c in enumerate(name):
        if c in BIDI_CONTROLS or unicodedata.category(c) in _REFUSED_CATEGORIES:
            kind = unicodedata.name(c, "a control character")
            raise ParameterError(
                f"{what}'s name {name!r} has U+{ord(c):04X} ({kind}) at position {i}: names "
                "label columns, CSV headers and reports: use printable characters"
            )
    return name
