"""Built-in generic vehicle classes: mass, dimensions, inertia and CRASH3 crush stiffness.

Reconstructionists often know only a vehicle's class. This module loads, once, the table in
``crashsim/vehicles/data/vehicle_classes.toml``: for each class, every number in SI (kg, m, kg
m^2, N/m,
N/m^2) with one standard deviation where one is published (or derived from a published sample),
and its source: a key of :data:`SOURCES` or a sentence "derived: <how>". The published value and
unit are kept beside each converted number. ``docs/vehicle-data.md`` shows the table, every
source and every derivation, and states the gaps (no published class stiffness was found for most
classes and faces: those values are flagged as derived).

Lengths follow the vehicle body frame (ISO 8855: x forward, y left, z up): ``length`` along x,
``width`` along y, ``height`` along z, ``cg_to_front_axle`` along x from the centre of mass to the
front axle, ``cg_height`` above the ground. ``yaw_inertia`` is about the vertical axis through the
centre of mass. ``track_front`` and ``track_rear`` are the distances
between the wheel centres of an axle (along y); ``tyre_radius`` is the tyre's rolling radius
(m); ``roll_gradient`` the body's roll per g of steady lateral acceleration (rad per g), which
sets the anti-roll bars of a vehicle on the class's wheels. Crush stiffness per face: force per
unit width F/W = A + B C (see :mod:`crashsim.vehicles.stiffness`); the "side" face gives both
"left" and "right".
"""

from __future__ import annotations

import math
import tomllib
from collections.abc import Mapping
from dataclasses import dataclass, field
from functools import cache
from importlib import resources
from typing import Any

from crashsim.errors import ParameterError
from crashsim.vehicles.stiffness import FaceStiffness, Stiffness

__all__ = [
    "ALIASES",
    "SOURCES",
    "FaceData",
    "Figure",
    "VehicleClass",
    "vehicle_class",
    "vehicle_classes",
]

_DATA = "vehicle_classes.toml"
_FIELDS = (
    "mass",
    "length",
    "width",
    "height",
    "wheelbase",
    "cg_to_front_axle",
    "cg_height",
    "yaw_inertia",
    "track_front",
    "track_rear",
    "tyre_radius",
    "roll_gradient",
)
_FACES = ("front", "rear", "side")


@dataclass(frozen=True)
class Figure:
    """One number of the table.

    ``value`` and ``sd`` are SI (kg, m, kg m^2, N/m, N/m^2); ``sd`` is one standard deviation in
    the same unit, None where none is published. ``source`` is a key of :data:`SOURCES`, or a
    sentence starting "derived: " that says how the value was obtained. ``refs`` lists the keys of
    :data:`SOURCES` the number rests on; ``published`` is the value as published (its unit under
    "unit"), empty for a number that has no published form.
    """

    value: float
    sd: float | None
    source: str
    refs: tuple[str, ...] = ()
    published: Mapping[str, Any] = field(default_factory=dict)

    @property
    def derived(self) -> bool:
        """True when the number was derived here rather than read as published."""
        return self.source.startswith("derived:")

    def bounds(self, k: float = 1.0) -> tuple[float, float]:
        """(value - k sd, value + k sd); (value, value) when no sd is published."""
        s = 0.0 if self.sd is None else k * self.sd
        return (self.value - s, self.value + s)


@dataclass(frozen=True)
class FaceData:
    """One face's CRASH3 coefficients: ``A`` (N/m) and ``B`` (N/m^2)."""

    A: Figure
    B: Figure

    def to_stiffness(self) -> FaceStiffness:
        """The face as a :class:`crashsim.vehicles.stiffness.FaceStiffness` (values only)."""
        return FaceStiffness(A=self.A.value, B=self.B.value)


@dataclass(frozen=True)
class VehicleClass:
    """A generic vehicle class: see the module docstring for frames and units."""

    name: str
    description: str
    mass: Figure
    length: Figure
    width: Figure
    height: Figure
    wheelbase: Figure
    cg_to_front_axle: Figure
    cg_height: Figure
    yaw_inertia: Figure
    track_front: Figure
    track_rear: Figure
    tyre_radius: Figure
    roll_gradient: Figure
    front: FaceData
    rear: FaceData
    side: FaceData

    @property
    def stiffness(self) -> Stiffness:
        """The class's mean coefficients as a :class:`crashsim.vehicles.stiffness.Stiffness`;
        the side
        face gives both left and right."""
        side = self.side.to_stiffness()
        return Stiffness(
            front=self.front.to_stiffness(), rear=self.rear.to_stiffness(), left=side, right=side
        )

    @property
    def radius_of_gyration(self) -> float:
        """Yaw radius of gyration k = sqrt(Izz / m) (m)."""
        return math.sqrt(self.yaw_inertia.value / self.mass.value)

    def figures(self) -> dict[str, Figure]:
        """Every number of the class by dotted name ("mass", ..., "front.A", "side.B")."""
        out = {f: getattr(self, f) for f in _FIELDS}
        for face in _FACES:
            data: FaceData = getattr(self, face)
            out[f"{face}.A"] = data.A
            out[f"{face}.B"] = data.B
        return out


def read_data_table(filename: str) -> dict[str, Any]:
    """The TOML table ``crashsim/vehicles/data/<filename>``, parsed (no checks)."""
    path = resources.files("crashsim.vehicles").joinpath("data", filename)
    return tomllib.loads(path.read_text(encoding="utf-8"))


def sources_of(table: Mapping[str, Any]) -> dict[str, str]:
    """A data table's ``[sources]``: key -> full citation."""
    return {k: str(v["citation"]) for k, v in table["sources"].items()}


def figure_from(raw: Mapping[str, Any], where: str, table: str = "vehicle class table") -> Figure:
    """One number of a data table as a :class:`Figure`; ``where`` and ``table`` name it in the
    ParameterError raised when it lacks a value or a source."""
    try:
        value = float(raw["value"])
        sd = raw.get("sd")
        source = str(raw["source"])
    except (KeyError, TypeError, ValueError) as e:
        raise ParameterError(f"{table}: {where} lacks a value or a source ({e})") from e
    return Figure(
        value=value,
        sd=None if sd is None else float(sd),
        source=source,
        refs=tuple(raw.get("refs", ())),
        published=dict(raw.get("published", {})),
    )


@cache
def _load() -> tuple[dict[str, VehicleClass], dict[str, str], dict[str, str]]:
    table = read_data_table(_DATA)
    sources = sources_of(table)
    aliases = {str(k): str(v) for k, v in table.get("aliases", {}).items()}
    classes: dict[str, VehicleClass] = {}
    for name in table["order"]:
        raw = table["classes"][name]
        figs = {f: figure_from(raw[f], f"{name}.{f}") for f in _FIELDS}
        faces = {
            face: FaceData(
                A=figure_from(raw[face]["A"], f"{name}.{face}.A"),
                B=figure_from(raw[face]["B"], f"{name}.{face}.B"),
            )
            for face in _FACES
        }
        classes[name] = VehicleClass(
            name=name, description=str(raw["description"]), **figs, **faces
        )
    return classes, sources, aliases


SOURCES: dict[str, str] = dict(_load()[1])
"""Source key -> full citation."""

ALIASES: dict[str, str] = dict(_load()[2])
"""Other accepted names -> class name (e.g. "mid_car" -> "sedan")."""


def vehicle_classes() -> dict[str, VehicleClass]:
    """Every built-in class by name, in a stable order (small to large; aliases not repeated)."""
    return dict(_load()[0])


def vehicle_class(name: str) -> VehicleClass:
    """The named class (an alias such as "mid_car" is accepted). Raises ParameterError for an
    unknown name, listing the known ones."""
    classes = _load()[0]
    if not isinstance(name, str):
        raise ParameterError(f"vehicle class name must be a string, got {name!r}")
    key = name.strip().lower()
    key = ALIASES.get(key, key)
    if key not in classes:
        known = ", ".join(list(classes) + [f"{a} (= {t})" for a, t in ALIASES.items()])
        raise ParameterError(f"unknown vehicle class {name!r}: use one of {known}")
    return classes[key]
