"""A run's contacts per pair: each *engagement* from a pair's first overlap to its separation,
with its exchanges grouped (the primary and its secondary exchanges, their summed delta-V and
energy) and every timer that ended without an impulse.

Why secondary exchanges happen (docs/model.md, "After the exchange"): after an exchange
a pair stays engaged while its meshes overlap. When the relative velocity at the centroid along
the normal turns closing again, a new depth-of-penetration timer starts and another impulse
follows. Between exchanges the motion is torque-free, so that happens only when (a) another
exchange changed the velocity of one of the pair's vehicles (three vehicles pressed together)
or (b) the vehicles rotate while they overlap. :attr:`Engagement.causes` says which, per
secondary exchange. Several small exchanges of a pair that stays inside another add up: the
summed delta-V is what the pair's contact did to each vehicle.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import TYPE_CHECKING

import numpy as np
from numpy.typing import NDArray

if TYPE_CHECKING:
    from crashsim.records import Impact
    from crashsim.result import Result

__all__ = ["Engagement", "WHY_SECONDARY", "engagement_of", "engagements", "secondary_cause"]

Array = NDArray[np.float64]

# A closing-again instant within this of another exchange was caused by it (s): the engine
# bisects the closing instant to 1e-9 s.
SAME_INSTANT = 1e-6

WHY_SECONDARY = (
    "a secondary exchange happens when a pair is still engaged (its meshes overlap) after an "
    "exchange and the relative velocity at the centroid along the normal turns closing again "
    "(another vehicle's exchange changed one of the pair, or the vehicles rotated while "
    "overlapping): a new depth-of-penetration timer starts and another impulse follows; its "
    "delta-V adds to the primary's"
)


@dataclass(frozen=True)
class Engagement:
    """One contact of a pair (``vehicles``, in the engine's order: the normals of its
    exchanges point from the first into the second), from its first overlap to its separation.

    ``first_overlap_time`` (s); ``separation_time`` (s), None when the log has no separation
    for it (still overlapping when the run ended, or found apart only when a timer expired:
    see ``no_exchange``); ``exchanges`` are indices into ``result.impacts`` in time order (the
    first is the primary unless the engagement's first timer ended without an impulse);
    ``causes`` {index of each secondary exchange: why the pair closed again}; ``no_exchange``
    ((time s, the engine's reason), ...) of timers that expired without an impulse;
    ``delta_v`` {name: summed delta-V of the CG over the exchanges, world, m/s; a fixed
    obstacle has none};
    ``energy_dissipated`` the exchanges' sum (J)."""

    vehicles: tuple[str, str]
    first_overlap_time: float
    separation_time: float | None
    exchanges: tuple[int, ...]
    causes: dict[int, str] = field(default_factory=dict)
    no_exchange: tuple[tuple[float, str], ...] = ()
    delta_v: dict[str, Array] = field(default_factory=dict)
    energy_dissipated: float = 0.0

    @property
    def primary(self) -> int | None:
        """The index of the first exchange (None: the engagement had none)."""
        return self.exchanges[0] if self.exchanges else None

    @property
    def secondary(self) -> tuple[int, ...]:
        """The indices of the exchanges after the primary."""
        return self.exchanges[1:]

    @property
    def exchanged(self) -> bool:
        """False for a first overlap that ended without any impulse."""
        return bool(self.exchanges)


def _pair_of(names: tuple[str, str]) -> frozenset[str]:
    return frozenset(names)


def secondary_cause(result: Result, index: int) -> str:
    """Why the engaged pair of the secondary exchange ``result.impacts[index]`` closed again:
    the exchange of another pair at that instant that changed one of its vehicles, else the
    vehicles' rotation while overlapping ("" for a first exchange)."""
    imp = result.impacts[index]
    if not imp.secondary:
        return ""
    start = imp.first_contact_time
    for k, other in enumerate(result.impacts):
        shared = set(other.vehicles) & set(imp.vehicles)
        if k != index and shared and set(other.vehicles) != set(imp.vehicles):
            if abs(other.time - start) <= SAME_INSTANT:
                who = " and ".join(sorted(shared))
                return (
                    f"impact {k + 1} ({other.vehicles[0]}-{other.vehicles[1]}) at "
                    f"{other.time:.6f} s changed {who}'s velocity and the engaged pair closed "
                    "again"
                )
    return (
        "the vehicles rotated while their meshes overlapped and the relative velocity at the "
        "centroid along the normal turned closing again"
    )


def _summed(result: Result, indices: list[int], names: tuple[str, str]) -> dict[str, Array]:
    out = {}
    for name in names:
        if name in result.obstacles:  # a fixed obstacle has no delta-V
            continue
        total = np.zeros(3)
        for i in indices:
            total = total + result.impacts[i].delta_v[name]
        total.setflags(write=False)
        out[name] = total
    return out


@dataclass
class _Open:
    """An engagement while the log is read."""

    vehicles: tuple[str, str]
    start: float
    end: float | None = None
    no_exchange: list[tuple[float, str]] = field(default_factory=list)
    members: list[int] = field(default_factory=list)


def engagements(result: Result) -> list[Engagement]:
    """The engagements of a run in the order of their first overlaps. Built from the contact
    log (first_overlap, closing_again, separation, no_exchange) and the impacts: an impact
    belongs to the latest first overlap of its pair at or before its timer's start."""
    found: list[_Open] = []
    current: dict[frozenset[str], _Open] = {}
    for c in result.contacts:
        key = _pair_of(c.vehicles)
        if c.kind == "first_overlap" or key not in current:
            current[key] = _Open(vehicles=c.vehicles, start=c.time)
            found.append(current[key])
        if c.kind == "separation":
            current[key].end = c.time
        elif c.kind == "no_exchange":
            current[key].no_exchange.append((c.time, c.reason or "no reason given"))
    for i, imp in enumerate(result.impacts):
        key = _pair_of(imp.vehicles)
        mine = [
            e
            for e in found
            if _pair_of(e.vehicles) == key and e.start <= imp.first_contact_time + 1e-12
        ]
        if not mine:  # no first overlap logged for it: an engagement of its own
            found.append(_Open(vehicles=imp.vehicles, start=imp.first_contact_time))
            mine = [found[-1]]
        mine[-1].members.append(i)
    out = []
    for e in found:
        # the impacts' own order of the pair (their normals point from the first)
        names = result.impacts[e.members[0]].vehicles if e.members else e.vehicles
        out.append(
            Engagement(
                vehicles=names,
                first_overlap_time=e.start,
                separation_time=e.end,
                exchanges=tuple(e.members),
                causes={
                    i: secondary_cause(result, i) for i in e.members if result.impacts[i].secondary
                },
                no_exchange=tuple(e.no_exchange),
                delta_v=_summed(result, e.members, names),
                energy_dissipated=float(
                    sum(result.impacts[i].energy_dissipated for i in e.members)
                ),
            )
        )
    out.sort(key=lambda e: e.first_overlap_time)
    return out


def engagement_of(result: Result, impact: Impact) -> Engagement | None:
    """The engagement an impact belongs to."""
    for e in engagements(result):
        for i in e.exchanges:
            if result.impacts[i] is impact:
                return e
    return None
