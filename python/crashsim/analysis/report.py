"""Reports a reconstructionist can use: per impulse exchange the impact report (delta-V, PDOF,
clock direction, yaw-rate change, energy and its split, EES) and the deformation report
(bounding-box and mesh deformation, overlap depth, spring-model maximum and residual crush),
as a text table and as versioned JSON (schema ``crashsim-report`` version 1,
``crashsim/analysis/schema/report-1.schema.json``; every field, unit, frame and sign:
docs/report.md).

    report = crashsim.report(result)    # = crashsim.analysis.report.build_report(result)
    print(report)                       # the text table
    report.write_json("case.json")      # the JSON report

Frames and signs. World: right-handed, z up, SI. Vehicle body frame: ISO 8855 (origin at the
CG, x forward, y left, z up), posed at the exchange instant. The normal n (unit, world) points
from vehicle 1 into vehicle 2; the impulse J (N s, world) acts on vehicle 2 and -J on vehicle 1.
Event-data-recorder components: longitudinal +forward (body x), lateral +RIGHT (-body y).
PDOF (SAE J224): the direction FROM which the force acts on the vehicle, in its horizontal
(body x-y) plane, degrees clockwise seen from above from straight ahead: 0 = from ahead,
90 = from the right, 180 = from behind, 270 = from the left, in [0, 360). Clock direction:
the PDOF to the nearest hour, 12 = 0 deg, 3 = 90 deg (half hours round up). Yaw-rate change:
the world z component of the change of angular velocity, deg/s, + counter-clockwise seen from
above.

The parts live beside this module: impact_report.py (an exchange, each vehicle's figures),
deformation.py (the crush), report_json.py and report_text.py (the JSON's records and the
text's lines), report_common.py (what they share); their public names are re-exported here.
"""

from __future__ import annotations

import json
from os import PathLike
from typing import TYPE_CHECKING, Any

from crashsim import _core
from crashsim.analysis.deformation import DeformationReport
from crashsim.analysis.engagements import WHY_SECONDARY, Engagement, engagements
from crashsim.analysis.impact_report import (
    ImpactReport,
    ObstacleImpactReport,
    VehicleImpactReport,
    _impact_report,
    clock_direction,
    pdof,
)
from crashsim.analysis.joints import (
    ArticulationEvent,
    JointReport,
    articulation_events,
    articulation_lines,
    joint_lines,
    joint_reports,
)
from crashsim.analysis.pedestrian import (
    PedestrianReport,
    pedestrian_lines,
    pedestrian_reports,
    person_bodies,
)
from crashsim.analysis.report_common import _plain
from crashsim.analysis.report_json import (
    CONVENTIONS,
    SCHEMA_NAME,
    SCHEMA_VERSION,
    UNITS,
    _engagement_record,
    _scene_record,
    report_schema,
)
from crashsim.analysis.report_text import (
    _engagement_lines,
    _impact_lines,
    _table,
    _vehicle_data_lines,
)
from crashsim.analysis.runout import RunOutReport, run_out, run_out_lines
from crashsim.errors import SceneError

if TYPE_CHECKING:
    from crashsim.result import Result

__all__ = [
    "SCHEMA_NAME",
    "SCHEMA_VERSION",
    "DeformationReport",
    "ImpactReport",
    "JointReport",
    "ObstacleImpactReport",
    "Report",
    "RunOutReport",
    "VehicleImpactReport",
    "build_report",
    "clock_direction",
    "pdof",
    "report_schema",
]


def build_report(result: Result) -> Report:
    """The report of a run (a Result that keeps its scene, as Scene.run returns it)."""
    if result.scene is None:
        raise SceneError(
            "this result has no scene, so the report lacks the vehicles' meshes and masses: "
            "build the report from the Result that Scene.run returned"
        )
    impacts = [_impact_report(result, imp, i) for i, imp in enumerate(result.impacts, start=1)]
    # a pedestrian's segments, a cyclist's and its bicycle's bodies are reported as one person
    # (its own section), not as vehicles
    segments = set(person_bodies(result.scene))
    runout = (
        [run_out(result, n) for n in result.vehicles if n not in segments]
        if result.on_ground
        else []
    )
    return Report(
        result=result,
        impacts=impacts,
        engagements=engagements(result),
        run_out=runout,
        joints=joint_reports(result),
        articulation=articulation_events(result),
        pedestrians=pedestrian_reports(result),
    )


class Report:
    """The report of a run: ``impacts`` (ImpactReport list, in time order), ``result`` (the
    Result it was built from), ``run_out`` (a run on a ground: each vehicle's
    RunOutReport, from its separation to rest; crashsim.analysis.runout), ``joints`` (a
    scene with joints: each JointReport, crashsim.analysis.joints).
    ``summary_table()`` / ``str(report)``: the text table; ``to_dict()`` / ``to_json()`` /
    ``write_json(path)``: the versioned JSON report."""

    def __init__(
        self,
        result: Result,
        impacts: list[ImpactReport],
        engagements: list[Engagement] | None = None,
        run_out: list[RunOutReport] | None = None,
        joints: list[JointReport] | None = None,
        articulation: list[ArticulationEvent] | None = None,
        pedestrians: list[PedestrianReport] | None = None,
    ) -> None:
        self.result = result
        self.impacts = list(impacts)
        #: the pairs' contacts, exchanges grouped (crashsim.analysis.engagements)
        self.engagements = list(engagements) if engagements is not None else []
        #: each vehicle's run-out to rest (runs on a ground; empty otherwise)
        self.run_out = list(run_out) if run_out is not None else []
        #: each joint over the run (a scene with joints; empty otherwise)
        self.joints = list(joints) if joints is not None else []
        #: the combinations' jackknifes and trailer swings (crashsim.analysis.joints' rules)
        self.articulation = list(articulation) if articulation is not None else []
        #: each pedestrian, then each cyclist: first contacts, head impact, throw, end (and a
        #: cyclist's bicycle's; crashsim.analysis.pedestrian)
        self.pedestrians = list(pedestrians) if pedestrians is not None else []

    def vehicle_run_out(self, name: str) -> RunOutReport:
        """The run-out of a named vehicle (SceneError when the run had no ground)."""
        for r in self.run_out:
            if r.vehicle == name:
                return r
        if not self.run_out:
            raise SceneError("the run had no ground: its report has no run-out")
        raise SceneError(f"no vehicle named {name!r} in this report: {self.vehicles}")

    @property
    def vehicles(self) -> list[str]:
        return list(self.result.vehicles)

    def summary_table(self) -> str:
        """The text report: per impact a header, then per vehicle delta-V (m/s, km/h, mph),
        EDR components, PDOF, clock and yaw-rate change; speeds before and after; energy,
        EES and the deformations."""
        lines = [
            f"crashsim {_core.__version__} report: {len(self.impacts)} impact(s); vehicles "
            + ", ".join(
                f"{n} ({self.result.vehicle(n).mass:.1f} kg)" for n in self.result.vehicles
            ),
            "Signs: dV long +forward, dV lat +right (event data recorder axes, at the exchange "
            "pose); PDOF SAE: direction the force comes FROM, deg clockwise from ahead seen from "
            "above (90 = from the right); dYaw rate + counter-clockwise seen from above. "
            "Deformation: vehicle 1 along +n, vehicle 2 along -n, centroid to bounding box or "
            "mesh; C max = share x closing speed x dt_p; C residual by SAE 880223.",
        ]
        if not self.impacts:
            lines.append("No impulse exchange in this run.")
        # Contacts by pair, when a pair had more than one exchange or one had none (a
        # first overlap without an exchange is never left out).
        if any(len(e.exchanges) != 1 or e.no_exchange for e in self.engagements):
            lines += [
                "",
                "Contacts by pair (each from its first overlap to its separation; the "
                "delta-V of a pair's exchanges summed):",
            ]
            for e in self.engagements:
                lines += _engagement_lines(e, self.impacts)
            if any(e.secondary for e in self.engagements):
                lines.append(f"  Why secondary exchanges: {WHY_SECONDARY}.")
        primaries = {
            i: e.primary + 1 for e in self.engagements if e.primary is not None for i in e.secondary
        }
        for k, imp in enumerate(self.impacts):
            lines.append("")
            lines += _impact_lines(imp, primaries.get(k))
        if self.run_out:
            lines.append("")
            lines += run_out_lines(self.run_out, _table, obstacles=bool(self.result.obstacles))
            lines += _vehicle_data_lines(self.result)
        if self.joints:
            lines.append("")
            lines += joint_lines(self.joints)
            if self.articulation:
                lines.append("Jackknifes and trailer swings (crashsim's rules, docs/joints.md):")
                lines += articulation_lines(self.articulation)
        if self.pedestrians:
            lines.append("")
            lines += pedestrian_lines(self.pedestrians)
        return "\n".join(lines)

    def __str__(self) -> str:
        return self.summary_table()

    def __repr__(self) -> str:
        return f"Report(vehicles={self.vehicles}, impacts={len(self.impacts)})"

    def to_dict(self, include_meshes: bool = False) -> dict[str, Any]:
        """The JSON report as plain Python (dicts, lists, str, bool, int, float, None);
        ``include_meshes`` adds every vehicle's vertices and faces (model frame)."""
        r = self.result
        scene = _scene_record(r, include_meshes)
        if self.joints:  # optional: a scene with joints (schema version stays 1)
            scene["joints"] = [j.definition() for j in self.joints]
        return {
            "schema": SCHEMA_NAME,
            "schema_version": SCHEMA_VERSION,
            "crashsim_version": str(_core.__version__),
            "units": dict(UNITS),
            "conventions": dict(CONVENTIONS),
            "scene": scene,
            "run": {
                "start_time": float(r.t[0]),
                "duration": None if r.duration is None else float(r.duration),
                "dt": None if r.dt is None else float(r.dt),
                "end_time": float(r.t[-1]),
                "samples": int(r.t.size),
                # optional: a run on the ground (its states between samples are interpolated)
                **({"on_ground": True} if getattr(r, "on_ground", False) else {}),
            },
            "impacts": [imp.to_dict() for imp in self.impacts],
            "contacts": [_plain(c.to_dict()) for c in r.contacts],
            "engagements": [_engagement_record(e) for e in self.engagements],
            # optional: a run on a ground (schema version stays 1)
            **({"run_out": [r.to_dict() for r in self.run_out]} if self.run_out else {}),
            # optional: a scene with joints (schema version stays 1)
            **(
                {
                    "joints": [j.to_dict() for j in self.joints],
                    "joint_events": [e.to_dict() for e in r.joint_events],
                    "articulation_events": [e.to_dict() for e in self.articulation],
                }
                if self.joints
                else {}
            ),
            # optional: a scene with pedestrians or cyclists (schema version stays 1; kind,
            # bodies, height, mass, throws and bicycle added later, also without a change)
            **(
                {"pedestrians": [p.to_dict() for p in self.pedestrians]}
                if self.pedestrians
                else {}
            ),
        }

    def to_json(self, include_meshes: bool = False, indent: int | None = 2) -> str:
        """The JSON report as text (NaN and infinity refused: JSON has no such numbers)."""
        return json.dumps(self.to_dict(include_meshes), indent=indent, allow_nan=False)

    def write_json(self, path: str | PathLike[str], include_meshes: bool = False) -> None:
        """Write the JSON report (UTF-8) to ``path``."""
        with open(path, "w", encoding="utf-8") as f:
            f.write(self.to_json(include_meshes))
            f.write("\n")
