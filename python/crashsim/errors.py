"""The crashsim exception tree. The classes are defined once, in the compiled core.

CrashsimError
├── InputError (also a ValueError): the input is at fault
│   ├── MeshError            empty or broken mesh, unreadable file
│   ├── ParameterError       non-finite or out-of-range number
│   ├── InitialOverlapError  vehicles overlap when the run starts
│   └── SceneError           a scene-level mistake (unknown or duplicate vehicle)
└── SimulationError (also a RuntimeError)
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


__all__ = [
    "CrashsimError",
    "InputError",
    "MeshError",
    "ParameterError",
    "InitialOverlapError",
    "SceneError",
    "SimulationError",
]
