"""Built-in classes of the units of vehicle combinations: tractors, rigid trucks, semitrailers,
light trailers and drawbar trailers, every number with its source.

The table ``crashsim/vehicles/data/combination_classes.toml`` is read once, with the reading code
of :mod:`crashsim.vehicles.vehicle_data` (its :class:`~crashsim.vehicles.vehicle_data.Figure`:
value and sd in SI, the source key or the sentence "derived: <how>", the refs and the number as
published). Unlike the car classes, each class carries only the quantities a source was found
for: ``cls.quantities`` lists them in the table's order (see :data:`QUANTITIES` for every
quantity's unit and meaning), ``cls["wheelbase"]`` gives one, and asking for a quantity the class
does not carry raises a ParameterError naming the ones it does. ``docs/vehicle-data.md``
("Combination classes") documents every source, every derivation and every quantity not found.

Lengths follow the unit's body frame (ISO 8855: x forward, y left, z up); masses in kg, lengths
in m, inertias in kg m^2, shares as fractions (0.06 = 6 %).
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass
from functools import cache
from types import MappingProxyType
from typing import Any

from crashsim.errors import ParameterError
from crashsim.vehicles.vehicle_data import Figure, figure_from, read_data_table, sources_of

__all__ = [
    "QUANTITIES",
    "SOURCES",
    "CombinationClass",
    "combination_class",
    "combination_classes",
]

_DATA = "combination_classes.toml"
_TABLE = "combination class table"
_CLASS_KEYS = ("kind", "description", "axle_group")  # a class's entries that are not quantities


@dataclass(frozen=True)
class CombinationClass:
    """One unit of a combination: its quantities as :class:`Figure` in the table's order."""

    name: str
    kind: str  # "tractor", "rigid", "semitrailer", "light_trailer", "full_trailer"
    description: str
    axle_group: str | None
    figures: Mapping[str, Figure]

    @property
    def quantities(self) -> tuple[str, ...]:
        """The quantities this class carries, in the table's order."""
        return tuple(self.figures)

    def __getitem__(self, quantity: str) -> Figure:
        try:
            return self.figures[quantity]
        except KeyError:
            raise ParameterError(
                f"combination class {self.name!r} has no sourced {quantity!r}: "
                f"it carries {', '.join(self.figures)}"
            ) from None

    def __contains__(self, quantity: object) -> bool:
        return quantity in self.figures


def _class(name: str, raw: Mapping[str, Any], quantities: Mapping[str, Any]) -> CombinationClass:
    unknown = [k for k in raw if k not in _CLASS_KEYS and k not in quantities]
    if unknown:
        raise ParameterError(f"{_TABLE}: {name} has unknown quantities {unknown}")
    figures = {
        q: figure_from(raw[q], f"{name}.{q}", _TABLE) for q in quantities if q in raw
    }
    axle_group = raw.get("axle_group")
    return CombinationClass(
        name=name,
        kind=str(raw["kind"]),
        description=str(raw["description"]),
        axle_group=None if axle_group is None else str(axle_group),
        figures=MappingProxyType(figures),
    )


@cache
def _load() -> tuple[dict[str, CombinationClass], dict[str, str], dict[str, str]]:
    table = read_data_table(_DATA)
    quantities = {q: f"{v['meaning']} ({v['unit']})" for q, v in table["quantities"].items()}
    classes = {
        name: _class(name, table["classes"][name], table["quantities"]) for name in table["order"]
    }
    return classes, sources_of(table), quantities


SOURCES: dict[str, str] = dict(_load()[1])
"""Source key -> full citation."""

QUANTITIES: dict[str, str] = dict(_load()[2])
"""Every quantity a class may carry -> its meaning and unit, in the table's order."""


def combination_classes() -> dict[str, CombinationClass]:
    """Every built-in combination class by name, in the table's order."""
    return dict(_load()[0])


def combination_class(name: str) -> CombinationClass:
    """The named class. Raises ParameterError for an unknown name, listing the known ones."""
    classes = _load()[0]
    if not isinstance(name, str):
        raise ParameterError(f"combination class name must be a string, got {name!r}")
    key = name.strip().lower()
    if key not in classes:
        raise ParameterError(
            f"unknown combination class {name!r}: use one of {', '.join(classes)}"
        )
    return classes[key]
