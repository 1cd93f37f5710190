"""Wheels: what a vehicle stands and runs on when the scene has a ground (its tyre:
:mod:`crashsim.vehicles.tyre`).

Frames and units: SI. Wheel centres are in the vehicle's body frame (ISO 8855: origin at the
CG, x forward, y left, z up; m) at static ride height, so a wheel of radius R under a CG at
height h above level ground has its centre at z = R - h. Each wheel is a vertical
spring-damper whose preload is its static load (the axle shares of the weight, from the
engine's ``_core.static_loads``); its rate and damping come from a natural frequency and a
damping ratio (``_core.suspension``) unless given. The engine's defaults (1.3 Hz, 0.3, the
tyre's saturation angle, relaxation length and rolling resistance) are read from
``_core.dynamics_defaults()``: this module repeats none of them.

The usual four wheels are named ``front_left``, ``front_right``, ``rear_left``,
``rear_right`` (also ``FL``, ``FR``, ``RL``, ``RR``), in that order (the engine's wheel
indices); the axles are ``front`` and ``rear``. The engine checks every number (positive
radii and rates, a CG over the wheels, wheels inside the body's outline); its messages are
passed on with the wheels' names.
"""

from __future__ import annotations

import copy
import functools
import math
from collections.abc import Iterator, Sequence
from typing import Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

from crashsim import _core
from crashsim.errors import Naming, ParameterError, Place, at, naming, renamed, vehicle_place
from crashsim.names import check_name
from crashsim.vehicles.numbers import finite as _number
from crashsim.vehicles.tyre import TYRE_MODELS, Tyre

__all__ = [
    "ABBREVIATIONS",
    "AXLES",
    "STANDARD_NAMES",
    "TYRE_MODELS",
    "Tyre",
    "Wheels",
    "dynamics_defaults",
    "wheel_index",
]

Array = NDArray[np.float64]

STANDARD_NAMES = ("front_left", "front_right", "rear_left", "rear_right")
"""The names of the usual four wheels, in the engine's order."""
ABBREVIATIONS = {"FL": "front_left", "FR": "front_right", "RL": "rear_left", "RR": "rear_right"}
"""Short names of the usual four wheels."""
AXLES = {"front": ("front_left", "front_right"), "rear": ("rear_left", "rear_right")}
"""The wheels of each axle of the usual four."""


@functools.cache
def _defaults() -> dict[str, float]:
    return dict(_core.dynamics_defaults())


def dynamics_defaults() -> dict[str, float]:
    """The engine's defaults for the ground, wheels and tyres, and its rest thresholds
    (``_core.dynamics_defaults()``): gravity (m/s^2), natural_frequency (Hz),
    damping_ratio, saturation_angle (rad), relaxation_length (m), rolling_resistance,
    tyre_friction, body_friction, rest_speed (m/s), rest_yaw_rate (rad/s), rest_turn_speed
    (m/s: a body smaller than 0.57 m from its CG to its box's corner is slow in yaw below this
    over that distance), rest_time (s)."""
    return dict(_defaults())


def wheel_index(names: Sequence[str], wheel: str | int) -> int:
    """The index in ``names`` of a wheel given by its name ("front_left", also "Front left"),
    short name ("FL") or index: the one lookup of Wheels.index and the Result's wheel
    records. ParameterError listing the names otherwise."""
    if isinstance(wheel, int | np.integer) and not isinstance(wheel, bool):
        if 0 <= int(wheel) < len(names):
            return int(wheel)
    elif isinstance(wheel, str):
        key = wheel.strip()
        key = ABBREVIATIONS.get(key.upper(), key) if key.upper() in ABBREVIATIONS else key
        for k in (key, key.lower().replace(" ", "_").replace("-", "_")):
            if k in names:
                return list(names).index(k)
    short = [k for k, v in ABBREVIATIONS.items() if v in names]
    raise ParameterError(
        f"unknown wheel {wheel!r}: the wheels are {', '.join(names)}"
        + (f" (or {', '.join(short)})" if short else "")
        + f" or an index 0-{len(names) - 1}"
    )


def wheel_naming(names: Sequence[str]) -> Naming:
    """Names the engine's wheel places ("wheel k") by the wheels' names."""
    return naming(wheel=lambda k: f"wheel {names[k]!r}" if 0 <= k < len(names) else None)


def _renamed(error: ParameterError, names: Sequence[str]) -> ParameterError:
    """The engine's error with its wheel places named."""
    return renamed(error, wheel_naming(names))


# -- wheels ---------------------------------------------------------------------------------------


def _roll_input(
    anti_roll: Any, roll_gradient: Any, front_share: Any, *, axles: bool
) -> tuple[Any, ...]:
    """How the usual four wheels' anti-roll bars are given: ("axles", (front, rear)) N m/rad,
    or ("gradient", rad per g, front share or None); neither given, the sedan class's roll
    gradient (6 deg per g)."""
    if anti_roll is not None and roll_gradient is not None:
        raise ParameterError(
            "give anti_roll (each axle's bar, N m/rad) or roll_gradient (the vehicle's roll "
            "per g of lateral acceleration, rad), not both"
        )
    share = None if front_share is None else _number(front_share, "anti_roll_front_share", "1")
    if share is not None and not 0.0 <= share <= 1.0:
        raise ParameterError(f"anti_roll_front_share = {share} is invalid: it must lie in [0, 1]")
    if anti_roll is not None:
        if share is not None:
            raise ParameterError("anti_roll_front_share is for roll_gradient: drop it or give that")
        return ("axles", _pair(anti_roll, "anti_roll", "N m/rad"))
    if roll_gradient is not None:
        g = _number(roll_gradient, "roll_gradient", "rad per g")
        if g <= 0.0:
            raise ParameterError(
                f"roll_gradient = {g} rad per g is invalid: it must be > 0 (a sedan rolls "
                "about 6 deg per g: 0.105)"
            )
        return ("gradient", g, share)
    if share is not None:
        raise ParameterError("anti_roll_front_share is for roll_gradient: drop it or give that")
    # Neither given: a car's usual roll, the sedan class's (anti_roll=(0, 0) for no bars).
    from crashsim.vehicles.vehicle_data import vehicle_class

    return ("gradient", vehicle_class("sedan").roll_gradient.value, None)


def _pair(value: Any, name: str, unit: str) -> tuple[float, float]:
    """(front, rear) from one number or two."""
    if isinstance(value, tuple | list | np.ndarray) and not isinstance(value, str):
        items = list(np.asarray(value, dtype=object).reshape(-1))
        if len(items) != 2:
            raise ParameterError(
                f"{name} must be one number or (front, rear) ({unit}), got {len(items)} values"
            )
        return _number(items[0], f"{name} (front)", unit), _number(items[1], f"{name} (rear)", unit)
    x = _number(value, name, unit)
    return x, x


def _per_wheel(
    value: Any, name: str, unit: str, n: int, axles: Sequence[int] | None
) -> Array | None:
    """None, or one value per wheel from one number, (front, rear) (axle wheels only) or
    one per wheel."""
    if value is None:
        return None
    if isinstance(value, str | bool):
        raise ParameterError(f"{name} must be numbers ({unit}), got {value!r}")
    try:
        a = np.asarray(value, dtype=np.float64).reshape(-1)
    except (TypeError, ValueError) as e:
        raise ParameterError(f"{name} must be numbers ({unit}), got {value!r}") from e
    if a.size == 1:
        return np.full(n, float(a[0]))
    if a.size == 2 and axles is not None:
        return np.asarray([a[i] for i in axles], dtype=np.float64)
    if a.size == n:
        return a
    shapes = "one number, (front, rear) or one per wheel" if axles is not None else "one number"
    raise ParameterError(f"{name} must be {shapes} ({n} wheels), got {a.size} values ({unit})")


class Wheels:
    """A vehicle's wheels (body frame, SI): names, centres at static ride height, tyre radii,
    which ones steer, their springs and dampers, and the tyre.

    The usual four (this constructor): ``wheelbase`` (m), ``track`` (m; one number or
    (front, rear)), ``cg_to_front_axle`` (m, from the CG forward to the front axle),
    ``cg_height`` (m, the CG above level ground at static ride height) and ``radius`` (m,
    tyre radius; one number or (front, rear)). ``steer``: the steerable axle ("front",
    "rear", "both" or "none"). ``centerline_y``: the body-frame y of the wheels' centre
    line (m; 0 when the CG is on it). Springs: ``natural_frequency`` (Hz) and
    ``damping_ratio`` (one number or (front, rear); None: the engine's defaults), or
    explicit ``spring_rates`` (N/m) and ``damping`` (N s/m) (one number, (front, rear) or
    one per wheel), which take precedence. ``tyre``: a :class:`Tyre` (or a dict of its
    fields). Anti-roll bars: ``anti_roll`` (front, rear) roll stiffness (N m/rad), or
    ``roll_gradient`` (rad of roll per g of steady lateral acceleration) with
    ``anti_roll_front_share`` (default the static front axle load's share); neither given,
    the sedan class's 6 deg per g (``anti_roll=(0, 0)`` for none). The steering linkage:
    ``steering_ratio`` (steering-wheel angle per road-wheel angle), ``ackermann`` (fraction,
    default 1: full Ackermann), ``steering_reference`` ("outer", default: the input's angle is
    the outer wheel's; or "centre"), ``steering_interpolation`` (what is linear between a
    steering table's points: "input", default, each wheel following it through the linkage
    at every instant as a real linkage does; or "wheels", each wheel moving linearly between
    its angles at the points, as a reconstruction program's steering ramp: docs/
    vehicle-model.md). ``abs``: anti-lock brakes (default True). Other
    layouts: :meth:`custom`. ``source`` says where the numbers came from ("user", or the
    class table for a generated vehicle).

    Raises ParameterError naming the wheel for a bad number (a radius <= 0, a natural
    frequency past (0, 20] Hz, a damping ratio past [0, 5]) or a CG that is not over the wheels
    (the engine's checks); wheels outside the body and explicit rates (whose frequency and
    ratio need the vehicle's mass) are checked when the wheels are put on a vehicle
    (:meth:`crashsim.Vehicle.with_wheels`).
    """

    def __init__(
        self,
        wheelbase: float,
        track: float | tuple[float, float],
        cg_to_front_axle: float,
        cg_height: float,
        radius: float | tuple[float, float],
        *,
        steer: str = "front",
        centerline_y: float = 0.0,
        natural_frequency: float | tuple[float, float] | None = None,
        damping_ratio: float | tuple[float, float] | None = None,
        spring_rates: ArrayLike | None = None,
        damping: ArrayLike | None = None,
        tyre: Tyre | dict[str, Any] | None = None,
        anti_roll: tuple[float, float] | None = None,
        roll_gradient: float | None = None,
        anti_roll_front_share: float | None = None,
        steering_ratio: float | None = None,
        ackermann: float | None = None,
        steering_reference: str | None = None,
        steering_interpolation: str | None = None,
        abs: bool = True,
    ) -> None:
        wb = _number(wheelbase, "wheelbase", "m")
        a = _number(cg_to_front_axle, "cg_to_front_axle", "m")
        h = _number(cg_height, "cg_height", "m")
        yc = _number(centerline_y, "centerline_y", "m")
        tf, tr = _pair(track, "track", "m")
        rf, rr = _pair(radius, "radius", "m")
        for what, x in (("wheelbase", wb), ("track", min(tf, tr)), ("cg_height", h)):
            if x <= 0.0:
                raise ParameterError(f"{what} = {x} m is invalid: it must be > 0 m")
        if not 0.0 < a < wb:
            raise ParameterError(
                f"cg_to_front_axle = {a} m with wheelbase = {wb} m: the CG is not over the "
                "wheels; it must lie between the axles (0 < cg_to_front_axle < wheelbase)"
            )
        if steer not in ("front", "rear", "both", "none"):
            raise ParameterError(
                f"steer = {steer!r} is unknown: the steerable axle is 'front', 'rear', 'both' "
                "or 'none'"
            )
        x = np.array([a, a, a - wb, a - wb])
        y = yc + np.array([tf, -tf, tr, -tr]) / 2.0
        radii = np.array([rf, rf, rr, rr])
        centers = np.c_[x, y, radii - h]
        steerable = (steer in ("front", "both"),) * 2 + (steer in ("rear", "both"),) * 2
        self._init(
            STANDARD_NAMES,
            centers,
            radii,
            steerable,
            natural_frequency,
            damping_ratio,
            spring_rates,
            damping,
            tyre,
            axles=(0, 0, 1, 1),
            linkage=(steering_ratio, ackermann, steering_reference, steering_interpolation, abs),
        )
        self._roll = _roll_input(anti_roll, roll_gradient, anti_roll_front_share, axles=True)
        self.wheelbase: float | None = wb
        self.track: tuple[float, float] | None = (tf, tr)
        self.cg_to_front_axle: float | None = a
        self.cg_height: float | None = h
        self.steer: str = steer
        self._check(1.0, explicit_rates=False)

    @classmethod
    def from_class(
        cls,
        vehicle_class: str,
        *,
        wheelbase: float | None = None,
        width: float | None = None,
        cg_to_front_axle: float | None = None,
        cg_height: float | None = None,
        **kwargs: Any,
    ) -> Wheels:
        """The usual four wheels of a built-in vehicle class
        (:func:`crashsim.vehicles.vehicle_data.vehicle_class`): its wheelbase, CG position,
        CG height, front and rear track, tyre radius and roll gradient (anti-roll bars that give
        it, unless ``anti_roll`` is given) (docs/vehicle-data.md). Given
        ``wheelbase`` or ``width`` (m), the CG's distance to the front axle scales with the
        wheelbase and the tracks with the width; ``cg_to_front_axle`` and ``cg_height``
        replace the class's; other keywords as for the constructor (``radius``, ``tyre``,
        springs)."""
        from crashsim.vehicles.vehicle_data import vehicle_class as lookup

        vc = lookup(vehicle_class)
        wb = vc.wheelbase.value if wheelbase is None else _number(wheelbase, "wheelbase", "m")
        w = vc.width.value if width is None else _number(width, "width", "m")
        a = vc.cg_to_front_axle.value * wb / vc.wheelbase.value
        kwargs.setdefault("radius", vc.tyre_radius.value)
        if kwargs.get("anti_roll") is None and kwargs.get("roll_gradient") is None:
            kwargs["roll_gradient"] = vc.roll_gradient.value
        out = cls(
            wb,
            (vc.track_front.value * w / vc.width.value, vc.track_rear.value * w / vc.width.value),
            a if cg_to_front_axle is None else cg_to_front_axle,
            vc.cg_height.value if cg_height is None else cg_height,
            **kwargs,
        )
        out.source = f"class table ({vc.name})"
        return out

    @classmethod
    def custom(
        cls,
        centers: ArrayLike,
        radii: ArrayLike,
        steerable: Sequence[bool],
        *,
        names: Sequence[str] | None = None,
        natural_frequency: ArrayLike | None = None,
        damping_ratio: ArrayLike | None = None,
        spring_rates: ArrayLike | None = None,
        damping: ArrayLike | None = None,
        tyre: Tyre | dict[str, Any] | None = None,
        anti_roll: Sequence[tuple[str | int, str | int, float]] = (),
        steering_ratio: float | None = None,
        ackermann: float | None = None,
        steering_reference: str | None = None,
        steering_interpolation: str | None = None,
        abs: bool = True,
        coupling: ArrayLike | None = None,
        load_groups: Sequence[Sequence[str | int]] = (),
    ) -> Wheels:
        """Any layout of at least 3 wheels: ``centers`` (n, 3) body frame at static ride
        height (m), ``radii`` (one or n, m), ``steerable`` flags, ``names`` (default
        "wheel_0", ...); springs as for the constructor (one number or one per wheel);
        ``anti_roll`` bars as (left wheel, right wheel, roll stiffness N m/rad); the steering
        linkage and ABS as for the constructor. ``coupling``: a trailer's coupler or kingpin
        (body frame, m), where it rests on its tractor: that point carries its share of the
        weight at rest and at least 2 wheels the rest (the engine's wheel_loads).
        ``load_groups``: sets of wheels (names or indices) that share their load equally, a
        tandem's or tridem's load-equalising suspension (each side's wheels one set): their
        springs act on the set's mean travel, each wheel on the ground carries an equal share
        (the engine's VehicleSpec.load_groups); at rest each set is one support of the static
        loads' rule, at its wheels' mean position, its load split equally."""
        try:
            c = np.asarray(centers, dtype=np.float64)
        except (TypeError, ValueError) as e:
            raise ParameterError(f"wheel centres must be (n, 3) numbers (m): {e}") from e
        if c.ndim != 2 or c.shape[1] != 3:
            raise ParameterError(f"wheel centres must have shape (n, 3) (m), got {c.shape}")
        n = len(c)
        r = _per_wheel(radii, "radii", "m", n, None)
        assert r is not None
        flags = [bool(s) for s in steerable]
        if len(flags) != n:
            raise ParameterError(f"steerable must have one flag per wheel ({n}), got {len(flags)}")
        wheel_names = tuple(f"wheel_{k}" for k in range(n)) if names is None else tuple(names)
        if len(wheel_names) != n or len(set(wheel_names)) != n:
            raise ParameterError(f"names must be {n} different wheel names, got {wheel_names}")
        for w in wheel_names:
            check_name(w, "a wheel")
        self = cls.__new__(cls)
        self._init(
            wheel_names,
            c,
            r,
            tuple(flags),
            natural_frequency,
            damping_ratio,
            spring_rates,
            damping,
            tyre,
            axles=None,
            linkage=(steering_ratio, ackermann, steering_reference, steering_interpolation, abs),
        )
        self.wheelbase = self.track = self.cg_to_front_axle = self.cg_height = None
        self.steer = "custom"
        self.load_groups = tuple(
            tuple(self.index(w) for w in group) for group in load_groups
        )
        if coupling is not None:
            try:
                point = np.asarray(coupling, dtype=np.float64).reshape(-1)
            except (TypeError, ValueError) as e:
                raise ParameterError(f"coupling must be 3 numbers (m), got {coupling!r}") from e
            if point.shape != (3,) or not np.all(np.isfinite(point)):
                raise ParameterError(f"coupling must be 3 finite numbers (m), got {coupling!r}")
            self.coupling = _frozen(point)
        bars = []
        for k, bar in enumerate(anti_roll):
            if not isinstance(bar, tuple | list) or len(bar) != 3:
                raise ParameterError(
                    f"anti_roll[{k}] must be (left wheel, right wheel, roll stiffness N m/rad), "
                    f"got {bar!r}"
                )
            left, right = self.index(bar[0]), self.index(bar[1])
            bars.append((left, right, _number(bar[2], f"anti_roll[{k}] roll stiffness", "N m/rad")))
        self._roll = ("bars", tuple(bars))
        self._check(1.0, explicit_rates=False)
        return self

    def _init(
        self,
        names: tuple[str, ...],
        centers: Array,
        radii: Array,
        steerable: tuple[bool, ...],
        natural_frequency: Any,
        damping_ratio: Any,
        spring_rates: Any,
        damping: Any,
        tyre: Any,
        axles: Sequence[int] | None,
        linkage: tuple[float | None, float | None, str | None, str | None, bool],
    ) -> None:
        n = len(names)
        self._names = names
        self._centers = _frozen(centers)
        self._radii = _frozen(radii)
        self._steerable = steerable
        self._frequency = _per_wheel(natural_frequency, "natural_frequency", "Hz", n, axles)
        self._damping_ratio = _per_wheel(damping_ratio, "damping_ratio", "1", n, axles)
        self._rates = _per_wheel(spring_rates, "spring_rates", "N/m", n, axles)
        self._damping = _per_wheel(damping, "damping", "N s/m", n, axles)
        self.tyre: Tyre = Tyre.coerce(tyre)
        self.source = "user"
        # A trailer's coupler or kingpin (body frame, m): it carries a share of the weight.
        self.coupling: Array | None = None
        # Sets of wheel indices sharing their load equally (load-equalising tandems).
        self.load_groups: tuple[tuple[int, ...], ...] = ()
        ratio, ackermann, reference, interpolation, abs_ = linkage
        self.steering_ratio: float | None = (
            None if ratio is None else _number(ratio, "steering_ratio", "1")
        )
        self.ackermann: float | None = (
            None if ackermann is None else _number(ackermann, "ackermann", "1")
        )
        if reference is not None and reference not in ("outer", "centre"):
            raise ParameterError(
                f"steering_reference = {reference!r} is unknown: the steering input's road-wheel "
                "angle is the 'outer' wheel's (default, as the reconstruction programs) or the "
                "axle 'centre''s"
            )
        self.steering_reference: str | None = reference
        # Checked by the engine's rules with the rest (spec.rs, the constructors' _check).
        self.steering_interpolation: str | None = interpolation
        if not isinstance(abs_, bool | np.bool_):
            raise ParameterError(f"abs must be True or False, got {abs_!r}")
        self.abs: bool = bool(abs_)
        # The constructors then ask the engine what only it knows (CG over the wheels,
        # positive numbers; weight scales): explicit rates and the anti-roll bars wait for the
        # vehicle's mass (check_on), as the frequencies they make with each load have bounds.

    def check_inputs(self, **inputs: Any) -> None:
        """The engine's checks of driver inputs (SceneSpec.set_vehicle's steer, brake, drive,
        switches) on these wheels (``_core.check_vehicle``); the engine's ParameterError
        otherwise."""
        _core.check_vehicle(1.0, **{**self.spec(1.0, explicit_rates=False), **inputs})

    # -- what the engine gets --------------------------------------------------------------

    @property
    def names(self) -> tuple[str, ...]:
        """The wheels' names, in the engine's order."""
        return self._names

    @property
    def centers(self) -> Array:
        """(n, 3) wheel centres at static ride height, body frame (m)."""
        return self._centers

    @property
    def radii(self) -> Array:
        """(n,) tyre radii (m)."""
        return self._radii

    @property
    def steerable(self) -> tuple[bool, ...]:
        """Which wheels the steering turns."""
        return self._steerable

    def __len__(self) -> int:
        return len(self._names)

    def index(self, wheel: str | int) -> int:
        """The engine's index of a wheel: its name ("front_left"), short name ("FL") or
        index. ParameterError listing the names otherwise."""
        return wheel_index(self._names, wheel)

    def axle(self, axle: str) -> tuple[int, ...]:
        """The indices of an axle's wheels ("front" or "rear"; the usual four only)."""
        if self.steer == "custom" or axle not in AXLES:
            raise ParameterError(
                f"unknown axle {axle!r}: the axles are 'front' and 'rear' (the usual four "
                "wheels; name the wheels of a custom layout one by one)"
            )
        return tuple(self._names.index(w) for w in AXLES[axle])

    def static_loads(self, mass: float, hitch_load: tuple[ArrayLike, float] | None = None) -> Array:
        """Each wheel's static load on level ground (N) for a vehicle of ``mass`` kg: the
        axle shares of the weight (the engine's ``wheel_loads``: a load group one support
        shared equally; with a coupling, what the coupling leaves), plus, with ``hitch_load``
        (its hitch, body frame m; N), the shares of the load its trailer puts on its hitch."""
        return self._loads(mass, hitch_load)[0]

    def _loads(
        self, mass: float, hitch_load: tuple[ArrayLike, float] | None = None
    ) -> tuple[Array, float]:
        """The engine's static loads (wheel_loads): each wheel's and the coupling's (N)."""
        weight = _number(mass, "mass", "kg") * _defaults()["gravity"]
        xy = [tuple(p) for p in self._centers[:, :2].tolist()]
        towed = None
        if hitch_load is not None:
            point, force = hitch_load
            towed = ((float(point[0]), float(point[1])), float(force))
        coupling = None
        if self.coupling is not None:
            coupling = (float(self.coupling[0]), float(self.coupling[1]))
        groups = [list(g) for g in self.load_groups]
        try:
            loads, share = _core.wheel_loads(xy, weight, groups, coupling, towed)
        except ParameterError as e:
            raise _renamed(e, self._names) from e
        return np.asarray(loads, dtype=np.float64), float(share)

    def coupling_load(
        self, mass: float, hitch_load: tuple[ArrayLike, float] | None = None
    ) -> float:
        """The static load (N) a trailer of ``mass`` kg puts on its coupling on level ground
        (0 without a coupling), with ``hitch_load`` what the trailer it tows in turn puts on
        its own hitch (a dolly under a drawbar trailer's body, a B-double's first trailer)."""
        return self._loads(mass, hitch_load)[1]

    def spec(
        self,
        mass: float,
        *,
        explicit_rates: bool = True,
        hitch_load: tuple[ArrayLike, float] | None = None,
    ) -> dict[str, Any]:
        """SceneSpec.set_vehicle keywords (centers, radii, steerable, static_loads, spring_rates,
        damping, tyre, steering, anti-roll bars, abs, coupling, hitch_load) for a vehicle of
        ``mass`` kg (towing a trailer that puts ``hitch_load`` on its hitch: the springs are
        set for the combination); ``explicit_rates=False`` leaves given rates and the bars out
        (the springs from the frequency and ratio instead): what the checks without the
        vehicle's mass take."""
        loads = self.static_loads(mass, hitch_load)
        d = _defaults()
        rates = np.empty(len(self))
        damp = np.empty(len(self))
        for k, f in enumerate(loads):
            freq = d["natural_frequency"] if self._frequency is None else self._frequency[k]
            zeta = d["damping_ratio"] if self._damping_ratio is None else self._damping_ratio[k]
            try:
                rates[k], damp[k] = _core.suspension(float(f), float(freq), float(zeta))
            except ParameterError as e:
                raise _renamed(at(e, ("wheel", k, None)), self._names) from e
        if self._rates is not None and explicit_rates:
            rates = self._rates.copy()
        if self._damping is not None and explicit_rates:
            damp = self._damping.copy()
        return {
            "centers": self._centers,
            "radii": self._radii,
            "steerable": list(self._steerable),
            "static_loads": loads,
            "spring_rates": rates,
            "damping": damp,
            "tyre": self.tyre.to_core(),
            "steering_ratio": self.steering_ratio,
            "ackermann": self.ackermann,
            "steering_reference": self.steering_reference,
            "steering_interpolation": self.steering_interpolation,
            "anti_roll": self.anti_roll_bars(mass, loads, rates) if explicit_rates else [],
            "abs": self.abs,
            "coupling": self.coupling,
            "hitch_load": hitch_load,
            "load_groups": [list(g) for g in self.load_groups],
        }

    def describe(self, mass: float) -> dict[str, Any]:
        """What the engine runs for a vehicle of ``mass`` kg, as plain data (SI): the wheels
        (names, body-frame centres m, radii m, steerable, static loads N, spring rates N/m,
        damping N s/m, natural frequencies Hz and damping ratios), the anti-roll bars (left,
        right, roll stiffness N m/rad) and each axle's roll stiffness (springs and bars), the
        steering linkage (ratio, Ackermann fraction, reference wheel, what is linear between a
        table's points), ABS, the tyre as run,
        and where the numbers came from."""
        spec = self.spec(mass)
        g = _defaults()["gravity"]
        loads = np.asarray(spec["static_loads"], dtype=np.float64)
        rates = np.asarray(spec["spring_rates"], dtype=np.float64)
        damping = np.asarray(spec["damping"], dtype=np.float64)
        sprung = loads / g
        bars = [
            {"left": self._names[b[0]], "right": self._names[b[1]], "roll_stiffness": float(b[2])}
            for b in spec["anti_roll"]
        ]
        out: dict[str, Any] = {
            "source": self.source,
            "names": list(self._names),
            "centers": self._centers.tolist(),
            "radii": self._radii.tolist(),
            "steerable": list(self._steerable),
            "static_loads": loads.tolist(),
            "spring_rates": rates.tolist(),
            "damping": damping.tolist(),
            "natural_frequencies": (np.sqrt(rates / sprung) / (2.0 * math.pi)).tolist(),
            "damping_ratios": (damping / (2.0 * np.sqrt(rates * sprung))).tolist(),
            "anti_roll": bars,
            "steering": {
                "ratio": self.steering_ratio,
                "ackermann": _defaults()["ackermann"] if self.ackermann is None else self.ackermann,
                "reference": self.steering_reference or "outer",
                "interpolation": self.steering_interpolation or "input",
            },
            "abs": self.abs,
            "tyre": self.tyre.resolved(),
        }
        if self.coupling is not None:
            out["coupling"] = {
                "point": self.coupling.tolist(),
                "static_load": self.coupling_load(mass),
            }
        if self.steer != "custom" and self.track is not None:
            tf, tr = self.track
            bar = {b[0]: float(b[2]) for b in spec["anti_roll"]}
            out["roll_stiffness"] = {
                "front": float((rates[0] + rates[1]) * tf**2 / 4.0 + bar.get(0, 0.0)),
                "rear": float((rates[2] + rates[3]) * tr**2 / 4.0 + bar.get(2, 0.0)),
            }
            if self.cg_height is not None:
                total = out["roll_stiffness"]["front"] + out["roll_stiffness"]["rear"]
                moment = mass * g * self.cg_height
                # rad per g: phi = m a h / (K - m g h), the roll axis at the ground
                out["roll_gradient"] = float(moment / (total - moment)) if total > moment else None
        return out

    def anti_roll_bars(
        self, mass: float, loads: Array | None = None, rates: Array | None = None
    ) -> list[tuple[int, int, float]]:
        """The anti-roll bars for a vehicle of ``mass`` kg, as the engine takes them: (left
        wheel, right wheel, roll stiffness N m/rad). From a roll gradient G (rad of roll per g
        of lateral acceleration, the whole vehicle rolling about the ground on its springs and
        bars): the roll stiffness it needs, ``K = m g h (1 / G + 1)`` (the roll moment m a_y h
        plus the CG's own m g h phi), less what the springs give (``(k_l + k_r) t^2 / 4`` per
        axle), split front : rear by ``anti_roll_front_share`` (default: the static front axle
        load's share, as PC-Crash's wheel loads split the lateral load transfer in a fishhook,
        0.644 against 0.641); none if the springs alone are stiffer."""
        kind = self._roll[0]
        if kind == "bars":
            return [tuple(b) for b in self._roll[1]]  # type: ignore[misc]
        if kind == "axles":
            front, rear = self._roll[1]
            return [(0, 1, front), (2, 3, rear)]
        _, gradient, share = self._roll
        if loads is None:
            loads = self.static_loads(mass)
        if rates is None:
            rates = self.spec(mass)["spring_rates"]
        assert self.track is not None and self.cg_height is not None
        g = _defaults()["gravity"]
        needed = mass * g * self.cg_height * (1.0 / gradient + 1.0)
        tf, tr = self.track
        springs = (rates[0] + rates[1]) * tf**2 / 4.0 + (rates[2] + rates[3]) * tr**2 / 4.0
        bars = max(0.0, needed - springs)
        if share is None:
            share = float((loads[0] + loads[1]) / np.sum(loads))
        return [(0, 1, share * bars), (2, 3, (1.0 - share) * bars)]

    def _check(
        self,
        mass: float,
        outer: Place | None = None,
        *,
        explicit_rates: bool = True,
        shape: _core.Shape | None = None,
    ) -> None:
        """The engine's checks of these wheels for a vehicle of ``mass`` kg
        (``_core.check_vehicle``: no scene is made), on its body's ``shape`` when given;
        errors name the wheels, inside the place ``outer`` when given."""
        try:
            _core.check_vehicle(mass, shape=shape, **self.spec(mass, explicit_rates=explicit_rates))
        except ParameterError as e:
            named = _renamed(e, self._names)
            raise (named if outer is None else at(named, outer)) from e

    def with_mass_ratio(self, ratio: float) -> Wheels:
        """These wheels under a vehicle ``ratio`` times as heavy, keeping their natural
        frequencies: explicit spring rates and damping scaled by the ratio (a copy); these
        wheels themselves when they have neither (rates from natural frequencies follow the
        static loads)."""
        if self._rates is None and self._damping is None:
            return self
        other = copy.copy(self)
        if self._rates is not None:
            other._rates = self._rates * ratio
        if self._damping is not None:
            other._damping = self._damping * ratio
        return other

    def check_on(self, shape: _core.Shape, mass: float, vehicle: str) -> None:
        """The engine's checks of these wheels on a body (its shape, body frame, and mass in
        kg): wheels inside the body's outline, loads carrying the weight, explicit rates and
        the anti-roll bars. Errors are placed in the vehicle named ``vehicle``
        (:func:`crashsim.errors.vehicle_place`)."""
        self._check(mass, vehicle_place(vehicle), shape=shape)

    def contact_points(self) -> Array:
        """(n, 3) body-frame points where the tyres touch level ground at static ride height
        (m): each centre lowered by its radius."""
        out = self._centers.copy()
        out[:, 2] -= self._radii
        return out

    def __iter__(self) -> Iterator[str]:
        return iter(self._names)

    def __repr__(self) -> str:
        if self.wheelbase is not None:
            assert self.track is not None
            return (
                f"Wheels(wheelbase={self.wheelbase:g}, track={self.track}, "
                f"cg_to_front_axle={self.cg_to_front_axle:g}, cg_height={self.cg_height:g}, "
                f"radius={tuple(float(r) for r in self._radii[[0, 2]])}, steer={self.steer!r}, "
                f"tyre={self.tyre})"
            )
        return f"Wheels.custom(names={self._names}, tyre={self.tyre})"


def _frozen(a: ArrayLike) -> Array:
    out = np.array(a, dtype=np.float64)
    out.setflags(write=False)
    return out
