"""How a scene holds pedestrians, cyclists and bicycles: each placed as its bodies (vehicles
named "<name>/<body>"), the joints between them and their pairs (the ones that never
collide, a rider's soft contacts with the frame), and the people added, by name
(:class:`_People`, a base class of :class:`crashsim.Scene`).
"""

from __future__ import annotations

import copy
from collections.abc import Callable, Mapping
from itertools import combinations
from typing import TYPE_CHECKING, Any, Self

import numpy as np
from numpy.typing import ArrayLike, NDArray

from crashsim.contacts import _Contacts
from crashsim.environment.ground import Ground
from crashsim.errors import SceneError
from crashsim.human.bicycle import Bicycle
from crashsim.human.cyclist import Cyclist
from crashsim.human.pedestrian import Pedestrian
from crashsim.joints import Joint
from crashsim.placement import Placement, _ground_height, _read_only
from crashsim.vehicles.checks import _as_float

Array = NDArray[np.float64]


class _People(_Contacts):
    """The Scene's methods that place people and bicycles, with the pairs' methods they use
    (the state they read and change is the scene's, made by Scene.__init__)."""

    # the scene's state (crashsim.Scene.__init__ makes it)
    _ground: Ground | None
    _pedestrians: dict[str, Pedestrian]
    _cyclists: dict[str, Cyclist | Bicycle]
    _pedestrian_places: dict[str, tuple[Array, float, Array]]
    _placements: list[Placement]
    _joints: list[Joint]

    if TYPE_CHECKING:  # the scene's own methods (crashsim.Scene)
        add: Callable[..., Self]
        join: Callable[..., Self]

        def __init__(self, *args: Any, ground: Ground | None = None, **kw: Any) -> None: ...

    @property
    def pedestrians(self) -> dict[str, Pedestrian]:
        """The pedestrians added (each one's segments are vehicles of the scene), by name."""
        return dict(self._pedestrians)

    @property
    def cyclists(self) -> dict[str, Cyclist]:
        """The cyclists added (each one's rider segments and bicycle bodies are vehicles of
        the scene), by name."""
        return {k: v for k, v in self._cyclists.items() if isinstance(v, Cyclist)}

    @property
    def bicycles(self) -> dict[str, Bicycle]:
        """The bicycles added on their own (a cyclist's is its ``bicycle``), by name."""
        return {k: v for k, v in self._cyclists.items() if isinstance(v, Bicycle)}

    def _ground_frictions(self) -> dict[str, float]:
        """Each person's segments' own friction with the road (its Pedestrian's
        ``road_friction``; a cyclist's rider's too), by the segment's vehicle name."""
        people = [*self._pedestrians.values(),
                  *(c.rider for c in self._cyclists.values() if isinstance(c, Cyclist))]
        return {seg.name: p.road_friction for p in people for seg in p.segments}

    def pedestrian_place(self, name: str) -> tuple[Array, float, Array]:
        """Where pedestrian ``name`` was added: (position as given to :meth:`add` (m),
        heading (rad), velocity (m/s, world))."""
        if name not in self._pedestrian_places:
            known = ", ".join(repr(n) for n in self._pedestrian_places) or "none"
            raise SceneError(f"no pedestrian {name!r} (pedestrians: {known})")
        return self._pedestrian_places[name]

    def _with_people(
        self,
        people: Mapping[str, tuple[Pedestrian, ArrayLike, float, ArrayLike]],
        soft: Mapping[frozenset[str], tuple[float, float]],
    ) -> tuple[Self, set[str]]:
        """A copy of this scene for one variant of a study (crashsim.studies.pedestrians):
        each pedestrian named in ``people`` rebuilt as the Pedestrian given, placed at
        (position, heading rad, velocity m/s) as :meth:`add` places one; its segments and
        joints take the places of the old ones under the same names, so every pair's
        contact parameters, the no-contact pairs and the soft contacts carry over. ``soft``
        sets pairs' soft contacts (stiffness N/m, damping ratio), values the engine has
        checked. Returns the copy and the names of the segments placed."""
        new = copy.copy(self)
        new._placements = list(self._placements)
        new._joints = list(self._joints)
        new._pedestrians = dict(self._pedestrians)
        new._pedestrian_places = dict(self._pedestrian_places)
        new._soft = dict(self._soft)
        made: set[str] = set()
        index = {p.vehicle.name: j for j, p in enumerate(new._placements)}
        joint_index = {jt.name: j for j, jt in enumerate(new._joints)}
        for name, (person, position, heading, velocity) in people.items():
            alone = type(self)(ground=self._ground)  # a Scene: the person placed alone
            alone.add(person, position, heading=heading, velocity=velocity)
            for p in alone._placements:
                new._placements[index[p.vehicle.name]] = p
                made.add(p.vehicle.name)
            for jt in alone._joints:
                new._joints[joint_index[jt.name]] = jt
            new._pedestrians[name] = person
            new._pedestrian_places[name] = alone._pedestrian_places[name]
        new._soft.update(soft)
        return new, made

    def _add_pedestrian(
        self, pedestrian: Pedestrian, position: ArrayLike, heading: float | None,
        velocity: ArrayLike,
    ) -> Self:
        """Places a pedestrian's segments and joins them (:meth:`add`)."""
        what = f"pedestrian {pedestrian.name!r}"
        if self._ground is None:
            raise SceneError(f"{what} needs a ground: set scene.ground = crashsim.Ground(...)")
        xy = np.asarray(position, dtype=np.float64).reshape(-1)[:2]
        ground = _ground_height(self._ground, float(xy[0]), float(xy[1]), what)
        h = 0.0 if heading is None else _as_float(heading, "heading", "rad")
        bodies, joints = pedestrian.placement(position, h, velocity, ground)
        for body, cg, rotation, v in bodies:
            self.add(body, cg, orientation=rotation, velocity=v)
        for j, at, axes, child_axes in joints:
            self.join(
                f"{pedestrian.name}/{j.parent}",
                f"{pedestrian.name}/{j.child}",
                at=at,
                kind=j.kind,
                axes=axes,
                limits=j.limits,
                stiffness=j.stiffness,
                damping=j.damping,
                friction=j.friction,
                name=f"{pedestrian.name}/{j.name}",
                axes2=child_axes,
                passive=j.passive_in(f"{pedestrian.name}/"),
            )
        # A passive body's segments never strike each other (the joints hold the neighbours).
        names = [body.name for body, *_ in bodies]
        self._pedestrians[pedestrian.name] = pedestrian
        self._pedestrian_places[pedestrian.name] = (_read_only(position), h, _read_only(velocity))
        joined = {frozenset((f"{pedestrian.name}/{j.parent}", f"{pedestrian.name}/{j.child}"))
                  for j, *_ in joints}  # fmt: skip
        for a, b in combinations(names, 2):
            if frozenset((a, b)) not in joined:
                self.no_contact(a, b)
        return self

    def _add_bicycle(
        self, thing: Cyclist | Bicycle, position: ArrayLike, heading: float | None,
        velocity: ArrayLike,
    ) -> Self:
        """Places a cyclist's or a bicycle's bodies, joins them and sets their pairs (the
        rider's soft contacts with the frame, the pairs that never collide) (:meth:`add`)."""
        what = f"{type(thing).__name__.lower()} {thing.name!r}"
        if self._ground is None:
            raise SceneError(f"{what} needs a ground: set scene.ground = crashsim.Ground(...)")
        if thing.name in self._cyclists or thing.name in self._pedestrians:
            raise SceneError(f"{what} is already in the scene: names must be unique")
        xy = np.asarray(position, dtype=np.float64).reshape(-1)[:2]
        ground = _ground_height(self._ground, float(xy[0]), float(xy[1]), what)
        h = 0.0 if heading is None else _as_float(heading, "heading", "rad")
        parts = thing.placement(position, h, velocity, ground)
        for body, cg, rotation, v, w in parts.bodies:
            self.add(body, cg, orientation=rotation, velocity=v, angular_velocity=w)
        for j in parts.joints:
            j = dict(j)
            self.join(j.pop("vehicle1"), j.pop("vehicle2"), **j)
        for a, b in parts.no_contact:
            self.no_contact(a, b)
        for a, b, k, zeta, params in parts.soft:
            self.contact(a, b, **params)
            self.soft_contact(a, b, stiffness=k, damping_ratio=zeta)
        self._cyclists[thing.name] = thing
        return self
