"""Driver inputs: steering, braking and drive force as time tables, and wheel states.

Every table is a list of (time s, value) rows, linear between rows and held beyond its ends;
times must increase. SI units: angles in rad (+ to the left, i.e. counter-clockwise seen from
above), forces in N, decelerations in m/s^2, braking fractions in [0, 1] of the friction
available at the wheel. A single number stands for a constant table.

Wheels are named as in :mod:`crashsim.vehicles.wheels` ("front_left" or "FL", ...; an index
for a custom layout), axles "front" and "rear", and "all" means every wheel. The engine
checks the tables and ranges (increasing times, road-wheel angles within 60 deg, fractions in
[0, 1], ...); its messages are passed on naming the table.

    DriverInputs(
        steering_wheel=[(0.0, 0.0), (0.5, deg(90))], steering_ratio=16.0,
        brake={"front": [(0.2, 0.0), (0.4, 1.0)], "rear": [(0.2, 0.0), (0.4, 0.7)]},
        wheel_states=[("FL", "locked", "exchange 1")],
    )
"""

from __future__ import annotations

import re
from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from typing import Any, TypeAlias

import numpy as np
from numpy.typing import ArrayLike, NDArray

from crashsim import _core
from crashsim.errors import ParameterError, at, renamed
from crashsim.vehicles.wheels import Wheels, wheel_naming

__all__ = ["Brake", "DriverInputs", "TableLike", "WheelStateSwitch"]

Array = NDArray[np.float64]
TableLike: TypeAlias = float | ArrayLike
"""A number (constant) or rows (time s, value)."""

STATES = ("free", "locked", "braked")


def _table(value: Any, name: str) -> Array:
    """(k, 2) rows from a number or rows, checked by the engine (increasing times, finite
    numbers); ParameterError naming the table otherwise."""
    if isinstance(value, bool | str):
        raise ParameterError(f"the {name} table must be numbers, got {value!r}")
    try:
        a = np.array(value, dtype=np.float64)
    except (TypeError, ValueError) as e:
        raise ParameterError(
            f"the {name} table must be rows of (time s, value), got {value!r}"
        ) from e
    if a.ndim == 0:
        a = np.array([[0.0, float(a)]])
    if a.ndim != 2 or a.shape[1] != 2 or len(a) == 0:
        raise ParameterError(
            f"the {name} table must be rows of (time s, value), got shape {a.shape}"
        )
    _core.check_table(a, name)
    a.setflags(write=False)
    return a


@dataclass(frozen=True)
class Brake:
    """A braking demand: ``kind`` "fraction" (of the friction available at the wheel, 0-1),
    "deceleration" (m/s^2: each wheel's force at most its load times demand / g, so every
    wheel braked this way decelerates the vehicle at the demand while friction allows: the
    ideal distribution) or "distributed" (m/s^2: the vehicle's brake force m a split between
    the axles at a fixed ``front_share``, each axle's equally between its wheels; a wheel asked
    for more than its friction locks unless the vehicle has ABS), and its ``table`` of
    (time s, value) rows (a number is a constant). Checked when made, by the engine's rules
    of a braking (``_core.check_brake``: a fraction in [0, 1], a deceleration in
    [0, 20] m/s^2); ``front_share`` in [0, 1], given for "distributed" only."""

    kind: str
    table: Array
    front_share: float | None = None

    def __post_init__(self) -> None:
        if self.kind not in _BRAKE_KINDS:
            raise ParameterError(
                f"braking is a 'fraction' of the friction, a 'deceleration' or 'distributed', "
                f"not {self.kind!r}"
            )
        demand = "fraction" if self.kind == "fraction" else "deceleration"
        table = _table(self.table, f"braking {demand}")
        share = self.front_share
        if self.kind == "distributed":
            if share is None:
                raise ParameterError("a distributed brake needs its front_share")
            share = float(share)
            if not 0.0 <= share <= 1.0:
                raise ParameterError(
                    f"front_share = {self.front_share} is invalid: the front axle's share of "
                    "the brake force must lie in [0, 1] (passenger cars 0.6-0.8)"
                )
        elif share is not None:
            raise ParameterError(f"front_share is for a distributed brake, not a {self.kind} one")
        _core.check_brake(demand, table)
        object.__setattr__(self, "table", table)
        object.__setattr__(self, "front_share", share)

    @classmethod
    def fraction(cls, table: TableLike) -> Brake:
        """Braking at a fraction of the available friction (0 = none, 1 = at the limit)."""
        return cls("fraction", table)

    @classmethod
    def deceleration(cls, table: TableLike) -> Brake:
        """Braking at a deceleration demand (m/s^2), each wheel in proportion to its load."""
        return cls("deceleration", table)

    @classmethod
    def distributed(cls, table: TableLike, front_share: float) -> Brake:
        """The vehicle braked at a deceleration demand (m/s^2) with a fixed front/rear split of
        its brake force: ``front_share`` (0-1; passenger cars 0.6-0.8) to the front axle."""
        return cls("distributed", table, front_share)


_BRAKE_KINDS = ("fraction", "deceleration", "distributed")


def _brake(value: Any, name: str) -> Brake:
    """A Brake (checked when it was made), or a table of fractions named ``name``."""
    if isinstance(value, Brake):
        return value
    return named_brake("fraction", value, name)


def named_brake(kind: str, table: TableLike, name: str, front_share: float | None = None) -> Brake:
    """The Brake of ``kind``, its table named ``name`` ("brake['RR']"): the table's own errors
    name it ("the brake['RR'] table's times must increase"), a value out of range is placed
    in the part ``name``."""
    rows = _table(table, name)
    try:
        return Brake(kind, rows, front_share)
    except ParameterError as e:
        raise at(e, ("part", None, name)) from e


@dataclass(frozen=True)
class WheelStateSwitch:
    """From ``at`` on, ``wheel`` (a name, an axle, "all" or an index) is ``state``: "free",
    "locked" or "braked" at ``fraction`` of the friction (a wheel jammed by the crush; the
    fraction is required for "braked" and only for it). ``at`` is a time (s) or
    ("exchange", n): the vehicle's n-th impulse exchange (1 = its first), whichever the other
    party."""

    wheel: str | int
    state: str
    at: float | tuple[str, int]
    fraction: float | None = None


def _switch(value: Any, k: int) -> WheelStateSwitch:
    if isinstance(value, WheelStateSwitch):
        item = value
    else:
        if not isinstance(value, tuple | list) or len(value) not in (3, 4):
            raise ParameterError(
                f"wheel_states[{k}] must be (wheel, state, at) or (wheel, 'braked', at, "
                f"fraction), got {value!r}"
            )
        item = WheelStateSwitch(*value)
    state = item.state.strip().lower() if isinstance(item.state, str) else item.state
    if state not in STATES:
        raise ParameterError(
            f"wheel_states[{k}]: state {item.state!r} is unknown: use 'free', 'locked' or "
            "'braked' (with a fraction)"
        )
    when = item.at
    if isinstance(when, str):
        m = re.fullmatch(r"\s*exchange\s*(\d*)\s*", when.lower())
        if m is None:
            raise ParameterError(
                f"wheel_states[{k}]: at = {when!r} is unknown: give a time (s), 'exchange' "
                "(the vehicle's first) or 'exchange N'"
            )
        when = ("exchange", int(m.group(1) or 1))
    elif isinstance(when, tuple | list):
        if len(when) != 2 or when[0] != "exchange" or isinstance(when[1], bool):
            raise ParameterError(f"wheel_states[{k}]: at = {when!r}: give ('exchange', n)")
        n = when[1]
        if not isinstance(n, int | np.integer):
            raise ParameterError(
                f"wheel_states[{k}]: exchange {n!r}: exchanges count from 1 (a whole number)"
            )
        when = ("exchange", int(n))
    else:
        if isinstance(when, bool):
            raise ParameterError(f"wheel_states[{k}]: at must be a time (s), got {when!r}")
        try:
            when = float(when)
        except (TypeError, ValueError) as e:
            raise ParameterError(
                f"wheel_states[{k}]: at must be a time (s) or an exchange, got {when!r}"
            ) from e
    fraction = None
    if state != "braked":
        if item.fraction is not None:
            raise ParameterError(f"wheel_states[{k}]: a fraction is for the 'braked' state only")
    elif item.fraction is None:
        raise ParameterError(
            f"wheel_states[{k}]: 'braked' needs its fraction of the friction (0-1): "
            "(wheel, 'braked', at, fraction); a wheel that does not turn at all is 'locked'"
        )
    else:
        try:
            fraction = float(item.fraction)
        except (TypeError, ValueError) as e:
            raise ParameterError(f"wheel_states[{k}]: fraction must be a number in [0, 1]") from e
    switch = WheelStateSwitch(item.wheel, state, when, fraction)
    try:  # the engine's rules of a switch: a finite time, exchanges from 1, a fraction in [0, 1]
        _core.check_wheel_switch(*_engine_terms(switch))
    except ParameterError as e:
        raise at(e, ("part", None, f"wheel_states[{k}]")) from e
    return switch


def _engine_terms(s: WheelStateSwitch) -> tuple[str, float, str, float]:
    """(trigger, when, state, fraction) of a switch as the engine takes it: "time" and s, or
    "exchange" and n; the fraction (1 when not braked: the engine does not read it)."""
    trigger, when = ("exchange", float(s.at[1])) if isinstance(s.at, tuple) else ("time", s.at)
    return trigger, float(when), s.state, 1.0 if s.fraction is None else s.fraction


def _targets(wheels: Wheels, key: str | int, what: str) -> tuple[int, ...]:
    """The wheel indices a key names: a wheel, an axle or "all"."""
    if isinstance(key, str) and key.strip().lower() == "all":
        return tuple(range(len(wheels)))
    if isinstance(key, str) and key.strip().lower() in ("front", "rear"):
        return wheels.axle(key.strip().lower())
    try:
        return (wheels.index(key),)
    except ParameterError as e:
        raise at(e, ("part", None, what)) from e


class DriverInputs:
    """A vehicle's driver inputs and wheel states (SI; see the module docstring).

    - ``steer``: road-wheel angle (rad, + left) of the steering linkage's reference (the
      steered axle's centre; each wheel turns through the linkage's Ackermann geometry), a
      table or a number; or a mapping from steerable wheels to their own tables (per-wheel
      angles replace the linkage); or ``steering_wheel`` (rad) over the steering ratio (the
      vehicle's, :class:`crashsim.Wheels`, or ``steering_ratio`` here); or ``path``: (n, 2)
      world points (m) a driver follows by pure pursuit, looking ``preview`` s ahead at the
      current speed (default 1 s) and at least ``min_distance`` m (default 3 m).
    - ``brake``: a table of fractions (or a :class:`Brake`) for every wheel, or a mapping
      from wheels, axles or "all" to tables or Brakes.
    - ``drive``: drive force (N, + forward): a table for the whole vehicle (split equally
      over every wheel), or a mapping from axles (the axle's total, split equally between
      its wheels), wheels or "all" to tables.
    - ``wheel_states``: (wheel, state, at) or (wheel, "braked", at, fraction) switches (see
      :class:`WheelStateSwitch`); later ones win; every wheel starts free.

    Tables are checked here (ParameterError naming the table); the rest (wheel names, the
    steering range, fractions in [0, 1]) when a vehicle's wheels are known
    (:meth:`to_core`, called by :meth:`crashsim.Scene.add`).
    """

    def __init__(
        self,
        *,
        steer: TableLike | Mapping[str | int, TableLike] | None = None,
        steering_wheel: TableLike | None = None,
        steering_ratio: float | None = None,
        path: ArrayLike | None = None,
        preview: float | None = None,
        min_distance: float | None = None,
        brake: TableLike | Brake | Mapping[str | int, TableLike | Brake] | None = None,
        drive: TableLike | Mapping[str | int, TableLike] | None = None,
        wheel_states: Sequence[Any] = (),
    ) -> None:
        given = [k for k, v in (("steer", steer), ("steering_wheel", steering_wheel),
                                ("path", path)) if v is not None]  # fmt: skip
        if len(given) > 1:
            raise ParameterError(
                "give one steering input (steer, steering_wheel or path), not "
                + " and ".join(given)
            )
        self.path: Array | None = None
        self.preview: float | None = None
        self.min_distance: float | None = None
        if path is not None:
            try:
                points = np.array(path, dtype=np.float64)
            except (TypeError, ValueError) as e:
                raise ParameterError(f"path must be (n, 2) points (m), got {path!r}") from e
            if points.ndim != 2 or points.shape[1] != 2:
                raise ParameterError(f"path must be (n, 2) points (m), got shape {points.shape}")
            points.setflags(write=False)
            self.path = points
            self.preview = None if preview is None else float(preview)
            self.min_distance = None if min_distance is None else float(min_distance)
        elif preview is not None or min_distance is not None:
            raise ParameterError("preview and min_distance are for a path: drop them or give it")
        self.steering_ratio: float | None = None
        self.steering_wheel: Array | None = None
        self.steer: Array | None = None
        self.wheel_steer: dict[str | int, Array] = {}
        if steering_wheel is not None:
            if steering_ratio is not None:
                ratio = float(steering_ratio)
                _core.check_steering_ratio(ratio)
                self.steering_ratio = ratio
            self.steering_wheel = _table(steering_wheel, "steering_wheel")
        elif steering_ratio is not None:
            raise ParameterError("steering_ratio is for steering_wheel: drop it or give that")
        elif isinstance(steer, Mapping):
            for key, t in steer.items():
                self.wheel_steer[key] = _table(t, f"steer[{key!r}]")
        elif steer is not None:
            self.steer = _table(steer, "steer")
        self.brake: dict[str | int, Brake] = {}
        if isinstance(brake, Mapping):
            for key, b in brake.items():
                self.brake[key] = _brake(b, f"brake[{key!r}]")
        elif brake is not None:
            self.brake["all"] = _brake(brake, "brake")
        self.drive: dict[str | int, Array] = {}
        self._drive_total = False
        if isinstance(drive, Mapping):
            for key, d in drive.items():
                self.drive[key] = _table(d, f"drive[{key!r}]")
        elif drive is not None:
            self.drive["all"] = _table(drive, "drive")
            self._drive_total = True
        if isinstance(wheel_states, str | WheelStateSwitch) or (
            isinstance(wheel_states, tuple) and wheel_states and isinstance(wheel_states[0], str)
        ):
            raise ParameterError(
                "wheel_states must be a list of (wheel, state, at) switches, e.g. "
                "[('FL', 'locked', 0.0)]"
            )
        self.wheel_states: tuple[WheelStateSwitch, ...] = tuple(
            _switch(s, k) for k, s in enumerate(wheel_states)
        )

    def to_core(self, wheels: Wheels, what: str = "inputs") -> dict[str, Any]:
        """SceneSpec.set_vehicle keywords (steer, brake, drive, switches) for these wheels,
        checked by the engine; ``what`` names the vehicle in messages."""
        n = len(wheels)
        brake: list[tuple[str, Array, float | None] | None] = [None] * n
        # "all" first, then axles, then wheels: the most specific key wins.
        order = sorted(self.brake, key=lambda k: _rank(k))
        for key in order:
            b = self.brake[key]
            if b.kind == "distributed":
                brake = _distributed(b, key, wheels, f"{what}: brake[{key!r}]")
                continue
            for i in _targets(wheels, key, f"{what}: brake[{key!r}]"):
                brake[i] = (b.kind, b.table, None)
        drive: list[Array | None] = [None] * n
        for key in sorted(self.drive, key=lambda k: _rank(k)):
            targets = _targets(wheels, key, f"{what}: drive[{key!r}]")
            table = self.drive[key]
            share = 1.0 if isinstance(key, int) or _rank(key) == 2 else 1.0 / len(targets)
            for i in targets:
                t = table.copy()
                t[:, 1] *= share
                drive[i] = t
        switches = []
        for k, s in enumerate(self.wheel_states):
            terms = _engine_terms(s)
            for i in _targets(wheels, s.wheel, f"{what}: wheel_states[{k}]"):
                switches.append((i, *terms))
        out: dict[str, Any] = {"switches": switches}
        if self.steer is not None:
            out["steer"] = ("road_wheel", self.steer)
        elif self.steering_wheel is not None:
            out["steer"] = ("steering_wheel", self.steering_wheel)
            if self.steering_ratio is not None:
                out["steering_ratio"] = self.steering_ratio
        elif self.path is not None:
            out["steer"] = ("path", (self.path, self.preview, self.min_distance))
        elif self.wheel_steer:
            per: list[Array | None] = [None] * n
            for key, table in self.wheel_steer.items():
                for i in _targets(wheels, key, f"{what}: steer[{key!r}]"):
                    per[i] = table
            out["steer"] = ("per_wheel", per)
        if any(b is not None for b in brake):
            out["brake"] = brake
        if any(d is not None for d in drive):
            out["drive"] = drive
        try:
            wheels.check_inputs(**out)
        except ParameterError as e:
            note = ""
            if self.steering_wheel is not None and "steering angle" in str(e):
                ratio = self.steering_ratio or wheels.steering_ratio
                note = f" (steering_wheel / steering_ratio {ratio:g})"
            raise at(renamed(e, wheel_naming(wheels.names), note), ("part", None, what)) from e
        return out

    def __repr__(self) -> str:
        parts = []
        if self.steer is not None:
            parts.append(f"steer={len(self.steer)} rows")
        if self.steering_wheel is not None:
            parts.append(f"steering_wheel={len(self.steering_wheel)} rows")
        if self.wheel_steer:
            parts.append(f"steer={list(self.wheel_steer)}")
        if self.path is not None:
            parts.append(f"path={len(self.path)} points")
        if self.brake:
            parts.append(f"brake={list(self.brake)}")
        if self.drive:
            parts.append(f"drive={list(self.drive)}")
        if self.wheel_states:
            parts.append(f"wheel_states={len(self.wheel_states)}")
        return f"DriverInputs({', '.join(parts)})"


def _distributed(
    b: Brake, key: str | int, wheels: Wheels, what: str
) -> list[tuple[str, Array, float | None] | None]:
    """Every wheel's share of a vehicle-level distributed brake (the usual four wheels)."""
    if _rank(key) != 0:
        raise ParameterError(
            f"{what}: a distributed brake (Brake.distributed) is the whole vehicle's: give it "
            "for 'all' (brake=Brake.distributed(...))"
        )
    front = wheels.axle("front")
    rear = wheels.axle("rear")
    assert b.front_share is not None
    out: list[tuple[str, Array, float | None] | None] = [None] * len(wheels)
    for axle, share in ((front, b.front_share), (rear, 1.0 - b.front_share)):
        for i in axle:
            out[i] = ("distributed", b.table, share / len(axle))
    return out


def _rank(key: str | int) -> int:
    """0 for "all", 1 for an axle, 2 for a wheel."""
    if isinstance(key, str) and key.strip().lower() == "all":
        return 0
    if isinstance(key, str) and key.strip().lower() in ("front", "rear"):
        return 1
    return 2

