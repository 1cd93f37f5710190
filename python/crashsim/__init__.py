"""crashsim: an open 3-D vehicle collision engine for accident reconstruction.

Vehicles are rigid bodies with triangle meshes; when two meshes first overlap a
depth-of-penetration timer starts, and when it expires one pair of impulses is exchanged at
the impulse centroid by the Kudlich-Slibar model. SI units, world z up, body x forward.
"""

from crashsim import units
from crashsim._core import __version__
from crashsim.errors import (
    CrashsimError,
    InitialOverlapError,
    InputError,
    MeshError,
    ParameterError,
    SceneError,
    SimulationError,
)
from crashsim.result import Impact, Result, Trajectory
from crashsim.scene import Scene
from crashsim.units import deg, ft, ft_s, kmh, lb, mph
from crashsim.vehicle import Vehicle

__all__ = [
    "__version__",
    "Vehicle",
    "Scene",
    "Result",
    "Impact",
    "Trajectory",
    "units",
    "mph",
    "kmh",
    "ft",
    "ft_s",
    "lb",
    "deg",
    "CrashsimError",
    "InputError",
    "MeshError",
    "ParameterError",
    "InitialOverlapError",
    "SceneError",
    "SimulationError",
]
