"""crashsim: an open 3-D vehicle collision engine for accident reconstruction.

Vehicles are rigid bodies with triangle meshes; when two meshes first overlap a
depth-of-penetration timer starts, and when it expires one pair of impulses is exchanged at
the impulse centroid by the Kudlich-Slibar model. SI units inside (m, kg, s, rad); world
frame right-handed with z up; vehicle body frame ISO 8855 (x forward, y left, z up).

    import crashsim as cs
    red = cs.Vehicle.box(length=4.5, width=1.8, height=1.4, mass=1450.0, name="red")
    ...
    result = scene.run(duration=1.0, dt=1e-3)
"""

from crashsim import plots, units
from crashsim._core import __version__
from crashsim.analysis import crosscheck, montecarlo, penetration
from crashsim.analysis.crosscheck import CrossCheck, cross_check
from crashsim.analysis.montecarlo import dtp_montecarlo
from crashsim.analysis.report import Report, build_report
from crashsim.analysis.report import build_report as report
from crashsim.environment import FrictionZone, Ground, Obstacle, surfaces
from crashsim.errors import (
    CrashsimError,
    InitialOverlapError,
    InputError,
    MeshError,
    ParameterError,
    PlausibilityWarning,
    SceneError,
    SimulationError,
    StudyError,
)
from crashsim.human.bicycle import Bicycle
from crashsim.human.cyclist import Cyclist
from crashsim.human.pedestrian import Pedestrian
from crashsim.io import export, scenefile
from crashsim.io.export import export_frames, export_glb
from crashsim.io.viewer import view
from crashsim.joints import CoupledAngle, JointEvent, JointRecord, PassiveMoment
from crashsim.placement import Placement
from crashsim.plots import plot_impact, plot_trajectories
from crashsim.records import (
    ContactEvent,
    Impact,
    RestState,
    SeparationState,
    Trajectory,
    WheelRecord,
)
from crashsim.result import Result
from crashsim.scene import DepthOfPenetrationWarning, RestNotReachedWarning, Scene
from crashsim.studies import Study, monte_carlo, sobol, sweep, tornado
from crashsim.studies.fit import FitError, FitResult, fit
from crashsim.units import (
    deg,
    ft,
    ft_s,
    kmh,
    lb,
    mph,
    to_deg,
    to_ft,
    to_ft_s,
    to_kmh,
    to_lb,
    to_mph,
)
from crashsim.vehicles import generator, meshio, vehicle_data
from crashsim.vehicles.inputs import Brake, DriverInputs
from crashsim.vehicles.meshio import MeshQuality, load_mesh, mesh_quality
from crashsim.vehicles.stiffness import FaceStiffness, Stiffness
from crashsim.vehicles.trailer import Trailer
from crashsim.vehicles.trucks import rigid_truck, tractor
from crashsim.vehicles.vehicle import Vehicle
from crashsim.vehicles.vehicle_data import VehicleClass, vehicle_class, vehicle_classes
from crashsim.vehicles.wheels import Tyre, Wheels

__all__ = [
    "__version__",
    "Vehicle",
    "Pedestrian",
    "Cyclist",
    "Bicycle",
    "Trailer",
    "tractor",
    "rigid_truck",
    "Scene",
    "Placement",
    "DepthOfPenetrationWarning",
    "Result",
    "Impact",
    "Trajectory",
    "ContactEvent",
    "RestState",
    "SeparationState",
    "WheelRecord",
    "JointRecord",
    "JointEvent",
    "PassiveMoment",
    "CoupledAngle",
    "RestNotReachedWarning",
    "Study",
    "sweep",
    "fit",
    "FitError",
    "FitResult",
    "monte_carlo",
    "tornado",
    "sobol",
    "Ground",
    "FrictionZone",
    "Obstacle",
    "Wheels",
    "Tyre",
    "DriverInputs",
    "Brake",
    "surfaces",
    "Stiffness",
    "FaceStiffness",
    "VehicleClass",
    "vehicle_class",
    "vehicle_classes",
    "MeshQuality",
    "load_mesh",
    "mesh_quality",
    "Report",
    "report",
    "build_report",
    "plot_impact",
    "plot_trajectories",
    "export_glb",
    "export_frames",
    "view",
    "dtp_montecarlo",
    "CrossCheck",
    "cross_check",
    "crosscheck",
    "export",
    "generator",
    "meshio",
    "montecarlo",
    "penetration",
    "plots",
    "scenefile",
    "units",
    "vehicle_data",
    "mph",
    "kmh",
    "ft",
    "ft_s",
    "lb",
    "deg",
    "to_mph",
    "to_kmh",
    "to_ft",
    "to_ft_s",
    "to_lb",
    "to_deg",
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
