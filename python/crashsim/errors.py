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
"""

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
]
