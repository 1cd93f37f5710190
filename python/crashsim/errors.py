"""The crashsim exception tree. The classes are defined once, in the compiled core.

CrashsimError
├── InputError (also a ValueError): the input is at fault
│   ├── MeshError            empty or broken mesh, unreadable file
│   ├── ParameterError       non-finite or out-of-range number
│   ├── InitialOverlapError  vehicles overlap when the run starts
│   ├── SceneError           a scene-level mistake (unknown or duplicate vehicle)
│   └── StudyError           a study's mistake (unknown parameter path, bad distribution)
└── SimulationError (also a RuntimeError)

PlausibilityWarning (a UserWarning): input that is possible but unlikely for a road vehicle
(a size or density outside road vehicles' ranges: a wrong unit or up axis?).

Every error carries ``loc``, where it happened, outermost first: a tuple of (kind, index,
name) places the engine sets (kinds: "variant", "body", "bodies", "wheel", "zone", "zones",
"part": the ground, a vehicle being built, :func:`vehicle_place`, or its inputs;
"parameter": the value at fault, by the name its message gives it, innermost; "time": the
simulated time in s, as the index, at which a run failed; empty when the error is the whole
input's), and ``message``, the text without the places written before it (a parameter is
named in it with its value; None for errors raised with a text alone). A layer that knows
the names of what the engine numbers (a vehicle's wheels, the ground's zones, the scene's
bodies) gives them with :func:`renamed`, which rebuilds the text from ``loc`` and
``message`` (:func:`text`): no text is parsed.
"""

from collections.abc import Callable
from typing import Any, TypeVar

from crashsim import _core
from crashsim._core import (
    CrashsimError,
    InitialOverlapError,
    InputError,
    MeshError,
    ParameterError,
    SimulationError,
)


class SceneError(InputError):
    """A scene-level mistake: an unknown vehicle, a vehicle added twice, a duplicate name."""


class StudyError(InputError):
    """A mistake in a study (crashsim.studies): an unknown parameter path, a distribution or
    grid with an invalid parameter, conflicting paths. ``key`` is the parameter path at fault
    (None when the mistake is not one key's); the message names it and says how to fix it."""

    def __init__(self, message: str, key: str | None = None) -> None:
        super().__init__(message)
        self.key = key

    def __reduce__(self) -> tuple[object, ...]:  # pickles with its key (Dask sends errors)
        return (type(self), (str(self), self.key))


class PlausibilityWarning(UserWarning):
    """Input that is possible but unlikely for a road vehicle: a size or a density outside
    road vehicles' ranges (crashsim.vehicles.plausibility). The message names the likely
    mistake (a unit, an up axis, the mass) and how to fix it; silence it with
    ``warnings.filterwarnings("ignore", category=crashsim.PlausibilityWarning)`` when the
    vehicle is meant to be so. Impossible input (an inertia no body has, a density above
    any material's) is an error instead."""


Place = tuple[str, Any, Any]
"""One step of an error's ``loc``: (kind, index, name)."""

_E = TypeVar("_E", bound=CrashsimError)


def describe(place: Place) -> str:
    """The engine's text of one place: "wheel 2", "body 0 ("red")", "friction zones 1 and 3",
    "variant 7", "t = 0.125000 s"; "" for a parameter, which the message names (the core's
    own rendering, ``_core.describe_place``)."""
    return _core.describe_place(place)


Naming = Callable[[Place, tuple[Place, ...]], "str | None"]
"""Gives a place's text from the place and the places outside it (a wheel's name depends on
its vehicle); None keeps the engine's text (:func:`describe`), "" drops the place."""


def text(loc: tuple[Place, ...], message: str, name: Naming | None = None) -> str:
    """An error's text as the engine writes it: the text of each place of ``loc`` (outermost
    first; ``name``'s (:data:`Naming`) where it gives one, else :func:`describe`) and ": ",
    then ``message``; a place whose text is "" is not written."""
    where = [None if name is None else name(p, loc[:k]) for k, p in enumerate(loc)]
    where = [describe(p) if t is None else t for p, t in zip(loc, where, strict=True)]
    return "".join(f"{w}: " for w in where if w) + message


def renamed(error: _E, name: Naming | None, suffix: str = "") -> _E:
    """``error`` again (the same class, ``loc`` and ``message``) with its text rebuilt from
    its places, each named by ``name`` (:data:`Naming`), then the message and ``suffix``. An
    error without places, or ``name`` None, keeps its text. (A place further out is added
    with :func:`at`, not as text.)"""
    if error.message is None or name is None:
        written = str(error)
    else:
        written = text(error.loc, error.message, name)
    out = type(error)(written + suffix)
    out.loc = error.loc
    out.message = error.message
    return out


def at(error: _E, place: Place) -> _E:
    """``error`` one place further out, as the engine's ``Error::at`` puts it: ``place``
    first in its ``loc`` and its text (:func:`describe`) first in its text."""
    out = type(error)(text((place,), str(error)))
    out.loc = (place, *error.loc)
    out.message = str(error) if error.message is None else error.message
    return out


def vehicle_place(name: str) -> Place:
    """The place of a vehicle that is not yet in a scene (its own construction and checks):
    the part "vehicle 'red'". In a scene the engine's places name it as a body."""
    return ("part", None, f"vehicle {name!r}")


def naming(**names: Callable[[Any], str | None]) -> Naming:
    """A :data:`Naming` from one function per kind, each given the place's index:
    ``naming(wheel=lambda k: f"wheel {names[k]!r}")``."""

    def name(place: Place, outer: tuple[Place, ...]) -> str | None:
        f = names.get(place[0])
        return None if f is None else f(place[1])

    return name


__all__ = [
    "CrashsimError",
    "InputError",
    "MeshError",
    "ParameterError",
    "InitialOverlapError",
    "SceneError",
    "SimulationError",
    "StudyError",
    "PlausibilityWarning",
    "Place",
    "Naming",
    "describe",
    "text",
    "renamed",
    "at",
    "naming",
]
