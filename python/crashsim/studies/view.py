"""What the studies read of a scene and how they make its variants: :class:`SceneView`, the
part of :class:`crashsim.scene.Scene` that crashsim.studies.paths and .pedestrians use. They
take a SceneView, not the Scene class, so they do not import crashsim.scene, which imports
them (``Scene.with_``)."""

from __future__ import annotations

from collections.abc import Mapping
from typing import TYPE_CHECKING, Any, Protocol, Self, TypeVar

import numpy as np
from numpy.typing import ArrayLike, NDArray

if TYPE_CHECKING:
    from crashsim.environment.ground import Ground
    from crashsim.environment.obstacles import Obstacle
    from crashsim.human.pedestrian import Pedestrian
    from crashsim.joints import Joint
    from crashsim.placement import Placement
    from crashsim.vehicles.vehicle import Vehicle

__all__ = ["SceneView", "SceneLike"]


class SceneView(Protocol):
    """A scene as the parameter paths see it (crashsim.scene.Scene is one)."""

    @property
    def ground(self) -> Ground | None: ...
    @property
    def vehicles(self) -> list[Vehicle]: ...
    @property
    def obstacles(self) -> list[Obstacle]: ...
    @property
    def joints(self) -> list[Joint]: ...
    @property
    def placements(self) -> tuple[Placement, ...]: ...
    @property
    def pedestrians(self) -> dict[str, Pedestrian]: ...
    def pairs(self) -> list[tuple[str, str, dict[str, Any]]]: ...
    def pedestrian_place(self, name: str) -> tuple[NDArray[np.float64], float,
                                                   NDArray[np.float64]]: ...
    def soft_contact_of(self, vehicle1: str, vehicle2: str) -> tuple[float, float] | None: ...
    def _varied(
        self,
        placements: list[Placement],
        pair_changes: Mapping[tuple[str, str], Mapping[str, Any]],
        ground: Ground | None = None,
    ) -> Self: ...
    def _with_people(
        self,
        people: Mapping[str, tuple[Pedestrian, ArrayLike, float, ArrayLike]],
        soft: Mapping[frozenset[str], tuple[float, float]],
    ) -> tuple[Self, set[str]]: ...


# A scene passed through and given back as its own type (a Scene in, a Scene out).
SceneLike = TypeVar("SceneLike", bound=SceneView)
