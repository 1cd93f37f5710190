"""The text report's lines (crashsim.analysis.report): number formats, plain tables, a
pair's contacts in words, one impact's tables, and the vehicles on their wheels."""

from __future__ import annotations

import math
from typing import TYPE_CHECKING

import numpy as np
from numpy.typing import ArrayLike

from crashsim.analysis.report_common import BY_STIFFNESS, RIGID_OBSTACLE
from crashsim.small_linalg import norm
from crashsim.units import to_kmh, to_mph

if TYPE_CHECKING:
    from crashsim.analysis.engagements import Engagement
    from crashsim.analysis.impact_report import ImpactReport
    from crashsim.result import Result


def _fmt(x: float | None, digits: int) -> str:
    """A fixed-point number ("unknown" for None); a negative zero after rounding loses its
    sign (round-off must not read as a direction)."""
    if x is None:
        return "unknown"
    text = f"{x:.{digits}f}"
    return text[1:] if text.startswith("-") and float(text) == 0.0 else text


def _fmt_angle(deg: float | None) -> str:
    """A PDOF to 0.01 deg in [0, 360) ("n/a" for None: no horizontal delta-V)."""
    if deg is None:
        return "n/a"
    text = _fmt(deg, 2)
    return "0.00" if text == "360.00" else text


def _fmt3(v: ArrayLike, digits: int) -> str:
    """(x, y, z) with _fmt's numbers."""
    return "(" + ", ".join(_fmt(float(x), digits) for x in np.asarray(v).reshape(-1)) + ")"


def _table(headers: list[str], rows: list[list[str]]) -> list[str]:
    """Lines of a plain table: first column left-aligned, the others right-aligned."""
    widths = [max(len(h), *(len(r[i]) for r in rows)) for i, h in enumerate(headers)]

    def line(cells: list[str]) -> str:
        out = [cells[0].ljust(widths[0])]
        out += [c.rjust(w) for c, w in zip(cells[1:], widths[1:], strict=True)]
        return "  " + " | ".join(out)

    rule = "  " + "-+-".join("-" * w for w in widths)
    return [line(headers), rule, *(line(r) for r in rows)]


def _pair(names: tuple[str, str] | list[str]) -> str:
    return f"{names[0]}-{names[1]}"


def _numbers(indices: tuple[int, ...]) -> str:
    """Impact numbers (1-based) of impact indices: "3", "3 and 5", "3, 5 and 7"."""
    n = [str(i + 1) for i in indices]
    return n[0] if len(n) == 1 else ", ".join(n[:-1]) + " and " + n[-1]


def _engagement_lines(e: Engagement, impacts: list[ImpactReport]) -> list[str]:
    """A pair's contact in words: its exchanges grouped, their summed delta-V, the causes of
    its secondary exchanges, and any timer that ended without an impulse (labelled)."""
    apart = [t for t, reason in e.no_exchange if "no longer overlap" in reason]
    if e.separation_time is not None:
        end = f"separated at {_fmt(e.separation_time, 6)} s"
    elif apart:
        end = f"found apart when its timer expired at {_fmt(apart[-1], 6)} s"
    else:
        end = "still overlapping when the run ended"
    head = f"  {_pair(e.vehicles)}: first overlap at {_fmt(e.first_overlap_time, 6)} s, {end}"
    if not e.exchanged:
        lines = [head]
        for t, reason in e.no_exchange or ((e.first_overlap_time, "no timer expired"),):
            lines.append(
                f"    NO EXCHANGE: the overlap that began at {_fmt(e.first_overlap_time, 6)} s "
                f"ended without an impulse (timer end {_fmt(t, 6)} s: {reason})"
            )
        return lines
    primary, secondary = e.exchanges[0], e.exchanges[1:]
    which = f"impact {primary + 1}"
    which += f" (primary) and secondary {_numbers(secondary)}" if secondary else " only"
    lines = [head + f"; {which}"]
    summed = []
    for name in e.vehicles:
        if name not in e.delta_v:  # a fixed obstacle
            continue
        dv = float(norm(e.delta_v[name]))
        summed.append(
            f"{name} {_fmt(dv, 3)} m/s ({_fmt(to_kmh(dv), 2)} km/h, {_fmt(to_mph(dv), 2)} mph)"
        )
    lines.append(
        f"    summed delta-V (vector sum over its {len(e.exchanges)} exchange(s)): "
        + ", ".join(summed)
        + f"; energy dissipated {_fmt(e.energy_dissipated, 1)} J"
    )
    for i in e.exchanges:
        if i in e.causes:
            closing = impacts[i].closing_speed
            lines.append(
                f"    impact {i + 1} (secondary, closing speed {_fmt(closing, 3)} m/s): "
                f"{e.causes[i]}"
            )
    for t, reason in e.no_exchange:
        lines.append(
            f"    NO EXCHANGE: a timer ended at {_fmt(t, 6)} s without an impulse: {reason}"
        )
    return lines


def _speed_cells(v: float | None) -> list[str]:
    if v is None:
        return ["unknown"] * 3
    return [_fmt(v, 3), _fmt(to_kmh(v), 2), _fmt(to_mph(v), 2)]


def _impact_lines(imp: ImpactReport, primary: int | None = None) -> list[str]:
    """The text of one impact; ``primary``: the number of the impact a secondary one
    follows in its pair's engagement."""
    lines = _impact_head_lines(imp, primary)
    lines.append("")
    lines += _delta_v_table(imp)
    lines.append("")
    lines += _table(
        [
            "Vehicle",
            "v before (m/s)",
            "v before (km/h)",
            "v before (mph)",
            "v after (m/s)",
            "v after (km/h)",
            "v after (mph)",
        ],
        [
            [p.name, *_speed_cells(p.speed_before), *_speed_cells(p.speed_after)]
            for p in imp.parties
        ],
    )
    lines.append("")
    lines += _energy_table(imp)
    notes = list(imp.notes)
    for p in imp.parties:
        notes += [f"{p.name}: {x}" for x in p.deformation.notes]
    if notes:
        lines.append("  notes:")
        lines += [f"  - {x}" for x in notes]
    return lines


def _impact_head_lines(imp: ImpactReport, primary: int | None) -> list[str]:
    """An impact's heading, times, centroid, impulse and energy, and where the centroid is in
    each party's frame."""
    v1, v2 = imp.vehicles
    c = imp.centroid
    n = imp.normal
    dtp = f"{_fmt(imp.depth_of_penetration * 1e3, 3)} ms ({imp.depth_of_penetration_mode}"
    if imp.series_stiffness is not None:
        dtp += f"; m' = {_fmt(imp.reduced_mass, 1)} kg, k' = {imp.series_stiffness:.6g} N/m"
    else:
        dtp += f"; m' = {_fmt(imp.reduced_mass, 1)} kg, k' unknown"
    dtp += ")"
    lines = [
        f"Impact {imp.number}: {v1} (1) -> {v2} (2)"
        + (
            " [secondary" + (f" to impact {primary}" if primary else "") + "]"
            if imp.secondary
            else ""
        )
        + f", {imp.impact_type} impact",
        f"  first overlap t0 = {_fmt(imp.first_contact_time, 6)} s, exchange "
        f"t = {_fmt(imp.exchange_time, 6)} s, depth of penetration {dtp}",
        f"  centroid (world) {_fmt3(c, 4)} m; normal 1->2 {_fmt3(n, 4)}",
        f"  impulse on {v2} {_fmt3(imp.impulse, 1)} N s, "
        f"|J| = {_fmt(imp.impulse_magnitude, 1)} N s; closing speed "
        f"{_fmt(imp.closing_speed, 3)} m/s",
        f"  energy dissipated {_fmt(imp.energy_dissipated, 1)} J, split by stiffness: "
        + {BY_STIFFNESS: "yes", RIGID_OBSTACLE: "all to the vehicle (rigid obstacle)"}.get(
            imp.energy_split_basis, "unknown"
        )
        + f"; overlap depth along n {_fmt(imp.overlap_depth, 4)} m, "
        + f"width {_fmt(imp.overlap_width, 4)} m",
        *_figure_lines(imp),
    ]
    for p in imp.parties:
        cb = p.centroid_body
        lines.append(
            f"  centroid in {p.name}'s body frame {_fmt3(cb, 4)} m"
            f" (x fwd, y left, z up from the CG); struck face: {p.struck_face}"
        )
    if imp.obstacle is not None:
        o = imp.obstacle
        lines.append(
            f"  {o.name} is a fixed obstacle (infinite mass, no delta-V); centroid in its "
            f"frame {_fmt3(o.centroid_body, 4)} m; struck on its {o.struck_side} side (its "
            f"frame; the {o.struck_face} face for its stiffness)"
        )
    return lines


def _figure_lines(imp: ImpactReport) -> list[str]:
    """One line per figure of the impact (ImpactReport.figures): its label, value ("n/a"
    where undefined) and unit."""
    return [
        f"  {f['label']}: "
        + ("n/a" if f["value"] is None else _fmt(f["value"], f["digits"]))
        + (f" {f['unit']}" if f["unit"] else "")
        for f in imp.figures()
    ]


def _delta_v_table(imp: ImpactReport) -> list[str]:
    """Each vehicle's delta-V (m/s, km/h, mph; body long and lat), PDOF, clock and yaw rate
    change."""
    return _table(
        [
            "Vehicle",
            "dV (m/s)",
            "dV (km/h)",
            "dV (mph)",
            "dV long (m/s)",
            "dV lat (m/s)",
            "PDOF (deg)",
            "Clock",
            "dYaw rate (deg/s)",
        ],
        [
            [
                p.name,
                *_speed_cells(p.delta_v_magnitude),
                _fmt(p.longitudinal, 3),
                _fmt(p.lateral, 3),
                _fmt_angle(p.pdof_deg),
                "unknown" if p.clock is None else f"{p.clock}",
                _fmt(p.yaw_rate_change, 2),
            ]
            for p in imp.parties
        ],
    )


def _energy_table(imp: ImpactReport) -> list[str]:
    """Each vehicle's share of the energy (J), EES and deformation figures (m)."""
    return _table(
        [
            "Vehicle",
            "Energy (J)",
            "EES (m/s)",
            "EES (km/h)",
            "EES (mph)",
            "Box def. (m)",
            "Mesh def. (m)",
            "Overlap (m)",
            "C max (m)",
            "C residual (m)",
        ],
        [
            [
                p.name,
                _fmt(p.energy, 1),
                *_speed_cells(p.ees),
                _fmt(p.deformation.bounding_box, 4),
                "n/a" if p.deformation.mesh is None else _fmt(p.deformation.mesh, 4),
                _fmt(p.deformation.overlap_depth, 4),
                _fmt(p.deformation.max_crush, 4),
                _fmt(p.deformation.residual_crush, 4),
            ]
            for p in imp.parties
        ],
    )


def _vehicle_data_lines(result: Result) -> list[str]:
    """The vehicles on the ground as the engine ran them: tyre, steering, springs and bars."""
    lines: list[str] = []
    for name in result.vehicles:
        v = result.vehicle(name)
        if v.wheels is None:
            continue
        d = v.wheels.describe(v.mass)
        if not lines:
            lines += ["", "Vehicles on their wheels (as run):"]
        t = d["tyre"]
        law = {
            "linear": f"linear, cornering {math.radians(t.get('cornering', 0.0)):.4f} per deg "
            f"(1 per {1.0 / math.radians(t.get('cornering', 1.0)):.1f} deg)",
            "linear_friction_scaled": "linear scaled by the friction, mu Fz at "
            f"{math.degrees(t.get('saturation_angle', 0.0)):.1f} deg",
            "magic_formula": f"Magic Formula B {t.get('b')}, C {t.get('c')}, E {t.get('e')}",
        }[t["model"]]
        combined = t["combined"]
        if combined == "nicolas_comstock":
            cs = t.get("longitudinal_stiffness")
            combined += " (longitudinal stiffness " + (
                "= cornering)" if cs is None else f"{cs:g} Fz per unit slip)"
            )
        lines.append(
            f"  {name}: tyre {law}; relaxation length {t['relaxation_length']:.3f} m; rolling "
            f"resistance {t['rolling_resistance']:g}; combined slip {combined}; load "
            f"sensitivity {t['load_sensitivity']:g}"
        )
        st = d["steering"]
        ratio = "none" if st["ratio"] is None else f"{st['ratio']:g}"
        ramp = (
            "; each wheel linear between the table's points"
            if st.get("interpolation") == "wheels"
            else ""
        )
        lines.append(
            f"  {name}: steering ratio {ratio}, Ackermann {st['ackermann']:g} (input: the "
            f"{st['reference']} wheel's angle{ramp}); ABS {'on' if d['abs'] else 'off'}"
        )
        freq = ", ".join(f"{f:.2f}" for f in d["natural_frequencies"])
        zeta = ", ".join(f"{z:.2f}" for z in d["damping_ratios"])
        springs = f"  {name}: springs {freq} Hz, damping ratios {zeta}"
        if "roll_stiffness" in d:
            rs = d["roll_stiffness"]
            bars = ", ".join(
                f"bar {b['left']}-{b['right']} {math.radians(b['roll_stiffness']):.0f}"
                for b in d["anti_roll"]
            )
            springs += (
                f"; roll stiffness front {math.radians(rs['front']):.0f}, rear "
                f"{math.radians(rs['rear']):.0f} N m/deg ({bars or 'springs only, no bars'})"
            )
            if d.get("roll_gradient") is not None:
                springs += f"; roll gradient {math.degrees(d['roll_gradient']):.1f} deg/g"
        lines.append(springs)
    return lines
