"""The deformation report of one vehicle at one exchange (crashsim.analysis.report): the
bounding-box and mesh deformation along the measuring direction, the overlap depth, and the
spring model's maximum and residual crush (SAE 880223)."""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

import numpy as np

from crashsim.analysis import penetration
from crashsim.analysis.report_common import EQUAL_SHARES, Array, _freeze_arrays, _opt, _vec
from crashsim.small_linalg import dot, matmul

if TYPE_CHECKING:
    from crashsim.vehicles.vehicle import Vehicle


@dataclass(frozen=True)
class DeformationReport:
    """One vehicle's deformation at one exchange (all m, along ``direction``).

    ``direction``: the world unit vector the vehicle's deformation is measured along (+n for
    vehicle 1, -n for vehicle 2). ``bounding_box``: from the impulse centroid P to the far
    side of the vehicle's undeformed body-frame bounding box posed at the exchange
    (max over the box's corners of direction.c minus direction.P; the seed's "deformation").
    ``mesh``: from P to the farthest crossing of the ray from P along ``direction`` with the
    vehicle's mesh (the outer surface; the seed's implied maximum crush); None when the ray
    crosses nothing (P outside the mesh on that side, or a hole in an open mesh), with a note.
    ``mesh_crossings``: how many times that ray crosses the mesh. ``overlap_depth``: the
    overlap region's extent along n (region_max - region_min along n; the same for both
    vehicles). Spring model (seed eqs. 34-35): ``crush_share`` of the total crush
    v_n dt_p (k_other / (k1 + k2), or 1/2 when ``crush_share_basis`` says the stiffness is
    unknown); ``max_crush`` = share x v_n x dt_p with v_n the closing speed along n at the
    centroid; ``residual_crush`` from it by SAE 880223 (C_max = 3.5 in + 1.14 C_residual; 0
    below 3.5 in, flagged by ``residual_below_threshold``)."""

    vehicle: str
    direction: Array
    bounding_box: float
    mesh: float | None
    mesh_crossings: int
    overlap_depth: float
    crush_share: float
    crush_share_basis: str
    max_crush: float
    residual_crush: float
    residual_below_threshold: bool
    notes: tuple[str, ...] = ()

    def __post_init__(self) -> None:
        _freeze_arrays(self)

    def to_dict(self) -> dict[str, Any]:
        return {
            "direction": _vec(self.direction),
            "bounding_box": float(self.bounding_box),
            "mesh": _opt(self.mesh),
            "mesh_ray_crossings": int(self.mesh_crossings),
            "overlap_depth": float(self.overlap_depth),
            "spring_model": {
                "share": float(self.crush_share),
                "share_basis": self.crush_share_basis,
                "max_crush": float(self.max_crush),
                "residual_crush": float(self.residual_crush),
                "residual_below_threshold": bool(self.residual_below_threshold),
            },
            "notes": list(self.notes),
        }


def _deformation(
    vehicle: Vehicle,
    position: Array,
    rotation: Array,
    centroid: Array,
    direction: Array,
    overlap_depth: float,
    share: float,
    share_basis: str,
    total_crush: float,
) -> DeformationReport:
    """The deformation figures of one vehicle (see DeformationReport)."""
    notes: list[str] = []
    lo, hi = (np.asarray(a, dtype=np.float64) for a in vehicle.shape.aabb())
    corners = np.array(
        [[x, y, z] for x in (lo[0], hi[0]) for y in (lo[1], hi[1]) for z in (lo[2], hi[2])]
    )
    world_corners = position + matmul(corners, rotation.T)
    bounding_box = float(np.max(dot(world_corners, direction)) - dot(centroid, direction))
    origin_body = matmul(rotation.T, centroid - position)
    ray = matmul(rotation.T, direction)
    hits = np.asarray(vehicle.shape.ray_hits(origin_body, ray), dtype=np.float64)
    mesh = float(hits[-1]) if hits.size else None
    if mesh is None:
        notes.append(
            "no mesh deformation: the ray from the centroid along the measuring direction "
            "crosses no triangle of the mesh (the centroid is outside the vehicle on that "
            "side, or the mesh is open there)"
        )
    max_crush = share * total_crush
    residual = float(penetration.residual_crush_from_max(max_crush))
    below = max_crush < penetration.SAE_880223_INTERCEPT
    if below:
        notes.append(
            f"maximum crush {max_crush:.4f} m is below 3.5 in (0.0889 m): SAE 880223 "
            "predicts no residual crush (0 reported)"
        )
    if share_basis == EQUAL_SHARES:
        notes.append("stiffness unknown: the spring-model crush is split equally")
    return DeformationReport(
        vehicle=vehicle.name,
        direction=direction,
        bounding_box=bounding_box,
        mesh=mesh,
        mesh_crossings=int(hits.size),
        overlap_depth=overlap_depth,
        crush_share=share,
        crush_share_basis=share_basis,
        max_crush=max_crush,
        residual_crush=residual,
        residual_below_threshold=below,
        notes=tuple(notes),
    )
