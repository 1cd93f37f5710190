"""How a scene's pairs meet: the seven contact parameters of a pair (their keys, the engine's
defaults, the engine's value of a pair, ``_core.ContactParams``, and the face stiffness some
of them need), and the Scene's methods that set them per pair, make a pair never collide or
give it a soft contact (:class:`_Contacts`, a base class of :class:`crashsim.Scene`).

Meanings, units and ranges: :class:`crashsim.Scene`. Ranges are checked by the engine itself
(crates/crashsim-core), when the value is made.
"""

from __future__ import annotations

import enum
from collections.abc import Callable
from itertools import combinations
from typing import TYPE_CHECKING, Any, Literal, Self, TypeAlias

from numpy.typing import ArrayLike

from crashsim import _core
from crashsim.environment.obstacles import Obstacle
from crashsim.errors import ParameterError, SceneError, naming, renamed
from crashsim.human.bicycle import Bicycle
from crashsim.human.cyclist import Cyclist
from crashsim.human.pedestrian import Pedestrian
from crashsim.joints import Joint
from crashsim.vehicles.checks import _as_float
from crashsim.vehicles.stiffness import FACES
from crashsim.vehicles.vehicle import Vehicle

if TYPE_CHECKING:
    from crashsim.placement import Placement

VehicleRef: TypeAlias = Vehicle | Obstacle | str
# None: horizontal part of the volume normal tilted by pitch; "volume": the full 3-D one;
# a 3-vector: a fixed world direction from vehicle 1 into vehicle 2.
NormalSpec: TypeAlias = None | Literal["horizontal", "volume"] | ArrayLike
# None: automatic; a 3-vector: a fixed world point (m); (vehicle, (x, y, z)): a point fixed in
# that vehicle's body frame (m from its CG).
CentroidSpec: TypeAlias = None | ArrayLike | tuple[VehicleRef, ArrayLike]


class _Unset(enum.Enum):
    UNSET = "unset"


UNSET = _Unset.UNSET
"""Marks a contact parameter that is not overridden (the scene default applies)."""


CONTACT_KEYS = (
    "depth_of_penetration",
    "restitution",
    "friction",
    "restitution_mode",
    "normal",
    "pitch",
    "centroid",
)
"""The seven contact parameters of a pair (meanings, units and ranges: :class:`crashsim.Scene`)."""

_DEFAULTS = _core.ContactParams()
"""The engine's defaults of a pair's parameters (crates/crashsim-core/src/contact.rs)."""


def _check_stiffness(
    params: _core.ContactParams, bodies: tuple[Vehicle | Obstacle, Vehicle | Obstacle]
) -> None:
    """The engine's check that a pair's parameters have the face stiffness they need
    (ContactParams.check_stiffness: auto depth of penetration and the stiffness centroid need
    every face of both bodies, a fixed obstacle without any is rigid); ParameterError naming
    the body that lacks it."""
    sides: list[Any] = []
    for b in bodies:
        faces = [None if (s := b.stiffness.face(f)) is None else (s.A, s.B) for f in FACES]
        sides += [faces, isinstance(b, Obstacle)]
    try:
        _core.check_contact_stiffness(params, *sides)
    except ParameterError as e:

        def body(k: int) -> str:
            kind = "obstacle" if isinstance(bodies[k], Obstacle) else "vehicle"
            return f"{kind} {bodies[k].name!r}"

        raise renamed(e, naming(body=body)) from e


def _core_params(
    params: dict[str, Any],
    pair: tuple[int, int] | None,
    index: Callable[[VehicleRef], int],
    scene_bodies: Callable[[], list[Vehicle | Obstacle]],
) -> _core.ContactParams:
    """The engine's ContactParams of one pair (body indices (i, j)) from the scene's
    parameter values, checked by the engine (ParameterError naming the bad one). Pair None
    means the scene defaults, before any vehicle is known (a centroid fixed in a vehicle
    is then checked as a point; its vehicle when a pair takes it). ``index`` and ``scene_bodies``
    are the scene's lookups (a body's index; the bodies in the engine's order)."""
    dtp = params["depth_of_penetration"]
    kw: dict[str, Any] = {
        "depth_of_penetration": dtp
        if isinstance(dtp, str)
        else _as_float(dtp, "depth_of_penetration", "s"),
        "restitution": _as_float(params["restitution"], "restitution", "1"),
        "friction": _as_float(params["friction"], "friction", "1"),
        "restitution_mode": params["restitution_mode"],
        "pitch": _as_float(params["pitch"], "pitch", "rad"),
    }
    if not isinstance(kw["restitution_mode"], str):
        raise ParameterError(
            f'restitution_mode must be "total" or "normal", got {kw["restitution_mode"]!r}'
        )
    normal = params["normal"]
    if normal is None or (isinstance(normal, str) and normal == "horizontal"):
        kw["normal"] = "horizontal"
    elif isinstance(normal, str):
        if normal != "volume":
            raise ParameterError(
                f"normal = {normal!r} is unknown: use None (horizontal, tilted by pitch), "
                "'volume' (full 3-D) or a world vector (x, y, z)"
            )
        kw["normal"] = "volume"
    else:
        kw["normal"] = "vector"
        kw["normal_vector"] = normal
    centroid = params["centroid"]
    if centroid is None or (isinstance(centroid, str) and centroid == "auto"):
        kw["centroid"] = "auto"
    elif isinstance(centroid, str) and centroid == "stiffness":
        kw["centroid"] = "stiffness"
    elif (
        isinstance(centroid, tuple | list)
        and len(centroid) == 2
        and isinstance(centroid[0], Vehicle | Obstacle | str)
    ):
        if pair is None:  # a scene default fixed in a vehicle: checked per pair
            kw.update(centroid="world", centroid_point=centroid[1])
        else:
            body = index(centroid[0])
            if body not in pair:
                bodies = scene_bodies()
                a, b = (bodies[k].name for k in pair)
                raise SceneError(
                    f"the centroid is fixed in {bodies[body].name!r}, "
                    f"which is not in the pair ({a!r}, {b!r}): fix it in one of the two"
                )
            kw.update(centroid="body", centroid_body=body, centroid_point=centroid[1])
    elif isinstance(centroid, str):
        raise ParameterError(
            f"centroid = {centroid!r} is unknown: use None (automatic), 'stiffness', a world "
            "point (x, y, z) or (vehicle, (x, y, z)) fixed in a vehicle"
        )
    else:
        kw.update(centroid="world", centroid_point=centroid)
    return _core.ContactParams(**kw)


class _Contacts:
    """The rules of a scene's pairs: :class:`crashsim.Scene`'s contact, no_contact,
    soft_contact, pairs and contact_parameters (Scene derives from this class; the state they
    read and change is the scene's, made by Scene.__init__)."""

    # the scene's state (crashsim.Scene.__init__ makes it)
    _defaults: dict[str, Any]
    _placements: list[Placement]
    _overrides: dict[tuple[str, str], dict[str, Any]]
    _joints: list[Joint]
    _no_contact: set[frozenset[str]]
    _soft: dict[frozenset[str], tuple[float, float]]

    if TYPE_CHECKING:  # the scene's lookups (crashsim.Scene)

        def _index(self, vehicle: VehicleRef) -> int: ...

        def _bodies(self) -> list[Vehicle | Obstacle]: ...

    def contact(
        self,
        vehicle1: VehicleRef,
        vehicle2: VehicleRef,
        *,
        depth_of_penetration: float | Literal["auto"] | _Unset = UNSET,
        restitution: float | _Unset = UNSET,
        friction: float | _Unset = UNSET,
        restitution_mode: str | _Unset = UNSET,
        normal: NormalSpec | _Unset = UNSET,
        pitch: float | _Unset = UNSET,
        centroid: CentroidSpec | _Unset = UNSET,
    ) -> Self:
        """Override parameters of one pair (vehicles or names); the rest keep the scene's
        defaults. The normal points from vehicle1 into vehicle2. Calling again for the same
        ordered pair adds to its overrides; calling with the pair reversed replaces them.
        Meanings and units are those of :class:`crashsim.Scene`. Returns the scene."""
        i, j = self._index(vehicle1), self._index(vehicle2)
        if i == j:
            raise SceneError("a contact needs two different vehicles")
        bodies = self._bodies()
        n = len(self._placements)
        if i >= n and j >= n:
            raise SceneError("two obstacles never meet: a contact needs a vehicle")
        names = (bodies[i].name, bodies[j].name)
        if frozenset(names) in self._no_contact:
            raise SceneError(
                f"{names[0]!r} and {names[1]!r} never collide (scene.no_contact): they take no "
                "contact parameters"
            )
        given = dict(
            zip(
                CONTACT_KEYS,
                (
                    depth_of_penetration,
                    restitution,
                    friction,
                    restitution_mode,
                    normal,
                    pitch,
                    centroid,
                ),
                strict=True,
            )
        )
        overrides = dict(self._overrides.get(names, {}))
        overrides.update({k: v for k, v in given.items() if v is not UNSET})
        merged = {**self._defaults, **overrides}
        core = _core_params(merged, (i, j), self._index, self._bodies)
        _check_stiffness(core, (bodies[i], bodies[j]))
        self._overrides.pop((names[1], names[0]), None)
        self._overrides[names] = overrides
        return self

    def no_contact(self, vehicle1: VehicleRef, vehicle2: VehicleRef) -> Self:
        """Make two vehicles (or a vehicle and an obstacle; objects or names) never collide:
        their meshes pass through each other, with no contact and no exchange, as joined
        vehicles do (a pedestrian's segments among themselves). Returns the scene."""
        i, j = self._index(vehicle1), self._index(vehicle2)
        if i == j:
            raise SceneError("no_contact needs two different vehicles")
        bodies = self._bodies()
        if i >= len(self._placements) and j >= len(self._placements):
            raise SceneError("two obstacles never meet: no_contact needs a vehicle")
        names = (bodies[i].name, bodies[j].name)
        if frozenset(names) in self._soft:
            raise SceneError(
                f"{names[0]!r} and {names[1]!r} have a soft contact (scene.soft_contact): a pair "
                "that never collides takes none"
            )
        if names in self._overrides or names[::-1] in self._overrides:
            raise SceneError(
                f"{names[0]!r} and {names[1]!r} have contact parameters (scene.contact): a pair "
                "that never collides takes none"
            )
        self._no_contact.add(frozenset(names))
        return self

    def soft_contact(
        self,
        vehicle1: VehicleRef | Pedestrian | Cyclist | Bicycle,
        vehicle2: VehicleRef | Pedestrian | Cyclist | Bicycle,
        stiffness: float,
        damping_ratio: float = 0.5,
    ) -> Self:
        """Give a pair a compliant contact in place of the depth-of-penetration timer and the
        impulse exchange (docs/human.md, "Soft contacts"): while their meshes overlap, a
        normal force ``max(0, k d + c v)`` (``d`` the overlap's depth, m; ``v`` its closing
        speed, m/s; ``c = 2 damping_ratio sqrt(k m)``) acts at its centre of pressure with
        friction up to the pair's ``friction`` times it. ``stiffness`` k in N/m (up to 1e8),
        ``damping_ratio`` in [0, 2] (0.5: a head-on restitution of about 0.16). Either side
        may be a :class:`crashsim.Pedestrian` in the scene: every segment of it (a
        :class:`crashsim.Cyclist` or :class:`crashsim.Bicycle`: every body of it). The pair's
        normal and friction are its contact parameters (:meth:`contact`; ``normal="volume"``
        for contacts from above). While the pair presses, the run cuts each step into
        n = ceil(sqrt(k / m) dt / 0.2) sub-steps (m the lighter body's mass; none when
        ``sqrt(k / m) dt`` is at most 0.2) and refuses a step that would need more than 50.
        Returns the scene."""
        k = _as_float(stiffness, "stiffness", "N/m")
        zeta = _as_float(damping_ratio, "damping_ratio", "1")
        _core.check_soft_contact(k, zeta)

        def names(v: VehicleRef | Pedestrian | Cyclist | Bicycle) -> list[str]:
            if isinstance(v, Pedestrian):
                return [s.name for s in v.segments]
            if isinstance(v, (Cyclist, Bicycle)):
                return [b.name for b in v.bodies]
            return [self._bodies()[self._index(v)].name]

        for a in names(vehicle1):
            for b in names(vehicle2):
                i, j = self._index(a), self._index(b)
                if i == j:
                    raise SceneError("a soft contact needs two different vehicles")
                if i >= len(self._placements) and j >= len(self._placements):
                    raise SceneError("two obstacles never meet: a soft contact needs a vehicle")
                if frozenset((a, b)) in self._no_contact:
                    raise SceneError(
                        f"{a!r} and {b!r} never collide (scene.no_contact): they take no soft "
                        "contact"
                    )
                self._soft[frozenset((a, b))] = (k, zeta)
        return self

    def soft_contact_of(
        self, vehicle1: VehicleRef, vehicle2: VehicleRef
    ) -> tuple[float, float] | None:
        """The pair's soft contact (:meth:`soft_contact`): (stiffness N/m, damping ratio), or
        None when the pair has none."""
        bodies = self._bodies()
        names = frozenset((bodies[self._index(vehicle1)].name, bodies[self._index(vehicle2)].name))
        return self._soft.get(names)

    def pairs(self) -> list[tuple[str, str, dict[str, Any]]]:
        """Every pair of vehicles as the engine gets it: (vehicle 1, vehicle 2, parameters),
        vehicle 1 being the one the normal points away from (the first argument of the last
        :meth:`contact` call for the pair, else the one added first)."""
        names = [b.name for b in self._bodies()]
        n = len(self._placements)
        joined = {frozenset(j.vehicles) for j in self._joints if not j.core.collide}
        joined |= self._no_contact
        out = []
        for i, j in combinations(range(len(names)), 2):
            if i >= n and j >= n:
                continue  # two obstacles never meet
            a, b = names[i], names[j]
            if frozenset((a, b)) in joined:
                continue  # joined vehicles (and no-contact pairs) pass through each other
            if (b, a) in self._overrides:
                a, b = b, a
            out.append((a, b, {**self._defaults, **self._overrides.get((a, b), {})}))
        return out

    def contact_parameters(self, vehicle1: VehicleRef, vehicle2: VehicleRef) -> dict[str, Any]:
        """The parameters the pair will run with (defaults merged with overrides), as seen
        from vehicle1 (the normal points from vehicle1 into vehicle2 when set that way)."""
        i, j = self._index(vehicle1), self._index(vehicle2)
        bodies = self._bodies()
        names = (bodies[i].name, bodies[j].name)
        overrides = self._overrides.get(names, self._overrides.get(names[::-1], {}))
        return {**self._defaults, **overrides}
