"""The impact report of one impulse exchange (crashsim.analysis.report): per vehicle its
delta-V (world, body, event-data-recorder components), PDOF and clock direction, yaw-rate
change, speeds, kinetic-energy changes, energy share and EES; the obstacle's side; the
exchange's depth of penetration, overlap and energy split. Frames and signs: the module
docstring of crashsim.analysis.report."""

from __future__ import annotations

import math
from dataclasses import dataclass, field, fields
from typing import TYPE_CHECKING, Any

import numpy as np
from numpy.typing import ArrayLike

from crashsim.analysis import penetration
from crashsim.analysis.deformation import DeformationReport, _deformation
from crashsim.analysis.report_common import (
    BY_STIFFNESS,
    EQUAL_SHARES,
    FACE_SIDES,
    FULL,
    RIGID_OBSTACLE,
    SLIDING,
    UNKNOWN,
    Array,
    _freeze_arrays,
    _mat,
    _opt,
    _vec,
)
from crashsim.errors import ParameterError, SceneError
from crashsim.small_linalg import dot, matmul, norm

if TYPE_CHECKING:
    from crashsim.records import Impact
    from crashsim.result import Result


# -- figures ---------------------------------------------------------------------------------

_FIGURE = "figure"  # dataclass field metadata: (label, unit, digits shown)


def figure(label: str, unit: str, digits: int) -> Any:
    """An ImpactReport field that is one figure of the impact: report.json lists it under
    the impact's ``figures`` (name, label, unit, digits, value), and the text report and the
    case page show it from that alone (report_text.py and report.js render every figure the
    same way). ``unit`` "" for a pure number; its value None (JSON null, the default) where
    undefined."""
    return field(default=None, metadata={_FIGURE: (label, unit, digits)})


# -- PDOF and clock -------------------------------------------------------------------------


def pdof(delta_v_body: ArrayLike) -> float | None:
    """The SAE principal direction of force (deg, in [0, 360)) from a delta-V in the ISO body
    frame (x forward, y left, z up; m/s): the direction FROM which the force acts, in the
    vehicle's x-y plane, clockwise seen from above from straight ahead (0 ahead, 90 right,
    180 behind, 270 left). The force is along delta-V, so it comes from -delta-V:
    PDOF = atan2(dv_y, -dv_x). None when delta-V has no horizontal part (exactly, or below
    1e-12 of |delta-V|)."""
    dv = np.asarray(delta_v_body, dtype=np.float64).reshape(-1)
    if dv.size != 3 or not np.all(np.isfinite(dv)):
        raise ParameterError(f"delta_v_body must be 3 finite numbers (m/s), got {dv.tolist()}")
    horizontal = math.hypot(dv[0], dv[1])
    if horizontal == 0.0 or horizontal <= 1e-12 * float(norm(dv)):
        return None
    angle = math.degrees(math.atan2(dv[1], -dv[0])) % 360.0
    return 0.0 if angle >= 360.0 else angle  # -1e-17 % 360 is 360.0 in floating point


def clock_direction(pdof_deg: float | None) -> int | None:
    """The clock direction (1-12) of a PDOF in degrees: the nearest hour, 30 deg each,
    12 = 0 deg, 3 = 90, 6 = 180, 9 = 270; a PDOF half-way between two hours rounds up
    (15 deg -> 1). None for None."""
    if pdof_deg is None:
        return None
    if not math.isfinite(pdof_deg):
        raise ParameterError(f"PDOF = {pdof_deg} deg is invalid: give a finite angle")
    hour = math.floor((pdof_deg % 360.0) / 30.0 + 0.5) % 12
    return 12 if hour == 0 else hour


@dataclass(frozen=True)
class VehicleImpactReport:
    """One vehicle's side of one exchange (SI, world frame unless named otherwise).

    ``role`` 1 or 2 (vehicle 1 or 2 of the pair). ``centroid_body``: the impulse centroid in
    this vehicle's ISO body frame at the exchange (m from the CG). ``impulse``: the impulse
    on this vehicle (N s). ``delta_v``: world (m/s); ``delta_v_body``: ISO body frame at the
    exchange pose; ``longitudinal`` (+forward), ``lateral`` (+RIGHT, = -body y) and
    ``vertical`` (+up) are the event-data-recorder components. ``pdof_deg`` (SAE, [0, 360))
    and ``clock`` (1-12), None without a horizontal delta-V. ``yaw_rate_change``: deg/s,
    world z, + counter-clockwise seen from above; ``delta_omega``: the whole change, world,
    rad/s. ``speed_before`` / ``speed_after``: |velocity| of the CG (m/s).
    ``translational_energy_change`` / ``rotational_energy_change``: this vehicle's kinetic
    energy after minus before (J; the rotational part with the world inertia at the
    exchange). ``energy``: its share of the dissipated energy by stiffness (J) and ``ees``
    = sqrt(2 energy / mass) (m/s), both None when the stiffness is unknown."""

    name: str
    role: int
    mass: float
    struck_face: str
    effective_mass: float
    spring_rate: float | None
    centroid_body: Array
    impulse: Array
    delta_v: Array
    delta_v_body: Array
    longitudinal: float
    lateral: float
    vertical: float
    delta_v_magnitude: float
    pdof_deg: float | None
    clock: int | None
    yaw_rate_change: float
    delta_omega: Array
    velocity_before: Array
    velocity_after: Array
    speed_before: float
    speed_after: float
    translational_energy_change: float
    rotational_energy_change: float
    energy: float | None
    ees: float | None
    deformation: DeformationReport

    def __post_init__(self) -> None:
        _freeze_arrays(self)

    def to_dict(self) -> dict[str, Any]:
        return {
            "name": self.name,
            "role": int(self.role),
            "mass": float(self.mass),
            "struck_face": self.struck_face,
            "effective_mass": float(self.effective_mass),
            "spring_rate": _opt(self.spring_rate),
            "centroid_body": _vec(self.centroid_body),
            "impulse": _vec(self.impulse),
            "delta_v": {
                "world": _vec(self.delta_v),
                "body": _vec(self.delta_v_body),
                "longitudinal": float(self.longitudinal),
                "lateral": float(self.lateral),
                "vertical": float(self.vertical),
                "magnitude": float(self.delta_v_magnitude),
            },
            "pdof_deg": _opt(self.pdof_deg),
            "clock": None if self.clock is None else int(self.clock),
            "yaw_rate_change_deg_s": float(self.yaw_rate_change),
            "delta_omega_world": _vec(self.delta_omega),
            "velocity_before": _vec(self.velocity_before),
            "velocity_after": _vec(self.velocity_after),
            "speed_before": float(self.speed_before),
            "speed_after": float(self.speed_after),
            "kinetic_energy_change": {
                "translational": float(self.translational_energy_change),
                "rotational": float(self.rotational_energy_change),
            },
            "energy": {"share": _opt(self.energy), "ees": _opt(self.ees)},
            "deformation": self.deformation.to_dict(),
        }


@dataclass(frozen=True)
class ObstacleImpactReport:
    """The fixed obstacle's side of an exchange with a vehicle: ``name``, ``role`` (1 or 2
    in the pair), ``struck_face`` (the engine's name of the face of its own frame whose
    stiffness is taken: front +x, rear -x, left +y, right -y) and ``struck_side`` (the same
    as the side of its frame: "+x", "-x", "+y", "-y"; the words a reader is given, since a
    pole has no front or rear), ``spring_rate`` (k = B W, N/m; None without stiffness:
    then it is rigid), ``centroid_body`` (the centroid in the obstacle's frame, m). It has
    an infinite mass (``effective_mass`` is None in the JSON), never moves and has no
    delta-V."""

    name: str
    role: int
    struck_face: str
    spring_rate: float | None
    centroid_body: Array

    def __post_init__(self) -> None:
        _freeze_arrays(self)

    @property
    def struck_side(self) -> str:
        return FACE_SIDES[self.struck_face]

    def to_dict(self) -> dict[str, Any]:
        return {
            "name": self.name,
            "role": int(self.role),
            "struck_face": self.struck_face,
            "struck_side": self.struck_side,
            "effective_mass": None,
            "spring_rate": _opt(self.spring_rate),
            "centroid_body": _vec(self.centroid_body),
        }


@dataclass(frozen=True)
class ImpactReport:
    """One impulse exchange (SI, world frame).

    ``number``: 1, 2, ... in time order. ``vehicles``: (vehicle 1, vehicle 2).
    ``first_contact_time`` (the timer's start: first overlap, or closing again for a
    ``secondary`` exchange) and ``exchange_time`` (s). ``depth_of_penetration`` (s) and its
    ``depth_of_penetration_mode`` ("fixed": the pair's parameter; "auto": sqrt(m'/k') at the
    exchange); ``reduced_mass`` m' (kg) of the effective masses along n; ``series_stiffness``
    k' = k1 k2 / (k1 + k2) (N/m, None without stiffness; the vehicle's k against a rigid
    obstacle) and ``implied_depth_of_penetration``
    sqrt(m'/k') (s, None without stiffness). ``centroid`` and ``normal`` (unit, 1 -> 2);
    ``contact_frame`` rows n, t, b. ``impulse`` on vehicle 2 (N s) and its magnitude.
    ``impact_type`` "full" or "sliding". ``closing_speed``: the normal relative velocity at
    the centroid before the exchange (m/s, > 0 closing). ``energy_dissipated`` (J) and
    ``energy_split_basis`` ("stiffness", "unknown", or "rigid obstacle": a fixed obstacle
    without stiffness data for both parties takes none of the crush and energy).
    ``overlap_depth`` (along n) and ``overlap_width`` (along t), m. Figures (see
    ``figure``): ``restitution_along_normal`` -(u' . n) / (u . n), the normal relative
    velocity at the centroid after over before (None when not closing), and
    ``impulse_ratio`` |J_t| / J_n, the impulse's tangential part over its normal part (None
    without a compressive normal part; a sliding impact's is the pair's friction).
    ``parties``: the
    VehicleImpactReports of the moving vehicles, vehicle 1 first (one when the other party
    is a fixed obstacle, described by ``obstacle``: its mass is infinite, so m' is the
    vehicle's effective mass). ``notes``: the engine's remarks and the report's."""

    number: int
    vehicles: tuple[str, str]
    secondary: bool
    first_contact_time: float
    exchange_time: float
    depth_of_penetration: float
    depth_of_penetration_mode: str
    reduced_mass: float
    series_stiffness: float | None
    implied_depth_of_penetration: float | None
    centroid: Array
    normal: Array
    contact_frame: Array
    impulse: Array
    impulse_magnitude: float
    impact_type: str
    closing_speed: float
    energy_dissipated: float
    energy_split_basis: str
    overlap_depth: float
    overlap_width: float
    region_min: Array
    region_max: Array
    parties: tuple[VehicleImpactReport, ...]
    notes: tuple[str, ...] = ()
    obstacle: ObstacleImpactReport | None = None
    restitution_along_normal: float | None = figure("restitution along n (-u'.n / u.n)", "", 4)
    impulse_ratio: float | None = figure("impulse ratio (|J_t| / J_n)", "", 4)

    def __post_init__(self) -> None:
        _freeze_arrays(self)

    def vehicle(self, name: str) -> VehicleImpactReport:
        """The per-vehicle part of a named vehicle."""
        for p in self.parties:
            if p.name == name:
                return p
        raise SceneError(f"vehicle {name!r} is not in impact {self.number} {self.vehicles}")

    def figures(self) -> list[dict[str, Any]]:
        """The impact's figures (the fields declared with ``figure``) in declaration order:
        each its ``name``, ``label``, ``unit``, the ``digits`` shown and its ``value``."""
        out = []
        for f in fields(self):
            if _FIGURE in f.metadata:
                label, unit, digits = f.metadata[_FIGURE]
                value = _opt(getattr(self, f.name))
                out.append(
                    {"name": f.name, "label": label, "unit": unit, "digits": digits, "value": value}
                )
        return out

    @property
    def how_depth_of_penetration(self) -> str:
        """A sentence saying where dt_p came from."""
        if self.depth_of_penetration_mode == "auto":
            return (
                "auto: sqrt(m'/k') at the exchange, m' the reduced effective mass along n, "
                "k' the series stiffness of the struck faces (k = B W), at most 60 ms"
            )
        return "fixed: the pair's depth_of_penetration parameter"

    def to_dict(self) -> dict[str, Any]:
        return {
            "number": int(self.number),
            "vehicles": list(self.vehicles),
            "secondary": bool(self.secondary),
            "first_contact_time": float(self.first_contact_time),
            "exchange_time": float(self.exchange_time),
            "depth_of_penetration": {
                "value": float(self.depth_of_penetration),
                "mode": self.depth_of_penetration_mode,
                "how": self.how_depth_of_penetration,
                "reduced_effective_mass": float(self.reduced_mass),
                "series_stiffness": _opt(self.series_stiffness),
                "implied_by_spring_model": _opt(self.implied_depth_of_penetration),
            },
            "centroid": {
                "world": _vec(self.centroid),
                "body": {
                    n: _vec(
                        self.obstacle.centroid_body
                        if self.obstacle is not None and n == self.obstacle.name
                        else self.vehicle(n).centroid_body
                    )
                    for n in self.vehicles
                },
            },
            "normal": _vec(self.normal),
            "contact_frame": _mat(self.contact_frame),
            "impulse": {"on_vehicle_2": _vec(self.impulse), "magnitude": self.impulse_magnitude},
            "impact_type": self.impact_type,
            "closing_speed": float(self.closing_speed),
            "struck_faces": {
                n: (
                    self.obstacle.struck_face
                    if self.obstacle is not None and n == self.obstacle.name
                    else self.vehicle(n).struck_face
                )
                for n in self.vehicles
            },
            "overlap": {
                "depth_along_normal": float(self.overlap_depth),
                "width": float(self.overlap_width),
                "region_min": _vec(self.region_min),
                "region_max": _vec(self.region_max),
            },
            "energy": {
                "dissipated": float(self.energy_dissipated),
                "split_basis": self.energy_split_basis,
            },
            "figures": self.figures(),
            "parties": [p.to_dict() for p in self.parties],
            "notes": list(self.notes),
            **({} if self.obstacle is None else {"obstacle": self.obstacle.to_dict()}),
        }


def _impact_report(result: Result, impact: Impact, number: int) -> ImpactReport:
    names = impact.vehicles
    n = np.asarray(impact.normal, dtype=np.float64)
    p = np.asarray(impact.centroid, dtype=np.float64)
    e = float(impact.energy_dissipated)
    rates = impact.spring_rates
    k = None if rates is None else (float(rates[names[0]]), float(rates[names[1]]))
    m_eff = (float(impact.effective_mass[names[0]]), float(impact.effective_mass[names[1]]))
    if impact.obstacle is not None:  # infinite mass: m' = m1 m2 / (m1 + m2) -> the vehicle's
        reduced = m_eff[1] if names[0] == impact.obstacle else m_eff[0]
    else:
        reduced = float(penetration.reduced_mass(*m_eff))
    notes = list(impact.notes)
    split = _EnergySplit.of(impact, k, reduced, notes)
    overlap_depth = float(impact.region_max[0] - impact.region_min[0])  # row 0 of the frame: n
    v_n = float(impact.closing_speed)
    total_crush = v_n * float(impact.depth_of_penetration)
    if total_crush < 0.0:
        notes.append(
            f"closing speed {v_n:.6g} m/s is not closing: spring-model crush reported as 0"
        )
        total_crush = 0.0
    parties = []
    obstacle = None
    for role, name in enumerate(names, start=1):
        position, rotation = (
            np.asarray(a, dtype=np.float64) for a in result.pose(name, impact.time)
        )
        if name == impact.obstacle:
            obstacle = ObstacleImpactReport(
                name=name,
                role=role,
                struck_face=str(impact.struck_faces.get(name, UNKNOWN)),
                spring_rate=split.party_rates[role - 1],
                centroid_body=matmul(rotation.T, p - position),
            )
            continue
        vehicle = result.vehicle(name)
        direction = n if role == 1 else -n
        deformation = _deformation(
            vehicle,
            position,
            rotation,
            p,
            direction,
            overlap_depth,
            split.shares[role - 1],
            split.crush_basis,
            total_crush,
        )
        party = _vehicle_party(impact, name, vehicle, role, position, rotation, p, e, m_eff, split,
                               deformation)  # fmt: skip
        parties.append(party)
    return ImpactReport(
        number=number,
        vehicles=names,
        secondary=bool(impact.secondary),
        first_contact_time=float(impact.first_contact_time),
        exchange_time=float(impact.time),
        depth_of_penetration=float(impact.depth_of_penetration),
        depth_of_penetration_mode=str(impact.depth_of_penetration_mode),
        reduced_mass=reduced,
        series_stiffness=split.series,
        implied_depth_of_penetration=split.implied,
        centroid=p,
        normal=n,
        contact_frame=np.asarray(impact.contact_frame, dtype=np.float64),
        impulse=np.asarray(impact.impulse, dtype=np.float64),
        impulse_magnitude=float(norm(impact.impulse)),
        impact_type=SLIDING if impact.sliding else FULL,
        closing_speed=v_n,
        energy_dissipated=e,
        energy_split_basis=split.basis,
        overlap_depth=overlap_depth,
        overlap_width=float(impact.overlap_width),
        region_min=np.asarray(impact.region_min, dtype=np.float64),
        region_max=np.asarray(impact.region_max, dtype=np.float64),
        restitution_along_normal=_restitution_along_normal(impact),
        impulse_ratio=_impulse_ratio(impact),
        parties=tuple(parties),
        notes=tuple(notes),
        obstacle=obstacle,
    )


def _restitution_along_normal(impact: Impact) -> float | None:
    """-(u' . n) / (u . n) at the centroid (u, u' the relative velocity of 1 with respect to
    2 before and after, m/s); None when the bodies were not closing along n."""
    n = impact.normal
    before = float(dot(impact.relative_velocity_before, n))
    return -float(dot(impact.relative_velocity_after, n)) / before if before > 0.0 else None


def _impulse_ratio(impact: Impact) -> float | None:
    """|J_t| / J_n of the impulse J on vehicle 2 (J_n = J . n, J_t = J - J_n n); None when
    J_n is not positive (no compressive normal part)."""
    n = np.asarray(impact.normal, dtype=np.float64)
    j = np.asarray(impact.impulse, dtype=np.float64)
    j_n = float(dot(j, n))
    return float(norm(j - j_n * n)) / j_n if j_n > 0.0 else None


@dataclass(frozen=True)
class _EnergySplit:
    """How an impact's crush and dissipated energy are shared between its two parties, from
    their spring rates k = B W (N/m; None without data)."""

    series: float | None  # N/m: k' (None: unknown)
    implied: float | None  # s: sqrt(m'/k') (None: unknown)
    party_rates: tuple[float | None, float | None]  # N/m: each party's k as reported
    shares: tuple[float, float]  # of the energy and crush, vehicle 1's and 2's
    basis: str  # the energy split's
    crush_basis: str  # the crush split's

    @classmethod
    def of(
        cls,
        impact: Impact,
        k: tuple[float, float] | None,
        reduced: float,
        notes: list[str],
    ) -> _EnergySplit:
        """The split of ``impact`` with the parties' rates ``k`` and the reduced mass (kg);
        appends to ``notes`` why it is rigid or unknown."""
        names = impact.vehicles
        series: float | None = None
        implied: float | None = None
        # each party's k = B W as reported (None without data, or for a rigid obstacle)
        party_rates: tuple[float | None, float | None] = (None, None) if k is None else k
        if impact.obstacle is not None and (k is None or math.isinf(max(k))):
            # A fixed obstacle without stiffness data is rigid (the engine's infinite rate):
            # the vehicle takes the whole crush and energy (its EES is then the equivalent
            # barrier speed); with the vehicle's B W, k' is that and sqrt(m'/k') its spring's
            # time.
            vehicle_first = names[0] != impact.obstacle
            shares = (1.0, 0.0) if vehicle_first else (0.0, 1.0)
            basis, crush_basis = RIGID_OBSTACLE, RIGID_OBSTACLE
            if k is not None:
                series = k[0] if vehicle_first else k[1]
                implied = math.sqrt(reduced / series)
                party_rates = (series, None) if vehicle_first else (None, series)
            notes.append(
                f"{impact.obstacle} taken as rigid (no stiffness data): the vehicle takes all "
                "the crush and dissipated energy"
            )
        elif k is not None and k[0] > 0.0 and k[1] > 0.0:
            series = float(penetration.series_stiffness(*k))
            implied = math.sqrt(reduced / series)
            # E1 = E k2 / (k1 + k2): the softer vehicle absorbs more (equal spring forces)
            shares = (k[1] / (k[0] + k[1]), k[0] / (k[0] + k[1]))
            basis, crush_basis = BY_STIFFNESS, BY_STIFFNESS
        else:
            party_rates = (None, None)
            shares, basis, crush_basis = (0.5, 0.5), UNKNOWN, EQUAL_SHARES
            notes.append("stiffness unknown: the dissipated energy is not split, no EES")
        return cls(series, implied, party_rates, shares, basis, crush_basis)


def _vehicle_party(
    impact: Impact,
    name: str,
    vehicle: Any,
    role: int,
    position: Array,
    rotation: Array,
    p: Array,
    e: float,
    m_eff: tuple[float, float],
    split: _EnergySplit,
    deformation: DeformationReport,
) -> VehicleImpactReport:
    """A vehicle's part of the impact (``role`` 1 or 2; posed at the exchange: world
    ``position`` m, body-to-world ``rotation``; ``p`` the centroid, m, world; ``e`` the
    dissipated energy, J): its delta-V, PDOF, velocities, energy changes, share and EES."""
    dv = np.asarray(impact.delta_v[name], dtype=np.float64)
    # the engine's EDR frame and PDOF (events.rs): a batch's columns are the same bits
    dv_body = np.asarray(impact.delta_v_body[name], dtype=np.float64)
    pdof_deg = impact.pdof_deg[name]
    v0 = np.asarray(impact.velocity_before[name], dtype=np.float64)
    v1 = np.asarray(impact.velocity_after[name], dtype=np.float64)
    w0 = np.asarray(impact.angular_velocity_before[name], dtype=np.float64)
    w1 = np.asarray(impact.angular_velocity_after[name], dtype=np.float64)
    inertia_body = np.asarray(vehicle.inertia, dtype=np.float64)
    inertia_world = matmul(matmul(rotation, inertia_body), rotation.T)
    mass = float(vehicle.mass)
    share_energy = None if split.basis == UNKNOWN else e * split.shares[role - 1]
    ees = None if share_energy is None else math.sqrt(2.0 * max(share_energy, 0.0) / mass)
    return VehicleImpactReport(
        name=name,
        role=role,
        mass=mass,
        struck_face=str(impact.struck_faces.get(name, UNKNOWN)),
        effective_mass=m_eff[role - 1],
        spring_rate=split.party_rates[role - 1],
        centroid_body=matmul(rotation.T, p - position),
        impulse=np.asarray(impact.impulse_on(name), dtype=np.float64),
        delta_v=dv,
        delta_v_body=dv_body,
        longitudinal=float(dv_body[0]),
        lateral=float(-dv_body[1]),
        vertical=float(dv_body[2]),
        delta_v_magnitude=impact.speed_change(name),
        pdof_deg=pdof_deg,
        clock=clock_direction(pdof_deg),
        yaw_rate_change=math.degrees(float(w1[2] - w0[2])),
        delta_omega=w1 - w0,
        velocity_before=v0,
        velocity_after=v1,
        speed_before=float(norm(v0)),
        speed_after=float(norm(v1)),
        translational_energy_change=0.5 * mass * float(dot(v1, v1) - dot(v0, v0)),
        rotational_energy_change=0.5
        * float(dot(w1, matmul(inertia_world, w1)) - dot(w0, matmul(inertia_world, w0))),
        energy=share_energy,
        ees=ees,
        deformation=deformation,
    )
