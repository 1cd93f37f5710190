"""Built-in road surfaces: tyre-road friction coefficients with their published ranges.

The table lives in ``crashsim/environment/data/ground_surfaces.toml``; every value has a
source (a key of :data:`SOURCES`) or a sentence "derived: ..." that says how it was obtained,
and the published range it lies in (``low``, ``high``). docs/ground.md shows the table.

    from crashsim.environment.surfaces import surface, friction
    friction("wet asphalt")        # 0.5
    surface("gravel").low          # 0.35
"""

from __future__ import annotations

import tomllib
from dataclasses import dataclass
from functools import cache
from importlib import resources
from typing import Any

from crashsim.errors import ParameterError

__all__ = ["ALIASES", "SOURCES", "Surface", "friction", "surface", "surfaces"]


@dataclass(frozen=True)
class Surface:
    """One surface: ``name``, ``description``, the friction coefficient ``value`` a surface
    name gives, the published range ``low``-``high``, ``source`` (a key of :data:`SOURCES`
    or "derived: ...") and ``refs`` (the keys it rests on)."""

    name: str
    description: str
    value: float
    low: float
    high: float
    source: str
    refs: tuple[str, ...]

    @property
    def derived(self) -> bool:
        """True when the value was derived here rather than read as published."""
        return self.source.startswith("derived:")


@cache
def _load() -> tuple[dict[str, Surface], dict[str, str], dict[str, str]]:
    path = resources.files("crashsim.environment").joinpath("data", "ground_surfaces.toml")
    table: dict[str, Any] = tomllib.loads(path.read_text(encoding="utf-8"))
    sources = {k: str(v["citation"]) for k, v in table["sources"].items()}
    aliases = {str(k): str(v) for k, v in table.get("aliases", {}).items()}
    out = {}
    for name in table["order"]:
        raw = table["surfaces"][name]
        out[name] = Surface(
            name=name,
            description=str(raw["description"]),
            value=float(raw["value"]),
            low=float(raw["low"]),
            high=float(raw["high"]),
            source=str(raw["source"]),
            refs=tuple(raw.get("refs", ())),
        )
    return out, sources, aliases


SOURCES: dict[str, str] = dict(_load()[1])
"""Source key -> full citation."""

ALIASES: dict[str, str] = dict(_load()[2])
"""Other accepted names -> surface name (e.g. "asphalt" -> "dry_asphalt")."""


def surfaces() -> dict[str, Surface]:
    """Every built-in surface by name, in a stable order (dry paved first, ice last)."""
    return dict(_load()[0])


def _key(name: str) -> str:
    key = "_".join(name.strip().lower().replace("-", " ").split())
    return ALIASES.get(key, key)


def surface(name: str) -> Surface:
    """The named surface ("dry_asphalt", "wet asphalt", "Gravel", an alias such as
    "asphalt"...). ParameterError listing the known names otherwise."""
    if not isinstance(name, str):
        raise ParameterError(f"a surface name must be a string, got {name!r}")
    table = _load()[0]
    key = _key(name)
    if key not in table:
        known = ", ".join(list(table) + [f"{a} (= {t})" for a, t in ALIASES.items()])
        raise ParameterError(
            f"unknown surface {name!r}: use a friction coefficient or one of {known}"
        )
    return table[key]


def friction(value: float | str, what: str = "friction") -> float:
    """A friction coefficient from a number or a surface name (its table value). Finiteness
    and the range (0, 2] are the engine's checks; this only refuses what is not a number or a
    name."""
    if isinstance(value, str):
        return surface(value).value
    if isinstance(value, bool):
        raise ParameterError(f"{what} must be a number or a surface name, got {value!r}")
    try:
        mu = float(value)
    except (TypeError, ValueError) as e:
        raise ParameterError(f"{what} must be a number or a surface name, got {value!r}") from e
    return mu
