"""A struck pedestrian's throw distance: read off a run, and the published corridors it is
compared with (docs/human.md, "Throw distance").

Throw distance: the horizontal travel of the pedestrian's whole-body centre of mass (the
segments' CGs weighted by their masses) from its position at the first contact with the
vehicle to its position at rest (or at the end of the run).

Trajectory type (:func:`trajectory_type`): which of Ravani et al.'s post-impact kinematics
(SAE 811024, 1981: wrap, forward projection, fender vault, roof vault, somersault) a run
shows, read off the whole-body centre of mass's path over the vehicle's plan (its mesh's
extent in x and y, its model frame).

The corridors give the throw distance s (m) for a speed v (m/s), with g = 9.80665 m/s^2 and mu
the pedestrian's sliding friction on the road. Each function names the source it was read in;
the primary papers were not read (their first pages and abstracts only), see the docstrings.
"""

from __future__ import annotations

import math
from typing import TYPE_CHECKING

import numpy as np
from numpy.typing import NDArray

from crashsim.analysis.pedestrian import (
    TRAJECTORY_TYPES,
    path_type,
    plan_path_type,
    travel,
    whole_body,
)
from crashsim.errors import ParameterError

if TYPE_CHECKING:
    from crashsim.human.pedestrian import Pedestrian
    from crashsim.result import Result
    from crashsim.vehicles.vehicle import Vehicle

__all__ = [
    "G",
    "TRAJECTORY_TYPES",
    "VKU_THROW_FACTORS",
    "VKU_FRICTION",
    "first_contact_time",
    "plan_path_type",
    "searle_distance",
    "searle_speed",
    "throw_distance",
    "trajectory_type",
    "vku_throw_distance",
]

Array = NDArray[np.float64]

G = 9.80665  # m/s^2, standard gravity

# Throw factor f_w = v_min / v_k (Searle's minimum projection speed over the impact speed),
# for adults, from the 1997 Verkehrsunfall und Fahrzeugtechnik article (vku_throw_distance).
VKU_THROW_FACTORS = {"low front": 0.64, "high front": 0.744}
VKU_FRICTION = 0.66  # the pedestrian-road friction those factors were derived with


def _positive(value: float, name: str, unit: str) -> float:
    v = float(value)
    if not math.isfinite(v) or v <= 0.0:
        raise ParameterError(f"{name} must be a finite number > 0 ({unit}), got {value!r}")
    return v


def _speed(value: float) -> float:
    v = float(value)
    if not math.isfinite(v) or v < 0.0:
        raise ParameterError(f"speed must be a finite number >= 0 (m/s), got {value!r}")
    return v


def searle_distance(speed: float, mu: float) -> tuple[float, float]:
    """Searle's bounds on the total throw distance (flight, bounce and slide to rest, m) of a
    body projected at ``speed`` (m/s) from the ground's level onto a road of friction ``mu``:
    (s_min, s_max) = (v^2 / (2 mu g), (1 + mu^2) v^2 / (2 mu g)).

    Searle & Searle (1983), "The trajectories of pedestrians, motorcycles, motorcyclists, etc.,
    following a road accident", SAE 831622 (27th Stapp Car Crash Conference): the projection
    speed for a total distance s and launch angle theta is v = sqrt(2 mu g s) / (cos theta +
    mu sin theta) (a flight of v^2 sin(2 theta) / g, a landing whose normal impulse takes mu
    times it off the horizontal speed, a slide at mu g); it lies between v_min = sqrt(2 mu g
    s / (1 + mu^2)) (at tan theta = mu) and v_max = sqrt(2 mu g s) (a horizontal launch) for
    launch angles from 0 to 2 atan(mu), where cos theta + mu sin theta >= 1. Inverted: a
    speed v throws between v^2 / (2 mu g) and (1 + mu^2) times that. The paper's first page was read
    (scribd document 457995867); the bounds' form was read in the abstract of the 1997
    article cited in :func:`vku_throw_distance` (v_min = sqrt(2 mu g S0 / (1 + mu^2))) and in
    a public reconstruction-formula collection (v_min as above, v_max = sqrt(2 g f d)).

    The launch height is taken as zero (Searle's equation has a term for it; the CG of a
    pedestrian carried on a bonnet is about 1 m up). Applied with v the vehicle's impact
    speed, as reconstructionists do, it bounds a pedestrian projected at that speed."""
    v = _speed(speed)
    m = _positive(mu, "mu", "the pedestrian-road friction coefficient")
    s_min = v * v / (2.0 * m * G)
    return s_min, (1.0 + m * m) * s_min


def searle_speed(distance: float, mu: float) -> tuple[float, float]:
    """Searle's bounds on the projection speed (m/s) for a total throw ``distance`` (m) on a
    road of friction ``mu``: (sqrt(2 mu g s / (1 + mu^2)), sqrt(2 mu g s)) (the inverse of
    :func:`searle_distance`; same source)."""
    s = _speed(distance)  # >= 0, m
    m = _positive(mu, "mu", "the pedestrian-road friction coefficient")
    v_max = math.sqrt(2.0 * m * G * s)
    return v_max / math.sqrt(1.0 + m * m), v_max


def vku_throw_distance(speed: float, front: str, mu: float = VKU_FRICTION) -> float:
    """The throw distance (m) of an adult struck at ``speed`` (m/s) by a ``front`` "low front"
    or "high front" vehicle, from the throw factor f_w = v_min / v_k: Searle's minimum
    projection speed (:func:`searle_speed`) is f_w times the impact speed, so
    s = (1 + mu^2) (f_w v)^2 / (2 mu g).

    f_w for adults: 64 % for a low front, 74.4 % for a high front (children 72.7 % and
    74.4 %), derived from published test results with mu = 0.66 for the pedestrian sliding on
    the road: "Methoden zur Eingrenzung der Fahrzeuggeschwindigkeit aus der Längswurfweite des
    Fußgängers", Verkehrsunfall und Fahrzeugtechnik 35(5):131-134 (1997), as its abstract in
    the TEMA database states (fid-move.de, record TEMAM97050591519); the article (its authors
    too) was not read. Another ``mu`` applies the same factors on another road (an
    extrapolation: the factors were fitted at 0.66)."""
    if front not in VKU_THROW_FACTORS:
        raise ParameterError(
            f"front = {front!r} is unknown: use one of {', '.join(map(repr, VKU_THROW_FACTORS))}"
        )
    _, s_max = searle_distance(VKU_THROW_FACTORS[front] * _speed(speed), mu)
    return s_max


def first_contact_time(result: Result, vehicle: str, pedestrian: Pedestrian) -> float:
    """The time (s) of the first contact between ``vehicle`` and any of the pedestrian's
    segments: its first overlap in the contact log. Raises ParameterError when they never
    touched."""
    names = {seg.name for seg in pedestrian.segments}
    times = [
        c.time
        for c in result.contacts
        if c.kind == "first_overlap" and vehicle in c.vehicles
        and any(n in names for n in c.vehicles)
    ]
    if not times:
        raise ParameterError(
            f"{vehicle!r} never touched {pedestrian.name!r} in this run: no throw distance "
            "(check the placement, the speed and the duration)"
        )
    return min(times)


def throw_distance(result: Result, vehicle: str, pedestrian: Pedestrian) -> float:
    """The horizontal distance (m) the pedestrian's whole-body CG travelled from its position
    at the first contact with ``vehicle`` to its position at the end of the run (its rest
    position when the run lasted until it stopped)."""
    t0 = first_contact_time(result, vehicle, pedestrian)
    t, cg, _ = whole_body(result, pedestrian)
    return travel(t, cg, t0)



def trajectory_type(result: Result, vehicle: Vehicle, pedestrian: Pedestrian) -> str:
    """The pedestrian's post-impact trajectory type (one of TRAJECTORY_TYPES) after its first
    contact with ``vehicle``: :func:`crashsim.analysis.pedestrian.path_type` of its whole-body
    centre of mass from that instant. Never over the vehicle's plan (x between its mesh's
    rearmost and foremost points, y between its sides, its model frame): "forward projection"
    (pushed ahead of the front); still over it at the end, "carried"; else by where it left
    it for the last time: over the front, "wrap"; behind the rear, "roof vault"; over a side,
    "fender vault". Ravani et al. name the types; these geometric rules are crashsim's
    reading of them (their paper's criteria were not read), and a somersault (a turn in the
    air) is not told apart from the path it takes."""
    t0 = first_contact_time(result, vehicle.name, pedestrian)
    _, cg, _ = whole_body(result, pedestrian)
    return path_type(result, vehicle, cg, t0)
