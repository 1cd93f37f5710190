"""The tyre on a vehicle's wheels: its law and parameters, checked by the engine when it is made
(:class:`crashsim._core.Tyre`); docs/vehicle-model.md gives every default and its source."""

from __future__ import annotations

from dataclasses import dataclass, fields
from typing import Any

from crashsim import _core
from crashsim.errors import ParameterError, at
from crashsim.vehicles.numbers import finite as _number

__all__ = ["COMBINED_SLIP_LAWS", "TYRE_MODELS", "TYRE_PARAMETERS", "Tyre"]

TYRE_MODELS = ("linear", "linear_friction_scaled", "magic_formula")
"""The tyre models: the reconstruction programs' linear tyre, crashsim's law before 2026-11
(mu Fz at the saturation angle on every road) and Pacejka's Magic Formula."""

COMBINED_SLIP_LAWS = ("braking_priority", "circle", "nicolas_comstock")
"""How a wheel's longitudinal and lateral forces share the friction (docs/vehicle-model.md)."""


@dataclass(frozen=True)
class Tyre:
    """The tyre on every wheel of a vehicle (SI; the engine checks every value when it is
    made, :class:`crashsim._core.Tyre`).

    ``model``:

    - "linear" (default): the reconstruction programs' linear tyre, lateral force
      ``cornering * Fz * alpha`` (``cornering`` the cornering coefficient, 1/rad; default 1
      per 10 deg) capped at the friction the longitudinal force leaves; or give the
      ``saturation_angle`` (rad), its equivalent at mu = 1 (``cornering = 1 / angle``);
    - "linear_friction_scaled": crashsim's law before 2026-11, mu Fz at ``saturation_angle``
      (rad, default 10 deg) on every road (softer on slippery roads);
    - "magic_formula": Pacejka's D sin(C atan(B a - E (B a - atan(B a)))) with factors ``b``
      (1/rad), ``c``, ``e`` at mu = 1 and D = mu Fz by similarity.

    ``relaxation_length`` (m), ``rolling_resistance`` (force / load; default 0, as the
    reconstruction programs: give 0.010-0.015 for passenger tyres on asphalt), ``combined``
    ("braking_priority", the default: the brake force kept and the lateral force from what the
    friction leaves; "circle": both scaled onto the friction circle; or "nicolas_comstock":
    Brach and Brach's modified Nicolas-Comstock combination of the pure-slip forces, capped at
    mu Fz), ``load_sensitivity`` (cornering stiffness proportional to Fz^(1 - e); default 0),
    ``longitudinal_stiffness`` (nicolas_comstock only: the longitudinal slip stiffness per
    unit load, 1 per unit slip; default the cornering stiffness). A field left None takes the
    engine's default (:meth:`resolved` shows every value as run).
    """

    model: str = "linear"
    cornering: float | None = None
    saturation_angle: float | None = None
    b: float | None = None
    c: float | None = None
    e: float | None = None
    relaxation_length: float | None = None
    rolling_resistance: float | None = None
    combined: str | None = None
    load_sensitivity: float | None = None
    longitudinal_stiffness: float | None = None

    def __post_init__(self) -> None:
        if not isinstance(self.model, str):
            raise ParameterError(f"tyre model must be a string, got {self.model!r}")
        units = {
            "cornering": "1/rad",
            "saturation_angle": "rad",
            "b": "1/rad",
            "c": "1",
            "e": "1",
            "relaxation_length": "m",
            "rolling_resistance": "1",
            "load_sensitivity": "1",
            "longitudinal_stiffness": "1",
        }
        for name, unit in units.items():
            value = getattr(self, name)
            if value is not None:
                object.__setattr__(self, name, _number(value, f"tyre {name}", unit))
        if self.combined is not None and not isinstance(self.combined, str):
            raise ParameterError(f"tyre combined must be a string, got {self.combined!r}")
        try:
            core = _core.Tyre(self.model, **self._given())
        except ParameterError as err:
            raise at(err, ("part", None, "tyre")) from err
        object.__setattr__(self, "_core", core)

    def _given(self) -> dict[str, Any]:
        return {k: getattr(self, k) for k in TYRE_PARAMETERS[1:] if getattr(self, k) is not None}

    def to_core(self) -> _core.Tyre:
        """The engine's tyre (checked when this Tyre was made)."""
        core: _core.Tyre = self.__dict__["_core"]
        return core

    def resolved(self) -> dict[str, Any]:
        """Every parameter as the engine runs it: the given ones and the engine's defaults
        for the others (model, cornering 1/rad or saturation_angle rad or b, c, e;
        relaxation_length m, rolling_resistance, combined, load_sensitivity; with combined
        "nicolas_comstock" its longitudinal_stiffness, None for the cornering stiffness)."""
        return dict(self.to_core().resolved())

    def __reduce__(self) -> tuple[Any, ...]:
        return (_tyre_from, (self.model, self._given()))

    @classmethod
    def coerce(cls, value: Tyre | dict[str, Any] | None) -> Tyre:
        """A Tyre from a Tyre, a dict of its fields, or None (the default tyre)."""
        if value is None:
            return cls()
        if isinstance(value, Tyre):
            return value
        if isinstance(value, dict):
            unknown = sorted(set(value) - {f for f in cls.__dataclass_fields__})
            if unknown:
                raise ParameterError(
                    f"unknown tyre parameter(s) {', '.join(unknown)}: the tyre's parameters are "
                    f"{', '.join(cls.__dataclass_fields__)}"
                )
            return cls(**value)
        raise ParameterError(f"tyre must be a crashsim.Tyre or a dict, got {value!r}")


def _tyre_from(model: str, given: dict[str, Any]) -> Tyre:
    return Tyre(model, **given)


TYRE_PARAMETERS = tuple(f.name for f in fields(Tyre))
"""The tyre's parameters in order, "model" first: the scene file's [vehicles.wheels.tyre]
keys and the engine's keywords after the model."""
